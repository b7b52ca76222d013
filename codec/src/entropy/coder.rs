//! The range encoder and decoder: constriction's queue range coder
//! (`u32` words, `u64` state), so symbols are decoded in the order they
//! were encoded. The encoder is constriction's; the decoder is swm's own
//! implementation of the same arithmetic (Martin's range decoding step
//! with constriction's word size, state width and end-of-data rule), so
//! that a model can find most symbols without the coder's division, which
//! constriction's model interface does not allow (see [`Decoder`]).
//!
//! Source: the range coder of G. N. N. Martin, "Range encoding: an
//! algorithm for removing redundancy from a digitised message" (1979), as
//! implemented by R. Bamler's `constriction` crate (`stream::queue`).
//!
//! Byte layout: the coder's `u32` words, each little-endian, in order. A
//! stream of zero symbols is zero bytes; otherwise the coder adds one or
//! two words at the end that pin down the final interval.
//!
//! The decoder trusts nothing: it reads words through a bounds-checked
//! source that yields "no more data" past the end (constriction then
//! shifts in zeros), every model maps every quantile to a symbol, and the
//! only error constriction can report (a quantile outside the model, which
//! all-ones garbage can produce) becomes an [`Error::Format`]. Garbage in
//! gives garbage symbols or an error, never a panic, a loop or an
//! allocation; the layers above validate what the symbols mean.

use crate::prelude::*;

use core::borrow::Borrow;
use core::convert::Infallible;
use core::num::NonZeroU32;

use constriction::stream::model::{EncoderModel, EntropyModel};
use constriction::stream::queue::DefaultRangeEncoder;
use constriction::stream::Encode;

use super::model::{quantile, AdaptiveModel, PRECISION};
use crate::{Error, FormatError, Malformed};

/// Largest number of raw bits [`Encoder::encode_bits`] takes at once.
pub const MAX_RAW_BITS: u32 = 24;

/// Raw bits are coded in chunks of at most this many bits, one uniform
/// symbol per chunk (a chunk needs `2^-bits ≥ 2^-PRECISION`).
const RAW_CHUNK_BITS: u32 = PRECISION as u32;

/// A uniform distribution over `2^bits` values, `1 ≤ bits ≤ PRECISION`,
/// at the same precision as every other model (constriction can only
/// report an error on valid data when models mix precisions).
#[derive(Clone, Copy, Debug)]
struct Uniform {
    /// `PRECISION − bits`: each value owns `2^shift` quanta.
    shift: u32,
}

impl EntropyModel<PRECISION> for Uniform {
    type Symbol = u32;
    type Probability = u32;
}

impl EncoderModel<PRECISION> for Uniform {
    #[inline(always)]
    fn left_cumulative_and_probability(
        &self,
        symbol: impl Borrow<u32>,
    ) -> Option<(u32, NonZeroU32)> {
        let v = *symbol.borrow();
        if v >> (PRECISION as u32 - self.shift) != 0 {
            return None;
        }
        Some((v << self.shift, NonZeroU32::new(1 << self.shift)?))
    }
}

/// Unwraps a result whose error type is uninhabited.
#[inline(always)]
fn infallible<T>(r: Result<T, Infallible>) -> T {
    match r {
        Ok(v) => v,
        Err(e) => match e {},
    }
}

/// The error every invalid entropy-coded stream gives.
fn malformed(what: Malformed) -> Error {
    Error::Format(FormatError::new("SWM", what))
}

/// The decoder's only error (constriction's): the data points outside
/// the model.
#[cold]
fn invalid() -> Error {
    malformed(Malformed::BadSyntax(
        "entropy-coded data is invalid for its model",
    ))
}

/// Encodes symbols with adaptive models, and raw bits, into bytes.
#[derive(Debug, Default)]
pub struct Encoder {
    coder: DefaultRangeEncoder,
}

impl Encoder {
    /// An empty encoder.
    pub fn new() -> Self {
        Encoder::default()
    }

    /// Encodes `symbol` with `model`, then updates the model.
    ///
    /// # Panics
    ///
    /// If `symbol >= model.symbols()` (a bug in the caller).
    #[inline]
    pub fn encode(&mut self, model: &mut AdaptiveModel, symbol: u32) {
        assert!(
            symbol < model.symbols(),
            "symbol {symbol} outside a {}-symbol alphabet",
            model.symbols()
        );
        // Cannot fail: the symbol is in range and has frequency ≥ 1.
        if self.coder.encode_symbol(symbol, model.table()).is_err() {
            unreachable!("every symbol of a table is codable");
        }
        // Must match the decoder exactly: the same update, after the symbol.
        model.update(symbol);
    }

    /// Encodes the low `bits` bits of `value` as raw (uniform) bits,
    /// `bits` ≤ [`MAX_RAW_BITS`]; zero bits cost nothing.
    ///
    /// # Panics
    ///
    /// If `bits > MAX_RAW_BITS` or `value` has bits set above `bits`.
    #[inline]
    pub fn encode_bits(&mut self, value: u32, bits: u32) {
        assert!(bits <= MAX_RAW_BITS, "at most 24 raw bits at a time");
        assert!(
            value >> bits == 0,
            "value {value} does not fit in {bits} bits"
        );
        // High chunk first; must match the decoder exactly.
        if bits > RAW_CHUNK_BITS {
            self.raw(value >> RAW_CHUNK_BITS, bits - RAW_CHUNK_BITS);
            self.raw(value & ((1 << RAW_CHUNK_BITS) - 1), RAW_CHUNK_BITS);
        } else {
            self.raw(value, bits);
        }
    }

    #[inline(always)]
    fn raw(&mut self, value: u32, bits: u32) {
        if bits == 0 {
            return;
        }
        let model = Uniform {
            shift: PRECISION as u32 - bits,
        };
        if self.coder.encode_symbol(value, model).is_err() {
            unreachable!("a value below 2^bits is always codable");
        }
    }

    /// Bits written so far, including the one or two words that
    /// [`finish`](Self::finish) would add (an estimate while encoding).
    pub fn bits(&self) -> usize {
        self.coder.num_bits()
    }

    /// Ends the stream and returns its bytes (a multiple of 4).
    pub fn finish(self) -> Vec<u8> {
        let words = infallible(self.coder.into_compressed());
        let mut bytes = Vec::with_capacity(words.len() * 4);
        for w in words {
            bytes.extend_from_slice(&w.to_le_bytes());
        }
        bytes
    }
}

/// Decodes what an [`Encoder`] wrote, in the same order and with models
/// created and used the same way.
///
/// The decoding side of constriction's queue range coder (`u32` words,
/// `u64` state), implemented here so that the model sees the point's
/// offset and the interval's scale rather than their quotient: a symbol's decode waits on the
/// previous one's, and the 64-bit division is its longest step, which
/// `Table::find_scaled` skips for a model's first
/// symbol (and both of a binary model's). Every state change is
/// constriction's, in its order, so every symbol and every error is the
/// same (a test decodes random and valid streams with both).
#[derive(Clone, Debug)]
pub struct Decoder<'a> {
    /// The words not read yet.
    words: core::slice::ChunksExact<'a, u8>,
    /// Word requests so far, those past the end included (constriction
    /// then shifts in zeros): [`Decoder::finish`] counts them.
    reads: u64,
    /// The coder's interval `[lower, lower + range)` (wrapping), `range`
    /// never zero.
    lower: u64,
    range: u64,
    /// The point the encoder's output pins down, read two words ahead.
    point: u64,
    /// Length of the data in words.
    total: u64,
}

impl<'a> Decoder<'a> {
    /// A decoder over `bytes`, which must be whole words (a multiple of 4
    /// bytes long).
    pub fn new(bytes: &'a [u8]) -> Result<Self, Error> {
        if bytes.len() % 4 != 0 {
            return Err(malformed(Malformed::BadSyntax(
                "entropy-coded data is not a whole number of 32-bit words",
            )));
        }
        let mut d = Decoder {
            words: bytes.chunks_exact(4),
            reads: 0,
            lower: 0,
            range: u64::MAX,
            point: 0,
            total: (bytes.len() / 4) as u64,
        };
        // The point's first two words; constriction stops at the first
        // missing one and shifts what it read to the top.
        let mut read = 0;
        while let Some(w) = d.word() {
            d.point = (d.point << 32) | u64::from(w);
            read += 1;
            if read == 2 {
                break;
            }
        }
        if read == 1 {
            d.point <<= 32;
        }
        Ok(d)
    }

    /// The next word, counted; `None` past the end.
    #[inline(always)]
    fn word(&mut self) -> Option<u32> {
        self.reads += 1;
        match self.words.next() {
            Some(&[a, b, c, d]) => Some(u32::from_le_bytes([a, b, c, d])),
            _ => None,
        }
    }

    /// One symbol: `find` maps the point's offset in the interval and
    /// the interval's scale (`range / 2^PRECISION`) to the symbol whose
    /// interval holds the quantile `offset / scale`, with its left
    /// cumulative and its frequency (≥ 1, the intervals tiling
    /// `0..2^PRECISION`), or to `None` when that quantile is `2^PRECISION`
    /// or more (constriction's error). Given both, a model can often
    /// answer without the division (`Table::find_scaled`).
    #[inline(always)]
    fn symbol(
        &mut self,
        find: impl FnOnce(u64, u64) -> Option<(u32, u32, u32)>,
    ) -> Result<u32, Error> {
        let scale = self.range >> PRECISION;
        let offset = self.point.wrapping_sub(self.lower);
        let (symbol, left, frequency) = find(offset, scale).ok_or_else(invalid)?;
        self.lower = self.lower.wrapping_add(scale * u64::from(left));
        self.range = scale * u64::from(frequency);
        if self.range < 1 << 32 {
            self.lower <<= 32;
            self.range <<= 32;
            self.point <<= 32;
            if let Some(w) = self.word() {
                self.point |= u64::from(w);
            }
        }
        Ok(symbol)
    }

    /// Decodes one symbol with `model`, then updates the model.
    #[inline(always)]
    pub fn decode(&mut self, model: &mut AdaptiveModel) -> Result<u32, Error> {
        let symbol = self.symbol(|offset, scale| model.table().find_scaled(offset, scale))?;
        // Must match the encoder exactly: the same update, after the symbol.
        model.update(symbol);
        Ok(symbol)
    }

    /// Decodes `bits` raw bits (`bits` ≤ [`MAX_RAW_BITS`]).
    ///
    /// # Panics
    ///
    /// If `bits > MAX_RAW_BITS` (a bug in the caller).
    #[inline(always)]
    pub fn decode_bits(&mut self, bits: u32) -> Result<u32, Error> {
        assert!(bits <= MAX_RAW_BITS, "at most 24 raw bits at a time");
        // High chunk first; must match the encoder exactly.
        if bits > RAW_CHUNK_BITS {
            let high = self.raw(bits - RAW_CHUNK_BITS)?;
            let low = self.raw(RAW_CHUNK_BITS)?;
            Ok((high << RAW_CHUNK_BITS) | low)
        } else {
            self.raw(bits)
        }
    }

    /// `bits` (1 ≤ `bits` ≤ `PRECISION`) raw bits: the uniform model's
    /// symbol, as [`Uniform`] maps quantiles for the encoder.
    #[inline(always)]
    fn raw(&mut self, bits: u32) -> Result<u32, Error> {
        if bits == 0 {
            return Ok(0);
        }
        let shift = PRECISION as u32 - bits;
        self.symbol(|offset, scale| {
            let v = quantile(offset, scale)? >> shift;
            Some((v, v << shift, 1 << shift))
        })
    }

    /// Checks that the stream ends exactly where the decoded symbols say
    /// it should: a missing word is [`Malformed::Truncated`], an extra
    /// one [`Malformed::TrailingData`].
    ///
    /// Why this can be exact: the decoder reads two words to start and
    /// one per renormalization; the encoder writes one word per
    /// renormalization and then a flush of one word, or two when the
    /// final interval needs a trailing zero word to be pinned down. The
    /// decoder's interval is the encoder's (constriction updates both the
    /// same way), so it can tell which flush the encoder wrote, and hence
    /// how many words past the end it should have asked for (one or
    /// none).
    pub fn finish(self) -> Result<(), Error> {
        let (lower, range) = (self.lower, self.range);
        // The range is all ones until the first symbol narrows it, and
        // never again afterwards; the encoder writes nothing in that case.
        if range == u64::MAX {
            return if self.total == 0 {
                Ok(())
            } else {
                Err(malformed(Malformed::TrailingData))
            };
        }
        // Words the decoder needed: two to start with, then one per read
        // since. (constriction stops its first two reads at the first
        // "no more data", so those are counted apart.)
        let first_reads = self.total.min(2) + u64::from(self.total < 2);
        let needed = 2 + (self.reads - first_reads);
        // The encoder's flush, as constriction computes it: the word of
        // `lower + 2^32 − 1`, then a zero word if that word is also the
        // top word of `lower + range`. After a one-word flush the decoder
        // has asked for one word past the end.
        let point_word = lower.wrapping_add((1 << 32) - 1) >> 32;
        let upper_word = lower.wrapping_add(range) >> 32;
        let written = needed - u64::from(point_word != upper_word);
        match written.cmp(&self.total) {
            core::cmp::Ordering::Greater => Err(malformed(Malformed::Truncated)),
            core::cmp::Ordering::Less => Err(malformed(Malformed::TrailingData)),
            core::cmp::Ordering::Equal => Ok(()),
        }
    }
}

/// The decoder against constriction's own, which it writes out.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::entropy::tests::Rng;
    use constriction::backends::ReadWords;
    use constriction::stream::model::DecoderModel;
    use constriction::stream::queue::RangeDecoder;
    use constriction::stream::{Code, Decode};
    use constriction::Queue;

    /// constriction's view of the bytes, as the decoder had it before:
    /// words, then "no more data", every request counted.
    struct Words<'a> {
        words: core::slice::ChunksExact<'a, u8>,
        reads: u64,
    }

    impl ReadWords<u32, Queue> for Words<'_> {
        type ReadError = Infallible;

        fn read(&mut self) -> Result<Option<u32>, Infallible> {
            self.reads += 1;
            Ok(match self.words.next() {
                Some(&[a, b, c, d]) => Some(u32::from_le_bytes([a, b, c, d])),
                _ => None,
            })
        }

        fn maybe_exhausted(&self) -> bool {
            self.words.len() == 0
        }
    }

    impl DecoderModel<PRECISION> for Uniform {
        fn quantile_function(&self, quantile: u32) -> (u32, u32, NonZeroU32) {
            let v = quantile >> self.shift;
            (
                v,
                v << self.shift,
                NonZeroU32::new(1 << self.shift).unwrap(),
            )
        }
    }

    /// Random bytes, and valid streams cut or flipped: every symbol, every
    /// error, and the state `finish` reads are constriction's.
    #[test]
    fn symbols_errors_and_state_are_constrictions() {
        let mut rng = Rng(46);
        for round in 0..2_000 {
            let symbols = [2, 5, 22, 256, 4096][rng.below(5) as usize];
            let bytes: Vec<u8> = if round % 2 == 0 {
                let len = 4 * rng.below(60) as usize;
                (0..len).map(|_| rng.next() as u8).collect()
            } else {
                let mut enc = Encoder::new();
                let mut m = AdaptiveModel::new(symbols);
                for _ in 0..rng.below(400) {
                    let r = rng.unit();
                    enc.encode(&mut m, (r * r * f64::from(symbols)) as u32);
                    if rng.below(4) == 0 {
                        let bits = rng.below(MAX_RAW_BITS + 1);
                        enc.encode_bits(rng.next() as u32 & ((1u64 << bits) - 1) as u32, bits);
                    }
                }
                let mut b = enc.finish();
                if rng.below(3) == 0 && !b.is_empty() {
                    let k = rng.below(b.len() as u32) as usize;
                    b[k] ^= 1 << rng.below(8);
                }
                if rng.below(3) == 0 {
                    b.truncate(b.len() / 8 * 4);
                }
                b
            };
            let mut ours = Decoder::new(&bytes).unwrap();
            let words = Words {
                words: bytes.chunks_exact(4),
                reads: 0,
            };
            let mut theirs = RangeDecoder::<u32, u64, _>::with_backend(words).unwrap();
            let (mut m1, mut m2) = (AdaptiveModel::new(symbols), AdaptiveModel::new(symbols));
            for _ in 0..rng.below(500) {
                let (a, b) = if rng.below(4) == 0 {
                    let bits = 1 + rng.below(PRECISION as u32);
                    let u = Uniform {
                        shift: PRECISION as u32 - bits,
                    };
                    (ours.raw(bits), theirs.decode_symbol(u))
                } else {
                    let a = ours.decode(&mut m1);
                    let b = theirs.decode_symbol(m2.table());
                    if let Ok(s) = b {
                        m2.update(s);
                    }
                    (a, b)
                };
                match (a, b) {
                    (Ok(x), Ok(y)) => assert_eq!(x, y, "round {round}"),
                    (Err(_), Err(_)) => break,
                    (x, y) => panic!("round {round}: {x:?} vs {y:?}"),
                }
                let state = theirs.state();
                assert_eq!(
                    (ours.lower, ours.range),
                    (state.lower(), state.range().get())
                );
            }
            let (words, _, point) = theirs.into_raw_parts();
            assert_eq!(
                (ours.reads, ours.point),
                (words.reads, point),
                "round {round}"
            );
        }
    }
}
