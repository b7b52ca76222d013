//! The range encoder and decoder: constriction's queue range coder
//! (`u32` words, `u64` state), so symbols are decoded in the order they
//! were encoded.
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

use constriction::backends::ReadWords;
use constriction::stream::model::{DecoderModel, EncoderModel, EntropyModel};
use constriction::stream::queue::{DecoderFrontendError, DefaultRangeEncoder, RangeDecoder};
use constriction::stream::{Code, Decode, Encode};
use constriction::{CoderError, Queue};

use super::model::{AdaptiveModel, PRECISION};
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

impl DecoderModel<PRECISION> for Uniform {
    #[inline(always)]
    fn quantile_function(&self, quantile: u32) -> (u32, u32, NonZeroU32) {
        let v = quantile >> self.shift;
        // shift < PRECISION, so the probability is never zero.
        let p = NonZeroU32::new(1 << self.shift).unwrap_or(NonZeroU32::MIN);
        (v, v << self.shift, p)
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

/// constriction's only decoding error: the data points outside the model.
#[cold]
fn coder_error(e: CoderError<DecoderFrontendError, Infallible>) -> Error {
    match e {
        CoderError::Frontend(_) => malformed(Malformed::BadSyntax(
            "entropy-coded data is invalid for its model",
        )),
        CoderError::Backend(e) => match e {},
    }
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

/// The decoder's view of the bytes: little-endian `u32` words, then "no
/// more data" forever (constriction then shifts in zeros). Counts every
/// request, so [`Decoder::finish`] can tell where the stream ended.
#[derive(Clone, Debug)]
struct WordSource<'a> {
    words: core::slice::ChunksExact<'a, u8>,
    reads: u64,
}

impl ReadWords<u32, Queue> for WordSource<'_> {
    type ReadError = Infallible;

    #[inline(always)]
    fn read(&mut self) -> Result<Option<u32>, Infallible> {
        self.reads += 1;
        match self.words.next() {
            Some(&[a, b, c, d]) => Ok(Some(u32::from_le_bytes([a, b, c, d]))),
            _ => Ok(None),
        }
    }

    #[inline(always)]
    fn maybe_exhausted(&self) -> bool {
        self.words.len() == 0
    }
}

/// Decodes what an [`Encoder`] wrote, in the same order and with models
/// created and used the same way.
#[derive(Clone, Debug)]
pub struct Decoder<'a> {
    coder: RangeDecoder<u32, u64, WordSource<'a>>,
    /// Length of the data in words.
    words: u64,
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
        let source = WordSource {
            words: bytes.chunks_exact(4),
            reads: 0,
        };
        Ok(Decoder {
            coder: infallible(RangeDecoder::with_backend(source)),
            words: (bytes.len() / 4) as u64,
        })
    }

    /// Decodes one symbol with `model`, then updates the model.
    #[inline]
    pub fn decode(&mut self, model: &mut AdaptiveModel) -> Result<u32, Error> {
        let symbol = self
            .coder
            .decode_symbol(model.table())
            .map_err(coder_error)?;
        // Must match the encoder exactly: the same update, after the symbol.
        model.update(symbol);
        Ok(symbol)
    }

    /// Decodes `bits` raw bits (`bits` ≤ [`MAX_RAW_BITS`]).
    ///
    /// # Panics
    ///
    /// If `bits > MAX_RAW_BITS` (a bug in the caller).
    #[inline]
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

    #[inline(always)]
    fn raw(&mut self, bits: u32) -> Result<u32, Error> {
        if bits == 0 {
            return Ok(0);
        }
        let model = Uniform {
            shift: PRECISION as u32 - bits,
        };
        self.coder.decode_symbol(model).map_err(coder_error)
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
        let state = self.coder.state();
        let (lower, range) = (state.lower(), state.range().get());
        let (source, _, _) = self.coder.into_raw_parts();
        // The range is all ones until the first symbol narrows it, and
        // never again afterwards; the encoder writes nothing in that case.
        if range == u64::MAX {
            return if self.words == 0 {
                Ok(())
            } else {
                Err(malformed(Malformed::TrailingData))
            };
        }
        // Words the decoder needed: two to start with, then one per read
        // since. (constriction stops its first two reads at the first
        // "no more data", so those are counted apart.)
        let first_reads = self.words.min(2) + u64::from(self.words < 2);
        let needed = 2 + (source.reads - first_reads);
        // The encoder's flush, as constriction computes it: the word of
        // `lower + 2^32 − 1`, then a zero word if that word is also the
        // top word of `lower + range`. After a one-word flush the decoder
        // has asked for one word past the end.
        let point_word = lower.wrapping_add((1 << 32) - 1) >> 32;
        let upper_word = lower.wrapping_add(range) >> 32;
        let written = needed - u64::from(point_word != upper_word);
        match written.cmp(&self.words) {
            core::cmp::Ordering::Greater => Err(malformed(Malformed::Truncated)),
            core::cmp::Ordering::Less => Err(malformed(Malformed::TrailingData)),
            core::cmp::Ordering::Equal => Ok(()),
        }
    }
}
