//! `Builder`, the mesh a reader builds, checked against the [`Limits`]
//! before every allocation, and the limit error readers that count first
//! report themselves.
//!
//! Below every reader and apart from `io`'s dispatch (`mod.rs`), which
//! calls the readers: the readers import this, not the file that calls
//! them.

use super::Attributes;
use crate::{Error, LimitError, Limited, Limits, TriMesh};
use std::io;

/// The mesh a reader is building, the [`Limits`] it must stay within,
/// and the attributes the file carried that the mesh does not keep.
pub(super) struct Builder<'l> {
    pub(super) mesh: TriMesh,
    pub(super) limits: &'l Limits,
    pub(super) dropped: Attributes,
}

impl<'l> Builder<'l> {
    pub(super) fn new(limits: &'l Limits) -> Self {
        Builder {
            mesh: TriMesh::default(),
            limits,
            dropped: Attributes::default(),
        }
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
        // 12 bytes per position and per triangle.
        let bytes = vertices.saturating_add(triangles).saturating_mul(12);
        Ok(self.limits.check_alloc(bytes)?)
    }

    pub(super) fn finish(self) -> (TriMesh, Attributes) {
        (self.mesh, self.dropped)
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
