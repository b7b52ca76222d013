//! Line queries on the nearest-point tree ([`Bvh`]): the crossing of a
//! line with the triangles nearest a point along it, within a reach (the
//! displaced-subdivision encoder's "move along the normal to the input").
//!
//! Sources: Möller & Trumbore (1997) for each triangle (`ray::crossing`,
//! shared with `ray::Lines`); Kay & Kajiya's slab test (1986) for each of
//! a node's eight boxes, children visited nearest first.
//!
//! Why on this tree and not `ray::Lines`' own: the encoder already has
//! this tree over the input (the reference every candidate is measured
//! against), so the line queries need no second tree (on a million
//! triangles, 110 MB and a second build); its eight-wide SAH nodes also
//! read fewer boxes per query than a binary median split.
//!
//! Invariants: the answer is the crossing of smallest |t| within the
//! reach over all triangles, ties to positive t — the same total order as
//! `Lines::nearest_crossing`, so the same `f64`, bit for bit: the tree
//! holds the triangles scaled by a power of two and the query is scaled
//! the same way, which Möller–Trumbore's products and quotients carry
//! exactly (`t` scales as a length and is scaled back). The box tests
//! only prune, and are widened by a relative 2⁻⁴⁰ so that rounding never
//! prunes a box that holds a crossing within the bound.

use super::Bvh;
use crate::metrics::ray::crossing;

/// Relative widening of the slab intervals and of the bound (see the
/// module docs).
const WIDEN: f64 = 1.0 / (1u64 << 40) as f64;

impl Bvh {
    /// The `t` of smallest magnitude in `[−reach, reach]` where the line
    /// `p + t·d` crosses a triangle, if any; with `facing`, only triangles
    /// whose normal (their corners' right-hand turn) points along `d`.
    /// `stack` is scratch space (any contents; reused to avoid an
    /// allocation per query).
    pub fn nearest_crossing(
        &self,
        p: [f64; 3],
        d: [f64; 3],
        reach: f64,
        facing: bool,
        stack: &mut Vec<(u32, f64)>,
    ) -> Option<f64> {
        let p = p.map(|c| c * self.scale);
        let reach = reach * self.scale;
        let mut best: Option<f64> = None;
        let test = |first: usize, count: usize, best: &mut Option<f64>| {
            for t in &self.tris[first..first + count] {
                let t = t.map(|v| v.map(f64::from));
                let Some(s) = crossing(p, d, &t, facing) else {
                    continue;
                };
                let better = match *best {
                    None => s.abs() <= reach,
                    Some(b) => s.abs() < b.abs() || (s.abs() == b.abs() && s > b),
                };
                if better {
                    *best = Some(s);
                }
            }
        };
        if self.nodes.is_empty() {
            test(0, self.root_count as usize, &mut best);
            return best.map(|t| t * self.unscale);
        }
        let inv = d.map(|c| 1.0 / c);
        stack.clear();
        stack.push((0, 0.0));
        while let Some((i, near)) = stack.pop() {
            let bound = best.map_or(reach, f64::abs) * (1.0 + WIDEN);
            if near > bound {
                continue;
            }
            let node = &self.nodes[i as usize];
            // Each child's distance along the line from `p` to its box
            // (within the bound), or ∞.
            let mut gap = [f64::INFINITY; super::W];
            let mut m = node.lanes;
            while m != 0 {
                let j = m.trailing_zeros() as usize;
                m &= m - 1;
                let (mut t0, mut t1) = (-bound, bound);
                let mut inside = true;
                for k in 0..3 {
                    let (lo, hi) = (f64::from(node.lo[k][j]), f64::from(node.hi[k][j]));
                    if d[k] == 0.0 {
                        if p[k] < lo || p[k] > hi {
                            inside = false;
                            break;
                        }
                        continue;
                    }
                    let (a, b) = ((lo - p[k]) * inv[k], (hi - p[k]) * inv[k]);
                    let (a, b) = (a.min(b), a.max(b));
                    let w = WIDEN * a.abs().max(b.abs());
                    t0 = t0.max(a - w);
                    t1 = t1.min(b + w);
                    if t0 > t1 {
                        inside = false;
                        break;
                    }
                }
                if inside {
                    gap[j] = t0.max(-t1).max(0.0);
                }
            }
            // Leaves now, nearest first; inner nodes onto the stack,
            // farthest first so that the nearest is searched next.
            let mut inner: [(u32, f64); super::W] = [(0, 0.0); super::W];
            let mut n = 0;
            let mut open = node.lanes;
            while open != 0 {
                let mut j = open.trailing_zeros() as usize;
                let mut rest = open & (open - 1);
                while rest != 0 {
                    let k = rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    if gap[k] < gap[j] {
                        j = k;
                    }
                }
                open &= !(1 << j);
                if gap[j] == f64::INFINITY {
                    break;
                }
                if node.leaf[j] > 0 {
                    let bound = best.map_or(reach, f64::abs) * (1.0 + WIDEN);
                    if gap[j] <= bound {
                        test(node.child[j] as usize, node.leaf[j] as usize, &mut best);
                    }
                } else {
                    inner[n] = (node.child[j], gap[j]);
                    n += 1;
                }
            }
            stack.extend(inner[..n].iter().rev());
        }
        best.map(|t| t * self.unscale)
    }
}
