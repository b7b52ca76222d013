//! One attribute stream's parameters (kind, components, quantization,
//! grid) as `ATTR` lists them, written and read side by side (must
//! match exactly), with every field of a hostile file checked
//! (format-spec/08-attributes.md, Payload).

use crate::prelude::*;

use super::octahedral;
use crate::varint::Reader;
use crate::{AttributeKind, Error, FormatError, Malformed};

/// Most streams in one `ATTR` section.
pub(crate) const MAX_STREAMS: usize = 32;

/// Flag bit 0: normals are predicted by the negated geometric normal
/// (the input's normals point against its triangles' orientation).
pub(crate) const FLAG_NEGATED: u8 = 1;

/// Fewest and most quantization bits of each kind: normals per
/// octahedral coordinate, the others per component.
pub(crate) const NORMAL_BITS: core::ops::RangeInclusive<u8> =
    octahedral::MIN_BITS..=octahedral::MAX_BITS;
/// See [`NORMAL_BITS`].
pub(crate) const GRID_BITS: core::ops::RangeInclusive<u8> = 2..=24;

/// What a file says of one attribute stream, read without decoding it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AttributeInfo {
    /// What the values are.
    pub kind: AttributeKind,
    /// Components per value.
    pub dims: u8,
    /// Quantization bits (normals: per octahedral coordinate).
    pub bits: u8,
    /// Bytes of the stream's coded chunk.
    pub bytes: usize,
}

pub(crate) fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// One stream's parameters, as `ATTR` lists them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Spec {
    pub kind: AttributeKind,
    pub dims: u8,
    pub bits: u8,
    pub flags: u8,
    /// Grid point 0 per component (not for normals).
    pub origin: [f32; 4],
    /// Side of the grid, the same for every component (not for normals).
    pub range: f32,
}

impl Spec {
    pub(crate) fn is_normal(&self) -> bool {
        self.kind == AttributeKind::Normal
    }

    pub(crate) fn is_texcoord(&self) -> bool {
        matches!(self.kind, AttributeKind::TexCoord(_))
    }

    /// Components coded per value: two octahedral coordinates for a
    /// normal, `dims` otherwise.
    pub(crate) fn coded_dims(&self) -> usize {
        if self.is_normal() {
            2
        } else {
            usize::from(self.dims)
        }
    }

    /// Values lie in `0..modulus` per component: `2^bits` grid points,
    /// or the `2H + 1` octahedral coordinates (shifted by `H`).
    pub(crate) fn modulus(&self) -> u64 {
        if self.is_normal() {
            2 * octahedral::half(self.bits) as u64 + 1
        } else {
            1u64 << self.bits
        }
    }

    /// The grid step, `range / (2^bits − 1)` in binary64.
    pub(crate) fn step(&self) -> f64 {
        f64::from(self.range) / ((1u64 << self.bits) - 1) as f64
    }

    /// The decoded floats of a value (`dims` of them). Must match every
    /// decoder exactly: binary64 steps, one rounding to `f32`.
    pub(crate) fn dequantize(&self, q: &[u64], out: &mut Vec<f32>) {
        if self.is_normal() {
            let h = octahedral::half(self.bits);
            let n = octahedral::dequantize([q[0] as i64 - h, q[1] as i64 - h], self.bits);
            out.extend_from_slice(&n);
        } else {
            let step = self.step();
            for (&o, &g) in self.origin.iter().zip(q).take(usize::from(self.dims)) {
                out.push((f64::from(o) + g as f64 * step) as f32);
            }
        }
    }
}

// --- Stream headers: written and read side by side; must match exactly. ---

#[cfg(feature = "encoder")]
fn kind_code(kind: AttributeKind) -> (u8, u64) {
    match kind {
        AttributeKind::Normal => (0, 0),
        AttributeKind::TexCoord(n) => (1, n.into()),
        AttributeKind::Color(n) => (2, n.into()),
        AttributeKind::Generic(n) => (3, n.into()),
    }
}

#[cfg(feature = "encoder")]
pub(crate) fn write_spec(s: &Spec, len: usize, out: &mut Vec<u8>) {
    let (code, set) = kind_code(s.kind);
    out.push(code);
    crate::varint::put(out, set);
    out.extend_from_slice(&[s.dims, s.bits, s.flags]);
    if !s.is_normal() {
        for x in s.origin[..usize::from(s.dims)].iter().chain([&s.range]) {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    crate::varint::put(out, len as u64);
}

fn read_spec(r: &mut Reader<'_>) -> Result<(Spec, u64), Error> {
    let code = r.u8()?;
    let set = r.varu()?;
    let kind = match (code, u8::try_from(set), u16::try_from(set)) {
        (0, _, _) if set == 0 => AttributeKind::Normal,
        (1, Ok(n), _) => AttributeKind::TexCoord(n),
        (2, Ok(n), _) => AttributeKind::Color(n),
        (3, _, Ok(n)) => AttributeKind::Generic(n),
        _ => return Err(bad("unknown attribute kind")),
    };
    let (dims, bits, flags) = (r.u8()?, r.u8()?, r.u8()?);
    if !kind.allows_dims(dims) {
        return Err(bad("attribute dimension not allowed for its kind"));
    }
    let mut spec = Spec {
        kind,
        dims,
        bits,
        flags,
        origin: [0.0; 4],
        range: 0.0,
    };
    let allowed = if spec.is_normal() {
        NORMAL_BITS.contains(&bits) && flags & !FLAG_NEGATED == 0
    } else {
        GRID_BITS.contains(&bits) && flags == 0
    };
    if !allowed {
        return Err(bad("attribute quantization bits or flags out of range"));
    }
    if !spec.is_normal() {
        for k in 0..usize::from(dims) {
            spec.origin[k] = r.f32()?;
        }
        spec.range = r.f32()?;
        // Every dequantized value lies in origin..=origin + range.
        let finite = spec.origin[..usize::from(dims)]
            .iter()
            .all(|&o| o.is_finite() && ((f64::from(o) + f64::from(spec.range)) as f32).is_finite());
        if !finite || !spec.range.is_finite() || spec.range < 0.0 {
            return Err(bad("attribute grid is not finite"));
        }
    }
    Ok((spec, r.varu()?))
}

/// The streams' parameters and chunks, every field checked.
pub(crate) fn read_specs(bytes: &[u8]) -> Result<Vec<(Spec, &[u8])>, Error> {
    let mut r = Reader::new(bytes);
    let n = r.varu()?;
    if n == 0 || n > MAX_STREAMS as u64 {
        return Err(bad("attribute stream count out of range"));
    }
    let mut specs = Vec::with_capacity(n as usize);
    for _ in 0..n {
        let (spec, len) = read_spec(&mut r)?;
        if specs.iter().any(|(s, _): &(Spec, u64)| s.kind == spec.kind) {
            return Err(bad("two attribute streams of one kind"));
        }
        specs.push((spec, len));
    }
    let mut rest = &bytes[bytes.len() - r.remaining()..];
    let mut out = Vec::with_capacity(specs.len());
    for (spec, len) in specs {
        let len = usize::try_from(len).unwrap_or(usize::MAX);
        if len > rest.len() {
            return Err(FormatError::new("SWM", Malformed::Truncated).into());
        }
        let (chunk, tail) = rest.split_at(len);
        out.push((spec, chunk));
        rest = tail;
    }
    if !rest.is_empty() {
        return Err(FormatError::new("SWM", Malformed::TrailingData).into());
    }
    Ok(out)
}

/// The streams a file lists, without decoding them (`swm info`).
pub(crate) fn inspect(bytes: &[u8]) -> Result<Vec<AttributeInfo>, Error> {
    Ok(read_specs(bytes)?
        .into_iter()
        .map(|(s, chunk)| AttributeInfo {
            kind: s.kind,
            dims: s.dims,
            bits: s.bits,
            bytes: chunk.len(),
        })
        .collect())
}
