//! Quality measures of a triangle mesh, as the tests of this crate (and of
//! the remesher and codec that consume its meshes) check them.
//!
//! All measures are computed in `f64` from the stored `f32` positions, so
//! they describe exactly the mesh a consumer sees.

use swm::TriMesh;

use crate::vec::{dot, from_f32, length, min_angle, tri_normal, V3};

fn corners(mesh: &TriMesh, t: [u32; 3]) -> [V3; 3] {
    t.map(|v| from_f32(mesh.positions[v as usize]))
}

/// The smallest interior angle over all triangles, in degrees (180 for a
/// mesh without triangles).
pub fn min_angle_degrees(mesh: &TriMesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|&t| {
            let [a, b, c] = corners(mesh, t);
            min_angle(a, b, c).to_degrees()
        })
        .fold(180.0, f64::min)
}

/// The smallest triangle area (infinity for a mesh without triangles).
pub fn min_area(mesh: &TriMesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|&t| {
            let [a, b, c] = corners(mesh, t);
            0.5 * length(tri_normal(a, b, c))
        })
        .fold(f64::INFINITY, f64::min)
}

/// The signed volume enclosed by the triangles (divergence theorem):
/// positive for a closed mesh whose triangles are counter-clockwise seen
/// from outside.
pub fn signed_volume(mesh: &TriMesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|&t| {
            let [a, b, c] = corners(mesh, t);
            dot(a, tri_normal(a, b, c)) / 6.0
        })
        .sum()
}

/// The number of positions equal (bit for bit, after `-0 == 0`) to an
/// earlier position.
pub fn duplicate_positions(mesh: &TriMesh) -> usize {
    // Adding 0.0 maps -0.0 to +0.0, so the bit patterns compare as values.
    let mut keys: Vec<[u32; 3]> = mesh
        .positions
        .iter()
        .map(|p| p.map(|x| (x + 0.0).to_bits()))
        .collect();
    keys.sort_unstable();
    keys.windows(2).filter(|w| w[0] == w[1]).count()
}
