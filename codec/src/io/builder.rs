//! `Builder`, the mesh a reader builds, checked against the [`Limits`]
//! before every allocation, and the limit error readers that count first
//! report themselves.
//!
//! Attribute streams are read only when the caller asks for them
//! (the readers' `keep`): otherwise the readers skip them, allocating and
//! checking exactly what they did before streams existed. A stream is
//! *per vertex* (one value per position, its triples the triangles: PLY
//! vertex properties, glTF accessors, OBJ colours) or *per corner* (its
//! own triples: OBJ `vt`/`vn`, a PLY face `texcoord` list). A stream
//! that does not cover every vertex or corner (a glTF primitive without
//! the texture coordinates the others have), or holds a non-finite
//! value, is dropped at the end and reported, not kept in part.
//!
//! Below every reader and apart from `io`'s dispatch (`mod.rs`), which
//! calls the readers: the readers import this, not the file that calls
//! them.

use super::Attributes;
use crate::{
    AttributeKind, AttributeStream, AttributedMesh, Error, LimitError, Limited, Limits, TriMesh,
};
use std::io;

/// The mesh a reader is building, the [`Limits`] it must stay within,
/// and the attributes the file carried that the mesh does not keep.
pub(super) struct Builder<'l> {
    pub(super) mesh: TriMesh,
    pub(super) limits: &'l Limits,
    pub(super) dropped: Attributes,
    /// The streams being read.
    pub(super) streams: Vec<Pending>,
}

/// A stream being read.
pub(super) struct Pending {
    pub(super) stream: AttributeStream,
    /// One value per position, the triangles as triples (filled in by
    /// [`Builder::finish`]).
    pub(super) per_vertex: bool,
    /// Known not to cover the mesh: dropped at the end.
    pub(super) broken: bool,
}

impl<'l> Builder<'l> {
    pub(super) fn new(limits: &'l Limits) -> Self {
        Builder {
            mesh: TriMesh::default(),
            limits,
            dropped: Attributes::default(),
            streams: Vec::new(),
        }
    }

    /// Adds an empty stream; its index in `streams`.
    pub(super) fn add_stream(&mut self, kind: AttributeKind, dims: u8, per_vertex: bool) -> usize {
        self.streams.push(Pending {
            stream: AttributeStream::new(kind, dims, Vec::new(), Vec::new()),
            per_vertex,
            broken: false,
        });
        self.streams.len() - 1
    }

    /// Checks the limits for `n` more values of stream `s` (and, for a
    /// per-corner stream, `triples` more triples), then makes room.
    pub(super) fn reserve_values(&mut self, s: usize, n: u64, triples: u64) -> Result<(), Error> {
        let p = &self.streams[s];
        let floats = (p.stream.values.len() as u64)
            .saturating_add(n.saturating_mul(u64::from(p.stream.dims)));
        let corners = (p.stream.corners.len() as u64).saturating_add(triples);
        let extra = floats
            .saturating_sub(p.stream.values.capacity() as u64)
            .saturating_mul(4)
            .saturating_add(
                corners
                    .saturating_sub(p.stream.corners.capacity() as u64)
                    .saturating_mul(12),
            );
        let base = self.alloc_bytes(
            self.mesh.positions.capacity() as u64,
            self.mesh.triangles.capacity() as u64,
        );
        self.limits.check_alloc(base.saturating_add(extra))?;
        let p = &mut self.streams[s].stream;
        let more = |total: u64, len: usize| {
            usize::try_from(total - len as u64).map_err(|_| out_of_memory())
        };
        let (nf, nc) = (
            more(floats, p.values.len())?,
            more(corners, p.corners.len())?,
        );
        p.values.try_reserve(nf).map_err(|_| out_of_memory())?;
        p.corners.try_reserve(nc).map_err(|_| out_of_memory())
    }

    /// Checks the limits for `n` more vertices, then makes room for them.
    pub(super) fn reserve_vertices(&mut self, n: u64) -> Result<(), Error> {
        let total = (self.mesh.positions.len() as u64).saturating_add(n);
        self.limits.check_vertices(total)?;
        // Indices are u32: 2^32 vertices is the most a mesh can address.
        if total > 1 << 32 {
            return Err(limit(Limited::Vertices, total, 1 << 32));
        }
        self.check_alloc(total, self.mesh.triangles.capacity() as u64)?;
        let n = usize::try_from(n).map_err(|_| out_of_memory())?;
        self.mesh
            .positions
            .try_reserve_exact(n)
            .map_err(|_| out_of_memory())
    }

    /// Checks the limits for `n` more triangles, then makes room for them.
    pub(super) fn reserve_triangles(&mut self, n: u64) -> Result<(), Error> {
        let total = (self.mesh.triangles.len() as u64).saturating_add(n);
        self.limits.check_faces(total)?;
        self.check_alloc(self.mesh.positions.capacity() as u64, total)?;
        let n = usize::try_from(n).map_err(|_| out_of_memory())?;
        self.mesh
            .triangles
            .try_reserve_exact(n)
            .map_err(|_| out_of_memory())
    }

    /// Checks the limits against what the mesh holds now, for growth no
    /// declared count announced (polygons, strips, ASCII STL). Memory is
    /// bounded by the input size anyway; this keeps the limits exact.
    pub(super) fn check_growth(&self) -> Result<(), Error> {
        let mesh = &self.mesh;
        self.limits.check_vertices(mesh.positions.len() as u64)?;
        self.limits.check_faces(mesh.triangles.len() as u64)?;
        if mesh.positions.len() as u64 > 1 << 32 {
            return Err(limit(
                Limited::Vertices,
                mesh.positions.len() as u64,
                1 << 32,
            ));
        }
        self.check_alloc(
            mesh.positions.capacity() as u64,
            mesh.triangles.capacity() as u64,
        )
    }

    /// Checks the memory for vertex and triangle slots (allocated ones,
    /// not just used ones).
    pub(super) fn check_alloc(&self, vertices: u64, triangles: u64) -> Result<(), Error> {
        Ok(self
            .limits
            .check_alloc(self.alloc_bytes(vertices, triangles))?)
    }

    /// Bytes of `vertices` and `triangles` slots and of the streams: 12
    /// per position and per triangle, and each stream's values and
    /// triples (a per-vertex stream gets its copy of the triangles at the
    /// end, counted now).
    fn alloc_bytes(&self, vertices: u64, triangles: u64) -> u64 {
        let mut bytes = vertices.saturating_add(triangles).saturating_mul(12);
        for p in &self.streams {
            let corners = match p.per_vertex {
                true => triangles,
                false => p.stream.corners.capacity() as u64,
            };
            bytes = bytes
                .saturating_add((p.stream.values.capacity() as u64).saturating_mul(4))
                .saturating_add(corners.saturating_mul(12));
        }
        bytes
    }

    /// The mesh, its streams, and what the file carried that they do not
    /// keep: every stream that is broken, does not cover the mesh, or
    /// holds a non-finite value is dropped and reported.
    pub(super) fn finish(self) -> (AttributedMesh, Attributes) {
        let mut dropped = self.dropped;
        let mut streams = Vec::new();
        let positions = self.mesh.positions.len();
        let faces = self.mesh.triangles.len();
        for p in self.streams {
            let mut s = p.stream;
            let whole = match p.per_vertex {
                true => s.value_count() == positions,
                false => s.corners.len() == faces,
            };
            if p.broken || !whole || !s.values.iter().all(|x| x.is_finite()) {
                dropped = dropped.union(Attributes::of(s.kind));
                continue;
            }
            if p.per_vertex {
                s.corners = self.mesh.triangles.clone();
            }
            streams.push(s);
        }
        (AttributedMesh::new(self.mesh, streams), dropped)
    }
}

/// The allocator refused what the limits allowed.
fn out_of_memory() -> Error {
    Error::Io(io::Error::from(io::ErrorKind::OutOfMemory))
}

/// A limit error, for readers that count before they build.
pub(super) fn limit(what: Limited, requested: u64, limit: u64) -> Error {
    Error::LimitExceeded(LimitError {
        what,
        requested,
        limit,
    })
}
