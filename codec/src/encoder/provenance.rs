//! Where every decoded vertex came from (issue 45, item 3): for each
//! vertex of the file as decoded plainly (no post-processing, the
//! vertices the file itself places), a face of the input *as the caller
//! gave it* and barycentric coordinates on it, so that texture
//! coordinates, normals and colours can be resampled from the input
//! without asking the method that made the file.
//!
//! How: the nearest point of the job's reference surface (the cleaned
//! input, which the chooser and the check already hold in a tree) to the
//! decoded vertex, carried back to the caller's face by its corners'
//! positions. Cleaning never moves a vertex (it merges coincident ones,
//! drops degenerate and repeated faces, reorients and splits), so a
//! cleaned face has the same three positions as the face of the input it
//! came from: a sorted table of position triples finds it. A reference
//! face with no such twin (a wide fan the simplifier rebuilt,
//! `Simplifier::reference`) is replaced by the input face nearest the
//! point among those sharing a corner position with it.
//!
//! The same rule serves every method: the simplified method's vertices
//! are input vertices moved by their collapses and the refit, the
//! retiler's lie on the surface up to the tip offset and the angle's
//! quantization, so the nearest point is where each stands. What it can
//! miss: a sheet thinner than the file's error, whose far side may be the
//! nearer (a per-method origin, through the collapses or the face a tip
//! was placed in, would not; none is needed by the shared corpus yet).
//!
//! Invariants: one origin per decoded vertex, in the decoder's vertex
//! order; `face` indexes the caller's triangles; the barycentric
//! coordinates are non-negative, sum to one, and follow the caller's
//! corner order of that face. Deterministic (queries in vertex order, one
//! thread).

use super::stats::Origin;
use crate::mesh::clean::position_key as key;
use crate::metrics::{NearestScratch, Surface};
use crate::TriMesh;
use alloc::vec::Vec;

/// The origin of every vertex of the file `bytes` decoded plainly.
pub(crate) fn of_file(
    job: &super::method::Job<'_, '_>,
    bytes: &[u8],
) -> Result<Vec<Origin>, crate::Error> {
    let decoded = crate::decoder::decode(bytes, &crate::options::DecodeOptions::plain())?;
    Ok(origins(
        job.services_input(),
        job.simplifier().reference(),
        job.reference()?,
        &decoded,
    ))
}

/// The origin of every vertex of `decoded` on `input`, through the
/// surface `reference` made from `reference_mesh` (the cleaned input).
pub(crate) fn origins(
    input: &TriMesh,
    reference_mesh: &TriMesh,
    reference: &Surface,
    decoded: &TriMesh,
) -> Vec<Origin> {
    let twins = Twins::new(input);
    let mut around: Option<Around> = None;
    let mut scratch = NearestScratch::default();
    let mut hint = None;
    let mut out = Vec::with_capacity(decoded.positions.len());
    for p in &decoded.positions {
        let q = p.map(|c| c as f64);
        let Some((f, point, slot)) = reference.nearest_point(q, hint, &mut scratch) else {
            out.push(Origin {
                face: 0,
                barycentric: [1.0, 0.0, 0.0],
            });
            continue;
        };
        hint = Some(slot);
        let corners =
            reference_mesh.triangles[f as usize].map(|v| reference_mesh.positions[v as usize]);
        let face = match twins.find(&corners) {
            Some(face) => face,
            None => around
                .get_or_insert_with(|| Around::new(input))
                .nearest(input, &corners, point),
        };
        let t = input.triangles[face as usize].map(|v| input.positions[v as usize]);
        out.push(Origin {
            face,
            barycentric: barycentric(&t, point),
        });
    }
    out
}

/// Input faces by their sorted corner positions.
struct Twins {
    /// (sorted corner keys, face), sorted; the first face of a repeated
    /// triple wins.
    sorted: Vec<([[u32; 3]; 3], u32)>,
}

impl Twins {
    fn new(input: &TriMesh) -> Twins {
        let mut sorted: Vec<([[u32; 3]; 3], u32)> = input
            .triangles
            .iter()
            .enumerate()
            .filter_map(|(f, t)| {
                let mut k = [[0u32; 3]; 3];
                for (slot, &v) in k.iter_mut().zip(t) {
                    *slot = key(input.positions.get(v as usize)?);
                }
                k.sort_unstable();
                Some((k, f as u32))
            })
            .collect();
        sorted.sort_unstable();
        sorted.dedup_by_key(|e| e.0);
        Twins { sorted }
    }

    fn find(&self, corners: &[[f32; 3]; 3]) -> Option<u32> {
        let mut k = corners.map(|p| key(&p));
        k.sort_unstable();
        let i = self.sorted.binary_search_by(|e| e.0.cmp(&k)).ok()?;
        Some(self.sorted[i].1)
    }
}

/// Input faces by the positions of their corners, for reference faces
/// with no twin.
struct Around {
    /// (corner key, face), sorted.
    sorted: Vec<([u32; 3], u32)>,
}

impl Around {
    fn new(input: &TriMesh) -> Around {
        let mut sorted: Vec<([u32; 3], u32)> = input
            .triangles
            .iter()
            .enumerate()
            .flat_map(|(f, t)| t.iter().map(move |&v| (v, f as u32)))
            .filter_map(|(v, f)| Some((key(input.positions.get(v as usize)?), f)))
            .collect();
        sorted.sort_unstable();
        Around { sorted }
    }

    /// The input face nearest `point` among those with a corner at one
    /// of `corners` (the first such face on a tie; face 0 if none).
    fn nearest(&self, input: &TriMesh, corners: &[[f32; 3]; 3], point: [f64; 3]) -> u32 {
        let mut best: Option<(f64, u32)> = None;
        for c in corners {
            let k = key(c);
            let start = self.sorted.partition_point(|e| e.0 < k);
            for &(_, f) in self.sorted[start..].iter().take_while(|e| e.0 == k) {
                let t = input.triangles[f as usize].map(|v| input.positions[v as usize]);
                let d = crate::metrics::distance2(
                    point,
                    crate::metrics::closest_on_triangle(point, &t),
                );
                if best.is_none_or(|(b, g)| d < b || (d == b && f < g)) {
                    best = Some((d, f));
                }
            }
        }
        best.map_or(0, |(_, f)| f)
    }
}

/// Barycentric coordinates of `p` (a point on or near `t`) on `t`:
/// projected onto its plane, clamped to the triangle and summing to one;
/// a degenerate face gives its first corner.
fn barycentric(t: &[[f32; 3]; 3], p: [f64; 3]) -> [f32; 3] {
    let w = |q: [f32; 3]| q.map(|c| c as f64);
    let (a, b, c) = (w(t[0]), w(t[1]), w(t[2]));
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let (e0, e1, d) = (sub(b, a), sub(c, a), sub(p, a));
    let (d00, d01, d11) = (dot(e0, e0), dot(e0, e1), dot(e1, e1));
    let (d20, d21) = (dot(d, e0), dot(d, e1));
    let den = d00 * d11 - d01 * d01;
    if !(den > 0.0) || !den.is_finite() {
        return [1.0, 0.0, 0.0];
    }
    let v = ((d11 * d20 - d01 * d21) / den).max(0.0);
    let u = ((d00 * d21 - d01 * d20) / den).max(0.0);
    let (v, u) = if v + u > 1.0 {
        (v / (v + u), u / (v + u))
    } else {
        (v, u)
    };
    [(1.0 - v - u).max(0.0) as f32, v as f32, u as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point inside a face gives its barycentric coordinates in the
    /// face's corner order; outside, clamped onto the triangle.
    #[test]
    fn barycentric_coordinates() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        let b = barycentric(&t, [0.5, 1.0, 0.3]);
        for (x, y) in b.iter().zip([0.25, 0.25, 0.5]) {
            assert!((x - y).abs() < 1e-6, "{b:?}");
        }
        let b = barycentric(&t, [3.0, 3.0, 0.0]);
        assert!((b[0]).abs() < 1e-6 && (b[1] - 0.5).abs() < 1e-6, "{b:?}");
        let flat = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert_eq!(barycentric(&flat, [1.0, 0.0, 0.0]), [1.0, 0.0, 0.0]);
    }
}

#[cfg(test)]
mod file_tests {
    use crate::mesh::test_shapes::uv_sphere;
    use crate::{EncodeMode, EncodeOptions, SwingTarget, TriMesh};

    /// The point each origin names lies where its decoded vertex is,
    /// within the file's error, on a face of the mesh as given: here with
    /// a degenerate face and an unused vertex first (so cleaned and given
    /// face numbers differ) and with poles of 96 spokes, which the
    /// simplifier's reference rebuilds (faces with no twin in the input).
    #[test]
    fn every_decoded_vertex_points_at_the_input_where_it_stands() {
        for (segments, mode) in [(24, "auto"), (96, "auto"), (24, "swing")] {
            let sphere = uv_sphere(segments, 16);
            let mut positions = vec![[5.0f32, 5.0, 5.0]];
            positions.extend(&sphere.positions);
            let mut triangles = vec![[1u32, 1, 2]];
            triangles.extend(sphere.triangles.iter().map(|t| t.map(|v| v + 1)));
            let input = TriMesh::new(positions, triangles);
            let target = SwingTarget::BitsPerVertex(4.0);
            let options = EncodeOptions {
                mode: match mode {
                    "swing" => EncodeMode::Swing {
                        target,
                        angle_bits: None,
                        max_bytes: None,
                    },
                    _ => EncodeMode::Auto {
                        target,
                        max_bytes: None,
                    },
                },
                origins: true,
                ..Default::default()
            };
            let without = EncodeOptions {
                origins: false,
                ..options.clone()
            };
            assert!(crate::encode(&input, &without)
                .unwrap()
                .stats
                .origins
                .is_empty());
            let encoded = crate::encode(&input, &options).unwrap();
            let plain = crate::decode(&encoded.bytes, &crate::DecodeOptions::plain()).unwrap();
            let origins = &encoded.stats.origins;
            assert_eq!(origins.len(), plain.vertex_count(), "{segments} {mode}");
            for (p, o) in plain.positions.iter().zip(origins) {
                assert!(o.face >= 1, "the degenerate face 0 holds no point");
                let t = input.triangles[o.face as usize];
                let b = o.barycentric;
                assert!(b.iter().all(|&x| x >= 0.0) && (b.iter().sum::<f32>() - 1.0).abs() < 1e-5);
                let x: [f32; 3] = core::array::from_fn(|k| {
                    (0..3)
                        .map(|i| b[i] * input.positions[t[i] as usize][k])
                        .sum()
                });
                let d = (0..3).map(|k| (x[k] - p[k]).powi(2)).sum::<f32>().sqrt();
                assert!(d < 0.05, "{segments} {mode}: {d} from {p:?}");
            }
        }
    }
}
