//! `swm info MESH [--json]`: what a mesh is made of, after cleaning.
//!
//! Counts are taken after merging coincident vertices (so an STL file or
//! an OBJ with split texture seams reports its real vertex count), and
//! components join faces through any shared edge, as in the file; boundary
//! loops and genus are those of the cleaned, manifold mesh the encoder
//! would see.

use crate::error::CliError;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// A mesh file (.obj, .ply, .off, .stl, .gltf, .glb) or a .swm file.
    file: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let err = |e: swm::Error| CliError::new(&args.file, e);
    let is_swm = args
        .file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("swm"));
    if is_swm {
        return run_swm(args);
    }
    // A scene with swm-coded primitives lists them; one without is a mesh.
    if crate::scene::is_scene_input(&args.file) && crate::scene::info(&args.file, args.json)? {
        return Ok(());
    }
    let mesh = swm::io::read_mesh(&args.file).map_err(err)?;
    let cleaned = swm::clean(&mesh, &swm::CleanOptions::default()).map_err(err)?;
    let stats = cleaned.table.stats(&cleaned.mesh);
    let r = &cleaned.report;
    if args.json {
        let v = serde_json::json!({
            "vertices": cleaned.distinct_vertices,
            "faces": r.input_faces,
            "components": r.input_components,
            "boundary_loops": stats.boundary_loops,
            "genus": stats.genus,
            "non_manifold_edges": r.non_manifold_edges,
            "non_manifold_vertices": r.non_manifold_vertices,
            "degenerate_faces": r.degenerate_faces(),
            "bbox_diagonal": stats.bbox_diagonal,
            "area": stats.area,
        });
        crate::report::print_json(&v);
        return Ok(());
    }
    say!("{}", args.file.display());
    say!("  vertices              {}", cleaned.distinct_vertices);
    say!("  faces                 {}", r.input_faces);
    say!("  components            {}", r.input_components);
    say!("  boundary loops        {}", stats.boundary_loops);
    say!("  genus                 {}", stats.genus);
    say!("  bbox diagonal         {}", stats.bbox_diagonal);
    say!("  area                  {}", stats.area);
    if r.is_clean() {
        say!("  cleaning              nothing to repair");
    } else {
        say!("  cleaning:");
        let rows = [
            ("coincident vertices merged", r.merged_vertices),
            ("unreferenced vertices removed", r.unreferenced_vertices),
            (
                "faces with a repeated vertex dropped",
                r.repeated_index_faces,
            ),
            ("zero-area faces dropped", r.zero_area_faces),
            ("duplicate faces dropped", r.duplicate_faces),
            ("faces flipped to match their component", r.flipped_faces),
            ("non-manifold edges cut", r.non_manifold_edges),
            ("non-manifold vertices split", r.non_manifold_vertices),
            ("vertices added by splitting", r.split_vertices_added),
        ];
        for (what, n) in rows.iter().filter(|r| r.1 > 0) {
            say!("    {what:<40} {n}");
        }
        say!(
            "  after cleaning        {} vertices, {} faces, {} components",
            cleaned.mesh.vertex_count(),
            cleaned.mesh.face_count(),
            stats.components
        );
    }
    Ok(())
}

/// A displaced file's levels, coarse to fine: each one's chunk bytes and
/// triangle count (the file's count over 4 per finer level), so that a
/// reader sees where `--max-level` or a cut would stop, with its step
/// and bend; and its prediction rule and base.
fn print_levels(levels: &[usize], triangles: u64, d: Option<&swm::DisplacedInfo>) {
    if let Some(d) = d {
        let base = match d.bare_base {
            true => "bare (its sections alone)",
            false => "a whole mode-0 file",
        };
        say!("  prediction            {}", d.rule.name());
        say!("  base                  {base}, {} bytes", d.base_bytes);
    }
    say!("  levels                {}", levels.len());
    for (l, bytes) in levels.iter().enumerate() {
        let finer = 2 * (levels.len() - 1 - l) as u32;
        let t = triangles.checked_shr(finer).unwrap_or(0);
        let how = d
            .map(|d| {
                let step = d.steps.get(l).copied().unwrap_or(0.0);
                let bend = d.bends.get(l).copied().unwrap_or(0.0);
                format!(", step {step:.4e}, bend {bend}")
            })
            .unwrap_or_default();
        say!(
            "    level {}             {bytes} bytes, {t} triangles{how}",
            l + 1
        );
    }
}

/// `swm info FILE.swm`: the file's header, sections and CLERS histogram.
fn run_swm(args: &Args) -> Result<(), CliError> {
    let err = |e: swm::Error| CliError::new(&args.file, e);
    // Regular files only, within `max_input_bytes`.
    let bytes = swm::io::read_file(&args.file).map_err(err)?;
    let info = swm::inspect(&bytes, &swm::Limits::default()).map_err(err)?;
    if let Some(swing) = &info.swing {
        return print_swing(args, &info, swing);
    }
    let mut v = crate::report::lossless_json(&info.stats, info.qp);
    if info.mode == swm::Mode::Displaced {
        v["mode"] = "displaced".into();
        v["level_bytes"] = info.levels.clone().into();
        if let Some(d) = &info.displaced {
            v["prediction"] = d.rule.name().into();
            v["steps"] = d.steps.clone().into();
            v["bends"] = d.bends.clone().into();
            v["bare_base"] = d.bare_base.into();
            v["base_bytes"] = d.base_bytes.into();
        }
    }
    v["version"] = version(&info).into();
    v["framing"] = framing(&info).into();
    v["frame_bytes"] = info.frame_bytes.into();
    v["post"] = post_json(&info);
    if args.json {
        crate::report::print_json(&v);
        return Ok(());
    }
    let s = &info.stats;
    print_file_and_version(args, &info);
    if info.mode == swm::Mode::Displaced {
        say!(
            "  mode                  displaced subdivision, base at {} bits per coordinate",
            info.qp
        );
        print_levels(&info.levels, s.triangles, info.displaced.as_ref());
    } else {
        say!(
            "  mode                  lossless, {} bits per coordinate",
            info.qp
        );
    }
    say!("  vertices              {}", s.vertices);
    say!("  triangles             {}", s.triangles);
    say!("  components            {}", s.components);
    say!("  holes                 {}", s.holes);
    say!("  handle events         {}", s.handle_events);
    say!(
        "  bytes                 {} ({:.3} bits/triangle)",
        s.file_bytes,
        v["bits_per_triangle"].as_f64().unwrap_or(0.0)
    );
    print_post(&info);
    for a in &info.attributes {
        let what = if a.kind == swm::AttributeKind::Normal {
            "bits per octahedral coordinate"
        } else {
            "bits per component"
        };
        say!(
            "  attribute             {}, {} components, {} {what}, {} bytes",
            crate::report::attribute_name(a.kind),
            a.dims,
            a.bits,
            a.bytes
        );
    }
    print_sections_and_clers(&s.sections, s.triangles, s.clers);
    Ok(())
}

/// The post-processing hint as JSON: `{"sharpen", "bend_steps"}`, or
/// null when the file has none (a default decode is then plain).
fn post_json(info: &swm::FileInfo) -> serde_json::Value {
    match info.post {
        Some(p) => serde_json::json!({"sharpen": p.sharpen, "bend_steps": p.bend_steps}),
        None => serde_json::Value::Null,
    }
}

/// The line saying what a default decode runs after decoding.
fn print_post(info: &swm::FileInfo) {
    let what = match info.post {
        None => "none (no hint: swm decode runs neither step unless told)".to_string(),
        Some(p) if p.is_plain() => "none (the encoder's hint)".to_string(),
        Some(p) => {
            let bend = match p.bend_steps {
                0 => String::new(),
                1 => " + 1 Bender step".to_string(),
                n => format!(" + {n} Bender steps"),
            };
            let sharpen = if p.sharpen {
                "EdgeSharpener"
            } else {
                "no EdgeSharpener"
            };
            format!("{sharpen}{bend} (the encoder's hint; swm decode follows it unless told)")
        }
    };
    say!("  post-processing       {what}");
}

/// `", x bits/triangle"` for `bits` over `triangles`, or nothing when
/// there is no triangle to count against (a swing file whose whole mesh
/// is in `REST`).
fn per_triangle(bits: f64, triangles: u64) -> String {
    if triangles == 0 {
        String::new()
    } else {
        format!(", {:.3} bits/triangle", bits / triangles as f64)
    }
}

/// Section sizes and the CLERS histogram, shared by both modes' output.
fn print_sections_and_clers(sections: &[([u8; 4], usize)], triangles: u64, clers: [u64; 5]) {
    for (tag, n) in sections {
        say!(
            "    section {:<4}        {n} bytes{}",
            String::from_utf8_lossy(tag),
            per_triangle(8.0 * *n as f64, triangles)
        );
    }
    // A displaced file's connectivity is its base's and the splits':
    // there is no CLERS string to show.
    if clers.iter().all(|&n| n == 0) {
        return;
    }
    let total: u64 = clers.iter().sum::<u64>().max(1);
    let hist: Vec<String> = ["C", "L", "E", "R", "S"]
        .iter()
        .zip(clers)
        .map(|(l, n)| format!("{l} {n} ({:.1}%)", 100.0 * n as f64 / total as f64))
        .collect();
    say!("  CLERS                 {}", hist.join(", "));
}

/// The figures of a SwingWrapper file, as JSON.
pub fn swing_json(info: &swm::FileInfo, s: &swm::SwingStats) -> serde_json::Value {
    let mut v = crate::report::swing_json(s);
    v["version"] = version(info).into();
    v["framing"] = framing(info).into();
    v["frame_bytes"] = info.frame_bytes.into();
    v["post"] = post_json(info);
    v
}

/// "compact" or "fixed".
fn framing(info: &swm::FileInfo) -> &'static str {
    match info.framing {
        swm::Framing::Fixed => "fixed",
        _ => "compact",
    }
}

/// The file's format version, "major.minor".
fn version(info: &swm::FileInfo) -> String {
    format!("{}.{}", info.version.0, info.version.1)
}

/// The first two lines of `swm info` on a `.swm` file, for both modes.
fn print_file_and_version(args: &Args, info: &swm::FileInfo) {
    say!("{}", args.file.display());
    say!("  format version        {}", version(info));
    say!(
        "  framing               {}, {} bytes",
        framing(info),
        info.frame_bytes
    );
}

/// `swm info` of a SwingWrapper file.
fn print_swing(args: &Args, info: &swm::FileInfo, s: &swm::SwingStats) -> Result<(), CliError> {
    if args.json {
        crate::report::print_json(&swing_json(info, s));
        return Ok(());
    }
    let t = s.triangles.max(1) as f64;
    print_file_and_version(args, info);
    say!(
        "  mode                  SwingWrapper, edge length L = {}, {} angle bits",
        s.edge_length,
        s.angle_bits
    );
    say!("  vertices              {}", s.vertices);
    say!("  triangles             {}", s.triangles);
    say!("  components            {}", s.components);
    say!("  handle events         {}", s.handle_events);
    if s.triangles == 0 {
        // Nothing retiled: the whole mesh is in REST (below).
        say!("  bytes                 {}", s.file_bytes);
    } else {
        say!(
            "  bytes                 {} ({:.3} bits/triangle)",
            s.file_bytes,
            8.0 * s.file_bytes as f64 / t
        );
        say!(
            "  connectivity          {:.3} bits/triangle",
            s.connectivity_bits_per_triangle
        );
        say!(
            "  geometry              {:.3} bits/triangle, {:.3} bits/angle",
            s.geometry_bits_per_triangle,
            s.bits_per_angle
        );
    }
    if s.holes_masked_triangles > 0 || s.hole_bytes > 0 {
        say!(
            "  holes                 {} masked triangles ({:.1}% of the retiled ones), {} bytes ({:.1}% of the file)",
            s.holes_masked_triangles,
            100.0 * s.masked_share(),
            s.hole_bytes,
            100.0 * s.hole_bytes as f64 / s.file_bytes.max(1) as f64
        );
    }
    if s.loops > 0 {
        say!(
            "  boundary loops        {} coded as {} points, {} bytes ({:.1}% of the file); their fans ({} triangles) are dropped",
            s.loops,
            s.loop_points,
            s.loop_bytes,
            100.0 * s.loop_bytes as f64 / s.file_bytes.max(1) as f64,
            s.loop_points
        );
    }
    if let Some((lo, hi)) = s.density_levels {
        say!(
            "  density               levels {lo} to {hi} (tip radius {:.2}-{:.2} times the first's), {} bytes ({:.1}% of the file)",
            2f64.powf(f64::from(lo) / 4.0),
            2f64.powf(f64::from(hi) / 4.0),
            s.density_bytes,
            100.0 * s.density_bytes as f64 / s.file_bytes.max(1) as f64
        );
    }
    if s.rest_bytes > 0 {
        say!(
            "  kept losslessly       {} {} not retiled, {} triangles, {} bytes",
            s.rest_components,
            if s.rest_components == 1 {
                "component"
            } else {
                "components"
            },
            s.rest_triangles,
            s.rest_bytes
        );
    }
    print_post(info);
    print_sections_and_clers(&s.sections, s.triangles, s.clers);
    say!("  C or R labels         {:.1}%", 100.0 * s.cr_share);
    say!("  valence-6 vertices    {:.1}%", 100.0 * s.valence6_share);
    Ok(())
}
