//! Angle-weighted vertex normals (G. Thürrmer and C. A. Wüthrich,
//! "Computing vertex normals from polygonal facets", 1998).
//!
//! The format stores no normals; viewers need them for shading. Each
//! triangle adds its unit normal to each of its corners' vertices,
//! weighted by the triangle's angle at that corner:
//!
//! ```text
//!            c
//!           / \          n(a) += α · N(abc),  α = angle at a
//!          /   \
//!         a --- b
//! ```
//!
//! Weighting by angle (not by area, not uniformly) makes the normal depend
//! only on the surface around the vertex, not on how it was triangulated,
//! which matters here: retiled and subdivided meshes cut the same surface
//! into very different fans.
//!
//! Invariants: every output is unit length or, for a vertex with no
//! non-degenerate triangle (or non-finite input), exactly zero; the
//! result depends only on positions and triangles, computed in `f64`
//! with `libm` (`crate::math`), so every build gives the same bits.

use crate::math;
use crate::prelude::*;

use glam::DVec3;

use super::TriMesh;

/// Unit angle-weighted normals of every vertex of `mesh`, in vertex order.
///
/// Indices out of range are skipped, so a mesh that fails
/// [`TriMesh::validate`] still gets normals without a panic.
pub fn vertex_normals(mesh: &TriMesh) -> Vec<[f32; 3]> {
    let mut acc = vec![DVec3::ZERO; mesh.positions.len()];
    for t in &mesh.triangles {
        accumulate(&mut acc, |v| mesh.positions.get(v as usize).copied(), *t);
    }
    acc.into_iter().map(unit).collect()
}

/// [`vertex_normals`] with each triangle's corner contributions (three
/// arc tangents) made on all cores: the same bits at any thread count,
/// since the contributions are summed into their vertices serially in
/// triangle order, as [`vertex_normals`] sums them. The encoder's test of
/// a scan's normals (`encoder::smooth`) ran 12 ms on one core for horse's
/// 97k triangles, before the cleaning, with the other core idle.
#[cfg(feature = "encoder")]
pub(crate) fn vertex_normals_par(mesh: &TriMesh) -> Vec<[f32; 3]> {
    use rayon::prelude::*;
    let at = |v: u32| mesh.positions.get(v as usize).copied();
    let contributions: Vec<Option<[DVec3; 3]>> = mesh
        .triangles
        .par_iter()
        .with_min_len(4096)
        .map(|t| weighted(at, *t))
        .collect();
    let mut acc = vec![DVec3::ZERO; mesh.positions.len()];
    for (t, w) in mesh.triangles.iter().zip(contributions) {
        if let Some(w) = w {
            add(&mut acc, *t, &w);
        }
    }
    acc.into_iter().map(unit).collect()
}

/// [`vertex_normals`] over flat buffers, as a viewer holds them:
/// `positions` is `x y z` per vertex, `indices` three per triangle, and
/// `normals` receives `x y z` per vertex (its length must be that of
/// `positions`; a trailing partial vertex or triangle is ignored).
///
/// Accumulates in `f32` inside `normals` instead of allocating an `f64`
/// buffer, so the result can differ from [`vertex_normals`] in the last
/// bits.
pub fn vertex_normals_into(positions: &[f32], indices: &[u32], normals: &mut [f32]) {
    normals.fill(0.0);
    let n = positions.len().min(normals.len()) / 3;
    let at = |v: u32| -> Option<[f32; 3]> {
        let i = v as usize;
        (i < n).then(|| [positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]])
    };
    for t in indices.chunks_exact(3) {
        let Some(w) = weighted(at, [t[0], t[1], t[2]]) else {
            continue;
        };
        for (k, &v) in t.iter().enumerate() {
            let i = 3 * v as usize;
            normals[i] += w[k].x as f32;
            normals[i + 1] += w[k].y as f32;
            normals[i + 2] += w[k].z as f32;
        }
    }
    for c in normals[..3 * n].chunks_exact_mut(3) {
        let u = unit(DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64));
        c.copy_from_slice(&u);
    }
}

fn accumulate(acc: &mut [DVec3], at: impl Fn(u32) -> Option<[f32; 3]>, t: [u32; 3]) {
    if let Some(w) = weighted(at, t) {
        add(acc, t, &w);
    }
}

/// Adds triangle `t`'s corner contributions `w` to its vertices.
fn add(acc: &mut [DVec3], t: [u32; 3], w: &[DVec3; 3]) {
    for (k, &v) in t.iter().enumerate() {
        acc[v as usize] += w[k];
    }
}

/// The three corner contributions of triangle `t`: its unit normal times
/// the angle at each corner; `None` if a corner is out of range or the
/// triangle has no normal (zero area, non-finite).
fn weighted(at: impl Fn(u32) -> Option<[f32; 3]>, t: [u32; 3]) -> Option<[DVec3; 3]> {
    let p = [at(t[0])?, at(t[1])?, at(t[2])?].map(|q| DVec3::from(q.map(f64::from)));
    let cross = (p[1] - p[0]).cross(p[2] - p[0]);
    let len = math::sqrt(cross.length_squared());
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let n = cross / len;
    // |u × v| is twice the triangle's area at every corner, so only the
    // dot product differs between the three angles.
    let angle = |k: usize| {
        let (u, v) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
        math::atan2(len, u.dot(v))
    };
    Some([n * angle(0), n * angle(1), n * angle(2)])
}

/// `v / |v|` as `f32`, or zero when `v` has no direction.
fn unit(v: DVec3) -> [f32; 3] {
    let len = math::sqrt(v.length_squared());
    if len > 0.0 && len.is_finite() {
        (v / len).as_vec3().to_array()
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cube's corner sees three faces at right angles, each with the same
    /// total angle, whatever the diagonal of each face: the normal is the
    /// corner's diagonal. Area weighting would get it too; uniform weighting
    /// (per triangle) would not, as corners touch one or two triangles per
    /// face.
    #[test]
    fn cube_corners_point_along_diagonals() {
        let mesh = crate::mesh::test_shapes::unit_cube();
        let p = mesh.positions.clone();
        let normals = vertex_normals(&mesh);
        for (v, n) in normals.iter().enumerate() {
            let d = DVec3::from(p[v].map(f64::from)) - DVec3::splat(0.5);
            let want = d.normalize();
            let got = DVec3::from(n.map(f64::from));
            assert!((got - want).length() < 1e-6, "vertex {v}: {got} vs {want}");
        }
        let flat = mesh.positions.as_flattened();
        let idx = mesh.triangles.as_flattened();
        let mut into = vec![9.0; flat.len()];
        vertex_normals_into(flat, idx, &mut into);
        for (a, b) in into.iter().zip(normals.as_flattened()) {
            assert!((a - b).abs() < 1e-6);
        }
    }

    #[test]
    fn degenerate_and_out_of_range_give_zero_without_panic() {
        let mesh = TriMesh::new(
            vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [f32::NAN, 0.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 1, 3], [0, 1, 7]],
        );
        assert_eq!(vertex_normals(&mesh), vec![[0.0; 3]; 4]);
        let mut n = vec![1.0; 12];
        vertex_normals_into(
            mesh.positions.as_flattened(),
            &[0, 1, 2, 0, 1, 7, 5],
            &mut n,
        );
        assert_eq!(n, vec![0.0; 12]);
    }

    #[test]
    fn fan_split_unevenly_keeps_its_normal() {
        // A vertex on a crease between a flat face cut into many slivers
        // and one face tilted 90°: angle weighting gives both sides equal
        // say (90° each), so the normal bisects the crease.
        let mut p = vec![[0.0f32, 0.0, 0.0]];
        let mut t = Vec::new();
        let k = 12;
        for i in 0..=k {
            let a = core::f32::consts::FRAC_PI_2 * i as f32 / k as f32;
            p.push([a.cos(), a.sin(), 0.0]);
            if i > 0 {
                t.push([0, i as u32, i as u32 + 1]);
            }
        }
        let top = p.len() as u32;
        p.push([0.0, 0.0, 1.0]);
        t.push([0, top, 1]);
        let n = vertex_normals(&TriMesh::new(p, t))[0];
        let want = DVec3::new(0.0, 1.0, 1.0).normalize();
        assert!(
            (DVec3::from(n.map(f64::from)) - want).length() < 1e-6,
            "{n:?}"
        );
    }

    /// The parallel sum is the serial one, bit for bit, on a mesh large
    /// enough to be split between threads (and with a degenerate face).
    #[cfg(feature = "encoder")]
    #[test]
    fn the_parallel_normals_are_the_serial_ones() {
        let mut mesh = crate::mesh::test_shapes::uv_sphere(120, 90);
        mesh.triangles.push([0, 0, 1]);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        let par = pool.install(|| vertex_normals_par(&mesh));
        assert_eq!(par, vertex_normals(&mesh));
    }
}
