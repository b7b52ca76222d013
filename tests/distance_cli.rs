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

/// The area-weighted RMS of 1 - |p| over the faces of `mesh` (a polyhedron
/// inscribed in the unit sphere), from a barycentric grid on each face.
fn rms_depth_below_unit_sphere(mesh: &swm::TriMesh) -> f64 {
    const N: usize = 40;
    let (mut sum, mut area_sum) = (0.0, 0.0);
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize].map(f64::from));
        let (u, w) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        let cross = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let area = 0.5 * cross.iter().map(|x| x * x).sum::<f64>().sqrt();
        let (mut face, mut count) = (0.0, 0.0);
        for i in 0..N {
            for j in 0..N - i {
                // The centre of each small triangle of the grid.
                let (s, r) = (
                    (i as f64 + 1.0 / 3.0) / N as f64,
                    (j as f64 + 1.0 / 3.0) / N as f64,
                );
                let p = [0, 1, 2].map(|k| a[k] + s * u[k] + r * w[k]);
                let depth = 1.0 - p.iter().map(|x| x * x).sum::<f64>().sqrt();
                face += depth * depth;
                count += 1.0;
            }
        }
        sum += area * face / count;
        area_sum += area;
    }
    (sum / area_sum).sqrt()
}

/// Two parallel unit squares a distance d apart: every point of one is d
/// from the other, so L2, mean and Hausdorff are d, both ways.
#[test]
fn two_parallel_squares_are_their_gap_apart() {
    let dir = scratch("distance-squares");
    let d = 0.125f32;
    let square = |z: f32| {
        swm::TriMesh::new(
            vec![[0., 0., z], [1., 0., z], [1., 1., z], [0., 1., z]],
            vec![[0, 1, 2], [0, 2, 3]],
        )
    };
    let a = write(&dir, "a.obj", &square(0.0));
    let b = write(&dir, "b.obj", &square(d));
    let v = json(&swm(&[
        "distance",
        s(&a),
        s(&b),
        "--samples",
        "2000",
        "--json",
    ]));
    for key in ["l2", "mean", "hausdorff"] {
        let x = v[key].as_f64().unwrap();
        assert!((x - f64::from(d)).abs() < 1e-6, "{key} {x}: {v}");
    }
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
    // percent of the radius; vertices of both lie on it. The fine sphere
    // is the unit sphere to a few thousandths, so the backward distance
    // (coarse faces to the fine sphere) at a point p of a face is about
    // 1 - |p|: its RMS over the faces, worked out here, is the figure.
    let by_hand = rms_depth_below_unit_sphere(&swm_corpus::icosphere(1.0, 1));
    let backward = v["backward"]["rms"].as_f64().unwrap();
    assert!(
        (backward / by_hand - 1.0).abs() < 0.1,
        "backward RMS {backward} against {by_hand} worked out: {v}"
    );
    assert!(f("l2") >= backward && f("l2") < 1.5 * by_hand, "{v}");
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

/// Runs `swm` and kills it if it is still running after `secs` seconds: a
/// guard against hangs only (never a speed claim), failing the test.
fn swm_or_hang(args: &[&str], secs: u64) -> std::process::Output {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run swm");
    let start = std::time::Instant::now();
    while child.try_wait().expect("wait for swm").is_none() {
        if start.elapsed().as_secs() >= secs {
            let _ = child.kill();
            let _ = child.wait();
            panic!("swm {args:?} still running after {secs} s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.wait_with_output().expect("swm output")
}

/// Issue 18: a mesh in units of 1e30 or 1e-30 is measured as quickly and
/// with the same relative figures as in its own units (the tree's `f32`
/// box tests used to overflow or underflow there, so nothing was pruned
/// and `swm distance` ran for minutes). The bunny when the shared corpus
/// is there, a generated torus otherwise.
#[test]
fn distances_do_not_depend_on_the_units() {
    let dir = scratch("distance-units");
    let mesh = match shared_corpus() {
        Some(c) => swm::io::read_mesh(&c.join("stanford-bunny.obj")).unwrap(),
        None => swm_corpus::torus(1.0, 0.35, 200, 100),
    };
    // A second surface: every third vertex pushed along z by a little.
    let mut bumped = mesh.clone();
    for (i, p) in bumped.positions.iter_mut().enumerate() {
        if i % 3 == 0 {
            p[2] += 1e-3 * (1.0 + p[0].abs());
        }
    }
    let scaled = |m: &swm::TriMesh, s: f64| {
        let mut m = m.clone();
        for p in &mut m.positions {
            *p = p.map(|c| (c as f64 * s) as f32);
        }
        m
    };
    let mut base: Option<serde_json::Value> = None;
    // Powers of two scale every figure exactly; other factors round the
    // coordinates, which moves the samples a little (the tree's leaf
    // order, along which sample counts are carried, may change).
    let two = 2f64.powi(100);
    for (tag, k, tolerance) in [
        ("1", 1.0, 0.0),
        ("2^100", two, 0.0),
        ("1e30", 1e30, 1e-3),
        ("1e-30", 1e-30, 1e-3),
    ] {
        let a = write(&dir, &format!("a-{tag}.obj"), &scaled(&mesh, k));
        let b = write(&dir, &format!("b-{tag}.obj"), &scaled(&bumped, k));
        let run = |x: &PathBuf, y: &PathBuf| {
            let args = ["distance", s(x), s(y), "--samples", "1000", "--json"];
            json(&swm_or_hang(&args, 60))
        };
        let own = run(&a, &a);
        assert!(
            own["hausdorff_relative"].as_f64().unwrap() < 1e-9,
            "{tag}: {own}"
        );
        let v = run(&a, &b);
        let Some(base) = &base else {
            assert!(v["l2_relative"].as_f64().unwrap() > 1e-6, "{v}");
            base = Some(v);
            continue;
        };
        for key in ["l2_relative", "hausdorff_relative"] {
            let (x, y) = (v[key].as_f64().unwrap(), base[key].as_f64().unwrap());
            assert!(
                (x - y).abs() <= tolerance * y,
                "{tag} {key}: {x} against {y}"
            );
        }
        let d = v["diagonal"].as_f64().unwrap() / base["diagonal"].as_f64().unwrap();
        assert!((d / k - 1.0).abs() < 1e-6, "{tag}: {v}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A flat n x n grid in the xy plane as OBJ text, its texture coordinates
/// the positions scaled to [0, 1] with `shift` added to u, or none.
fn uv_grid_obj(n: usize, shift: Option<f64>) -> String {
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            s += &format!("v {} {} 0\n", i as f64 / n as f64, j as f64 / n as f64);
        }
    }
    if let Some(d) = shift {
        for j in 0..=n {
            for i in 0..=n {
                s += &format!("vt {} {}\n", i as f64 / n as f64 + d, j as f64 / n as f64);
            }
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            let (b, c, d) = (a + 1, a + n + 1, a + n + 2);
            if shift.is_some() {
                s += &format!("f {a}/{a} {b}/{b} {d}/{d}\nf {a}/{a} {d}/{d} {c}/{c}\n");
            } else {
                s += &format!("f {a} {b} {d}\nf {a} {d} {c}\n");
            }
        }
    }
    s
}

#[test]
fn texcoords_measure_the_uv_shift_in_texels() {
    let dir = scratch("distance-texcoords");
    let grid = dir.join("grid.obj");
    let shifted = dir.join("shifted.obj");
    let bare = dir.join("bare.obj");
    std::fs::write(&grid, uv_grid_obj(16, Some(0.0))).unwrap();
    std::fs::write(&shifted, uv_grid_obj(16, Some(0.01))).unwrap();
    std::fs::write(&bare, uv_grid_obj(16, None)).unwrap();

    let same = json(&swm(&[
        "distance",
        s(&grid),
        s(&grid),
        "--texcoords",
        "--json",
    ]));
    let t = &same["texcoords"];
    assert!(t["rms_texels"].as_f64().unwrap() <= 1e-3, "{same}");
    assert!(t["max_texels"].as_f64().unwrap() <= 1e-3, "{same}");
    assert_eq!(t["texture_size"].as_u64(), Some(1024), "{same}");
    assert!(t["samples"].as_u64().unwrap() > 0, "{same}");

    // Moved by 0.01 in u: 0.01 * 1024 = 10.24 texels everywhere, the
    // geometry unchanged.
    let expected = 0.01 * 1024.0;
    let v = json(&swm(&[
        "distance",
        s(&grid),
        s(&shifted),
        "--texcoords",
        "--json",
    ]));
    let t = &v["texcoords"];
    for key in ["rms_texels", "max_texels"] {
        let x = t[key].as_f64().unwrap();
        assert!((x - expected).abs() < 0.05 * expected, "{key} {x}: {v}");
    }
    assert!(v["l2_relative"].as_f64().unwrap() <= 1e-9, "{v}");
    // At another texture size the texels scale with it.
    let v = json(&swm(&[
        "distance",
        s(&grid),
        s(&shifted),
        "--texcoords",
        "--texture-size",
        "2048",
        "--json",
    ]));
    let x = v["texcoords"]["rms_texels"].as_f64().unwrap();
    assert!((x - 2.0 * expected).abs() < 0.1 * expected, "{v}");
    assert_eq!(v["texcoords"]["texture_size"].as_u64(), Some(2048), "{v}");
    // The text report says it on one line.
    let text = ok(&swm(&["distance", s(&grid), s(&shifted), "--texcoords"]));
    let line = text
        .lines()
        .find(|l| l.contains("texture coordinates:"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        line.contains("texels") && line.contains("1024x1024"),
        "{line}"
    );
    // Without --texcoords, no key.
    let v = json(&swm(&["distance", s(&grid), s(&shifted), "--json"]));
    assert!(v.get("texcoords").is_none(), "{v}");

    // A mesh without texture coordinates, on either side: one line naming it.
    for (a, b) in [(&grid, &bare), (&bare, &grid)] {
        let out = swm(&["distance", s(a), s(b), "--texcoords"]);
        assert_eq!(out.status.code(), Some(1));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!("swm: error: {}:", bare.display()))
                && err.contains("texture coordinates"),
            "{err}"
        );
    }
    // --texture-size needs --texcoords.
    let out = swm(&["distance", s(&grid), s(&grid), "--texture-size", "512"]);
    assert_eq!(out.status.code(), Some(2));
}
