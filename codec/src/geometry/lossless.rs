//! Lossless coding of quantized positions given their predictions.
//!
//! Per vertex `k`, in decoding order:
//!
//! 1. **Subset** (only for a [`Prediction::Multi`] with `n ≥ 2` selectable
//!    parallelograms): which non-empty subset of them to average, as one
//!    symbol `subset − 1` of an adaptive model over `2^n − 1` symbols, one
//!    model per `n`. The encoder picks the subset with the smallest
//!    estimated cost (its own code, residuals included); the decoder just
//!    reads it. This is Draco's "constrained multi-parallelogram" idea
//!    (choosing parallelograms explicitly) with our own coding of the
//!    choice; on the bunny it saves about 0.9 bits/vertex.
//! 2. **Residual** per axis x, y, z: `r = (q − pred) mod 2^bits`, read as a
//!    signed number in `[−2^(bits−1), 2^(bits−1))` — Draco's wrap-around,
//!    so every residual fits in `bits` bits whatever the prediction — then
//!    zig-zagged to `z` (0, −1, 1, −2, ... → 0, 1, 2, 3, ...).
//! 3. `z` is coded as its bit length `L` (0 for z = 0, else the position
//!    of its leading one, `1..=bits`) with an adaptive model chosen by the
//!    axis and a *neighbourhood length*; then the `L − 1` bits below the
//!    leading one: the top two with an adaptive model per `L` (they are
//!    skewed towards 0 for a peaked distribution), the rest raw.
//!
//! The neighbourhood length of an axis is the rounded mean of the lengths
//! `L` that the vertices the prediction uses (`from`, or `a`, `b`,
//! `opposite` of each selectable parallelogram) had on that axis, averaged
//! for y with x's `L` of this vertex, and for z with x's and y's: a vertex
//! in a noisy region has large residuals, and so do its axes together.
//!
//! Measured on the shared corpus (bits per vertex of this section; the
//! corpus test prints the first three rows):
//!
//! | order, predictions                                | bunny, 11 bits | horse, 12 bits |
//! |---------------------------------------------------|---------------:|---------------:|
//! | breadth-first, one parallelogram (or delta)        | 9.28           | 10.65          |
//! | breadth-first, all parallelograms, subset coded    | 8.22           |  9.22          |
//! | `traverse` order, all parallelograms, subset coded    | 7.79        |  8.76          |
//!
//! Design measurements (bunny, `traverse` order): averaging all
//! parallelograms without coding a subset 8.69; subset chosen by L1 error
//! instead of estimated cost 7.83; also offering 3:1 weighted averages of
//! two parallelograms 7.82 (no gain, so not offered). The neighbourhood
//! context beats the previous vertex's lengths (7.98) and the axis alone;
//! modelling the top mantissa bit gains 0.1–0.2 bits/vertex, the second
//! 0.03–0.06, a third nothing.
//!
//! **`GEOF` (format 1.1, [`Coding::Offsets`]), a rule beyond the
//! sources.** A `Multi` average is rounded to the grid, and where the
//! exact average fell inside its cell is known to both sides: on the
//! point, a third or a quarter of a step below or above, or half a step
//! below (ties round up). Where residuals are about a step (dense scans,
//! subdivision surfaces, low `qp`) that says which small residual is the
//! likelier, so `GEOF` codes lengths at neighbourhood levels ≤ 1, and
//! every mantissa, in contexts of that offset group, and turns the
//! residual's sign when the average lies above, so that its side gets
//! the shorter zig-zag code. The encoder also breaks subset ties towards
//! more parallelograms (see the encoder). Measured (bytes of the section,
//! `GEOM` → `GEOF`): bunny-1m 11 bits 281,288 → 227,212, 8 bits 224,884 →
//! 179,340; horse 8 bits 22,056 → 19,020; bunny 8 bits 18,496 → 16,820;
//! 11 and 14 bits on the 35k–50k-vertex scans within ±1.3% either way,
//! fandisk at 8 bits +7.7% — which is why the lossless mode writes
//! whichever of the two is shorter.
//!
//! Both sides keep the same model state and update it in the same order;
//! every step marked "must match the encoder exactly" is shared code or a
//! mirror of the encoder's step.
//!
//! Hostile input: each prediction is checked before use (a reference to a
//! vertex not yet decoded is [`Error::Format`]), decoded lengths never
//! exceed `bits`, so decoded coordinates are always in the grid, and
//! memory is bounded by the number of predictions.

use crate::prelude::*;

use super::predict::{
    mean_in_grid, offsets, parallelogram, sum_of, Prediction, Predictions, MAX_SELECTABLE,
};
use super::quantize::{max_value, MAX_BITS};
#[cfg(doc)]
use super::traverse::traverse;
use super::traverse::traverse_except;
use crate::entropy::{AdaptiveModel, ContextModel, Decoder, Encoder, PRECISION};
use crate::mesh::CornerTable;
use crate::{Error, FormatError, Malformed};

/// Mantissa bits below the leading one coded adaptively (the rest are raw).
const MODELED_MANTISSA_BITS: u32 = 2;

/// Which section's coding: format 1.0's `GEOM` or 1.1's `GEOF`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coding {
    /// `GEOM`: lengths in contexts of axis and neighbourhood level.
    Plain,
    /// `GEOF`: also in contexts of where the exact mean of the averaged
    /// parallelograms lies against the grid point it rounds to, with the
    /// residual's sign turned so that the mean's side comes first.
    Offsets,
}

/// Offset groups of [`Coding::offsets`]: on the grid point, a third or a
/// quarter off (oriented), half off.
const GROUPS: usize = 3;

/// The offset groups split the length contexts only at neighbourhood
/// levels up to this one (residuals of about a step): where residuals
/// are larger a fraction of a step hardly moves them, and three times the
/// contexts only thin the statistics. Measured (`GEOF` bytes, levels ≤ 1
/// against every level; ≤ 0 is clearly worse, bunny-1m 11 bits 239,508):
/// at 8 bits horse 19,328 → 19,020, homer 4,352 → 4,332, bunny-1m
/// 179,236 → 179,340; at 11 bits spot 5,296 → 5,236, homer 10,192 →
/// 10,008, bunny 34,064 → 34,344, bunny-1m 226,968 → 227,212.
const OFFSET_LEVELS: u32 = 1;

#[inline]
fn group(offset: u8) -> usize {
    match offset {
        0 => 0,
        1 | 2 => 1,
        _ => 2,
    }
}

/// The model state both sides keep. Must match the encoder exactly: the
/// encoder and the decoder create it the same way and update it after
/// every vertex in the same way.
struct Models {
    bits: u8,
    /// Bit lengths, per axis and neighbourhood length (`3 × (bits + 1)`
    /// contexts over `bits + 1` symbols).
    lengths: ContextModel,
    /// Top mantissa bits, per offset group and length `L` (entries 0 and
    /// 1 of each group unused).
    mantissa: Vec<AdaptiveModel>,
    /// Subset choice, for 2, 3, 4 selectable parallelograms.
    subsets: [AdaptiveModel; MAX_SELECTABLE - 1],
    /// Residual bit lengths of the vertices decoded so far.
    lens: Vec<[u8; 3]>,
    /// Neighbourhood length per axis of the current vertex.
    around: [u32; 3],
}

impl Models {
    fn new(bits: u8, vertices: usize, coding: Coding) -> Self {
        let symbols = bits as u32 + 1;
        let groups = if coding == Coding::Offsets { GROUPS } else { 1 };
        Models {
            bits,
            lengths: ContextModel::new(groups * 3 * symbols as usize, symbols),
            mantissa: (0..groups)
                .flat_map(|_| 0..=bits as u32)
                .map(|len| AdaptiveModel::new(1 << modeled_bits(len).max(1)))
                .collect(),
            subsets: core::array::from_fn(|i| AdaptiveModel::new((1 << (i + 2)) - 1)),
            lens: Vec::with_capacity(vertices),
            around: [0; 3],
        }
    }

    /// Sets the neighbourhood lengths for a vertex predicted by `p` (which
    /// passed [`Prediction::check`]).
    fn begin(&mut self, p: &Prediction, parallelograms: &[[u32; 3]]) {
        let mut sum = [0u32; 3];
        let mut n = 0u32;
        let mut add = |v: u32| {
            let l = self.lens[v as usize];
            for k in 0..3 {
                sum[k] += l[k] as u32;
            }
            n += 1;
        };
        match *p {
            Prediction::None => {}
            Prediction::Delta { from } => add(from),
            Prediction::Parallelogram { a, b, opposite } => {
                add(a);
                add(b);
                add(opposite);
            }
            Prediction::Multi { .. } => {
                for &[a, b, opposite] in p.selectable(parallelograms) {
                    add(a);
                    add(b);
                    add(opposite);
                }
            }
        }
        self.around = if n == 0 {
            [self.bits as u32 / 2; 3]
        } else {
            sum.map(|s| (s + n / 2) / n)
        };
    }

    /// The length model's context for `axis`, given the lengths already
    /// coded for this vertex's earlier axes.
    #[inline]
    fn context(&self, axis: usize, coded: &[u32; 3], group: usize) -> usize {
        let level = match axis {
            0 => self.around[0],
            1 => (self.around[1] + coded[0]).div_ceil(2),
            _ => (self.around[2] + coded[0] + coded[1] + 1) / 3,
        };
        let group = if level <= OFFSET_LEVELS { group } else { 0 };
        (group * 3 + axis) * (self.bits as usize + 1) + level as usize
    }

    /// The mantissa model for length `len` in offset group `group`.
    #[inline]
    fn mantissa(&mut self, group: usize, len: u32) -> &mut AdaptiveModel {
        &mut self.mantissa[group * (self.bits as usize + 1) + len as usize]
    }

    fn end(&mut self, coded: [u32; 3]) {
        self.lens.push(coded.map(|l| l as u8));
    }
}

/// How many of the `len − 1` mantissa bits are coded adaptively.
#[inline]
fn modeled_bits(len: u32) -> u32 {
    len.saturating_sub(1).min(MODELED_MANTISSA_BITS)
}

/// Bit length of `z`: 0 for 0, else 1 + the index of its leading one.
#[inline]
fn length(z: u32) -> u32 {
    u32::BITS - z.leading_zeros()
}

/// The zig-zagged wrap-around residual of `q` against `pred`.
/// With `flip`, the residual's sign is turned first (offset 2: the mean
/// lies above the prediction, so positive residuals are the likelier).
#[inline]
fn residual(q: u32, pred: u32, bits: u8, flip: bool) -> u32 {
    let r = q.wrapping_sub(pred) & max_value(bits);
    // Sign-extend from `bits` bits: values ≥ 2^(bits−1) are negative.
    let shift = 32 - bits as u32;
    let mut s = ((r << shift) as i32) >> shift;
    if flip {
        // −2^(bits−1) becomes 2^(bits−1), which wraps to the same
        // residual; zig-zag keeps it within `bits` bits either way.
        s = s.wrapping_neg();
        if s == 1 << (bits - 1) {
            s = -s;
        }
    }
    ((s << 1) ^ (s >> 31)) as u32
}

/// Inverse of [`residual`]: the grid coordinate `pred + s mod 2^bits`.
/// Must match the encoder exactly.
#[inline]
fn reconstruct(z: u32, pred: u32, bits: u8, flip: bool) -> u32 {
    let mut s = ((z >> 1) as i32) ^ -((z & 1) as i32);
    if flip {
        s = s.wrapping_neg();
    }
    pred.wrapping_add(s as u32) & max_value(bits)
}

/// Cost of coding `symbol` with `model`, in 1/16 bits, from its quantized
/// frequency: `16·(PRECISION − log2 f)` with a 4-bit linear fraction of
/// the logarithm. Integer-only, so the encoder's choices are the same on
/// every platform.
fn cost(model: &AdaptiveModel, symbol: u32) -> u32 {
    let f = model.table().frequency(symbol).max(1);
    let l = 31 - f.leading_zeros();
    let frac = if l >= 4 { f >> (l - 4) } else { f << (4 - l) } & 15;
    16 * PRECISION as u32 - (16 * l + frac)
}

fn check_bits(bits: u8) -> Result<(), Error> {
    if (1..=MAX_BITS).contains(&bits) {
        Ok(())
    } else {
        Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadHeader("quantization bits out of range"),
        )))
    }
}

/// Encodes quantized positions, in decoding order, with their predictions,
/// in format 1.0's coding ([`Coding::V1_0`]).
///
/// # Panics
///
/// If `quantized` and `predictions` differ in length, a prediction fails
/// [`Prediction::check`], a coordinate is outside the grid, or `bits` is
/// not in `1..=24` — all bugs in the caller.
pub fn encode_positions(
    quantized: &[[u32; 3]],
    predictions: &Predictions,
    bits: u8,
    enc: &mut Encoder,
) {
    encode_positions_as(quantized, predictions, bits, Coding::Plain, enc)
}

/// The predicted point of a vertex, the offsets of the exact mean against
/// it, and the subset coded for it (if any).
struct Predicted {
    point: [u32; 3],
    offsets: [u8; 3],
}

impl Predicted {
    /// The prediction of the parallelograms `points` selected by `subset`.
    #[inline]
    fn of(points: &[[i64; 3]], subset: u32, bits: u8, coding: Coding) -> Predicted {
        let (sum, n) = sum_of(points, subset);
        let point = mean_in_grid(sum, n, bits);
        let offsets = if coding == Coding::Offsets {
            offsets(sum, n, point)
        } else {
            [0; 3]
        };
        Predicted { point, offsets }
    }

    /// The coded value of grid coordinate `q` on `axis`, and its offset
    /// group.
    #[inline]
    fn residual(&self, axis: usize, q: u32, bits: u8) -> (u32, usize) {
        let o = self.offsets[axis];
        (residual(q, self.point[axis], bits, o == 2), group(o))
    }

    /// Inverse of [`Predicted::residual`]. Must match the encoder exactly.
    #[inline]
    fn reconstruct(&self, axis: usize, z: u32, bits: u8) -> u32 {
        reconstruct(z, self.point[axis], bits, self.offsets[axis] == 2)
    }

    /// A prediction without offsets (none, delta, one parallelogram).
    fn plain(point: [u32; 3]) -> Predicted {
        Predicted {
            point,
            offsets: [0; 3],
        }
    }
}

/// [`encode_positions`] in the coding `coding`.
///
/// # Panics
///
/// As [`encode_positions`].
pub fn encode_positions_as(
    quantized: &[[u32; 3]],
    predictions: &Predictions,
    bits: u8,
    coding: Coding,
    enc: &mut Encoder,
) {
    assert!(check_bits(bits).is_ok(), "quantization bits out of range");
    assert_eq!(
        quantized.len(),
        predictions.len(),
        "one prediction per vertex"
    );
    let max = max_value(bits);
    let paras = &predictions.parallelograms[..];
    let mut m = Models::new(bits, quantized.len(), coding);
    for (k, (q, p)) in quantized.iter().zip(&predictions.vertices).enumerate() {
        assert!(q.iter().all(|&c| c <= max), "coordinate outside the grid");
        if let Err(e) = p.check(k, paras) {
            panic!("invalid prediction for vertex {k}: {e}");
        }
        let decoded = &quantized[..k];
        m.begin(p, paras);

        // Step 1: the subset, chosen by estimated cost.
        let list = p.selectable(paras);
        let pred = if list.len() >= 2 {
            let mut points = [[0i64; 3]; MAX_SELECTABLE];
            for (p, &abo) in points.iter_mut().zip(list) {
                *p = parallelogram(decoded, abo);
            }
            let points = &points[..list.len()];
            let model = &m.subsets[list.len() - 2];
            let mut best = ((u32::MAX, 0), 0, Predicted::plain([0; 3]));
            for subset in 1u32..(1 << list.len()) {
                // The point `average(decoded, list, subset, bits)` gives.
                let pred = Predicted::of(points, subset, bits, coding);
                let mut bits16 = cost(model, subset - 1);
                let mut coded = [0u32; 3];
                for axis in 0..3 {
                    let (z, g) = pred.residual(axis, q[axis], bits);
                    let len = length(z);
                    let ctx = m.context(axis, &coded, g);
                    bits16 += cost(m.lengths.get_ref(ctx), len) + 16 * len.saturating_sub(1);
                    coded[axis] = len;
                }
                // Ties: `GEOM` takes the first subset (its files stay as
                // they were); `GEOF` the one with more parallelograms.
                // Where residuals are a step or less many subsets tie, and
                // taking the first locks the subset model onto a single
                // parallelogram, the noisiest prediction (bunny-1m at 11
                // bits: 276,300 against 227,212 bytes). Breaking ties by
                // the smaller residual instead fits the noise and spreads
                // the subset model (227,724; on a dense smooth sphere at
                // 8 bits 20,252 against 16,328).
                let key = match coding {
                    Coding::Plain => (bits16, 0),
                    Coding::Offsets => (bits16, MAX_SELECTABLE as u32 - subset.count_ones()),
                };
                if key < best.0 {
                    best = (key, subset, pred);
                }
            }
            enc.encode(&mut m.subsets[list.len() - 2], best.1 - 1);
            best.2
        } else {
            Predicted::plain(p.predict(decoded, paras, bits))
        };

        // Steps 2–3: the residuals.
        let mut coded = [0u32; 3];
        for axis in 0..3 {
            let (z, g) = pred.residual(axis, q[axis], bits);
            let len = length(z);
            let ctx = m.context(axis, &coded, g);
            enc.encode(m.lengths.get(ctx), len);
            if len >= 2 {
                let below = len - 1;
                let top = modeled_bits(len);
                let raw = below - top;
                enc.encode(m.mantissa(g, len), (z >> raw) & ((1 << top) - 1));
                enc.encode_bits(z & ((1 << raw) - 1), raw);
            }
            coded[axis] = len;
        }
        m.end(coded);
    }
}

/// Decodes what [`encode_positions`] wrote: `out` is cleared and receives
/// one grid point per prediction, in decoding order.
///
/// Fails with [`Error::Format`] if `bits` is not in `1..=24`, a prediction
/// refers to a vertex not decoded before it, or the entropy decoder
/// reports invalid data. Never panics; allocates `predictions.len()`
/// entries.
pub fn decode_positions(
    predictions: &Predictions,
    bits: u8,
    dec: &mut Decoder,
    out: &mut Vec<[u32; 3]>,
) -> Result<(), Error> {
    decode_positions_as(predictions, bits, Coding::Plain, dec, out)
}

/// Decodes what [`encode_positions_as`] wrote with the same `coding`.
/// Fails, never panics and allocates as [`decode_positions`].
pub fn decode_positions_as(
    predictions: &Predictions,
    bits: u8,
    coding: Coding,
    dec: &mut Decoder,
    out: &mut Vec<[u32; 3]>,
) -> Result<(), Error> {
    let mut pd = PositionDecoder::new(bits, coding, dec, predictions.len())?;
    let paras = &predictions.parallelograms[..];
    for &p in &predictions.vertices {
        pd.next(p, paras)?;
    }
    *out = pd.into_points();
    Ok(())
}

/// The decoder of [`decode_positions_as`] one vertex at a time, for a
/// traversal that hands over each prediction as it makes it
/// (`traverse_visiting`).
pub struct PositionDecoder<'d, 'b> {
    bits: u8,
    coding: Coding,
    dec: &'d mut Decoder<'b>,
    m: Models,
    out: Vec<[u32; 3]>,
}

impl<'d, 'b> PositionDecoder<'d, 'b> {
    /// A decoder for about `vertices` vertices (a capacity, not a limit).
    /// Fails if `bits` is not in `1..=24`.
    pub fn new(
        bits: u8,
        coding: Coding,
        dec: &'d mut Decoder<'b>,
        vertices: usize,
    ) -> Result<Self, Error> {
        check_bits(bits)?;
        Ok(PositionDecoder {
            bits,
            coding,
            dec,
            m: Models::new(bits, vertices, coding),
            out: Vec::with_capacity(vertices),
        })
    }

    /// Decodes the next vertex, predicted by `p` (whose `Multi` entries
    /// index `paras`).
    pub fn next(&mut self, p: Prediction, paras: &[[u32; 3]]) -> Result<(), Error> {
        let (bits, coding) = (self.bits, self.coding);
        let (m, out) = (&mut self.m, &mut self.out);
        p.check(out.len(), paras)?;
        m.begin(&p, paras);

        // Step 1, mirrored: must match the encoder exactly.
        let list = p.selectable(paras);
        let pred = if list.len() >= 2 {
            let mut points = [[0i64; 3]; MAX_SELECTABLE];
            for (p, &abo) in points.iter_mut().zip(list) {
                *p = parallelogram(out, abo);
            }
            let points = &points[..list.len()];
            let subset = self.dec.decode(&mut m.subsets[list.len() - 2])? + 1;
            Predicted::of(points, subset, bits, coding)
        } else {
            Predicted::plain(p.predict(out, paras, bits))
        };

        // Steps 2–3, mirrored: must match the encoder exactly.
        let mut q = [0u32; 3];
        let mut coded = [0u32; 3];
        for axis in 0..3 {
            let g = group(pred.offsets[axis]);
            let ctx = m.context(axis, &coded, g);
            let len = self.dec.decode(m.lengths.get(ctx))?;
            let z = if len >= 2 {
                let below = len - 1;
                let top = modeled_bits(len);
                let raw = below - top;
                let high = (1 << top) | self.dec.decode(m.mantissa(g, len))?;
                (high << raw) | self.dec.decode_bits(raw)?
            } else {
                len
            };
            q[axis] = pred.reconstruct(axis, z, bits);
            coded[axis] = len;
        }
        m.end(coded);
        out.push(q);
        Ok(())
    }

    /// The grid points decoded, in decoding order.
    pub fn into_points(self) -> Vec<[u32; 3]> {
        self.out
    }
}

/// Encodes the quantized positions of a mesh, one per vertex of `table`
/// (entries of excluded vertices are ignored), in the order and with the
/// predictions of [`traverse_except`]`(table, excluded)`.
///
/// Fails only if `table` is invalid (see [`traverse`]).
///
/// # Panics
///
/// As [`encode_positions`], or if `quantized` does not hold one point per
/// vertex of `table`.
pub fn encode_mesh_positions(
    table: &CornerTable,
    excluded: &[bool],
    quantized: &[[u32; 3]],
    bits: u8,
    enc: &mut Encoder,
) -> Result<(), Error> {
    assert_eq!(
        quantized.len(),
        table.vertex_count(),
        "one point per vertex"
    );
    let t = traverse_except(table, excluded)?;
    let ordered: Vec<[u32; 3]> = t.order.iter().map(|v| quantized[v.idx()]).collect();
    encode_positions(&ordered, &t.predictions, bits, enc);
    Ok(())
}

/// Decodes what [`encode_mesh_positions`] wrote for the same `table` and
/// `excluded`: `out` receives one grid point per vertex of `table`,
/// indexed by vertex (`[0, 0, 0]` for excluded ones).
pub fn decode_mesh_positions(
    table: &CornerTable,
    excluded: &[bool],
    bits: u8,
    dec: &mut Decoder,
    out: &mut Vec<[u32; 3]>,
) -> Result<(), Error> {
    let t = traverse_except(table, excluded)?;
    let mut ordered = Vec::new();
    decode_positions(&t.predictions, bits, dec, &mut ordered)?;
    out.clear();
    out.resize(table.vertex_count(), [0; 3]);
    for (v, q) in t.order.iter().zip(ordered) {
        out[v.idx()] = q;
    }
    Ok(())
}
