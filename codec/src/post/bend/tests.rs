//! Bender's tests: each stencil's polynomial precision on its own layout,
//! the dispatch on lattices where every rule's vertices are known, and
//! whole-mesh properties (planes stay planes, a cube stays a cube, tags
//! propagate, limits hold, odd input is refused or survived).

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::classify::{Classes, End, VertexClass};
use super::stencil::*;
use super::step::{step, DIRECT_MAX};
use super::{bend, Bent};
use crate::mesh::test_rng::Rng;
use crate::post::SharpEdges;
use crate::{CornerTable, Error, LimitError, Limited, Limits, TriMesh};

const H: f64 = 0.866_025_403_784_438_6; // √3/2

// ---------------------------------------------------------------------
// Stencils on their layouts.

/// Whether `Σ w·x^a·y^b` equals `mid_x^a·mid_y^b` (to 1e-12) for every
/// monomial of degree `d`.
fn exact_for_degree(pts: &[(f64, f64)], w: &[f64], mid: (f64, f64), d: i32) -> bool {
    assert_eq!(pts.len(), w.len());
    (0..=d).all(|a| {
        let b = d - a;
        let got: f64 = pts
            .iter()
            .zip(w)
            .map(|(p, w)| w * p.0.powi(a) * p.1.powi(b))
            .sum();
        (got - mid.0.powi(a) * mid.1.powi(b)).abs() < 1e-12
    })
}

/// Asserts exact reproduction up to degree `max`, and failure at `max + 1`.
fn assert_degree(name: &str, pts: &[(f64, f64)], w: &[f64], mid: (f64, f64), max: i32) {
    for d in 0..=max {
        assert!(exact_for_degree(pts, w, mid, d), "{name}: degree {d}");
    }
    assert!(
        !exact_for_degree(pts, w, mid, max + 1),
        "{name}: unexpectedly exact at degree {}",
        max + 1
    );
}

fn sum(w: &[f64]) -> f64 {
    w.iter().sum()
}

#[test]
fn r1_reproduces_cubics_on_the_regular_grid() {
    // [V, W, A, B, VA, WA, VB, WB]
    let pts = [
        (0.0, 0.0),
        (1.0, 0.0),
        (0.5, H),
        (0.5, -H),
        (-0.5, H),
        (1.5, H),
        (-0.5, -H),
        (1.5, -H),
    ];
    assert_degree("R1", &pts, &r1(), (0.5, 0.0), 3);
}

#[test]
fn e1_reproduces_quadratics_on_symmetric_fans_and_lines_at_valence_3() {
    for k in [3usize, 4, 5, 7, 8, 12] {
        let mut pts = vec![(0.0, 0.0)];
        let mut w = vec![e1_center(k)];
        for j in 0..k {
            let a = core::f64::consts::TAU * j as f64 / k as f64;
            pts.push((a.cos(), a.sin()));
            w.push(e1(k, j));
        }
        let max = if k == 3 { 1 } else { 2 };
        assert_degree(&format!("E1 k={k}"), &pts, &w, (0.5, 0.0), max);
    }
}

/// The half-fan of a sector of `k` triangles: V, then s_0 … s_k on the
/// unit circle at angles jπ/k.
fn half_fan(k: usize) -> Vec<(f64, f64)> {
    let mut pts = vec![(0.0, 0.0)];
    for j in 0..=k {
        let a = core::f64::consts::PI * j as f64 / k as f64;
        pts.push((a.cos(), a.sin()));
    }
    pts
}

fn e2_weights(k: usize, i: usize) -> Vec<f64> {
    let mut w = vec![e2_center(k, i)];
    w.extend((0..=k).map(|j| e2(k, i, j)));
    w
}

#[test]
fn e2_reproduces_lines_on_half_fans() {
    for k in 2..=6usize {
        let pts = half_fan(k);
        for i in 1..k {
            let mid = (pts[i + 1].0 / 2.0, pts[i + 1].1 / 2.0);
            assert_degree(&format!("E2 k={k} i={i}"), &pts, &e2_weights(k, i), mid, 1);
        }
    }
}

#[test]
fn e2_matches_the_notes_check_values_at_k3_i1() {
    let w = e2_weights(3, 1);
    let want = [0.5, 1.0 / 16.0, 3.0 / 8.0, 1.0 / 8.0, -1.0 / 16.0];
    for (got, want) in w.iter().zip(want) {
        assert!((got - want).abs() < 1e-15, "{w:?}");
    }
    // K = 2 is the midpoint: V 1/2, s_1 1/2.
    let w = e2_weights(2, 1);
    for (got, want) in w.iter().zip([0.5, 0.0, 0.5, 0.0]) {
        assert!((got - want).abs() < 1e-15, "{w:?}");
    }
}

#[test]
fn r4_reproduces_quadratics_across_a_straight_crease() {
    // [V, W, A, B, C1, C2, C3]; the crease is the x axis.
    let pts = [
        (0.0, 0.0),
        (0.5, H),
        (1.0, 0.0),
        (-0.5, H),
        (1.5, H),
        (-1.0, 0.0),
        (0.0, 2.0 * H),
    ];
    assert_degree("R4", &pts, &r4(), (0.25, H / 2.0), 2);
}

#[test]
fn r5_reproduces_quadratics_at_an_ear() {
    // [V, W, A, B, VB, WB]; creases A–V–VB and A–W–WB meet at 60° at A.
    let pts = [
        (1.0, 0.0),
        (0.5, H),
        (0.0, 0.0),
        (1.5, H),
        (2.0, 0.0),
        (1.0, 2.0 * H),
    ];
    assert_degree("R5", &pts, &r5(), (0.75, H / 2.0), 2);
}

#[test]
fn r3_keeps_lines_only() {
    let pts = [(0.0, 0.0), (0.5, H)];
    assert_degree("R3", &pts, &r3(), (0.25, H / 2.0), 1);
}

#[test]
fn r2_reproduces_cubics_along_a_chain() {
    let pts = [(-1.0, 0.0), (0.0, 0.0), (1.0, 0.0), (2.0, 0.0)];
    assert_degree("R2", &pts, &r2(), (0.5, 0.0), 3);
}

#[test]
fn r6_mirrors_the_far_edge() {
    let k = r2();
    let r6 = |v: DVec3, w: DVec3, w2: DVec3| {
        let v2 = r6_mirror(v, w, w2).expect("distinct ends");
        k[0] * v2 + k[1] * v + k[2] * w + k[3] * w2
    };
    // Collinear, unevenly spaced: the midpoint, by symmetry.
    let (o, d) = (DVec3::new(0.3, -1.0, 2.0), DVec3::new(0.2, 0.7, -0.4));
    let got = r6(o + d, o, o - 0.6 * d);
    assert!((got - (o + 0.5 * d)).length() < 1e-12, "{got}");
    // On a circle with even spacing the mirror is the circle's next point,
    // so R6 equals R2 on four points of the arc.
    let arc = |a: f64| DVec3::new(a.cos(), a.sin(), 0.0);
    let phi = 0.4;
    let v2 = r6_mirror(arc(phi), arc(0.0), arc(-phi)).unwrap();
    assert!((v2 - arc(2.0 * phi)).length() < 1e-12);
    let got = r6(arc(phi), arc(0.0), arc(-phi));
    let want = k[0] * arc(2.0 * phi) + k[1] * arc(phi) + k[2] * arc(0.0) + k[3] * arc(-phi);
    assert!((got - want).length() < 1e-12);
    // Affine: moving every point moves the result the same way (its
    // weights sum to 1).
    let (v, w, w2) = (
        DVec3::new(1.0, 2.0, 0.5),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(-1.0, 1.5, 0.3),
    );
    let shift = DVec3::new(5.0, -3.0, 7.0);
    let moved = r6(v + shift, w + shift, w2 + shift) - shift;
    assert!((moved - r6(v, w, w2)).length() < 1e-12);
    // Coincident ends have no bisecting plane.
    assert!(r6_mirror(w, w, w2).is_none());
    assert!(r6_mirror(DVec3::NAN, w, w2).is_none());
}

#[test]
fn stencils_sum_to_one() {
    for (name, s) in [
        ("R1", sum(&r1())),
        ("R2", sum(&r2())),
        ("R3", sum(&r3())),
        ("R4", sum(&r4())),
        ("R5", sum(&r5())),
    ] {
        assert!((s - 1.0).abs() < 1e-15, "{name}: {s}");
    }
    for k in 1..=40usize {
        let s = e1_center(k) + (0..k).map(|j| e1(k, j)).sum::<f64>();
        assert!((s - 1.0).abs() < 1e-14, "E1 k={k}: {s}");
    }
    for k in 2..=40usize {
        for i in 1..k {
            let s = sum(&e2_weights(k, i));
            assert!((s - 1.0).abs() < 1e-12, "E2 k={k} i={i}: {s}");
        }
    }
}

fn random_points(rng: &mut Rng, n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|_| DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0 - 1.0)
        .collect()
}

#[test]
fn shared_sums_equal_the_stencils() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for k in 3..=40usize {
        let ring = random_points(&mut rng, k);
        let c = random_points(&mut rng, 1)[0];
        let mut out = vec![DVec3::ZERO; k];
        e1_all(c, &ring, &mut out);
        for (e, got) in out.iter().enumerate() {
            let want =
                c * e1_center(k) + (0..k).map(|j| ring[(e + j) % k] * e1(k, j)).sum::<DVec3>();
            assert!((*got - want).length() < 1e-12, "E1 k={k} e={e}");
        }
    }
    for k in 2..=40usize {
        let sector = random_points(&mut rng, k + 1);
        let c = random_points(&mut rng, 1)[0];
        let mut out = vec![DVec3::ZERO; k + 1];
        e2_all(c, &sector, &mut out);
        for (i, got) in out.iter().enumerate().take(k).skip(1) {
            let want =
                c * e2_center(k, i) + (0..=k).map(|j| sector[j] * e2(k, i, j)).sum::<DVec3>();
            assert!((*got - want).length() < 1e-12, "E2 k={k} i={i}");
        }
    }
}

// ---------------------------------------------------------------------
// Meshes.

fn p64(m: &TriMesh, v: u32) -> DVec3 {
    let [x, y, z] = m.positions[v as usize];
    DVec3::new(x as f64, y as f64, z as f64)
}

/// The triangular lattice: vertex (i, j) = `j·nx + i` at (i + j/2, j·√3/2,
/// z(i, j)); interior vertices have valence 6 and neighbours (i±1, j),
/// (i, j±1), (i−1, j+1), (i+1, j−1).
fn lattice(nx: u32, ny: u32, z: impl Fn(u32, u32) -> f64) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (x, y) = (i as f64 + j as f64 / 2.0, j as f64 * H);
            positions.push([x as f32, y as f32, z(i, j) as f32]);
        }
    }
    let id = |i: u32, j: u32| j * nx + i;
    let mut triangles = Vec::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
            triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(positions, triangles)
}

/// The new vertex of every input edge, read from the 1→4 layout (which
/// this also checks).
fn midpoints(input: &TriMesh, out: &TriMesh) -> BTreeMap<[u32; 2], u32> {
    assert_eq!(out.triangles.len(), 4 * input.triangles.len());
    let mut mids = BTreeMap::new();
    let key = |a: u32, b: u32| [a.min(b), a.max(b)];
    for (t, &[v0, v1, v2]) in input.triangles.iter().enumerate() {
        let [a, b, c, d] = [0, 1, 2, 3].map(|k| out.triangles[4 * t + k]);
        let (m2, m1) = (a[1], a[2]);
        let m0 = b[2];
        assert_eq!(a, [v0, m2, m1]);
        assert_eq!(b, [m2, v1, m0]);
        assert_eq!(c, [m1, m0, v2]);
        assert_eq!(d, [m0, m1, m2]);
        for (e, m) in [(key(v1, v2), m0), (key(v2, v0), m1), (key(v0, v1), m2)] {
            assert!(m as usize >= input.positions.len());
            assert_eq!(*mids.entry(e).or_insert(m), m, "edge {e:?} split twice");
        }
    }
    mids
}

fn bend1(m: &TriMesh, tags: &SharpEdges) -> Bent {
    bend(m, tags, 1, &Limits::default()).expect("bend")
}

/// The new point of edge a–b after one step, in f64.
fn new_point(m: &TriMesh, tags: &SharpEdges, a: u32, b: u32) -> DVec3 {
    let out = bend1(m, tags);
    let mids = midpoints(m, &out.mesh);
    p64(&out.mesh, mids[&[a.min(b), a.max(b)]])
}

fn weighted(m: &TriMesh, verts: &[u32], w: &[f64]) -> DVec3 {
    verts.iter().zip(w).map(|(&v, &w)| p64(m, v) * w).sum()
}

fn assert_close(got: DVec3, want: DVec3, what: &str) {
    assert!(
        (got - want).length() < 2e-6 * (1.0 + want.length()),
        "{what}: got {got}, want {want}"
    );
}

/// A lattice with a random height field, so that every rule gives a
/// different point.
fn bumpy_lattice(seed: u64) -> (TriMesh, impl Fn(u32, u32) -> u32) {
    const NX: u32 = 12;
    let heights: Vec<f64> = {
        let mut rng = Rng(seed);
        (0..NX * NX).map(|_| rng.unit() * 0.4 - 0.2).collect()
    };
    let m = lattice(NX, NX, |i, j| heights[(j * NX + i) as usize]);
    (m, |i: u32, j: u32| j * NX + i)
}

/// Tags the chain of lattice vertices given.
fn chain(id: &impl Fn(u32, u32) -> u32, pts: &[(u32, u32)]) -> Vec<[u32; 2]> {
    pts.windows(2)
        .map(|w| [id(w[0].0, w[0].1), id(w[1].0, w[1].1)])
        .collect()
}

#[test]
fn dispatch_r1_away_from_creases_and_r4_next_to_one() {
    let (m, id) = bumpy_lattice(1);
    // A straight crease along row j = 5.
    let tags = SharpEdges::new(chain(&id, &(0..12).map(|i| (i, 5)).collect::<Vec<_>>()));
    // R1 on row 2, far from the crease.
    let (v, w) = (id(4, 2), id(5, 2));
    let verts = [
        v,
        w,
        id(4, 3),
        id(5, 1),
        id(3, 3),
        id(5, 3),
        id(4, 1),
        id(6, 1),
    ];
    assert_close(
        new_point(&m, &tags, v, w),
        weighted(&m, &verts, &r1()),
        "R1",
    );
    // R4: V = (5,5) on the crease, W = (5,6) above it (V + (1/2, h)).
    let (v, w) = (id(5, 5), id(5, 6));
    let verts = [v, w, id(6, 5), id(4, 6), id(6, 6), id(4, 5), id(4, 7)];
    assert_close(
        new_point(&m, &tags, v, w),
        weighted(&m, &verts, &r4()),
        "R4 above",
    );
    // Mirrored below the crease: W = (6,4) = V + (1/2, -h); the wings
    // are A = (6,5) on the crease and B = (5,4).
    let (v, w) = (id(5, 5), id(6, 4));
    let verts = [v, w, id(6, 5), id(5, 4), id(7, 4), id(4, 5), id(6, 3)];
    let bent = new_point(&m, &tags, v, w);
    assert_close(bent, weighted(&m, &verts, &r4()), "R4 below");
    // Without the tag the same edge takes R1, a different point.
    let smooth = new_point(&m, &SharpEdges::default(), v, w);
    assert_close(smooth, butterfly_reference(&m, v, w), "R1 untagged");
    assert!((bent - smooth).length() > 1e-3);
}

#[test]
fn dispatch_r5_at_an_ear_and_r3_across_a_strip() {
    let (m, id) = bumpy_lattice(2);
    // Creases A–V–… along row 4 and A–W–… up column 3, meeting at A =
    // (3,4) at 60°: the triangle A, V = (4,4), W = (3,5) is an ear.
    let mut pairs = chain(&id, &(3..12).map(|i| (i, 4)).collect::<Vec<_>>());
    pairs.extend(chain(&id, &(4..12).map(|j| (3, j)).collect::<Vec<_>>()));
    let tags = SharpEdges::new(pairs);
    let (v, w) = (id(4, 4), id(3, 5));
    let verts = [v, w, id(3, 4), id(4, 5), id(5, 4), id(3, 6)];
    assert_close(
        new_point(&m, &tags, v, w),
        weighted(&m, &verts, &r5()),
        "R5",
    );
    // Two parallel creases one row apart: the edges across the strip
    // take the midpoint.
    let mut pairs = chain(&id, &(0..12).map(|i| (i, 4)).collect::<Vec<_>>());
    pairs.extend(chain(&id, &(0..12).map(|i| (i, 5)).collect::<Vec<_>>()));
    let tags = SharpEdges::new(pairs);
    let (v, w) = (id(5, 4), id(5, 5));
    assert_close(
        new_point(&m, &tags, v, w),
        weighted(&m, &[v, w], &r3()),
        "R3",
    );
}

#[test]
fn dispatch_e2_at_a_bent_crease() {
    let (m, id) = bumpy_lattice(3);
    // The crease runs along row 5 up to V = (5,5) and turns up column 5
    // there: V's sectors have 2 triangles (above-left) and 4.
    let mut pairs = chain(&id, &(0..6).map(|i| (i, 5)).collect::<Vec<_>>());
    pairs.extend(chain(&id, &(5..12).map(|j| (5, j)).collect::<Vec<_>>()));
    let tags = SharpEdges::new(pairs);
    let v = id(5, 5);
    let table = CornerTable::new(&m.triangles, m.positions.len()).unwrap();
    let cl = Classes::new(&table, &tags);
    assert_eq!(cl.class(v), VertexClass::Crease);
    // Sector of 2 (from (5,6) round to (4,5)): s_1 = (4,6). The other end
    // is smooth and regular, so E2 alone; for k = 2 it is the midpoint.
    let w = id(4, 6);
    assert_close(
        new_point(&m, &tags, v, w),
        weighted(&m, &[v, w], &[0.5, 0.5]),
        "E2 k=2",
    );
    // The sector of 4 on the other side, listed clockwise from the crease
    // edge V–(5,6) to the crease edge V–(4,5). Bender lists it the other
    // way round; E2 is the same under i -> k - i with the sector
    // reversed, so either order gives the same point.
    let sector = [id(5, 6), id(6, 5), id(6, 4), id(5, 4), id(4, 5)];
    for i in 1..4 {
        let w = sector[i];
        let mut verts = vec![v];
        verts.extend(sector);
        let want = weighted(&m, &verts, &e2_weights(4, i));
        assert_close(new_point(&m, &tags, v, w), want, &format!("E2 k=4 i={i}"));
    }
}

#[test]
fn dispatch_r2_along_a_chain_and_r6_at_its_dead_end() {
    let (m, id) = bumpy_lattice(4);
    // A chain from (2,5) to (8,5): its ends have one sharp edge each.
    let tags = SharpEdges::new(chain(&id, &(2..9).map(|i| (i, 5)).collect::<Vec<_>>()));
    let (v2, v, w, w2) = (id(3, 5), id(4, 5), id(5, 5), id(6, 5));
    assert_close(
        new_point(&m, &tags, v, w),
        weighted(&m, &[v2, v, w, w2], &r2()),
        "R2",
    );
    // The dead ends (2,5) and (8,5) are not 1-manifold: R6 mirrors the
    // next edge of the chain. (The two ends sit on opposite sides of
    // their edges, so both orders of V and W in an edge are covered.)
    for (v, w, w2) in [
        (id(2, 5), id(3, 5), id(4, 5)),
        (id(8, 5), id(7, 5), id(6, 5)),
    ] {
        let k = r2();
        let mirror = r6_mirror(p64(&m, v), p64(&m, w), p64(&m, w2)).unwrap();
        let want = k[0] * mirror + weighted(&m, &[v, w, w2], &k[1..]);
        assert_close(new_point(&m, &tags, v, w), want, "R6");
    }
    // The dead end counts as an ordinary vertex for its other edges: R1.
    let (v, w) = (id(2, 5), id(2, 6));
    let want = butterfly_reference(&m, v, w);
    assert_close(new_point(&m, &tags, v, w), want, "R1 at a dead end");
}

/// R1 from the triangles alone: A completes the triangle with directed
/// edge V→W, B the one with W→V, and each far vertex the triangle across
/// the wing's edge.
fn butterfly_reference(m: &TriMesh, v: u32, w: u32) -> DVec3 {
    let third = third_vertices(m);
    let a = third[&(v, w)];
    let b = third[&(w, v)];
    let verts = [
        v,
        w,
        a,
        b,
        third[&(v, a)],
        third[&(a, w)],
        third[&(b, v)],
        third[&(w, b)],
    ];
    weighted(m, &verts, &r1())
}

/// Directed edge → the third vertex of its triangle.
fn third_vertices(m: &TriMesh) -> BTreeMap<(u32, u32), u32> {
    let mut third = BTreeMap::new();
    for &[a, b, c] in &m.triangles {
        third.insert((a, b), c);
        third.insert((b, c), a);
        third.insert((c, a), b);
    }
    third
}

/// E1 from the triangles alone: the ring of `v` from `w` on.
fn e1_reference(m: &TriMesh, third: &BTreeMap<(u32, u32), u32>, v: u32, w: u32) -> DVec3 {
    let mut ring = vec![w];
    loop {
        let next = third[&(v, *ring.last().unwrap())];
        if next == w {
            break;
        }
        ring.push(next);
    }
    let k = ring.len();
    let mut s = p64(m, v) * e1_center(k);
    for (j, &r) in ring.iter().enumerate() {
        s += p64(m, r) * e1(k, j);
    }
    s
}

/// The unit icosahedron (the edgebreaker tests' layout, on the sphere).
fn icosahedron() -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let (raw, triangles) = crate::edgebreaker::tests_support::icosahedron(t);
    let positions = raw
        .iter()
        .map(|p| {
            let d = DVec3::from_array(*p).normalize();
            [d.x as f32, d.y as f32, d.z as f32]
        })
        .collect();
    TriMesh::new(positions, triangles)
}

/// Every triangle split 1→4 at edge midpoints (no smoothing).
fn midpoint_split(m: &TriMesh) -> TriMesh {
    let mut positions = m.positions.clone();
    let mut mids = BTreeMap::new();
    let mut mid = |a: u32, b: u32, positions: &mut Vec<[f32; 3]>| {
        *mids.entry([a.min(b), a.max(b)]).or_insert_with(|| {
            let p = (p64(m, a) + p64(m, b)) / 2.0;
            positions.push([p.x as f32, p.y as f32, p.z as f32]);
            positions.len() as u32 - 1
        })
    };
    let mut triangles = Vec::new();
    for &[a, b, c] in &m.triangles {
        let (ab, bc, ca) = (
            mid(a, b, &mut positions),
            mid(b, c, &mut positions),
            mid(c, a, &mut positions),
        );
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    TriMesh::new(positions, triangles)
}

#[test]
fn smooth_rules_match_a_reference_built_from_triangles() {
    // Valences 5 and 6, jittered: R1, one-sided E1 and averaged E1.
    let mut m = midpoint_split(&icosahedron());
    let mut rng = Rng(7);
    for p in &mut m.positions {
        let d = DVec3::from_array(p.map(f64::from)).normalize() * (1.0 + 0.1 * rng.unit());
        *p = [d.x as f32, d.y as f32, d.z as f32];
    }
    let out = bend1(&m, &SharpEdges::default());
    let third = third_vertices(&m);
    let valence = |v: u32| third.keys().filter(|e| e.0 == v).count();
    let (mut r1s, mut one, mut both) = (0, 0, 0);
    for (&[a, b], &mid) in &midpoints(&m, &out.mesh) {
        let want = match (valence(a) == 6, valence(b) == 6) {
            (true, true) => {
                r1s += 1;
                butterfly_reference(&m, a, b)
            }
            (false, true) => {
                one += 1;
                e1_reference(&m, &third, a, b)
            }
            (true, false) => {
                one += 1;
                e1_reference(&m, &third, b, a)
            }
            (false, false) => {
                both += 1;
                (e1_reference(&m, &third, a, b) + e1_reference(&m, &third, b, a)) / 2.0
            }
        };
        assert_close(p64(&out.mesh, mid), want, &format!("edge {a}-{b}"));
    }
    assert!(r1s > 0 && one > 0 && both == 0, "{r1s} {one} {both}");
    // The icosahedron itself: every edge has two valence-5 ends.
    let m = icosahedron();
    let out = bend1(&m, &SharpEdges::default());
    let third = third_vertices(&m);
    for (&[a, b], &mid) in &midpoints(&m, &out.mesh) {
        let want = (e1_reference(&m, &third, a, b) + e1_reference(&m, &third, b, a)) / 2.0;
        assert_close(p64(&out.mesh, mid), want, "icosahedron");
    }
}

// ---------------------------------------------------------------------
// Whole meshes.

#[test]
fn a_tilted_plane_stays_planar() {
    let plane = |x: f64, y: f64| 0.3 * x - 0.2 * y + 0.1;
    let mut m = lattice(10, 10, |i, j| {
        plane(i as f64 + j as f64 / 2.0, j as f64 * H)
    });
    // Flip some diagonals for valences 4 to 8 (E1 of several sizes).
    let mut rng = Rng(11);
    for t in m.triangles.chunks_exact_mut(2) {
        if rng.below(3) == 0 {
            // [a, b, c], [b, d, c]  ->  [a, b, d], [a, d, c]
            let ([a, b, c], d) = (t[0], t[1][1]);
            t[0] = [a, b, d];
            t[1] = [a, d, c];
        }
    }
    let tags = SharpEdges::new([[0, 1], [1, 2], [12, 13]]);
    let out = bend(&m, &tags, 2, &Limits::default()).unwrap();
    for (v, p) in out.mesh.positions.iter().enumerate() {
        let [x, y, z] = p.map(f64::from);
        assert!((z - plane(x, y)).abs() < 1e-5, "vertex {v} off the plane");
    }
    // Orientation: every triangle still faces +z (the lattice does).
    for t in 0..out.mesh.triangles.len() {
        assert!(
            out.mesh.face_cross(crate::FaceId(t as u32)).z > 0.0,
            "triangle {t}"
        );
    }
}

#[test]
fn a_straight_boundary_stays_straight() {
    let (m, id) = bumpy_lattice(5);
    let out = bend1(&m, &SharpEdges::default());
    let mids = midpoints(&m, &out.mesh);
    // The bottom row lies on y = 0; R2 keeps its inner points there,
    // evenly spaced (away from the corners, whose R2 reaches round them).
    for i in 1..9 {
        let (a, b) = (id(i, 0), id(i + 1, 0));
        let p = p64(&out.mesh, mids[&[a, b]]);
        assert_eq!(p.y, 0.0);
        assert!((p.x - (i as f64 + 0.5)).abs() < 1e-6);
        let want = weighted(&m, &[id(i - 1, 0), a, b, id(i + 2, 0)], &r2());
        assert_close(p, want, "R2 on the boundary");
    }
}

#[test]
fn an_icosahedron_bends_into_a_smooth_convex_ball() {
    let out = bend(
        &icosahedron(),
        &SharpEdges::default(),
        3,
        &Limits::default(),
    )
    .unwrap();
    let m = &out.mesh;
    assert_eq!(m.triangles.len(), 20 * 64);
    let (mut lo, mut hi) = (f64::MAX, 0f64);
    for v in 0..m.positions.len() as u32 {
        let r = p64(m, v).length();
        (lo, hi) = (lo.min(r), hi.max(r));
    }
    // A plain 1→4 split would leave face centres at the inradius, 0.79.
    assert!(lo > 0.95 && hi < 1.0 + 1e-6, "radii {lo}..{hi}");
    // Convex, with small dihedral angles everywhere.
    let table = CornerTable::new(&m.triangles, m.positions.len()).unwrap();
    let mut worst = 0f64;
    for c in 0..table.corner_count() as u32 {
        let c = crate::CornerId(c);
        let o = table.opposite(c);
        assert!(o.is_some(), "closed mesh has a boundary");
        let (n1, n2) = (
            m.face_cross(c.face()).normalize(),
            m.face_cross(o.face()).normalize(),
        );
        worst = worst.max(n1.dot(n2).clamp(-1.0, 1.0).acos());
        let (a, d) = (p64(m, table.vertex(c.next()).0), p64(m, table.vertex(o).0));
        assert!((d - a).dot(n1) < 1e-6, "concave at corner {c:?}");
    }
    // A plain 1→4 split keeps the icosahedron's 41.8° along its edges.
    assert!(
        worst < 15f64.to_radians(),
        "worst normal angle {}",
        worst.to_degrees()
    );
}

/// The cube [-1, 1]³, each face an `n`×`n` grid of squares cut by a
/// diagonal, outward oriented, with its 12 edges tagged.
pub(crate) fn cube(n: u32) -> (TriMesh, SharpEdges) {
    let mut index = BTreeMap::new();
    let mut positions = Vec::new();
    let mut vertex = |p: [i32; 3]| {
        *index.entry(p).or_insert_with(|| {
            positions.push(p.map(|x| x as f32 / n as f32));
            positions.len() as u32 - 1
        })
    };
    let mut triangles = Vec::new();
    let n = n as i32;
    for axis in 0..3 {
        for sign in [-1, 1] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let at = |a: i32, b: i32| {
                let mut p = [0; 3];
                p[axis] = sign * n;
                p[u] = a;
                p[v] = b;
                p
            };
            for a in (-n..n).step_by(2) {
                for b in (-n..n).step_by(2) {
                    let q =
                        [at(a, b), at(a + 2, b), at(a + 2, b + 2), at(a, b + 2)].map(&mut vertex);
                    // u × v = axis, so (u, v) order faces +axis.
                    let (t1, t2) = ([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
                    if sign > 0 {
                        triangles.extend([t1, t2]);
                    } else {
                        triangles.extend([[t1[0], t1[2], t1[1]], [t2[0], t2[2], t2[1]]]);
                    }
                }
            }
        }
    }
    let mesh = TriMesh::new(positions, triangles);
    let tags = cube_edge_pairs(&mesh);
    (mesh, tags)
}

/// The edges of `m` that lie along an edge of the cube [-1, 1]³.
fn cube_edge_pairs(m: &TriMesh) -> SharpEdges {
    let on_edge = |a: u32, b: u32| {
        let (p, q) = (p64(m, a), p64(m, b));
        (0..3)
            .filter(|&k| p[k].abs() == 1.0 && q[k] == p[k])
            .count()
            >= 2
    };
    let mut pairs = Vec::new();
    for &[a, b, c] in &m.triangles {
        for (x, y) in [(a, b), (b, c), (c, a)] {
            if on_edge(x, y) {
                pairs.push([x, y]);
            }
        }
    }
    SharpEdges::new(pairs)
}

#[test]
fn a_cube_keeps_flat_faces_and_straight_edges() {
    for n in [1, 2] {
        let (m, tags) = cube(n);
        assert_eq!(tags.len() as u32, 12 * n);
        let out = bend(&m, &tags, 2, &Limits::default()).unwrap();
        for (v, p) in out.mesh.positions.iter().enumerate() {
            let p = p.map(f64::from);
            let max = p.iter().fold(0f64, |a, x| a.max(x.abs()));
            assert!(
                (max - 1.0).abs() < 1e-9,
                "n={n}: vertex {v} at {p:?} is off the cube"
            );
        }
        // Tags: exactly the pieces of the cube's edges, each a quarter of
        // an input edge.
        assert_eq!(out.sharp, cube_edge_pairs(&out.mesh), "n={n}");
        assert_eq!(out.sharp.len() as u32, 12 * n * 4);
        for &[a, b] in out.sharp.pairs() {
            let d = (p64(&out.mesh, a) - p64(&out.mesh, b)).length();
            assert!(
                (d - 0.5 / n as f64).abs() < 1e-6,
                "n={n}: piece {a}-{b} of length {d}"
            );
        }
        let table = CornerTable::new(&out.mesh.triangles, out.mesh.positions.len()).unwrap();
        assert!(table.opposites().iter().all(|o| o.is_some()));
    }
}

#[test]
fn tags_propagate_so_steps_compose() {
    let (m, id) = bumpy_lattice(6);
    let mut pairs = chain(
        &id,
        &[(1, 1), (2, 1), (3, 1), (3, 2), (3, 3), (2, 4), (1, 5)],
    );
    pairs.extend(chain(&id, &(0..12).map(|i| (i, 8)).collect::<Vec<_>>()));
    pairs.push([id(6, 6), id(7, 6)]); // a lone tag: two dead ends
    pairs.push([id(0, 0), id(11, 11)]); // not an edge: dropped
    let tags = SharpEdges::new(pairs);
    let once = bend1(&m, &tags);
    assert_eq!(once.sharp.len(), 2 * (tags.len() - 1));
    let twice = bend1(&once.mesh, &once.sharp);
    let both = bend(&m, &tags, 2, &Limits::default()).unwrap();
    assert_eq!(twice, both);
    // Old vertices never move.
    for (v, p) in m.positions.iter().enumerate() {
        assert_eq!(both.mesh.positions[v], *p);
    }
    // steps = 0 is the identity, minus the tags that name no edge.
    let same = bend(&m, &tags, 0, &Limits::default()).unwrap();
    assert_eq!(same.mesh, m);
    assert_eq!(same.sharp.len(), tags.len() - 1);
    assert!(!same.sharp.contains(id(0, 0), id(11, 11)));
}

#[test]
fn output_is_manifold_and_keeps_orientation() {
    let mut meshes = vec![
        icosahedron(),
        cube(2).0,
        bumpy_lattice(8).0,
        midpoint_split(&icosahedron()),
    ];
    // Two components, one of them open.
    let mut two = icosahedron();
    let lat = lattice(4, 4, |_, _| 3.0);
    let off = two.positions.len() as u32;
    two.positions.extend(&lat.positions);
    two.triangles
        .extend(lat.triangles.iter().map(|t| t.map(|v| v + off)));
    meshes.push(two);
    for (k, m) in meshes.iter().enumerate() {
        let out = bend(m, &cube_edge_pairs(m), 2, &Limits::default()).unwrap();
        let before = CornerTable::new(&m.triangles, m.positions.len()).unwrap();
        let after =
            CornerTable::new(&out.mesh.triangles, out.mesh.positions.len()).expect("manifold");
        // Half-edges pair only with reversed ones, so a flipped triangle
        // would leave unpaired edges: each boundary edge splits in two
        // per step, and no other edge may become one.
        let boundary = |t: &CornerTable| t.opposites().iter().filter(|o| o.is_none()).count();
        assert_eq!(boundary(&after), 4 * boundary(&before), "mesh {k}");
        let once = bend1(m, &SharpEdges::default());
        midpoints(m, &once.mesh);
    }
}

#[test]
fn classes_follow_the_number_of_hard_edges() {
    let (m, id) = bumpy_lattice(9);
    let mut pairs = chain(&id, &(2..12).map(|i| (i, 5)).collect::<Vec<_>>());
    pairs.extend(chain(&id, &[(5, 5), (5, 6), (5, 7)]));
    let tags = SharpEdges::new(pairs);
    let table = CornerTable::new(&m.triangles, m.positions.len()).unwrap();
    let cl = Classes::new(&table, &tags);
    // Smooth: no tag, or a dead end (2,5).
    assert_eq!(cl.class(id(5, 2)), VertexClass::Smooth { valence: 6 });
    assert_eq!(cl.class(id(2, 5)), VertexClass::Smooth { valence: 6 });
    // Crease: on the chain, on a plain boundary, at the lattice's corner.
    for (i, j) in [(3, 5), (4, 0), (0, 0), (0, 5)] {
        assert_eq!(cl.class(id(i, j)), VertexClass::Crease, "({i},{j})");
    }
    // Corner: three tags, or a boundary that a tag reaches.
    assert_eq!(cl.class(id(5, 5)), VertexClass::Corner);
    assert_eq!(cl.class(id(11, 5)), VertexClass::Corner);
    // At the corner (5,5) the edge to (6,4) lies in the sector below the
    // crease, s_0 = (4,5) (clockwise end) … s_3 = (6,5): k = 3, i = 2.
    let mut buf = [0u32; 8];
    let x = (0..table.corner_count() as u32)
        .map(crate::CornerId)
        .find(|&x| cl.at(x) == id(5, 5) && cl.at(x.next()) == id(6, 4))
        .unwrap();
    assert_eq!(cl.end(x, 7, &mut buf), End::Sector { k: 3, i: 2 });
    assert_eq!(&buf[..4], &[id(4, 5), id(5, 4), id(6, 4), id(6, 5)]);
    assert!(End::Sector { k: 3, i: 2 }.is_regular() && !End::Sector { k: 4, i: 2 }.is_regular());
    // A cap below the sector size reports a large sector.
    assert_eq!(cl.end(x, 2, &mut buf), End::LargeSector);
}

/// A disk: centre 0, rim 1..=n; `open` leaves one wedge out, making the
/// centre a boundary vertex.
fn disk(n: u32, open: bool) -> TriMesh {
    let mut positions = vec![[0.0, 0.0, 0.3f32]];
    let mut rng = Rng(n as u64);
    for k in 0..n {
        let a = core::f64::consts::TAU * k as f64 / n as f64;
        let r = 1.0 + 0.2 * rng.unit();
        positions.push([
            (r * a.cos()) as f32,
            (r * a.sin()) as f32,
            (0.1 * rng.unit()) as f32,
        ]);
    }
    let wedges = if open { n - 1 } else { n };
    let triangles = (0..wedges).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    TriMesh::new(positions, triangles)
}

#[test]
fn large_fans_use_shared_sums_with_the_same_result() {
    let spokes = |ks: &[u32]| SharpEdges::new(ks.iter().map(|&k| [0, 1 + k]).collect::<Vec<_>>());
    let cases = [
        (disk(40, false), SharpEdges::default()), // E1, valence 40
        (disk(41, false), spokes(&[0, 17])),      // E2, k = 17 and 24
        (disk(30, true), SharpEdges::default()),  // E2 at a boundary centre, k = 29
        (disk(30, false), spokes(&[0])),          // a dart: E1
    ];
    for (n, (m, tags)) in cases.iter().enumerate() {
        assert!(m.triangles.len() > DIRECT_MAX);
        let table = CornerTable::new(&m.triangles, m.positions.len()).unwrap();
        let (fast, fast_tags) = step(m, &table, tags, DIRECT_MAX);
        let (slow, slow_tags) = step(m, &table, tags, usize::MAX);
        assert_eq!(fast.triangles, slow.triangles);
        assert_eq!(fast_tags, slow_tags);
        for (a, b) in fast.positions.iter().zip(&slow.positions) {
            let (a, b) = (
                DVec3::from_array(a.map(f64::from)),
                DVec3::from_array(b.map(f64::from)),
            );
            assert!((a - b).length() < 1e-6, "case {n}: {a} vs {b}");
        }
        // And the shared sums really were used: with a cap of 1 every
        // sector is "large".
        let (tiny, _) = step(m, &table, tags, 1);
        for (a, b) in tiny.positions.iter().zip(&slow.positions) {
            let (a, b) = (
                DVec3::from_array(a.map(f64::from)),
                DVec3::from_array(b.map(f64::from)),
            );
            assert!((a - b).length() < 1e-6, "case {n}, cap 1: {a} vs {b}");
        }
    }
}

#[test]
fn a_huge_fan_takes_linear_time() {
    // 60 000 triangles round one vertex: summing each stencil would take
    // 3.6e9 multiply-adds per coordinate; the shared sums take 1.2e5.
    let m = disk(60_000, false);
    let tags = SharpEdges::new([[0, 1], [0, 20_001], [0, 40_001]]);
    let start = std::time::Instant::now();
    for tags in [SharpEdges::default(), tags] {
        let out = bend1(&m, &tags);
        assert_eq!(out.mesh.triangles.len(), 240_000);
        assert!(out.mesh.positions.iter().flatten().all(|x| x.is_finite()));
    }
    assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
}

// ---------------------------------------------------------------------
// Limits and odd input.

#[test]
fn limits_refuse_large_outputs_before_allocating() {
    let (m, tags) = cube(1);
    let small = Limits {
        max_faces: 1000,
        ..Limits::default()
    };
    match bend(&m, &tags, 10, &small) {
        Err(Error::LimitExceeded(LimitError {
            what: Limited::Faces,
            requested,
            limit: 1000,
        })) => {
            assert_eq!(requested, 12 << 20);
        }
        other => panic!("{other:?}"),
    }
    // Counts far past u64, and past 32-bit indices, with no limit at all.
    for steps in [16, 40, u32::MAX] {
        assert!(matches!(
            bend(&m, &tags, steps, &Limits::UNLIMITED),
            Err(Error::LimitExceeded(LimitError {
                what: Limited::Faces,
                ..
            }))
        ));
    }
    // The counts are exact: an output that just fits passes.
    let out = bend(&m, &tags, 3, &Limits::default()).unwrap();
    let (f, v) = (
        out.mesh.triangles.len() as u64,
        out.mesh.positions.len() as u64,
    );
    let fit = Limits {
        max_faces: f,
        max_vertices: v,
        ..Limits::default()
    };
    assert!(bend(&m, &tags, 3, &fit).is_ok());
    let one_less = Limits {
        max_vertices: v - 1,
        ..fit
    };
    assert!(matches!(
        bend(&m, &tags, 3, &one_less),
        Err(Error::LimitExceeded(LimitError { what: Limited::Vertices, requested, .. })) if requested == v
    ));
    let no_memory = Limits {
        max_alloc_bytes: 10_000,
        ..Limits::default()
    };
    assert!(matches!(
        bend(&m, &tags, 3, &no_memory),
        Err(Error::LimitExceeded(LimitError {
            what: Limited::AllocBytes,
            ..
        }))
    ));
}

#[test]
fn odd_input_is_refused_or_survived() {
    let lim = Limits::default();
    let none = SharpEdges::default();
    let tri =
        |positions: Vec<[f32; 3]>, triangles: Vec<[u32; 3]>| TriMesh::new(positions, triangles);
    let p3 = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    // Empty, with and without vertices; any number of steps.
    for positions in [vec![], p3.clone()] {
        let m = tri(positions, vec![]);
        for steps in [0, 1, u32::MAX] {
            let out = bend(&m, &SharpEdges::new([[0, 1]]), steps, &lim).unwrap();
            assert_eq!(out.mesh, m);
            assert!(out.sharp.is_empty());
        }
    }
    // One triangle: every edge a boundary, R2 round it.
    let out = bend(&tri(p3.clone(), vec![[0, 1, 2]]), &none, 3, &lim).unwrap();
    assert_eq!(out.mesh.triangles.len(), 64);
    // Out-of-range index; a vertex used twice; three faces on one edge.
    assert!(matches!(
        bend(&tri(p3.clone(), vec![[0, 1, 3]]), &none, 1, &lim),
        Err(Error::Format(_))
    ));
    assert!(matches!(
        bend(&tri(p3.clone(), vec![[0, 1, 1]]), &none, 1, &lim),
        Err(Error::Topology(_))
    ));
    let mut p4 = p3.clone();
    p4.extend([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]);
    let fin = tri(p4.clone(), vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    assert!(matches!(
        bend(&fin, &none, 1, &lim),
        Err(Error::Topology(_))
    ));
    // Degenerate (collinear and coincident) triangles, NaN, infinity.
    let flat = tri(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    bend(&flat, &SharpEdges::new([[0, 2], [0, 1]]), 2, &lim).unwrap();
    let mut bad = icosahedron();
    bad.positions[0] = [f32::NAN, 0.0, 0.0];
    bad.positions[5] = [f32::INFINITY, 0.0, 0.0];
    bend(&bad, &SharpEdges::new([[0, 1], [0, 5], [1, 5]]), 2, &lim).unwrap();
    // A two-triangle pillow shares three edges between two faces: the
    // corner table refuses it. A tetrahedron (valence 3) bends.
    assert!(matches!(
        bend(&tri(p3.clone(), vec![[0, 1, 2], [0, 2, 1]]), &none, 2, &lim),
        Err(Error::Topology(_))
    ));
    let tet = tri(
        p4[..4].to_vec(),
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
    );
    bend(&tet, &none, 2, &lim).unwrap();
    bend(
        &tet,
        &SharpEdges::new([[0, 1], [1, 2], [2, 0], [0, 3]]),
        2,
        &lim,
    )
    .unwrap();
    // Tags naming vertices that do not exist.
    bend(&tet, &SharpEdges::new([[0, 99], [7, u32::MAX]]), 1, &lim).unwrap();
    // Random triangle soups: whatever the corner table accepts bends.
    let mut rng = Rng(0x5eed);
    let mut bent = 0;
    for _ in 0..2000 {
        let nv = 3 + rng.below(8);
        let nf = 1 + rng.below(14) as usize;
        let positions = (0..nv)
            .map(|_| [rng.unit() as f32, rng.unit() as f32, rng.unit() as f32])
            .collect();
        let triangles = (0..nf)
            .map(|_| [0, 0, 0].map(|_| rng.below(nv as u64)))
            .collect();
        let m = tri(positions, triangles);
        let tags = SharpEdges::new(
            (0..rng.below(6))
                .map(|_| [rng.below(nv as u64), rng.below(nv as u64)])
                .collect::<Vec<_>>(),
        );
        if let Ok(out) = bend(&m, &tags, 2, &lim) {
            bent += 1;
            assert_eq!(out.mesh.triangles.len(), 16 * m.triangles.len());
            CornerTable::new(&out.mesh.triangles, out.mesh.positions.len()).expect("manifold");
        }
    }
    assert!(bent > 50, "{bent}");
}

#[test]
fn several_components_and_unused_vertices_are_kept() {
    let (mut m, _) = cube(1);
    m.positions.push([9.0, 9.0, 9.0]); // used by no triangle
    let ico = icosahedron();
    let off = m.positions.len() as u32;
    m.positions.extend(&ico.positions);
    m.triangles
        .extend(ico.triangles.iter().map(|t| t.map(|v| v + off)));
    let tags = cube_edge_pairs(&m);
    let out = bend(&m, &tags, 2, &Limits::default()).unwrap();
    assert_eq!(out.mesh.positions[8], [9.0, 9.0, 9.0]);
    assert_eq!(out.sharp.len(), 12 * 4);
    let used: BTreeSet<u32> = out.mesh.triangles.iter().flatten().copied().collect();
    assert!(!used.contains(&8));
    assert_eq!(used.len() + 1, out.mesh.positions.len());
}
