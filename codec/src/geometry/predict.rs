//! Predictions of a vertex's quantized position from vertices decoded
//! before it: the parallelogram rule of Touma & Gotsman, "Triangle mesh
//! compression" (Graphics Interface 1998), and its multi-parallelogram
//! average (Cohen-Or, Cohen & Irony, "Multi-way geometry encoding", 2002;
//! Isenburg & Alliez, "Compressing polygon mesh geometry with parallelogram
//! prediction", IEEE Visualization 2002; Draco's
//! `MeshPredictionSchemeMultiParallelogram`).
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
//! may only name vertices `< k`. The connectivity decoder produces the
//! predictions, so for the decoder they are hostile data: [`check`] rejects
//! a reference to a vertex not yet decoded with [`Error::Format`], and
//! nothing here can panic on any input that passed it.
//!
//! All arithmetic is on grid integers (`i64`, no overflow for 24-bit
//! coordinates and up to 2^32 parallelograms), with the result clamped
//! into the grid, so every platform predicts the same point. Must match
//! the encoder exactly: both sides call [`Prediction::predict`] /
//! [`predict_multi`].

use crate::{Error, FormatError, Malformed};

/// How vertex `k` is predicted (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prediction {
    /// No neighbour is known (the first vertex of a component): predict
    /// the centre of the grid, `2^(bits−1)` on every axis.
    None,
    /// Predict the position of an earlier vertex (e.g. the other end of
    /// the edge that reached this one).
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
    /// The average of several parallelograms: entries
    /// `first .. first + count` of the parallelogram list passed beside
    /// the predictions (each entry is `[a, b, opposite]`).
    Multi {
        /// First entry in the parallelogram list.
        first: u32,
        /// Number of entries, ≥ 1.
        count: u32,
    },
}

/// The error for a prediction that refers to something not available.
fn bad_reference(index: u32, available: usize) -> Error {
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
    /// `parallelograms` whose entries do too.
    pub fn check(&self, k: usize, parallelograms: &[[u32; 3]]) -> Result<(), Error> {
        let vertex = |v: u32| {
            if (v as usize) < k {
                Ok(())
            } else {
                Err(bad_reference(v, k))
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
                    return Err(bad_reference(first, parallelograms.len()));
                }
                for p in &parallelograms[first as usize..end as usize] {
                    for &v in p {
                        vertex(v)?;
                    }
                }
                Ok(())
            }
        }
    }

    /// The predicted grid point, given the vertices decoded so far.
    ///
    /// The prediction must have passed [`Prediction::check`] for
    /// `decoded.len()` (so every index is in bounds). Must match the
    /// encoder exactly: both sides call this.
    #[inline]
    pub fn predict(&self, decoded: &[[u32; 3]], parallelograms: &[[u32; 3]], bits: u8) -> [u32; 3] {
        match *self {
            Prediction::None => [1 << (bits - 1); 3],
            Prediction::Delta { from } => decoded[from as usize],
            Prediction::Parallelogram { a, b, opposite } => {
                parallelogram(decoded, [a, b, opposite], bits)
            }
            Prediction::Multi { first, count } => {
                let list = &parallelograms[first as usize..first as usize + count as usize];
                predict_multi(decoded, list, bits)
            }
        }
    }
}

/// `a + b − opposite`, clamped into the grid `[0, 2^bits − 1]`.
#[inline]
fn parallelogram(decoded: &[[u32; 3]], [a, b, o]: [u32; 3], bits: u8) -> [u32; 3] {
    let max = super::quantize::max_value(bits) as i64;
    let (a, b, o) = (
        decoded[a as usize],
        decoded[b as usize],
        decoded[o as usize],
    );
    core::array::from_fn(|k| (a[k] as i64 + b[k] as i64 - o[k] as i64).clamp(0, max) as u32)
}

/// The average of the parallelogram predictions `a + b − opposite` of
/// `list` (not empty), each taken unclamped, rounded to the nearest grid
/// point with ties rounded up (towards +∞), then clamped into the grid.
///
/// The sum is exact in `i64`; rounding is `⌊(2·sum + n) / (2n)⌋`, i.e.
/// `⌊sum/n + 1/2⌋`. Must match the encoder exactly: both sides call this.
pub fn predict_multi(decoded: &[[u32; 3]], list: &[[u32; 3]], bits: u8) -> [u32; 3] {
    let max = super::quantize::max_value(bits) as i64;
    let mut sum = [0i64; 3];
    for &[a, b, o] in list {
        let (a, b, o) = (
            decoded[a as usize],
            decoded[b as usize],
            decoded[o as usize],
        );
        for k in 0..3 {
            sum[k] += a[k] as i64 + b[k] as i64 - o[k] as i64;
        }
    }
    let n = list.len().max(1) as i64;
    core::array::from_fn(|k| (2 * sum[k] + n).div_euclid(2 * n).clamp(0, max) as u32)
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
        // Clamped into the grid: 0 + 0 − 15 < 0, 255 limit.
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
    }

    #[test]
    fn multi_rounds_ties_up() {
        let d = [[0, 0, 0], [1, 2, 3], [0, 0, 0]];
        // Parallelograms (1,2,3) and (0,0,0): means 0.5, 1, 1.5.
        let list = [[1, 0, 2], [0, 0, 2]];
        assert_eq!(predict_multi(&d, &list, 8), [1, 1, 2]);
        // Negative sums round towards +∞ too before clamping: −0.5 → 0.
        let d = [[1, 1, 1], [0, 0, 0], [0, 0, 0]];
        let list = [[1, 2, 0], [1, 2, 2]];
        assert_eq!(predict_multi(&d, &list, 8), [0, 0, 0]);
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
        assert!(Prediction::Multi { first: 0, count: 1 }
            .check(3, &list)
            .is_ok());
        assert!(Prediction::Multi { first: 0, count: 2 }
            .check(3, &list)
            .is_err());
        assert!(Prediction::Multi { first: 0, count: 0 }
            .check(9, &list)
            .is_err());
        assert!(Prediction::Multi {
            first: u32::MAX,
            count: u32::MAX
        }
        .check(9, &list)
        .is_err());
    }
}
