//! The encoder's work is bounded by its input (issue 18): one huge polygon
//! face and a double fan of very high valence encode with work linear in
//! the input, and `--max-work` / `--time-limit` end a run with a clear
//! limit error instead of letting it run away.
//!
//! Work is the encoder's own deterministic count of retiling steps
//! (`rate_control.work` in `swm encode --json`), so these bounds are exact
//! and do not depend on the machine's speed.

mod common;
use common::{json, scratch, swm};
use std::fmt::Write as _;
use std::path::Path;

/// One OBJ face with `n` vertices on the unit circle.
fn polygon(dir: &Path, n: u32) -> String {
    let mut s = String::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        writeln!(s, "v {} {} 0", a.cos(), a.sin()).unwrap();
    }
    s.push('f');
    for i in 1..=n {
        write!(s, " {i}").unwrap();
    }
    s.push('\n');
    let path = dir.join(format!("polygon-{n}.obj"));
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_owned()
}

/// Two cones over one ring of `n` vertices: both apexes have valence n.
fn double_fan(dir: &Path, n: u32) -> String {
    let mut s = String::from("v 0 0 1\nv 0 0 -1\n");
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        writeln!(s, "v {} {} 0", a.cos(), a.sin()).unwrap();
    }
    for i in 0..n {
        let (a, b) = (3 + i, 3 + (i + 1) % n);
        writeln!(s, "f 1 {a} {b}\nf 2 {b} {a}").unwrap();
    }
    let path = dir.join(format!("fan-{n}.obj"));
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_owned()
}

fn work(input: &str, out: &Path, target: &[&str]) -> u64 {
    let mut args = vec![
        "encode",
        input,
        "-o",
        out.to_str().unwrap(),
        "--json",
        "--mode",
        "swing",
    ];
    args.extend_from_slice(target);
    let j = json(&swm(&args));
    j["rate_control"]["work"]
        .as_u64()
        .expect("work in the report")
}

#[test]
fn a_polygon_face_of_thousands_of_vertices_costs_work_linear_in_it() {
    let dir = scratch("bounds-polygon");
    let out = dir.join("p.swm");
    let mut steps = Vec::new();
    for n in [1000, 4000] {
        // One edge length, so that the count of rate-control runs (which
        // follows how efficient the file is, not n) stays out of it.
        let w = work(&polygon(&dir, n), &out, &["--edge-length", "0.08"]);
        // Fanned by the reader, the polygon's spokes once cost every path
        // across it n crossings: about 31,000 steps per input corner at
        // n = 1000. Rebuilt as a graded mesh, a few hundred.
        assert!(w <= 3000 * 3 * u64::from(n), "n = {n}: {w} steps");
        steps.push(w);
    }
    // Linear: four times the corners cost at most about four times the
    // work (a factor of 8 leaves room for the graded mesh's rounding; a
    // quadratic cost would give 16).
    let (w1, w4) = (steps[0], steps[1]);
    assert!(
        w4 <= 8 * w1,
        "n = 1000: {w1} steps, n = 4000: {w4}: not linear in n"
    );
}

#[test]
fn a_polygon_whose_spokes_are_many_edge_lengths_long_retiles_at_the_length_asked() {
    // A fanned 64-gon: 62 triangles 40 L long and 4° wide at L = 0.025.
    // Without the refinement of M (`retile/refine.rs`) every path search
    // between a gate and its tip stopped at its length bound and all 16
    // runs failed, down to L = 0.0235.
    let dir = scratch("bounds-spokes");
    let j = json(&swm(&[
        "encode",
        &polygon(&dir, 64),
        "-o",
        dir.join("s.swm").to_str().unwrap(),
        "--mode",
        "swing",
        "--edge-length",
        "0.025",
        "--json",
    ]));
    let rc = &j["rate_control"];
    assert_eq!(rc["attempts"].as_array().unwrap().len(), 1, "{rc}");
    assert_eq!(rc["edge_length"].as_f64(), Some(0.025), "{rc}");
}

#[test]
fn a_double_fan_of_high_valence_costs_the_same_at_four_times_the_valence() {
    let dir = scratch("bounds-fan");
    let out = dir.join("f.swm");
    let small = work(&double_fan(&dir, 1000), &out, &["--edge-length", "0.3"]);
    let large = work(&double_fan(&dir, 4000), &out, &["--edge-length", "0.3"]);
    assert!(
        large < 2 * small,
        "valence 1000: {small} steps, 4000: {large}"
    );
    // And at a requested size, 20,000 faces around each apex.
    let j = json(&swm(&[
        "encode",
        &double_fan(&dir, 20_000),
        "-o",
        out.to_str().unwrap(),
        "--mode",
        "swing",
        "--size",
        "1000",
        "--json",
    ]));
    assert!(j["rate_control"]["work"].as_u64().unwrap() < 200_000_000);
}

#[test]
fn encode_limits_end_a_run_with_a_clear_error_and_no_file() {
    let dir = scratch("bounds-limits");
    let input = double_fan(&dir, 2000);
    let out = dir.join("x.swm");
    for (flag, value, says) in [
        (
            "--max-work",
            "1000",
            "steps of retiling work, more than the limit of 1000",
        ),
        (
            "--max-memory",
            "1000",
            "bytes of memory, more than the limit of 1000",
        ),
        (
            "--time-limit",
            "0.001",
            "milliseconds, more than the limit of 1",
        ),
    ] {
        let r = swm(&[
            "encode",
            &input,
            "-o",
            out.to_str().unwrap(),
            "--mode",
            "swing",
            flag,
            value,
        ]);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{flag}: {err}");
        assert!(
            err.contains(says) && err.contains("fan-2000.obj"),
            "{flag}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{flag}: {err}");
        assert!(!out.exists(), "{flag}: a file was written");
    }
    for bad in [
        ("--max-work", "0"),
        ("--time-limit", "-1"),
        ("--time-limit", "nan"),
    ] {
        let r = swm(&["encode", &input, "-o", out.to_str().unwrap(), bad.0, bad.1]);
        assert_eq!(r.status.code(), Some(2), "{bad:?}");
    }
}

/// A closed cylinder of `n` sides whose two caps are fanned from one rim
/// vertex each, as CAD exporters triangulate planar faces.
fn fanned_cylinder(dir: &Path, n: u32) -> String {
    let mut s = String::new();
    for z in [0, 1] {
        for i in 0..n {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
            writeln!(s, "v {} {} {z}", a.cos(), a.sin()).unwrap();
        }
    }
    for i in 1..=n {
        let j = i % n + 1;
        writeln!(s, "f {i} {j} {}\nf {i} {} {}", n + j, n + j, n + i).unwrap();
    }
    for i in 2..n {
        writeln!(s, "f 1 {} {i}\nf {} {} {}", i + 1, n + 1, n + i, n + i + 1).unwrap();
    }
    let path = dir.join(format!("cylinder-{n}.obj"));
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn a_closed_part_with_fanned_caps_retiles_at_the_length_asked() {
    // Both caps are planar: every inner vertex of theirs is equally flat,
    // and the start used to be the lowest-id one, a midpoint among the
    // fan's 0.9° needles after refinement, where no first triangle could
    // be laid: all 16 runs failed, down to L = 0.0188. Ties now go to the
    // vertex whose ring has the widest narrowest corner.
    let dir = scratch("bounds-caps");
    let j = json(&swm(&[
        "encode",
        &fanned_cylinder(&dir, 200),
        "-o",
        dir.join("c.swm").to_str().unwrap(),
        "--mode",
        "swing",
        "--edge-length",
        "0.03",
        "--json",
    ]));
    let rc = &j["rate_control"];
    assert!(rc["attempts"].as_array().unwrap().len() <= 4, "{rc}");
    assert_eq!(rc["edge_length"].as_f64(), Some(0.03), "{rc}");
}
