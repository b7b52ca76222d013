//! `ATTR` over the decoded mesh of a lossy file (format 1.2, mode 2,
//! format-spec/08-attributes.md, "Over a decoded mesh"): the streams are
//! coded exactly as in a mode-0 file, over a frame the decoder makes
//! from the mesh it has just decoded, not from a traversal.
//!
//! The frame: the corner table of the decoded triangles as they are (no
//! dummy vertices: every triangle is real, a border edge has no
//! opposite), the vertices in the order of the positions' traversal over
//! that table (format-spec/04-lossless.md, "Traversal"; no vertex
//! excluded), and a grid point per vertex from its binary32 position:
//!
//! ```text
//! lo[k] = min over vertices of p[k]        side = max over k of (hi[k] − lo[k])
//! S = 2^20 / side  (0 when side is 0)      G[v][k] = floor((p[k] − lo[k]) · S)
//! ```
//!
//! each operation in binary64, rounded once, so that every decoder finds
//! the same integers (below `2^20 + 1`, far inside the `2^24` the
//! predictions are exact for).
//!
//! Encoder and decoder both build the frame here ([`OverMesh::new`]), so
//! they cannot disagree; a mesh whose triangles make no corner table
//! (non-manifold) carries no `ATTR`, and a decoder rejects one.

use crate::prelude::*;

use super::frame::Frame;
use crate::mesh::{CornerTable, VertexId};

use crate::{AttributedMesh, Error, Limits, TriMesh};

/// Grid steps across the mesh's longest side.
const GRID_SPAN: f64 = (1u64 << 20) as f64;

/// The frame's parts, owned.
pub(crate) struct OverMesh {
    table: CornerTable,
    excluded: Vec<bool>,
    order: Vec<VertexId>,
    grid: Vec<[i64; 3]>,
}

impl OverMesh {
    /// The frame of `mesh`; `None` when its triangles make no corner
    /// table.
    pub(crate) fn new(mesh: &TriMesh) -> Option<OverMesh> {
        let n = mesh.positions.len();
        let table = CornerTable::new(&mesh.triangles, n).ok()?;
        let excluded = vec![false; n];
        // The positions' traversal (greatest parallelogram count first):
        // in vertex-number order, a subdivided level's vertices (edge
        // midpoints in key order) find few parallelograms decoded.
        let order = crate::geometry::traverse_except(&table, &excluded)
            .ok()?
            .order;
        Some(OverMesh {
            table,
            excluded,
            order,
            grid: grid_of(&mesh.positions),
        })
    }

    /// The frame the streams are coded over.
    pub(crate) fn frame(&self) -> Frame<'_> {
        Frame::new(&self.table, &self.excluded, self.grid.clone(), &self.order)
    }
}

/// Each vertex's grid point (the module's formula).
fn grid_of(positions: &[[f32; 3]]) -> Vec<[i64; 3]> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(f64::from(p[k]));
            hi[k] = hi[k].max(f64::from(p[k]));
        }
    }
    let side = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let scale = if side > 0.0 && side.is_finite() {
        GRID_SPAN / side
    } else {
        0.0
    };
    positions
        .iter()
        .map(|p| {
            core::array::from_fn(|k| crate::math::floor((f64::from(p[k]) - lo[k]) * scale) as i64)
        })
        .collect()
}

/// `mesh` (decoded plainly) with the streams of `ATTR`'s payload `bytes`
/// coded over it.
pub(crate) fn decode(
    bytes: &[u8],
    mesh: TriMesh,
    limits: &Limits,
) -> Result<AttributedMesh, Error> {
    let over = OverMesh::new(&mesh).ok_or(super::spec::bad(
        "ATTR over a decoded mesh that makes no corner table",
    ))?;
    let streams = super::decode(bytes, &over.frame(), limits)?;
    Ok(AttributedMesh::new(mesh, streams))
}

/// `ATTR` for `streams` over `mesh` (each stream one triple per triangle
/// of `mesh`), and what it holds; `None` when the mesh makes no corner
/// table.
#[cfg(feature = "encoder")]
pub(crate) fn encode(
    mesh: &TriMesh,
    streams: &[crate::AttributeStream],
    q: &crate::AttributeQuantization,
) -> Result<Option<(Vec<u8>, Vec<super::AttributeInfo>)>, Error> {
    let Some(over) = OverMesh::new(mesh) else {
        return Ok(None);
    };
    let index: Vec<Vec<u32>> = streams
        .iter()
        .map(|s| s.corners.iter().flatten().copied().collect())
        .collect();
    super::encode(&over.frame(), streams, &index, q).map(Some)
}
