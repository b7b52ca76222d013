//! Predictions of a vertex's quantized position from vertices decoded
//! before it: the parallelogram rule of Touma & Gotsman, "Triangle mesh
//! compression" (Graphics Interface 1998), and averages of several
//! parallelograms (Cohen-Or, Cohen & Irony, "Multi-way geometry encoding",
//! 2002; Isenburg & Alliez, "Compressing polygon mesh geometry with
//! parallelogram prediction", IEEE Visualization 2002).
//!
//! ```text
//!          opposite                 The new vertex closes the triangle
//!            /\                     (a, b, new) across the edge ab from
//!           /  \                    the decoded triangle (a, b, opposite):
//!          /    \                   predict  a + b − opposite,
//!        a +----+ b                 which completes the parallelogram.
//!          \    /
//!           \  /
//!            \/
//!        new ≈ a + b − opposite
//! ```
//!
//! Vertices are numbered in decoding order; the prediction of vertex `k`
//! may only name vertices `< k`. For a decoder the predictions are hostile
//! data (they come from decoded connectivity): [`Prediction::check`]
//! rejects a reference to a vertex not yet decoded, or a parallelogram
//! range outside the list, with [`Error::Format`]; nothing here can panic
//! on predictions that passed it.
//!
//! All arithmetic is on grid integers in `i64` (no overflow: at most
//! [`MAX_SELECTABLE`] parallelograms of 24-bit coordinates are summed),
//! with the result clamped into the grid, so every platform predicts the
//! same point. Must match the encoder exactly: both sides call
//! [`Prediction::predict`] and [`average`].

use crate::prelude::*;

use super::quantize::max_value;
use crate::{Error, FormatError, Malformed};

/// A [`Prediction::Multi`] averages a subset of at most this many of its
/// parallelograms (the first ones of its list); the encoder picks the
/// subset and codes it. Part of the bitstream definition.
pub const MAX_SELECTABLE: usize = 4;

/// How vertex `k` is predicted (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prediction {
    /// No neighbour is known (the first vertex of a component): predict
    /// the centre of the grid, `2^(bits−1)` on every axis.
    None,
    /// Predict the position of an earlier vertex (e.g. a neighbour when no
    /// parallelogram is available).
    Delta {
        /// The earlier vertex.
        from: u32,
    },
    /// Complete the parallelogram `a + b − opposite`.
    Parallelogram {
        /// One end of the shared edge.
        a: u32,
        /// The other end of the shared edge.
        b: u32,
        /// The vertex across the shared edge from the new one.
        opposite: u32,
    },
    /// Several parallelograms: entries `first .. first + count` of
    /// [`Predictions::parallelograms`]. The prediction is the average of a
    /// non-empty subset of the first [`MAX_SELECTABLE`] of them, which the
    /// encoder chooses and codes (see `geometry::lossless`).
    Multi {
        /// First entry in the parallelogram list.
        first: u32,
        /// Number of entries, ≥ 1.
        count: u32,
    },
}

/// The predictions of every vertex, in decoding order, and the shared list
/// of parallelograms `[a, b, opposite]` that [`Prediction::Multi`] entries
/// point into.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Predictions {
    /// Prediction of vertex `k`, for every `k`.
    pub vertices: Vec<Prediction>,
    /// Parallelograms of the `Multi` predictions, each `[a, b, opposite]`.
    pub parallelograms: Vec<[u32; 3]>,
}

impl Predictions {
    /// Number of vertices.
    #[inline]
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// True if there are no vertices.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }
}

/// The error for a prediction that refers to something not available.
fn bad_reference(index: u64, available: usize) -> Error {
    Error::Format(FormatError::new(
        "SWM",
        Malformed::IndexOutOfRange {
            index: index as i64,
            vertices: available as u64,
        },
    ))
}

impl Prediction {
    /// Checks that the prediction of vertex `k` refers only to vertices
    /// `< k` and, for [`Prediction::Multi`], to a non-empty range of
    /// `parallelograms` whose selectable entries (the first
    /// [`MAX_SELECTABLE`]) do too.
    pub fn check(&self, k: usize, parallelograms: &[[u32; 3]]) -> Result<(), Error> {
        let vertex = |v: u32| {
            if (v as usize) < k {
                Ok(())
            } else {
                Err(bad_reference(v as u64, k))
            }
        };
        match *self {
            Prediction::None => Ok(()),
            Prediction::Delta { from } => vertex(from),
            Prediction::Parallelogram { a, b, opposite } => {
                vertex(a)?;
                vertex(b)?;
                vertex(opposite)
            }
            Prediction::Multi { first, count } => {
                let end = first as u64 + count as u64;
                if count == 0 || end > parallelograms.len() as u64 {
                    return Err(bad_reference(end, parallelograms.len()));
                }
                // Only the selectable entries are ever used, so only they
                // are checked: constant work per vertex, whatever `count`.
                self.selectable(parallelograms)
                    .iter()
                    .flatten()
                    .try_for_each(|&v| vertex(v))
            }
        }
    }

    /// The parallelograms a [`Prediction::Multi`] may choose from (at most
    /// [`MAX_SELECTABLE`]); empty for the other kinds. The prediction must
    /// have passed [`Prediction::check`].
    #[inline]
    pub fn selectable<'p>(&self, parallelograms: &'p [[u32; 3]]) -> &'p [[u32; 3]] {
        match *self {
            Prediction::Multi { first, count } => {
                let n = (count as usize).min(MAX_SELECTABLE);
                &parallelograms[first as usize..first as usize + n]
            }
            _ => &[],
        }
    }

    /// The predicted grid point, given the vertices decoded so far; a
    /// [`Prediction::Multi`] averages all its selectable parallelograms
    /// (the lossless coder uses [`average`] with the coded subset instead).
    ///
    /// The prediction must have passed [`Prediction::check`] for
    /// `decoded.len()`, and `1 ≤ bits ≤ 32`. Must match the encoder
    /// exactly: both sides call this.
    #[inline]
    pub fn predict(&self, decoded: &[[u32; 3]], parallelograms: &[[u32; 3]], bits: u8) -> [u32; 3] {
        match *self {
            Prediction::None => [1 << (bits - 1); 3],
            Prediction::Delta { from } => decoded[from as usize],
            Prediction::Parallelogram { a, b, opposite } => {
                average(decoded, &[[a, b, opposite]], 1, bits)
            }
            Prediction::Multi { .. } => {
                let list = self.selectable(parallelograms);
                average(decoded, list, (1 << list.len()) - 1, bits)
            }
        }
    }
}

/// The average of the parallelogram predictions `a + b − opposite` of the
/// entries of `list` whose bit is set in `subset` (bit `i` ↔ `list[i]`;
/// `list` has at most 32 entries, `subset` selects at least one), each
/// taken unclamped, rounded to the nearest grid point with ties rounded up
/// (towards +∞), then clamped into the grid `[0, 2^bits − 1]`.
///
/// The sum is exact in `i64`; the rounding is `⌊(2·sum + n) / (2n)⌋`,
/// i.e. `⌊sum/n + 1/2⌋`, with a floor division. Must match the encoder
/// exactly: both sides call this.
pub fn average(decoded: &[[u32; 3]], list: &[[u32; 3]], subset: u32, bits: u8) -> [u32; 3] {
    let mut sum = [0i64; 3];
    let mut n = 0i64;
    for (i, &abo) in list.iter().enumerate() {
        if (subset >> i) & 1 == 1 {
            n += 1;
            let p = parallelogram(decoded, abo);
            for k in 0..3 {
                sum[k] += p[k];
            }
        }
    }
    mean_in_grid(sum, n, bits)
}

/// The unclamped parallelogram prediction `a + b − opposite` of
/// `[a, b, opposite]`.
#[inline]
pub(crate) fn parallelogram(decoded: &[[u32; 3]], [a, b, o]: [u32; 3]) -> [i64; 3] {
    let (a, b, o) = (
        decoded[a as usize],
        decoded[b as usize],
        decoded[o as usize],
    );
    core::array::from_fn(|k| a[k] as i64 + b[k] as i64 - o[k] as i64)
}

/// The sums behind [`average`] for parallelograms computed beforehand
/// with [`parallelogram`] (the encoder tries every subset of the same
/// few): per axis the sum of those `subset` selects, and how many there
/// are. [`mean_in_grid`] of them is the point [`average`] gives.
#[inline]
pub(crate) fn sum_of(points: &[[i64; 3]], subset: u32) -> ([i64; 3], i64) {
    let mut sum = [0i64; 3];
    let mut n = 0i64;
    for (i, p) in points.iter().enumerate() {
        if (subset >> i) & 1 == 1 {
            n += 1;
            for k in 0..3 {
                sum[k] += p[k];
            }
        }
    }
    (sum, n)
}

/// Where the exact mean `sum/n` lies against the grid point `pred` it
/// rounds to, per axis: 0 on it (or clamped away from it), 1 a third or a
/// quarter of a step below, 2 that much above, 3 half a step below (ties
/// round up, so a half is never above).
#[inline]
pub(crate) fn offsets(sum: [i64; 3], n: i64, pred: [u32; 3]) -> [u8; 3] {
    core::array::from_fn(|k| {
        let d = sum[k] - n * pred[k] as i64;
        if d == 0 || d.abs() >= n {
            0
        } else if 2 * d == -n {
            3
        } else if d < 0 {
            1
        } else {
            2
        }
    })
}

/// `⌊(2·sum + n) / (2n)⌋` per axis (n at least 1), clamped into the grid.
/// The usual n get constant divisors, which the compiler turns into
/// shifts and multiplications: a 64-bit division is the slowest
/// instruction of the whole prediction.
#[inline]
pub(crate) fn mean_in_grid(sum: [i64; 3], n: i64, bits: u8) -> [u32; 3] {
    let max = max_value(bits) as i64;
    let n = n.max(1);
    core::array::from_fn(|k| {
        let x = 2 * sum[k] + n;
        let mean = match n {
            1 => x.div_euclid(2),
            2 => x.div_euclid(4),
            3 => x.div_euclid(6),
            4 => x.div_euclid(8),
            _ => x.div_euclid(2 * n),
        };
        mean.clamp(0, max) as u32
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predictions() {
        let d = [[10, 10, 10], [20, 10, 10], [15, 20, 10], [0, 0, 0]];
        assert_eq!(Prediction::None.predict(&d, &[], 8), [128; 3]);
        assert_eq!(
            Prediction::Delta { from: 2 }.predict(&d, &[], 8),
            [15, 20, 10]
        );
        let p = Prediction::Parallelogram {
            a: 0,
            b: 1,
            opposite: 2,
        };
        assert_eq!(p.predict(&d, &[], 8), [15, 0, 10]);
        // Clamped into the grid: 0 + 0 − 15 < 0.
        let p = Prediction::Parallelogram {
            a: 3,
            b: 3,
            opposite: 2,
        };
        assert_eq!(p.predict(&d, &[], 8), [0, 0, 0]);
        // Average of (15,0,10) and (−10,0,0) = (2.5,0,5): ties round up.
        let list = [[0, 1, 2], [0, 3, 1]];
        let m = Prediction::Multi { first: 0, count: 2 };
        assert_eq!(m.predict(&d, &list, 8), [3, 0, 5]);
        assert_eq!(average(&d, &list, 0b01, 8), [15, 0, 10]);
        assert_eq!(average(&d, &list, 0b10, 8), [0, 0, 0]);
    }

    #[test]
    fn averages_round_ties_up() {
        let d = [[0, 0, 0], [1, 2, 3], [0, 0, 0]];
        // Parallelograms (1,2,3) and (0,0,0): means 0.5, 1, 1.5.
        let list = [[1, 0, 2], [0, 0, 2]];
        assert_eq!(average(&d, &list, 0b11, 8), [1, 1, 2]);
        // Negative sums round towards +∞ too before clamping: −0.5 → 0,
        // and −1.5 → −1 → clamped to 0.
        let d = [[1, 1, 3], [0, 0, 0], [0, 0, 0]];
        let list = [[1, 2, 0], [1, 2, 2]];
        assert_eq!(average(&d, &list, 0b11, 8), [0, 0, 0]);
        // At the top of the grid the clamp applies after rounding.
        let d = [[255, 255, 255], [255, 255, 255], [0, 0, 0]];
        assert_eq!(average(&d, &[[0, 1, 2]], 1, 8), [255; 3]);
    }

    #[test]
    fn references_must_precede() {
        let list = [[0, 1, 2], [0, 1, 5]];
        assert!(Prediction::None.check(0, &list).is_ok());
        assert!(Prediction::Delta { from: 2 }.check(3, &list).is_ok());
        assert!(Prediction::Delta { from: 3 }.check(3, &list).is_err());
        let p = Prediction::Parallelogram {
            a: 0,
            b: 1,
            opposite: 7,
        };
        assert!(p.check(7, &list).is_err());
        assert!(p.check(8, &list).is_ok());
        let m = |first, count| Prediction::Multi { first, count };
        assert!(m(0, 1).check(3, &list).is_ok());
        assert!(m(0, 2).check(3, &list).is_err());
        assert!(m(0, 2).check(6, &list).is_ok());
        // Entries past the selectable ones are never used, nor checked.
        let long = [[0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0], [9, 9, 9]];
        assert!(m(0, 5).check(1, &long).is_ok());
        assert!(m(1, 4).check(1, &long).is_err());
        assert!(m(0, 0).check(9, &list).is_err());
        assert!(m(1, 2).check(9, &list).is_err());
        assert!(m(u32::MAX, u32::MAX).check(9, &list).is_err());
    }

    #[test]
    fn precomputed_points_average_the_same() {
        let mut x = 0x1234_5678_9abc_def1u64;
        let mut rand = move |n: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % n) as u32
        };
        for bits in [6u8, 12, 24] {
            let d: Vec<[u32; 3]> = (0..20).map(|_| [0; 3].map(|_| rand(1 << bits))).collect();
            for _ in 0..500 {
                let n = 1 + rand(MAX_SELECTABLE as u64) as usize;
                let list: Vec<[u32; 3]> = (0..n).map(|_| [0; 3].map(|_| rand(20))).collect();
                let points: Vec<[i64; 3]> = list.iter().map(|&p| parallelogram(&d, p)).collect();
                for subset in 1..1u32 << n {
                    assert_eq!(
                        {
                            let (sum, n) = sum_of(&points, subset);
                            mean_in_grid(sum, n, bits)
                        },
                        average(&d, &list, subset, bits)
                    );
                    // The constant divisors agree with the plain division.
                    let sum = points
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| subset >> i & 1 == 1);
                    let (k, total) = sum.fold((0i64, 0i64), |(k, t), (_, p)| (k + 1, t + p[0]));
                    let plain =
                        ((2 * total + k).div_euclid(2 * k)).clamp(0, max_value(bits) as i64);
                    assert_eq!(
                        {
                            let (sum, n) = sum_of(&points, subset);
                            mean_in_grid(sum, n, bits)
                        }[0] as i64,
                        plain
                    );
                }
            }
        }
    }

    #[test]
    fn offsets_say_where_the_mean_fell() {
        // (sum, n) on one axis → the offset of the exact mean against the
        // grid point it rounds to (ties round up).
        for (sum, n, want) in [
            (7, 1, 0),  // one parallelogram: always on the point
            (3, 2, 3),  // 1.5 rounds to 2: half below
            (4, 2, 0),  // 2
            (4, 3, 2),  // 1.333 rounds to 1: a third above
            (5, 3, 1),  // 1.667 rounds to 2: a third below
            (5, 4, 2),  // 1.25: a quarter above
            (7, 4, 1),  // 1.75: a quarter below
            (6, 4, 3),  // 1.5: half below
            (-5, 2, 0), // −2.5 clamps to 0, 2.5 steps away
        ] {
            let pred = mean_in_grid([sum; 3], n, 8);
            assert_eq!(offsets([sum; 3], n, pred), [want; 3], "{sum}/{n}");
        }
    }
}
