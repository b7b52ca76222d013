//! The `GEOM` stream of the SwingWrapper mode: one angle residual per C
//! tip, range coded (format-spec/05-swing.md, "GEOM").
//!
//! Every code q is sent as s = (q − q_pred) mod 2^K read as a signed
//! K-bit number, zig-zag mapped to z (0, −1, 1, −2, … → 0, 1, 2, 3, …)
//! and split like the lossless residuals (`geometry::lossless`): the bit
//! length ℓ of z in an adaptive model chosen by context, the (up to) two
//! bits below the leading one in a model per length, the rest raw.
//!
//! Context of ℓ: the larger of the lengths that made the gate's two
//! vertices (0 for a first-triangle vertex). Large residuals cluster where
//! the surface bends sharply or the retiling is irregular, and a gate's
//! vertices are the nearest decoded evidence of that. Measured on
//! emulated retilings of spheres, bumpy spheres and ellipsoids at K = 8
//! (swing tests, `measure_residual_schemes`), this saves up to 0.25 bits
//! per angle over the previous angle's length as context and 0.6–0.9 over
//! one adaptive model of all 2^K residuals; predicting from the angle
//! that made GL instead of the global mean only paid at K = 10.
//!
//! The models, the order of the fields and the walk over the triangles
//! must match between [`encode`] and [`decode`] exactly.

use crate::prelude::*;

#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{AdaptiveModel, ContextModel, Decoder};
use crate::{CornerTable, Error, FormatError, Malformed};

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// The models of one stream, fresh at its start.
struct Models {
    /// `LEN[ctx]`, ctx = 0 … K, over the lengths 0 … K.
    len: ContextModel,
    /// `MAN[ℓ]` for ℓ = 2 … K (entries 0 and 1 unused): the
    /// `min(ℓ − 1, 2)` bits below the leading one.
    man: Vec<AdaptiveModel>,
}

impl Models {
    fn new(bits: u8) -> Models {
        let k = u32::from(bits);
        Models {
            len: ContextModel::new(k as usize + 1, k + 1),
            man: (0..=k)
                .map(|l| AdaptiveModel::new(if l <= 2 { 2 } else { 4 }))
                .collect(),
        }
    }
}

/// Calls `f(k, tip, gl, gr)` for the k-th C triangle of `table` in
/// triangle order, with its new vertex and its gate's vertices. Triangles whose corners 3t+1 and
/// 3t+2 are not yet numbered start a component (three new vertices);
/// one whose tip is the next vertex is a C. The decoded table is numbered
/// this way; anything else is an error.
pub(super) fn for_each_c(
    table: &CornerTable,
    mut f: impl FnMut(usize, usize, usize, usize) -> Result<(), Error>,
) -> Result<(), Error> {
    for_each_c_behind(table, |k, tip, gl, gr, _| f(k, tip, gl, gr))
}

/// [`for_each_c`], also with the vertex behind the gate (across it from
/// the tip; `usize::MAX` where the table has none).
pub(super) fn for_each_c_behind(
    table: &CornerTable,
    mut f: impl FnMut(usize, usize, usize, usize, usize) -> Result<(), Error>,
) -> Result<(), Error> {
    let v = table.vertices();
    let (mut next, mut k) = (0usize, 0usize);
    for (i, t) in v.chunks_exact(3).enumerate() {
        let [a, b, c] = [t[0].idx(), t[1].idx(), t[2].idx()];
        if b >= next {
            if (a, b, c) != (next, next + 1, next + 2) {
                return Err(bad("vertices are not numbered in coding order"));
            }
            next += 3;
        } else if a == next {
            if c >= next {
                return Err(bad("a C tip is built on vertices not yet placed"));
            }
            let o = table.opposite(crate::CornerId(3 * i as u32));
            let behind = if o.is_some() && o.idx() < v.len() {
                v[o.idx()].idx()
            } else {
                usize::MAX
            };
            f(k, a, b, c, behind)?;
            k += 1;
            next += 1;
        }
    }
    Ok(())
}

/// z → signed residual: 0, 1, 2, 3, … → 0, −1, 1, −2, ….
fn unzigzag(z: u32) -> i64 {
    if z & 1 == 0 {
        i64::from(z >> 1)
    } else {
        -i64::from(z >> 1) - 1
    }
}

/// Bit length: 0 for 0, else one plus the index of the highest set bit.
#[cfg(feature = "encoder")]
pub(super) fn bit_length(z: u32) -> u32 {
    u32::BITS - z.leading_zeros()
}

/// The circular mean of the codes, on the code grid: the q maximizing
/// C·cos(qΔ) + S·sin(qΔ), with C and S the sums of the codes' cosines and
/// sines in order (the first such q on ties; 0 for no codes). Encoder
/// side; only the result is stored.
#[cfg(feature = "encoder")]
pub(crate) fn predict(codes: &[u32], angles: &super::AngleTable) -> u32 {
    let (mut c, mut s) = (0.0, 0.0);
    for &q in codes {
        c += angles.cos(q);
        s += angles.sin(q);
    }
    let mut best = (0, f64::NEG_INFINITY);
    for q in 0..angles.codes() {
        let score = c * angles.cos(q) + s * angles.sin(q);
        if score > best.1 {
            best = (q, score);
        }
    }
    best.0
}

/// The GEOM coder, one C tip at a time, in coding order: [`encode`]'s
/// state, the mirror of [`Reader`] (which the `CLRF` pass of
/// `swing::forward` also drives).
#[cfg(feature = "encoder")]
pub(super) struct Writer {
    enc: Encoder,
    models: Models,
    lengths: Vec<u8>,
    n: i64,
    predicted: u32,
}

#[cfg(feature = "encoder")]
impl Writer {
    /// A fresh stream for a mesh of `vertices` vertices.
    pub(super) fn new(vertices: usize, bits: u8, predicted: u32) -> Writer {
        Writer {
            enc: Encoder::new(),
            models: Models::new(bits),
            lengths: vec![0; vertices],
            n: 1i64 << bits,
            predicted,
        }
    }

    /// Codes `q`, the code of C tip `tip` on the gate `gl`, `gr` (vertex
    /// numbers below the mesh's count, `tip` the next one).
    pub(super) fn put(&mut self, q: u32, tip: usize, gl: usize, gr: usize) -> Result<(), Error> {
        if tip >= self.lengths.len() || gl >= tip || gr >= tip || i64::from(q) >= self.n {
            return Err(bad("an angle code or a C tip out of range"));
        }
        let mut s = (i64::from(q) - i64::from(self.predicted)).rem_euclid(self.n);
        if s >= self.n / 2 {
            s -= self.n;
        }
        let z = if s >= 0 { 2 * s } else { -2 * s - 1 } as u32;
        let l = bit_length(z);
        let ctx = self.lengths[gl].max(self.lengths[gr]) as usize;
        self.enc.encode(self.models.len.get(ctx), l);
        if l >= 2 {
            let top = (l - 1).min(2);
            let below = l - 1 - top;
            self.enc.encode(
                &mut self.models.man[l as usize],
                (z >> below) & ((1 << top) - 1),
            );
            if below > 0 {
                self.enc.encode_bits(z & ((1 << below) - 1), below);
            }
        }
        self.lengths[tip] = l as u8;
        Ok(())
    }

    pub(super) fn finish(self) -> Vec<u8> {
        self.enc.finish()
    }
}

/// The GEOM decoder, the mirror of [`Writer`].
pub(super) struct Reader<'a> {
    dec: Decoder<'a>,
    models: Models,
    lengths: Vec<u8>,
    n: i64,
    predicted: u32,
}

impl<'a> Reader<'a> {
    /// The stream `bytes` of a mesh of `vertices` vertices (the caller
    /// has checked that count against the limits).
    pub(super) fn new(
        bytes: &'a [u8],
        vertices: usize,
        bits: u8,
        predicted: u32,
    ) -> Result<Reader<'a>, Error> {
        Ok(Reader {
            dec: Decoder::new(bytes)?,
            models: Models::new(bits),
            lengths: vec![0; vertices],
            n: 1i64 << bits,
            predicted,
        })
    }

    /// The code of C tip `tip` on the gate `gl`, `gr`.
    pub(super) fn get(&mut self, tip: usize, gl: usize, gr: usize) -> Result<u32, Error> {
        if tip >= self.lengths.len() || gl >= tip || gr >= tip {
            return Err(bad("a C tip is built on vertices not yet placed"));
        }
        let ctx = self.lengths[gl].max(self.lengths[gr]) as usize;
        let l = self.dec.decode(self.models.len.get(ctx))?;
        let z = match l {
            0 | 1 => l,
            _ => {
                let top = (l - 1).min(2);
                let below = l - 1 - top;
                let hi = self.dec.decode(&mut self.models.man[l as usize])?;
                let low = if below > 0 {
                    self.dec.decode_bits(below)?
                } else {
                    0
                };
                (((1 << top) | hi) << below) | low
            }
        };
        self.lengths[tip] = l as u8;
        Ok((i64::from(self.predicted) + unzigzag(z)).rem_euclid(self.n) as u32)
    }

    /// Checks that the stream ends where its encoder finished it.
    pub(super) fn finish(self) -> Result<(), Error> {
        self.dec.finish()
    }
}

/// Codes the C tips' codes (all below 2^K) of the decoded `table`.
#[cfg(feature = "encoder")]
pub(crate) fn encode(
    table: &CornerTable,
    codes: &[u32],
    bits: u8,
    predicted: u32,
) -> Result<Vec<u8>, Error> {
    let mut w = Writer::new(table.vertex_count(), bits, predicted);
    let mut used = 0;
    for_each_c(table, |k, tip, gl, gr| {
        used += 1;
        let q = *codes.get(k).ok_or(bad("fewer angle codes than C tips"))?;
        w.put(q, tip, gl, gr)
    })?;
    if used != codes.len() {
        return Err(bad("more angle codes than C tips"));
    }
    Ok(w.finish())
}

/// Decodes `count` codes for the C tips of the decoded `table`.
pub(crate) fn decode(
    table: &CornerTable,
    bytes: &[u8],
    count: usize,
    bits: u8,
    predicted: u32,
) -> Result<Vec<u32>, Error> {
    let mut r = Reader::new(bytes, table.vertex_count(), bits, predicted)?;
    let mut codes = Vec::with_capacity(count);
    for_each_c(table, |_, tip, gl, gr| {
        if codes.len() == count {
            return Err(bad("more C tips than angle codes"));
        }
        codes.push(r.get(tip, gl, gr)?);
        Ok(())
    })?;
    if codes.len() != count {
        return Err(bad("fewer C tips than angle codes"));
    }
    r.finish()?;
    Ok(codes)
}
