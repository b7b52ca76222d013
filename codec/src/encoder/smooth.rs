//! Normals that follow the geometry (beyond the sources): a lossy encode
//! of a mesh with normals that its own surface gives back (a scan's
//! normals estimated from its points, an exporter's smooth vertex
//! normals) does not code them, since a decoder recomputes them from the
//! decoded surface, which a simplified file has changed anyway; normals
//! that carry something the surface does not (split at creases, custom
//! or baked shading) are kept.
//!
//! Why: on horse (normals within 1.4° RMS of its own) the default encode
//! at 1 b/v kept the normals in 39% of the file (2,324 of 5,997 bytes at
//! qn 8), which left its L2 at 10.7 against 2.26 without them; Draco and
//! gltfpack code what they are given, but a user asking swm for a size
//! asks for the surface.
//!
//! The test: the RMS angle, over the face corners, between a corner's
//! normal and the angle-weighted normal of its position in the input
//! (`mesh::normals::vertex_normals`); at most [`SMOOTH_NORMAL_DEGREES`]
//! is smooth. A crease with split normals puts its corners tens of
//! degrees off, so a part with hard edges keeps them.

use crate::{AttributeKind, AttributedMesh};
use glam::DVec3;
use rayon::prelude::*;

/// Triangles per block of the angle sum (its order is fixed by them).
const BLOCK: usize = 8192;

/// The largest RMS angle (degrees) between a mesh's normals and its
/// geometry's that counts as following the geometry. Scanner and
/// smooth-shaded exporter normals measure 0-5°; a part whose normals
/// split at its creases 20° and more.
pub const SMOOTH_NORMAL_DEGREES: f64 = 10.0;

/// The RMS angle in degrees between `mesh`'s normal stream and its
/// geometry's own vertex normals, when it has a normal stream and that
/// angle is at most [`SMOOTH_NORMAL_DEGREES`]; `None` otherwise.
pub(crate) fn smooth_normals(mesh: &AttributedMesh) -> Option<f64> {
    let stream = mesh
        .streams
        .iter()
        .find(|s| s.kind == AttributeKind::Normal)?;
    if stream.dims != 3 {
        return None;
    }
    let geometric = crate::mesh::vertex_normals_par(&mesh.mesh);
    // Summed per block of triangles on all cores, the blocks' sums added
    // in order: the same figure at any thread count.
    let corners = mesh
        .mesh
        .triangles
        .par_chunks(BLOCK)
        .zip(stream.corners.par_chunks(BLOCK));
    let blocks: Option<Vec<(f64, u64)>> = corners
        .map(|(ts, cs)| {
            let (mut sum, mut n) = (0.0f64, 0u64);
            for (t, c) in ts.iter().zip(cs) {
                for k in 0..3 {
                    let g = DVec3::from(geometric.get(t[k] as usize)?.map(f64::from));
                    let at = c[k] as usize * 3;
                    let v = stream.values.get(at..at + 3)?;
                    let v = DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64);
                    if g == DVec3::ZERO || v == DVec3::ZERO {
                        continue;
                    }
                    let angle = g.angle_between(v).to_degrees();
                    sum += angle * angle;
                    n += 1;
                }
            }
            Some((sum, n))
        })
        .collect();
    let (mut sum, mut n) = (0.0f64, 0u64);
    for (s, k) in blocks? {
        sum += s;
        n += k;
    }
    if n == 0 {
        return None;
    }
    let rms = (sum / n as f64).sqrt();
    (rms <= SMOOTH_NORMAL_DEGREES).then_some(rms)
}

/// `mesh` without its normal stream.
pub(crate) fn without_normals(mesh: &AttributedMesh) -> AttributedMesh {
    AttributedMesh {
        mesh: mesh.mesh.clone(),
        streams: mesh
            .streams
            .iter()
            .filter(|s| s.kind != AttributeKind::Normal)
            .cloned()
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_shapes::{seamed_cube, uv_sphere};
    use crate::AttributeStream;

    #[test]
    fn a_spheres_own_normals_are_smooth_and_a_cubes_split_ones_are_not() {
        let mesh = uv_sphere(24, 16);
        let normals: Vec<f32> = mesh
            .positions
            .iter()
            .flat_map(|p| {
                let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                [p[0] / l, p[1] / l, p[2] / l]
            })
            .collect();
        let corners = mesh.triangles.clone();
        let sphere = AttributedMesh {
            mesh,
            streams: vec![AttributeStream::new(
                AttributeKind::Normal,
                3,
                normals,
                corners,
            )],
        };
        let rms = smooth_normals(&sphere).expect("smooth");
        assert!(rms < 5.0, "{rms}");
        assert!(without_normals(&sphere).streams.is_empty());
        // A cube with one normal per side: every corner 54.7° off its
        // vertex's diagonal normal.
        assert_eq!(smooth_normals(&seamed_cube()), None);
    }
}
