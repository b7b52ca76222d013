//! Construction of the binary tree: binned surface-area-heuristic splits
//! (Wald, "On fast construction of SAH-based bounding volume
//! hierarchies", 2007) over the triangles' boxes, partitioned in place.
//!
//! Invariants: the tree (its nodes in depth-first order, the left child
//! right after its parent, and the leaf order, which sets the order in
//! which `metrics::Surface` samples) depends only on the triangles. The
//! two halves of a split are disjoint ranges of the item array, so above
//! [`PAR_ITEMS`] they are built on two rayon tasks and their node lists
//! concatenated, the right one's inner indices shifted by what precedes
//! it: the same nodes, in the same order, as the one-thread loop makes,
//! at any thread count. Iterative below that, and below
//! [`PAR_DEPTH`] levels of parallel splits (a hostile mesh can make
//! every split peel off a few items): no recursion depth to exhaust.

use super::aabb::{Aabb, Node};
use crate::metrics::triangle::Tri;

/// Triangles per leaf at most. Part of the output: it sets the leaf
/// order, which is the order `Surface` samples in.
pub(super) const LEAF_SIZE: usize = 2;
/// Bins of the SAH split search (part of the output, as `LEAF_SIZE`).
const BINS: usize = 12;
/// Ranges of more items than this build their two halves in parallel:
/// below it a task costs more than it saves.
const PAR_ITEMS: usize = 16_384;
/// Levels of parallel splits at most: 2^12 tasks are far more than the
/// cores, and the recursion stays shallow whatever the splits.
const PAR_DEPTH: u32 = 12;

/// The binary tree over `tris` (nodes in depth-first order, empty for
/// no triangles) and the triangles' indices in leaf order.
pub(super) fn build(tris: &[Tri]) -> (Vec<Node>, Vec<u32>) {
    let mut items = items_of(tris);
    if items.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let (bounds, centroids) = bounds_of(&items);
    let nodes = subtree(&mut items, 0, bounds, centroids, 0);
    (nodes, items.iter().map(|it| it.id).collect())
}

/// The builder's items for `tris`, in their order: each triangle's box,
/// the centre of the box, and its index.
fn items_of(tris: &[Tri]) -> Vec<Item> {
    tris.iter()
        .enumerate()
        .map(|(i, t)| {
            let bounds = Aabb::of(t);
            Item {
                centroid: core::array::from_fn(|k| 0.5 * bounds.min[k] + 0.5 * bounds.max[k]),
                bounds,
                id: i as u32,
                bins: [0; 3],
            }
        })
        .collect()
}

/// The subtree over `items` (at least one), which start at `first` in
/// the whole array: inner nodes' indices count from this subtree's
/// root, leaves' from the whole array's start. `bounds` and `centroids`
/// are the items' boxes; `depth` counts the parallel splits above.
fn subtree(
    items: &mut [Item],
    first: usize,
    bounds: Aabb,
    centroids: Aabb,
    depth: u32,
) -> Vec<Node> {
    if items.len() <= PAR_ITEMS || depth >= PAR_DEPTH {
        return sequential(items, first, bounds, centroids);
    }
    let [l, r] = split(items, &centroids);
    let (left_items, right_items) = items.split_at_mut(l.count);
    let (left, right) = rayon::join(
        || subtree(left_items, first, l.bounds, l.centroids, depth + 1),
        || {
            subtree(
                right_items,
                first + l.count,
                r.bounds,
                r.centroids,
                depth + 1,
            )
        },
    );
    let mut nodes = Vec::with_capacity(1 + left.len() + right.len());
    nodes.push(Node {
        bounds,
        index: (1 + left.len()) as u32,
        count: 0,
    });
    let shifted = |by: usize| {
        move |n: &Node| Node {
            index: if n.count == 0 {
                n.index + by as u32
            } else {
                n.index
            },
            ..*n
        }
    };
    nodes.extend(left.iter().map(shifted(1)));
    nodes.extend(right.iter().map(shifted(1 + left.len())));
    nodes
}

/// [`subtree`] on one thread.
fn sequential(items: &mut [Item], first: usize, bounds: Aabb, centroids: Aabb) -> Vec<Node> {
    let n = items.len();
    let mut nodes: Vec<Node> = Vec::with_capacity(2 * n.div_ceil(LEAF_SIZE) + 1);
    // Ranges still to build, each with its box, its centroids' box and
    // the parent whose right-child index it must fill in (left children
    // need none: they follow their parent). Left is pushed last so that
    // it is built first.
    let mut todo: Vec<Range> = vec![Range {
        patch: None,
        first: 0,
        end: n,
        bounds,
        centroids,
    }];
    while let Some(r) = todo.pop() {
        let node = nodes.len();
        if let Some(parent) = r.patch {
            nodes[parent].index = node as u32;
        }
        let count = r.end - r.first;
        if count <= LEAF_SIZE {
            nodes.push(Node {
                bounds: r.bounds,
                index: (first + r.first) as u32,
                count: count as u32,
            });
            continue;
        }
        nodes.push(Node {
            bounds: r.bounds,
            index: 0,
            count: 0,
        });
        let [left, right] = split(&mut items[r.first..r.end], &r.centroids);
        let mid = r.first + left.count;
        todo.push(Range {
            patch: Some(node),
            first: mid,
            end: r.end,
            bounds: right.bounds,
            centroids: right.centroids,
        });
        todo.push(Range {
            patch: None,
            first: r.first,
            end: mid,
            bounds: left.bounds,
            centroids: left.centroids,
        });
    }
    nodes
}

/// A triangle as the builder moves it around: its box, the centre of
/// the box, and its index. Ranges of these are partitioned in place, so
/// every pass of the build reads memory in order.
#[derive(Clone, Copy, Debug)]
struct Item {
    bounds: Aabb,
    centroid: [f32; 3],
    id: u32,
    /// Its bin on each axis in the split under way (`split` writes them
    /// as it bins and reads the chosen axis's as it partitions: the
    /// division feeding the side's branch was the partition's stall).
    bins: [u8; 3],
}

/// A range of items still to be built into a subtree.
#[derive(Clone, Copy, Debug)]
struct Range {
    /// The parent whose right-child index is this subtree's first node.
    patch: Option<usize>,
    first: usize,
    end: usize,
    /// The union of the items' boxes.
    bounds: Aabb,
    /// The box of the items' centroids.
    centroids: Aabb,
}

/// One side of a split: its item count, box and centroids' box.
#[derive(Clone, Copy, Debug)]
struct Side {
    count: usize,
    bounds: Aabb,
    centroids: Aabb,
}

/// The box of the items and the box of their centroids.
fn bounds_of(items: &[Item]) -> (Aabb, Aabb) {
    let mut bounds = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    for it in items {
        bounds.grow(&it.bounds);
        centroids.grow_point(&it.centroid);
    }
    (bounds, centroids)
}

/// Reorders `items` (at least two) into two non-empty halves, the first
/// first: the binned SAH split over the three axes, or the middle when
/// all centroids coincide. `centroids` is the box of the items'
/// centroids.
fn split(items: &mut [Item], centroids: &Aabb) -> [Side; 2] {
    let n = items.len();
    let (lo, hi) = (centroids.min, centroids.max);
    // Bin of a centroid coordinate; the same function sorts items into
    // bins and then partitions them, so both agree exactly.
    let bin_of = |c: f32, k: usize| -> usize {
        let x = (c - lo[k]) as f64 / (hi[k] - lo[k]) as f64 * BINS as f64;
        // `x` is in [0, BINS] (or NaN on a flat axis, never split): `u32`
        // converts it as `usize` would, in fewer instructions.
        (x as u32).min(BINS as u32 - 1) as usize
    };
    let axes: Vec<usize> = (0..3).filter(|&k| hi[k] > lo[k]).collect();
    // One pass over the range bins it on every axis at once (a flat axis
    // is binned too, all in bin 0, but never split).
    let mut count = [[0usize; BINS]; 3];
    let mut bounds = [[Aabb::EMPTY; BINS]; 3];
    for it in items.iter_mut() {
        for k in 0..3 {
            let b = bin_of(it.centroid[k], k);
            it.bins[k] = b as u8;
            count[k][b] += 1;
            bounds[k][b].grow(&it.bounds);
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
            // An empty bin leaves both sides as they were, so the split
            // after it costs what the split before it did, which a
            // strict `<` already ranked first: skipped, the same choice
            // (most bins of a small range are empty).
            if count[b - 1] == 0 {
                continue;
            }
            left.grow(&bounds[b - 1]);
            left_count += count[b - 1];
            if left_count == n {
                continue;
            }
            let cost =
                left.half_area() * left_count as f64 + right_area[b] * (n - left_count) as f64;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, k, b));
            }
        }
    }
    let Some((_, k, b)) = best else {
        let (left, right) = items.split_at(n / 2);
        return [left, right].map(|half| {
            let (bounds, centroids) = bounds_of(half);
            Side {
                count: half.len(),
                bounds,
                centroids,
            }
        });
    };
    // In-place partition (deterministic for a given input order); the
    // sides' boxes are the unions of their bins', their centroids' boxes
    // are gathered on the way.
    let mut side = [Aabb::EMPTY; 2];
    for (bin, bounds) in bounds[k].iter().enumerate() {
        side[(bin >= b) as usize].grow(bounds);
    }
    let mut centroids = [Aabb::EMPTY; 2];
    let mut i = 0;
    for j in 0..n {
        let c = &items[j].centroid;
        if usize::from(items[j].bins[k]) < b {
            centroids[0].grow_point(c);
            items.swap(i, j);
            i += 1;
        } else {
            centroids[1].grow_point(c);
        }
    }
    [
        Side {
            count: i,
            bounds: side[0],
            centroids: centroids[0],
        },
        Side {
            count: n - i,
            bounds: side[1],
            centroids: centroids[1],
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node as comparable figures.
    fn key(n: &Node) -> ([f32; 3], [f32; 3], u32, u32) {
        (n.bounds.min, n.bounds.max, n.index, n.count)
    }

    /// Triangles scattered by a fixed generator, with clusters (many
    /// equal centroids) and a few far outliers, so that splits are both
    /// even and lopsided.
    fn soup(n: usize) -> Vec<Tri> {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..n)
            .map(|i| {
                let c = match i % 7 {
                    0 => [0.25, 0.25, 0.25],
                    1 if i % 1000 == 1 => [1e3 * next(), 0.0, 0.0],
                    _ => [next(), next(), next()],
                };
                let d = 1e-3 * next();
                [c, [c[0] + d, c[1], c[2]], [c[0], c[1] + d, c[2] + d]]
            })
            .collect()
    }

    #[test]
    fn the_parallel_build_is_the_sequential_tree_at_any_thread_count() {
        let tris = soup(5 * PAR_ITEMS + 123);
        // The one-thread loop over the whole array: the reference.
        let mut items = items_of(&tris);
        let (bounds, centroids) = bounds_of(&items);
        let reference: Vec<_> = sequential(&mut items, 0, bounds, centroids)
            .iter()
            .map(key)
            .collect();
        let order: Vec<u32> = items.iter().map(|it| it.id).collect();
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let (nodes, ids) = pool.install(|| build(&tris));
            assert_eq!(ids, order, "{threads} threads");
            let nodes: Vec<_> = nodes.iter().map(key).collect();
            assert_eq!(nodes, reference, "{threads} threads");
        }
    }
}
