//! Properties every generated mesh must have (see the crate docs).

use super::*;
use crate::quality::{duplicate_positions, min_angle_degrees, min_area, signed_volume};
use crate::vec::{from_f32, tri_normal};
use swm::CornerTable;

/// What a mesh's topology and quality must be.
struct Expect {
    genus: i64,
    boundary_loops: u64,
    /// Lower bound on the smallest angle, in degrees.
    min_angle: f64,
}

/// A closed surface of the given genus.
fn closed(genus: i64, min_angle: f64) -> Expect {
    Expect {
        genus,
        boundary_loops: 0,
        min_angle,
    }
}

/// A topological disc.
fn disc(min_angle: f64) -> Expect {
    Expect {
        genus: 0,
        boundary_loops: 1,
        min_angle,
    }
}

/// Checks one connected, manifold, consistently oriented mesh without
/// duplicate positions, unused vertices or degenerate triangles, with the
/// expected topology and angles, outward if closed.
fn check(name: &str, mesh: &TriMesh, e: Expect) {
    mesh.validate()
        .unwrap_or_else(|err| panic!("{name}: {err}"));
    let table = CornerTable::new(&mesh.triangles, mesh.vertex_count())
        .unwrap_or_else(|err| panic!("{name}: not manifold: {err}"));
    table.check().unwrap_or_else(|err| panic!("{name}: {err}"));
    let comps = table.components();
    assert_eq!(comps.len(), 1, "{name}: components");
    let c = &comps[0];
    assert_eq!(c.genus, e.genus, "{name}: genus");
    assert_eq!(c.boundary_loops, e.boundary_loops, "{name}: boundary loops");
    assert_eq!(
        c.vertices as usize,
        mesh.vertex_count(),
        "{name}: unused vertices"
    );
    assert_eq!(duplicate_positions(mesh), 0, "{name}: duplicate positions");
    assert!(min_area(mesh) > 0.0, "{name}: zero-area triangle");
    let angle = min_angle_degrees(mesh);
    assert!(
        angle > e.min_angle,
        "{name}: smallest angle {angle:.2} degrees"
    );
    if e.boundary_loops == 0 {
        assert!(signed_volume(mesh) > 0.0, "{name}: not outward");
    }
}

fn valences(mesh: &TriMesh) -> Vec<u32> {
    let mut val = vec![0u32; mesh.vertex_count()];
    for t in &mesh.triangles {
        for &v in t {
            val[v as usize] += 1;
        }
    }
    val
}

fn standard(name: &str) -> TriMesh {
    by_name(name).unwrap()
}

#[test]
fn uv_sphere_is_a_closed_sphere() {
    let m = standard("uv-sphere");
    // The thinnest triangles touch the poles: a little under 360 / slices.
    check("uv-sphere", &m, closed(0, 7.0));
    assert_eq!(m.vertex_count(), 2 + 23 * 48);
    assert_eq!(m.face_count(), 2 * 48 * 23);
    let v = signed_volume(&m);
    assert!(
        (v - 4.0 / 3.0 * std::f64::consts::PI).abs() < 0.05,
        "volume {v}"
    );
    // The smallest legal parameters still give a clean mesh.
    check("uv-sphere 2x3", &uv_sphere(2.0, 2, 3), closed(0, 1.0));
}

#[test]
fn icosphere_is_regular() {
    let m = standard("icosphere");
    check("icosphere", &m, closed(0, 50.0));
    assert_eq!(m.face_count(), 20 * 256);
    let val = valences(&m);
    assert_eq!(val.iter().filter(|&&k| k == 5).count(), 12);
    assert_eq!(
        val.iter().filter(|&&k| k == 6).count(),
        m.vertex_count() - 12
    );
    for s in 0..3 {
        check("icosphere small", &icosphere(0.5, s), closed(0, 50.0));
    }
}

#[test]
fn torus_has_genus_one() {
    let m = standard("torus");
    check("torus", &m, closed(1, 30.0));
    assert_eq!(m.face_count(), 2 * 64 * 24);
    check("torus 3x3", &torus(2.0, 1.0, 3, 3), closed(1, 10.0));
}

#[test]
fn double_torus_has_genus_two_and_lies_on_its_surface() {
    use crate::implicit::DoubleTorus;
    use crate::relax::Implicit;
    let m = standard("double-torus");
    // 26.7 degrees at the standard resolution.
    check("double-torus", &m, closed(2, 25.0));
    for p in &m.positions {
        let f = DoubleTorus.eval(from_f32(*p)).0;
        assert!(f.abs() < 1e-6, "vertex {p:?} off the surface by {f}");
    }
    // Outward face by face, not just in total.
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| from_f32(m.positions[v as usize]));
        let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
        let n = tri_normal(a, b, c);
        assert!(crate::vec::dot(n, DoubleTorus.normal(centroid)) > 0.0);
    }
    for res in [24, 48] {
        check("double-torus", &double_torus(res), closed(2, 20.0));
    }
}

#[test]
fn fandisk_like_is_a_closed_part_with_flat_caps() {
    let m = standard("fandisk-like");
    check("fandisk-like", &m, closed(0, 30.0));
    // Cap triangles have one z (exactly flat); the rest are vertical.
    let mut caps = 0;
    for t in &m.triangles {
        let z = t.map(|v| m.positions[v as usize][2]);
        if z[0] == z[1] && z[1] == z[2] {
            assert_eq!(z[0].abs(), 0.4);
            caps += 1;
        } else {
            let [a, b, c] = t.map(|v| from_f32(m.positions[v as usize]));
            assert!(tri_normal(a, b, c)[2].abs() < 1e-6);
        }
    }
    assert!(caps > m.face_count() / 4, "caps {caps}");
    for res in [8, 13, 64] {
        check("fandisk-like", &fandisk_like(res), closed(0, 25.0));
    }
}

#[test]
fn cube_is_a_closed_grid() {
    let m = standard("cube");
    check("cube", &m, closed(0, 44.9));
    assert_eq!(m.vertex_count(), 6 * 16 * 16 + 2);
    assert!((signed_volume(&m) - 1.0).abs() < 1e-6);
    check("cube 1", &cube(1), closed(0, 44.9));
}

#[test]
fn plane_patch_is_a_disc_facing_up() {
    let m = standard("plane-patch");
    check("plane-patch", &m, disc(40.0));
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| from_f32(m.positions[v as usize]));
        assert!(tri_normal(a, b, c)[2] > 0.0);
    }
    check("plane-patch 1x1", &plane_patch(1, 1), disc(40.0));
}

#[test]
fn all_is_the_standard_set_and_deterministic() {
    let set = all();
    let names: Vec<&str> = set.iter().map(|(n, _)| *n).collect();
    assert_eq!(names, NAMES);
    for (name, mesh) in &set {
        let f = mesh.face_count();
        assert!((1_000..=20_000).contains(&f), "{name}: {f} triangles");
        assert_eq!(
            by_name(name).as_ref(),
            Some(mesh),
            "{name}: not deterministic"
        );
    }
    assert!(by_name("teapot").is_none());
}
