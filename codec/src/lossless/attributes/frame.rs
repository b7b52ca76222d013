//! What every stream of `ATTR` is coded over: the closed mesh's corner
//! table, which faces are real, the decoded grid points and the
//! positions' decoding order; and the corner arithmetic of its
//! triangles (corner `c` of triangle `c / 3`, next and previous).

use crate::prelude::*;

use crate::mesh::{corners_by_vertex, CornerTable, VertexId};

/// "No group yet", and the value index of a corner of a dropped triangle.
pub(crate) const NONE: u32 = u32::MAX;

/// The next corner of `c`'s triangle.
pub(crate) fn next(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

/// The previous corner of `c`'s triangle.
pub(crate) fn prev(c: u32) -> u32 {
    if c.is_multiple_of(3) {
        c + 2
    } else {
        c - 1
    }
}

/// What every stream is coded over: the closed mesh's table, which of
/// its faces are real (no dummy vertex), the decoded grid point of each
/// vertex and the positions' decoding order.
pub(crate) struct Frame<'a> {
    pub table: &'a CornerTable,
    pub real: Vec<bool>,
    pub grid: Vec<[i64; 3]>,
    pub order: &'a [VertexId],
    start: Vec<u32>,
    corners: Vec<u32>,
}

impl<'a> Frame<'a> {
    /// `excluded[v]`: vertex `v` is a dummy; `grid[v]` its grid point.
    pub(crate) fn new(
        table: &'a CornerTable,
        excluded: &[bool],
        grid: Vec<[i64; 3]>,
        order: &'a [VertexId],
    ) -> Self {
        let is_dummy = |v: VertexId| excluded.get(v.idx()).copied().unwrap_or(true);
        let real = table
            .vertices()
            .chunks_exact(3)
            .map(|t| !t.iter().any(|&v| is_dummy(v)))
            .collect();
        let (start, corners) = corners_by_vertex(table.vertices(), table.vertex_count());
        Frame {
            table,
            real,
            grid,
            order,
            start,
            corners,
        }
    }

    /// The corners of `v`, increasing.
    pub(crate) fn corners_of(&self, v: VertexId) -> &[u32] {
        match (self.start.get(v.idx()), self.start.get(v.idx() + 1)) {
            (Some(&a), Some(&b)) => &self.corners[a as usize..b as usize],
            _ => &[],
        }
    }

    /// The real faces, in order: the decoded mesh's triangles.
    pub(crate) fn real_faces(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.real.len()).filter(|&t| self.real[t])
    }
}
