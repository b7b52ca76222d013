//! `swm distance A B`: the JSON contract, zero between a mesh and itself,
//! sane values between two different spheres, clean errors.

mod common;
use common::*;
use std::path::PathBuf;

fn write(dir: &std::path::Path, name: &str, mesh: &swm::TriMesh) -> PathBuf {
    let path = dir.join(name);
    swm::io::write_mesh(&path, mesh).unwrap();
    path
}

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn json_keys_and_zero_for_identical_meshes() {
    let dir = scratch("distance-same");
    let torus = write(&dir, "torus.obj", &swm_corpus::torus(1.0, 0.35, 32, 12));
    let v = json(&swm(&[
        "distance",
        s(&torus),
        s(&torus),
        "--samples",
        "2000",
        "--json",
    ]));
    for key in [
        "l2",
        "hausdorff",
        "mean",
        "l2_relative",
        "hausdorff_relative",
        "diagonal",
    ] {
        assert!(v[key].is_number(), "missing {key}: {v}");
    }
    for side in ["forward", "backward"] {
        for key in ["samples", "mean", "rms", "max"] {
            assert!(v[side][key].is_number(), "missing {side}.{key}: {v}");
        }
        // Face samples plus every vertex and points along every edge.
        assert!(v[side]["samples"].as_u64().unwrap() > 2000, "{v}");
    }
    // Nearest-point arithmetic may leave rounding, never a real distance.
    let diag = v["diagonal"].as_f64().unwrap();
    assert!(diag > 2.0, "{v}");
    assert!(v["hausdorff"].as_f64().unwrap() <= 1e-9 * diag, "{v}");
    assert!(v["l2_relative"].as_f64().unwrap() <= 1e-9, "{v}");
}

#[test]
fn two_spheres_differ_by_their_facets() {
    let dir = scratch("distance-spheres");
    let fine = write(&dir, "fine.ply", &swm_corpus::icosphere(1.0, 4));
    let coarse = write(&dir, "coarse.off", &swm_corpus::icosphere(1.0, 1));
    let args = [
        "distance",
        s(&fine),
        s(&coarse),
        "--samples",
        "5000",
        "--json",
    ];
    let v = json(&swm(&args));
    let f = |k: &str| v[k].as_f64().unwrap();
    // A level-1 icosphere's faces sink below the unit sphere by a few
    // percent of the radius; vertices of both lie on it.
    assert!(f("l2") > 0.005 && f("l2") < 0.2, "{v}");
    assert!(f("hausdorff") >= f("l2") && f("l2") >= f("mean"), "{v}");
    assert!(
        (f("l2_relative") - f("l2") / f("diagonal")).abs() < 1e-12,
        "{v}"
    );
    assert!((f("hausdorff_relative") - f("hausdorff") / f("diagonal")).abs() < 1e-12);
    assert_eq!(
        f("l2"),
        v["forward"]["rms"]
            .as_f64()
            .unwrap()
            .max(v["backward"]["rms"].as_f64().unwrap())
    );
    // Same inputs, same numbers.
    let again = json(&swm(&args));
    assert_eq!(v, again);

    let text = swm(&["distance", s(&fine), s(&coarse), "--samples", "5000"]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("L2") && text.contains("Hausdorff"), "{text}");
}

#[test]
fn bad_inputs_give_one_line_errors() {
    let dir = scratch("distance-errors");
    let torus = write(&dir, "torus.obj", &swm_corpus::torus(1.0, 0.35, 16, 8));
    let missing = dir.join("missing.obj");
    let garbage = dir.join("garbage.ply");
    std::fs::write(&garbage, b"ply\nformat nonsense\n").unwrap();
    for (a, b, culprit) in [
        (&torus, &missing, &missing),
        (&missing, &torus, &missing),
        (&torus, &garbage, &garbage),
    ] {
        let out = swm(&["distance", s(a), s(b)]);
        assert_eq!(out.status.code(), Some(1));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!("swm: error: {}:", culprit.display())),
            "{err}"
        );
    }
    let out = swm(&["distance", s(&torus), s(&torus), "--samples", "0"]);
    assert_eq!(out.status.code(), Some(2), "--samples 0 is a usage error");
}
