//! Where a line crosses a triangle mesh: the crossing nearest a point
//! along a direction, within a distance (the displaced-subdivision
//! encoder's "move along the normal to the input").
//!
//! Sources: Möller & Trumbore, "Fast, minimum storage ray/triangle
//! intersection" (1997), for each triangle; Kay & Kajiya's slab test
//! (1986) for each box of a binary bounding-volume hierarchy split at the
//! median centroid of its longest axis (leaves of up to [`LEAF`]
//! triangles).
//!
//! The encoder asks these queries of the nearest-point tree it already
//! has (`bvh::crossing`, with [`crossing`] below for each triangle);
//! [`Lines`], a plain binary tree, is kept as the simple reference the
//! tests check that one against.
//!
//! Invariants: the answer depends only on the triangles and the query
//! (the tree's build is deterministic, the search keeps the crossing of
//! smallest |t| and breaks exact ties towards positive t); encoder-side
//! only, so `f64` throughout and no promise of bit-exact agreement with
//! any other code.

#[cfg(test)]
use crate::prelude::*;

#[cfg(test)]
/// Most triangles in a leaf.
const LEAF: usize = 4;
/// Barycentric slack: a line through a shared edge or vertex hits one
/// of the triangles around it rather than slipping between them.
const EDGE_SLACK: f64 = 1e-9;

#[cfg(test)]
struct Node {
    lo: [f64; 3],
    hi: [f64; 3],
    /// Leaf: first triangle in `order`; inner: the right child (the left
    /// is the next node).
    index: u32,
    /// Leaf: triangle count; inner: 0.
    count: u32,
}

#[cfg(test)]
/// Triangles arranged for line queries.
pub(crate) struct Lines {
    nodes: Vec<Node>,
    tris: Vec<[[f64; 3]; 3]>,
}

#[cfg(test)]
impl Lines {
    /// The tree over `triangles` of `positions` (indices in range).
    pub fn new(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Lines {
        let tris: Vec<[[f64; 3]; 3]> = triangles
            .iter()
            .map(|t| t.map(|v| positions[v as usize].map(f64::from)))
            .collect();
        let centre: Vec<[f64; 3]> = tris
            .iter()
            .map(|t| core::array::from_fn(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0))
            .collect();
        let mut order: Vec<u32> = (0..tris.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * tris.len() / LEAF + 1);
        if !tris.is_empty() {
            build(&mut nodes, &mut order, 0, &tris, &centre);
        }
        let tris = order.iter().map(|&i| tris[i as usize]).collect();
        Lines { nodes, tris }
    }

    /// The `t` of smallest magnitude in `[−reach, reach]` where the line
    /// `p + t·d` crosses a triangle, if any; with `facing`, only
    /// triangles whose normal (their corners' right-hand turn) points
    /// along `d`: on an oriented surface, the sheet that faces the same
    /// way, not the far side of a thin part.
    pub fn nearest_crossing(
        &self,
        p: [f64; 3],
        d: [f64; 3],
        reach: f64,
        facing: bool,
    ) -> Option<f64> {
        let mut best: Option<f64> = None;
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let Some(node) = self.nodes.get(i as usize) else {
                break;
            };
            let bound = best.map_or(reach, f64::abs);
            if !slab(node, p, d, bound) {
                continue;
            }
            if node.count == 0 {
                stack.push(node.index);
                stack.push(i + 1);
                continue;
            }
            let first = node.index as usize;
            for t in &self.tris[first..first + node.count as usize] {
                let Some(s) = crossing(p, d, t, facing) else {
                    continue;
                };
                let better = match best {
                    None => s.abs() <= reach,
                    Some(b) => s.abs() < b.abs() || (s.abs() == b.abs() && s > b),
                };
                if better {
                    best = Some(s);
                }
            }
        }
        best
    }
}

#[cfg(test)]
fn build(
    nodes: &mut Vec<Node>,
    order: &mut [u32],
    first: usize,
    tris: &[[[f64; 3]; 3]],
    centre: &[[f64; 3]],
) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let (mut clo, mut chi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &i in order.iter() {
        for v in &tris[i as usize] {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        for k in 0..3 {
            clo[k] = clo[k].min(centre[i as usize][k]);
            chi[k] = chi[k].max(centre[i as usize][k]);
        }
    }
    let me = nodes.len();
    nodes.push(Node {
        lo,
        hi,
        index: first as u32,
        count: order.len() as u32,
    });
    if order.len() <= LEAF {
        return;
    }
    let axis = (0..3)
        .max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b])))
        .unwrap_or(0);
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        centre[a as usize][axis]
            .total_cmp(&centre[b as usize][axis])
            .then(a.cmp(&b))
    });
    let (left, right) = order.split_at_mut(mid);
    build(nodes, left, first, tris, centre);
    let r = nodes.len() as u32;
    build(nodes, right, first + mid, tris, centre);
    nodes[me].index = r;
    nodes[me].count = 0;
}

#[cfg(test)]
/// Does the segment `p + t·d`, |t| ≤ bound, meet the node's box?
fn slab(n: &Node, p: [f64; 3], d: [f64; 3], bound: f64) -> bool {
    let (mut t0, mut t1) = (-bound, bound);
    for k in 0..3 {
        if d[k] == 0.0 {
            if p[k] < n.lo[k] || p[k] > n.hi[k] {
                return false;
            }
            continue;
        }
        let (a, b) = ((n.lo[k] - p[k]) / d[k], (n.hi[k] - p[k]) / d[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// Möller–Trumbore: the `t` where the line `p + t·d` crosses triangle
/// `t`, if it does (either side; with `facing`, only a triangle whose
/// normal points along `d`).
pub(crate) fn crossing(p: [f64; 3], d: [f64; 3], t: &[[f64; 3]; 3], facing: bool) -> Option<f64> {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let h = cross(d, e2);
    let det = dot(e1, h);
    // det = d · (e2 × e1) = −d · n.
    if det == 0.0 || !det.is_finite() || (facing && det > 0.0) {
        return None;
    }
    let inv = 1.0 / det;
    let s = sub(p, t[0]);
    let u = dot(s, h) * inv;
    if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if v < -EDGE_SLACK || u + v > 1.0 + EDGE_SLACK {
        return None;
    }
    Some(dot(e2, q) * inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_nearer_of_two_sheets_within_reach() {
        // Two unit squares at z = 1 and z = −0.5.
        let p = vec![
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
            [0.0, 0.0, -0.5],
            [1.0, 0.0, -0.5],
            [1.0, 1.0, -0.5],
            [0.0, 1.0, -0.5],
        ];
        let mut p = p;
        let mut t = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
        // Enough far-away triangles to make inner nodes.
        for k in 0..20u32 {
            let x = 10.0 + k as f32;
            p.extend([[x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0]]);
            t.push([8 + 3 * k, 9 + 3 * k, 10 + 3 * k]);
        }
        let lines = Lines::new(&p, &t);
        let up = [0.0, 0.0, 1.0];
        let q = [0.3, 0.4, 0.0];
        assert_eq!(lines.nearest_crossing(q, up, 2.0, false), Some(-0.5));
        assert_eq!(lines.nearest_crossing(q, up, 0.4, false), None);
        assert_eq!(
            lines.nearest_crossing([0.3, 0.4, 0.75], up, 2.0, false),
            Some(0.25)
        );
        assert_eq!(
            lines.nearest_crossing([5.0, 0.4, 0.0], up, 2.0, false),
            None
        );
        assert_eq!(
            lines.nearest_crossing([10.2, 0.2, 0.3], up, 1.0, false),
            Some(-0.3)
        );
        // Every square faces +z: looking down, nothing faces the line.
        let down = [0.0, 0.0, -1.0];
        assert_eq!(lines.nearest_crossing(q, up, 2.0, true), Some(-0.5));
        assert_eq!(lines.nearest_crossing(q, down, 2.0, true), None);
    }
}

#[cfg(test)]
mod against_the_tree {
    use super::*;
    use crate::metrics::{Build, Surface};

    /// The nearest-point tree's line query (`bvh::crossing`) gives the
    /// reference's `f64`, bit for bit, on a curved mesh in awkward units,
    /// for lines in every direction, both facings and several reaches.
    #[test]
    fn the_wide_tree_agrees_with_the_reference_bit_for_bit() {
        let mut m = crate::mesh::test_shapes::uv_sphere(40, 30);
        for p in &mut m.positions {
            let r = 1.0 + 0.1 * (5.0 * p[0]).sin() * (3.0 * p[1]).cos();
            *p = p.map(|c| c * r * 1000.0 + 3.0);
        }
        let lines = Lines::new(&m.positions, &m.triangles);
        let mut seed = 7u64;
        let mut r = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for how in [Build::Sah, Build::Morton] {
            let surface = Surface::with_build(&m, how).unwrap();
            let mut stack = Vec::new();
            let mut hits = 0;
            for _ in 0..4000 {
                let p = [r() * 1200.0 + 3.0, r() * 1200.0 + 3.0, r() * 1200.0 + 3.0];
                let d = [r(), r(), r()];
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let d = d.map(|c| c / n);
                for reach in [50.0, 400.0, 5000.0] {
                    for facing in [false, true] {
                        let a = lines.nearest_crossing(p, d, reach, facing);
                        let b = surface.nearest_crossing(p, d, reach, facing, &mut stack);
                        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "{p:?} {d:?}");
                        hits += a.is_some() as usize;
                    }
                }
            }
            assert!(hits > 1000, "{hits}");
        }
    }
}
