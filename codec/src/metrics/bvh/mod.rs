//! A bounding-volume hierarchy over triangles for exact nearest-point
//! queries: axis-aligned boxes, binned surface-area-heuristic splits
//! (Wald, "On fast construction of SAH-based bounding volume hierarchies",
//! 2007), collapsed into a tree of eight-wide nodes (Dammertz, Hanika &
//! Keller, "Shallow bounding volume hierarchies for fast SIMD ray tracing
//! of incoherent rays", 2008) searched closest-first with a shrinking
//! bound.
//!
//! Why our own and not parry3d: the queries here are one kind only
//! (closest point of a triangle soup), they must give the same answer on
//! every run and thread count, and they profit from warm starts
//! (consecutive samples lie close together). A small tree in `f32` with
//! `f64` distance arithmetic does exactly that in a few hundred lines,
//! without pulling in nalgebra.
//!
//! Where the speed comes from (issue 4 asks for 2 million queries per
//! second against a million faces on one core):
//! * a node holds up to eight children's boxes axis by axis, so one pass
//!   of four-lane `f32` arithmetic per half measures them all, and a
//!   query reads about a third as many nodes as in a binary tree;
//! * the box tests are in `f32` against a threshold inflated just enough
//!   to cover every rounding ([`Bound`]), so they stay exact;
//! * warm starts: the caller's hint (the previous query's triangle) gives
//!   the starting bound, and the [`Scratch`] remembers the path the last
//!   query took down the tree, so the next one skips the levels whose
//!   other children are certainly too far ([`Path`]).
//!
//! Invariants:
//! * every node's box contains the boxes of all triangles below it, so a
//!   subtree whose box is farther than the best distance found cannot hold
//!   a nearer point: pruning is exact, not heuristic;
//! * triangle distances are computed in `f64` from the stored `f32`
//!   corners (exactly representable); a subtree is discarded only if its
//!   `f32` box distance, allowing for every rounding, exceeds the best
//!   `f64` distance found: the result equals a brute-force minimum over
//!   all triangles, bit for bit;
//! * triangles are stored in leaf order, every subtree holding a
//!   contiguous run; this order is also the order in which
//!   `metrics::Surface` samples, so it is part of the output: the build
//!   below must keep producing the same tree for the same input.
//!
//! Units: the tree stores its triangles scaled by a power of two that
//! brings the largest coordinate into `[1/2, 1)`, and scales each query
//! point the same way (issue 18). Without it, a mesh in units of 1e30 or
//! 1e-30 overflows or underflows the `f32` squared box distances (to
//! infinity or zero), nothing is pruned and every query visits every
//! node. A power of two scales exactly: the tree, the leaf order and every
//! distance are those of the unscaled input, bit for bit (short of
//! coordinates below 2⁻¹⁴⁹ of the largest one, which `f32` cannot hold
//! after scaling and which are far below its precision anyway).
//!
//! Far queries: a query farther from the tree's box than 2³⁰ times the
//! box's diagonal `d` takes the hint's triangle (or the first) without a
//! search. Every triangle then lies between `D` and `D + d` from it, so
//! the answer is within a relative 2⁻³⁰ of the minimum — and no box test,
//! in `f32` or `f64`, could tell the triangles apart: with every bound
//! within the rounding slack, the search would read every node for every
//! query (two meshes in units 1e30 apart measured against each other).
//!
//! Construction (`build`) splits large ranges on two rayon tasks and
//! the rest iteratively with an explicit stack (no recursion depth to
//! exhaust on adversarial input), making the same tree at any thread
//! count: a range whose centroids all coincide is split at its middle,
//! so every split makes progress.

use super::triangle::{triangle_distance2, Tri};
use aabb::{Aabb, Node};
use build::LEAF_SIZE;

mod aabb;
mod build;
#[cfg(feature = "encoder")]
mod crossing;
mod morton;
use std::sync::atomic::{AtomicU64, Ordering};

/// Children per node of the searched tree (eight measured about 3% faster
/// than four; see BENCHMARKS.md).
const W: usize = 8;
// Leaf counts are stored in a byte, lanes in a `u32` mask.
const _: () = assert!(LEAF_SIZE <= u8::MAX as usize && W <= 32);

/// The nearest point found by [`Bvh::nearest`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// Squared distance from the query point.
    pub distance2: f64,
    /// Index of the triangle (in the order given to [`Bvh::new`]).
    pub triangle: u32,
    /// Its position in the tree's leaf order: the hint for a next query.
    pub slot: u32,
}

/// A node as it is searched: up to `W` children, their boxes stored axis
/// by axis so that one pass of `f32` arithmetic measures them all, and
/// deciding where to go reads only this node (256 bytes, four cache
/// lines).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Wide {
    /// `lo[axis][child]`, `hi[axis][child]`; unused lanes hold an empty
    /// box (`+∞`, `−∞`), which is infinitely far.
    lo: [[f32; W]; 3],
    hi: [[f32; W]; 3],
    /// Per child: the node's index, or for a leaf its first triangle.
    child: [u32; W],
    /// Per child: 0 for a node, else the leaf's triangle count.
    leaf: [u8; W],
    /// Bit `j` set if lane `j` holds a child (2 to `W` children, in the
    /// first lanes).
    lanes: u32,
    /// Bit `j` set if lane `j` holds a leaf.
    leaves: u32,
}

impl Wide {
    /// The smallest of `d` over the children other than `j` (`d` as
    /// returned by [`Self::distance2`], where unused lanes are infinite).
    #[inline(always)]
    fn clearance(&self, d: &[f32; W], j: usize) -> f32 {
        let mut m = f32::INFINITY;
        for (k, &dk) in d.iter().enumerate() {
            let v = if k == j { f32::INFINITY } else { dk };
            m = if v < m { v } else { m };
        }
        m
    }

    /// Squared distances from `q` to the children's boxes, in `f32` (each
    /// a slight under- or over-estimate: see [`Bound`]).
    #[inline(always)]
    fn distance2(&self, q: [f32; 3]) -> [f32; W] {
        let mut d2 = [0.0f32; W];
        for ((lo, hi), &x) in self.lo.iter().zip(&self.hi).zip(&q) {
            for ((d, &lo), &hi) in d2.iter_mut().zip(lo).zip(hi) {
                // Branch-free max: compiles to `maxps`.
                let below = lo - x;
                let above = x - hi;
                let g = if below > above { below } else { above };
                let g = if g > 0.0 { g } else { 0.0 };
                *d += g * g;
            }
        }
        d2
    }
}

/// The search bound in both precisions: `best`, the smallest exact (`f64`)
/// squared triangle distance found so far, and `prune`, an `f32` threshold
/// such that a box whose computed `f32` squared distance exceeds it is
/// certainly farther than `best`, whatever the rounding.
///
/// Why it is safe: the box distance is computed from `q`, the query
/// rounded to `f32` (`|p − q| ≤ 2⁻²³·|p|∞`), with a relative error below
/// `8·2⁻²⁴` (one rounding per subtraction, square and sum) plus at most
/// `1e-44` from underflow. A box is pruned only when it is at least
/// `√best + s` from `q`, where `s = 2⁻²⁰·max(|p|∞, largest |coordinate|
/// of the triangles)` exceeds both `|p − q|` and the rounding of the `f64`
/// triangle distances; so it holds no triangle whose computed distance is
/// below `best`. Without a square root: `(√b + s)² ≤ (1 + t)·b + (1 +
/// 1/t)·s²` for any `t > 0` (here `2⁻¹⁰`); the threshold is that, times
/// `1 + 2⁻¹⁶` for the `f32` rounding, plus `1e-30`. An infinite threshold
/// (no bound yet, or a huge one) prunes nothing.
#[derive(Clone, Copy, Debug)]
struct Bound {
    best: f64,
    prune: f32,
    /// The threshold's constant term.
    floor: f64,
}

impl Bound {
    const GROW: f64 = 1.0 + 1.0 / (1u64 << 16) as f64;
    const T: f64 = 1.0 / (1u64 << 10) as f64;

    fn new(best: f64, slack: f64) -> Bound {
        let mut b = Bound {
            best,
            prune: 0.0,
            floor: slack * slack * (1.0 + 1.0 / Self::T) * Self::GROW + 1e-30,
        };
        b.set(best);
        b
    }

    #[inline(always)]
    fn set(&mut self, best: f64) {
        self.best = best;
        self.prune = (best * ((1.0 + Self::T) * Self::GROW) + self.floor) as f32;
    }

    /// Whether a box at computed `f32` squared distance `d2` may hold a
    /// nearer triangle.
    #[inline(always)]
    fn admits(&self, d2: f32) -> bool {
        d2 <= self.prune
    }
}

/// Triangles arranged for nearest-point queries.
#[derive(Clone, Debug)]
pub struct Bvh {
    /// Unique per built tree (clones share it): what a [`Scratch`]'s
    /// remembered path belongs to.
    id: u64,
    /// Nodes, the root first (empty when the root is a leaf).
    nodes: Vec<Wide>,
    /// Triangle count when the root is a leaf (no nodes).
    root_count: u32,
    /// The box of all (scaled) triangles.
    bounds: Aabb,
    /// Largest absolute coordinate of any stored (scaled) triangle.
    extent: f64,
    /// The power of two the stored triangles and the queries are
    /// multiplied by (see the module docs), and its inverse.
    scale: f64,
    unscale: f64,
    /// Triangles in leaf order, multiplied by `scale`.
    tris: Vec<Tri>,
    /// Original index of each entry of `tris`.
    ids: Vec<u32>,
}

/// What a thread keeps between queries: the traversal stack, so queries do
/// not allocate, and the last query's [`Path`].
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    stack: Vec<(u32, f32)>,
    path: Path,
    /// Nodes read by the queries made with this scratch: the work done,
    /// which tests compare across units.
    visits: u64,
}

#[cfg(test)]
impl Scratch {
    /// Nodes read so far by queries made with this scratch.
    pub fn visits(&self) -> u64 {
        self.visits
    }
}

/// `2^k` for `k` in the normal range of `f64`.
fn power_of_two(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// The power of two that brings `extent` (finite, ≥ 0) into `[1/2, 1)`;
/// 1 for zero.
fn normalizing_scale(extent: f64) -> f64 {
    if extent.is_normal() {
        // extent is in [2^e, 2^(e + 1)): the biased exponent field.
        let e = ((extent.to_bits() >> 52) & 0x7ff) as i32 - 1023;
        power_of_two(-(e + 1))
    } else {
        1.0
    }
}

/// How a tree is built: the answers are the same, the leaf order (where
/// `metrics::Surface` samples) and the time differ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Build {
    /// Binned SAH splits (`build`): the tightest tree, for surfaces
    /// queried many times (the reference every candidate is measured
    /// against). Its leaf order is part of the encoder's output.
    #[default]
    Sah,
    /// Splits along a Morton curve (`morton`): a tenth of the time, a
    /// looser tree, for surfaces queried a few times (the check of the
    /// file the encoder returns; effort `fast`).
    Morton,
}

impl Build {
    /// The cheaper build for a tree over `triangles` that answers about
    /// `queries` nearest-point queries: the Morton build saves about
    /// 0.5 µs of work per triangle and costs about as much per query (its
    /// boxes overlap more), so it pays only where the triangles far
    /// outnumber the queries. Measured: the check and `fast`'s reference
    /// on bunny (69,451 triangles, about 64,000 queries) ran 30 ms slower
    /// with it; on bunny-1m (1.1 M triangles) it saved 0.5 s.
    pub fn for_queries(triangles: usize, queries: u64) -> Build {
        if triangles as u64 > 4 * queries {
            Build::Morton
        } else {
            Build::Sah
        }
    }
}

impl Bvh {
    /// Builds the tree. Every coordinate must be finite (the caller
    /// checks); an empty list gives a tree that finds nothing.
    pub fn new(tris: &[Tri]) -> Bvh {
        Bvh::with_build(tris, Build::Sah)
    }

    /// [`Bvh::new`] with the given construction.
    pub fn with_build(tris: &[Tri], how: Build) -> Bvh {
        let extent = largest_coordinate(tris);
        let scale = normalizing_scale(extent);
        // Exact (a power of two), short of the underflow the module docs
        // allow for.
        let scaled: Vec<Tri>;
        let tris = if scale == 1.0 {
            tris
        } else {
            scaled = tris
                .iter()
                .map(|t| t.map(|v| v.map(|c| (c as f64 * scale) as f32)))
                .collect();
            &scaled
        };
        let (nodes, ids) = match how {
            Build::Sah => build::build(tris),
            Build::Morton => morton::build(tris),
        };
        static TREES: AtomicU64 = AtomicU64::new(1);
        Bvh {
            id: TREES.fetch_add(1, Ordering::Relaxed),
            nodes: widen(&nodes),
            root_count: nodes.first().map_or(0, |r| r.count),
            bounds: nodes.first().map_or(Aabb::EMPTY, |r| r.bounds),
            extent: largest_coordinate(tris),
            scale,
            unscale: 1.0 / scale,
            tris: ids.iter().map(|&i| tris[i as usize]).collect(),
            ids,
        }
    }

    /// Original triangle indices in leaf order (a spatially coherent
    /// order).
    pub fn order(&self) -> &[u32] {
        &self.ids
    }

    /// The triangle nearest to `p`, if any. `hint`, the [`Nearest::slot`]
    /// of an earlier answer likely to be near (such as the previous
    /// query's), only speeds the search up: its triangle's distance is the
    /// starting bound, and a nearer triangle still wins. `scratch` carries
    /// the search path from one query to the next (any scratch works with
    /// any tree). Ties go to the triangle met first, which may depend on
    /// the earlier queries: the distance, not the triangle, is the
    /// meaningful output.
    pub fn nearest(
        &self,
        p: [f64; 3],
        hint: Option<u32>,
        scratch: &mut Scratch,
    ) -> Option<Nearest> {
        // Into the tree's units and back: exact (powers of two; `f64`
        // holds any `f32` coordinate times any such scale).
        let p = p.map(|c| c * self.scale);
        self.nearest_scaled(p, hint, scratch).map(|n| Nearest {
            distance2: n.distance2 * (self.unscale * self.unscale),
            ..n
        })
    }

    /// The answer to a far query (see the module docs): the hint's
    /// triangle, or the first; `None` for a query near enough to search.
    fn far(&self, p: [f64; 3], hint: Option<u32>) -> Option<Nearest> {
        let (lo, hi) = (self.bounds.min, self.bounds.max);
        let (mut gap2, mut diagonal2) = (0.0f64, 0.0f64);
        for k in 0..3 {
            let (lo, hi) = (lo[k] as f64, hi[k] as f64);
            let g = (lo - p[k]).max(p[k] - hi).max(0.0);
            gap2 += g * g;
            diagonal2 += (hi - lo) * (hi - lo);
        }
        let far = gap2 > diagonal2 * (1u64 << 60) as f64;
        if !far || self.tris.is_empty() {
            return None;
        }
        let slot = hint
            .filter(|&h| (h as usize) < self.tris.len())
            .unwrap_or(0);
        Some(Nearest {
            distance2: triangle_distance2(p, &self.tris[slot as usize]),
            triangle: self.ids[slot as usize],
            slot,
        })
    }

    /// [`Self::nearest`] for a query already in the tree's units.
    fn nearest_scaled(
        &self,
        p: [f64; 3],
        hint: Option<u32>,
        scratch: &mut Scratch,
    ) -> Option<Nearest> {
        if let Some(far) = self.far(p, hint) {
            return Some(far);
        }
        // Covers the rounding of `p` to `f32` and of the triangle distances
        // (see `Bound`).
        let slack = self.extent.max(p[0].abs()).max(p[1].abs()).max(p[2].abs())
            * (1.0 / (1u64 << 20) as f64);
        let mut found = u32::MAX;
        let mut bound = Bound::new(f64::INFINITY, slack);
        if let Some(h) = hint.filter(|&h| (h as usize) < self.tris.len()) {
            found = h;
            bound.set(triangle_distance2(p, &self.tris[h as usize]));
        }
        // The hint's triangle, already measured, is skipped in its leaf.
        let skip = found as usize;
        let mut test = |first: u32, count: u8, bound: &mut Bound| {
            let first = first as usize;
            for (s, t) in self.tris[first..first + count as usize].iter().enumerate() {
                if first + s == skip {
                    continue;
                }
                let d = triangle_distance2(p, t);
                if d < bound.best {
                    bound.set(d);
                    found = (first + s) as u32;
                }
            }
        };
        if self.nodes.is_empty() {
            test(0, self.root_count as u8, &mut bound);
            return (found != u32::MAX).then(|| Nearest {
                distance2: bound.best,
                triangle: self.ids[found as usize],
                slot: found,
            });
        }
        let q = p.map(|c| c as f32);
        let Scratch {
            stack,
            path,
            visits,
        } = scratch;
        let mut level = path.entry(self, p, bound.best, slack);
        let mut primary = true;
        stack.clear();
        // The node to search next without a trip through the stack: the
        // nearest child of the last one, when it has one.
        let mut next = Some((path.nodes[level], 0.0f32));
        loop {
            let i = match next.take() {
                Some((i, _)) => i,
                None => match stack.pop() {
                    Some((i, d2)) if bound.admits(d2) => i,
                    Some(_) => continue,
                    None => break,
                },
            };
            *visits += 1;
            let node = &self.nodes[i as usize];
            let d = node.distance2(q);
            let mut admitted = 0u32;
            for (j, &dj) in d.iter().enumerate() {
                admitted |= (bound.admits(dj) as u32) << j;
            }
            admitted &= node.lanes;
            let single = admitted != 0 && admitted & (admitted - 1) == 0;
            if primary {
                // Still on the way down from the entry: remember the path
                // while it has one inner child to follow.
                let j = admitted.trailing_zeros() as usize;
                if single && node.leaf[j] == 0 {
                    path.descend(level, node.child[j], node.clearance(&d, j), slack);
                    level += 1;
                } else {
                    path.stop(level);
                    primary = false;
                }
            }
            if admitted == 0 {
                continue;
            }
            if single {
                // One child: the common case on the way down.
                let j = admitted.trailing_zeros() as usize;
                if node.leaf[j] > 0 {
                    test(node.child[j], node.leaf[j], &mut bound);
                } else {
                    next = Some((node.child[j], d[j]));
                }
                continue;
            }
            // Several. Leaves are searched at once, nearest first (ties:
            // lane order), which may shrink the bound before the farther
            // ones and the nodes are judged.
            let mut m = admitted & node.leaves;
            while m != 0 {
                let mut j = m.trailing_zeros() as usize;
                let mut rest = m & (m - 1);
                while rest != 0 {
                    let k = rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    if d[k] < d[j] {
                        j = k;
                    }
                }
                m &= !(1 << j);
                if bound.admits(d[j]) {
                    test(node.child[j], node.leaf[j], &mut bound);
                }
            }
            // The nearest node is searched next, the others wait on the
            // stack.
            let mut m = admitted & !node.leaves;
            while m != 0 {
                let j = m.trailing_zeros() as usize;
                m &= m - 1;
                if !bound.admits(d[j]) {
                    continue;
                }
                let c = (node.child[j], d[j]);
                match next {
                    Some(n) if n.1 <= c.1 => stack.push(c),
                    _ => {
                        if let Some(n) = next.replace(c) {
                            stack.push(n);
                        }
                    }
                }
            }
        }
        (found != u32::MAX).then(|| Nearest {
            distance2: bound.best,
            triangle: self.ids[found as usize],
            slot: found,
        })
    }
}

/// Where the last queries went down the tree, so that the next one can
/// skip the levels that cannot matter to it.
///
/// `nodes[0]` is the root and `nodes[i + 1]` the only child that a query
/// entered from `nodes[i]`; `clear[i]` is a lower bound, minus `shift`, on
/// the distance from `anchor` (the last query point) to the boxes of
/// `nodes[i]`'s other children. Moving the query by `δ` lowers each such
/// distance by at most `δ`, so each move adds `δ` to `shift` instead of
/// touching every level. A query whose search radius (`√best` plus the
/// rounding slack) is below the distance to every sibling box above level
/// `k` can find nothing nearer outside `nodes[k]`, and starts there: box
/// containment makes the skip exact.
#[derive(Clone, Debug, Default)]
struct Path {
    /// Identity of the tree the path belongs to (0: none).
    tree: u64,
    anchor: [f64; 3],
    shift: f64,
    nodes: Vec<u32>,
    clear: Vec<f64>,
}

impl Path {
    /// Moves the anchor to `p` and returns the deepest level at which a
    /// query with bound `best` may start.
    #[inline]
    fn entry(&mut self, tree: &Bvh, p: [f64; 3], best: f64, slack: f64) -> usize {
        if self.tree != tree.id {
            *self = Path {
                tree: tree.id,
                anchor: p,
                nodes: vec![0],
                ..Path::default()
            };
        }
        let a = self.anchor;
        let moved = ((p[0] - a[0]).powi(2) + (p[1] - a[1]).powi(2) + (p[2] - a[2]).powi(2)).sqrt();
        self.anchor = p;
        self.shift += moved * (1.0 + 1.0 / (1u64 << 40) as f64);
        // The radius within which a nearer triangle could lie, rounded
        // up; levels whose siblings all lie beyond it are skipped.
        let reach = (best.sqrt() + slack) * (1.0 + 1.0 / (1u64 << 20) as f64)
            + self.shift * (1.0 + 1.0 / (1u64 << 40) as f64);
        let level = self.clear.iter().take_while(|&&c| c >= reach).count();
        if level == 0 {
            // Everything below is measured afresh from here.
            self.shift = 0.0;
        }
        level
    }

    /// Records that the query went from `nodes[level]` into `child` only,
    /// its other children lying at computed `f32` squared distance
    /// `clearance` or more from the query.
    #[inline]
    fn descend(&mut self, level: usize, child: u32, clearance: f32, slack: f64) {
        // A lower bound on the true distance from the query point: undo
        // the `f32` rounding of the box distance (see `Bound`; an overflow
        // to infinity still means at least `f32::MAX`) and of the query
        // point (under `slack`).
        let c = ((clearance.min(f32::MAX) as f64) * (1.0 - 1.0 / (1u64 << 19) as f64) - 1e-40)
            .max(0.0)
            .sqrt()
            - slack;
        self.clear.truncate(level);
        self.clear.push(c + self.shift);
        self.nodes.truncate(level + 1);
        self.nodes.push(child);
    }

    /// Records that the query left the single path at `nodes[level]`.
    #[inline]
    fn stop(&mut self, level: usize) {
        self.clear.truncate(level);
        self.nodes.truncate(level + 1);
    }
}

/// The largest absolute coordinate of any triangle (0 for none).
fn largest_coordinate(tris: &[Tri]) -> f64 {
    tris.iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, &c| m.max((c as f64).abs()))
}

/// The search layout of a built binary tree: each node takes up to `W`
/// of its descendants as children, opening the one with the largest
/// surface (the likeliest to be entered) first; leaves and the leaf order
/// stay as built; nodes in depth-first order. Empty when the root is a
/// leaf.
fn widen(nodes: &[Node]) -> Vec<Wide> {
    let mut out: Vec<Wide> = Vec::with_capacity(nodes.len() / 3 + 1);
    if nodes.first().is_none_or(|r| r.count > 0) {
        return out;
    }
    let is_inner = |b: usize| nodes[b].count == 0;
    // (binary node, (wide parent, lane) whose child index to fill in).
    let mut todo: Vec<(usize, Option<(usize, usize)>)> = vec![(0, None)];
    while let Some((b, patch)) = todo.pop() {
        let me = out.len();
        if let Some((parent, lane)) = patch {
            out[parent].child[lane] = me as u32;
        }
        let mut kids = [0usize; W];
        kids[0] = b + 1;
        kids[1] = nodes[b].index as usize;
        let mut len = 2;
        while len < W {
            let open = (0..len).filter(|&j| is_inner(kids[j])).max_by(|&x, &y| {
                let (ax, ay) = (
                    nodes[kids[x]].bounds.half_area(),
                    nodes[kids[y]].bounds.half_area(),
                );
                // Ties: the first lane (max_by keeps the last).
                ax.total_cmp(&ay).then(y.cmp(&x))
            });
            let Some(j) = open else { break };
            let k = kids[j];
            // Children stay in spatial (left-to-right) order.
            kids.copy_within(j + 1..len, j + 2);
            kids[j] = k + 1;
            kids[j + 1] = nodes[k].index as usize;
            len += 1;
        }
        let mut node = Wide {
            lo: [[f32::INFINITY; W]; 3],
            hi: [[f32::NEG_INFINITY; W]; 3],
            child: [0; W],
            leaf: [0; W],
            lanes: (1u32 << len) - 1,
            leaves: 0,
        };
        for (j, &k) in kids[..len].iter().enumerate() {
            let c = &nodes[k];
            for a in 0..3 {
                node.lo[a][j] = c.bounds.min[a];
                node.hi[a][j] = c.bounds.max[a];
            }
            if c.count > 0 {
                node.child[j] = c.index;
                node.leaf[j] = c.count as u8;
                node.leaves |= 1 << j;
            }
        }
        out.push(node);
        // First child popped first: depth-first order.
        for (j, &k) in kids[..len].iter().enumerate().rev() {
            if is_inner(k) {
                todo.push((k, Some((me, j))));
            }
        }
    }
    out
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
                let brute = brute(&tris, p);
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

    /// A bumpy height field of `2(k − 1)²` triangles over the unit square.
    fn terrain(k: usize, phase: f32) -> Vec<Tri> {
        let at = |i: usize, j: usize| {
            let (x, y) = (i as f32 / (k - 1) as f32, j as f32 / (k - 1) as f32);
            [x, y, 0.05 * (9.0 * x + phase).sin() * (7.0 * y).cos()]
        };
        let mut tris = Vec::new();
        for i in 0..k - 1 {
            for j in 0..k - 1 {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        tris
    }

    fn brute(tris: &[Tri], p: [f64; 3]) -> f64 {
        tris.iter()
            .map(|t| triangle_distance2(p, t))
            .fold(f64::INFINITY, f64::min)
    }

    /// Queries that walk along the surface, as samples do, reuse the
    /// remembered path; far jumps, points exactly on corners and one
    /// scratch shared by two trees must not change any answer.
    #[test]
    fn warm_started_walks_equal_brute_force() {
        let mut r = rng(0x0dd_ba11_cafe_f00d);
        let trees = [terrain(60, 0.0), terrain(45, 1.0)];
        let bvhs = trees.each_ref().map(|t| Bvh::new(t));
        let mut scratch = Scratch::default();
        let mut hints = [None, None];
        let mut p = [0.5f64, 0.5, 0.0];
        for step in 0..3000 {
            let which = (step / 250) % 2;
            let tris = &trees[which];
            if step % 500 == 0 {
                // A far jump, outside the surface's box.
                p = [2.0 * r() as f64 - 0.5, 2.0 * r() as f64 - 0.5, r() as f64];
            } else if step % 37 == 0 {
                // Exactly on a corner: distance zero.
                let t = &tris[(r() * tris.len() as f32) as usize % tris.len()];
                p = t[step % 3].map(|c| c as f64);
            } else {
                for c in &mut p[..2] {
                    *c = (*c + 0.01 * (r() as f64 - 0.5)).clamp(-0.1, 1.1);
                }
                p[2] = 0.02 * (r() as f64 - 0.5);
            }
            let hit = bvhs[which].nearest(p, hints[which], &mut scratch).unwrap();
            assert_eq!(hit.distance2, brute(tris, p), "step {step}");
            hints[which] = Some(hit.slot);
        }
    }

    /// A query 2³⁰ diagonals or more away is answered without a search,
    /// within a relative 2⁻³⁰ of the brute-force distance; nearer ones
    /// are still searched and exact.
    #[test]
    fn far_queries_are_answered_without_a_search() {
        let tris = terrain(40, 0.5);
        let bvh = Bvh::new(&tris);
        let mut scratch = Scratch::default();
        for (p, far) in [
            ([1e30, -3e29, 2e30], true),
            ([0.5, 0.5, -1e12], true),
            ([0.5, 0.5, 1e8], false),
            ([3.0, 0.2, 0.1], false),
        ] {
            let before = scratch.visits();
            let hit = bvh.nearest(p, None, &mut scratch).unwrap();
            let exact = brute(&tris, p);
            if far {
                assert_eq!(scratch.visits(), before, "{p:?}");
                let rel = (hit.distance2.sqrt() - exact.sqrt()) / exact.sqrt();
                assert!((0.0..1e-9).contains(&rel), "{p:?}: {rel}");
            } else {
                assert!(scratch.visits() > before, "{p:?}");
                assert_eq!(hit.distance2, exact, "{p:?}");
            }
        }
        assert!(Bvh::new(&[])
            .nearest([1e30; 3], None, &mut scratch)
            .is_none());
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
