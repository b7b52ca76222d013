//! The range coding of one level's scalars (format-spec/07-displaced.md,
//! "DISP").
//!
//! Each scalar `q` (a signed step count, `|q| < 2^20`) is zig-zagged to
//! `z` (0, −1, 1, −2, … → 0, 1, 2, 3, …) and coded as its bit length `L`
//! (0 for `z = 0`, else the position of its leading one, 1..=21) with one
//! adaptive model per level, then the `L − 1` bits below the leading one:
//! the highest with an adaptive model per `L`, the others raw, high to
//! low. The same scheme as the lossless mode's residuals
//! (`geometry::lossless`) without their contexts: displacements of a
//! level are about one step wide and nearly symmetric, so the length
//! carries almost all of the information.
//!
//! Every level's chunk is its own range-coder stream with fresh models,
//! so a file cut after a level's chunk still decodes.

use crate::entropy::{AdaptiveModel, Decoder};
use crate::prelude::*;
use crate::Error;

/// Scalars are below 2^MAGNITUDE_BITS in magnitude.
pub(crate) const MAGNITUDE_BITS: u32 = 20;
/// Bit lengths 0..=21 of a zig-zagged scalar.
const LENGTHS: u32 = MAGNITUDE_BITS + 2;

/// The largest scalar magnitude the format holds.
#[cfg(feature = "encoder")]
pub(crate) const MAX_SCALAR: i32 = (1 << MAGNITUDE_BITS) - 1;

/// Fewest bits one scalar can cost, as a fraction `NUM / DEN` (for the
/// "count cannot fit" rule): its length symbol, whose model gives every
/// other symbol one quantum of 2^16, costs at least
/// −log2(1 − 21/2^16) > 1/2163 bits.
pub(crate) const MIN_BITS: (u64, u64) = (1, 4096);

#[cfg(feature = "encoder")]
fn zigzag(q: i32) -> u32 {
    ((q << 1) ^ (q >> 31)) as u32
}

fn unzigzag(z: u32) -> i32 {
    ((z >> 1) as i32) ^ -((z & 1) as i32)
}

/// The models of one level's stream.
struct Models {
    length: AdaptiveModel,
    top: Vec<AdaptiveModel>,
}

impl Models {
    fn new() -> Models {
        Models {
            length: AdaptiveModel::new(LENGTHS),
            top: (0..LENGTHS).map(|_| AdaptiveModel::new(2)).collect(),
        }
    }
}

#[cfg(feature = "encoder")]
/// The chunk of one level's scalars (each within ±[`MAX_SCALAR`]).
pub(crate) fn encode_level(qs: &[i32]) -> Vec<u8> {
    let mut enc = crate::entropy::Encoder::new();
    let mut m = Models::new();
    for &q in qs {
        debug_assert!(q.abs() <= MAX_SCALAR);
        let z = zigzag(q);
        let len = u32::BITS - z.leading_zeros();
        enc.encode(&mut m.length, len);
        if len >= 2 {
            enc.encode(&mut m.top[len as usize], (z >> (len - 2)) & 1);
        }
        if len >= 3 {
            enc.encode_bits(z & ((1 << (len - 2)) - 1), len - 2);
        }
    }
    enc.finish()
}

/// Decodes `count` scalars of one level's chunk into `out`.
pub(crate) fn decode_level(bytes: &[u8], count: usize, out: &mut Vec<i32>) -> Result<(), Error> {
    let mut dec = Decoder::new(bytes)?;
    let mut m = Models::new();
    out.clear();
    out.reserve(count);
    for _ in 0..count {
        let len = dec.decode(&mut m.length)?;
        let z = match len {
            0 => 0,
            1 => 1,
            _ => {
                let top = dec.decode(&mut m.top[len as usize])?;
                let rest = if len >= 3 {
                    dec.decode_bits(len - 2)?
                } else {
                    0
                };
                (1 << (len - 1)) | (top << (len - 2)) | rest
            }
        };
        out.push(unzigzag(z));
    }
    dec.finish()
}

#[cfg(all(test, feature = "encoder"))]
mod tests {
    use super::*;

    #[test]
    fn scalars_round_trip_at_every_length() {
        let mut qs = vec![0, 1, -1, 2, -2, 3, 7, -8, 100, -1000];
        qs.extend([MAX_SCALAR, -MAX_SCALAR, 1 << 19, -(1 << 19)]);
        qs.extend((0..500).map(|i| (i % 7) - 3));
        let bytes = encode_level(&qs);
        let mut out = Vec::new();
        decode_level(&bytes, qs.len(), &mut out).unwrap();
        assert_eq!(out, qs);
        // One more scalar than was coded runs past the stream's end, or
        // the stream has bytes left: refused either way.
        assert!(decode_level(&bytes, qs.len() + 50, &mut out).is_err());
    }

    #[test]
    fn zigzag_is_its_own_inverse() {
        for q in [-MAX_SCALAR, -5, -1, 0, 1, 5, MAX_SCALAR] {
            assert_eq!(unzigzag(zigzag(q)), q);
        }
    }
}
