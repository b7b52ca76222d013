//! The encoder's side of `ATTR`: each input stream quantized (normals
//! onto the octahedron, the others on a grid over their bounding box, as
//! Draco's attribute quantization), its corners mapped onto the closed
//! mesh's table, and coded by `stream::encode`. Deterministic: no
//! choice depends on anything but the input.

use super::frame::{Frame, NONE};
use super::octahedral;
use super::spec::{AttributeInfo, Spec, FLAG_NEGATED, GRID_BITS, MAX_STREAMS, NORMAL_BITS};
use super::stream;
use crate::options::AttributeQuantization;
use crate::prelude::*;
use crate::{AttributeKind, AttributeStream, Error, ParameterError};

/// The bits of `kind` under `q`, checked against the format's range.
fn bits_of(kind: AttributeKind, q: &AttributeQuantization) -> Result<u8, Error> {
    let (name, bits, range) = match kind {
        AttributeKind::Normal => ("qn", q.normal_bits, NORMAL_BITS),
        AttributeKind::TexCoord(_) => ("qt", q.texcoord_bits, GRID_BITS),
        _ => (
            "qg",
            if matches!(kind, AttributeKind::Color(_)) {
                q.color_bits
            } else {
                q.generic_bits
            },
            GRID_BITS,
        ),
    };
    if !range.contains(&bits) {
        return Err(ParameterError::OutOfRange {
            name,
            value: bits.into(),
            min: (*range.start()).into(),
            max: (*range.end()).into(),
        }
        .into());
    }
    Ok(bits)
}

/// The smallest `f32` not below `x` (`x ≥ 0`).
fn f32_at_least(x: f64) -> f32 {
    let r = x as f32;
    if f64::from(r) < x {
        f32::from_bits(r.to_bits() + 1)
    } else {
        r
    }
}

/// The stream's parameters and its values quantized (`dims` per value,
/// normals as two shifted octahedral coordinates and a zero). `used[i]`:
/// value `i` is at some corner coded (only those shape the grid).
fn quantize(s: &AttributeStream, bits: u8, used: &[bool]) -> (Spec, Vec<u64>) {
    let d = usize::from(s.dims);
    let mut spec = Spec {
        kind: s.kind,
        dims: s.dims,
        bits,
        flags: 0,
        origin: [0.0; 4],
        range: 0.0,
    };
    if spec.is_normal() {
        let h = octahedral::half(bits);
        let q = s
            .values
            .chunks_exact(3)
            .flat_map(|n| {
                let q = octahedral::quantize([n[0], n[1], n[2]], bits);
                [(q[0] + h) as u64, (q[1] + h) as u64]
            })
            .collect();
        return (spec, q);
    }
    let (mut lo, mut hi) = ([f32::INFINITY; 4], [f32::NEG_INFINITY; 4]);
    for (i, v) in s.values.chunks_exact(d).enumerate() {
        if used.get(i).copied().unwrap_or(false) {
            for k in 0..d {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
    }
    if lo[0] > hi[0] {
        (lo, hi) = ([0.0; 4], [0.0; 4]);
    }
    let side = (0..d)
        .map(|k| f64::from(hi[k]) - f64::from(lo[k]))
        .fold(0.0, f64::max);
    spec.origin = lo;
    spec.range = f32_at_least(side);
    let step = spec.step();
    let top = (1u64 << bits) - 1;
    let q = s
        .values
        .chunks_exact(d)
        .flat_map(|v| {
            (0..d).map(move |k| {
                if step == 0.0 {
                    return 0;
                }
                let t = (f64::from(v[k]) - f64::from(spec.origin[k])) / step;
                (crate::math::floor(t + 0.5).max(0.0) as u64).min(top)
            })
        })
        .collect();
    (spec, q)
}

/// `ATTR` for `streams`, whose value at table corner `c` is
/// `index[k][c]` (`NONE` on dropped faces), and what it holds
/// per stream. The grid of a value kind spans the values some corner
/// uses; normals are coded with the geometric prediction as it is and
/// negated, and the shorter kept.
pub(crate) fn encode(
    frame: &Frame<'_>,
    streams: &[AttributeStream],
    index: &[Vec<u32>],
    q: &AttributeQuantization,
) -> Result<(Vec<u8>, Vec<AttributeInfo>), Error> {
    if streams.len() > MAX_STREAMS {
        return Err(ParameterError::OutOfRange {
            name: "attribute streams",
            value: streams.len() as f64,
            min: 0.0,
            max: MAX_STREAMS as f64,
        }
        .into());
    }
    let mut coded = Vec::with_capacity(streams.len());
    for (s, idx) in streams.iter().zip(index) {
        let bits = bits_of(s.kind, q)?;
        let mut used = vec![false; s.value_count()];
        for &i in idx.iter().filter(|&&i| i != NONE) {
            used[i as usize] = true;
        }
        let (mut spec, values) = quantize(s, bits, &used);
        let mut chunk = stream::encode(frame, &spec, idx, &values);
        if spec.is_normal() {
            let plain = spec.clone();
            spec.flags = FLAG_NEGATED;
            let negated = stream::encode(frame, &spec, idx, &values);
            if negated.len() < chunk.len() {
                chunk = negated;
            } else {
                spec = plain;
            }
        }
        coded.push((spec, chunk));
    }
    let mut out = Vec::new();
    crate::varint::put(&mut out, coded.len() as u64);
    for (spec, chunk) in &coded {
        super::spec::write_spec(spec, chunk.len(), &mut out);
    }
    let mut infos = Vec::with_capacity(coded.len());
    for (spec, chunk) in &coded {
        out.extend_from_slice(chunk);
        infos.push(AttributeInfo {
            kind: spec.kind,
            dims: spec.dims,
            bits: spec.bits,
            bytes: chunk.len(),
        });
    }
    Ok((out, infos))
}
