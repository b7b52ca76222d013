//! Bender's classification of edges and vertices: which edges are sharp,
//! what each vertex is, and what each end of a non-sharp edge looks like
//! to the stencils (M. Attene, *Surface Remeshing and Applications*,
//! 2004, §8.4.1; D. Zorin, P. Schröder, W. Sweldens, SIGGRAPH 1996, for
//! the smooth and boundary cases; `../shared/design/ALGORITHMS.md` §8).
//!
//! Edges are numbered once through the corner table: edge `e` is facing
//! the lower of its two corners (or its only one on a boundary), in
//! increasing corner order. A *hard* edge is a tagged edge or a boundary
//! edge: mesh boundaries are subdivided like sharp edges (R2) and count as
//! sharp when vertices are classified.
//!
//! Around a vertex V, corner `x` of V sees its triangle's two other
//! vertices: R(x) = V[n(x)] on its right, L(x) = V[p(x)] on its left;
//! [`CornerTable::swing_left`] crosses the edge V–L(x), so the ring of V
//! counter-clockwise reads R(x₀), R(x₁), … (and L of the last corner on a
//! boundary).
//!
//! ```text
//!          L(x) ------ R(x)            sector of k = 3 triangles,
//!              \  x   /                bounded by the hard edges
//!               \    /                 V–s_0 and V–s_3:
//!                 V                       s_2 -- s_1
//!                                        /  \   / \
//!                                 s_3 ===== V ===== s_0
//! ```
//!
//! Invariants kept: every walk is bounded (by the fan's size, or by the
//! caller's cap), and a walk only crosses non-hard edges, which are never
//! boundaries, so it never meets a missing neighbour.

use crate::prelude::*;

use super::super::SharpEdges;
use crate::{CornerId, CornerTable, VertexId};

/// Edge flag: tagged sharp or on the boundary.
pub(super) const HARD: u8 = 1;
/// Edge flag: tagged sharp (its halves stay tagged).
pub(super) const TAGGED: u8 = 2;

/// What a vertex is, by the number n of hard edges at it (§8.4.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum VertexClass {
    /// No triangle uses it; it is copied and never read.
    Unused,
    /// Interior, with n ≤ 1: a dart end (n = 1) is treated as an ordinary
    /// vertex (§8.4.1.2). Regular (R1) at valence 6, extraordinary (E1)
    /// otherwise.
    Smooth {
        /// Edges (and triangles) round it.
        valence: u32,
    },
    /// n = 2: a 1-manifold sharp vertex, R2's kind of vertex on a sharp
    /// edge. A plain boundary vertex (two boundary edges) is one.
    Crease,
    /// n ≥ 3: a non-manifold sharp vertex (a corner of the sharp-edge
    /// graph, or a boundary vertex that a tagged edge also reaches).
    Corner,
}

/// One end V of a non-sharp edge V–W, as its stencil sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum End {
    /// V is a smooth vertex of this valence: regular at 6, else E1.
    Smooth {
        /// V's valence.
        valence: usize,
    },
    /// V has n ≥ 2 hard edges, so the edge lies in a sector between two
    /// of them (the "topological cut" of §8.4.1.2, done without copying
    /// V): W = s_i of the sector s_0 … s_k of k triangles. A crease end is
    /// regular (R3/R4/R5) at k = 3, else E2.
    Sector {
        /// Triangles in the sector.
        k: usize,
        /// W's place in it, 0 < i < k.
        i: usize,
    },
    /// A sector larger than the caller's cap (handled from sums shared by
    /// the whole sector, see `stencil::e2_all`).
    LargeSector,
}

impl End {
    /// Whether this end is regular: valence 6, or a sector of 3 triangles.
    pub(super) fn is_regular(self) -> bool {
        matches!(self, End::Smooth { valence: 6 } | End::Sector { k: 3, .. })
    }
}

/// Edges and vertices of one mesh, classified for one subdivision step.
pub(super) struct Classes<'a> {
    /// The mesh's corner table.
    pub table: &'a CornerTable,
    /// The edge facing each corner.
    pub edge_of: Vec<u32>,
    /// Each edge's lower corner (its only one on a boundary).
    pub edge_corner: Vec<CornerId>,
    /// [`HARD`] and [`TAGGED`] bits per edge.
    pub flags: Vec<u8>,
    /// Triangles round each vertex (its valence when interior).
    pub faces: Vec<u32>,
    /// Hard edges at each vertex, saturating at 3: only 0, 1, 2 and
    /// "more" matter.
    hard: Vec<u8>,
    /// The other ends of a vertex's first two hard edges: R2's V2 and W2.
    hard_nbr: Vec<[u32; 2]>,
}

impl<'a> Classes<'a> {
    /// Numbers the edges, reads the tags (edges that do not exist are
    /// ignored) and counts, per vertex, triangles and hard edges. Linear
    /// in the mesh, plus a binary search in `tags` per edge when there
    /// are tags.
    pub(super) fn new(table: &'a CornerTable, tags: &SharpEdges) -> Self {
        let nc = table.corner_count();
        let nv = table.vertex_count();
        let (v, o) = (table.vertices(), table.opposites());
        let mut edge_of = vec![u32::MAX; nc];
        let mut edge_corner = Vec::with_capacity(nc / 2 + 1);
        for c in 0..nc {
            let d = o[c];
            // Opposite corners share the edge; the lower one numbers it.
            if d.is_none() || (c as u32) < d.0 {
                let e = edge_corner.len() as u32;
                edge_of[c] = e;
                if d.is_some() {
                    edge_of[d.idx()] = e;
                }
                edge_corner.push(CornerId(c as u32));
            }
        }
        let mut faces = vec![0u32; nv];
        for x in v {
            faces[x.idx()] += 1;
        }
        let mut flags = vec![0u8; edge_corner.len()];
        let mut hard = vec![0u8; nv];
        let mut hard_nbr = vec![[u32::MAX; 2]; nv];
        for (f, &c) in flags.iter_mut().zip(&edge_corner) {
            let (a, b) = (v[c.next().idx()].0, v[c.prev().idx()].0);
            let tagged = !tags.is_empty() && tags.contains(a, b);
            if tagged {
                *f |= TAGGED;
            }
            if tagged || o[c.idx()].is_none() {
                *f |= HARD;
                for (x, y) in [(a, b), (b, a)] {
                    let n = &mut hard[x as usize];
                    if *n < 2 {
                        hard_nbr[x as usize][*n as usize] = y;
                    }
                    *n = (*n + 1).min(3);
                }
            }
        }
        Classes {
            table,
            edge_of,
            edge_corner,
            flags,
            faces,
            hard,
            hard_nbr,
        }
    }

    /// Number of edges.
    pub(super) fn edge_count(&self) -> usize {
        self.edge_corner.len()
    }

    /// Whether the edge facing corner `c` is hard.
    #[inline]
    pub(super) fn hard_facing(&self, c: CornerId) -> bool {
        self.flags[self.edge_of[c.idx()] as usize] & HARD != 0
    }

    /// The vertex of a corner, as an index.
    #[inline]
    pub(super) fn at(&self, c: CornerId) -> u32 {
        self.table.vertex(c).0
    }

    /// The vertex across the edge facing `c` from `c`, if that edge is
    /// not a boundary.
    #[inline]
    pub(super) fn across(&self, c: CornerId) -> Option<u32> {
        let d = self.table.opposite(c);
        d.is_some().then(|| self.at(d))
    }

    /// What vertex `v` is (see [`VertexClass`]).
    pub(super) fn class(&self, v: u32) -> VertexClass {
        match (self.faces[v as usize], self.hard[v as usize]) {
            (0, _) => VertexClass::Unused,
            (valence, 0 | 1) => VertexClass::Smooth { valence },
            (_, 2) => VertexClass::Crease,
            _ => VertexClass::Corner,
        }
    }

    /// For a 1-manifold sharp vertex `v` and one of its hard neighbours
    /// `w`, the other one; `None` if `v` is not 1-manifold.
    #[inline]
    pub(super) fn chain_next(&self, v: u32, w: u32) -> Option<u32> {
        if self.class(v) != VertexClass::Crease {
            return None;
        }
        let [a, b] = self.hard_nbr[v as usize];
        Some(if a == w { b } else { a })
    }

    /// Whether `v` is a used vertex with at most one hard edge (so that
    /// non-sharp edges at it use the smooth rules).
    #[inline]
    pub(super) fn is_smooth(&self, v: u32) -> bool {
        matches!(self.class(v), VertexClass::Smooth { .. })
    }

    /// How the vertex V of corner `x` sees the non-hard edge V–R(x). For
    /// a crease end, `sector[..=k]` receives s_0 … s_k; a sector of more
    /// than `cap` triangles (or more than `sector` can hold) is reported
    /// as [`End::LargeSector`] after at most `cap` steps.
    pub(super) fn end(&self, x: CornerId, cap: usize, sector: &mut [u32]) -> End {
        let v = self.at(x);
        if self.is_smooth(v) {
            return End::Smooth {
                valence: self.faces[v as usize] as usize,
            };
        }
        let cap = cap.min(sector.len().saturating_sub(1));
        let t = self.table;
        // Clockwise to the sector's first triangle, whose right edge is
        // hard: the edge is then the i-th inner edge.
        let mut y = x;
        let mut i = 0;
        while !self.hard_facing(y.prev()) {
            i += 1;
            if i > cap {
                return End::LargeSector;
            }
            // The right edge is not hard, so not a boundary.
            y = t.swing_right(y);
        }
        // Counter-clockwise over the sector, collecting its vertices.
        sector[0] = self.at(y.next());
        let mut k = 0;
        loop {
            k += 1;
            if k > cap {
                return End::LargeSector;
            }
            sector[k] = self.at(y.prev());
            if self.hard_facing(y.next()) {
                break;
            }
            y = t.swing_left(y);
        }
        End::Sector { k, i }
    }

    /// The corners of vertex `v` counter-clockwise, starting, when `v` has
    /// a hard edge, at a corner whose right edge is hard (the first
    /// triangle of a sector). Calls `f` once per corner; at most
    /// `faces[v]` steps.
    pub(super) fn for_each_corner(&self, v: u32, mut f: impl FnMut(CornerId)) {
        let t = self.table;
        let n = self.faces[v as usize] as usize;
        let mut x = t.vertex_corner(VertexId(v));
        if x.is_none() {
            return;
        }
        // On a boundary the fan's first corner already has the boundary on
        // its right; an interior vertex with hard edges turns to one.
        if self.hard[v as usize] > 0 {
            for _ in 0..n {
                if self.hard_facing(x.prev()) {
                    break;
                }
                x = t.swing_left(x);
            }
        }
        for _ in 0..n {
            f(x);
            x = t.swing_left(x);
            if x.is_none() {
                break;
            }
        }
    }
}

/// The tags that name edges of the mesh, in the same form; the rest are
/// dropped.
pub(super) fn existing_tags(table: &CornerTable, tags: &SharpEdges) -> SharpEdges {
    if tags.is_empty() {
        return SharpEdges::default();
    }
    let v = table.vertices();
    let pairs = (0..table.corner_count()).filter_map(|c| {
        let d = table.opposite(CornerId(c as u32));
        let c = CornerId(c as u32);
        let (a, b) = (v[c.next().idx()].0, v[c.prev().idx()].0);
        ((d.is_none() || c.0 < d.0) && tags.contains(a, b)).then_some([a, b])
    });
    SharpEdges::new(pairs)
}
