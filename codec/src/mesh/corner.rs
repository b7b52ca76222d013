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

use crate::prelude::*;

use super::{CornerId, FaceId, VertexId};
use crate::TopologyError;

/// Opposite-corner table over a triangle list (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CornerTable {
    v: Vec<VertexId>,
    o: Vec<CornerId>,
    vertex_corner: Vec<CornerId>,
}

/// "No successor" in [`vertex_fans`]' groups.
const NO_LINK: u32 = u32::MAX;

/// The corners of each vertex, in increasing order, by a counting sort:
/// `corners[start[v] .. start[v + 1]]` are vertex `v`'s. Corners whose
/// vertex is not below `vertex_count` are left out.
pub(crate) fn corners_by_vertex(v: &[VertexId], vertex_count: usize) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; vertex_count + 1];
    for x in v {
        if let Some(n) = start.get_mut(x.idx() + 1) {
            *n += 1;
        }
    }
    for i in 0..vertex_count {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut corners = vec![0u32; start[vertex_count] as usize];
    for (c, x) in v.iter().enumerate() {
        if x.idx() < vertex_count {
            let slot = &mut fill[x.idx()];
            corners[*slot as usize] = c as u32;
            *slot += 1;
        }
    }
    (start, corners)
}

/// Result of matching half-edges, before any manifold check.
#[derive(Clone)]
pub(crate) struct Pairing {
    /// Opposite corner per corner; NONE for boundaries and cut edges.
    pub o: Vec<CornerId>,
    /// Undirected edges left unpaired because more than two faces share
    /// them or because both faces run along them the same way.
    pub cut_edges: u64,
    /// Pairs whose two half-edges run the same way (paired only when
    /// pairing undirected edges; zero means the faces agree everywhere).
    /// Read by cleaning only.
    #[cfg_attr(not(feature = "encoder"), allow(dead_code))]
    pub same_direction: u64,
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
    let mut same_direction = 0u64;
    // What a group of half-edges on one undirected edge becomes.
    let mut settle = |group: &[(u32, u32)]| match *group {
        [_] => {} // a boundary edge
        [(_, a), (_, b)] if undirected || (a ^ b) >> 31 == 1 => {
            same_direction += u64::from((a ^ b) >> 31 == 0);
            let (a, b) = (a & 0x7fff_ffff, b & 0x7fff_ffff);
            o[a as usize] = CornerId(b);
            o[b as usize] = CornerId(a);
        }
        _ => cut_edges += 1,
    };
    for v in 0..vertex_count {
        let bucket = &mut entries[start[v] as usize..start[v + 1] as usize];
        if bucket.len() <= 8 {
            // Buckets average six entries: gather each entry's partners
            // by scanning the few after it (a mask marks those taken).
            let mut taken = 0u32;
            for i in 0..bucket.len() {
                if taken >> i & 1 == 1 {
                    continue;
                }
                let mut group = [bucket[i]; 3];
                let mut n = 1;
                for j in i + 1..bucket.len() {
                    if bucket[j].0 == bucket[i].0 {
                        taken |= 1 << j;
                        if n < 3 {
                            group[n] = bucket[j];
                        }
                        n += 1;
                    }
                }
                settle(&group[..n.min(3)]);
            }
        } else {
            // Sorting puts the half-edges of each undirected edge next to
            // each other: O(k log k) for a vertex of huge valence.
            crate::sort::sort_unstable(bucket);
            bucket.chunk_by(|a, b| a.0 == b.0).for_each(&mut settle);
        }
    }
    Pairing {
        o,
        cut_edges,
        same_direction,
    }
}

/// For every vertex, the most clockwise corner of each of its fans.
/// Returns (first fan corner per vertex, extra fans as (vertex, corner)).
///
/// A fan is a maximal run of corners of one vertex linked by
/// `swing_left(c) = n(O[n(c)])`: a path from its most clockwise corner
/// (the one no corner swings to) when it touches a boundary, else a
/// cycle, whose start is its lowest corner. The fan holding a vertex's
/// lowest corner is its first; the others are listed in the order of
/// their lowest corners.
///
/// Why not walk the fans round the table: each step of such a walk waits
/// for the load before it, and on a large mesh every load is a cache
/// miss. Grouping the corners by vertex first (a counting sort) makes
/// every `O` lookup independent of the others, so the processor overlaps
/// the misses, and the walks then run inside a group of a few corners.
///
/// Robust to any `O` (as [`CornerTable::from_parts`] may get): a link
/// that leaves the vertex, or a second link into the same corner, counts
/// as a boundary; corners whose vertex is out of range are ignored.
pub(crate) fn vertex_fans(
    v: &[VertexId],
    o: &[CornerId],
    vertex_count: usize,
) -> (Vec<CornerId>, Vec<(VertexId, CornerId)>) {
    // Each corner's swing_left target n(O[n(c)]), grouped by vertex with
    // a counting sort. O[n(c)] lies in c's own triangle, so both arrays
    // are read in order; the only scattered accesses are the sort's.
    let mut start = vec![0u32; vertex_count + 1];
    for x in v {
        if x.idx() < vertex_count {
            start[x.idx() + 1] += 1;
        }
    }
    for i in 0..vertex_count {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut entries = vec![(0u32, NO_LINK); start[vertex_count] as usize];
    for (c, x) in v.iter().enumerate() {
        if x.idx() < vertex_count {
            let c = CornerId(c as u32);
            let target = match o.get(c.next().idx()) {
                Some(d) if d.is_some() => d.next().0,
                _ => NO_LINK,
            };
            let slot = &mut fill[x.idx()];
            entries[*slot as usize] = (c.0, target);
            *slot += 1;
        }
    }
    let mut first = vec![CornerId::NONE; vertex_count];
    // (lowest corner, vertex, start) of every fan but a vertex's first.
    let mut extra: Vec<(CornerId, VertexId, CornerId)> = Vec::new();
    // Scratch for one group: on the stack for the usual few corners, on
    // the heap for a vertex of high valence.
    let mut big = (Vec::new(), Vec::new(), Vec::new());
    let mut starts: Vec<CornerId> = Vec::new();
    for vv in 0..vertex_count {
        let group = &entries[start[vv] as usize..start[vv + 1] as usize];
        if group.is_empty() {
            continue;
        }
        let k = group.len();
        let mut small = (
            [NO_LINK; SMALL_GROUP],
            [false; SMALL_GROUP],
            [NO_LINK; SMALL_GROUP],
        );
        let (succ, has_pred, fan) = if k <= SMALL_GROUP {
            (&mut small.0[..k], &mut small.1[..k], &mut small.2[..k])
        } else {
            big.0.clear();
            big.0.resize(k, NO_LINK);
            big.1.clear();
            big.1.resize(k, false);
            big.2.clear();
            big.2.resize(k, NO_LINK);
            (&mut big.0[..], &mut big.1[..], &mut big.2[..])
        };
        group_fans(group, succ, has_pred, fan, &mut starts);
        let main = fan[0] as usize;
        first[vv] = starts[main];
        if starts.len() > 1 {
            // Each other fan, keyed by its lowest corner: the first of its
            // corners in the (sorted) group.
            let mut listed = vec![false; starts.len()];
            listed[main] = true;
            for (j, &(c, _)) in group.iter().enumerate() {
                let f = fan[j] as usize;
                if !listed[f] {
                    listed[f] = true;
                    extra.push((CornerId(c), VertexId(vv as u32), starts[f]));
                }
            }
        }
    }
    crate::sort::sort_unstable(&mut extra);
    (first, extra.into_iter().map(|(_, vv, c)| (vv, c)).collect())
}

/// Groups up to this size are resolved in scratch space on the stack.
const SMALL_GROUP: usize = 16;

/// Splits one vertex's group of `(corner, swing_left target)` entries,
/// sorted by corner, into fans: `fan[j]` receives the fan of entry `j`
/// and `starts` the start of each fan (see [`vertex_fans`]). The scratch
/// slices have the group's length; `succ` and `fan` come filled with
/// [`NO_LINK`], `has_pred` with `false`.
fn group_fans(
    group: &[(u32, u32)],
    succ: &mut [u32],
    has_pred: &mut [bool],
    fan: &mut [u32],
    starts: &mut Vec<CornerId>,
) {
    // Link each corner to its successor, unless another corner already
    // links there (only possible in a broken table).
    for (j, &(_, target)) in group.iter().enumerate() {
        let found = if group.len() <= 8 {
            group.iter().position(|e| e.0 == target)
        } else {
            group.binary_search_by_key(&target, |e| e.0).ok()
        };
        if let Some(i) = found {
            if !has_pred[i] {
                has_pred[i] = true;
                succ[j] = i as u32;
            }
        }
    }
    // Label the fans: paths first, each from the corner nothing swings
    // to, then cycles, each from its lowest corner. A walk stops at a
    // labelled corner, so a group of k corners costs O(k).
    starts.clear();
    for cycles in [false, true] {
        for j in 0..group.len() {
            if fan[j] != NO_LINK || (!cycles && has_pred[j]) {
                continue;
            }
            let label = starts.len() as u32;
            starts.push(CornerId(group[j].0));
            let mut i = j;
            while fan[i] == NO_LINK {
                fan[i] = label;
                match succ[i] {
                    NO_LINK => break,
                    next => i = next as usize,
                }
            }
        }
    }
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
            crate::sort::sort_unstable(&mut vs);
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

    /// Assembles a table from parts that already satisfy the invariants
    /// (computed by this module's functions, or by a decoder that proves
    /// them by construction); nothing is checked.
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference [`vertex_fans`]: walk round each fan from the first
    /// corner not seen yet, swinging right to the most clockwise corner
    /// and then left over the fan.
    fn vertex_fans_by_walking(
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

    use crate::mesh::test_rng::Rng;

    #[test]
    fn fans_match_the_walking_reference() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut several_fans = 0;
        for round in 0..3000 {
            let faces = 1 + rng.below(if round % 2 == 0 { 12 } else { 40 }) as usize;
            let vertices = 3 + rng.below(8) as usize;
            let tris: Vec<[u32; 3]> = (0..faces)
                .map(|_| loop {
                    let t = [0, 0, 0].map(|_| rng.below(vertices as u64));
                    if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
                        break t;
                    }
                })
                .collect();
            let v: Vec<VertexId> = tris.iter().flatten().map(|&x| VertexId(x)).collect();
            // Real pairings (bow ties, several fans, boundaries), and in one
            // round out of four a random O, where only "no panic" counts.
            let o = if round % 4 == 3 {
                (0..v.len())
                    .map(|_| match rng.below(3) {
                        0 => CornerId::NONE,
                        _ => CornerId(rng.below(v.len() as u64)),
                    })
                    .collect()
            } else {
                pair_half_edges(&tris, vertices).o
            };
            let fast = vertex_fans(&v, &o, vertices);
            if round % 4 != 3 {
                assert_eq!(fast, vertex_fans_by_walking(&v, &o, vertices), "{tris:?}");
                several_fans += usize::from(!fast.1.is_empty());
            }
        }
        assert!(several_fans > 100, "{several_fans} rounds with extra fans");
    }
}
