//! The `DENS` stream of the SwingWrapper mode (format 1.1): an edge
//! length that follows the shape, one level step per C tip
//! (format-spec/05-swing.md, "DENS"; issue 19, adaptive sampling).
//!
//! Every vertex has a *level* ℓ; its tip circle had radius r·2^(ℓ/4),
//! with r the file's radius (from the first edge). First-triangle
//! vertices have level 0. A C tip on gate (GL, GR) gets
//!
//! ```text
//! ℓ(tip) = floor((ℓ(GL) + ℓ(GR)) / 2) + d,     d ∈ {−1, 0, +1} coded here
//! ```
//!
//! so the edge length changes by at most 2^(1/4) ≈ 1.19 per ring of
//! triangles and never jumps: smooth grading keeps the retiled triangles
//! near-equilateral. Levels stay within ±[`LEVEL_MAX`] (¼ to 4 times r).
//! A file without `DENS` is a file whose every d is 0: all radii are r,
//! exactly as in format 1.0 ([`RATIO`]`[0]` is 1).
//!
//! Context of d: how many of the gate's two vertices were themselves
//! made by a step (d ≠ 0). Steps cluster where the shape changes scale,
//! and are rare on the regions between, where the symbol costs almost
//! nothing.
//!
//! Invariants: the walk over the triangles is the one of `GEOM`
//! (`residual::for_each_c`), so [`encode`] and [`decode`] see the same
//! gates in the same order; the radius arithmetic is one binary64
//! multiplication by a constant, so every decoder computes the same bits.

use crate::prelude::*;

#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{ContextModel, Decoder};
use crate::{CornerTable, Error, FormatError, Malformed};

/// Largest |level|: radii from r/4 to 4r.
pub const LEVEL_MAX: i8 = 8;

/// 2^(k/4) for k = 0 … 3, each the binary64 value nearest the exact one
/// (bit patterns 3FF0000000000000, 3FF306FE0A31B715, 3FF6A09E667F3BCD,
/// 3FFAE89F995AD3AD).
const FOURTH_ROOTS: [f64; 4] = [
    1.0,
    f64::from_bits(0x3FF3_06FE_0A31_B715),
    f64::from_bits(0x3FF6_A09E_667F_3BCD),
    f64::from_bits(0x3FFA_E89F_995A_D3AD),
];

/// `RATIO[ℓ + LEVEL_MAX]` = 2^(ℓ/4): `FOURTH_ROOTS[ℓ mod 4]` times the
/// power of two 2^floor(ℓ/4), an exact scaling.
pub const RATIO: [f64; 2 * LEVEL_MAX as usize + 1] = {
    let mut out = [0.0; 2 * LEVEL_MAX as usize + 1];
    let mut i = 0;
    while i < out.len() {
        let l = i as i32 - LEVEL_MAX as i32;
        let pow = l.div_euclid(4);
        let scale = if pow >= 0 {
            (1u64 << pow) as f64
        } else {
            1.0 / (1u64 << -pow) as f64
        };
        out[i] = FOURTH_ROOTS[l.rem_euclid(4) as usize] * scale;
        i += 1;
    }
    out
};

/// The radius ratio of level `l` (|l| ≤ [`LEVEL_MAX`]).
pub fn ratio(l: i8) -> f64 {
    RATIO[(l + LEVEL_MAX) as usize]
}

/// The level a C tip on a gate of levels `a`, `b` has before its step.
pub fn gate_level(a: i8, b: i8) -> i8 {
    (i16::from(a) + i16::from(b)).div_euclid(2) as i8
}

/// Context of a step: how many of the gate's vertices were made by one.
fn context(stepped: &[bool], gl: usize, gr: usize) -> usize {
    usize::from(stepped[gl]) + usize::from(stepped[gr])
}

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// Symbol of step d: 0 → 0, 1 → −1, 2 → +1.
#[cfg(feature = "encoder")]
fn symbol(d: i8) -> u32 {
    match d {
        0 => 0,
        -1 => 1,
        _ => 2,
    }
}

/// The DENS coder, one C tip at a time, in coding order: [`encode`]'s
/// state, the mirror of [`Reader`] (which the `CLRF` pass of
/// `swing::forward` also drives).
#[cfg(feature = "encoder")]
pub(super) struct Writer {
    enc: Encoder,
    models: ContextModel,
    level: Vec<i8>,
    stepped: Vec<bool>,
}

#[cfg(feature = "encoder")]
impl Writer {
    pub(super) fn new(vertices: usize) -> Writer {
        Writer {
            enc: Encoder::new(),
            models: ContextModel::new(3, 3),
            level: vec![0; vertices],
            stepped: vec![false; vertices],
        }
    }

    /// Codes step `d` of C tip `tip` on the gate `gl`, `gr`; returns the
    /// tip's level.
    pub(super) fn put(&mut self, d: i8, tip: usize, gl: usize, gr: usize) -> Result<i8, Error> {
        if tip >= self.level.len() || gl >= tip || gr >= tip {
            return Err(bad("a C tip out of range"));
        }
        if !(-1..=1).contains(&d) {
            return Err(bad("a level step out of range"));
        }
        let l = gate_level(self.level[gl], self.level[gr]) + d;
        if l.abs() > LEVEL_MAX {
            return Err(bad("a level step out of range"));
        }
        self.enc
            .encode(self.models.get(context(&self.stepped, gl, gr)), symbol(d));
        self.level[tip] = l;
        self.stepped[tip] = d != 0;
        Ok(l)
    }

    pub(super) fn finish(self) -> Vec<u8> {
        self.enc.finish()
    }
}

/// The DENS decoder, the mirror of [`Writer`].
pub(super) struct Reader<'a> {
    dec: Decoder<'a>,
    models: ContextModel,
    level: Vec<i8>,
    stepped: Vec<bool>,
}

impl<'a> Reader<'a> {
    /// The stream `bytes` of a mesh of `vertices` vertices (the caller
    /// has checked that count against the limits).
    pub(super) fn new(bytes: &'a [u8], vertices: usize) -> Result<Reader<'a>, Error> {
        Ok(Reader {
            dec: Decoder::new(bytes)?,
            models: ContextModel::new(3, 3),
            level: vec![0; vertices],
            stepped: vec![false; vertices],
        })
    }

    /// The level of C tip `tip` on the gate `gl`, `gr`.
    pub(super) fn get(&mut self, tip: usize, gl: usize, gr: usize) -> Result<i8, Error> {
        if tip >= self.level.len() || gl >= tip || gr >= tip {
            return Err(bad("a C tip is built on vertices not yet placed"));
        }
        let d = match self
            .dec
            .decode(self.models.get(context(&self.stepped, gl, gr)))?
        {
            0 => 0,
            1 => -1,
            _ => 1,
        };
        let l = gate_level(self.level[gl], self.level[gr]) + d;
        if l.abs() > LEVEL_MAX {
            return Err(bad("a level beyond the largest"));
        }
        self.level[tip] = l;
        self.stepped[tip] = d != 0;
        Ok(l)
    }

    /// Checks that the stream ends where its encoder finished it.
    pub(super) fn finish(self) -> Result<(), Error> {
        self.dec.finish()
    }
}

/// Codes one step per C tip of the decoded `table` (each −1, 0 or 1,
/// levels within ±[`LEVEL_MAX`]); returns the stream.
#[cfg(feature = "encoder")]
pub(crate) fn encode(table: &CornerTable, steps: &[i8]) -> Result<Vec<u8>, Error> {
    let mut w = Writer::new(table.vertex_count());
    let mut used = 0;
    super::residual::for_each_c(table, |k, tip, gl, gr| {
        used += 1;
        let d = *steps.get(k).ok_or(bad("fewer level steps than C tips"))?;
        w.put(d, tip, gl, gr).map(|_| ())
    })?;
    if used != steps.len() {
        return Err(bad("more level steps than C tips"));
    }
    Ok(w.finish())
}

/// Decodes `count` steps for the C tips of the decoded `table`; returns
/// each C tip's level, in the order of the codes.
pub(crate) fn decode(table: &CornerTable, bytes: &[u8], count: usize) -> Result<Vec<i8>, Error> {
    let mut r = Reader::new(bytes, table.vertex_count())?;
    let mut levels = Vec::with_capacity(count);
    super::residual::for_each_c(table, |_, tip, gl, gr| {
        if levels.len() == count {
            return Err(bad("more C tips than level steps"));
        }
        levels.push(r.get(tip, gl, gr)?);
        Ok(())
    })?;
    if levels.len() != count {
        return Err(bad("fewer C tips than level steps"));
    }
    r.finish()?;
    Ok(levels)
}

#[cfg(all(test, feature = "encoder"))]
mod tests {
    use super::*;
    use crate::container::{parse_container, with_section, write_container, Tag};
    use crate::entropy::{ContextModel, Encoder};
    use crate::{EncodeMode, EncodeOptions, SwingTarget, SwingTuning, TriMesh};

    #[test]
    fn ratios_are_exact_fourth_roots_of_two() {
        assert_eq!(ratio(0), 1.0);
        assert_eq!(ratio(4), 2.0);
        assert_eq!(ratio(-8), 0.25);
        assert_eq!(ratio(1).to_bits(), 0x3FF3_06FE_0A31_B715);
        assert_eq!(ratio(-3).to_bits(), (ratio(1) / 2.0).to_bits());
        for l in -LEVEL_MAX..LEVEL_MAX - 3 {
            assert_eq!(ratio(l + 4), 2.0 * ratio(l), "level {l}");
            let exact = 2f64.powf(f64::from(l) / 4.0);
            assert!((ratio(l) / exact - 1.0).abs() < 1e-15, "level {l}");
        }
        // Rounded down, also for negative sums.
        assert_eq!(
            (gate_level(2, 3), gate_level(-2, -3), gate_level(-1, 0)),
            (2, -3, -1)
        );
    }

    /// An ellipsoid whose curvature varies enough for levels to step.
    fn ellipsoid() -> TriMesh {
        let mut m = crate::swing::retile::tests::sphere(4);
        for p in &mut m.positions {
            let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            *p = [p[0] / n, 0.5 * p[1] / n, 0.25 * p[2] / n];
        }
        m
    }

    fn adaptive_file() -> Vec<u8> {
        let options = EncodeOptions {
            mode: EncodeMode::Swing {
                target: SwingTarget::EdgeLength(0.12),
                angle_bits: Some(8),
                max_bytes: None,
            },
            swing: SwingTuning {
                approximate_tips: true,
                fit_tips: true,
                adaptive_density: true,
                front_contexts: false,
                loop_start: false,
                crease_tips: false,
                post_hint: false,
            },
            ..EncodeOptions::default()
        };
        crate::encode(&ellipsoid(), &options).unwrap().bytes
    }

    #[test]
    fn adaptive_files_are_1_1_with_varied_edges_and_decode() {
        let bytes = adaptive_file();
        assert_eq!((bytes[4], bytes[5]), (1, 1));
        let file = parse_container(&bytes, &Default::default()).unwrap();
        assert!(file.find(Tag::DENS).is_some());
        let mesh = crate::decode(&bytes, &Default::default()).unwrap();
        // Edges near the tips of the long axis (|x| near 1, curvature up
        // to 16) are shorter than around the flat faces (|z| near 0.25).
        let mut near_tip = Vec::new();
        let mut near_face = Vec::new();
        for t in &mesh.triangles {
            let p = t.map(|v| mesh.positions[v as usize].map(f64::from));
            let e = ((p[0][0] - p[1][0]).powi(2)
                + (p[0][1] - p[1][1]).powi(2)
                + (p[0][2] - p[1][2]).powi(2))
            .sqrt();
            let x = (p[0][0] + p[1][0]) / 2.0;
            if x.abs() > 0.85 {
                near_tip.push(e);
            } else if x.abs() < 0.3 {
                near_face.push(e);
            }
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        assert!(
            mean(&near_tip) < 0.8 * mean(&near_face),
            "tips {} vs faces {}",
            mean(&near_tip),
            mean(&near_face)
        );
    }

    #[test]
    fn hostile_density_streams_are_errors() {
        let bytes = adaptive_file();
        let file = parse_container(&bytes, &Default::default()).unwrap();
        let dens = file.section(Tag::DENS).unwrap().to_vec();
        let c_tips = crate::inspect(&bytes, &Default::default())
            .unwrap()
            .stats
            .clers[0] as usize;
        let decode = |b: &[u8]| crate::decode(b, &Default::default());
        // A missing or extra word, nothing at all.
        let mut longer = dens.clone();
        longer.extend_from_slice(&[0, 0, 0, 0]);
        assert!(decode(&with_section(&bytes, Tag::DENS, &longer)).is_err());
        assert!(decode(&with_section(&bytes, Tag::DENS, &dens[..dens.len() - 4])).is_err());
        assert!(decode(&with_section(&bytes, Tag::DENS, &[])).is_err());
        // Every step +1: the levels run past the largest.
        let mut models = ContextModel::new(3, 3);
        let mut enc = Encoder::new();
        for _ in 0..c_tips {
            enc.encode(models.get(0), 2);
        }
        let up = enc.finish();
        assert!(decode(&with_section(&bytes, Tag::DENS, &up)).is_err());
        // Every step 0 is valid: the file of one radius, as 1.0 decodes it.
        let mut models = ContextModel::new(3, 3);
        let mut enc = Encoder::new();
        for _ in 0..c_tips {
            enc.encode(models.get(0), 0);
        }
        let flat = decode(&with_section(&bytes, Tag::DENS, &enc.finish())).unwrap();
        let without: Vec<(Tag, &[u8])> = file
            .sections()
            .filter(|s| s.tag != Tag::DENS)
            .map(|s| (s.tag, s.bytes))
            .collect();
        let plain = decode(&write_container(&file.header, &without).unwrap()).unwrap();
        assert_eq!(flat, plain);
        // A lossless file never has one.
        let lossless = crate::encode(&ellipsoid(), &EncodeOptions::default())
            .unwrap()
            .bytes;
        let l = parse_container(&lossless, &Default::default()).unwrap();
        let mut with: Vec<(Tag, &[u8])> = l.sections().map(|s| (s.tag, s.bytes)).collect();
        with.push((Tag::DENS, &dens));
        assert!(decode(&write_container(&l.header, &with).unwrap()).is_err());
    }
}
