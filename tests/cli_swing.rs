//! `swm encode` in the SwingWrapper mode (the default) end to end: the
//! three targets, the size cap, determinism, `swm decode` and `swm info`
//! on the files, and clean refusals of what the mode does not take yet.
//!
//! The test mesh is an ellipsoid (an icosphere of 2,562 vertices with
//! axes 1, 0.7 and 0.45), written to a scratch folder: closed, genus 0,
//! and less symmetric than a sphere. Every encode takes well under a
//! second.

mod common;
use common::*;
use std::path::{Path, PathBuf};
use std::process::Output;

/// Vertices of the test ellipsoid (icosphere, 4 subdivisions).
const VERTICES: u64 = 2562;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Writes the test ellipsoid into a fresh scratch folder.
fn ellipsoid(name: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let mut mesh = swm_corpus::icosphere(1.0, 4);
    for p in &mut mesh.positions {
        p[1] *= 0.7;
        p[2] *= 0.45;
    }
    assert_eq!(mesh.positions.len() as u64, VERTICES);
    let path = dir.join("ellipsoid.obj");
    swm::io::write_mesh(&path, &mesh).unwrap();
    (dir, path)
}

/// `swm encode IN -o OUT EXTRA... --json`, parsed.
fn encode_json(input: &Path, output: &Path, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["encode", s(input), "-o", s(output)];
    args.extend_from_slice(extra);
    args.push("--json");
    json(&swm(&args))
}

/// A failed run: exit status 1, one line on stderr naming `file`.
fn one_line_error(out: &Output, file: &Path) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(
        err.starts_with(&format!("swm: error: {}: ", file.display())),
        "{err}"
    );
    err
}

/// Names of the files in `dir` that `keep` rejects.
fn files_but(dir: &Path, keep: impl Fn(&str) -> bool) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| !keep(f))
        .collect()
}

/// Neither `output` nor a temporary file of any output is in its folder.
fn assert_no_output(output: &Path) {
    assert!(!output.exists(), "{} was written", output.display());
    let left = files_but(output.parent().unwrap(), |f| !is_temporary(f));
    assert!(left.is_empty(), "temporary files left behind: {left:?}");
}

/// Checks the encoder's JSON against the file on disk and the request;
/// returns (bytes, triangles).
fn check_encoded(v: &serde_json::Value, file: &Path, requested: Option<u64>) -> (u64, u64) {
    assert_eq!(v["mode"], "swing", "{v}");
    // Rate control chooses the angle bits for a size or a rate (6, or 5
    // or 7: see `swm::EncodeMode::Swing`); an edge length keeps 8.
    let bits = v["angle_bits"].as_u64().unwrap();
    if requested.is_some() {
        assert!((5..=7).contains(&bits), "{v}");
    } else {
        assert_eq!(bits, u64::from(swm::DEFAULT_ANGLE_BITS), "{v}");
    }
    let bytes = v["bytes"].as_u64().unwrap();
    assert_eq!(bytes, std::fs::metadata(file).unwrap().len());
    let triangles = v["triangles"].as_u64().unwrap();
    let vertices = v["vertices"].as_u64().unwrap();
    // A closed genus-0 triangle mesh: T = 2V - 4.
    assert!(triangles >= 4 && triangles == 2 * vertices - 4, "{v}");
    assert_eq!(v["input_vertices"], VERTICES);
    let rate = &v["rate_control"];
    assert_eq!(rate["requested_bytes"].as_u64(), requested, "{v}");
    let within = rate["within_tolerance"].as_bool().expect("a verdict");
    if let (Some(r), true) = (requested, within) {
        let miss = (bytes as f64 - r as f64).abs() / r as f64;
        assert!(miss <= 0.03, "{bytes} bytes for {r} requested: {v}");
    }
    // The file is one of the retilings the search reports.
    let attempts = rate["attempts"].as_array().unwrap();
    assert!(
        attempts
            .iter()
            .any(|a| a["edge_length"] == rate["edge_length"] && a["bytes"] == bytes),
        "{v}"
    );
    (bytes, triangles)
}

#[test]
fn the_three_targets_decode_and_inspect() {
    let (dir, input) = ellipsoid("swing-targets");
    let bpv = (2.0 * VERTICES as f64 / 8.0).round() as u64;
    let targets: [(&str, &[&str], Option<u64>); 4] = [
        ("bpv", &["--bpv", "2"], Some(bpv)),
        ("default", &[], Some(bpv)),
        ("size", &["--mode", "swing", "--size", "900"], Some(900)),
        ("length", &["--edge-length", "0.1"], None),
    ];
    let mut files = Vec::new();
    for (name, extra, requested) in targets {
        let file = dir.join(format!("{name}.swm"));
        let v = encode_json(&input, &file, extra);
        let (bytes, triangles) = check_encoded(&v, &file, requested);
        if name == "length" {
            let rate = &v["rate_control"];
            assert_eq!(rate["within_tolerance"], true, "{v}");
            if rate["reduced"] == false {
                // The file stores L as an f32.
                let l = v["edge_length"].as_f64().unwrap();
                assert!((l - 0.1).abs() < 1e-7, "{v}");
            }
        } else {
            // The ellipsoid is easy: the rate control must land.
            assert_eq!(v["rate_control"]["within_tolerance"], true, "{name}: {v}");
        }

        let info = json(&swm(&["info", s(&file), "--json"]));
        assert_eq!(info["mode"], "swing");
        // A retiling's symbols go in CLRF (format 1.1): smaller than CLRS.
        let tags: Vec<&str> = info["sections"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t["tag"].as_str().unwrap())
            .collect();
        assert!(
            tags.contains(&"CLRF") && !tags.contains(&"CLRS"),
            "{tags:?}"
        );
        assert_eq!(info["version"], "1.1");
        for key in [
            "bytes",
            "triangles",
            "vertices",
            "edge_length",
            "angle_bits",
        ] {
            assert_eq!(info[key], v[key], "{name}: {key}");
        }
        for key in ["cr_share", "valence6_share"] {
            let share = info[key].as_f64().unwrap();
            assert!((0.0..=1.0).contains(&share), "{key} {share}");
        }
        let clers: u64 = ["C", "L", "E", "R", "S"]
            .iter()
            .map(|k| info["clers"][k].as_u64().unwrap())
            .sum();
        assert!(clers > 0 && clers <= triangles, "{info}");

        let out = dir.join(format!("{name}.ply"));
        let d = json(&swm(&["decode", s(&file), "-o", s(&out), "--json"]));
        assert_eq!(d["mode"], "swing", "decode --json names the file's mode");
        assert_eq!(d["triangles"], triangles);
        assert_eq!(d["bytes"], bytes);
        assert!(d["decode_seconds"].as_f64().unwrap() >= 0.0);
        let back = json(&swm(&["info", s(&out), "--json"]));
        assert_eq!(back["faces"], triangles);
        assert_eq!(
            (&back["components"], &back["boundary_loops"], &back["genus"]),
            (&1.into(), &0.into(), &0.into()),
            "the retiled mesh is one closed sphere: {back}"
        );
        files.push(std::fs::read(&file).unwrap());
    }
    // No target means --bpv 2.
    assert_eq!(files[0], files[1], "the default target is not --bpv 2");

    // The text of `swm info` on a swing file.
    let out = swm(&["info", s(&dir.join("length.swm"))]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    for needle in [
        "SwingWrapper",
        "8 angle bits",
        "connectivity",
        "bits/angle",
        "C or R labels",
        "valence-6 vertices",
    ] {
        assert!(text.contains(needle), "no `{needle}` in:\n{text}");
    }
    let left = files_but(&dir, |f| !is_temporary(f));
    assert!(left.is_empty(), "temporary files left behind: {left:?}");
}

#[test]
fn encoding_is_deterministic() {
    let (dir, input) = ellipsoid("swing-determinism");
    for extra in [
        &["--bpv", "3"][..],
        &["--mode", "swing", "--size", "700", "--angle-bits", "6"],
    ] {
        let a = dir.join("a.swm");
        let b = dir.join("b.swm");
        for f in [&a, &b] {
            let mut args = vec!["encode", s(&input), "-o", s(f)];
            args.extend_from_slice(extra);
            let out = swm(&args);
            assert!(out.status.success(), "{out:?}");
        }
        let (a, b) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        assert!(!a.is_empty());
        assert_eq!(a, b, "{extra:?}: two encodings differ");
    }
    let info = json(&swm(&["info", s(&dir.join("a.swm")), "--json"]));
    assert_eq!(info["angle_bits"], 6);
}

#[test]
fn max_size_is_never_exceeded() {
    let (dir, input) = ellipsoid("swing-max-size");
    // A cap at and above the target must be met; a cap below the target,
    // or too small for any retiling of this shape, may give an error, but
    // never a larger file.
    for (target, cap, must) in [
        ("800", "800", true),
        ("500", "2000", true),
        ("1200", "1000", false),
        ("300", "40", false),
    ] {
        let file = dir.join("capped.swm");
        let _ = std::fs::remove_file(&file);
        let out = swm(&[
            "encode",
            s(&input),
            "-o",
            s(&file),
            "--size",
            target,
            "--max-size",
            cap,
            "--json",
        ]);
        let cap: u64 = cap.parse().unwrap();
        if out.status.success() {
            let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            let bytes = std::fs::metadata(&file).unwrap().len();
            assert_eq!(v["bytes"], bytes);
            assert!(bytes <= cap, "{bytes} bytes over a cap of {cap}");
        } else {
            one_line_error(&out, &input);
            assert_no_output(&file);
            assert!(!must, "a cap of {cap} should be reachable: {out:?}");
        }
    }
}

#[test]
fn swing_takes_holes_handles_and_components() {
    let dir = scratch("swing-topology");
    let mut open = swm_corpus::icosphere(1.0, 3);
    open.triangles.truncate(open.triangles.len() - 3);
    let mut two = swm_corpus::icosphere(1.0, 2);
    let shifted: Vec<[f32; 3]> = two
        .positions
        .iter()
        .map(|p| [p[0] + 3.0, p[1], p[2]])
        .collect();
    let n = two.positions.len() as u32;
    let more: Vec<[u32; 3]> = two.triangles.iter().map(|t| t.map(|v| v + n)).collect();
    two.positions.extend(shifted);
    two.triangles.extend(more);
    // (mesh, boundary loops, components, V − E + F) to keep.
    let meshes = [
        ("open.obj", open, 1, 1, 1),
        ("torus.off", swm_corpus::torus(1.0, 0.35, 96, 36), 0, 1, 0),
        ("two-spheres.ply", two, 0, 2, 4),
    ];
    for (name, mesh, loops, components, euler) in meshes {
        let input = dir.join(name);
        swm::io::write_mesh(&input, &mesh).unwrap();
        let output = dir.join("out.swm");
        let decoded = dir.join("out.obj");
        let out = swm(&[
            "encode",
            s(&input),
            "-o",
            s(&output),
            "--edge-length",
            "0.15",
        ]);
        assert!(out.status.success(), "{name}: {out:?}");
        let out = swm(&["decode", s(&output), "-o", s(&decoded)]);
        assert!(out.status.success(), "{name}: {out:?}");
        let m = swm::io::read_mesh(&decoded).unwrap();
        let table = swm::CornerTable::new(&m.triangles, m.vertex_count()).unwrap();
        assert_eq!(table.boundary_loops().len(), loops, "{name}");
        assert_eq!(table.component_labels().1 as usize, components, "{name}");
        let boundary = table.opposites().iter().filter(|o| o.is_none()).count() as i64;
        let (v, f) = (m.vertex_count() as i64, m.face_count() as i64);
        let e = (3 * f + boundary) / 2;
        assert_eq!(v - e + f, euler, "{name}");
    }
}

#[test]
fn bad_swing_options_are_usage_errors() {
    let (dir, input) = ellipsoid("swing-usage");
    let output = dir.join("out.swm");
    for (extra, option) in [
        (&["--size", "900", "--bpv", "2"][..], "--size"),
        (&["--bpv", "2", "--edge-length", "0.1"], "--bpv"),
        (&["--angle-bits", "3"], "--angle-bits"),
        (&["--angle-bits", "13"], "--angle-bits"),
        (&["--mode", "lossy"], "--mode"),
    ] {
        let mut args = vec!["encode", s(&input), "-o", s(&output)];
        args.extend_from_slice(extra);
        let out = swm(&args);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {out:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.lines().next().unwrap().contains(option),
            "{extra:?}: {err}"
        );
    }
    // Issue 18: values outside the range are usage errors too (exit 2),
    // the accepted range said plainly, never containing the refused value
    // nor f64::MAX's 309 digits.
    for (extra, option, accepted) in [
        (
            &["--bpv=-1"][..],
            "--bpv",
            "must be a positive finite number",
        ),
        (
            &["--edge-length", "0"],
            "--edge-length",
            "must be a positive finite number",
        ),
        (
            &["--bpv", "nan"],
            "--bpv",
            "must be a positive finite number",
        ),
        (
            &["--bpv", "inf"],
            "--bpv",
            "must be a positive finite number",
        ),
        (&["--size", "0"], "--size", "at least 1"),
        (&["--max-size", "0"], "--max-size", "at least 1"),
        (&["--size", "-5"], "--size", "at least 1"),
        (
            &["--edge-length", "-1"],
            "--edge-length",
            "must be a positive finite number",
        ),
    ] {
        let mut args = vec!["encode", s(&input), "-o", s(&output)];
        args.extend_from_slice(extra);
        let out = swm(&args);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {out:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        let first = err.lines().next().unwrap();
        assert!(
            first.contains(option) && first.contains(accepted),
            "{extra:?}: {err}"
        );
        assert!(!err.contains("17976931348623157"), "{extra:?}: {err}");
    }
    // Options of the other mode are refused, not silently ignored.
    for (extra, named) in [
        (&["--qp", "10"][..], &["--qp"][..]),
        (&["--mode", "swing", "--qp", "12"], &["--qp"]),
        (&["--mode", "auto", "--angle-bits", "6"], &["--angle-bits"]),
        (
            &["--mode", "lossless", "--size", "900", "--qp", "9"],
            &["--qp with --size"],
        ),
        (
            &["--mode", "lossless", "--edge-length", "0.1"],
            &["--edge-length"],
        ),
        (
            &[
                "--mode",
                "lossless",
                "--angle-bits",
                "8",
                "--max-size",
                "99",
            ],
            &["--angle-bits", "--max-size"],
        ),
    ] {
        let mut args = vec!["encode", s(&input), "-o", s(&output)];
        args.extend_from_slice(extra);
        let out = swm(&args);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {out:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        let first = err.lines().next().unwrap();
        assert!(
            first.contains("does not apply") || first.contains("do not apply"),
            "{err}"
        );
        for n in named {
            assert!(first.contains(n), "{extra:?}: {err}");
        }
        assert!(err.contains("Usage: swm encode"), "{err}");
    }
    // Each mode's own options still work.
    let lossless = dir.join("lossless.swm");
    ok(&swm(&[
        "encode",
        s(&input),
        "-o",
        s(&lossless),
        "--mode",
        "lossless",
        "--qp",
        "10",
    ]));
    assert_no_output(&output);
}

/// A tetrahedron at 4 b/v is below what retiling is worth: the file keeps
/// it whole in `REST`, decodes to it, and neither `encode` nor `info`
/// invents a bits-per-triangle figure for the empty retiled mesh.
#[test]
fn a_mesh_too_small_to_retile_is_kept_in_rest() {
    let dir = scratch("swing_all_rest");
    let input = dir.join("tet.obj");
    std::fs::write(
        &input,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let file = dir.join("tet.swm");
    // The default mode will not write 91 bytes for an explicit 1-byte
    // request, and says how to get them...
    let refused = swm(&["encode", s(&input), "-o", s(&file), "--size", "1"]);
    assert_eq!(refused.status.code(), Some(1));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("the smallest possible is") && err.contains("--or-smallest"),
        "{err}"
    );
    assert!(!file.exists());
    // ... while with no size at all (the default 2 b/v asks for 1 byte)
    // the smallest file is written, with a note.
    let written = swm(&["encode", s(&input), "-o", s(&file)]);
    let err = String::from_utf8_lossy(&written.stderr);
    assert_eq!(written.status.code(), Some(0), "{err}");
    assert!(err.contains("no size was given"), "{err}");
    assert!(file.exists());
    std::fs::remove_file(&file).unwrap();
    // ... the swing mode keeps the nearest file it made.
    let summary = ok(&swm(&[
        "encode",
        s(&input),
        "-o",
        s(&file),
        "--mode",
        "swing",
    ]));
    assert!(
        summary.contains("0 triangles, no bits/triangle"),
        "{summary}"
    );
    let info = swm(&["info", s(&file)]);
    let text = String::from_utf8_lossy(&info.stdout).into_owned();
    assert!(
        text.contains("kept losslessly       1 component not retiled, 4 triangles"),
        "{text}"
    );
    assert!(!text.contains("bits/triangle"), "{text}");
    let obj = dir.join("tet.obj.out.obj");
    let out = swm(&["decode", s(&file), "-o", s(&obj)]);
    assert!(out.status.success());
    let decoded = swm::io::read_mesh(&obj).unwrap();
    assert_eq!((decoded.vertex_count(), decoded.face_count()), (4, 4));
}

/// Issue 18: a mesh of many components does not print a line per
/// component (on stderr): the first few, then the rest counted by fate;
/// `--verbose` lists them all, and JSON always has them all.
#[test]
fn long_component_reports_are_summarized() {
    let dir = scratch("swing-many-pieces");
    let mut mesh = swm_corpus::icosphere(1.0, 3);
    // Tetrahedra far below the edge length, each its own component.
    const TINY: usize = 500;
    for k in 0..TINY {
        let base = mesh.positions.len() as u32;
        let (x, y) = (3.0 + (k % 25) as f32 * 0.1, (k / 25) as f32 * 0.1);
        for d in [
            [0.0, 0.0, 0.0],
            [0.01, 0.0, 0.0],
            [0.0, 0.01, 0.0],
            [0.0, 0.0, 0.01],
        ] {
            mesh.positions.push([x + d[0], y + d[1], d[2]]);
        }
        for t in [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]] {
            mesh.triangles.push(t.map(|v| v + base));
        }
    }
    let input = dir.join("many.obj");
    swm::io::write_mesh(&input, &mesh).unwrap();
    let output = dir.join("many.swm");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "encode",
            s(&input),
            "-o",
            s(&output),
            "--edge-length",
            "0.2",
        ];
        args.extend_from_slice(extra);
        // The component lines are on stderr, the results on stdout.
        let out = swm(&args);
        let stdout = ok(&out);
        assert!(!stdout.contains("component "), "{stdout}");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let listed = |text: &str| text.lines().filter(|l| l.starts_with("component ")).count();
    let short = run(&[]);
    assert!(listed(&short) <= 10, "{short}");
    let summary = short
        .lines()
        .find(|l| l.starts_with("... "))
        .expect("a summary line");
    let all = TINY + 1;
    assert!(summary.contains(&format!("{all} in all")), "{summary}");
    assert!(summary.contains("1 retiled"), "{summary}");
    assert!(
        summary.contains(&format!("{TINY} kept by lossless coding")),
        "{summary}"
    );
    assert!(summary.contains("--verbose"), "{summary}");
    assert!(short.lines().count() < 20, "{short}");
    let long = run(&["--verbose"]);
    assert_eq!(listed(&long), all, "{long}");
    assert!(!long.contains("\n... "), "{long}");
    let v = encode_json(&input, &output, &["--edge-length", "0.2"]);
    assert_eq!(v["components"].as_array().unwrap().len(), all, "{v}");
    let _ = std::fs::remove_dir_all(&dir);
}
