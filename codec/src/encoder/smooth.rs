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
/// geometry's own vertex normals; `None` without a normal stream of
/// three components (or a corner to compare). At most
/// [`SMOOTH_NORMAL_DEGREES`], the normals follow the geometry.
pub(crate) fn normals_off(mesh: &AttributedMesh) -> Option<f64> {
    let stream = mesh
        .streams
        .iter()
        .find(|s| s.kind == AttributeKind::Normal)?;
    if stream.dims != 3 {
        return None;
    }
    // Over the surface welded by position: a mesh split where its normals
    // are (Python's per-vertex arrays, a glTF primitive) has, at a
    // crease, a vertex on each side whose own normal follows its side,
    // which is not what a decoder recomputes.
    let (welded, at) = welded(&mesh.mesh);
    let geometric = |v: u32| Some(welded[*at.get(v as usize)? as usize]);
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
                    let g = DVec3::from(geometric(t[k])?.map(f64::from));
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
    Some((sum / n as f64).sqrt())
}

/// The vertex normals of `mesh` welded by position (positions equal to
/// the bit, either zero: `-0.0` is read as `0.0`, the same point), and
/// each vertex's welded one (`mesh::dedupe`, as `AttributedMesh::weld`).
fn welded(mesh: &crate::TriMesh) -> (Vec<[f32; 3]>, Vec<u32>) {
    let flat: Vec<f32> = (mesh.positions.iter().flatten())
        .map(|&c| if c == 0.0 { 0.0 } else { c })
        .collect();
    let (kept, at) = crate::mesh::dedupe(&flat, 3);
    let positions = kept.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| at.get(v as usize).copied().unwrap_or(u32::MAX)))
        .collect();
    let normals = crate::mesh::vertex_normals_par(&crate::TriMesh::new(positions, triangles));
    (normals, at)
}

/// What one degree of RMS normal error weighs beside L2, as a fraction
/// of the input's diagonal: 1e-4, as a texel and an 8-bit colour step
/// do (`simplify::attributed`): a shading normal a degree off is at the
/// edge of what shows, as is a surface 1e-4 of the diagonal off.
pub const NORMAL_DEGREE_WEIGHT: f64 = 1e-4;

/// Normals that do not follow the geometry (creases, custom shading) but
/// crowd the surface out (beyond the sources): a lossy file that keeps
/// them is weighed against the file without them at the same size, the
/// latter's error counted as its L2 plus the dropped normals' own error,
/// `off_degrees` (their RMS angle from the input geometry's normals,
/// [`normals_off`]: what a decoder recomputing them from the input's
/// own surface would miss) at [`NORMAL_DEGREE_WEIGHT`]. Beetle's crease
/// normals at 454 bytes took 252 of them, and the surface was 443e-4 of
/// the diagonal off against 34e-4 without them.
///
/// The second file is searched at effort `fast` when `default` was asked
/// for (`encoder::without_costly_normals`), so the comparison leans
/// towards keeping them.
///
/// This tells whether that second file is worth making: only where the
/// kept file's L2 (`l2_kept`, relative) is above the dropped normals'
/// weighed error can the file without them win, since its own L2 adds
/// to that.
pub(crate) fn may_cost_more_than_they_give(l2_kept: f64, off_degrees: f64) -> bool {
    l2_kept > NORMAL_DEGREE_WEIGHT * off_degrees
}

/// Whether the file without the normals (`l2_without`, relative) is
/// closer to the input than the one that kept them, the normals' error
/// weighed as [`may_cost_more_than_they_give`] says.
pub(crate) fn cost_more_than_they_give(l2_kept: f64, l2_without: f64, off_degrees: f64) -> bool {
    l2_without + NORMAL_DEGREE_WEIGHT * off_degrees < l2_kept
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
        let rms = normals_off(&sphere).expect("normals");
        assert!(rms < 5.0, "{rms}");
        assert!(without_normals(&sphere).streams.is_empty());
        // A cube with one normal per side: every corner 54.7° off its
        // vertex's diagonal normal.
        assert!(normals_off(&seamed_cube()).expect("normals") > SMOOTH_NORMAL_DEGREES);
    }

    /// The same cube with every triangle on vertices of its own (as
    /// Python's per-vertex arrays and glTF split a mesh at its normals'
    /// seams): judged as the welded surface, the same angle.
    #[test]
    fn a_mesh_split_at_its_normals_is_judged_welded() {
        let cube = seamed_cube();
        let normals = cube.stream(AttributeKind::Normal).unwrap();
        let (mut positions, mut values, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        for (f, t) in cube.mesh.triangles.iter().enumerate() {
            let first = positions.len() as u32;
            for (k, &v) in t.iter().enumerate() {
                positions.push(cube.mesh.positions[v as usize]);
                values.extend(normals.corner_value(crate::FaceId(f as u32), k));
            }
            triangles.push([first, first + 1, first + 2]);
        }
        let corners = triangles.clone();
        let split = AttributedMesh {
            mesh: crate::TriMesh::new(positions, triangles),
            streams: vec![AttributeStream::new(
                AttributeKind::Normal,
                3,
                values,
                corners,
            )],
        };
        let (a, b) = (normals_off(&split).unwrap(), normals_off(&cube).unwrap());
        assert!((a - b).abs() < 1e-9 && a > 50.0, "{a} {b}");
    }
}
