//! Meshes of parametric surfaces: UV sphere, icosphere, torus, plane patch.
//!
//! Each generator samples its parameter domain on a regular grid and
//! connects the samples by index, so seams and poles are welded by
//! construction (no duplicate positions, no merging step). Guarantees:
//! manifold, consistently counter-clockwise seen from outside (from +z for
//! the plane patch), no zero-area triangles, and the topology in each
//! function's documentation.

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

use swm::TriMesh;

use crate::vec::{dot, normalize, scale, to_f32, tri_normal, V3};

/// Pushes the two triangles of the quad `a b c d` (counter-clockwise),
/// split along the diagonal `a c`.
fn quad(tris: &mut Vec<[u32; 3]>, a: u32, b: u32, c: u32, d: u32) {
    tris.push([a, b, c]);
    tris.push([a, c, d]);
}

/// A latitude-longitude sphere centred at the origin.
///
/// `stacks` rings of latitude divide the pole-to-pole arc; `slices`
/// meridians divide each ring. The poles are single vertices joined to the
/// first and last ring by triangle fans, so the mesh is closed, genus 0,
/// with `2 + (stacks - 1) * slices` vertices and `2 * slices * (stacks - 1)`
/// triangles. The thinnest triangles touch the poles, with a smallest
/// angle a little under `360 / slices` degrees (7.4 for 48 slices), so keep
/// `slices` moderate.
///
/// # Panics
/// If `stacks < 2`, `slices < 3` or `radius` is not positive.
pub fn uv_sphere(radius: f64, stacks: u32, slices: u32) -> TriMesh {
    assert!(
        stacks >= 2 && slices >= 3,
        "uv_sphere needs stacks >= 2 and slices >= 3"
    );
    assert!(radius > 0.0, "uv_sphere needs a positive radius");
    let mut positions = vec![to_f32([0.0, 0.0, radius])];
    for j in 1..stacks {
        let theta = PI * j as f64 / stacks as f64;
        for i in 0..slices {
            let phi = TAU * i as f64 / slices as f64;
            positions.push(to_f32([
                radius * theta.sin() * phi.cos(),
                radius * theta.sin() * phi.sin(),
                radius * theta.cos(),
            ]));
        }
    }
    let south = positions.len() as u32;
    positions.push(to_f32([0.0, 0.0, -radius]));

    let ring = |j: u32, i: u32| 1 + (j - 1) * slices + i % slices;
    let mut tris = Vec::with_capacity(2 * (slices * (stacks - 1)) as usize);
    for i in 0..slices {
        // North fan: seen from +z, increasing longitude runs counter-clockwise.
        tris.push([0, ring(1, i), ring(1, i + 1)]);
    }
    for j in 1..stacks - 1 {
        for i in 0..slices {
            quad(
                &mut tris,
                ring(j, i),
                ring(j + 1, i),
                ring(j + 1, i + 1),
                ring(j, i + 1),
            );
        }
    }
    for i in 0..slices {
        tris.push([south, ring(stacks - 1, i + 1), ring(stacks - 1, i)]);
    }
    TriMesh::new(positions, tris)
}

/// A geodesic sphere centred at the origin: the regular icosahedron with
/// each triangle split 1-to-4 `subdivisions` times, new vertices projected
/// onto the sphere.
///
/// Closed, genus 0, `10 * 4^s + 2` vertices and `20 * 4^s` triangles. The
/// 12 icosahedron vertices have valence 5; every other vertex has valence
/// 6, which makes this the "regular" connectivity test mesh. Triangles are
/// nearly equilateral (smallest angle above 50 degrees).
///
/// # Panics
/// If `subdivisions > 9` (over 5 million triangles) or `radius` is not
/// positive.
pub fn icosphere(radius: f64, subdivisions: u32) -> TriMesh {
    assert!(subdivisions <= 9, "icosphere: at most 9 subdivisions");
    assert!(radius > 0.0, "icosphere needs a positive radius");
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    // The 12 vertices are the cyclic permutations of (0, +-1, +-g).
    let mut pts: Vec<V3> = [
        [-1.0, g, 0.0],
        [1.0, g, 0.0],
        [-1.0, -g, 0.0],
        [1.0, -g, 0.0],
        [0.0, -1.0, g],
        [0.0, 1.0, g],
        [0.0, -1.0, -g],
        [0.0, 1.0, -g],
        [g, 0.0, -1.0],
        [g, 0.0, 1.0],
        [-g, 0.0, -1.0],
        [-g, 0.0, 1.0],
    ]
    .into_iter()
    .map(normalize)
    .collect();
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    debug_assert!(tris.iter().all(|t| {
        let [a, b, c] = t.map(|v| pts[v as usize]);
        dot(tri_normal(a, b, c), a) > 0.0
    }));
    for _ in 0..subdivisions {
        // One new vertex per edge, shared by the edge's two triangles.
        let mut mid: HashMap<(u32, u32), u32> = HashMap::with_capacity(tris.len() * 3 / 2);
        let mut midpoint = |a: u32, b: u32, pts: &mut Vec<V3>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (pts[a as usize], pts[b as usize]);
                pts.push(normalize([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                pts.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(tris.len() * 4);
        for &[a, b, c] in &tris {
            let ab = midpoint(a, b, &mut pts);
            let bc = midpoint(b, c, &mut pts);
            let ca = midpoint(c, a, &mut pts);
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    let positions = pts.into_iter().map(|p| to_f32(scale(p, radius))).collect();
    TriMesh::new(positions, tris)
}

/// A ring torus around the z axis, centred at the origin.
///
/// `major_segments` samples run around the z axis, `minor_segments` around
/// the tube. Closed, genus 1, `major * minor` vertices, `2 * major * minor`
/// triangles; quads are split along the same diagonal everywhere.
///
/// # Panics
/// If a segment count is below 3 or `0 < minor_r < major_r` fails.
pub fn torus(major_r: f64, minor_r: f64, major_segments: u32, minor_segments: u32) -> TriMesh {
    assert!(
        major_segments >= 3 && minor_segments >= 3,
        "torus needs at least 3 segments each way"
    );
    assert!(
        0.0 < minor_r && minor_r < major_r,
        "torus needs 0 < minor_r < major_r"
    );
    let (nu, nv) = (major_segments, minor_segments);
    let mut positions = Vec::with_capacity((nu * nv) as usize);
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            let rho = major_r + minor_r * v.cos();
            positions.push(to_f32([rho * u.cos(), rho * u.sin(), minor_r * v.sin()]));
        }
    }
    let id = |i: u32, j: u32| (i % nu) * nv + j % nv;
    let mut tris = Vec::with_capacity(2 * (nu * nv) as usize);
    for i in 0..nu {
        for j in 0..nv {
            // dP/du x dP/dv points out of the tube, so (u, v) order is
            // counter-clockwise seen from outside.
            quad(
                &mut tris,
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1),
            );
        }
    }
    TriMesh::new(positions, tris)
}

/// A gently curved rectangular grid: `nx` by `ny` square cells over
/// `[-1, 1] x [-ny/nx, ny/nx]`, lifted to `z = 0.1 sin(pi x) cos(pi y / 2)`.
///
/// Genus 0 with one boundary loop, `(nx + 1) * (ny + 1)` vertices and
/// `2 * nx * ny` triangles, counter-clockwise seen from +z. Every quad is
/// split along the same diagonal, so interior vertices have valence 6.
///
/// # Panics
/// If `nx` or `ny` is 0.
pub fn plane_patch(nx: u32, ny: u32) -> TriMesh {
    assert!(
        nx >= 1 && ny >= 1,
        "plane_patch needs at least one cell each way"
    );
    let step = 2.0 / nx as f64;
    let y0 = -(ny as f64) / nx as f64;
    let mut positions = Vec::with_capacity(((nx + 1) * (ny + 1)) as usize);
    for j in 0..=ny {
        let y = y0 + step * j as f64;
        for i in 0..=nx {
            let x = -1.0 + step * i as f64;
            let z = 0.1 * (PI * x).sin() * (0.5 * PI * y).cos();
            positions.push(to_f32([x, y, z]));
        }
    }
    let id = |i: u32, j: u32| j * (nx + 1) + i;
    let mut tris = Vec::with_capacity(2 * (nx * ny) as usize);
    for j in 0..ny {
        for i in 0..nx {
            quad(
                &mut tris,
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1),
            );
        }
    }
    TriMesh::new(positions, tris)
}
