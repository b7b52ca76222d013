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

/// [`unit_cube`] with per-face normals (6 values, one per side: a crease
/// at every edge) and texture coordinates laid out as a cross of six
/// squares, so that most edges are UV seams (24 values, 14 distinct), the quads'
/// corners as on a real unwrapped cube: a position carries up to three
/// normals and three texture coordinates.
pub(crate) fn seamed_cube() -> super::AttributedMesh {
    use super::{AttributeKind, AttributeStream};
    let mesh = unit_cube();
    let normals = [
        [-1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 0.0, 1.0],
    ];
    let normal_corners = (0..12).map(|f| [f / 2; 3]).collect();
    // A cross: squares (column, row) of a 4 x 3 grid, in quarters/thirds.
    let cells = [(0, 1), (2, 1), (1, 0), (1, 2), (1, 1), (3, 1)];
    let mut uv = Vec::new();
    let mut uv_corners = Vec::new();
    for &(i, j) in &cells {
        let base = (uv.len() / 2) as u32;
        for (du, dv) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
            uv.push((i + du) as f32 / 4.0);
            uv.push((j + dv) as f32 / 3.0);
        }
        uv_corners.push([base, base + 1, base + 2]);
        uv_corners.push([base, base + 2, base + 3]);
    }
    super::AttributedMesh::new(
        mesh,
        vec![
            AttributeStream::new(
                AttributeKind::Normal,
                3,
                normals.iter().flatten().copied().collect(),
                normal_corners,
            ),
            AttributeStream::new(AttributeKind::TexCoord(0), 2, uv, uv_corners),
        ],
    )
}

/// [`uv_sphere`] with an RGBA colour per vertex that no `u8` gives
/// exactly (a float file keeps them, an 8-bit one would round them).
pub(crate) fn coloured_sphere() -> super::AttributedMesh {
    use super::{AttributeKind, AttributeStream};
    let mesh = uv_sphere(12, 6);
    let colours = mesh
        .positions
        .iter()
        .flat_map(|p| [0.5 + 0.5 * p[0], 0.5 + 0.5 * p[1], 0.5 + 0.5 * p[2], 0.3])
        .collect();
    let corners = mesh.triangles.clone();
    super::AttributedMesh::new(
        mesh,
        vec![AttributeStream::new(
            AttributeKind::Color(0),
            4,
            colours,
            corners,
        )],
    )
}

/// `uv_sphere(nu, nv)` with latitude-longitude texture coordinates (a
/// seam along longitude 0, where `u` is 0 on one side and 1 on the
/// other; one value per pole corner) and smooth normals. Shared by the
/// lossless mode's round trips and the lossy encodes that keep
/// attributes (`encoder::tests_attributed`).
pub(crate) fn textured_sphere(nu: u32, nv: u32) -> super::AttributedMesh {
    use super::{AttributeKind, AttributeStream, AttributedMesh};
    let mesh = uv_sphere(nu, nv);
    let mut uv = Vec::new();
    let mut uv_corners = Vec::new();
    let mut value = |u: f32, v: f32| {
        uv.extend_from_slice(&[u, v]);
        (uv.len() / 2 - 1) as u32
    };
    // Grid values (i, j) for i in 0..=nu, j in 1..nv; pole corners apart.
    let mut grid = vec![0u32; ((nu + 1) * (nv + 1)) as usize];
    for j in 1..nv {
        for i in 0..=nu {
            grid[(j * (nu + 1) + i) as usize] = value(i as f32 / nu as f32, j as f32 / nv as f32);
        }
    }
    let g = |i: u32, j: u32| grid[(j * (nu + 1) + i) as usize];
    for i in 0..nu {
        let top = value((i as f32 + 0.5) / nu as f32, 0.0);
        uv_corners.push([top, g(i, 1), g(i + 1, 1)]);
        let bottom = value((i as f32 + 0.5) / nu as f32, 1.0);
        uv_corners.push([bottom, g(i + 1, nv - 1), g(i, nv - 1)]);
        for j in 1..nv - 1 {
            uv_corners.push([g(i, j), g(i, j + 1), g(i + 1, j + 1)]);
            uv_corners.push([g(i, j), g(i + 1, j + 1), g(i + 1, j)]);
        }
    }
    let normals = mesh.positions.iter().flatten().copied().collect();
    let corners = mesh.triangles.clone();
    AttributedMesh::new(
        mesh,
        vec![
            AttributeStream::new(AttributeKind::TexCoord(0), 2, uv, uv_corners),
            AttributeStream::new(AttributeKind::Normal, 3, normals, corners),
        ],
    )
}
