//! A quick construction of the binary tree for surfaces measured a few
//! times only: triangles sorted along a Morton (Z-order) curve of their
//! boxes' centres, each range split where the codes' highest differing
//! bit changes (Lauterbach et al., "Fast BVH construction on GPUs", 2009:
//! the linear BVH), boxes gathered bottom-up.
//!
//! Why beside the SAH build (`build`): a binned SAH build costs about
//! 0.6 µs per triangle, a second on two cores for the million triangles
//! of a scan's whole-mesh file, to answer the encoder's check of 60,000
//! queries (`encoder::check`); this one costs a sort and two linear
//! passes. Its tree is looser (boxes overlap more), so a query reads more
//! nodes: worth it only where queries are few against the triangles
//! (`Build::for_queries`).
//! Nearest-point answers are exact with either tree (pruning is exact);
//! only the leaf order, hence where `metrics::Surface` puts its samples,
//! differs.
//!
//! Invariants: the tree depends only on the triangles (codes tied are
//! ordered by index, so the sort has one answer at any thread count);
//! nodes in depth-first order, the left child right after its parent, as
//! `build` makes them; every split leaves both sides non-empty.

use super::aabb::{Aabb, Node};
use super::build::LEAF_SIZE;
use crate::metrics::triangle::Tri;
use rayon::prelude::*;

/// Bits per axis of a code (three axes in a `u64`).
const BITS: u32 = 21;

/// The tree over `tris` (nodes in depth-first order, empty for no
/// triangles) and the triangles' indices in leaf order.
pub(super) fn build(tris: &[Tri]) -> (Vec<Node>, Vec<u32>) {
    if tris.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let boxes: Vec<Aabb> = tris.par_iter().map(Aabb::of).collect();
    let centre =
        |b: &Aabb| -> [f32; 3] { core::array::from_fn(|k| 0.5 * b.min[k] + 0.5 * b.max[k]) };
    let mut span = Aabb::EMPTY;
    for b in &boxes {
        span.grow_point(&centre(b));
    }
    let scale: [f64; 3] = core::array::from_fn(|k| {
        let d = span.max[k] as f64 - span.min[k] as f64;
        if d > 0.0 {
            ((1u64 << BITS) - 1) as f64 / d
        } else {
            0.0
        }
    });
    let mut keyed: Vec<(u64, u32)> = boxes
        .par_iter()
        .enumerate()
        .map(|(i, b)| {
            let c = centre(b);
            let cell: [u64; 3] =
                core::array::from_fn(|k| ((c[k] as f64 - span.min[k] as f64) * scale[k]) as u64);
            (interleave(cell), i as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let codes: Vec<u64> = keyed.iter().map(|k| k.0).collect();
    let ids: Vec<u32> = keyed.iter().map(|k| k.1).collect();
    let mut nodes = topology(&codes);
    gather_boxes(&mut nodes, &ids, &boxes);
    (nodes, ids)
}

/// The three cells' bits interleaved, x lowest: `BITS` bits each.
fn interleave(cell: [u64; 3]) -> u64 {
    // Spreads the low 21 bits of `v` to every third bit.
    fn spread(v: u64) -> u64 {
        let mut x = v & 0x1f_ffff;
        x = (x | x << 32) & 0x1f_0000_0000_ffff;
        x = (x | x << 16) & 0x1f_0000_ff00_00ff;
        x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
        x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
        x = (x | x << 2) & 0x1249_2492_4924_9249;
        x
    }
    spread(cell[0]) | spread(cell[1]) << 1 | spread(cell[2]) << 2
}

/// The nodes over sorted `codes`, boxes left empty: each range of more
/// than [`LEAF_SIZE`] items splits where its highest differing bit turns
/// from 0 to 1, or at its middle when all its codes are equal.
fn topology(codes: &[u64]) -> Vec<Node> {
    let n = codes.len();
    let mut nodes: Vec<Node> = Vec::with_capacity(2 * n.div_ceil(LEAF_SIZE) + 1);
    // (range start, end, parent whose right-child index to fill in).
    let mut todo: Vec<(usize, usize, Option<usize>)> = vec![(0, n, None)];
    while let Some((first, end, patch)) = todo.pop() {
        let node = nodes.len();
        if let Some(parent) = patch {
            nodes[parent].index = node as u32;
        }
        let count = end - first;
        if count <= LEAF_SIZE {
            nodes.push(Node {
                bounds: Aabb::EMPTY,
                index: first as u32,
                count: count as u32,
            });
            continue;
        }
        nodes.push(Node {
            bounds: Aabb::EMPTY,
            index: 0,
            count: 0,
        });
        let (a, b) = (codes[first], codes[end - 1]);
        let mid = if a == b {
            first + count / 2
        } else {
            // The first code with the highest differing bit set: codes are
            // sorted, so those without it come first.
            let bit = 63 - (a ^ b).leading_zeros();
            let high = |c: &u64| (c >> bit) & 1 == 1;
            first + codes[first..end].partition_point(|c| !high(c))
        };
        // Right pushed first, so the left is built next (depth first).
        todo.push((mid, end, Some(node)));
        todo.push((first, mid, None));
    }
    nodes
}

/// Fills every node's box: children follow their parents, so one pass
/// from the last node back sees both children of a node before it.
fn gather_boxes(nodes: &mut [Node], ids: &[u32], boxes: &[Aabb]) {
    for i in (0..nodes.len()).rev() {
        let n = nodes[i];
        let mut b = Aabb::EMPTY;
        if n.count > 0 {
            let first = n.index as usize;
            for &id in &ids[first..first + n.count as usize] {
                b.grow(&boxes[id as usize]);
            }
        } else {
            b.grow(&nodes[i + 1].bounds);
            b.grow(&nodes[n.index as usize].bounds);
        }
        nodes[i].bounds = b;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn its_tree_finds_the_same_nearest_distances_as_the_sah_tree() {
        // A wavy sheet with a far outlier cluster, queried on and off it.
        let mut tris: Vec<Tri> = Vec::new();
        for i in 0..60 {
            for j in 0..50 {
                let z = |a: f32, b: f32| 0.3 * (0.4 * a).sin() * (0.3 * b).cos();
                let (x, y) = (i as f32, j as f32);
                let p = |a: f32, b: f32| [a, b, z(a, b)];
                tris.push([p(x, y), p(x + 1.0, y), p(x, y + 1.0)]);
                tris.push([p(x + 1.0, y), p(x + 1.0, y + 1.0), p(x, y + 1.0)]);
            }
        }
        for k in 0..40 {
            let c = 500.0 + k as f32;
            tris.push([[c, 0.0, 0.0], [c, 1.0, 0.0], [c, 0.0, 1.0]]);
        }
        let sah = super::super::Bvh::with_build(&tris, super::super::Build::Sah);
        let morton = super::super::Bvh::with_build(&tris, super::super::Build::Morton);
        let (mut a, mut b) = (Default::default(), Default::default());
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..2000 {
            let mut next = || {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64
            };
            let q = [
                700.0 * next() - 50.0,
                70.0 * next() - 10.0,
                20.0 * next() - 10.0,
            ];
            let (s, m) = (
                sah.nearest(q, None, &mut a).unwrap(),
                morton.nearest(q, None, &mut b).unwrap(),
            );
            assert_eq!(s.distance2, m.distance2, "{q:?}");
        }
    }

    #[test]
    fn codes_interleave_the_axes() {
        assert_eq!(interleave([1, 0, 0]), 0b001);
        assert_eq!(interleave([0, 1, 0]), 0b010);
        assert_eq!(interleave([0, 0, 1]), 0b100);
        assert_eq!(interleave([0b11, 0, 0]), 0b001_001);
        let top = (1u64 << BITS) - 1;
        assert_eq!(interleave([top, top, top]), (1u64 << 63) - 1);
    }

    #[test]
    fn every_triangle_sits_in_one_leaf_inside_every_box_above_it() {
        // A grid with repeated centres, so equal codes split at the middle.
        let tris: Vec<Tri> = (0..5000)
            .map(|i| {
                let (x, y) = ((i % 70) as f32, (i / 70 % 13) as f32);
                [[x, y, 0.0], [x + 1.0, y, 0.0], [x, y + 1.0, 0.5]]
            })
            .collect();
        let (nodes, ids) = build(&tris);
        let mut seen = vec![0u32; tris.len()];
        let mut stack = vec![(0usize, Aabb::EMPTY, true)];
        while let Some((i, parent, root)) = stack.pop() {
            let n = nodes[i];
            if !root {
                for k in 0..3 {
                    assert!(parent.min[k] <= n.bounds.min[k] && n.bounds.max[k] <= parent.max[k]);
                }
            }
            if n.count > 0 {
                assert!(n.count as usize <= LEAF_SIZE);
                for &id in &ids[n.index as usize..(n.index + n.count) as usize] {
                    seen[id as usize] += 1;
                    let b = Aabb::of(&tris[id as usize]);
                    for k in 0..3 {
                        assert!(n.bounds.min[k] <= b.min[k] && b.max[k] <= n.bounds.max[k]);
                    }
                }
            } else {
                stack.push((i + 1, n.bounds, false));
                stack.push((n.index as usize, n.bounds, false));
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
    }
}
