//! The range coding of one level's scalars (format-spec/07-displaced.md,
//! "DISP").
//!
//! Each scalar `q` (a signed step count, `|q| < 2^20`) is zig-zagged to
//! `z` (0, −1, 1, −2, … → 0, 1, 2, 3, …) and coded as its bit length `L`
//! (0 for `z = 0`, else the position of its leading one, 1..=21) with an
//! adaptive model chosen by its **parents' context**, then the `L − 1`
//! bits below the leading one: the highest with an adaptive model per
//! `L`, the others raw, high to low. The same scheme as the lossless
//! mode's residuals (`geometry::lossless`); displacements of a level are
//! about one step wide and nearly symmetric, so the length carries almost
//! all of the information.
//!
//! The context of a new vertex of level `l + 1` (its edge's ends `a`,
//! `b` on level `l`) comes from the ends that were new on level `l`, its
//! parents: none (every vertex of the first level, and none after), or
//! one or two, with the largest of their bit lengths capped at 3:
//! `1 + 4·(parents − 1) + min(3, max L)`. A vertex whose parents moved
//! far tends to move far too (PGC's and the normal-mesh coders'
//! observation that wavelet magnitudes persist across scales).
//!
//! Every level's chunk is its own range-coder stream with fresh models,
//! so a file cut after a level's chunk still decodes.
//!
//! Speed: a level's contexts are made into a flat byte array before its
//! scalars are decoded into a flat `i32` array that placement then reads
//! in edge order; for a level whose edges were derived from the level
//! above (`finer`), by that construction, which knows each edge's parents
//! (no triangle read), else in one pass over its edges (each edge's
//! first corner read directly).

use crate::entropy::{AdaptiveModel, Decoder};
use crate::prelude::*;
use crate::Error;

/// Scalars are below 2^MAGNITUDE_BITS in magnitude.
pub(crate) const MAGNITUDE_BITS: u32 = 20;
/// Bit lengths 0..=21 of a zig-zagged scalar.
const LENGTHS: u32 = MAGNITUDE_BITS + 2;
/// Parents' contexts: none, or one or two parents with a length of
/// 0, 1, 2 or 3 and more.
pub(crate) const CONTEXTS: usize = 9;

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

fn length_of(z: u32) -> u32 {
    u32::BITS - z.leading_zeros()
}

/// The context of each edge of a level (see the module's docs): `first`
/// is the first vertex made by the level below, `below` that level's
/// scalars (empty for the first level). A level whose edges were derived
/// from the level above (`finer`) gets the same contexts from
/// [`capped_lengths`] and [`context`] without reading its triangles.
pub(crate) fn contexts(
    edges: &super::subdivide::Edges,
    triangles: &[[u32; 3]],
    first: usize,
    below: &[i32],
) -> Vec<u8> {
    if below.is_empty() {
        return vec![0; edges.len()];
    }
    (0..edges.len())
        .map(|e| {
            let [a, b, _] = super::subdivide::corner_vertices(edges.first_corner(e), triangles);
            let (mut parents, mut len) = (0u8, 0u8);
            for v in [a, b] {
                if let Some(&q) = (v as usize).checked_sub(first).and_then(|i| below.get(i)) {
                    parents += 1;
                    len = len.max(capped_length(q));
                }
            }
            context(parents, len)
        })
        .collect()
}

/// A scalar's bit length, capped at 3: its share of a context.
#[inline]
pub(crate) fn capped_length(q: i32) -> u8 {
    let z = ((q as u32) << 1) ^ ((q >> 31) as u32);
    length_of(z).min(3) as u8
}

/// The context of a vertex with `parents` parents (0, 1 or 2) whose
/// largest [`capped_length`] is `len`.
#[inline]
pub(crate) fn context(parents: u8, len: u8) -> u8 {
    match parents {
        0 => 0,
        p => 1 + 4 * (p - 1) + len,
    }
}

/// The models of one level's stream.
struct Models {
    length: Vec<AdaptiveModel>,
    top: Vec<AdaptiveModel>,
}

impl Models {
    fn new() -> Models {
        Models {
            length: (0..CONTEXTS).map(|_| AdaptiveModel::new(LENGTHS)).collect(),
            top: (0..LENGTHS).map(|_| AdaptiveModel::new(2)).collect(),
        }
    }
}

#[cfg(feature = "encoder")]
/// The chunk of one level's scalars (each within ±[`MAX_SCALAR`]), each
/// with its context (below [`CONTEXTS`]).
pub(crate) fn encode_level(qs: &[i32], contexts: &[u8]) -> Vec<u8> {
    let mut enc = crate::entropy::Encoder::new();
    let mut m = Models::new();
    for (&q, &c) in qs.iter().zip(contexts) {
        debug_assert!(q.abs() <= MAX_SCALAR);
        let z = zigzag(q);
        let len = length_of(z);
        enc.encode(&mut m.length[c as usize], len);
        if len >= 2 {
            enc.encode(&mut m.top[len as usize], (z >> (len - 2)) & 1);
        }
        if len >= 3 {
            enc.encode_bits(z & ((1 << (len - 2)) - 1), len - 2);
        }
    }
    enc.finish()
}

/// Decodes one level's chunk into `out`: one scalar per context.
pub(crate) fn decode_level(bytes: &[u8], contexts: &[u8], out: &mut Vec<i32>) -> Result<(), Error> {
    let mut dec = Decoder::new(bytes)?;
    let mut m = Models::new();
    out.clear();
    out.reserve(contexts.len());
    for &c in contexts {
        let len = dec.decode(&mut m.length[usize::from(c)])?;
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
        let contexts: Vec<u8> = (0..qs.len()).map(|i| (i % CONTEXTS) as u8).collect();
        let bytes = encode_level(&qs, &contexts);
        let mut out = Vec::new();
        decode_level(&bytes, &contexts, &mut out).unwrap();
        assert_eq!(out, qs);
        // One more scalar than was coded runs past the stream's end, or
        // the stream has bytes left: refused either way.
        let more: Vec<u8> = (0..qs.len() + 50).map(|i| (i % CONTEXTS) as u8).collect();
        assert!(decode_level(&bytes, &more, &mut out).is_err());
    }

    #[test]
    fn zigzag_is_its_own_inverse() {
        for q in [-MAX_SCALAR, -5, -1, 0, 1, 5, MAX_SCALAR] {
            assert_eq!(unzigzag(zigzag(q)), q);
        }
    }
}
