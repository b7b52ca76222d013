//! Attributes for the files of a method that makes new vertices (issue
//! 47, item 3: displaced subdivision and SwingWrapper): each decoded vertex's value
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

use super::method::{Job, Made};
use super::stats::Origin;
use crate::container::{parse_container, write_container, Tag};
use crate::{AttributeKind, AttributeStream, Error, Limits, SizeError, TriMesh};

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
/// where the method gave them). `None` when its decoded mesh makes no
/// corner table.
pub(crate) fn with_attributes(
    job: &Job<'_, '_>,
    bytes: &[u8],
    seeds: Option<&[u32]>,
) -> Result<Option<Vec<u8>>, Error> {
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
    // `ATTR` is a 1.2 section (a SwingWrapper file is 1.0 or 1.1 without).
    let mut header = file.header;
    header.minor = header.minor.max(2);
    Ok(Some(write_container(&header, &sections)?))
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

/// Whole encodes of a file with attributes at most: the first from the
/// streams' cost over the input, then at the geometry budget where the
/// sum is predicted to meet the budget (two on the tests' spheres and a
/// coloured bunny at 2 b/v; five at 8 b/v, where a level more or less
/// moves the sum by a fifth).
const PASSES: usize = 5;

/// A file with the job's streams at about `budget` bytes (never above
/// `cap`), `make` giving the file whose geometry alone is about its
/// argument, streams appended. The first geometry budget leaves room for
/// the streams at what they cost over the input ([`input_bits`]) against
/// `geometry_bits` per decoded vertex of geometry; each file tells how
/// far the sum misses (the streams cost more per vertex on a coarser
/// mesh, whose neighbours differ more), and the next geometry budget is
/// where the sum meets the budget on the line, in log-log, through the
/// nearest files on either side of it once there are some (else the
/// last two; in proportion after the first): the streams' bytes grow
/// with the vertices, faster than the geometry's where the values are
/// rough, and not smoothly (a level count changes). The file nearest
/// the budget within the cap wins; `None` when `make` has none.
pub(crate) fn sized(
    job: &Job<'_, '_>,
    budget: u64,
    cap: Option<u64>,
    geometry_bits: f64,
    make: impl Fn(u64) -> Result<Option<Made>, Error>,
) -> Result<Option<Made>, Error> {
    // Rate control's tolerance, as every method's.
    use crate::swing::retile::rate::TOLERANCE;
    let cap = cap.unwrap_or(u64::MAX);
    let aim = (budget.min(cap) as f64).ln();
    let mut geometry = match input_bits(job)? {
        Some(a) => ((budget as f64) / (1.0 + a / geometry_bits)).max(1.0) as u64,
        None => budget,
    };
    let mut best: Option<Made> = None;
    let off = |m: &Made| ((m.bytes.len() as f64).ln() - aim).abs();
    // (ln geometry budget, ln total) of each file made.
    let mut tried: Vec<(f64, f64)> = Vec::new();
    for _ in 0..PASSES {
        let Some(m) = make(geometry)? else {
            return Ok(None);
        };
        let total = m.bytes.len() as u64;
        let on_size = (total as f64 - budget as f64).abs() <= TOLERANCE * budget as f64;
        tried.push(((geometry as f64).ln(), (total as f64).ln()));
        if total <= cap && best.as_ref().is_none_or(|b| off(&m) < off(b)) {
            best = Some(m);
        }
        if total <= cap && on_size {
            break;
        }
        let below = (tried.iter().filter(|p| p.1 < aim)).max_by(|a, b| a.1.total_cmp(&b.1));
        let above = (tried.iter().filter(|p| p.1 >= aim)).min_by(|a, b| a.1.total_cmp(&b.1));
        let (p0, p1) = match (below, above) {
            (Some(&a), Some(&b)) => (a, b),
            _ if tried.len() >= 2 => (tried[tried.len() - 2], tried[tried.len() - 1]),
            _ => (tried[0], tried[0]),
        };
        let slope = match p1.0 - p0.0 {
            d if d != 0.0 => ((p1.1 - p0.1) / d).clamp(0.5, 4.0),
            _ => 1.0,
        };
        let next = (p1.0 + (aim - p1.1) / slope).exp().max(1.0) as u64;
        if next == geometry {
            break;
        }
        geometry = next;
    }
    let smallest = tried.iter().map(|p| p.1.exp().round() as u64).min();
    match best {
        Some(m) => Ok(Some(m)),
        None => Err(SizeError {
            requested: budget,
            smallest: smallest.unwrap_or(u64::MAX),
        }
        .into()),
    }
}
