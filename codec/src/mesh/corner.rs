//! The corner table of Rossignac, Safonova and Szymczak ("3D compression
//! made simple: Edgebreaker with Zip&Wrap on a corner-table", SMI 2001),
//! the representation every Edgebreaker and SwingWrapper step walks.
//!
//! ```text
//!                 V[p(c)]
//!                  /\
//!                 /  \            Triangle t owns corners 3t, 3t+1, 3t+2,
//!                / p  \           counter-clockwise seen from outside.
//!               /      \          n(c) = next corner, p(c) = n(n(c)).
//!              /   t    \         O[c] is the corner facing c across the
//!             / c      n \        edge V[n(c)] -> V[p(c)], in the
//!     V[c]   +------------+ V[n(c)]   neighbouring triangle; NONE on a
//!             \    t'    /            boundary.
//!              \        /
//!               \ O[p]  /     swing_left(c)  = n(O[n(c)])  (next triangle
//!                \    /                          counter-clockwise around V[c])
//!                 \  /        swing_right(c) = p(O[p(c)])
//!                  \/
//! ```
//!
//! Invariants kept (checked by [`CornerTable::check`]):
//! * `O[O[c]] = c` wherever `O[c]` is set;
//! * opposite corners see the same edge reversed:
//!   `V[n(O[c])] = V[p(c)]` and `V[p(O[c])] = V[n(c)]`;
//! * each vertex's corners form exactly one fan (a manifold vertex), and
//!   `vertex_corner[v]` is the fan's most clockwise corner, so that
//!   swinging left from it visits the whole fan.
//!
//! Building is linear: half-edges are bucketed by their lower vertex
//! (a counting sort), then matched inside each bucket.

use super::{CornerId, FaceId, VertexId};
use crate::TopologyError;

/// Opposite-corner table over a triangle list (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CornerTable {
    v: Vec<VertexId>,
    o: Vec<CornerId>,
    vertex_corner: Vec<CornerId>,
}

/// Result of matching half-edges, before any manifold check.
pub(crate) struct Pairing {
    /// Opposite corner per corner; NONE for boundaries and cut edges.
    pub o: Vec<CornerId>,
    /// Undirected edges left unpaired because more than two faces share
    /// them or because both faces run along them the same way.
    pub cut_edges: u64,
}

/// Matches each half-edge `V[n(c)] -> V[p(c)]` with its reverse.
///
/// An undirected edge used by exactly two half-edges of opposite direction
/// is paired; any other multiplicity leaves all its half-edges unpaired
/// and counts as one cut edge. Runs in O(corners + vertices) for bounded
/// valence, O(k log k) for a vertex of valence k.
pub(crate) fn pair_half_edges(triangles: &[[u32; 3]], vertex_count: usize) -> Pairing {
    pair_edges(triangles, vertex_count, false)
}

/// Like [`pair_half_edges`], but with `undirected` two half-edges of the
/// same direction are paired too (used to orient a mesh before the real
/// pairing). The caller tells the two apart by comparing directions.
pub(crate) fn pair_edges(triangles: &[[u32; 3]], vertex_count: usize, undirected: bool) -> Pairing {
    let nc = triangles.len() * 3;
    // Counting sort of half-edges by their lower endpoint.
    let mut start = vec![0u32; vertex_count + 1];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
            start[a.min(b) as usize + 1] += 1;
        }
    }
    for i in 0..vertex_count {
        start[i + 1] += start[i];
    }
    // Entry: (higher endpoint, corner with the direction bit in bit 31).
    let mut fill = start.clone();
    let mut entries = vec![(0u32, 0u32); nc];
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let (lo, hi, up) = if a < b { (a, b, 0) } else { (b, a, 1u32 << 31) };
            let slot = &mut fill[lo as usize];
            entries[*slot as usize] = (hi, (3 * t + k) as u32 | up);
            *slot += 1;
        }
    }
    let mut o = vec![CornerId::NONE; nc];
    let mut cut_edges = 0u64;
    for v in 0..vertex_count {
        // Buckets average six entries; sorting them (insertion sort at that
        // size, O(k log k) for a hostile vertex of huge valence) puts the
        // half-edges of each undirected edge next to each other.
        let bucket = &mut entries[start[v] as usize..start[v + 1] as usize];
        bucket.sort_unstable();
        for group in bucket.chunk_by(|a, b| a.0 == b.0) {
            match group {
                [_] => {} // a boundary edge
                [(_, a), (_, b)] if undirected || (a ^ b) >> 31 == 1 => {
                    let (a, b) = (a & 0x7fff_ffff, b & 0x7fff_ffff);
                    o[a as usize] = CornerId(b);
                    o[b as usize] = CornerId(a);
                }
                _ => cut_edges += 1,
            }
        }
    }
    Pairing { o, cut_edges }
}

/// For every vertex, the most clockwise corner of each of its fans.
/// Returns (first fan corner per vertex, extra fans as (vertex, corner)).
pub(crate) fn vertex_fans(
    v: &[VertexId],
    o: &[CornerId],
    vertex_count: usize,
) -> (Vec<CornerId>, Vec<(VertexId, CornerId)>) {
    let mut first = vec![CornerId::NONE; vertex_count];
    let mut extra = Vec::new();
    let mut seen = vec![false; v.len()];
    for c0 in 0..v.len() {
        if seen[c0] {
            continue;
        }
        // Swing right to the most clockwise corner (or all the way round).
        let mut c = CornerId(c0 as u32);
        // Step bounds keep a corrupt O (from `from_parts`) from looping forever.
        let mut steps = 0usize;
        loop {
            steps += 1;
            if steps > v.len() {
                break;
            }
            let r = o[c.prev().idx()];
            if r.is_none() {
                break;
            }
            let nc = r.prev();
            if nc.idx() == c0 {
                break; // closed fan: c0 itself is as good a start as any
            }
            c = nc;
        }
        let start = if o[c.prev().idx()].is_none() {
            c
        } else {
            CornerId(c0 as u32)
        };
        // Swing left over the whole fan, marking it.
        let mut d = start;
        let mut steps = 0usize;
        loop {
            steps += 1;
            if seen[d.idx()] || steps > v.len() {
                break;
            }
            seen[d.idx()] = true;
            let l = o[d.next().idx()];
            if l.is_none() {
                break;
            }
            d = l.next();
            if d == start {
                break;
            }
        }
        let vv = v[c0];
        if first[vv.idx()].is_none() {
            first[vv.idx()] = start;
        } else {
            extra.push((vv, start));
        }
    }
    (first, extra)
}

impl CornerTable {
    /// Builds the corner table of a manifold, consistently oriented mesh.
    ///
    /// Fails with [`TopologyError::NonManifold`] if an edge is shared by
    /// more than two faces (or by two faces running the same way), or a
    /// vertex's faces form more than one fan; [`crate::clean`] repairs both.
    /// Unreferenced vertices are allowed and have no corner.
    pub fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Result<Self, TopologyError> {
        let pairing = pair_half_edges(triangles, vertex_count);
        let v: Vec<VertexId> = triangles
            .iter()
            .flat_map(|t| t.iter().map(|&i| VertexId(i)))
            .collect();
        let (vertex_corner, extra) = vertex_fans(&v, &pairing.o, vertex_count);
        if pairing.cut_edges > 0 || !extra.is_empty() {
            let mut vs: Vec<u32> = extra.iter().map(|e| e.0 .0).collect();
            vs.sort_unstable();
            vs.dedup();
            return Err(TopologyError::NonManifold {
                edges: pairing.cut_edges,
                vertices: vs.len() as u64,
            });
        }
        Ok(CornerTable {
            v,
            o: pairing.o,
            vertex_corner,
        })
    }

    /// Assembles a table whose parts were computed by this module's functions.
    #[cfg(feature = "encoder")]
    pub(crate) fn from_raw(
        v: Vec<VertexId>,
        o: Vec<CornerId>,
        vertex_corner: Vec<CornerId>,
    ) -> Self {
        CornerTable {
            v,
            o,
            vertex_corner,
        }
    }

    /// Builds from raw arrays, for decoders that produce V and O directly.
    /// The caller guarantees the invariants; [`CornerTable::check`] verifies them.
    pub fn from_parts(v: Vec<VertexId>, o: Vec<CornerId>, vertex_count: usize) -> Self {
        let (vertex_corner, _) = vertex_fans(&v, &o, vertex_count);
        CornerTable {
            v,
            o,
            vertex_corner,
        }
    }

    /// Number of corners (three per triangle).
    #[inline]
    pub fn corner_count(&self) -> usize {
        self.v.len()
    }

    /// Number of triangles.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.v.len() / 3
    }

    /// Number of vertex slots (including unreferenced vertices).
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.vertex_corner.len()
    }

    /// The vertex of a corner.
    #[inline(always)]
    pub fn vertex(&self, c: CornerId) -> VertexId {
        self.v[c.idx()]
    }

    /// The opposite corner, or `CornerId::NONE` on a boundary.
    #[inline(always)]
    pub fn opposite(&self, c: CornerId) -> CornerId {
        self.o[c.idx()]
    }

    /// The right neighbour's corner, `O[n(c)]`.
    #[inline(always)]
    pub fn right(&self, c: CornerId) -> CornerId {
        self.o[c.next().idx()]
    }

    /// The left neighbour's corner, `O[p(c)]`.
    #[inline(always)]
    pub fn left(&self, c: CornerId) -> CornerId {
        self.o[c.prev().idx()]
    }

    /// The corner of `V[c]` in the next triangle counter-clockwise around
    /// it, or NONE at a boundary.
    #[inline(always)]
    pub fn swing_left(&self, c: CornerId) -> CornerId {
        let r = self.o[c.next().idx()];
        if r.is_none() {
            r
        } else {
            r.next()
        }
    }

    /// The corner of `V[c]` in the next triangle clockwise around it, or
    /// NONE at a boundary.
    #[inline(always)]
    pub fn swing_right(&self, c: CornerId) -> CornerId {
        let l = self.o[c.prev().idx()];
        if l.is_none() {
            l
        } else {
            l.prev()
        }
    }

    /// True if the edge facing `c` is a boundary edge.
    #[inline(always)]
    pub fn is_boundary(&self, c: CornerId) -> bool {
        self.o[c.idx()].is_none()
    }

    /// A corner of `v` from which [`Self::swing_left`] visits `v`'s whole
    /// fan (NONE for an unreferenced vertex).
    #[inline]
    pub fn vertex_corner(&self, v: VertexId) -> CornerId {
        self.vertex_corner[v.idx()]
    }

    /// The corners around `v`, counter-clockwise, starting at the most
    /// clockwise one on a boundary.
    pub fn ring(&self, v: VertexId) -> Ring<'_> {
        let start = self.vertex_corner[v.idx()];
        Ring {
            table: self,
            start,
            next: start,
        }
    }

    /// True if `v` lies on a boundary.
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        let c = self.vertex_corner[v.idx()];
        c.is_some() && self.o[c.prev().idx()].is_none()
    }

    /// The V array (vertex per corner).
    pub fn vertices(&self) -> &[VertexId] {
        &self.v
    }

    /// The O array (opposite corner per corner).
    pub fn opposites(&self) -> &[CornerId] {
        &self.o
    }

    /// The triangle list, three vertex indices per face.
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        self.v
            .chunks_exact(3)
            .map(|t| [t[0].0, t[1].0, t[2].0])
            .collect()
    }

    /// Verifies the invariants listed in the module docs.
    pub fn check(&self) -> Result<(), &'static str> {
        let nc = self.v.len() as u32;
        if nc % 3 != 0 {
            return Err("corner count is not a multiple of 3");
        }
        for c in 0..nc {
            let c = CornerId(c);
            if self.v[c.idx()].idx() >= self.vertex_corner.len() {
                return Err("vertex index out of range");
            }
            let d = self.o[c.idx()];
            if d.is_none() {
                continue;
            }
            if d.0 >= nc {
                return Err("opposite corner out of range");
            }
            if self.o[d.idx()] != c {
                return Err("O[O[c]] != c");
            }
            if d.face() == c.face() {
                return Err("a corner is opposite a corner of its own triangle");
            }
            if self.vertex(d.next()) != self.vertex(c.prev())
                || self.vertex(d.prev()) != self.vertex(c.next())
            {
                return Err("opposite corners do not see the same edge reversed");
            }
        }
        let (first, extra) = vertex_fans(&self.v, &self.o, self.vertex_corner.len());
        if !extra.is_empty() {
            return Err("a vertex has more than one fan");
        }
        if first != self.vertex_corner {
            return Err("vertex_corner is not each fan's most clockwise corner");
        }
        Ok(())
    }

    /// The triangle that owns a corner (convenience re-export of [`CornerId::face`]).
    #[inline(always)]
    pub fn face(&self, c: CornerId) -> FaceId {
        c.face()
    }
}

/// Iterator over the corners of one vertex fan, counter-clockwise.
pub struct Ring<'a> {
    table: &'a CornerTable,
    start: CornerId,
    next: CornerId,
}

impl Iterator for Ring<'_> {
    type Item = CornerId;
    fn next(&mut self) -> Option<CornerId> {
        let c = self.next;
        if c.is_none() {
            return None;
        }
        let n = self.table.swing_left(c);
        self.next = if n == self.start { CornerId::NONE } else { n };
        Some(c)
    }
}
