//! A bounding-volume hierarchy over triangles for exact nearest-point
//! queries: axis-aligned boxes, binned surface-area-heuristic splits
//! (Wald, "On fast construction of SAH-based bounding volume hierarchies",
//! 2007), depth-first closest-first traversal with a shrinking bound.
//!
//! Why our own and not parry3d: the queries here are one kind only
//! (closest point of a triangle soup), they must give the same answer on
//! every run and thread count, and they profit from a caller-supplied
//! starting bound (consecutive samples lie close together, so the previous
//! sample's triangle bounds the next search tightly). A small tree in
//! `f32` with `f64` distance arithmetic does exactly that in a few hundred
//! lines, without pulling in nalgebra.
//!
//! Invariants:
//! * every node's box contains the boxes of all triangles below it, so a
//!   subtree whose box is farther than the best distance found cannot hold
//!   a nearer point: pruning is exact, not heuristic;
//! * box and triangle distances are computed in `f64` from the stored
//!   `f32` values (exactly representable), so the pruning test never
//!   discards a subtree because of rounding in a narrower type;
//! * nodes are stored depth-first: an inner node's left child follows it,
//!   its right child is named; leaves hold a contiguous run of triangles.
//!
//! Construction is iterative with an explicit stack (no recursion depth
//! to exhaust on adversarial input): a range whose centroids all coincide
//! is split at its middle, so every split makes progress.

use super::triangle::{triangle_distance2, Tri};

/// Triangles per leaf at most.
const LEAF_SIZE: usize = 2;
/// Bins of the SAH split search.
const BINS: usize = 12;

#[derive(Clone, Copy, Debug)]
struct Aabb {
    min: [f32; 3],
    max: [f32; 3],
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    fn grow(&mut self, other: &Aabb) {
        for k in 0..3 {
            self.min[k] = self.min[k].min(other.min[k]);
            self.max[k] = self.max[k].max(other.max[k]);
        }
    }

    fn of(t: &Tri) -> Aabb {
        Aabb {
            min: core::array::from_fn(|k| t[0][k].min(t[1][k]).min(t[2][k])),
            max: core::array::from_fn(|k| t[0][k].max(t[1][k]).max(t[2][k])),
        }
    }

    fn half_area(&self) -> f64 {
        if self.min[0] > self.max[0] {
            return 0.0;
        }
        let d: [f64; 3] = core::array::from_fn(|k| self.max[k] as f64 - self.min[k] as f64);
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }

    /// Squared distance from `p` to the box (0 inside).
    #[inline(always)]
    fn distance2(&self, p: [f64; 3]) -> f64 {
        (0..3).map(|k| gap2(self.min[k], self.max[k], p[k])).sum()
    }
}

/// Squared distance along one axis from `x` to `[lo, hi]`. Plain
/// comparisons rather than `f64::max`, whose NaN rules cost instructions
/// (every value here is finite).
#[inline(always)]
fn gap2(lo: f32, hi: f32, x: f64) -> f64 {
    let below = lo as f64 - x;
    let above = x - hi as f64;
    let d = if below > 0.0 {
        below
    } else if above > 0.0 {
        above
    } else {
        0.0
    };
    d * d
}

/// A node of the tree as it is built (one box per node).
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: first triangle; inner node: index of the right child.
    index: u32,
    /// Leaf: number of triangles (≥ 1); inner node: 0.
    count: u32,
}

/// The nearest point found by [`Bvh::nearest`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// Squared distance from the query point.
    pub distance2: f64,
    /// Index of the triangle (in the order given to [`Bvh::new`]).
    pub triangle: u32,
}

/// An inner node as it is searched: both children's boxes in one cache
/// line, so that deciding where to go reads only this node (a child's own
/// box would be a second, usually distant, memory access per level).
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Inner {
    min: [[f32; 3]; 2],
    max: [[f32; 3]; 2],
    /// Per child: the inner node's index, or for a leaf its first
    /// triangle.
    child: [u32; 2],
    /// Per child: 0 for an inner node, else the leaf's triangle count.
    count: [u32; 2],
}

impl Inner {
    #[inline(always)]
    fn distance2(&self, side: usize, p: [f64; 3]) -> f64 {
        gap2(self.min[side][0], self.max[side][0], p[0])
            + gap2(self.min[side][1], self.max[side][1], p[1])
            + gap2(self.min[side][2], self.max[side][2], p[2])
    }
}

/// Triangles arranged for nearest-point queries.
#[derive(Clone, Debug)]
pub struct Bvh {
    /// Inner nodes, the root first (empty when the root is a leaf).
    inner: Vec<Inner>,
    /// The root's box, and its triangle count if it is a leaf.
    root: (Aabb, u32),
    /// Triangles in leaf order.
    tris: Vec<Tri>,
    /// Original index of each entry of `tris`.
    ids: Vec<u32>,
    /// Position in `tris` of each original triangle.
    slot: Vec<u32>,
}

/// Reusable traversal stack (one per thread), so queries do not allocate.
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    stack: Vec<(u32, f64)>,
}

impl Bvh {
    /// Builds the tree. Every coordinate must be finite (the caller
    /// checks); an empty list gives a tree that finds nothing.
    pub fn new(tris: &[Tri]) -> Bvh {
        let n = tris.len();
        let boxes: Vec<Aabb> = tris.iter().map(Aabb::of).collect();
        let centroids: Vec<[f32; 3]> = boxes
            .iter()
            .map(|b| core::array::from_fn(|k| 0.5 * b.min[k] + 0.5 * b.max[k]))
            .collect();
        let mut order: Vec<u32> = (0..n as u32).collect();
        let mut nodes: Vec<Node> = Vec::with_capacity(2 * n.div_ceil(LEAF_SIZE) + 1);
        // Ranges still to build, each with the parent whose right-child
        // index it must fill in (left children need none: they follow
        // their parent). Left is pushed last so that it is built first.
        let mut todo: Vec<(Option<usize>, usize, usize)> = Vec::new();
        if n > 0 {
            todo.push((None, 0, n));
        }
        while let Some((patch, first, end)) = todo.pop() {
            let node = nodes.len();
            if let Some(parent) = patch {
                nodes[parent].index = node as u32;
            }
            let mut bounds = Aabb::EMPTY;
            for &t in &order[first..end] {
                bounds.grow(&boxes[t as usize]);
            }
            let count = end - first;
            if count <= LEAF_SIZE {
                nodes.push(Node {
                    bounds,
                    index: first as u32,
                    count: count as u32,
                });
                continue;
            }
            nodes.push(Node {
                bounds,
                index: 0,
                count: 0,
            });
            let mid = first + split(&mut order[first..end], &boxes, &centroids);
            todo.push((Some(node), mid, end));
            todo.push((None, first, mid));
        }
        let mut slot = vec![0u32; n];
        for (i, &t) in order.iter().enumerate() {
            slot[t as usize] = i as u32;
        }
        let (inner, root) = pack(&nodes);
        Bvh {
            inner,
            root,
            tris: order.iter().map(|&t| tris[t as usize]).collect(),
            ids: order,
            slot,
        }
    }

    /// Original triangle indices in leaf order (a spatially coherent
    /// order).
    pub fn order(&self) -> &[u32] {
        &self.ids
    }

    /// The triangles in leaf order.
    pub fn triangles(&self) -> &[Tri] {
        &self.tris
    }

    /// The triangle nearest to `p`, if any. `hint`, a triangle likely to be
    /// near (such as the previous query's answer), only speeds the search
    /// up: its distance is the starting bound, and a nearer triangle still
    /// wins. Ties go to the triangle met first, so the distance, not the
    /// triangle, is the meaningful output.
    pub fn nearest(
        &self,
        p: [f64; 3],
        hint: Option<u32>,
        scratch: &mut Scratch,
    ) -> Option<Nearest> {
        let mut best = match hint.and_then(|h| self.slot.get(h as usize)) {
            Some(&s) => Nearest {
                distance2: triangle_distance2(p, &self.tris[s as usize]),
                triangle: s,
            },
            None => Nearest {
                distance2: f64::INFINITY,
                triangle: u32::MAX,
            },
        };
        let (root_box, root_count) = self.root;
        let test = |first: u32, count: u32, best: &mut Nearest| {
            let first = first as usize;
            for (s, t) in self.tris[first..first + count as usize].iter().enumerate() {
                let d = triangle_distance2(p, t);
                if d < best.distance2 {
                    *best = Nearest {
                        distance2: d,
                        triangle: (first + s) as u32,
                    };
                }
            }
        };
        if self.inner.is_empty() {
            test(0, root_count, &mut best);
        } else {
            let stack = &mut scratch.stack;
            stack.clear();
            stack.push((0, root_box.distance2(p)));
            while let Some((i, d2)) = stack.pop() {
                if d2 >= best.distance2 {
                    continue;
                }
                let node = &self.inner[i as usize];
                let d = [node.distance2(0, p), node.distance2(1, p)];
                let order = if d[0] <= d[1] { [0, 1] } else { [1, 0] };
                let mut push = [None; 2];
                // Nearer child first: a leaf is searched at once, which
                // may shrink the bound before the farther child is judged.
                for (slot, side) in push.iter_mut().zip(order) {
                    if d[side] >= best.distance2 {
                        continue;
                    }
                    if node.count[side] > 0 {
                        test(node.child[side], node.count[side], &mut best);
                    } else {
                        *slot = Some((node.child[side], d[side]));
                    }
                }
                // Farther pushed first, so the nearer is popped first.
                stack.extend(push[1]);
                stack.extend(push[0]);
            }
        }
        (best.triangle != u32::MAX).then(|| Nearest {
            distance2: best.distance2,
            triangle: self.ids[best.triangle as usize],
        })
    }
}

/// The search layout of a built tree: its inner nodes with their children's
/// boxes, and the root's box and leaf count (0 unless the root is a leaf).
fn pack(nodes: &[Node]) -> (Vec<Inner>, (Aabb, u32)) {
    let Some(root) = nodes.first() else {
        return (Vec::new(), (Aabb::EMPTY, 0));
    };
    // Inner nodes keep their relative (depth-first) order.
    let mut id = vec![u32::MAX; nodes.len()];
    let mut count = 0u32;
    for (i, n) in nodes.iter().enumerate() {
        if n.count == 0 {
            id[i] = count;
            count += 1;
        }
    }
    let mut inner = Vec::with_capacity(count as usize);
    for (i, n) in nodes.iter().enumerate() {
        if n.count > 0 {
            continue;
        }
        let kids = [i + 1, n.index as usize];
        let c = kids.map(|k| &nodes[k]);
        inner.push(Inner {
            min: c.map(|k| k.bounds.min),
            max: c.map(|k| k.bounds.max),
            child: [0, 1].map(|s| {
                if c[s].count > 0 {
                    c[s].index
                } else {
                    id[kids[s]]
                }
            }),
            count: c.map(|k| k.count),
        });
    }
    (inner, (root.bounds, root.count))
}

/// Reorders `order` (a range of triangles) into two non-empty halves and
/// returns the size of the first: the binned SAH split over the three
/// axes, or the middle when all centroids coincide.
fn split(order: &mut [u32], boxes: &[Aabb], centroids: &[[f32; 3]]) -> usize {
    let n = order.len();
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for &t in order.iter() {
        let c = centroids[t as usize];
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let bin_of = |c: f32, k: usize| -> usize {
        let x = (c - lo[k]) as f64 / (hi[k] - lo[k]) as f64 * BINS as f64;
        (x as usize).min(BINS - 1)
    };
    let axes: Vec<usize> = (0..3).filter(|&k| hi[k] > lo[k]).collect();
    // One pass over the range bins it on every axis at once.
    let mut count = [[0usize; BINS]; 3];
    let mut bounds = [[Aabb::EMPTY; BINS]; 3];
    for &t in order.iter() {
        let c = centroids[t as usize];
        for &k in &axes {
            let b = bin_of(c[k], k);
            count[k][b] += 1;
            bounds[k][b].grow(&boxes[t as usize]);
        }
    }
    // (cost, axis, bins on the left)
    let mut best: Option<(f64, usize, usize)> = None;
    for &k in &axes {
        let (count, bounds) = (&count[k], &bounds[k]);
        // Right-to-left sweep first, then evaluate left-to-right.
        let mut right_area = [0.0f64; BINS];
        let mut acc = Aabb::EMPTY;
        for b in (1..BINS).rev() {
            acc.grow(&bounds[b]);
            right_area[b] = acc.half_area();
        }
        let mut left = Aabb::EMPTY;
        let mut left_count = 0;
        for b in 1..BINS {
            left.grow(&bounds[b - 1]);
            left_count += count[b - 1];
            if left_count == 0 || left_count == n {
                continue;
            }
            let cost =
                left.half_area() * left_count as f64 + right_area[b] * (n - left_count) as f64;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, k, b));
            }
        }
    }
    match best {
        Some((_, k, b)) => {
            // In-place partition; deterministic for a given input order.
            let mut i = 0;
            for j in 0..n {
                if bin_of(centroids[order[j] as usize][k], k) < b {
                    order.swap(i, j);
                    i += 1;
                }
            }
            i
        }
        None => n / 2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(seed: u64) -> impl FnMut() -> f32 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    #[test]
    fn nearest_equals_brute_force() {
        let mut r = rng(0x1234_5678_9abc_def1);
        for n in [1usize, 2, 5, 37, 400] {
            let tris: Vec<Tri> = (0..n)
                .map(|_| {
                    let c = [r(), r(), r()];
                    core::array::from_fn(|_| core::array::from_fn(|k| c[k] + 0.1 * r()))
                })
                .collect();
            let bvh = Bvh::new(&tris);
            let mut scratch = Scratch::default();
            let mut hint = None;
            for q in 0..300 {
                let p = [
                    r() as f64 * 1.4 - 0.2,
                    r() as f64 * 1.4 - 0.2,
                    r() as f64 * 1.4 - 0.2,
                ];
                let brute = tris
                    .iter()
                    .map(|t| triangle_distance2(p, t))
                    .fold(f64::INFINITY, f64::min);
                // With and without a hint (any triangle, even a far one).
                let a = bvh.nearest(p, None, &mut scratch).unwrap();
                let b = bvh.nearest(p, hint, &mut scratch).unwrap();
                assert_eq!(a.distance2, brute);
                assert_eq!(b.distance2, brute);
                assert_eq!(triangle_distance2(p, &tris[a.triangle as usize]), brute);
                hint = Some((q * 7 % n) as u32);
            }
        }
    }

    #[test]
    fn coincident_centroids_and_empty_input() {
        let t: Tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let bvh = Bvh::new(&vec![t; 1000]);
        let mut s = Scratch::default();
        let hit = bvh.nearest([0.25, 0.25, 2.0], None, &mut s).unwrap();
        assert_eq!(hit.distance2, 4.0);
        assert!(Bvh::new(&[]).nearest([0.0; 3], Some(3), &mut s).is_none());
    }
}
