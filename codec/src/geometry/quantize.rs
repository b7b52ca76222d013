//! Uniform quantization of positions on a cubic grid over the bounding box.
//!
//! The grid has `2^bits` points per axis, from `origin` to
//! `origin + range`, where `range` is the largest side of the bounding box
//! (the same for all axes, so the grid is cubic and a quantization step is
//! the same length in every direction, as in Draco's position quantization).
//!
//! ```text
//!   step = range / (2^bits − 1)                       (in f64)
//!   quantize:   q = clamp(round((p − origin) / step), 0, 2^bits − 1)
//!   dequantize: p' = f32(origin + q · step)            (f64, then rounded)
//! ```
//!
//! **Guarantee.** For every point `p` inside the box the quantizer was
//! built from, and on every axis,
//! `|p − dequantize(quantize(p))| ≤ step/2 + ulp(p')/2`:
//! rounding to the nearest grid point moves `p` by at most half a step,
//! the f64 arithmetic adds a relative error near 2^-52 (far below an f32
//! ulp), and storing the result as f32 moves it by at most half an f32
//! ulp. The test checks exactly that bound (with the f64 slack).
//!
//! `range` is rounded *up* to an f32 when built from a bounding box, so
//! the top grid point is never inside the box and clamping never moves a
//! point of the box. A degenerate box (one point, `range` 0) quantizes
//! everything to 0 and dequantizes to `origin`.
//!
//! Dequantization is what the decoder computes, and the spec fixes its
//! arithmetic: `step` and `origin + q·step` in f64 (IEEE, round to
//! nearest, this operation order), then one rounding to f32.

use crate::{Error, ParameterError};

/// Fewest quantization bits accepted.
pub const MIN_BITS: u8 = 6;

/// Most quantization bits accepted (an f32 mantissa holds 24 bits).
pub const MAX_BITS: u8 = 24;

/// A cubic quantization grid (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantizer {
    /// The grid point 0 on every axis (the bounding box's minimum corner).
    pub origin: [f32; 3],
    /// Side of the grid: the largest side of the bounding box, ≥ 0.
    pub range: f32,
    /// Bits per coordinate, [`MIN_BITS`]`..=`[`MAX_BITS`].
    pub bits: u8,
}

impl Quantizer {
    /// The grid over the bounding box of `positions` (origin 0 and range
    /// 0 when there are none).
    ///
    /// Fails with [`Error::Parameter`] if `bits` is outside
    /// [`MIN_BITS`]`..=`[`MAX_BITS`] or a coordinate is not finite.
    pub fn from_positions(positions: &[[f32; 3]], bits: u8) -> Result<Self, Error> {
        check_bits(bits)?;
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in positions {
            for k in 0..3 {
                if !p[k].is_finite() {
                    return Err(Error::Parameter(ParameterError::OutOfRange {
                        name: "coordinate",
                        value: p[k] as f64,
                        min: f32::MIN as f64,
                        max: f32::MAX as f64,
                    }));
                }
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if positions.is_empty() {
            return Ok(Quantizer {
                origin: [0.0; 3],
                range: 0.0,
                bits,
            });
        }
        let side = (0..3)
            .map(|k| hi[k] as f64 - lo[k] as f64)
            .fold(0.0, f64::max);
        Ok(Quantizer {
            origin: lo,
            range: f32_at_least(side),
            bits,
        })
    }

    /// Largest grid coordinate, `2^bits − 1`.
    #[inline]
    pub fn max_value(&self) -> u32 {
        max_value(self.bits)
    }

    /// Length of one quantization step, `range / (2^bits − 1)`.
    #[inline]
    pub fn step(&self) -> f64 {
        self.range as f64 / self.max_value().max(1) as f64
    }

    /// The nearest grid point (ties round up), clamped into the grid.
    pub fn quantize(&self, p: [f32; 3]) -> [u32; 3] {
        let step = self.step();
        let max = self.max_value();
        core::array::from_fn(|k| {
            if step == 0.0 {
                return 0;
            }
            let t = (p[k] as f64 - self.origin[k] as f64) / step;
            // `as` saturates (NaN becomes 0), then the clamp keeps the grid.
            (crate::math::floor(t + 0.5) as u32).min(max)
        })
    }

    /// The position of a grid point: `origin + q·step` in f64, rounded
    /// once to f32. Must match the encoder exactly (the encoder's
    /// reconstruction, which later stages see, is this function).
    pub fn dequantize(&self, q: [u32; 3]) -> [f32; 3] {
        let step = self.step();
        core::array::from_fn(|k| (self.origin[k] as f64 + q[k] as f64 * step) as f32)
    }
}

/// `2^bits − 1`, for bits ≤ 32.
#[inline]
pub(crate) fn max_value(bits: u8) -> u32 {
    (((1u64) << bits.min(32)) - 1) as u32
}

fn check_bits(bits: u8) -> Result<(), Error> {
    if (MIN_BITS..=MAX_BITS).contains(&bits) {
        Ok(())
    } else {
        Err(Error::Parameter(ParameterError::OutOfRange {
            name: "quantization bits",
            value: bits as f64,
            min: MIN_BITS as f64,
            max: MAX_BITS as f64,
        }))
    }
}

/// The smallest f32 that is ≥ `x` (x ≥ 0 and finite as f32).
fn f32_at_least(x: f64) -> f32 {
    let r = x as f32;
    if (r as f64) < x {
        // One ulp up; r is finite and ≥ 0, so its bits count upwards.
        f32::from_bits(r.to_bits() + 1)
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Half an f32 ulp at `x`: the most rounding an f64 to f32 can move it.
    fn half_ulp(x: f32) -> f64 {
        let a = x.abs();
        let next = f32::from_bits(a.to_bits() + 1);
        (next as f64 - a as f64) / 2.0
    }

    fn check_bound(points: &[[f32; 3]], bits: u8) {
        let quant = Quantizer::from_positions(points, bits).unwrap();
        let step = quant.step();
        for &p in points {
            let q = quant.quantize(p);
            let d = quant.dequantize(q);
            for k in 0..3 {
                assert!(q[k] <= quant.max_value());
                let err = (p[k] as f64 - d[k] as f64).abs();
                // step/2 from rounding to the grid, half an f32 ulp from
                // storing the result, and a hair for the f64 arithmetic.
                let bound = step / 2.0 + half_ulp(d[k]) + 1e-12 * (1.0 + p[k].abs() as f64);
                assert!(
                    err <= bound,
                    "bits {bits}: p={} deq={} err={err:e} bound={bound:e}",
                    p[k],
                    d[k]
                );
            }
        }
    }

    #[test]
    fn error_is_at_most_half_a_step() {
        let mut s = 12345u64;
        let mut rnd = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
        };
        for bits in MIN_BITS..=MAX_BITS {
            for scale in [1e-3f32, 1.0, 37.5, 1e4] {
                let offset = [5.0 * scale, -3.0 * scale, 1e3];
                let pts: Vec<[f32; 3]> = (0..2_000)
                    .map(|_| {
                        [
                            offset[0] + rnd() * scale,
                            offset[1] + rnd() * scale * 0.5,
                            offset[2] + rnd() * scale * 0.25,
                        ]
                    })
                    .collect();
                check_bound(&pts, bits);
            }
        }
    }

    #[test]
    fn box_corners_are_exact_and_inside() {
        let pts = [[-1.0, 2.0, 0.5], [3.0, 2.5, 0.75], [0.1, 2.2, 0.6]];
        let quant = Quantizer::from_positions(&pts, 11).unwrap();
        assert_eq!(quant.origin, [-1.0, 2.0, 0.5]);
        assert_eq!(quant.range, 4.0);
        assert_eq!(quant.quantize(pts[0]), [0, 0, 0]);
        assert_eq!(quant.quantize(pts[1])[0], 2047);
        assert_eq!(quant.dequantize([2047, 0, 0])[0], 3.0);
        check_bound(&pts, 11);
    }

    #[test]
    fn degenerate_box() {
        let pts = [[1.5f32, -2.0, 7.0]; 4];
        let quant = Quantizer::from_positions(&pts, 12).unwrap();
        assert_eq!(quant.range, 0.0);
        assert_eq!(quant.quantize(pts[0]), [0, 0, 0]);
        assert_eq!(quant.dequantize([0, 0, 0]), pts[0]);
        // A grid point beyond 0 still gives the origin (step 0), no NaN.
        assert_eq!(quant.dequantize([5, 9, 4095]), pts[0]);
        let empty = Quantizer::from_positions(&[], 12).unwrap();
        assert_eq!(empty.dequantize(empty.quantize([3.0, 4.0, 5.0])), [0.0; 3]);
    }

    #[test]
    fn bad_parameters() {
        assert!(Quantizer::from_positions(&[[0.0; 3]], 5).is_err());
        assert!(Quantizer::from_positions(&[[0.0; 3]], 25).is_err());
        assert!(Quantizer::from_positions(&[[f32::NAN, 0.0, 0.0]], 12).is_err());
        // Out-of-box and non-finite points clamp instead of panicking.
        let quant = Quantizer::from_positions(&[[0.0; 3], [1.0; 3]], 8).unwrap();
        assert_eq!(quant.quantize([-5.0, 9.0, f32::NAN]), [0, 255, 0]);
    }

    #[test]
    fn range_rounds_up() {
        // A side whose f64 length is not an f32: the range must cover it.
        let pts = [[1.0e-8f32, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let quant = Quantizer::from_positions(&pts, 24).unwrap();
        assert!(quant.range as f64 >= 1.0 - 1.0e-8f32 as f64);
        check_bound(&pts, 24);
    }
}
