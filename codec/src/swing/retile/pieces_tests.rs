//! Holes and several components (`fill`, `mask`, `compose`).

use super::compose::{retile_pieces, PieceOutcome};
use super::fill::pieces;
use super::tests::{retiled, sphere};
use super::valence::max_valence;
use super::valence::tests::fanned_polygon;
use super::RetileOptions;
use crate::{CornerTable, TriMesh};
use glam::DVec3;

fn options(l: f64) -> RetileOptions {
    RetileOptions {
        edge_length: l,
        angle_bits: 8,
        start_vertex: None,
        start_rank: 0,
        start_by_shape: false,
        approximate_tips: true,
        fit_tips: true,
        adaptive_density: false,
        last_resort: false,
        loop_start: false,
        crease_tips: false,
    }
}

/// A sphere of radius 1 without the faces with a vertex that `cut`
/// selects.
fn cut_sphere(levels: u32, cut: impl Fn(DVec3) -> bool) -> TriMesh {
    let m = sphere(levels);
    let keep: Vec<[u32; 3]> = m
        .triangles
        .iter()
        .copied()
        .filter(|t| {
            let c: DVec3 = t
                .iter()
                .map(|&v| DVec3::from(m.positions[v as usize].map(f64::from)))
                .sum();
            !cut(c / 3.0)
        })
        .collect();
    TriMesh::new(m.positions.clone(), keep)
}

fn prepared(m: &TriMesh) -> Vec<super::fill::Piece> {
    let cleaned = crate::clean(m, &Default::default()).unwrap();
    pieces(&cleaned.mesh, &cleaned.table).unwrap()
}

/// The retiled triangles the decoder keeps.
fn kept(r: &crate::swing::Retiled) -> Vec<[u32; 3]> {
    r.triangles
        .iter()
        .zip(r.hole_mask.iter().chain(std::iter::repeat(&false)))
        .filter(|(_, &m)| !m)
        .map(|(t, _)| *t)
        .collect()
}

#[test]
fn patches_close_every_loop_into_a_sphere() {
    let m = cut_sphere(4, |c| c.z > 0.7 || c.x > 0.85);
    let p = prepared(&m);
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].holes, 2);
    assert_eq!(p[0].genus, 0);
    assert!(p[0].table.opposites().iter().all(|o| o.is_some()));
    // The patches span the holes: their area is near the two caps'.
    let real = m.area();
    let patch = p[0].area - real;
    let caps = 2.0 * std::f64::consts::PI * (0.3 + 0.15);
    assert!(
        (patch / caps - 1.0).abs() < 0.25,
        "patch area {patch}, caps {caps}"
    );
}

#[test]
fn holes_come_back_as_one_boundary_loop_each() {
    let m = cut_sphere(5, |c| c.z > 0.7 || c.x > 0.85);
    for l in [0.1, 0.16] {
        let c = retile_pieces(&prepared(&m), &options(l), &super::Budget::unlimited()).unwrap();
        let r = &c.retiled;
        assert_eq!(r.hole_mask.len(), r.triangles.len());
        let kept = kept(r);
        let table = CornerTable::new(&kept, r.positions.len()).expect("manifold after the mask");
        let loops = table.boundary_loops().len();
        assert_eq!(loops, 2, "L = {l}: {:?}", c.report);
        match &c.report[0].outcome {
            PieceOutcome::Retiled {
                masked, lost_holes, ..
            } => {
                assert_eq!(*lost_holes, 0);
                // The masked area is about the holes' (the caps).
                let tri = l * l * 3f64.sqrt() / 4.0;
                let caps = 2.0 * std::f64::consts::PI * (0.3 + 0.15);
                let ratio = *masked as f64 * tri / caps;
                assert!((0.6..1.5).contains(&ratio), "masked {masked}: {ratio}");
            }
            o => panic!("{o:?}"),
        }
    }
}

#[test]
fn components_are_retiled_in_order_and_tiny_ones_kept_losslessly() {
    let a = sphere(4);
    let mut m = a.clone();
    for (shift, scale) in [(3.0, 0.8), (6.0, 0.02)] {
        let base = m.positions.len() as u32;
        m.positions.extend(
            a.positions
                .iter()
                .map(|p| [p[0] * scale + shift, p[1] * scale, p[2] * scale]),
        );
        m.triangles
            .extend(a.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    let c = retile_pieces(&prepared(&m), &options(0.15), &super::Budget::unlimited()).unwrap();
    let r = &c.retiled;
    assert_eq!(r.first.len(), 2);
    assert_eq!(r.symbols.len() + 2, r.triangles.len());
    assert!(r.hole_mask.is_empty());
    assert!(matches!(c.report[0].outcome, PieceOutcome::Retiled { .. }));
    assert!(matches!(c.report[1].outcome, PieceOutcome::Retiled { .. }));
    assert_eq!(c.report[2].outcome, PieceOutcome::Lossless);
    let (rest, _) = r.rest.as_ref().expect("the tiny sphere is kept");
    assert_eq!(rest.face_count(), a.face_count());
    // One closed manifold of two spheres.
    let table = CornerTable::new(&r.triangles, r.positions.len()).unwrap();
    assert!(table.opposites().iter().all(|o| o.is_some()));
    assert_eq!(table.component_labels().1, 2);
    // Component 1's first triangle starts right after component 0.
    let second = r.triangles.len()
        - table
            .component_labels()
            .0
            .iter()
            .filter(|&&k| k == 1)
            .count();
    let first1 = r.triangles[second].map(|v| r.positions[v as usize]);
    assert_eq!(first1, r.first[1]);
}

/// A torus: tube radius `r` around a circle of radius 1, `n` × `m` quads.
fn torus(r: f64, n: u32, m: u32) -> TriMesh {
    let mut p = Vec::new();
    for i in 0..n {
        let u = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        for j in 0..m {
            let v = std::f64::consts::TAU * f64::from(j) / f64::from(m);
            let w = 1.0 + r * v.cos();
            p.push([
                (w * u.cos()) as f32,
                (w * u.sin()) as f32,
                (r * v.sin()) as f32,
            ]);
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut t = Vec::new();
    for i in 0..n {
        for j in 0..m {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(p, t)
}

/// A slab `w` × `h` cells of size 1, `depth` thick, with the cells in
/// `holes` (each a rectangle [x0, x1) × [y0, y1)) cut through: genus =
/// the number of holes. Every face is cut in quarters around its centre
/// so that its triangles are not long slivers.
fn slab(w: u32, h: u32, depth: f32, holes: &[[u32; 4]]) -> TriMesh {
    let solid = |x: i64, y: i64| {
        x >= 0
            && y >= 0
            && x < i64::from(w)
            && y < i64::from(h)
            && !holes.iter().any(|&[x0, y0, x1, y1]| {
                (x0..x1).contains(&(x as u32)) && (y0..y1).contains(&(y as u32))
            })
    };
    let mut p: Vec<[f32; 3]> = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut v = |q: [f32; 3], p: &mut Vec<[f32; 3]>| {
        let key = q.map(f32::to_bits);
        *index.entry(key).or_insert_with(|| {
            p.push(q);
            p.len() as u32 - 1
        })
    };
    let mut t = Vec::new();
    // A quad a b c d (counterclockwise seen from outside) as four
    // triangles around its centre.
    let mut quad = |q: [[f32; 3]; 4], p: &mut Vec<[f32; 3]>, t: &mut Vec<[u32; 3]>| {
        let c = [0, 1, 2].map(|k| (q[0][k] + q[1][k] + q[2][k] + q[3][k]) / 4.0);
        let ci = v(c, p);
        let ids = q.map(|x| v(x, p));
        for k in 0..4 {
            t.push([ids[k], ids[(k + 1) % 4], ci]);
        }
    };
    for x in 0..i64::from(w) {
        for y in 0..i64::from(h) {
            if !solid(x, y) {
                continue;
            }
            let (x0, y0, x1, y1) = (x as f32, y as f32, x as f32 + 1.0, y as f32 + 1.0);
            quad(
                [
                    [x0, y0, depth],
                    [x1, y0, depth],
                    [x1, y1, depth],
                    [x0, y1, depth],
                ],
                &mut p,
                &mut t,
            );
            quad(
                [[x0, y0, 0.0], [x0, y1, 0.0], [x1, y1, 0.0], [x1, y0, 0.0]],
                &mut p,
                &mut t,
            );
            // Walls where the neighbour is empty, facing it.
            let walls = [
                ((1, 0), [[x1, y0], [x1, y1]]),
                ((-1, 0), [[x0, y1], [x0, y0]]),
                ((0, 1), [[x1, y1], [x0, y1]]),
                ((0, -1), [[x0, y0], [x1, y0]]),
            ];
            for ((dx, dy), [a, b]) in walls {
                if !solid(x + dx, y + dy) {
                    quad(
                        [
                            [a[0], a[1], 0.0],
                            [b[0], b[1], 0.0],
                            [b[0], b[1], depth],
                            [a[0], a[1], depth],
                        ],
                        &mut p,
                        &mut t,
                    );
                }
            }
        }
    }
    TriMesh::new(p, t)
}

/// `m` gently bent, so that no two faces are coplanar.
fn bent(mut m: TriMesh) -> TriMesh {
    for p in &mut m.positions {
        let (x, y) = (f64::from(p[0]), f64::from(p[1]));
        p[2] += (0.15 * (0.9 * x).sin() * (1.3 * y).cos()) as f32;
        p[0] += (0.05 * (1.1 * y).sin()) as f32;
    }
    m
}

/// V − E + F of a closed triangle mesh's referenced vertices.
fn euler(m: &TriMesh) -> i64 {
    let table = CornerTable::new(&m.triangles, m.vertex_count()).unwrap();
    assert!(table.opposites().iter().all(|o| o.is_some()), "closed");
    let (v, f) = (m.vertex_count() as i64, m.face_count() as i64);
    v - 3 * f / 2 + f
}

fn encode_decode(m: &TriMesh, l: f64) -> TriMesh {
    retiled(m, crate::SwingTarget::EdgeLength(l))
}

#[test]
fn a_torus_keeps_its_handle() {
    let t = torus(0.4, 96, 40);
    assert_eq!(euler(&t), 0);
    let d = encode_decode(&t, 0.12);
    assert_eq!(euler(&d), 0, "genus 1 after decoding");
}

#[test]
fn a_slab_with_two_holes_keeps_genus_two() {
    // 9 × 5 × 1.5 with two 1 × 1 holes, in cells of 1/4, gently bent;
    // L well below the bars (1 wide) and the thickness.
    let mut s = slab(36, 20, 6.0, &[[8, 8, 12, 12], [24, 8, 28, 12]]);
    for p in &mut s.positions {
        *p = p.map(|c| c / 4.0);
    }
    let s = bent(s);
    assert_eq!(euler(&s), -2);
    let d = encode_decode(&s, 0.3);
    assert_eq!(euler(&d), -2, "genus 2 after decoding");
}

/// Manual probe of every piece of a real mesh: `SWM_PIECES=path:L[,L...]`
/// (L relative to the diagonal), e.g. `SWM_PIECES=../shared/corpus/woody.obj:0.02
/// cargo test -p swm --release --lib retile::pieces_tests::probe -- --ignored --nocapture`.
/// Prints each piece's faces, holes, genus and the retiler's outcome.
#[test]
#[ignore]
#[cfg(feature = "io")]
fn probe() {
    let Ok(spec) = std::env::var("SWM_PIECES") else {
        return;
    };
    let (path, ls) = spec.rsplit_once(':').unwrap();
    let mesh = crate::io::read_mesh(std::path::Path::new(path)).unwrap();
    let ps = prepared(&mesh);
    let diag = mesh.bbox_diagonal();
    let rank = std::env::var("SWM_RETILE_RANK").map_or(0, |s| s.parse().unwrap());
    for l in ls.split(',') {
        let l: f64 = l.parse::<f64>().unwrap() * diag;
        for (i, p) in ps.iter().enumerate() {
            if std::env::var("SWM_PIECE").is_ok_and(|k| k != i.to_string()) {
                continue;
            }
            let patch = p
                .patch
                .iter()
                .filter(|&&x| x != super::surface::NONE)
                .count();
            let opt = RetileOptions {
                start_rank: rank,
                start_by_shape: false,
                ..options(l)
            };
            let r = super::retile_piece(
                &p.mesh,
                &p.table,
                Some(&p.patch),
                &opt,
                None,
                p.genus > 0,
                &super::Budget::unlimited(),
            );
            println!(
                "L {l:.4e} piece {i}: {} faces ({patch} patch), {} holes, genus {}, area {:.1} tri: {:?}",
                p.mesh.face_count(),
                p.holes,
                p.genus,
                p.area / (l * l * 3f64.sqrt() / 4.0),
                r.map(|(r, _, _)| r.triangles.len())
            );
        }
    }
}

/// A non-flat 70,000-gon fanned from its vertex 0 (as the OBJ reader
/// triangulates it): its patch is one ring fanned to a centre on the loop
/// itself, so the centre's rebuild puts new vertices next to loop
/// vertices whose fans are rebuilt after it (this panicked once, on a
/// vertex without an incidence list). The closed piece comes out a
/// manifold sphere of bounded valence.
#[test]
fn a_huge_wavy_polygon_closes_into_a_piece_of_bounded_valence() {
    let p = prepared(&fanned_polygon(70_000, 0.1));
    assert_eq!(p.len(), 1);
    let valence = max_valence(&p[0].mesh);
    assert!(valence <= 64, "{valence}");
    assert_eq!(p[0].genus, 0);
    assert!(p[0].table.opposites().iter().all(|o| o.is_some()));
}

/// A flat 3,000-gon fanned from vertex 0: a flat disk, closed by a shell
/// whose wall is graded (its loop is too long for full rows). The piece
/// is a closed manifold sphere with every wall face about as high as
/// wide, not one sliver per loop edge.
#[test]
fn a_long_flat_loop_gets_a_graded_wall() {
    let n = 3000u32;
    let p = prepared(&fanned_polygon(n, 0.0));
    assert_eq!((p.len(), p[0].genus), (1, 0));
    assert!(p[0].table.opposites().iter().all(|o| o.is_some()));
    // Wall faces: neither on the disk (z = 0) nor on its copy.
    let m = &p[0].mesh;
    let depth = m.positions.iter().map(|q| q[2]).fold(0f32, f32::min);
    let wall: Vec<[DVec3; 3]> = m
        .triangles
        .iter()
        .map(|t| t.map(|x| DVec3::from(m.positions[x as usize].map(f64::from))))
        .filter(|t| !t.iter().all(|q| q.z == 0.0) && !t.iter().all(|q| q.z as f32 == depth))
        .collect();
    assert!(wall.len() < 6 * n as usize, "{} wall faces", wall.len());
    // Outward: the wall's normals point away from the axis.
    for t in &wall {
        let c = (t[0] + t[1] + t[2]) / 3.0;
        let normal = (t[1] - t[0]).cross(t[2] - t[0]);
        assert!(
            normal.dot(DVec3::new(c.x, c.y, 0.0)) > 0.0,
            "a wall face turned inward"
        );
    }
}
