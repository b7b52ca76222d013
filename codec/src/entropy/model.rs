//! Adaptive frequency models with periodic rescaling, coded from a
//! quantized table that is rebuilt every `k` updates.
//!
//! Source: the adaptive model of Witten, Neal and Cleary, "Arithmetic
//! coding for data compression" (CACM 30(6), 1987): counts that start at
//! 1, grow by one per coded symbol and are halved when their total passes
//! a limit (which also lets the model follow a drifting source). Coding
//! from a table that is only refreshed from the counts every `k` updates
//! (a "quasi-static" model between refreshes) trades a little adaptation
//! speed for a lot of decoding speed; the schedule below, with `k`
//! doubling from 16 to 1024, is this project's own.
//!
//! ```text
//!  counts (exact, adaptive)          quantized table (what is coded with)
//!  c[0] c[1] ... c[n-1], total T ──► f[s] = 1 + ⌊c[s]·(2^P − n) / T⌋,
//!         every update                leftover added to the first most
//!                                     frequent symbol, so Σ f = 2^P;
//!                                     cum[s] = f[0] + ... + f[s-1];
//!                                     rebuilt after 16, 32, ..., 1024
//!                                     updates, then every 1024
//! ```
//!
//! Invariants of a [`Table`]: `cum[0] = 0`, `cum[n] = 2^PRECISION`,
//! `f[s] = cum[s+1] − cum[s] ≥ 1` for every symbol (any symbol can always
//! be coded, whatever the counts), and `f[s] < 2^PRECISION` (because
//! n ≥ 2), which constriction requires.
//!
//! **Decoding** does not search the table from the start. Each table
//! keeps a lookup array over the top `LB` bits of the quantile
//! (`LB = ⌈log2 n⌉ + 2`, at least [`MIN_LOOKUP_BITS`], at most
//! `PRECISION`): entry `b` is the symbol whose interval holds the quantile
//! `b·2^(P−LB)`. The decoder starts there and steps forward while the next
//! cumulative is still ≤ the quantile. The scan is bounded by `n` (so
//! hostile input cannot make it loop), and on average costs at most
//! `n / 2^LB ≤ 1/4` extra steps, because a bucket holds at most one
//! symbol start per quantum and is visited with probability `2^−LB`. A
//! binary search would cost `log2 n` dependent loads every time; a full
//! `2^P` lookup table would cost 128 KB per model and a slow rebuild.
//! Before any of that, the first symbol (and the second of a binary
//! model) is recognized from the coder's offset and scale without the
//! division that makes the quantile (`Table::find_scaled`): the same
//! symbol, without the longest step of its decode.
//!
//! The update step ([`AdaptiveModel::update`]) is the single function both
//! the encoder and the decoder call after every symbol: the two sides stay
//! in step only because it is the same code.

use crate::prelude::*;

use core::borrow::Borrow;
use core::num::NonZeroU32;

use constriction::stream::model::{DecoderModel, EncoderModel, EntropyModel};

/// Bits of fixed-point precision of every quantized table: probabilities
/// are multiples of `2^-PRECISION`, and the cumulatives sum to exactly
/// `2^PRECISION`. Part of the bitstream definition.
pub const PRECISION: usize = 16;

/// The total of every quantized table, `2^PRECISION`.
const TOTAL: u32 = 1 << PRECISION;

/// Smallest alphabet an [`AdaptiveModel`] accepts. constriction does not
/// support a model that puts all mass on one symbol.
pub const MIN_SYMBOLS: u32 = 2;

/// Largest alphabet an [`AdaptiveModel`] accepts. With `2^PRECISION`
/// quanta, 4096 symbols still leave 15/16 of the mass to share by counts.
pub const MAX_SYMBOLS: u32 = 4096;

/// When the counts' total exceeds this, every count is halved (rounding
/// up, so none reaches zero). Part of the bitstream definition.
pub const COUNT_LIMIT: u32 = 1 << 16;

/// Updates before the first rebuild of the quantized table; the interval
/// then doubles after each rebuild up to [`MAX_REBUILD_INTERVAL`]. Part of
/// the bitstream definition.
pub const FIRST_REBUILD_INTERVAL: u32 = 16;

/// Longest interval between two rebuilds of the quantized table.
pub const MAX_REBUILD_INTERVAL: u32 = 1024;

/// Lower bound on the lookup bits of a table (not part of the bitstream:
/// it only changes how fast decoding finds a symbol, never which one).
const MIN_LOOKUP_BITS: u32 = 6;

/// A quantized frequency table: what the range coder actually codes with.
///
/// See the module docs for its invariants and the decoder's lookup.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Table {
    /// `n + 1` cumulatives, from 0 to `2^PRECISION`.
    cum: Box<[u32]>,
    /// `2^LB` entries: the symbol holding quantile `b << shift`.
    lookup: Box<[u16]>,
    /// `PRECISION − LB`.
    shift: u32,
}

impl Table {
    /// The uniform table over `n` symbols (what a fresh model codes with).
    fn uniform(n: u32) -> Self {
        let lookup_bits = lookup_bits(n);
        let mut table = Table {
            cum: vec![0; n as usize + 1].into_boxed_slice(),
            lookup: vec![0; 1 << lookup_bits].into_boxed_slice(),
            shift: PRECISION as u32 - lookup_bits,
        };
        let ones = vec![1u32; n as usize];
        table.rebuild(&ones, n);
        table
    }

    /// Number of symbols.
    #[inline]
    pub fn symbols(&self) -> u32 {
        (self.cum.len() - 1) as u32
    }

    /// The quantized frequency of `symbol` (out of `2^PRECISION`).
    ///
    /// # Panics
    ///
    /// If `symbol >= self.symbols()`.
    #[inline]
    pub fn frequency(&self, symbol: u32) -> u32 {
        let s = symbol as usize;
        self.cum[s + 1] - self.cum[s]
    }

    /// Recomputes the table from exact counts whose sum is `total`.
    ///
    /// Each symbol first gets one quantum (so it stays codable), then a
    /// share of the other `2^P − n` in proportion to its count, rounded
    /// down; what rounding leaves over goes to the first symbol with the
    /// largest count, where it costs the least. Integer arithmetic only,
    /// so every platform builds the same table. Must match the encoder
    /// exactly (it does, being the same function).
    fn rebuild(&mut self, counts: &[u32], total: u32) {
        let n = counts.len();
        debug_assert_eq!(self.cum.len(), n + 1);
        let spare = u64::from(TOTAL - n as u32);
        let total = u64::from(total);
        let mut best = 0;
        let mut sum = 0u32;
        for (s, &c) in counts.iter().enumerate() {
            let f = 1 + (u64::from(c) * spare / total) as u32;
            self.cum[s + 1] = f;
            sum += f;
            if c > counts[best] {
                best = s;
            }
        }
        // Σ ⌊c·spare/T⌋ ≤ spare, so sum ≤ 2^P and the leftover is ≥ 0.
        self.cum[best + 1] += TOTAL - sum;
        self.cum[0] = 0;
        for s in 0..n {
            self.cum[s + 1] += self.cum[s];
        }
        debug_assert_eq!(self.cum[n], TOTAL);

        // lookup[b] = the symbol whose interval [cum[s], cum[s+1]) holds
        // b << shift, i.e. buckets ⌈cum[s]/w⌉ .. ⌈cum[s+1]/w⌉ go to s.
        let round_up = (1u32 << self.shift) - 1;
        let mut start = 0usize;
        for s in 0..n {
            let end = ((self.cum[s + 1] + round_up) >> self.shift) as usize;
            self.lookup[start..end].fill(s as u16);
            start = end;
        }
        debug_assert_eq!(start, self.lookup.len());
    }

    /// [`find`](Self::find) of the quantile `offset / scale` (the range
    /// decoder's), `None` when that is `2^PRECISION` or more. The first
    /// symbol, the most frequent of most models (a zero residual, a zero
    /// displacement), is recognized without the division: `offset / scale`
    /// (rounded down) is below the integer `cum[1]` exactly when `offset`
    /// is below `scale · cum[1]`, which cannot overflow since
    /// `scale · 2^PRECISION` is at most the coder's range. So is the second
    /// of a two-symbol model, below `scale · 2^PRECISION`. The division is
    /// the longest step of a symbol's decode, and the next symbol waits
    /// on this one: the same symbol, sooner.
    #[inline(always)]
    pub(super) fn find_scaled(&self, offset: u64, scale: u64) -> Option<(u32, u32, u32)> {
        let one = self.cum[1];
        if offset < scale * u64::from(one) {
            return Some((0, 0, one));
        }
        if self.cum.len() == 3 {
            return (offset < scale << PRECISION).then_some((1, one, TOTAL - one));
        }
        Some(self.find(quantile(offset, scale)?))
    }

    /// The symbol whose interval holds `quantile` (< `2^PRECISION`), with
    /// its left cumulative and frequency.
    #[inline(always)]
    fn find(&self, quantile: u32) -> (u32, u32, u32) {
        debug_assert!(quantile < TOTAL);
        let mut s = self.lookup[(quantile >> self.shift) as usize] as usize;
        // Terminates by `cum[n] = 2^P > quantile`, after at most n steps.
        while self.cum[s + 1] <= quantile {
            s += 1;
        }
        let left = self.cum[s];
        (s as u32, left, self.cum[s + 1] - left)
    }
}

/// `⌈log2 n⌉ + 2` bits of lookup, clamped to `[MIN_LOOKUP_BITS, PRECISION]`.
fn lookup_bits(n: u32) -> u32 {
    let ceil_log2 = u32::BITS - (n - 1).leading_zeros();
    (ceil_log2 + 2).clamp(MIN_LOOKUP_BITS, PRECISION as u32)
}

impl EntropyModel<PRECISION> for Table {
    type Symbol = u32;
    type Probability = u32;
}

impl EncoderModel<PRECISION> for Table {
    #[inline(always)]
    fn left_cumulative_and_probability(
        &self,
        symbol: impl Borrow<u32>,
    ) -> Option<(u32, NonZeroU32)> {
        let s = *symbol.borrow() as usize;
        let left = *self.cum.get(s)?;
        let right = *self.cum.get(s + 1)?;
        Some((left, NonZeroU32::new(right - left)?))
    }
}

impl DecoderModel<PRECISION> for Table {
    #[inline(always)]
    fn quantile_function(&self, quantile: u32) -> (u32, u32, NonZeroU32) {
        let (s, left, f) = self.find(quantile);
        // f ≥ 1 is a table invariant (every symbol keeps one quantum).
        let f = NonZeroU32::new(f).unwrap_or(NonZeroU32::MIN);
        (s, left, f)
    }
}

/// An adaptive model over the symbols `0..n` (see the module docs).
///
/// Encoder and decoder must create their models with the same `n` and
/// code the same sequence of symbols with them; the models then evolve
/// identically.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdaptiveModel {
    /// Exact counts, each ≥ 1.
    counts: Box<[u32]>,
    /// Their sum, ≤ [`COUNT_LIMIT`] between updates.
    total: u32,
    /// The table symbols are coded with.
    table: Table,
    /// Updates left before the next rebuild of `table`.
    until_rebuild: u32,
    /// Length of the current rebuild interval.
    interval: u32,
}

impl AdaptiveModel {
    /// A fresh model over `symbols` symbols, all equally likely.
    ///
    /// # Panics
    ///
    /// If `symbols` is outside [`MIN_SYMBOLS`]`..=`[`MAX_SYMBOLS`]. Callers
    /// that take an alphabet size from a file must check it first.
    pub fn new(symbols: u32) -> Self {
        assert!(
            (MIN_SYMBOLS..=MAX_SYMBOLS).contains(&symbols),
            "an adaptive model needs 2..=4096 symbols, not {symbols}"
        );
        AdaptiveModel {
            counts: vec![1; symbols as usize].into_boxed_slice(),
            total: symbols,
            table: Table::uniform(symbols),
            until_rebuild: FIRST_REBUILD_INTERVAL,
            interval: FIRST_REBUILD_INTERVAL,
        }
    }

    /// Number of symbols.
    #[inline]
    pub fn symbols(&self) -> u32 {
        self.counts.len() as u32
    }

    /// The table the next symbol will be coded with.
    #[inline]
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// Records that `symbol` was coded. The encoder calls it after
    /// encoding, the decoder after decoding: must match the encoder
    /// exactly, which is why both sides call this one function.
    #[inline(always)]
    pub(crate) fn update(&mut self, symbol: u32) {
        self.counts[symbol as usize] += 1;
        self.total += 1;
        if self.total > COUNT_LIMIT {
            self.halve();
        }
        self.until_rebuild -= 1;
        if self.until_rebuild == 0 {
            self.rebuild();
        }
    }

    /// Refreshes the coding table and schedules the next refresh.
    #[cold]
    fn rebuild(&mut self) {
        self.table.rebuild(&self.counts, self.total);
        self.interval = (self.interval * 2).min(MAX_REBUILD_INTERVAL);
        self.until_rebuild = self.interval;
    }

    /// Halves every count, rounding up so none reaches zero.
    #[cold]
    fn halve(&mut self) {
        let mut total = 0;
        for c in self.counts.iter_mut() {
            *c = (*c + 1) >> 1;
            total += *c;
        }
        self.total = total;
    }
}

/// One [`AdaptiveModel`] per context, all over the same alphabet: e.g.
/// the CLERS symbols with the previous symbol as context (5 × 5).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ContextModel {
    models: Vec<AdaptiveModel>,
}

impl ContextModel {
    /// `contexts` fresh models over `symbols` symbols each.
    ///
    /// # Panics
    ///
    /// If `contexts` is zero or `symbols` is out of range (see
    /// [`AdaptiveModel::new`]).
    pub fn new(contexts: usize, symbols: u32) -> Self {
        assert!(contexts > 0, "a context model needs at least one context");
        ContextModel {
            models: vec![AdaptiveModel::new(symbols); contexts],
        }
    }

    /// Number of contexts.
    #[inline]
    pub fn contexts(&self) -> usize {
        self.models.len()
    }

    /// The model of context `context`, to code with.
    ///
    /// # Panics
    ///
    /// If `context >= self.contexts()`.
    #[inline(always)]
    pub fn get(&mut self, context: usize) -> &mut AdaptiveModel {
        &mut self.models[context]
    }

    /// The model of context `context`, to inspect (e.g. to estimate costs).
    ///
    /// # Panics
    ///
    /// If `context >= self.contexts()`.
    #[inline]
    pub fn get_ref(&self, context: usize) -> &AdaptiveModel {
        &self.models[context]
    }
}

/// The quantile `offset / scale` of the range decoder's interval
/// (`coder::Decoder`), `None` when it is `2^PRECISION` or more (or the
/// scale zero, which the coder's invariants rule out: no panic may come
/// from the data). Here, below the coder, so that models and the coder's
/// raw bits share it without the two files importing each other.
#[inline(always)]
pub(super) fn quantile(offset: u64, scale: u64) -> Option<u32> {
    let q = offset.checked_div(scale)?;
    (q < 1 << PRECISION).then_some(q as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_keep_their_invariants() {
        for n in [2, 3, 5, 17, 256, 1000, 4096] {
            let mut m = AdaptiveModel::new(n);
            // A very skewed history: symbol 0 dominates, the top symbol too.
            for i in 0..200_000u32 {
                let s = if i % 97 == 0 { n - 1 } else { 0 };
                m.update(s);
                assert!(m.total <= COUNT_LIMIT);
            }
            let t = m.table();
            assert_eq!(t.cum[0], 0);
            assert_eq!(t.cum[n as usize], TOTAL);
            for s in 0..n {
                assert!(t.frequency(s) >= 1);
            }
            // Every quantile maps to the symbol whose interval holds it.
            for q in (0..TOTAL).step_by(7).chain([TOTAL - 1]) {
                let (s, left, f) = t.find(q);
                assert!(left <= q && q < left + f, "n={n} q={q}");
                assert_eq!(left, t.cum[s as usize]);
            }
        }
    }

    #[test]
    fn lookup_bits_are_bounded() {
        assert_eq!(lookup_bits(2), MIN_LOOKUP_BITS);
        assert_eq!(lookup_bits(5), MIN_LOOKUP_BITS);
        assert_eq!(lookup_bits(256), 10);
        assert_eq!(lookup_bits(4096), 14);
    }
}
