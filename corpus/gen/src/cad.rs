//! CAD-like parts with sharp and rounded edges: an extruded fillet profile
//! ("fandisk-like") and a gridded cube.
//!
//! Both are closed genus-0 meshes, counter-clockwise seen from outside,
//! with no duplicate positions and no zero-area triangles. Their flat faces
//! are exactly flat (all vertices of a cap share one z) and their sharp
//! edges are polylines of mesh edges, so sharp-feature tests can find them
//! by dihedral angle.

use std::f64::consts::{FRAC_PI_2, PI};

use swm::TriMesh;

use crate::planar::{triangulate_convex, P2};
use crate::vec::to_f32;

/// Width (x), depth (y) and height (z) of the fandisk-like part.
const PART_W: f64 = 2.0;
const PART_D: f64 = 1.2;
const PART_H: f64 = 0.8;
/// Fillet radii of its two rounded vertical edges.
const FILLET_A: f64 = 0.45;
const FILLET_B: f64 = 0.3;

/// A CAD-like part: the `PART_W x PART_D` rectangle with two diagonally
/// opposite corners rounded by circular fillets (radii 0.45 and 0.3) and
/// two left sharp, extruded to height 0.8 and capped, centred at the
/// origin.
///
/// Features: sharp 90-degree edges around both caps and along the two
/// sharp vertical edges; two smoothly rounded vertical edges (the fillets,
/// tangent to the flat sides); sharp corners where they meet. `resolution`
/// is the number of edges along the long side, which sets the target edge
/// length `L = 2 / resolution` everywhere: the sides are grids of near-square
/// quads split in two, the caps are constrained Delaunay triangulations of
/// the rim with an equilateral lattice inside, smoothed (see the crate's
/// `planar` module). Smallest angle: 30.6 degrees at resolution 32, and
/// 26.6 or more for every resolution from 8 to 64.
///
/// # Panics
/// If `resolution < 8`.
pub fn fandisk_like(resolution: u32) -> TriMesh {
    assert!(resolution >= 8, "fandisk_like needs resolution >= 8");
    let len = PART_W / resolution as f64;
    let profile = fillet_profile(len);
    let n = profile.len() as u32;
    let layers = ((PART_H / len).round() as u32).max(1);

    let mut positions = Vec::new();
    for j in 0..=layers {
        let z = -PART_H / 2.0 + PART_H * j as f64 / layers as f64;
        positions.extend(profile.iter().map(|p| to_f32([p[0], p[1], z])));
    }
    let side = |i: u32, j: u32| j * n + i % n;
    let mut tris = Vec::new();
    for j in 0..layers {
        for i in 0..n {
            // The profile runs counter-clockwise seen from +z, so
            // (profile direction) x (+z) points out of the part.
            let (a, b, c, d) = (
                side(i, j),
                side(i + 1, j),
                side(i + 1, j + 1),
                side(i, j + 1),
            );
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }

    let (cap_pts, cap_tris) = triangulate_convex(&profile, &lattice_inside(&profile, len));
    for (z, layer, flip) in [(-PART_H / 2.0, 0, true), (PART_H / 2.0, layers, false)] {
        let base = positions.len() as u32;
        positions.extend(
            cap_pts[profile.len()..]
                .iter()
                .map(|p| to_f32([p[0], p[1], z])),
        );
        // Rim points are the side vertices of the first or last layer.
        let map = |v: u32| if v < n { side(v, layer) } else { base + v - n };
        for t in &cap_tris {
            let t = t.map(map);
            // The cap triangulation is counter-clockwise seen from +z:
            // right for the top, reversed for the bottom.
            tris.push(if flip { [t[0], t[2], t[1]] } else { t });
        }
    }
    TriMesh::new(positions, tris)
}

/// The part's outline, counter-clockwise, sampled with spacing close to
/// `len`: straight sides and fillet arcs each get a whole number of equal
/// steps, so the rim vertices fall exactly on the corners and tangent points.
fn fillet_profile(len: f64) -> Vec<P2> {
    let (w, d) = (PART_W / 2.0, PART_D / 2.0);
    let (ra, rb) = (FILLET_A, FILLET_B);
    // (start, end, Some((centre, radius, start angle)) for arcs).
    type Piece = (P2, P2, Option<(P2, f64, f64)>);
    let pieces: [Piece; 6] = [
        // Bottom side, from the end of fillet A to the sharp corner (w, -d).
        ([-w + ra, -d], [w, -d], None),
        // Right side up to fillet B.
        ([w, -d], [w, d - rb], None),
        // Fillet B at the top-right corner, a quarter turn from angle 0.
        ([w, d - rb], [w - rb, d], Some(([w - rb, d - rb], rb, 0.0))),
        // Top side to the sharp corner (-w, d).
        ([w - rb, d], [-w, d], None),
        // Left side down to fillet A.
        ([-w, d], [-w, -d + ra], None),
        // Fillet A at the bottom-left corner, from angle pi.
        (
            [-w, -d + ra],
            [-w + ra, -d],
            Some(([-w + ra, -d + ra], ra, PI)),
        ),
    ];
    let mut out = Vec::new();
    for (a, b, arc) in pieces {
        match arc {
            None => {
                let l = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
                let steps = ((l / len).round() as usize).max(1);
                for s in 0..steps {
                    let t = s as f64 / steps as f64;
                    out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
                }
            }
            Some((c, r, a0)) => {
                // At least 3 steps, so even a coarse fillet reads as round.
                let steps = ((r * FRAC_PI_2 / len).round() as usize).max(3);
                out.push(a);
                for s in 1..steps {
                    let th = a0 + FRAC_PI_2 * s as f64 / steps as f64;
                    out.push([c[0] + r * th.cos(), c[1] + r * th.sin()]);
                }
            }
        }
    }
    out
}

/// Points of an equilateral lattice of spacing `len` that lie inside the
/// convex polygon and at least `0.6 len` from its rim.
fn lattice_inside(poly: &[P2], len: f64) -> Vec<P2> {
    let (mut lo, mut hi) = (poly[0], poly[0]);
    for p in poly {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let row = len * 3f64.sqrt() / 2.0;
    let rows = ((hi[1] - lo[1]) / row).ceil() as usize;
    let cols = ((hi[0] - lo[0]) / len).ceil() as usize + 1;
    let mut out = Vec::new();
    for j in 0..=rows {
        let y = lo[1] + j as f64 * row;
        let shift = if j % 2 == 1 { 0.5 * len } else { 0.0 };
        for i in 0..=cols {
            let p = [lo[0] + shift + i as f64 * len, y];
            if rim_distance(poly, p) >= 0.6 * len {
                out.push(p);
            }
        }
    }
    out
}

/// Distance from `p` to the rim of a counter-clockwise convex polygon,
/// negative outside.
fn rim_distance(poly: &[P2], p: P2) -> f64 {
    let mut best = f64::INFINITY;
    let mut inside = true;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
        let (px, py) = (p[0] - a[0], p[1] - a[1]);
        if ex * py - ey * px <= 0.0 {
            inside = false;
        }
        let t = ((px * ex + py * ey) / (ex * ex + ey * ey)).clamp(0.0, 1.0);
        let (dx, dy) = (px - t * ex, py - t * ey);
        best = best.min((dx * dx + dy * dy).sqrt());
    }
    if inside {
        best
    } else {
        -best
    }
}

/// The cube `[-0.5, 0.5]^3` with each face an `n x n` grid of squares,
/// each split in two along the same diagonal.
///
/// Closed, genus 0, `6 n^2 + 2` vertices, `12 n^2` triangles, all right
/// isosceles (smallest angle 45 degrees). All 12 edges and 8 corners are
/// sharp.
///
/// # Panics
/// If `n` is 0 or above 1000.
pub fn cube(n: u32) -> TriMesh {
    assert!((1..=1000).contains(&n), "cube needs 1 <= n <= 1000");
    let m = n as usize + 1;
    // Dense lattice index -> vertex, so edges and corners shared by two or
    // three faces get one vertex.
    let mut id = vec![u32::MAX; m * m * m];
    let mut positions = Vec::new();
    let mut vertex = |g: [usize; 3], positions: &mut Vec<[f32; 3]>| -> u32 {
        let slot = &mut id[g[0] + m * (g[1] + m * g[2])];
        if *slot == u32::MAX {
            *slot = positions.len() as u32;
            positions.push(to_f32(g.map(|c| c as f64 / n as f64 - 0.5)));
        }
        *slot
    };
    let mut tris = Vec::with_capacity(12 * (n * n) as usize);
    for axis in 0..3 {
        // (u, v, axis) is a right-handed frame, so u x v = +axis.
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, n as usize] {
            for j in 0..n as usize {
                for i in 0..n as usize {
                    let mut q = [0u32; 4];
                    for (k, (di, dj)) in [(0, 0), (1, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                        let mut g = [0; 3];
                        g[axis] = side;
                        g[u] = i + di;
                        g[v] = j + dj;
                        q[k] = vertex(g, &mut positions);
                    }
                    let [a, b, c, d] = q;
                    if side == 0 {
                        // Outward is -axis here: reverse the quad.
                        tris.push([a, c, b]);
                        tris.push([a, d, c]);
                    } else {
                        tris.push([a, b, c]);
                        tris.push([a, c, d]);
                    }
                }
            }
        }
    }
    TriMesh::new(positions, tris)
}
