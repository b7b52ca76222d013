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

/// A closed UV sphere of `nu` x `nv` quads (poles fanned).
pub(crate) fn uv_sphere(nu: u32, nv: u32) -> TriMesh {
    let mut positions = vec![[0.0, 0.0, 1.0f32], [0.0, 0.0, -1.0]];
    for j in 1..nv {
        let t = core::f32::consts::PI * j as f32 / nv as f32;
        for i in 0..nu {
            let p = core::f32::consts::TAU * i as f32 / nu as f32;
            positions.push([t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]);
        }
    }
    let id = |i: u32, j: u32| 2 + (j - 1) * nu + i % nu;
    let mut triangles = Vec::new();
    for i in 0..nu {
        triangles.push([0, id(i, 1), id(i + 1, 1)]);
        triangles.push([1, id(i + 1, nv - 1), id(i, nv - 1)]);
        for j in 1..nv - 1 {
            let (a, b, c, d) = (id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles)
}
