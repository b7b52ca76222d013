//! Attributes for the files of a method that makes new vertices (issue
//! 47, item 3; today displaced subdivision): each decoded vertex's value
//! is read from the input where the vertex stands for (`provenance`: a
//! face and barycentric coordinates on it), one value per vertex, and the
//! streams are coded as `ATTR` over the decoded mesh
//! (`lossless::attributes::over_mesh`) and appended to the method's file.
//!
//! Which streams: normals, colours and generic values. Texture
//! coordinates are not resampled: a new mesh's triangle may straddle a
//! seam of the input, and one value per vertex would stretch a chart
//! across it; an input with them is coded by a method that keeps its
//! seams (the simplified method: the chooser runs only methods that
//! carry the input's streams, [`carries`]).
//!
//! The value: the barycentric mix of the origin face's corner values,
//! which reads the side of a seam (a crease's normals, a colour border)
//! the face is on; a normal is renormalized (a zero mix keeps the face's
//! first corner's). Deterministic: one pass in vertex order.

use super::method::Job;
use super::stats::Origin;
use crate::container::{parse_container, write_container, Tag};
use crate::{AttributeKind, AttributeStream, Error, Limits, TriMesh};

/// Whether a file of a method that makes new vertices can carry all of
/// `streams` (none is a texture coordinate set).
pub(crate) fn carries(streams: &[AttributeStream]) -> bool {
    streams
        .iter()
        .all(|s| !matches!(s.kind, AttributeKind::TexCoord(_)))
}

/// The streams of `input` (one triple per face of `input`) read at each
/// vertex of `decoded` from its origin (faces of `input`): one value per
/// vertex, each triangle's corners its vertices'.
pub(crate) fn resampled(
    streams: &[AttributeStream],
    decoded: &TriMesh,
    origins: &[Origin],
) -> Vec<AttributeStream> {
    streams
        .iter()
        .map(|s| {
            let d = usize::from(s.dims);
            let mut values = Vec::with_capacity(d * origins.len());
            for o in origins {
                let corners = s.corners.get(o.face as usize).copied().unwrap_or_default();
                let value = |k: usize| -> &[f32] {
                    let at = corners[k] as usize * d;
                    s.values.get(at..at + d).unwrap_or(&[0.0; 4][..d])
                };
                let mut mix = [0f64; 4];
                for (k, &b) in o.barycentric.iter().enumerate() {
                    for (m, &x) in mix.iter_mut().zip(value(k)) {
                        *m += f64::from(b) * f64::from(x);
                    }
                }
                if s.kind == AttributeKind::Normal {
                    let l = mix[..3].iter().map(|x| x * x).sum::<f64>().sqrt();
                    if l > 0.0 && l.is_finite() {
                        mix.iter_mut().for_each(|x| *x /= l);
                    } else {
                        for (m, &x) in mix.iter_mut().zip(value(0)) {
                            *m = f64::from(x);
                        }
                    }
                }
                values.extend(mix[..d].iter().map(|&x| x as f32));
            }
            AttributeStream::new(s.kind, s.dims, values, decoded.triangles.clone())
        })
        .collect()
}

/// The method's file `bytes` with `ATTR` appended: the job's streams
/// resampled at the vertices of its plain decode (origins from `seeds`
/// where the method gave them), and the bytes of `ATTR`'s payload.
/// `None` when its decoded mesh makes no corner table.
pub(crate) fn with_attributes(
    job: &Job<'_, '_>,
    bytes: &[u8],
    seeds: Option<&[u32]>,
) -> Result<Option<(Vec<u8>, usize)>, Error> {
    let decoded = crate::decoder::decode(bytes, &crate::options::DecodeOptions::plain())?;
    let origins = super::provenance::origins(
        &job.cleaned.mesh,
        job.simplifier().reference(),
        job.reference()?,
        &decoded,
        seeds.filter(|s| s.len() <= decoded.vertex_count()),
    );
    let streams = resampled(job.streams(), &decoded, &origins);
    let coded = crate::lossless::attributes::over_mesh::encode(
        &decoded,
        &streams,
        &job.services.quantization(),
    )?;
    let Some((attr, _)) = coded else {
        return Ok(None);
    };
    let file = parse_container(bytes, &Limits::default())?;
    let mut sections: Vec<(Tag, &[u8])> = file.sections().map(|s| (s.tag, s.bytes)).collect();
    sections.push((Tag::ATTR, &attr));
    Ok(Some((
        write_container(&file.header, &sections)?,
        attr.len(),
    )))
}

/// Bits per vertex the job's streams cost coded as `ATTR` over the
/// cleaned input itself (`None` when it makes no corner table): what a
/// method sizing a file with them starts from.
pub(crate) fn input_bits(job: &Job<'_, '_>) -> Result<Option<f64>, Error> {
    let mesh = &job.cleaned.mesh;
    let coded = crate::lossless::attributes::over_mesh::encode(
        mesh,
        job.streams(),
        &job.services.quantization(),
    )?;
    Ok(coded.map(|(attr, _)| 8.0 * attr.len() as f64 / mesh.vertex_count().max(1) as f64))
}
