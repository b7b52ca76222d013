//! `TriMesh`, the indexed triangle mesh every part of the crate reads and
//! writes, and the removal of the vertices no triangle uses.
//!
//! Positions are `f32`; [`TriMesh::point`] and the other geometric
//! accessors give `f64` (see the module header of `mesh`).

use crate::prelude::*;

use super::ids::{FaceId, VertexId};
use glam::DVec3;

/// An indexed triangle mesh: vertex positions and counter-clockwise
/// triangles (seen from outside) that index them.
///
/// The fields are public so that viewers can hand them to a GPU directly;
/// [`TriMesh::validate`] checks the invariants that the rest of the crate
/// assumes (finite positions, indices in range).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, as three vertex indices each.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// A mesh from its parts (not validated).
    pub fn new(positions: Vec<[f32; 3]>, triangles: Vec<[u32; 3]>) -> Self {
        TriMesh {
            positions,
            triangles,
        }
    }

    /// Number of vertices.
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of distinct positions (bit for bit, `-0.0` as `0.0`), used
    /// or not: what a rate in bits per vertex counts. An OBJ file lists
    /// each position once, a glTF file repeats it for every normal or
    /// texture coordinate it carries (a box: 24 vertices, 8 positions),
    /// so a rate means the same bytes for the same shape in either.
    pub fn distinct_positions(&self) -> usize {
        let key = |p: &[f32; 3]| p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
        let mut keys: Vec<[u32; 3]> = self.positions.iter().map(key).collect();
        crate::sort::sort_unstable(&mut keys);
        keys.dedup();
        keys.len()
    }

    /// Number of triangles.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.triangles.len()
    }

    /// A vertex position in double precision.
    #[inline]
    pub fn point(&self, v: VertexId) -> DVec3 {
        let p = self.positions[v.idx()];
        DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
    }

    /// The three corner positions of a triangle, in double precision.
    #[inline]
    pub fn face_points(&self, f: FaceId) -> [DVec3; 3] {
        let t = self.triangles[f.idx()];
        [
            self.point(VertexId(t[0])),
            self.point(VertexId(t[1])),
            self.point(VertexId(t[2])),
        ]
    }

    /// Twice the area vector of a triangle (its unnormalized normal).
    #[inline]
    pub fn face_cross(&self, f: FaceId) -> DVec3 {
        let [a, b, c] = self.face_points(f);
        (b - a).cross(c - a)
    }

    /// Axis-aligned bounding box of all vertices, `None` for an empty mesh.
    pub fn bbox(&self) -> Option<(DVec3, DVec3)> {
        let first = self.positions.first()?;
        let (mut lo, mut hi) = (*first, *first);
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let d = |a: [f32; 3]| DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64);
        Some((d(lo), d(hi)))
    }

    /// Length of the bounding-box diagonal (0 for an empty mesh).
    pub fn bbox_diagonal(&self) -> f64 {
        self.bbox().map_or(0.0, |(lo, hi)| (hi - lo).length())
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len() as u32)
            .map(|f| 0.5 * self.face_cross(FaceId(f)).length())
            .sum()
    }

    /// Checks that every position is finite and every index is in range.
    pub fn validate(&self) -> Result<(), crate::FormatError> {
        use crate::{FormatError, Malformed};
        for (i, p) in self.positions.iter().enumerate() {
            if !p.iter().all(|x| x.is_finite()) {
                return Err(FormatError::new(
                    "mesh",
                    Malformed::NonFinite { vertex: i as u64 },
                ));
            }
        }
        let n = self.positions.len() as u64;
        for t in &self.triangles {
            for &v in t {
                if v as u64 >= n {
                    return Err(FormatError::new(
                        "mesh",
                        Malformed::IndexOutOfRange {
                            index: v as i64,
                            vertices: n,
                        },
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The positions `triangles` use, in their order, with `triangles`
/// renumbered to them: what is left of a mesh once the vertices no
/// triangle uses are dropped. An index out of range becomes `u32::MAX`
/// (which `TriMesh::validate` rejects) instead of panicking.
pub(crate) fn compact_vertices(
    positions: &[[f32; 3]],
    triangles: &mut [[u32; 3]],
) -> Vec<[f32; 3]> {
    compact_vertices_as(positions, triangles, |p| p)
}

/// [`compact_vertices`] of positions of another type, each kept one made
/// a binary32 position by `convert` (the SwingWrapper decoder keeps its
/// vertices in binary64 until they are output).
pub(crate) fn compact_vertices_as<P: Copy>(
    positions: &[P],
    triangles: &mut [[u32; 3]],
    convert: impl Fn(P) -> [f32; 3],
) -> Vec<[f32; 3]> {
    let mut new_id = vec![u32::MAX; positions.len()];
    for &v in triangles.iter().flatten() {
        if let Some(id) = new_id.get_mut(v as usize) {
            *id = 0;
        }
    }
    let mut out = Vec::with_capacity(positions.len());
    for (id, p) in new_id.iter_mut().zip(positions) {
        if *id == 0 {
            *id = out.len() as u32;
            out.push(convert(*p));
        }
    }
    for v in triangles.iter_mut().flatten() {
        *v = new_id.get(*v as usize).copied().unwrap_or(u32::MAX);
    }
    out
}
