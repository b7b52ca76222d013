//! The `RADS` stream of the SwingWrapper mode (format 1.1): a radius
//! code per C tip, so that a tip can sit anywhere on its gate's
//! bisecting plane, not only on the circle — on a crease of the input
//! (format-spec/05-swing.md, "RADS"; issue 21, retiling that respects
//! creases).
//!
//! The thesis fixes every tip on the circle of radius r around its gate's
//! midpoint, so one angle places it. A sharp edge of the input crosses
//! that plane at one point, generally off the circle: the tip then lands
//! beside the crease and the retiled mesh chamfers it. With a radius code
//! j the tip's radius is
//!
//! ```text
//! r_j = r_ℓ · (1 + j·2^(3−K)),    |j| ≤ J = 2^(K−3),   so r_j ∈ [0, 2r_ℓ]
//! ```
//!
//! (r_ℓ the radius after the tip's level, `density`), and the encoder
//! can put the tip where the crease crosses the plane: two consecutive
//! such tips make an edge along the crease, and the Edgebreaker growth
//! then walks along it by itself (`retile::crease`). The radial step is
//! about the angle step's arc (2π·2^−K·r), so both coordinates of a tip
//! are quantized alike. `1 + j·2^(3−K)` is exact in binary64, so the
//! radius is one rounded multiplication, the same in every decoder.
//!
//! Coding, per C tip in the order of `GEOM`: a flag j ≠ 0 in an adaptive
//! model whose context is how many of the gate's two vertices had one and
//! whether the vertex behind the gate had ([`context`]: crease tips
//! follow each other along a crease and are rare elsewhere); then, if
//! set, the sign as one raw bit, and m = |j| − 1 as its bit length (an
//! adaptive model over 0 … 9) and the bits below the leading one, raw. A
//! file without `RADS` is a file whose every j is 0.
//!
//! Invariants: the walk over the triangles is `residual::for_each_c`'s
//! (with the vertex behind each gate), so [`encode`] and [`decode`] see
//! the same gates in the same order; a decoded |j| above J is an error,
//! never a clamp.

use crate::prelude::*;

#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{AdaptiveModel, ContextModel, Decoder};
use crate::{CornerTable, Error, FormatError, Malformed};

/// Symbols of the bit-length model: lengths 0 … 9 (J − 1 < 2^9 at
/// K = 12).
const LENGTHS: u32 = 10;

/// The largest |j| at `bits` angle bits: J = 2^(K−3).
pub fn max_code(bits: u8) -> i32 {
    1 << (bits.clamp(3, 12) - 3)
}

/// 2^(3−K), the step of the code in units of r_ℓ (exact).
fn step(bits: u8) -> f64 {
    1.0 / f64::from(1u32 << (bits.clamp(3, 12) - 3))
}

/// The radius a tip of level radius `rl` and radius code `j` is built
/// with: `rl · (1 + j·2^(3−K))`, exact but for the one multiplication;
/// `rl` itself for a code of 0.
pub fn apply(bits: u8, rl: f64, j: i32) -> f64 {
    if j == 0 {
        rl
    } else {
        rl * (1.0 + f64::from(j) * step(bits))
    }
}

/// The code nearest to `x` steps of 2^(3−K) (encoder side), within ±J.
#[cfg(feature = "encoder")]
pub fn nearest(bits: u8, x: f64) -> i32 {
    let j = (x / step(bits)).round();
    let limit = max_code(bits);
    if j.is_nan() {
        0
    } else {
        (j as i64).clamp(-i64::from(limit), i64::from(limit)) as i32
    }
}

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// The models of one stream, fresh at its start.
struct Models {
    /// j ≠ 0 or not, by [`context`].
    flag: ContextModel,
    /// Bit length of |j| − 1.
    len: AdaptiveModel,
}

impl Models {
    fn new() -> Models {
        Models {
            flag: ContextModel::new(6, 2),
            len: AdaptiveModel::new(LENGTHS),
        }
    }
}

/// Context of the flag: how many of the gate's vertices had one, and
/// whether the vertex behind the gate had. Along a crease the
/// growth alternates a tip on the crease (gate from the front to the last
/// crease tip, behind it a front vertex) with one beside it (the gate
/// ends at the new crease tip, the previous one behind it).
fn context(marked: &[bool], gl: usize, gr: usize, behind: usize) -> usize {
    let back = marked.get(behind).copied().unwrap_or(false);
    usize::from(marked[gl]) + usize::from(marked[gr]) + 3 * usize::from(back)
}

/// The RADS coder, one C tip at a time, in coding order: the mirror of
/// [`Reader`] (which the `CLRF` pass of `swing::forward` also drives).
#[cfg(feature = "encoder")]
pub(super) struct Writer {
    enc: Encoder,
    models: Models,
    marked: Vec<bool>,
    limit: i32,
}

#[cfg(feature = "encoder")]
impl Writer {
    pub(super) fn new(vertices: usize, bits: u8) -> Writer {
        Writer {
            enc: Encoder::new(),
            models: Models::new(),
            marked: vec![false; vertices],
            limit: max_code(bits),
        }
    }

    /// Codes radius code `j` of C tip `tip` on the gate `gl`, `gr` with
    /// `behind` behind it.
    pub(super) fn put(&mut self, j: i32, [tip, gl, gr, behind]: [usize; 4]) -> Result<(), Error> {
        if tip >= self.marked.len() || gl >= tip || gr >= tip {
            return Err(bad("a C tip out of range"));
        }
        if j.abs() > self.limit {
            return Err(bad("a radius code out of range"));
        }
        let (enc, models) = (&mut self.enc, &mut self.models);
        let ctx = context(&self.marked, gl, gr, behind);
        enc.encode(models.flag.get(ctx), u32::from(j != 0));
        if j != 0 {
            enc.encode_bits(u32::from(j < 0), 1);
            let m = j.unsigned_abs() - 1;
            let len = super::residual::bit_length(m);
            enc.encode(&mut models.len, len);
            if len > 1 {
                enc.encode_bits(m - (1 << (len - 1)), len - 1);
            }
        }
        self.marked[tip] = j != 0;
        Ok(())
    }

    pub(super) fn finish(self) -> Vec<u8> {
        self.enc.finish()
    }
}

/// The RADS decoder, the mirror of [`Writer`].
pub(super) struct Reader<'a> {
    dec: Decoder<'a>,
    models: Models,
    marked: Vec<bool>,
    limit: i32,
}

impl<'a> Reader<'a> {
    /// The stream `bytes` of a mesh of `vertices` vertices (the caller
    /// has checked that count against the limits) at `bits` angle bits.
    pub(super) fn new(bytes: &'a [u8], vertices: usize, bits: u8) -> Result<Reader<'a>, Error> {
        Ok(Reader {
            dec: Decoder::new(bytes)?,
            models: Models::new(),
            marked: vec![false; vertices],
            limit: max_code(bits),
        })
    }

    /// The radius code of C tip `tip` on the gate `gl`, `gr` with
    /// `behind` behind it.
    pub(super) fn get(&mut self, [tip, gl, gr, behind]: [usize; 4]) -> Result<i32, Error> {
        if tip >= self.marked.len() || gl >= tip || gr >= tip {
            return Err(bad("a C tip is built on vertices not yet placed"));
        }
        let (dec, models) = (&mut self.dec, &mut self.models);
        let ctx = context(&self.marked, gl, gr, behind);
        let j = if dec.decode(models.flag.get(ctx))? == 1 {
            let negative = dec.decode_bits(1)? == 1;
            let m = match dec.decode(&mut models.len)? {
                0 => 0,
                1 => 1,
                len => (1u32 << (len - 1)) + dec.decode_bits(len - 1)?,
            };
            // m < 2^9: the model has 10 lengths.
            let magnitude = m as i32 + 1;
            if magnitude > self.limit {
                return Err(bad("a radius code out of range"));
            }
            if negative {
                -magnitude
            } else {
                magnitude
            }
        } else {
            0
        };
        self.marked[tip] = j != 0;
        Ok(j)
    }

    /// Checks that the stream ends where its encoder finished it.
    pub(super) fn finish(self) -> Result<(), Error> {
        self.dec.finish()
    }
}

/// Codes one radius code per C tip of the decoded `table` (each within
/// ±[`max_code`]); returns the stream.
#[cfg(feature = "encoder")]
pub(crate) fn encode(table: &CornerTable, bits: u8, codes: &[i32]) -> Result<Vec<u8>, Error> {
    let mut w = Writer::new(table.vertex_count(), bits);
    let mut used = 0;
    super::residual::for_each_c_behind(table, |k, tip, gl, gr, behind| {
        used += 1;
        let j = *codes.get(k).ok_or(bad("fewer radius codes than C tips"))?;
        w.put(j, [tip, gl, gr, behind])
    })?;
    if used != codes.len() {
        return Err(bad("more radius codes than C tips"));
    }
    Ok(w.finish())
}

/// Decodes `count` radius codes for the C tips of the decoded `table`,
/// in the order of the angle codes.
pub(crate) fn decode(
    table: &CornerTable,
    bits: u8,
    bytes: &[u8],
    count: usize,
) -> Result<Vec<i32>, Error> {
    let mut r = Reader::new(bytes, table.vertex_count(), bits)?;
    let mut out = Vec::with_capacity(count);
    super::residual::for_each_c_behind(table, |_, tip, gl, gr, behind| {
        if out.len() == count {
            return Err(bad("more C tips than radius codes"));
        }
        out.push(r.get([tip, gl, gr, behind])?);
        Ok(())
    })?;
    if out.len() != count {
        return Err(bad("fewer C tips than radius codes"));
    }
    r.finish()?;
    Ok(out)
}

#[cfg(all(test, feature = "encoder"))]
mod tests {
    use super::*;
    use crate::container::{parse_container, with_section, write_container, Tag};
    use crate::{EncodeMode, EncodeOptions, SwingTarget, SwingTuning};

    #[test]
    fn radii_are_exact_steps_of_the_level_radius() {
        assert_eq!((max_code(4), max_code(8), max_code(12)), (2, 32, 512));
        assert_eq!(apply(8, 0.75, 0).to_bits(), 0.75f64.to_bits());
        assert_eq!(apply(8, 1.0, 1), 1.0 + 1.0 / 32.0);
        assert_eq!(apply(8, 1.0, -32), 0.0);
        assert_eq!(apply(4, 2.0, 2), 4.0);
        assert_eq!(nearest(8, 0.25), 8);
        assert_eq!(nearest(8, -5.0), -32);
        assert_eq!(nearest(8, f64::NAN), 0);
    }

    /// Bender's test cube (8 × 8 squares a face) retiled at L = 0.3 with its
    /// tips on the edges (an edge-length request uses them outright);
    /// `CLRS`, so that other radius codes change the positions only (the
    /// `CLRF` pass takes its contexts from them).
    fn creased_file() -> Vec<u8> {
        let options = EncodeOptions {
            mode: EncodeMode::Swing {
                target: SwingTarget::EdgeLength(0.3),
                angle_bits: Some(8),
                max_bytes: None,
            },
            swing: SwingTuning {
                approximate_tips: false,
                fit_tips: false,
                post_hint: false,
                front_contexts: false,
                ..SwingTuning::default()
            },
            ..EncodeOptions::default()
        };
        let mesh = crate::post::bend::tests::cube(8).0;
        crate::encode(&mesh, &options).unwrap().bytes
    }

    #[test]
    fn crease_files_are_1_1_with_radius_codes_and_hostile_streams_are_errors() {
        let bytes = creased_file();
        assert_eq!((bytes[4], bytes[5]), (1, 1));
        let file = parse_container(&bytes, &Default::default()).unwrap();
        let rads = file.section(Tag::RADS).expect("a RADS section").to_vec();
        let decode = |b: &[u8]| crate::decode(b, &Default::default());
        let mesh = decode(&bytes).unwrap();
        // A missing or extra word, nothing at all.
        let mut longer = rads.clone();
        longer.extend_from_slice(&[0, 0, 0, 0]);
        assert!(decode(&with_section(&bytes, Tag::RADS, &longer)).is_err());
        assert!(decode(&with_section(&bytes, Tag::RADS, &rads[..rads.len() - 4])).is_err());
        assert!(decode(&with_section(&bytes, Tag::RADS, &[])).is_err());
        let c_tips = crate::inspect(&bytes, &Default::default())
            .unwrap()
            .stats
            .clers[0] as usize;
        let stream = |first: u32, len: u32| {
            let mut models = Models::new();
            let mut enc = Encoder::new();
            // (No tip is marked before the first flag 1: context 0.)
            for k in 0..c_tips {
                enc.encode(models.flag.get(0), if k == 0 { first } else { 0 });
                if k == 0 && first == 1 {
                    enc.encode_bits(0, 1);
                    enc.encode(&mut models.len, len);
                    if len > 1 {
                        enc.encode_bits(0, len - 1);
                    }
                }
            }
            enc.finish()
        };
        // The first tip's code 2^8 + 1 > J = 32 at 8 bits: out of range.
        assert!(decode(&with_section(&bytes, Tag::RADS, &stream(1, 9))).is_err());
        // Every code 0 is valid: the file of tips on their circles, as
        // without the section.
        let flat = decode(&with_section(&bytes, Tag::RADS, &stream(0, 0))).unwrap();
        let without: Vec<(Tag, &[u8])> = file
            .sections()
            .filter(|s| s.tag != Tag::RADS)
            .map(|s| (s.tag, s.bytes))
            .collect();
        let plain = decode(&write_container(&file.header, &without).unwrap()).unwrap();
        assert_eq!(flat, plain);
        assert_ne!(flat, mesh);
        // A lossless file never has one.
        let lossless = crate::encode(&mesh, &EncodeOptions::default())
            .unwrap()
            .bytes;
        let l = parse_container(&lossless, &Default::default()).unwrap();
        let mut with: Vec<(Tag, &[u8])> = l.sections().map(|s| (s.tag, s.bytes)).collect();
        with.push((Tag::RADS, &rads));
        assert!(decode(&write_container(&l.header, &with).unwrap()).is_err());
    }
}
