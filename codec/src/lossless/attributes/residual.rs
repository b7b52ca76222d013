//! The residual coder of attribute values: per component, the signed
//! difference between the value and its prediction, wrapped around the
//! value's range, zig-zagged and coded as a bit length (adaptive, in the
//! context of the lengths around it) and a mantissa (the two bits below
//! the leading one adaptive, the rest raw).
//!
//! Source: the length-and-mantissa split is the one `GEOM` uses for
//! positions (format-spec/04-lossless.md, Residuals), itself the
//! "Elias-gamma with adaptive prefixes" scheme common to mesh coders
//! (Touma and Gotsman's and Draco's residuals are coded per bit plane
//! to the same effect). What differs: the range is any modulus `m`
//! (`2^bits` for grid values, `2H + 1` for octahedral normals), and the
//! length's context is the previous value's length for the same
//! component, averaged with this value's previous component.
//!
//! Invariants: a value `v` and prediction `p` in `0..m` give a code `z <
//! 2^bits`, so lengths fit `0..=bits`; [`Residuals::decode`] returns a
//! value in `0..m` whatever the bytes. Encoder and decoder update the
//! same models in the same order (must match exactly).

#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{ContextModel, Decoder};
use crate::Error;

/// Residual classes, each with its own length models: 0 for values a
/// rule predicted from their neighbourhood, 1 for the fallbacks (a
/// neighbour's value or the previous value), whose residuals are larger.
pub(crate) const CLASSES: usize = 2;

/// The models of one stream's residuals.
pub(crate) struct Residuals {
    bits: u32,
    dims: usize,
    modulus: u64,
    lengths: ContextModel,
    mantissas: ContextModel,
    /// The previous value's lengths, per component.
    last: [u32; 4],
}

impl Residuals {
    /// Models for `dims` components of `bits`-bit codes in `0..modulus`
    /// (`modulus ≤ 2^bits`, `bits` 2..=24).
    pub(crate) fn new(dims: usize, bits: u8, modulus: u64) -> Self {
        let bits = u32::from(bits);
        let symbols = bits + 1;
        Residuals {
            bits,
            dims,
            modulus,
            lengths: ContextModel::new(CLASSES * dims * symbols as usize, symbols),
            mantissas: ContextModel::new(symbols as usize, 4),
            last: [0; 4],
        }
    }

    /// The length model of component `k` of a value of `class`, given
    /// the lengths coded so far for this value.
    fn context(&self, class: usize, k: usize, coded: &[u32; 4]) -> usize {
        let level = if k == 0 {
            self.last[0]
        } else {
            (self.last[k] + coded[k - 1]).div_ceil(2)
        };
        (class * self.dims + k) * (self.bits as usize + 1) + level as usize
    }

    #[cfg(feature = "encoder")]
    /// Codes `value` (each component in `0..modulus`) against `pred`.
    pub(crate) fn encode(&mut self, enc: &mut Encoder, class: usize, value: &[u64], pred: &[u64]) {
        let mut coded = [0u32; 4];
        for k in 0..self.dims {
            let m = self.modulus;
            let raw = (value[k] + m - pred[k] % m) % m;
            let s = if raw >= m.div_ceil(2) {
                raw as i64 - m as i64
            } else {
                raw as i64
            };
            let z = if s >= 0 {
                2 * s as u64
            } else {
                (-2 * s - 1) as u64
            } as u32;
            let len = u32::BITS - z.leading_zeros();
            let ctx = self.context(class, k, &coded);
            enc.encode(self.lengths.get(ctx), len);
            if len >= 2 {
                let top = (len - 1).min(2);
                let rest = len - 1 - top;
                let t = (z >> rest) & ((1 << top) - 1);
                enc.encode(self.mantissas.get(len as usize), t);
                if rest > 0 {
                    enc.encode_bits(z & ((1 << rest) - 1), rest);
                }
            }
            coded[k] = len;
        }
        self.last = coded;
    }

    /// Decodes a value against `pred` (must match [`Self::encode`]
    /// exactly). Every component comes back in `0..modulus`.
    pub(crate) fn decode(
        &mut self,
        dec: &mut Decoder<'_>,
        class: usize,
        pred: &[u64],
        out: &mut [u64],
    ) -> Result<(), Error> {
        let mut coded = [0u32; 4];
        for k in 0..self.dims {
            let ctx = self.context(class, k, &coded);
            let len = dec.decode(self.lengths.get(ctx))?;
            let z = if len >= 2 {
                let top = (len - 1).min(2);
                let rest = len - 1 - top;
                let t = dec.decode(self.mantissas.get(len as usize))?;
                let low = if rest > 0 { dec.decode_bits(rest)? } else { 0 };
                (((1 << top) | t) << rest) | low
            } else {
                len
            };
            let s = if z & 1 == 0 {
                i64::from(z / 2)
            } else {
                -i64::from(z / 2) - 1
            };
            let m = self.modulus as i64;
            out[k] = (pred[k] as i64 % m + s).rem_euclid(m) as u64;
            coded[k] = len;
        }
        self.last = coded;
        Ok(())
    }
}

#[cfg(all(test, feature = "encoder"))]
mod tests {
    use super::*;

    #[test]
    fn every_value_and_prediction_round_trips() {
        for (bits, m) in [(4u8, 16u64), (4, 15), (8, 255), (10, 1024)] {
            let mut enc = Encoder::new();
            let mut r = Residuals::new(2, bits, m);
            let step = (m / 7).max(1);
            let mut pairs = Vec::new();
            for v in (0..m).step_by(step as usize) {
                for p in (0..m).step_by(step as usize / 2 + 1) {
                    pairs.push((v, p));
                    r.encode(&mut enc, (v % 2) as usize, &[v, p], &[p, v]);
                }
            }
            let bytes = enc.finish();
            let mut dec = Decoder::new(&bytes).unwrap();
            let mut r = Residuals::new(2, bits, m);
            for (v, p) in pairs {
                let mut out = [0u64; 2];
                r.decode(&mut dec, (v % 2) as usize, &[p, v], &mut out)
                    .unwrap();
                assert_eq!(out, [v, p]);
            }
            dec.finish().unwrap();
        }
    }
}
