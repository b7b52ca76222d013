//! `swm encode` / `swm decode` / `swm info` on .swm files: round trips,
//! determinism, and clean errors on malformed files.

mod common;
use common::*;
use std::path::Path;

fn encode(input: &Path, output: &Path, qp: &str) {
    ok(&swm(&[
        "encode",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--mode",
        "lossless",
        "--qp",
        qp,
    ]));
}

#[test]
fn encode_decode_info_roundtrip() {
    let dir = scratch("cli-roundtrip");
    let input = dir.join("torus.ply");
    swm::io::write_mesh(&input, &swm_corpus::torus(1.0, 0.35, 48, 16)).unwrap();
    let swm_file = dir.join("torus.swm");
    encode(&input, &swm_file, "14");
    let first = std::fs::read(&swm_file).unwrap();
    encode(&input, &swm_file, "14");
    assert_eq!(
        first,
        std::fs::read(&swm_file).unwrap(),
        "encoding is not deterministic"
    );

    let info = json(&swm(&["info", swm_file.to_str().unwrap(), "--json"]));
    assert_eq!(info["mode"], "lossless");
    // The compact framing (format 1.1) is the default.
    assert_eq!(info["version"], "1.1");
    assert_eq!(info["framing"], "compact");
    assert_eq!(info["triangles"], 48 * 16 * 2);
    assert_eq!(info["qp"], 14);
    let clers = &info["clers"];
    let total: u64 = ["C", "L", "E", "R", "S"]
        .iter()
        .map(|k| clers[k].as_u64().unwrap())
        .sum();
    assert_eq!(total + info["components"].as_u64().unwrap(), 48 * 16 * 2);

    for ext in ["obj", "ply", "off"] {
        let output = dir.join(format!("back.{ext}"));
        let out = swm(&[
            "decode",
            swm_file.to_str().unwrap(),
            "-o",
            output.to_str().unwrap(),
            "--json",
        ]);
        let stats = json(&out);
        assert_eq!(stats["mode"], "lossless");
        assert_eq!(stats["vertices"], 48 * 16);
        let back = swm::io::read_mesh(&output).unwrap();
        assert_eq!(back.face_count(), 48 * 16 * 2);
        let v = json(&swm(&["info", output.to_str().unwrap(), "--json"]));
        assert_eq!(v["genus"], 1, "the decoded torus keeps its handle");
    }
    let leftovers = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| is_temporary(&e.as_ref().unwrap().file_name().to_string_lossy()));
    assert_eq!(leftovers.count(), 0, "temporary files left behind");
}

fn assert_clean_error(args: &[&str], file: &str, what: &str) {
    let out = swm_capped(args, 1 << 20);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{what}: {stderr}");
    assert!(
        stderr.starts_with("swm: error:") && stderr.contains(file),
        "{what}: {stderr}"
    );
    assert_eq!(stderr.trim_end().lines().count(), 1, "{what}: {stderr}");
}

#[test]
fn malformed_swm_files_are_clean_errors() {
    let dir = scratch("cli-malformed");
    let input = dir.join("sphere.obj");
    swm::io::write_mesh(&input, &swm_corpus::icosphere(1.0, 2)).unwrap();
    let good = dir.join("good.swm");
    encode(&input, &good, "12");
    let bytes = std::fs::read(&good).unwrap();
    let out = dir.join("out.obj");
    let mut cases: Vec<(String, Vec<u8>)> = vec![
        ("empty".into(), vec![]),
        ("truncated".into(), bytes[..bytes.len() / 2].to_vec()),
        ("mesh-not-swm".into(), std::fs::read(&input).unwrap()),
    ];
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 3] ^= 0x10;
    cases.push(("bit flip".into(), flipped));
    let mut newer = bytes.clone();
    newer[4] = 9; // major version
    cases.push(("newer major".into(), newer));
    let mut huge = bytes.clone();
    huge[9..13].copy_from_slice(&u32::MAX.to_le_bytes()); // vertex count
    let n = huge.len() - 4;
    let crc = swm::container::crc32(&huge[..n]);
    huge[n..].copy_from_slice(&crc.to_le_bytes());
    cases.push(("absurd count".into(), huge));
    for (what, data) in cases {
        let path = dir.join(format!("{}.swm", what.replace(' ', "-")));
        std::fs::write(&path, data).unwrap();
        let p = path.to_str().unwrap();
        assert_clean_error(&["decode", p, "-o", out.to_str().unwrap()], p, &what);
        assert_clean_error(&["info", p], p, &what);
        assert!(!out.exists(), "{what}: an output file was written");
    }
}

#[test]
fn output_never_overwrites_input_with_garbage() {
    let dir = scratch("cli-same-path");
    let input = dir.join("m.obj");
    swm::io::write_mesh(&input, &swm_corpus::icosphere(1.0, 1)).unwrap();
    let before = std::fs::read(&input).unwrap();
    // Decoding a non-swm file onto itself fails and leaves it untouched.
    let p = input.to_str().unwrap();
    let out = swm(&["decode", p, "-o", p]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(std::fs::read(&input).unwrap(), before);
}

#[test]
fn bunny_is_smaller_than_draco() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    let dir = scratch("cli-draco");
    let output = dir.join("bunny.swm");
    encode(&corpus.join("stanford-bunny.obj"), &output, "11");
    let size = std::fs::metadata(&output).unwrap().len();
    println!("stanford-bunny at qp 11: {size} bytes (Draco level 10: 42,828; level 7: 46,952)");
    assert!(
        size <= 42_828,
        "{size} bytes: larger than Draco at its highest level"
    );
}

/// Runs swm with `stdin` piped in, returning its output.
fn swm_piped(args: &[&str], stdin: &[u8]) -> std::process::Output {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run swm");
    let mut pipe = child.stdin.take().unwrap();
    let input = stdin.to_vec();
    // Written from another thread: swm may fill stdout before it has
    // read all of stdin.
    let writer = std::thread::spawn(move || {
        let _ = pipe.write_all(&input);
    });
    let out = child.wait_with_output().expect("wait for swm");
    writer.join().unwrap();
    out
}

/// `-` for standard input and output: `encode - -o - --format obj` then
/// `decode - -o - --format obj` gives the mesh a file round trip gives,
/// with the reports on stderr and only the data on stdout.
#[test]
fn pipes_round_trip() {
    let dir = scratch("cli-pipes");
    let mesh = swm_corpus::torus(1.0, 0.35, 24, 8);
    let obj = dir.join("torus.obj");
    swm::io::write_mesh(&obj, &mesh).unwrap();
    let text = std::fs::read(&obj).unwrap();

    let args = [
        "encode", "-", "-o", "-", "--format", "obj", "--mode", "lossless",
    ];
    let encoded = swm_piped(&args, &text);
    ok(&encoded);
    let from_file = dir.join("torus.swm");
    encode(&obj, &from_file, "12");
    assert_eq!(encoded.stdout, std::fs::read(&from_file).unwrap());
    let report = String::from_utf8_lossy(&encoded.stderr);
    assert!(
        report.contains("bytes"),
        "the summary goes to stderr: {report}"
    );

    let decoded = swm_piped(
        &["decode", "-", "-o", "-", "--format", "obj"],
        &encoded.stdout,
    );
    ok(&decoded);
    let back = swm::io::read_mesh_bytes(
        &decoded.stdout,
        swm::io::MeshFormat::Obj,
        &swm::Limits::default(),
    )
    .unwrap();
    let out = dir.join("back.obj");
    ok(&swm(&[
        "decode",
        from_file.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(decoded.stdout, std::fs::read(&out).unwrap());
    assert_eq!(back.face_count(), mesh.face_count());
    // --json goes to stderr too, whole.
    let args = ["decode", "-", "-o", "-", "--format", "glb", "--json"];
    let glb = swm_piped(&args, &encoded.stdout);
    ok(&glb);
    assert_eq!(&glb.stdout[..4], b"glTF");
    let v: serde_json::Value = serde_json::from_slice(&glb.stderr).unwrap();
    assert_eq!(v["mode"], "lossless");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Without --format, standard input or output is a usage error; a
/// format is taken from --format for a file without an extension; a
/// failed decode writes nothing to stdout.
#[test]
fn pipes_need_a_format() {
    let dir = scratch("cli-pipes-format");
    // One line naming the pipe and the missing option, for either side.
    for args in [
        &["encode", "-", "-o", "x.swm", "--mode", "lossless"][..],
        &["decode", "-", "-o", "-"],
        &["decode", "x.swm", "-o", "-"],
    ] {
        let o = swm_piped(args, b"");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
        assert!(
            stderr.starts_with("swm: error: -: ") && stderr.contains("needs --format"),
            "{args:?}: {stderr}"
        );
        assert!(o.stdout.is_empty(), "{args:?}");
    }
    let o = swm_piped(&["decode", "-", "-o", "-", "--format", "gltf"], b"");
    assert_eq!(o.status.code(), Some(2));
    let o = swm_piped(&["decode", "-", "-o", "-", "--format", "xyz"], b"");
    assert_eq!(o.status.code(), Some(2));
    let o = swm_piped(
        &["decode", "-", "-o", "-", "--format", "obj"],
        b"not a swm file",
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty());
    // Standard input is bounded as files are.
    let args = [
        "decode",
        "-",
        "-o",
        "-",
        "--format",
        "obj",
        "--max-input",
        "10",
    ];
    let o = swm_piped(&args, &[0u8; 100]);
    assert_eq!(o.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("more than the input limit of 10"),
        "{stderr}"
    );

    let bare = dir.join("mesh");
    swm::io::write_mesh_as(
        &bare,
        swm::io::MeshFormat::Ply,
        &swm_corpus::icosphere(1.0, 1),
    )
    .unwrap();
    let out = dir.join("out");
    let (b, o) = (bare.to_str().unwrap(), out.to_str().unwrap());
    ok(&swm(&[
        "encode", b, "-o", o, "--format", "ply", "--mode", "lossless",
    ]));
    let back = dir.join("back");
    ok(&swm(&[
        "decode",
        o,
        "-o",
        back.to_str().unwrap(),
        "--format",
        "off",
    ]));
    let mesh = swm::io::read_mesh_as(&back, swm::io::MeshFormat::Off, &Default::default());
    assert_eq!(mesh.unwrap().face_count(), 80);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--mode displaced` (format 1.2): the file is on size, says mode 2 and
/// version 1.2, decodes to the counts it announces, is the same on a
/// second encode, and options of other modes are refused.
#[test]
fn displaced_mode_round_trips_on_size() {
    let dir = scratch("cli-displaced");
    let input = dir.join("sphere.ply");
    // Fine enough (20,480 triangles) that 2,000 bytes is far from the
    // whole mesh, with a hole for the boundary rules.
    let m = swm_corpus::icosphere(1.0, 5);
    let keep = m.triangles.iter().copied();
    let keep = keep.filter(|t| t.iter().any(|&v| m.positions[v as usize][2] < 0.7));
    let mesh = swm::TriMesh::new(m.positions.clone(), keep.collect());
    swm::io::write_mesh(&input, &mesh).unwrap();
    let file = dir.join("sphere.swm");
    let (i, f) = (input.to_str().unwrap(), file.to_str().unwrap());
    let args = [
        "encode",
        i,
        "-o",
        f,
        "--mode",
        "displaced",
        "--size",
        "2000",
        "--json",
    ];
    let report = json(&swm(&args));
    assert_eq!(report["mode"], "displaced");
    let bytes = std::fs::read(&file).unwrap();
    assert!(
        (1940..=2000).contains(&bytes.len()),
        "{} bytes",
        bytes.len()
    );
    // The report counts the file's bytes as every mode's does.
    assert_eq!(report["bytes"].as_u64(), Some(bytes.len() as u64));
    ok(&swm(&args));
    assert_eq!(bytes, std::fs::read(&file).unwrap(), "not deterministic");

    let info = json(&swm(&["info", f, "--json"]));
    assert_eq!(info["mode"], "displaced");
    assert_eq!(info["version"], "1.2");
    let levels = report["levels"].as_u64().unwrap();
    let base = report["base_faces"].as_u64().unwrap();
    assert_eq!(info["triangles"].as_u64().unwrap(), base << (2 * levels));

    let back = dir.join("back.ply");
    ok(&swm(&["decode", f, "-o", back.to_str().unwrap()]));
    let mesh = swm::io::read_mesh(&back).unwrap();
    assert_eq!(mesh.face_count() as u64, base << (2 * levels));

    let refused = swm(&[
        "encode",
        i,
        "-o",
        f,
        "--mode",
        "displaced",
        "--size",
        "2000",
        "--qp",
        "9",
    ]);
    assert!(!refused.status.success());
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("--qp does not apply to --mode displaced"),
        "{err}"
    );
}
