//! Retilings started on a boundary loop (`boundary`, `swing::chain`).

use super::tests::sphere;
use crate::container::{parse_container, Tag};
use crate::{CornerTable, EncodeMode, EncodeOptions, SwingTarget, SwingTuning, TriMesh};

/// A wavy square sheet of `n` × `n` quads, side 2: one boundary loop.
fn sheet(n: u32) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (
                2.0 * i as f32 / n as f32 - 1.0,
                2.0 * j as f32 / n as f32 - 1.0,
            );
            positions.push([x, y, 0.15 * (2.0 * x).sin() * (1.5 * y).cos()]);
        }
    }
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    TriMesh::new(positions, triangles)
}

fn options(l: f64, loop_start: bool) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: SwingTarget::EdgeLength(l),
            angle_bits: Some(7),
            max_bytes: None,
        },
        swing: SwingTuning {
            loop_start,
            // The tests look at the retiled mesh itself.
            post_hint: false,
            ..SwingTuning::default()
        },
        ..EncodeOptions::default()
    }
}

/// Distance from `p` to the square's border (the input's boundary).
fn off_border(p: [f32; 3]) -> f64 {
    let (x, y) = (f64::from(p[0]).abs(), f64::from(p[1]).abs());
    (1.0 - x.max(y)).abs()
}

#[test]
fn a_sheet_started_on_its_loop_keeps_its_border_and_drops_only_the_fan() {
    let m = sheet(24);
    let l = 0.12;
    let on = crate::encode(&m, &options(l, true)).unwrap();
    let inside = crate::encode(&m, &options(l, false)).unwrap();
    let file = parse_container(&on.bytes, &Default::default()).unwrap();
    assert!(file.find(Tag::LOOP).is_some());
    assert_eq!(file.header.minor, 1);
    assert!(parse_container(&inside.bytes, &Default::default())
        .unwrap()
        .find(Tag::LOOP)
        .is_none());
    let stats = on.stats.swing().unwrap();
    assert_eq!(stats.loops, 1);
    assert_eq!(stats.holes_masked_triangles, 0);
    // About perimeter / L points.
    let expected = 8.0 / l;
    assert!(
        (stats.loop_points as f64 / expected - 1.0).abs() < 0.1,
        "{} points",
        stats.loop_points
    );
    // Started inside, the patch over the sheet's one hole costs about as
    // many triangles as the sheet itself.
    let inside_stats = inside.stats.swing().unwrap();
    assert!(inside_stats.holes_masked_triangles as f64 > 0.5 * inside_stats.triangles as f64);
    assert!(stats.triangles < inside_stats.triangles);

    let decoded = crate::decode(&on.bytes, &Default::default()).unwrap();
    let table = CornerTable::new(&decoded.triangles, decoded.vertex_count()).unwrap();
    let loops = table.boundary_loops();
    assert_eq!(loops.len(), 1);
    // The decoded border is the loop's points: on the input's border, to
    // the angles' precision (a point is a step ρ ≈ L from the previous
    // one, its direction within half a code, 2π/2^K, of the border's).
    let h = 1.1 * stats.edge_length * std::f64::consts::TAU / 128.0;
    let worst = loops[0]
        .iter()
        .map(|&c| off_border(decoded.positions[table.vertex(c.next()).idx()]))
        .fold(0.0, f64::max);
    assert!(worst <= h, "border off by {worst} (h = {h})");
    // No decoded triangle lies outside the square.
    assert!(decoded
        .positions
        .iter()
        .all(|p| p[0].abs() <= 1.0 + h as f32 && p[1].abs() <= 1.0 + h as f32));
}

#[test]
fn loop_starts_are_deterministic_and_closed_pieces_unchanged() {
    let m = sheet(16);
    let a = crate::encode(&m, &options(0.2, true)).unwrap();
    let b = crate::encode(&m, &options(0.2, true)).unwrap();
    assert_eq!(a.bytes, b.bytes);
    // A closed mesh has no loop to start on: same file either way.
    let s = sphere(3);
    let on = crate::encode(&s, &options(0.3, true)).unwrap();
    let off = crate::encode(&s, &options(0.3, false)).unwrap();
    assert_eq!(on.bytes, off.bytes);
}
