//! Vertex attributes beside a [`TriMesh`]: normals, texture coordinates,
//! colours and generic float streams, with seams.
//!
//! The model is Wavefront OBJ's `f v/vt/vn` (Advanced Visualizer manual,
//! Appendix B1): each [`AttributeStream`] has its own array of values and
//! one index triple per triangle, parallel to `TriMesh::triangles`.
//!
//! ```text
//! triangles  f: [ p0  p1  p2 ]     positions   p: [x y z]
//! stream s   f: [ a0  a1  a2 ]     values of s a: [dims floats]
//!                corner k of f has position p_k and value a_k of s
//! ```
//!
//! Why per-corner indices rather than split vertices: a seam (a position
//! carrying two texture coordinates, a crease with two normals) needs no
//! copy of the position, so welding or splitting positions (cleaning,
//! the corner table) never touches attributes, and every stream can be
//! seamed independently of the others. The split form that glTF, PLY and
//! GPU buffers need (one vertex per distinct position and attribute
//! indices) is derived on demand ([`AttributedMesh::split_vertices`]),
//! and read back by [`AttributedMesh::weld`].
//!
//! Code that does not care which kind a stream is treats all streams
//! alike, as `dims` floats per value (meshoptimizer's attribute streams
//! for `meshopt_simplifyWithAttributes` are the model); the kind matters
//! only to file formats and to what a value means (normals are unit
//! vectors, colours are 0..1).
//!
//! Invariants, checked by [`AttributedMesh::validate`]: every value is
//! finite; `dims` suits the kind (normals 3, texture coordinates 2 or 3,
//! colours 3 or 4, generic 1 to 4); `values.len()` is a multiple of
//! `dims`; every stream has one triple per triangle and its indices are
//! in range; no two streams have the same kind.

use crate::prelude::*;

use super::ids::FaceId;
use super::trimesh::TriMesh;
use crate::{AttributeError, Error};

/// What an attribute stream holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum AttributeKind {
    /// Shading normals, 3 components (unit vectors where a format
    /// requires it: glTF).
    Normal,
    /// Texture coordinate set `n` (glTF `TEXCOORD_n`; OBJ's `vt` is set
    /// 0): 2 components, or 3 when a file gives a third (OBJ `vt u v w`).
    TexCoord(u8),
    /// Vertex colour set `n` (glTF `COLOR_n`): RGB or RGBA, 3 or 4
    /// components in 0..1, linear as glTF defines them or as the file
    /// wrote them.
    Color(u8),
    /// An application-defined stream, told apart by its number: 1 to 4
    /// components.
    Generic(u16),
}

impl AttributeKind {
    /// Whether a stream of this kind may have `dims` components.
    pub fn allows_dims(self, dims: u8) -> bool {
        match self {
            AttributeKind::Normal => dims == 3,
            AttributeKind::TexCoord(_) => matches!(dims, 2 | 3),
            AttributeKind::Color(_) => matches!(dims, 3 | 4),
            AttributeKind::Generic(_) => matches!(dims, 1..=4),
        }
    }
}

/// One attribute: `values` holds `dims` floats per value, and `corners`
/// one triple of value indices per triangle of the mesh (corner `k` of
/// triangle `f` takes value `corners[f][k]`).
#[derive(Clone, Debug, PartialEq)]
pub struct AttributeStream {
    /// What the values are.
    pub kind: AttributeKind,
    /// Components per value, 1 to 4.
    pub dims: u8,
    /// The values, `dims` floats each.
    pub values: Vec<f32>,
    /// Per triangle, the values of its three corners.
    pub corners: Vec<[u32; 3]>,
}

impl AttributeStream {
    /// A stream from its parts (not validated).
    pub fn new(kind: AttributeKind, dims: u8, values: Vec<f32>, corners: Vec<[u32; 3]>) -> Self {
        AttributeStream {
            kind,
            dims,
            values,
            corners,
        }
    }

    /// Number of values (`values.len() / dims`).
    pub fn value_count(&self) -> usize {
        self.values.len() / usize::from(self.dims.max(1))
    }

    /// Value `i`, `dims` floats.
    pub fn value(&self, i: u32) -> &[f32] {
        let d = usize::from(self.dims);
        &self.values[i as usize * d..(i as usize + 1) * d]
    }

    /// The value at corner `k` (0, 1 or 2) of triangle `f`.
    pub fn corner_value(&self, f: FaceId, k: usize) -> &[f32] {
        self.value(self.corners[f.idx()][k])
    }
}

/// A triangle mesh with attribute streams (see the module header).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AttributedMesh {
    /// Positions and triangles.
    pub mesh: TriMesh,
    /// Attribute streams, each with one triple per triangle of `mesh`.
    pub streams: Vec<AttributeStream>,
}

impl From<TriMesh> for AttributedMesh {
    fn from(mesh: TriMesh) -> Self {
        AttributedMesh {
            mesh,
            streams: Vec::new(),
        }
    }
}

impl AttributedMesh {
    /// A mesh from its parts (not validated).
    pub fn new(mesh: TriMesh, streams: Vec<AttributeStream>) -> Self {
        AttributedMesh { mesh, streams }
    }

    /// The stream of the given kind, if any.
    pub fn stream(&self, kind: AttributeKind) -> Option<&AttributeStream> {
        self.streams.iter().find(|s| s.kind == kind)
    }

    /// Checks the mesh ([`TriMesh::validate`]) and every stream against
    /// the invariants of the module header.
    pub fn validate(&self) -> Result<(), Error> {
        self.mesh.validate()?;
        let faces = self.mesh.triangles.len() as u64;
        for (k, s) in self.streams.iter().enumerate() {
            let stream = k as u32;
            if !s.kind.allows_dims(s.dims) {
                return Err(AttributeError::Dims {
                    stream,
                    dims: s.dims,
                }
                .into());
            }
            if self.streams[..k].iter().any(|t| t.kind == s.kind) {
                return Err(AttributeError::DuplicateKind { stream }.into());
            }
            let d = usize::from(s.dims);
            if !s.values.len().is_multiple_of(d) {
                let floats = s.values.len() as u64;
                let dims = s.dims;
                return Err(AttributeError::ValueCount {
                    stream,
                    floats,
                    dims,
                }
                .into());
            }
            if let Some(i) = s.values.iter().position(|x| !x.is_finite()) {
                let value = (i / d) as u64;
                return Err(AttributeError::NonFinite { stream, value }.into());
            }
            if s.corners.len() as u64 != faces {
                let triples = s.corners.len() as u64;
                return Err(AttributeError::CornerCount {
                    stream,
                    triples,
                    faces,
                }
                .into());
            }
            let values = s.value_count() as u64;
            if let Some(&index) = s
                .corners
                .iter()
                .flatten()
                .find(|&&i| u64::from(i) >= values)
            {
                return Err(AttributeError::IndexOutOfRange {
                    stream,
                    index,
                    values,
                }
                .into());
            }
        }
        Ok(())
    }

    /// Whether every stream indexes like the positions (its triples are
    /// the triangles): the split form of [`split_vertices`](Self::split_vertices).
    pub fn is_split(&self) -> bool {
        self.streams.iter().all(|s| {
            s.corners == self.mesh.triangles && s.value_count() == self.mesh.positions.len()
        })
    }

    /// The same surface with one vertex per distinct (position, value
    /// indices of every stream) of a corner: what glTF, PLY and GPU
    /// vertex buffers hold. Every stream of the result has one value per
    /// vertex and the triangles as its triples.
    ///
    /// Deterministic order: vertices come in the order of their
    /// positions, and the copies of one position in the order their
    /// first corner comes (face by face), so a mesh without seams keeps
    /// its vertex order. A position no triangle uses stays, with zeros
    /// for its attributes. The mesh must be valid ([`validate`](Self::validate)).
    pub fn split_vertices(&self) -> AttributedMesh {
        self.split_vertices_by(|_| true)
    }

    /// [`split_vertices`](Self::split_vertices) for the streams `split`
    /// selects; the others keep their values and triples (which a vertex
    /// split does not change). For formats that carry some attributes per
    /// vertex and others per corner (OBJ: colours on `v` lines, `vt` and
    /// `vn` per corner).
    pub fn split_vertices_by(&self, split: impl Fn(&AttributeStream) -> bool) -> AttributedMesh {
        let selected: Vec<usize> = (0..self.streams.len())
            .filter(|&k| split(&self.streams[k]))
            .collect();
        let tris = &self.mesh.triangles;
        let width = 1 + selected.len();
        let corner_count = tris.len() * 3;
        // Key of corner c: its position, then its value in each selected stream.
        let mut keys = Vec::with_capacity(corner_count * width);
        for (f, t) in tris.iter().enumerate() {
            for k in 0..3 {
                keys.push(t[k]);
                keys.extend(selected.iter().map(|&s| self.streams[s].corners[f][k]));
            }
        }
        let key = |c: u32| &keys[c as usize * width..(c as usize + 1) * width];
        // Corners by key, ties by corner: each key's run starts with its
        // first corner. (The corner makes the key unique, so any sort
        // gives this order.)
        let mut order: Vec<u32> = (0..corner_count as u32).collect();
        crate::sort::sort_by_unique_key(&mut order, |&c| (key(c), c));
        // Runs as (position, first corner, start in `order`), then in
        // output order: by position, then by first corner.
        let mut runs: Vec<(u32, u32, u32)> = Vec::new();
        for (i, &c) in order.iter().enumerate() {
            if i == 0 || key(order[i - 1]) != key(c) {
                runs.push((key(c)[0], c, i as u32));
            }
        }
        let run_end: Vec<u32> = (0..runs.len())
            .map(|r| runs.get(r + 1).map_or(corner_count as u32, |n| n.2))
            .collect();
        let mut by_output: Vec<u32> = (0..runs.len() as u32).collect();
        crate::sort::sort_by_unique_key(&mut by_output, |&r| {
            let (p, first, _) = runs[r as usize];
            (p, first)
        });

        let mut positions = Vec::with_capacity(runs.len());
        let mut triangles = vec![[0u32; 3]; tris.len()];
        let mut values: Vec<Vec<f32>> = selected.iter().map(|_| Vec::new()).collect();
        let mut emit = |p: u32, run: Option<usize>, positions: &mut Vec<[f32; 3]>| {
            let v = positions.len() as u32;
            positions.push(self.mesh.positions[p as usize]);
            for (j, &s) in selected.iter().enumerate() {
                let stream = &self.streams[s];
                match run {
                    Some(r) => {
                        let value = key(runs[r].1)[1 + j];
                        values[j].extend_from_slice(stream.value(value));
                    }
                    None => values[j].extend((0..stream.dims).map(|_| 0.0)),
                }
            }
            v
        };
        let mut next = by_output.iter().peekable();
        for p in 0..self.mesh.positions.len() as u32 {
            let mut used = false;
            while let Some(&&r) = next.peek().filter(|&&&r| runs[r as usize].0 == p) {
                next.next();
                used = true;
                let v = emit(p, Some(r as usize), &mut positions);
                for &c in &order[runs[r as usize].2 as usize..run_end[r as usize] as usize] {
                    triangles[c as usize / 3][c as usize % 3] = v;
                }
            }
            if !used {
                emit(p, None, &mut positions);
            }
        }
        let mut streams = self.streams.clone();
        for (j, &s) in selected.iter().enumerate() {
            streams[s].values = core::mem::take(&mut values[j]);
            streams[s].corners = triangles.clone();
        }
        AttributedMesh {
            mesh: TriMesh::new(positions, triangles),
            streams,
        }
    }

    /// Merges positions that are equal bit for bit, and in each stream
    /// values that are equal bit for bit (so `-0.0` and `0.0` stay
    /// apart): the inverse of [`split_vertices`](Self::split_vertices),
    /// which makes per-vertex data of a glTF or PLY file per-corner. Each
    /// kept position or value is the first of its equals, in their order;
    /// nothing is dropped, used or not. The mesh must be valid.
    pub fn weld(&self) -> AttributedMesh {
        let flat: Vec<f32> = self.mesh.positions.iter().flatten().copied().collect();
        let (positions, remap) = dedupe(&flat, 3);
        let remap_all = |t: &[[u32; 3]], remap: &[u32]| -> Vec<[u32; 3]> {
            t.iter().map(|t| t.map(|i| remap[i as usize])).collect()
        };
        let triangles = remap_all(&self.mesh.triangles, &remap);
        let streams = self
            .streams
            .iter()
            .map(|s| {
                let (values, remap) = dedupe(&s.values, usize::from(s.dims));
                AttributeStream {
                    kind: s.kind,
                    dims: s.dims,
                    values,
                    corners: remap_all(&s.corners, &remap),
                }
            })
            .collect();
        let positions = positions
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect();
        AttributedMesh {
            mesh: TriMesh::new(positions, triangles),
            streams,
        }
    }
}

/// The distinct `dims`-float values of `values` (bit for bit), first
/// ones first, and the map from each value to its kept copy.
pub(crate) fn dedupe(values: &[f32], dims: usize) -> (Vec<f32>, Vec<u32>) {
    let n = values.len() / dims;
    let bits = |i: u32| -> [u32; 4] {
        let mut b = [0u32; 4];
        for (k, x) in values[i as usize * dims..(i as usize + 1) * dims]
            .iter()
            .enumerate()
        {
            b[k] = x.to_bits();
        }
        b
    };
    let mut order: Vec<u32> = (0..n as u32).collect();
    crate::sort::sort_by_unique_key(&mut order, |&i| (bits(i), i));
    // The first of each run of equals is its lowest index.
    let mut first = vec![0u32; n];
    for (k, &i) in order.iter().enumerate() {
        first[i as usize] = if k > 0 && bits(order[k - 1]) == bits(i) {
            first[order[k - 1] as usize]
        } else {
            i
        };
    }
    let mut kept = Vec::new();
    let mut remap = vec![0u32; n];
    for i in 0..n {
        if first[i] as usize == i {
            remap[i] = (kept.len() / dims) as u32;
            kept.extend_from_slice(&values[i * dims..(i + 1) * dims]);
        } else {
            remap[i] = remap[first[i] as usize];
        }
    }
    (kept, remap)
}

#[cfg(test)]
mod tests;
