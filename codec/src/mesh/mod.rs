//! The indexed triangle mesh and its corner table.
//!
//! Positions are stored as `f32` (what files and GPUs hold); every
//! geometric computation converts to `f64` first (glam `DVec3`), so sums
//! of many small terms and nearly-degenerate cross products stay accurate.
//!
//! This file only declares and re-exports: `TriMesh` is in `trimesh`, so
//! that the parts built on it (normals, topology) import it without
//! importing the file that re-exports them.

mod attributes;
mod corner;
mod ids;
mod normals;
mod topology;
mod trimesh;

#[cfg(test)]
pub(crate) mod test_rng;
#[cfg(test)]
pub(crate) mod test_shapes;

#[cfg(feature = "encoder")]
pub mod clean;

#[cfg(feature = "encoder")]
pub(crate) use attributes::dedupe;
pub use attributes::{AttributeKind, AttributeStream, AttributedMesh};
pub(crate) use corner::corners_by_vertex;
pub use corner::CornerTable;
pub use ids::{CornerId, FaceId, VertexId};
#[cfg(feature = "encoder")]
pub(crate) use normals::vertex_normals_par;
pub use normals::{vertex_normals, vertex_normals_into};
pub use topology::{Component, MeshStats};
pub use trimesh::TriMesh;
pub(crate) use trimesh::{compact_vertices, compact_vertices_as};
