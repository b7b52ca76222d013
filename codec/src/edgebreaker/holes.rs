//! Closing boundary loops with dummy vertices (Rossignac's TPATCH scheme)
//! so that Edgebreaker only ever sees closed surfaces.
//!
//! Each boundary loop gets one dummy vertex and a fan of triangles, one per
//! boundary edge, oriented to agree with the surface. The fan triangles are
//! coded like any others (about a bit each, mostly C and R), and the
//! decoder, told which vertices are dummies, drops them with their fans.
//! A boundary vertex lies on exactly one loop once (the corner table is
//! manifold), so the result is a closed manifold.

use crate::CornerTable;

/// A mesh closed by [`fill_holes`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Filled {
    /// The input triangles, then the dummy fans.
    pub triangles: Vec<[u32; 3]>,
    /// Vertex count including the dummies.
    pub vertex_count: usize,
    /// The dummy vertices (numbered after the input's vertices), one per loop.
    pub dummies: Vec<u32>,
}

/// Cones every boundary loop of `table` to a new dummy vertex.
pub fn fill_holes(table: &CornerTable) -> Filled {
    let mut triangles = table.triangles();
    let mut dummies = Vec::new();
    let mut vertex_count = table.vertex_count();
    for lp in table.boundary_loops() {
        let d = vertex_count as u32;
        vertex_count += 1;
        dummies.push(d);
        for c in lp {
            // The boundary edge runs V[n(c)] -> V[p(c)]; the fan triangle
            // must run along it the other way.
            triangles.push([d, table.vertex(c.prev()).0, table.vertex(c.next()).0]);
        }
    }
    Filled {
        triangles,
        vertex_count,
        dummies,
    }
}
