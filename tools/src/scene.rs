//! Whole glTF scenes (format-spec/09-gltf.md): `swm encode scene.glb -o
//! out.glb` codes each triangle primitive inside `SWM_mesh_compression`
//! and keeps the rest of the scene (`swm::io::encode_scene`); `swm decode
//! out.glb -o plain.glb` expands it (`swm::io::decode_scene`); `swm info
//! out.glb` lists the primitives and their sizes. A scene is meant when
//! both the input and the output are named `.glb` or `.gltf`.
//!
//! Nothing silently lost (issue 47, item 6): every primitive left
//! uncompressed is named, with why, in one line on standard error and in
//! `--json`; `--strict` makes that an error and writes nothing.

use crate::encode::{encode_options, Args};
use crate::error::CliError;
use serde_json::json;
use std::path::Path;
use swm::io::{PrimitiveOutcome, SceneFormat, SceneOptions, SceneReport};

/// The scene container a path's extension names, if any.
fn format_of(path: &Path) -> Option<SceneFormat> {
    let ext = path.extension()?.to_str()?;
    if ext.eq_ignore_ascii_case("glb") {
        Some(SceneFormat::Glb)
    } else if ext.eq_ignore_ascii_case("gltf") {
        Some(SceneFormat::Gltf)
    } else {
        None
    }
}

/// Whether `encode` is asked for a scene: a glTF input (by name or
/// `--format`) and an output named `.glb` or `.gltf`, without `--force`
/// (which writes a `.swm` file whatever the output's name, as before).
pub fn scene_output(args: &Args) -> Option<SceneFormat> {
    if args.force {
        return None;
    }
    let input = match args.format {
        Some(f) => matches!(f, swm::io::MeshFormat::Glb | swm::io::MeshFormat::Gltf),
        None => format_of(&args.input).is_some(),
    };
    if !input || crate::pipe::is_stdio(&args.input) {
        return None;
    }
    format_of(&args.output)
}

/// `swm encode scene.glb -o out.glb`.
pub fn encode(args: &Args, format: SceneFormat) -> Result<(), CliError> {
    crate::refuse_same_file(&args.input, &args.output)?;
    if args.max_size.is_some() {
        let e = std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "--max-size does not apply to glTF scenes (--size is the whole scene's swm budget)",
        );
        return Err(CliError::usage(&args.output, e));
    }
    let err = |e| CliError::new(&args.input, e);
    let bytes = swm::io::read_file(&args.input).map_err(err)?;
    let options = SceneOptions {
        encode: encode_options(args),
        attributes_qp: args.qp(),
        // The default rate counts positions only: without a target of
        // the user's, textured primitives keep their own triangles.
        lossy_attributes: args.size.is_some()
            || args.bpv.is_some()
            || args.max_error.is_some()
            || args.max_error_units.is_some(),
        fallback: args.gltf_fallback,
        format,
        limits: swm::Limits::default(),
    };
    let start = std::time::Instant::now();
    let base = args.input.parent();
    let encoded = swm::io::encode_scene(&bytes, base, &options).map_err(err)?;
    let seconds = start.elapsed().as_secs_f64();
    let report = &encoded.report;
    let kept = kept_line(report);
    if let Some(line) = &kept {
        if args.strict {
            let what = format!("{line}; --strict refuses to leave them uncompressed");
            return Err(crate::error::fail(&args.input, what));
        }
    }
    crate::pipe::write_bytes(&args.output, &encoded.bytes)
        .map_err(|e| CliError::new(&args.output, e))?;
    if let Some(line) = &kept {
        eprintln!("swm: note: {}: {line}", args.input.display());
    }
    if !report.unknown_extensions.is_empty() {
        eprintln!(
            "swm: note: {}: extensions swm does not know, passed through as written (the data they may refer to is kept whole): {}",
            args.input.display(),
            report.unknown_extensions.join(", ")
        );
    }
    let coded: Vec<_> = report.coded().collect();
    if args.json {
        let primitives: Vec<_> = report
            .primitives
            .iter()
            .map(|p| match &p.outcome {
                PrimitiveOutcome::Coded(c) => json!({
                    "mesh": p.mesh, "primitive": p.primitive, "name": p.name,
                    "coded": true, "method": c.method.name(), "bytes": c.bytes,
                    "share": c.share, "input_vertices": c.input_vertices,
                    "input_triangles": c.input_triangles, "vertices": c.vertices,
                    "triangles": c.triangles, "attributes": c.attributes,
                }),
                PrimitiveOutcome::Uncoded(u) => json!({
                    "mesh": p.mesh, "primitive": p.primitive, "name": p.name,
                    "coded": false, "kept_because": u.to_string(),
                }),
            })
            .collect();
        let uncompressed: Vec<String> = report
            .uncoded()
            .map(|(p, u)| format!("{} ({u})", p.label()))
            .collect();
        crate::report::print_json(&json!({
            "scene": true,
            "bytes": encoded.bytes.len(),
            "input_bytes": bytes.len(),
            "swm_bytes": report.coded_bytes(),
            "requested": report.requested,
            "encode_seconds": seconds,
            "primitives": primitives,
            "uncompressed": uncompressed,
            "unknown_extensions": report.unknown_extensions,
        }));
        return Ok(());
    }
    let budget = report
        .requested
        .map_or(String::new(), |r| format!(" (budget {r})"));
    say!(
        "{}: {} bytes ({}: {} bytes); {} of {} primitives coded in {} bytes of swm{budget}",
        args.output.display(),
        encoded.bytes.len(),
        args.input.display(),
        bytes.len(),
        coded.len(),
        report.primitives.len(),
        report.coded_bytes(),
    );
    if args.verbose {
        for (p, c) in coded {
            say!(
                "  {}: {} {} bytes, {} -> {} vertices, {} triangles{}",
                p.label(),
                c.method.name(),
                c.bytes,
                c.input_vertices,
                c.vertices,
                c.triangles,
                if c.attributes.is_empty() {
                    String::new()
                } else {
                    format!(", {}", c.attributes.join(" "))
                }
            );
        }
    }
    Ok(())
}

/// The one line that names every primitive kept uncompressed, if any.
fn kept_line(report: &SceneReport) -> Option<String> {
    let kept: Vec<String> = report
        .uncoded()
        .map(|(p, u)| format!("{} ({u})", p.label()))
        .collect();
    (!kept.is_empty()).then(|| format!("kept uncompressed: {}", kept.join("; ")))
}

/// Whether `decode` is asked for a scene: a glTF input by name.
pub fn is_scene_input(input: &Path) -> bool {
    format_of(input).is_some()
}

/// `swm decode out.glb -o plain.glb`.
pub fn decode(
    input: &Path,
    output: &Path,
    limits: swm::Limits,
    json: bool,
) -> Result<(), CliError> {
    crate::same_file::refuse_same_file(input, output)?;
    let Some(format) = format_of(output) else {
        let e = std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "a glTF scene decodes to a glTF scene: name the output .glb or .gltf",
        );
        return Err(CliError::usage(output, e));
    };
    let err = |e| CliError::new(input, e);
    let bytes = swm::io::read_file_with(input, &limits).map_err(err)?;
    let options = swm::DecodeOptions {
        limits,
        ..swm::DecodeOptions::plain()
    };
    let start = std::time::Instant::now();
    let decoded = swm::io::decode_scene(&bytes, input.parent(), &options, format).map_err(err)?;
    let seconds = start.elapsed().as_secs_f64();
    crate::pipe::write_bytes(output, &decoded.bytes).map_err(|e| CliError::new(output, e))?;
    if json {
        crate::report::print_json(&json!({
            "scene": true,
            "bytes": decoded.bytes.len(),
            "primitives": decoded.primitives,
            "decoded_vertices": decoded.vertices,
            "decoded_triangles": decoded.triangles,
            "decode_seconds": seconds,
        }));
    } else {
        say!(
            "{}: {} bytes; {} primitives expanded, {} vertices, {} triangles ({:.3} s)",
            output.display(),
            decoded.bytes.len(),
            decoded.primitives,
            decoded.vertices,
            decoded.triangles,
            seconds
        );
    }
    Ok(())
}

/// `swm info out.glb` for a scene with swm-coded primitives: `false`
/// when it has none (then it is described as a mesh).
pub fn info(file: &Path, json: bool) -> Result<bool, CliError> {
    let err = |e| CliError::new(file, e);
    let limits = swm::Limits::default();
    let bytes = swm::io::read_file_with(file, &limits).map_err(err)?;
    let primitives = swm::io::scene_info(&bytes, file.parent(), &limits).map_err(err)?;
    if !primitives.iter().any(|p| p.swm_bytes.is_some()) {
        return Ok(false);
    }
    let swm_bytes: u64 = primitives.iter().filter_map(|p| p.swm_bytes).sum();
    if json {
        let list: Vec<_> = primitives
            .iter()
            .map(|p| {
                json!({
                    "mesh": p.mesh, "primitive": p.primitive, "name": p.name,
                    "swm_bytes": p.swm_bytes, "vertices": p.vertices,
                    "triangles": p.triangles, "attributes": p.attributes,
                })
            })
            .collect();
        crate::report::print_json(&json!({
            "scene": true,
            "extension": swm::io::SCENE_EXTENSION,
            "bytes": bytes.len(),
            "swm_bytes": swm_bytes,
            "primitives": list,
        }));
        return Ok(true);
    }
    say!("{}", file.display());
    say!(
        "  {} bytes, {} in {} swm-coded primitives of {} ({})",
        bytes.len(),
        swm_bytes,
        primitives.iter().filter(|p| p.swm_bytes.is_some()).count(),
        primitives.len(),
        swm::io::SCENE_EXTENSION
    );
    for p in &primitives {
        let label = match &p.name {
            Some(n) => format!("mesh {} {n:?} primitive {}", p.mesh, p.primitive),
            None => format!("mesh {} primitive {}", p.mesh, p.primitive),
        };
        let size = p
            .swm_bytes
            .map_or("uncompressed".to_string(), |b| format!("{b} bytes of swm"));
        say!(
            "  {label}: {size}, {} vertices, {} triangles, {}",
            p.vertices,
            p.triangles,
            p.attributes.join(" ")
        );
    }
    Ok(true)
}
