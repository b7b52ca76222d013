//! How far a lossy file's texture coordinates are from the input's
//! (issue 47, item 3), in texels of a texture of [`TEXTURE_SIZE`] texels
//! a side: what a viewer sees as the texture sliding over the surface.
//! The encoder reports it (`EncodeStats::attributes`) and the simplified
//! method's climb weighs it beside L2 (`simplify::climb`).
//!
//! At points spread over the decoded surface (each decoded face's
//! centroid and three points a sixth of the way from its corners toward
//! it, at most [`MAX_SAMPLES`] faces, evenly strided), the decoded
//! coordinate, interpolated over its face, is compared with the input's at
//! the nearest point of the input. Next to a seam the nearest point may
//! lie across it, in another chart whose coordinates are far off though
//! the texture there is the same colour: so the input's coordinate is the
//! nearest to the decoded one among the faces around the nearest face's
//! corners that lie about as near (within twice its distance and a
//! millionth of the diagonal), one per side of any seam there.
//!
//! The figure is a measure, not a bound: texture coordinates on the
//! lossless mode's grid (10 bits by default: a texel at 1024) add half a
//! step of rounding, simplification the rest (a simplified face maps its
//! texture linearly where the input had several faces).

use super::triangle::{closest_point as closest_on_triangle, distance2};
use super::{NearestScratch, Surface};
use crate::{AttributeKind, AttributedMesh};

/// The texture size texel-scale figures are stated at: a texel is
/// 1/`TEXTURE_SIZE` of the [0, 1] texture coordinate range (the lossless
/// mode's default 10 bits of texture coordinate are one such texel).
pub const TEXTURE_SIZE: f64 = 1024.0;

/// How far a lossy file's texture coordinates (set 0) are from the
/// input's, in texels of a square texture of `texture_size` texels
/// ([`TEXTURE_SIZE`]): at points spread over the decoded surface, the
/// decoded coordinate against the input's at the nearest point of the
/// input, on the side of any seam whose coordinate is nearest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexcoordError {
    /// Root mean square, in texels.
    pub rms_texels: f64,
    /// The largest, in texels.
    pub max_texels: f64,
    /// The texture size the texels are of.
    pub texture_size: f64,
    /// Points measured.
    pub samples: u64,
}

/// Decoded faces sampled at most; beyond, every k-th.
pub const MAX_SAMPLES: usize = 20_000;

/// The texture coordinates (set 0) of `decoded` against those of `input`
/// (`surface` is `input.mesh`'s surface); `None` when either has none or
/// nothing was measured.
pub fn texcoord_error(
    input: &AttributedMesh,
    surface: &Surface,
    decoded: &AttributedMesh,
) -> Option<TexcoordError> {
    let (rms, max, samples) = value_error(input, surface, decoded, AttributeKind::TexCoord(0))?;
    Some(TexcoordError {
        rms_texels: rms * TEXTURE_SIZE,
        max_texels: max * TEXTURE_SIZE,
        texture_size: TEXTURE_SIZE,
        samples,
    })
}

/// The colours (set 0) of `decoded` against those of `input`, as
/// [`texcoord_error`] measures texture coordinates: the root mean square
/// distance between colours (all components, 0..1), in steps of 1/255.
/// `None` when either has none.
pub fn colour_error_steps(
    input: &AttributedMesh,
    surface: &Surface,
    decoded: &AttributedMesh,
) -> Option<f64> {
    let (rms, _, _) = value_error(input, surface, decoded, AttributeKind::Color(0))?;
    Some(rms * 255.0)
}

/// The stream of `kind` of `decoded` against `input`'s: root mean square
/// and largest distance between values (in the stream's units) and the
/// points measured (see the module header).
fn value_error(
    input: &AttributedMesh,
    surface: &Surface,
    decoded: &AttributedMesh,
    kind: AttributeKind,
) -> Option<(f64, f64, u64)> {
    let uv_in = input.stream(kind)?;
    let uv_out = decoded.stream(kind)?;
    if uv_in.dims != uv_out.dims {
        return None;
    }
    let dims = usize::from(uv_in.dims);
    let faces_in = &input.mesh.triangles;
    let pos_in = &input.mesh.positions;
    // The faces around each input vertex.
    let mut start = vec![0u32; pos_in.len() + 1];
    for t in faces_in {
        for &v in t {
            start[v as usize + 1] += 1;
        }
    }
    for i in 0..pos_in.len() {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut around = vec![0u32; 3 * faces_in.len()];
    for (f, t) in faces_in.iter().enumerate() {
        for &v in t {
            around[fill[v as usize] as usize] = f as u32;
            fill[v as usize] += 1;
        }
    }
    let slack = 1e-6 * surface.diagonal();
    let uv_at = |f: usize, p: [f64; 3]| -> [f64; 4] {
        let t = faces_in[f].map(|v| pos_in[v as usize]);
        let b = super::triangle::barycentric(&t, p);
        let mut u = [0.0; 4];
        for k in 0..3 {
            let q = uv_in.corner_value(crate::FaceId(f as u32), k);
            for d in 0..dims {
                u[d] += b[k] as f64 * q[d] as f64;
            }
        }
        u
    };
    let stride = decoded.mesh.face_count().div_ceil(MAX_SAMPLES).max(1);
    let mut scratch = NearestScratch::default();
    let mut hint = None;
    let (mut sum, mut max, mut n) = (0.0f64, 0.0f64, 0u64);
    let mut candidates: Vec<u32> = Vec::new();
    for f in (0..decoded.mesh.face_count()).step_by(stride) {
        let t = decoded.mesh.triangles[f];
        let p = t.map(|v| decoded.mesh.positions[v as usize].map(f64::from));
        let u: Vec<[f64; 4]> = (0..3)
            .map(|k| {
                let q = uv_out.corner_value(crate::FaceId(f as u32), k);
                let mut w = [0.0; 4];
                for d in 0..dims {
                    w[d] = q[d] as f64;
                }
                w
            })
            .collect();
        for w in [
            [1.0, 1.0, 1.0],
            [4.0, 1.0, 1.0],
            [1.0, 4.0, 1.0],
            [1.0, 1.0, 4.0],
        ] {
            let s: f64 = w.iter().sum();
            let mix = |k: usize| (w[0] * p[0][k] + w[1] * p[1][k] + w[2] * p[2][k]) / s;
            let point = [mix(0), mix(1), mix(2)];
            let uv = [0, 1, 2, 3].map(|k| (w[0] * u[0][k] + w[1] * u[1][k] + w[2] * u[2][k]) / s);
            let Some((near, q, h)) = surface.nearest_point(point, hint, &mut scratch) else {
                continue;
            };
            hint = Some(h);
            let reach = 2.0 * distance2(point, q).sqrt() + slack;
            candidates.clear();
            for &v in &faces_in[near as usize] {
                let ring = &around[start[v as usize] as usize..start[v as usize + 1] as usize];
                candidates.extend_from_slice(ring);
            }
            candidates.sort_unstable();
            candidates.dedup();
            let mut best = f64::INFINITY;
            for &g in &candidates {
                let tri = faces_in[g as usize].map(|v| pos_in[v as usize]);
                let c = closest_on_triangle(point, &tri);
                if g != near && distance2(point, c).sqrt() > reach {
                    continue;
                }
                let v = uv_at(g as usize, c);
                let d = (0..dims)
                    .map(|k| (v[k] - uv[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                best = best.min(d);
            }
            if best.is_finite() {
                sum += best * best;
                max = max.max(best);
                n += 1;
            }
        }
    }
    (n > 0).then(|| ((sum / n as f64).sqrt(), max, n))
}
