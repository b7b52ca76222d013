//! Prediction rules of attribute values, in integer arithmetic: what
//! each side computes from the decoded positions and the values already
//! decoded, before the residual.
//!
//! Sources (Draco's prediction schemes, `compression/attributes/
//! prediction_schemes/`, read for the rules, written anew):
//! * texture coordinates: the constrained multi-parallelogram below
//!   first, and where no parallelogram is complete,
//!   `MeshPredictionSchemeTexCoordsPortable` — the new corner's position
//!   projected onto the opposite edge in 3D gives a point along the edge
//!   and a distance from it, which the edge's two decoded texture
//!   coordinates turn into a prediction, on one side of the edge or the
//!   other (an orientation bit, as Draco's). Ours averages the
//!   predictions of every triangle of the value's corners whose two
//!   other corners are decoded, where Draco takes the first. Measured
//!   (BENCHMARKS.md, "Attributes in the lossless mode"): with the
//!   positions' degree-first traversal most values have two or more
//!   complete parallelograms, and their average beats the projection
//!   (spot's UVs 3,072 bytes against 3,376 with the projection first,
//!   3,572 with Draco's first triangle only; a cylindrically mapped
//!   bunny 17,808 against 29,372), which helps where a value starts a
//!   chart's second row;
//! * normals: `MeshPredictionSchemeGeometricNormal` — the area-weighted
//!   normal of the value's triangles (module `octahedral`);
//! * colours and generic values: the (constrained) multi-parallelogram
//!   of `MeshPredictionSchemeConstrainedMultiParallelogram`, taken only
//!   across edges the stream is continuous over (a parallelogram across
//!   a seam would mix two charts), averaged over every complete one.
//!
//! Invariants: a prediction only reads values of corners whose group is
//! decoded (`group != NONE`) and positions (all decoded before any
//! attribute); every predicted component lies in `0..modulus`; no
//! arithmetic overflows for grid coordinates below `2^24` and values
//! below `2^24` (products are taken in `i128`).

use crate::prelude::*;

use super::frame::{next, prev, Frame, NONE};
use super::spec::{Spec, FLAG_NEGATED};

/// A prediction and its residual class (`residual::CLASSES`).
pub(crate) enum Prediction {
    /// One value.
    Fixed { class: usize, value: [u64; 4] },
    /// Two values, the texture coordinates on either side of the edge:
    /// an orientation bit says which (0: the triangle keeps its
    /// orientation in texture space).
    Oriented { kept: [u64; 4], mirrored: [u64; 4] },
}

/// `floor(n / d + 1/2)` for `d > 0`: the nearest integer, halves up.
fn div_round(n: i128, d: i128) -> i128 {
    (2 * n + d).div_euclid(2 * d)
}

/// `floor(sqrt(x))`, exactly (binary search on the result, at most 64
/// steps: the arithmetic every decoder repeats bit for bit).
fn isqrt(x: u128) -> u128 {
    let (mut lo, mut hi) = (0u128, 1u128 << 64);
    // Invariant: lo² ≤ x < hi².
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if mid * mid <= x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// What a prediction reads: the mesh, the stream's parameters and what
/// the stream has decoded so far.
pub(crate) struct Known<'a> {
    pub frame: &'a Frame<'a>,
    pub spec: &'a Spec,
    /// Values are in `0..modulus` per component.
    pub modulus: u64,
    /// Per corner: the stream is continuous across the edge facing it.
    pub continuous: &'a [bool],
    /// Per corner: its group, `NONE` until decoded.
    pub group: &'a [u32],
    /// The groups' values, `spec.coded_dims()` per group.
    pub values: &'a [u64],
}

impl Known<'_> {
    /// The value of group `g`.
    fn value(&self, g: u32) -> &[u64] {
        let d = self.spec.coded_dims();
        &self.values[g as usize * d..(g as usize + 1) * d]
    }

    /// Groups decoded so far.
    fn count(&self) -> u32 {
        (self.values.len() / self.spec.coded_dims()) as u32
    }

    /// The prediction of a new value whose corners are `corners`
    /// (increasing), by the stream's rule: for normals the geometric
    /// normal; for the others the parallelograms across continuous
    /// edges, else (two-component texture coordinates) the portable
    /// projection, else the fallback.
    pub(crate) fn predict(&self, corners: &[u32]) -> Prediction {
        if self.spec.is_normal() {
            return Prediction::Fixed {
                class: 0,
                value: self.normal_prediction(corners),
            };
        }
        if let Some(value) = self.parallelogram(corners) {
            return Prediction::Fixed { class: 0, value };
        }
        if self.spec.dims == 2 && self.spec.is_texcoord() {
            if let Some(p) = self.portable(corners) {
                return p;
            }
        }
        Prediction::Fixed {
            class: 1,
            value: self.neighbour(corners),
        }
    }

    /// The grid point of corner `c`'s vertex.
    fn point(&self, c: u32) -> [i64; 3] {
        let v = self.frame.table.vertices()[c as usize];
        self.frame.grid[v.idx()]
    }

    /// The decoded value of corner `c`'s group, if it has one.
    fn value_at(&self, c: u32) -> Option<&[u64]> {
        let g = *self.group.get(c as usize)?;
        (g != NONE).then(|| self.value(g))
    }

    /// Texture coordinates by projection (Draco's portable rule, module
    /// header), averaged over the triangles that allow it, for both
    /// orientations; `None` when no triangle has its two other corners
    /// decoded.
    fn portable(&self, corners: &[u32]) -> Option<Prediction> {
        let top = self.modulus as i128 - 1;
        let (mut kept, mut mirrored, mut n) = ([0i128; 2], [0i128; 2], 0i128);
        for &c in corners {
            let (a, b) = (next(c), prev(c));
            let (Some(ua), Some(ub)) = (self.value_at(a), self.value_at(b)) else {
                continue;
            };
            let (pa, pb, pc) = (self.point(a), self.point(b), self.point(c));
            let e: [i128; 3] = core::array::from_fn(|k| i128::from(pb[k] - pa[k]));
            let f: [i128; 3] = core::array::from_fn(|k| i128::from(pc[k] - pa[k]));
            let ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
            let ua = [ua[0] as i128, ua[1] as i128];
            let ub = [ub[0] as i128, ub[1] as i128];
            n += 1;
            if ee == 0 {
                // Both edge ends at one grid point: nothing to project on.
                for k in 0..2 {
                    kept[k] += ua[k];
                    mirrored[k] += ua[k];
                }
                continue;
            }
            let ef = e[0] * f[0] + e[1] * f[1] + e[2] * f[2];
            let cross = [
                e[1] * f[2] - e[2] * f[1],
                e[2] * f[0] - e[0] * f[2],
                e[0] * f[1] - e[1] * f[0],
            ];
            let h = isqrt(cross.iter().map(|x| (x * x) as u128).sum()) as i128;
            let d = [ub[0] - ua[0], ub[1] - ua[1]];
            // The foot of the perpendicular, ua + d·ef/ee, and the
            // distance from it, |cross|/ee along d turned a quarter
            // (counter-clockwise for a triangle that keeps its
            // orientation: corner c lies left of the edge a → b).
            let turned = [-d[1], d[0]];
            for k in 0..2 {
                let foot = ua[k] * ee + d[k] * ef;
                kept[k] += div_round(foot + h * turned[k], ee).clamp(0, top);
                mirrored[k] += div_round(foot - h * turned[k], ee).clamp(0, top);
            }
        }
        if n == 0 {
            return None;
        }
        let avg = |s: [i128; 2]| {
            let mut out = [0u64; 4];
            for k in 0..2 {
                out[k] = div_round(s[k], n).clamp(0, top) as u64;
            }
            out
        };
        Some(Prediction::Oriented {
            kept: avg(kept),
            mirrored: avg(mirrored),
        })
    }

    /// The average of the complete parallelograms across edges the
    /// stream is continuous over, or `None` without one.
    fn parallelogram(&self, corners: &[u32]) -> Option<[u64; 4]> {
        let dims = self.spec.coded_dims();
        let (mut sum, mut n) = ([0i128; 4], 0i128);
        for &c in corners {
            if !self.continuous[c as usize] {
                continue;
            }
            let o = self.frame.table.opposites()[c as usize].0;
            let (Some(a), Some(b), Some(x)) = (
                self.value_at(next(c)),
                self.value_at(prev(c)),
                self.value_at(o),
            ) else {
                continue;
            };
            for k in 0..dims {
                sum[k] += a[k] as i128 + b[k] as i128 - x[k] as i128;
            }
            n += 1;
        }
        (n > 0).then(|| {
            let top = self.modulus as i128 - 1;
            core::array::from_fn(|k| div_round(sum[k], n).clamp(0, top) as u64)
        })
    }

    /// The fallback: the average of the decoded values at the other two
    /// corners of the value's triangles (the first triangle that has
    /// one), else the stream's previous value, else the middle of the
    /// range.
    fn neighbour(&self, corners: &[u32]) -> [u64; 4] {
        let dims = self.spec.coded_dims();
        for &c in corners {
            let known: Vec<&[u64]> = [next(c), prev(c)]
                .iter()
                .filter_map(|&x| self.value_at(x))
                .collect();
            if !known.is_empty() {
                let n = known.len() as i128;
                return core::array::from_fn(|k| {
                    if k >= dims {
                        return 0;
                    }
                    let s: i128 = known.iter().map(|v| v[k] as i128).sum();
                    div_round(s, n) as u64
                });
            }
        }
        match self.count() {
            0 => [self.modulus / 2; 4],
            g => {
                let last = self.value(g - 1);
                core::array::from_fn(|k| last.get(k).copied().unwrap_or(0))
            }
        }
    }

    /// The octahedral coordinates (shifted into `0..2H+1`) of the
    /// area-weighted normal of the value's triangles, negated when the
    /// stream says its normals point the other way.
    fn normal_prediction(&self, corners: &[u32]) -> [u64; 4] {
        use super::octahedral::{face_normal, half, of_vector};
        let mut sum = [0i128; 3];
        for &c in corners {
            let n = face_normal(self.point(c), self.point(next(c)), self.point(prev(c)));
            for k in 0..3 {
                sum[k] += n[k];
            }
        }
        if self.spec.flags & FLAG_NEGATED != 0 {
            sum = sum.map(|x| -x);
        }
        let q = of_vector(sum, self.spec.bits);
        let h = half(self.spec.bits);
        [(q[0] + h) as u64, (q[1] + h) as u64, 0, 0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isqrt_is_exact() {
        for x in [
            0u128,
            1,
            2,
            3,
            4,
            15,
            16,
            17,
            1 << 100,
            (1 << 100) - 1,
            u64::MAX as u128,
        ] {
            let r = isqrt(x);
            assert!(r * r <= x && (r + 1) * (r + 1) > x, "{x}");
        }
    }

    #[test]
    fn rounding_is_to_nearest_halves_up() {
        assert_eq!(div_round(5, 2), 3);
        assert_eq!(div_round(-5, 2), -2);
        assert_eq!(div_round(-7, 3), -2);
        assert_eq!(div_round(7, 3), 2);
    }
}
