//! Small meshes shared by the unit tests of several modules.

use super::TriMesh;

/// The unit cube [0, 1]³ as 12 triangles, outward oriented: faces wider
/// than any edge length a test retiles at, and corners whose normals
/// point along the diagonals.
pub(crate) fn unit_cube() -> TriMesh {
    let p = (0..8)
        .map(|i| [(i >> 2) as f32, ((i >> 1) & 1) as f32, (i & 1) as f32])
        .collect();
    let quads = [
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 6, 7, 5],
    ];
    let f = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    TriMesh::new(p, f)
}
