//! Closing boundary loops with dummy vertices (Rossignac's TPATCH scheme)
//! so that Edgebreaker only ever sees closed surfaces.
//!
//! Each boundary loop gets one dummy vertex and a fan of triangles, one per
//! boundary edge, oriented to agree with the surface. The fan triangles are
//! coded like any others (about a bit each, mostly C and R), and the
//! decoder, told which vertices are dummies, drops them with their fans.
//! A boundary vertex lies on exactly one loop once (the corner table is
//! manifold), so the result is a closed manifold.

use crate::prelude::*;

use crate::{CornerId, CornerTable, VertexId};

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

/// A closed corner table made by [`close_holes`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Closed {
    /// The table of [`fill_holes`]'s triangles: the input's corners, then
    /// the dummy fans.
    pub table: CornerTable,
    /// The dummy vertices (numbered after the input's vertices), one per loop.
    pub dummies: Vec<u32>,
}

/// The corner table of [`fill_holes`]`(table)`, built without pairing the
/// edges again: exactly `CornerTable::new(&filled.triangles, ..)`.
///
/// Why it is the same table: the input's pairs stay pairs (each of their
/// edges keeps its two half-edges), and every new half-edge has exactly
/// one reverse, which this function pairs it with directly. The fan
/// triangle of boundary corner `c_i`, `[d, b_i, a_i]` for the edge
/// `a_i -> b_i` that `c_i` faces, has
///
/// ```text
///   corner 0 (d)    facing b_i -> a_i: paired with c_i
///   corner 1 (b_i)  facing a_i -> d:   paired with corner 2 of fan i - 1
///   corner 2 (a_i)  facing d -> b_i:   paired with corner 1 of fan i + 1
/// ```
///
/// since consecutive loop edges share a vertex (`a_{i+1} = b_i`). Every
/// fan of the result is closed, so each vertex's corner is its lowest
/// one, which a scan in corner order finds. Linear in the corners, and
/// without the edge sort that dominated building the table anew.
pub fn close_holes(table: &CornerTable) -> Closed {
    let loops = table.boundary_loops();
    let boundary: usize = loops.iter().map(Vec::len).sum();
    let mut v = Vec::with_capacity(table.corner_count() + 3 * boundary);
    v.extend_from_slice(table.vertices());
    let mut o = Vec::with_capacity(v.capacity());
    o.extend_from_slice(table.opposites());
    let mut vertex_count = table.vertex_count();
    let mut dummies = Vec::with_capacity(loops.len());
    for lp in &loops {
        let d = VertexId(vertex_count as u32);
        vertex_count += 1;
        dummies.push(d.0);
        let first = (v.len() / 3) as u32;
        let m = lp.len() as u32;
        for (i, &c) in lp.iter().enumerate() {
            let i = i as u32;
            let fan = first + i;
            let (before, after) = (first + (i + m - 1) % m, first + (i + 1) % m);
            v.extend_from_slice(&[d, table.vertex(c.prev()), table.vertex(c.next())]);
            o[c.idx()] = CornerId(3 * fan);
            o.extend_from_slice(&[c, CornerId(3 * before + 2), CornerId(3 * after + 1)]);
        }
    }
    let mut vertex_corner = vec![CornerId::NONE; vertex_count];
    for (c, x) in v.iter().enumerate() {
        let first = &mut vertex_corner[x.idx()];
        if first.is_none() {
            *first = CornerId(c as u32);
        }
    }
    Closed {
        table: CornerTable::from_raw(v, o, vertex_corner),
        dummies,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edgebreaker::tests_support::{grid, torus};

    #[test]
    fn closing_builds_the_table_of_the_filled_mesh() {
        let mut both = torus(7, 5);
        let g = grid(6, 4);
        let off = both.positions.len() as u32;
        both.positions.extend(&g.positions);
        both.triangles
            .extend(g.triangles.iter().map(|t| t.map(|x| x + off)));
        // Punch holes: drop some faces of the torus (two loops) too.
        both.triangles.remove(20);
        both.triangles.remove(3);
        for mesh in [torus(7, 5), grid(6, 4), both] {
            let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
            let filled = fill_holes(&table);
            let fresh = CornerTable::new(&filled.triangles, filled.vertex_count).unwrap();
            let closed = close_holes(&table);
            assert_eq!(closed.table, fresh);
            assert_eq!(closed.dummies, filled.dummies);
        }
    }

    #[test]
    #[cfg(all(feature = "io", feature = "encoder"))]
    fn closing_corpus_meshes_builds_the_same_table() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus");
        if !dir.is_dir() {
            crate::test_skip::skip("../shared/corpus not found");
            return;
        }
        for name in ["stanford-bunny.obj", "horse.ply", "cheburashka.obj"] {
            let mesh = crate::io::read_mesh(&dir.join(name)).unwrap();
            let table = crate::clean(&mesh, &Default::default()).unwrap().table;
            let filled = fill_holes(&table);
            let fresh = CornerTable::new(&filled.triangles, filled.vertex_count).unwrap();
            assert_eq!(close_holes(&table).table, fresh, "{name}");
        }
    }
}
