//! Refitting a simplified mesh to the surface it stands for: each vertex
//! moves along its normal by the mean signed distance from the input's
//! samples to the triangles around it, so that chords that cut inside a
//! curved surface (and the quadric's minimum, which sits on the tangent
//! planes) straddle it instead.
//!
//! Source: the fitting step of Hoppe et al., "Mesh optimization"
//! (SIGGRAPH 1993), restricted to normal displacements and solved by
//! Jacobi sweeps: each input sample's signed distance to its nearest
//! triangle (along that triangle's normal) counts for the triangle's
//! three vertices; a vertex moves along its area-weighted normal by the
//! sum of its samples' distances over their count plus [`PRIOR`].
//!
//! Invariants: connectivity never changes; the samples are the input's
//! vertices (deterministic), at most [`MAX_SAMPLES`] of them by a fixed
//! stride; per-sample work runs in parallel but is summed in sample
//! order, so the result does not depend on the thread count.

use super::qem::{cross, dot, sub};
use crate::metrics::{closest_on_triangle, NearestScratch, NearestTree};
use crate::TriMesh;
use rayon::prelude::*;

/// Input vertices used as samples at most.
const MAX_SAMPLES: usize = 200_000;
/// Samples at distance zero each vertex is assumed to have besides its
/// own: a vertex with few samples (a fine simplification, where each
/// triangle holds a handful of input vertices and their mean is mostly
/// noise) moves little. Measured: without it the refit costs 3-14% at
/// 4-8 b/v; with 8 or 32 it gains at every rate but one (BENCHMARKS,
/// "Refitting the simplified mesh").
const PRIOR: f64 = 8.0;
/// Moves shorter than this fraction of the input's diagonal are not made.
const NOISE: f64 = 1e-6;

fn f64v(p: [f32; 3]) -> [f64; 3] {
    p.map(f64::from)
}

/// `sweeps` refits of `mesh` to `reference`'s vertices.
pub fn refit(mesh: &mut TriMesh, reference: &TriMesh, sweeps: usize) {
    if mesh.face_count() == 0 || reference.vertex_count() == 0 {
        return;
    }
    let stride = reference.vertex_count().div_ceil(MAX_SAMPLES);
    // Moves below this are rounding noise (samples on a plane measure
    // 1e-8 off it through f32 triangles): a part exact at a few faces
    // stays exact.
    let still = NOISE * reference.bbox_diagonal();
    let samples: Vec<[f64; 3]> = reference
        .positions
        .iter()
        .step_by(stride)
        .map(|&p| f64v(p))
        .collect();
    for _ in 0..sweeps {
        let tris: Vec<[[f32; 3]; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| mesh.positions[v as usize]))
            .collect();
        let normals: Vec<([f64; 3], f64)> = tris
            .iter()
            .map(|t| {
                let n = cross(sub(f64v(t[1]), f64v(t[0])), sub(f64v(t[2]), f64v(t[0])));
                let len = dot(n, n).sqrt();
                if len > 0.0 {
                    ([n[0] / len, n[1] / len, n[2] / len], 0.5 * len)
                } else {
                    ([0.0; 3], 0.0)
                }
            })
            .collect();
        let tree = NearestTree::new(&tris);
        let hits: Vec<Option<(u32, f64)>> = samples
            .par_chunks(4096)
            .flat_map_iter(|chunk| {
                let mut scratch = NearestScratch::default();
                let mut hint = None;
                chunk
                    .iter()
                    .map(|&p| {
                        let n = tree.nearest(p, hint, &mut scratch)?;
                        hint = Some(n.slot);
                        let t = n.triangle as usize;
                        let q = closest_on_triangle(p, &tris[t]);
                        Some((n.triangle, dot(sub(p, q), normals[t].0)))
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let mut sum = vec![(0.0f64, 0u32); tris.len()];
        for (t, s) in hits.into_iter().flatten() {
            sum[t as usize].0 += s;
            sum[t as usize].1 += 1;
        }
        let mut shift = vec![(0.0f64, 0.0f64, [0.0f64; 3]); mesh.vertex_count()];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let (n, area) = normals[t];
            let (s, k) = sum[t];
            for &v in tri {
                let e = &mut shift[v as usize];
                e.0 += s;
                e.1 += f64::from(k);
                for (acc, c) in e.2.iter_mut().zip(n) {
                    *acc += area * c;
                }
            }
        }
        for (p, (s, w, n)) in mesh.positions.iter_mut().zip(shift) {
            let len = dot(n, n).sqrt();
            if w > 0.0 && len > 0.0 && (s / (w + PRIOR)).abs() > still {
                let d = s / (w + PRIOR) / len;
                for (c, dir) in p.iter_mut().zip(n) {
                    *c = (f64::from(*c) + d * dir) as f32;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_shapes::uv_sphere;
    use crate::metrics::{distance_between, DistanceOptions, Surface};

    fn l2(a: &TriMesh, b: &TriMesh) -> f64 {
        let options = DistanceOptions::area_uniform(20_000);
        distance_between(
            &Surface::new(a).unwrap(),
            &Surface::new(b).unwrap(),
            &options,
        )
        .unwrap()
        .l2()
    }

    #[test]
    fn a_coarse_sphere_moves_out_to_straddle_the_fine_one() {
        let fine = uv_sphere(96, 64);
        let mut coarse = uv_sphere(12, 8);
        let before = l2(&fine, &coarse);
        refit(&mut coarse, &fine, 1);
        let after = l2(&fine, &coarse);
        assert!(after < 0.8 * before, "{before} -> {after}");
        // Chords cut inside: the vertices moved outward, and the
        // connectivity stayed.
        assert!(coarse.positions.iter().all(|p| {
            let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            (1.0..1.2).contains(&r)
        }));
        assert_eq!(coarse.triangles, uv_sphere(12, 8).triangles);
    }

    #[test]
    fn a_mesh_that_is_its_own_reference_barely_moves() {
        let m = uv_sphere(24, 16);
        let mut copy = m.clone();
        refit(&mut copy, &m, 1);
        for (a, b) in m.positions.iter().zip(&copy.positions) {
            let d = (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0f32, f32::max);
            assert!(d < 1e-5, "{a:?} -> {b:?}");
        }
    }
}
