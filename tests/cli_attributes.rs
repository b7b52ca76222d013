//! `swm encode` on inputs that carry vertex attributes (texture
//! coordinates, normals, colours): the lossless, automatic and simplified
//! modes keep them (`ATTR`, format 1.2) without a warning and say so in
//! the report; the swing mode does not code them, and says so in one
//! warning line on stderr naming exactly what was found, stdout (text or
//! `--json`) the same as for the bare mesh.

mod common;
use common::*;
use serde_json::{json, Value};
use std::path::Path;
use std::process::Output;

fn torus() -> swm::TriMesh {
    swm_corpus::torus(1.0, 0.35, 48, 16)
}

/// The torus as OBJ, with `extra` statements before its faces.
fn obj(extra: &str) -> String {
    let m = torus();
    let mut s = String::new();
    for [x, y, z] in &m.positions {
        s.push_str(&format!("v {x} {y} {z}\n"));
    }
    s.push_str(extra);
    for [a, b, c] in &m.triangles {
        s.push_str(&format!("f {} {} {}\n", a + 1, b + 1, c + 1));
    }
    s
}

/// The torus as ASCII PLY with vertex normals and colours.
fn ply_with_normals_and_colours() -> String {
    let m = torus();
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        m.positions.len(),
        m.triangles.len()
    );
    for [x, y, z] in &m.positions {
        s.push_str(&format!("{x} {y} {z} 0 0 1 200 100 50\n"));
    }
    for [a, b, c] in &m.triangles {
        s.push_str(&format!("3 {a} {b} {c}\n"));
    }
    s
}

/// The torus as GLB with a TEXCOORD_0 accessor.
fn glb_with_texcoords() -> Vec<u8> {
    let m = torus();
    let n = m.positions.len();
    let mut bin: Vec<u8> = m
        .positions
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    let uv_at = bin.len();
    bin.extend((0..2 * n).flat_map(|k| (k as f32 / n as f32).to_le_bytes()));
    let index_at = bin.len();
    bin.extend(m.triangles.iter().flatten().flat_map(|i| i.to_le_bytes()));
    let doc = json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteLength": uv_at},
            {"buffer": 0, "byteOffset": uv_at, "byteLength": index_at - uv_at},
            {"buffer": 0, "byteOffset": index_at, "byteLength": bin.len() - index_at}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5125, "count": 3 * m.triangles.len(), "type": "SCALAR"}
        ]
    });
    glb(&doc, &bin)
}

fn encode(input: &Path, extra: &[&str]) -> Output {
    let output = input.with_extension("swm");
    let mut args = vec![
        "encode",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
    ];
    args.extend(extra);
    swm(&args)
}

/// The report without its timings, which differ from run to run.
fn untimed(v: &Value) -> Value {
    match v {
        Value::Object(map) => Value::Object(
            map.iter()
                .filter(|(k, _)| !k.ends_with("seconds"))
                .map(|(k, v)| (k.clone(), untimed(v)))
                .collect(),
        ),
        Value::Array(items) => Value::Array(items.iter().map(untimed).collect()),
        other => other.clone(),
    }
}

/// The text report's lines, the time at the end of the first cut off.
fn untimed_text(out: &Output) -> Vec<String> {
    ok(out)
        .lines()
        .map(|l| match l.rsplit_once(", ") {
            Some((head, tail)) if tail.ends_with(" s") => head.to_string(),
            _ => l.to_string(),
        })
        .collect()
}

/// The warning lines of a run's stderr.
fn warnings(out: &Output) -> Vec<String> {
    String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| l.starts_with("swm: warning:"))
        .map(str::to_string)
        .collect()
}

/// Encodes `file` and the bare torus the same ways. The lossless mode,
/// the automatic mode and the lossless mode at a size keep the streams
/// the reader attached (`streams` of them; none warns with the reader's
/// reason, and then stdout is the bare mesh's); `--json` names them under
/// `attribute_report`, and so do the displaced and swing modes unless
/// they include texture coordinates: then those modes drop them with one
/// warning naming `names`, and their stdout (text and JSON) is the bare
/// mesh's.
fn check(dir: &Path, file: &Path, names: &str, streams: usize) {
    let unattached = format!(
        "swm: warning: {}: the input's {names} are not kept (not every face corner names them, or a value is malformed)",
        file.display()
    );
    let out = encode(file, &["--mode", "lossless"]);
    if streams == 0 {
        // Values no face corner names (`f 1 2 3` after `vt` lines) stay
        // behind, and the warning says why.
        assert_eq!(warnings(&out), [unattached.clone()]);
    } else {
        assert!(warnings(&out).is_empty(), "{:?}", warnings(&out));
    }
    let bytes = std::fs::read(file.with_extension("swm")).unwrap();
    let decoded = swm::decode_attributed(&bytes, &Default::default()).unwrap();
    assert_eq!(decoded.streams.len(), streams);
    let bare = dir.join("bare.obj");
    std::fs::write(&bare, obj("")).unwrap();
    let text = |o: &Output| -> Vec<String> {
        // The input's name differs; the rest must not.
        let name = |p: &Path| p.display().to_string();
        untimed_text(o)
            .into_iter()
            .map(|l| l.replace(&name(file), "IN").replace(&name(&bare), "IN"))
            .map(|l| l.replace(&name(&file.with_extension("swm")), "OUT"))
            .map(|l| l.replace(&name(&bare.with_extension("swm")), "OUT"))
            .collect()
    };
    for mode in [
        // Rates that leave the geometry room beside the streams (at the
        // default 2 b/v a torus's normals and colours take most of 192
        // bytes).
        &["--mode", "auto", "--bpv", "12"][..],
        &["--mode", "lossless", "--size", "1200"],
        &["--mode", "displaced", "--bpv", "12"],
        &["--mode", "swing", "--bpv", "12"],
    ] {
        let plain = encode(&bare, mode);
        assert!(warnings(&plain).is_empty(), "{:?}", warnings(&plain));
        let out = encode(file, mode);
        let json_args: Vec<&str> = mode.iter().copied().chain(["--json"]).collect();
        let out_json = encode(file, &json_args);
        // Displaced and SwingWrapper files carry all but texture
        // coordinates.
        let uvs = names.contains("texture coordinates");
        let kept = streams > 0 && !(matches!(mode[1], "displaced" | "swing") && uvs);
        if kept {
            // A retiled mesh's size moves in steps (its edge length), and
            // on this small torus the streams are most of the file:
            // SwingWrapper may land outside 3% of the request, and says so.
            let landed =
                |w: &String| mode[1] == "swing" && w.contains("rate control could not land");
            let other: Vec<_> = warnings(&out).into_iter().filter(|w| !landed(w)).collect();
            assert!(other.is_empty(), "{mode:?}: {other:?}");
            let bytes = std::fs::read(file.with_extension("swm")).unwrap();
            let decoded = swm::decode_attributed(&bytes, &Default::default()).unwrap();
            assert_eq!(decoded.streams.len(), streams, "{mode:?}");
            assert!(ok(&out).contains("attributes kept: "), "{mode:?}");
            let v = json(&out_json);
            assert_eq!(
                v["attribute_report"]["kept"].as_array().unwrap().len(),
                streams
            );
            assert_eq!(v["attribute_report"]["dropped"], json!([]));
            continue;
        }
        let expected = if streams == 0 {
            unattached.clone()
        } else {
            let why = format!(
                "the {} method's file cannot carry texture coordinates",
                mode[1]
            );
            format!(
                "swm: warning: {}: the input's {names} are not kept ({why}; --mode auto keeps them)",
                file.display()
            )
        };
        assert_eq!(warnings(&out), [expected], "{mode:?}");
        assert_eq!(text(&out), text(&plain), "{mode:?}");
        assert!(!ok(&out).contains("warning"));
        assert_eq!(warnings(&out_json).len(), 1);
        assert_eq!(
            untimed(&json(&out_json)),
            untimed(&json(&encode(&bare, &json_args))),
            "{mode:?}"
        );
    }
}

#[test]
fn obj_texture_coordinates_and_normals() {
    let dir = scratch("attributes-obj");
    let file = dir.join("uv.obj");
    std::fs::write(&file, obj("vt 0 0\nvt 1 0\nvn 0 0 1\n")).unwrap();
    check(&dir, &file, "texture coordinates and normals", 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn ply_normals_and_colours() {
    let dir = scratch("attributes-ply");
    let file = dir.join("painted.ply");
    std::fs::write(&file, ply_with_normals_and_colours()).unwrap();
    check(&dir, &file, "normals and colours", 2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn gltf_texcoord_0() {
    let dir = scratch("attributes-glb");
    let file = dir.join("textured.glb");
    std::fs::write(&file, glb_with_texcoords()).unwrap();
    check(&dir, &file, "texture coordinates", 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A bare mesh, and STL whose facet normals are no vertex attribute,
/// give no warning.
#[test]
fn bare_meshes_and_stl_warn_of_nothing() {
    let dir = scratch("attributes-none");
    for name in ["bare.obj", "bare.stl", "bare.ply", "bare.off"] {
        let file = dir.join(name);
        swm::io::write_mesh(&file, &torus()).unwrap();
        let out = encode(&file, &["--mode", "lossless"]);
        ok(&out);
        // stderr may say what cleaning did (STL's welded corners), but
        // warns of nothing.
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("warning"), "{name}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// On the pipe path too: the input named `-`, the warning on stderr, and
/// with `-o -` the file alone on stdout.
#[test]
fn standard_input_warns_too() {
    let dir = scratch("attributes-stdin");
    let file = dir.join("uv.obj");
    std::fs::write(&file, obj("vt 0 0\n")).unwrap();
    let run = |output: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_swm"))
            .args([
                "encode", "-", "--format", "obj", "-o", output, "--mode", "lossless", "--size",
                "900",
            ])
            .stdin(std::fs::File::open(&file).unwrap())
            .output()
            .unwrap()
    };
    let to_file = dir.join("uv.swm");
    let out = run(to_file.to_str().unwrap());
    ok(&out);
    let expected = "swm: warning: -: the input's texture coordinates are not kept (not every face corner names them, or a value is malformed)";
    assert_eq!(warnings(&out), [expected]);
    let piped = run("-");
    ok(&piped);
    assert_eq!(warnings(&piped), [expected]);
    assert_eq!(piped.stdout, std::fs::read(&to_file).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The torus as ASCII PLY with its own smooth vertex normals (as a
/// scanner or a smooth-shading exporter writes them).
fn ply_with_smooth_normals() -> String {
    let m = torus();
    let normals = swm::vertex_normals(&m);
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        m.positions.len(),
        m.triangles.len()
    );
    for ([x, y, z], [a, b, c]) in m.positions.iter().zip(&normals) {
        s.push_str(&format!("{x} {y} {z} {a} {b} {c}\n"));
    }
    for [a, b, c] in &m.triangles {
        s.push_str(&format!("3 {a} {b} {c}\n"));
    }
    s
}

#[test]
fn normals_that_follow_the_geometry_are_left_to_decoders_unless_asked() {
    let dir = scratch("attributes-smooth");
    let file = dir.join("scan.ply");
    std::fs::write(&file, ply_with_smooth_normals()).unwrap();
    let out = encode(&file, &["--bpv", "4"]);
    assert!(warnings(&out).is_empty(), "{:?}", warnings(&out));
    let said = ok(&out);
    assert!(
        said.contains("attributes kept: none; normals not coded: the normals follow the geometry"),
        "{said}"
    );
    let bytes = std::fs::read(file.with_extension("swm")).unwrap();
    let decoded = swm::decode_attributed(&bytes, &Default::default()).unwrap();
    assert!(decoded.streams.is_empty());
    let v = json(&encode(&file, &["--bpv", "4", "--json"]));
    assert_eq!(v["attribute_report"]["dropped"], json!(["normals"]));
    // The same file as the bare mesh's.
    let bare = dir.join("bare.obj");
    std::fs::write(&bare, obj("")).unwrap();
    encode(&bare, &["--bpv", "4"]);
    assert_eq!(std::fs::read(bare.with_extension("swm")).unwrap(), bytes);
    // Asked for, they are coded.
    let out = encode(&file, &["--bpv", "4", "--keep-normals"]);
    assert!(
        ok(&out).contains("attributes kept: normals"),
        "{}",
        ok(&out)
    );
    let bytes = std::fs::read(file.with_extension("swm")).unwrap();
    let decoded = swm::decode_attributed(&bytes, &Default::default()).unwrap();
    assert_eq!(decoded.streams.len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The torus as OBJ with a texture coordinate per vertex (its positions'
/// x and y, a chart without seams).
fn obj_with_texcoords() -> String {
    let m = torus();
    let mut s = String::new();
    for [x, y, z] in &m.positions {
        s.push_str(&format!("v {x} {y} {z}\n"));
    }
    for [x, y, _] in &m.positions {
        s.push_str(&format!("vt {} {}\n", 0.5 + 0.3 * x, 0.5 + 0.3 * y));
    }
    for [a, b, c] in &m.triangles {
        let (a, b, c) = (a + 1, b + 1, c + 1);
        s.push_str(&format!("f {a}/{a} {b}/{b} {c}/{c}\n"));
    }
    s
}

#[test]
fn a_size_below_the_smallest_file_with_the_streams_keeps_the_surface_and_says_so() {
    let dir = scratch("attributes-no-room");
    let file = dir.join("textured.obj");
    std::fs::write(&file, obj_with_texcoords()).unwrap();
    // Room for the texture coordinates: kept.
    let out = encode(&file, &["--bpv", "8"]);
    assert!(warnings(&out).is_empty(), "{:?}", warnings(&out));
    assert!(ok(&out).contains("attributes kept: texture coordinates 0"));
    // A size the surface fits and the coordinates do not: the surface,
    // a warning naming what was lost, and --strict refuses.
    // (At 90 bytes the torus is coarse enough for the fidelity warning
    // too.)
    let out = encode(&file, &["--size", "90"]);
    let warned = warnings(&out);
    assert!(
        warned.iter().any(|w| w.contains("the input's texture coordinates 0 are not kept (the size asked for is below the smallest file that keeps them")),
        "{warned:?}"
    );
    let bytes = std::fs::read(file.with_extension("swm")).unwrap();
    assert!(bytes.len() <= 90);
    let decoded = swm::decode_attributed(&bytes, &Default::default()).unwrap();
    assert!(decoded.streams.is_empty());
    let v = json(&encode(&file, &["--size", "90", "--json"]));
    assert_eq!(
        v["attribute_report"]["dropped"],
        json!(["texture coordinates 0"])
    );
    std::fs::remove_file(file.with_extension("swm")).unwrap();
    let out = encode(&file, &["--size", "90", "--strict"]);
    assert!(!out.status.success());
    assert!(!file.with_extension("swm").exists(), "nothing written");
    // A mode that cannot carry them: a warning, or with --strict an error.
    let out = encode(&file, &["--mode", "swing", "--strict"]);
    assert!(!out.status.success());
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("--strict: the input's texture coordinates are not kept (the swing method's file cannot carry texture coordinates"),
        "{said}"
    );
    assert!(!file.with_extension("swm").exists(), "nothing written");
    let _ = std::fs::remove_dir_all(&dir);
}

/// beetle's crease normals (12.1° RMS off its geometry's own) at 454
/// bytes would leave its surface 443e-4 of the diagonal off: the file
/// without them is written, with a warning that says why and how to keep
/// them; `--strict` refuses, `--keep-normals` keeps them, and a size
/// with room for both keeps them.
#[test]
fn normals_that_crowd_the_surface_out_are_dropped_with_a_warning() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    let dir = scratch("attributes-costly-normals");
    let file = dir.join("beetle.obj");
    std::fs::copy(corpus.join("beetle.obj"), &file).unwrap();
    let out = encode(&file, &["--size", "454"]);
    let warned = warnings(&out);
    assert!(
        warned.iter().any(|w| w.contains("the input's normals are not kept (the normals (12.1 degrees RMS off the geometry's) cost the surface more than they give at this size")
            && w.ends_with("--keep-normals keeps them)")),
        "{warned:?}"
    );
    let decoded = swm::decode_attributed(
        &std::fs::read(file.with_extension("swm")).unwrap(),
        &Default::default(),
    )
    .unwrap();
    assert!(decoded.streams.is_empty());
    let v = json(&encode(&file, &["--size", "454", "--json"]));
    assert_eq!(v["attribute_report"]["dropped"], json!(["normals"]));
    let l2 = v["check"]["l2_relative"].as_f64().unwrap();
    let kept = json(&encode(
        &file,
        &["--size", "454", "--keep-normals", "--json"],
    ));
    assert_eq!(kept["attribute_report"]["kept"], json!(["normals"]));
    assert!(l2 * 4.0 < kept["check"]["l2_relative"].as_f64().unwrap());
    std::fs::remove_file(file.with_extension("swm")).unwrap();
    let out = encode(&file, &["--size", "454", "--strict"]);
    assert!(!out.status.success());
    assert!(!file.with_extension("swm").exists(), "nothing written");
    let v = json(&encode(&file, &["--size", "4600", "--json"]));
    assert_eq!(v["attribute_report"]["kept"], json!(["normals"]));
    let _ = std::fs::remove_dir_all(&dir);
}

/// An edge length asks for SwingWrapper, which keeps no texture
/// coordinates: the automatic mode says so and names both ways out, and
/// forcing the method encodes (dropping them, with a warning).
#[test]
fn an_edge_length_on_a_textured_mesh_says_what_it_asks_for() {
    let dir = scratch("attributes-edge-length");
    let file = dir.join("textured.glb");
    std::fs::write(&file, glb_with_texcoords()).unwrap();
    let out = encode(&file, &["--edge-length", "0.2"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("asks for the swing method, which keeps no attribute streams")
            && err.contains("--mode swing"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    let out = encode(&file, &["--edge-length", "0.2", "--mode", "swing"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `swm decode --sharpen` or `--bend N` on a file with attribute streams
/// post-processes the mesh as asked, and since that changes the mesh the
/// streams were coded over, leaves them out with one warning.
#[test]
fn post_processing_asked_for_leaves_the_streams_out_and_says_so() {
    let dir = scratch("attributes-post");
    let file = dir.join("painted.ply");
    std::fs::write(&file, ply_with_normals_and_colours()).unwrap();
    let out = encode(&file, &["--mode", "lossless"]);
    assert!(out.status.success());
    let swm_file = file.with_extension("swm");
    let plain = dir.join("plain.obj");
    let out = swm(&[
        "decode",
        swm_file.to_str().unwrap(),
        "-o",
        plain.to_str().unwrap(),
    ]);
    assert!(warnings(&out).is_empty(), "{:?}", warnings(&out));
    // Colours are the fourth to sixth number of an OBJ `v` line.
    let coloured = |text: &str| {
        text.lines()
            .any(|l| l.starts_with("v ") && l.split(' ').count() == 7)
    };
    assert!(coloured(&std::fs::read_to_string(&plain).unwrap()));
    let bent = dir.join("bent.obj");
    let out = swm(&[
        "decode",
        swm_file.to_str().unwrap(),
        "-o",
        bent.to_str().unwrap(),
        "--bend",
        "1",
    ]);
    assert!(out.status.success());
    assert_eq!(
        warnings(&out),
        [format!(
            "swm: warning: {}: the file's attributes are not written (--sharpen and --bend change the mesh they were coded over)",
            swm_file.display()
        )]
    );
    let text = std::fs::read_to_string(&bent).unwrap();
    assert!(!coloured(&text));
    let bytes = std::fs::read(&swm_file).unwrap();
    let options = swm::DecodeOptions {
        bend_steps: Some(1),
        ..Default::default()
    };
    let mesh = swm::decode(&bytes, &options).unwrap();
    let vertices = text.lines().filter(|l| l.starts_with("v ")).count();
    assert_eq!(vertices, mesh.vertex_count());
    let _ = std::fs::remove_dir_all(&dir);
}
