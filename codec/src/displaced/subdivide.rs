//! Regular 1-to-4 subdivision of a triangle mesh's connectivity, with the
//! order of the new vertices the format fixes (format-spec/07-displaced.md,
//! "Subdivision").
//!
//! Source: the midpoint split every subdivision scheme shares (Loop,
//! "Smooth subdivision surfaces based on triangles", 1987; Dyn, Levin &
//! Gregory's butterfly, 1990): one new vertex per edge, each triangle
//! replaced by its three corner triangles and the middle one.
//!
//! ```text
//!            c                    face (a, b, c) with edge vertices
//!           / \                   m0 on ab, m1 on bc, m2 on ca:
//!         m2---m1                 4f + 0: (a, m0, m2)
//!         / \ / \                 4f + 1: (m0, b, m1)
//!        a---m0--b                4f + 2: (m2, m1, c)
//!                                 4f + 3: (m0, m1, m2)
//! ```
//!
//! Invariants (the decoder's order, which the encoder must match exactly):
//! - an edge is the unordered pair {lo, hi} of a triangle's consecutive
//!   corners; edges are numbered in increasing order of the key
//!   `(lo, hi)`, and edge `e`'s new vertex is `vertex_count + e`;
//! - the corners of one edge are listed in increasing corner order
//!   (corner `3f + k` runs from vertex `k` to vertex `k + 1` of face `f`);
//!   an edge with one corner is on a boundary, with two of opposite
//!   directions is interior and manifold, anything else is neither;
//! - nothing depends on the input beyond its triangle list: no hashing,
//!   no float.
//!
//! Why it is fast (the decoder builds one [`Edges`] per level, the largest
//! single part of a level's decode): the sort by `(lo, hi, corner)` is a
//! two-pass radix sort (stable counting passes by `hi`, then by `lo`), so
//! no comparison and no branch on the data, whatever a vertex's valence;
//! each entry is one `u64` that also carries its corner's direction, so
//! the interior test of an edge's two corners reads no triangle; and the
//! same pass records each corner's interior mate (the corner table's
//! `opposite`), which the stencils read as one word. [`split`] walks the
//! triangles and the corners' edges side by side in flat arrays.

use crate::prelude::*;

/// The bit of a radix entry's corner word that marks a corner running
/// from its edge's `hi` to its `lo`.
const BACKWARD: u32 = 1 << 31;

/// No corner: the `mate` of a corner whose edge is not interior.
pub(crate) const NONE: u32 = u32::MAX;

/// The edges of a triangle list.
#[derive(Debug)]
pub(crate) struct Edges {
    /// Corners (`3f + k`), grouped by edge, each group in corner order.
    corners: Vec<u32>,
    /// Edge `e`'s corners are `corners[start[e]..start[e + 1]]`.
    start: Vec<u32>,
    /// The edge of each corner.
    of_corner: Vec<u32>,
    /// For each corner, the other corner of its edge when the edge is
    /// interior (two corners of opposite directions), else [`NONE`]: the
    /// corner table's `opposite`, made once so that [`Edges::mate`]
    /// and the stencils read one word.
    mate: Vec<u32>,
}

impl Edges {
    /// The edges of `triangles` (each corner a vertex below 2^32 − 1).
    ///
    /// The order of the sort by `(lo, hi, corner)`, made in linear time
    /// with no comparison: a least-significant-first radix sort of two
    /// counting passes, the corners (in corner order) scattered by `hi`,
    /// then, read in that order, by `lo`; both are stable, so each `lo`
    /// bucket ends ordered by `(hi, corner)` whatever its size (a hostile
    /// fan costs no more than a strip). Each entry is one `u64`, `lo` or
    /// `hi` in the high word and the corner in the low one, and each
    /// bucket's end is its count's running sum after the scatter (no
    /// second array). Memory: about 32 bytes per corner and 8 per vertex.
    pub fn new(triangles: &[[u32; 3]]) -> Edges {
        let corners = 3 * triangles.len();
        let vertices = triangles
            .iter()
            .flatten()
            .max()
            .map_or(0, |&v| v as usize + 1);
        // by_lo[v + 1] and by_hi[v + 1] count the corners whose lo (hi)
        // is v; after the running sums, by_*[v] is bucket v's start, and
        // after its scatter (which advances it) bucket v's end.
        let mut by_lo = vec![0u32; vertices + 1];
        let mut by_hi = vec![0u32; vertices + 1];
        for t in triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[if k == 2 { 0 } else { k + 1 }]);
                by_lo[a.min(b) as usize + 1] += 1;
                by_hi[a.max(b) as usize + 1] += 1;
            }
        }
        for at in [&mut by_lo, &mut by_hi] {
            let mut sum = 0;
            for a in at.iter_mut() {
                sum += *a;
                *a = sum;
            }
        }
        // A corner that runs from hi to lo carries BACKWARD in its
        // entry's low word (when corner numbers leave bit 31 free, as they
        // do below 715 M triangles), so that the interior test of an
        // edge's two corners reads no triangle.
        let backward = if corners <= 1 << 31 { BACKWARD } else { 0 };
        // Pass 1, by hi: lo << 32 | corner, in corner order per bucket.
        let mut hi_sorted = vec![0u64; corners];
        for (f, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[if k == 2 { 0 } else { k + 1 }]);
                let slot = &mut by_hi[a.max(b) as usize];
                let flag = if a > b { backward } else { 0 };
                hi_sorted[*slot as usize] =
                    u64::from(a.min(b)) << 32 | u64::from(flag) | (3 * f + k) as u64;
                *slot += 1;
            }
        }
        // Pass 2, by lo, reading pass 1's buckets in hi order:
        // hi << 32 | corner, ordered by (lo, hi, corner).
        let mut keyed = vec![0u64; corners];
        let mut first = 0;
        for (hi, &end) in by_hi[..vertices].iter().enumerate() {
            for &entry in &hi_sorted[first..end as usize] {
                let slot = &mut by_lo[(entry >> 32) as usize];
                keyed[*slot as usize] = (hi as u64) << 32 | (entry & 0xffff_ffff);
                *slot += 1;
            }
            first = end as usize;
        }
        drop(hi_sorted);
        let at = by_lo;
        // Groups of equal hi within a bucket are the edges, in order.
        let mut start = Vec::with_capacity(corners / 2 + 2);
        let mut of_corner = vec![0u32; corners];
        let mut mate = vec![NONE; corners];
        let mut list = vec![0u32; corners];
        let mut first = 0;
        for (lo, &end) in at[..vertices].iter().enumerate() {
            let end = end as usize;
            let mut i = first;
            while i < end {
                let hi = keyed[i] >> 32;
                let mut j = i + 1;
                while j < end && keyed[j] >> 32 == hi {
                    j += 1;
                }
                let e = start.len() as u32;
                start.push(i as u32);
                for (slot, &key) in list[i..j].iter_mut().zip(&keyed[i..j]) {
                    let c = key as u32 & !backward;
                    *slot = c;
                    of_corner[c as usize] = e;
                }
                if j == i + 2 {
                    let (x, y) = (keyed[i] as u32, keyed[i + 1] as u32);
                    let opposite = if backward != 0 {
                        // Opposite directions, or a corner from a vertex
                        // to itself (which `interior` also accepts).
                        (x ^ y) & BACKWARD != 0 || lo as u64 == hi
                    } else {
                        interior(x, y, triangles)
                    };
                    let (x, y) = (x & !backward, y & !backward);
                    if opposite {
                        mate[x as usize] = y;
                        mate[y as usize] = x;
                    }
                }
                i = j;
            }
            first = end;
        }
        start.push(corners as u32);
        Edges {
            corners: list,
            start,
            of_corner,
            mate,
        }
    }

    /// An `Edges` from its arrays, as `new` would make them (the caller
    /// vouches: `finer`, which derives a level's edges from the level
    /// above, and is tested against `new`).
    pub(crate) fn from_parts(
        corners: Vec<u32>,
        start: Vec<u32>,
        of_corner: Vec<u32>,
        mate: Vec<u32>,
    ) -> Edges {
        Edges {
            corners,
            start,
            of_corner,
            mate,
        }
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// The corners of edge `e`, in corner order.
    pub fn corners(&self, e: usize) -> &[u32] {
        &self.corners[self.start[e] as usize..self.start[e + 1] as usize]
    }

    /// The first corner of edge `e` (every edge has one).
    pub fn first_corner(&self, e: usize) -> u32 {
        self.corners[self.start[e] as usize]
    }

    /// The edge of corner `c`.
    #[cfg(test)]
    pub fn of_corner(&self, c: usize) -> usize {
        self.of_corner[c] as usize
    }

    /// The edge of each corner, by corner.
    pub fn of_corners(&self) -> &[u32] {
        &self.of_corner
    }

    /// The other corner of corner `c`'s edge when that edge is interior
    /// and manifold (two corners of opposite directions); `None`
    /// otherwise.
    pub fn mate(&self, c: u32) -> Option<u32> {
        match self.mate[c as usize] {
            NONE => None,
            m => Some(m),
        }
    }
}

/// The two directed corners run in opposite directions along their edge.
fn interior(x: u32, y: u32, triangles: &[[u32; 3]]) -> bool {
    let (fx, kx) = ((x / 3) as usize, (x % 3) as usize);
    let (fy, ky) = ((y / 3) as usize, (y % 3) as usize);
    let (tx, ty) = (triangles[fx], triangles[fy]);
    tx[kx] == ty[(ky + 1) % 3] && tx[(kx + 1) % 3] == ty[ky]
}

/// The vertex of corner `c` (its start), its end and the vertex opposite
/// it in its triangle.
pub(crate) fn corner_vertices(c: u32, triangles: &[[u32; 3]]) -> [u32; 3] {
    let (f, k) = ((c / 3) as usize, (c % 3) as usize);
    let t = triangles[f];
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

/// The triangles of one 1-to-4 split: face `f` becomes faces `4f..4f + 4`
/// (see the module's figure); `vertex_count` is the coarse level's.
pub(crate) fn split(triangles: &[[u32; 3]], edges: &Edges, vertex_count: u32) -> Vec<[u32; 3]> {
    let mut out = Vec::with_capacity(4 * triangles.len());
    for (t, m) in triangles.iter().zip(edges.of_corners().chunks_exact(3)) {
        out.extend_from_slice(&quarters(t, m, vertex_count));
    }
    out
}

/// [`split`] into `out`, three indices per triangle (`12 ×` the coarse
/// triangles): the decoder's last level, straight into the caller's
/// index buffer.
pub(crate) fn split_into(
    triangles: &[[u32; 3]],
    edges: &Edges,
    vertex_count: u32,
    out: &mut [u32],
) {
    debug_assert_eq!(out.len(), 12 * triangles.len());
    for ((t, m), o) in triangles
        .iter()
        .zip(edges.of_corners().chunks_exact(3))
        .zip(out.chunks_exact_mut(12))
    {
        o.copy_from_slice(quarters(t, m, vertex_count).as_flattened());
    }
}

/// The four triangles of face `[a, b, c]` whose corners' edges are `m`.
#[inline(always)]
fn quarters(&[a, b, c]: &[u32; 3], m: &[u32], vertex_count: u32) -> [[u32; 3]; 4] {
    let (m0, m1, m2) = (
        vertex_count + m[0],
        vertex_count + m[1],
        vertex_count + m[2],
    );
    [[a, m0, m2], [m0, b, m1], [m2, m1, c], [m0, m1, m2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_triangles_split_into_eight_with_five_edge_vertices() {
        // A quad (0, 1, 2, 3) cut along 0-2.
        let tris = [[0, 1, 2], [0, 2, 3]];
        let e = Edges::new(&tris);
        assert_eq!(e.len(), 5);
        // Keys in order: 01, 02, 03, 12, 23.
        assert_eq!(e.corners(1), &[2, 3]);
        assert_eq!(e.mate(2), Some(3));
        assert_eq!(e.mate(0), None, "boundary");
        let t = split(&tris, &e, 4);
        assert_eq!(t.len(), 8);
        assert_eq!(t[3], [4, 7, 5], "middle of the first face");
        assert_eq!(t[7], [5, 8, 6]);
    }

    #[test]
    fn the_order_is_the_sort_by_key_and_corner() {
        // A fan of 40 triangles around vertex 0 (one large bucket) plus a strip, in a scrambled vertex numbering.
        let mut tris: Vec<[u32; 3]> = (0..40)
            .map(|k| [0, 1 + (k * 7) % 41, 1 + (k * 7 + 7) % 41])
            .collect();
        tris.extend((0..30).map(|k| [50 + (k * 13) % 31, 50 + (k * 13 + 1) % 31, 3 + k % 5]));
        let e = Edges::new(&tris);
        let mut keyed: Vec<(u64, u32)> = Vec::new();
        for (f, t) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                keyed.push((
                    (u64::from(a.min(b)) << 32) | u64::from(a.max(b)),
                    (3 * f + k) as u32,
                ));
            }
        }
        keyed.sort_unstable();
        let flat: Vec<u32> = (0..e.len()).flat_map(|i| e.corners(i).to_vec()).collect();
        assert_eq!(flat, keyed.iter().map(|k| k.1).collect::<Vec<_>>());
        let groups = keyed.windows(2).filter(|w| w[0].0 != w[1].0).count() + 1;
        assert_eq!(e.len(), groups);
        for (i, &(_, c)) in keyed.iter().enumerate() {
            let group = keyed[..=i].windows(2).filter(|w| w[0].0 != w[1].0).count();
            assert_eq!(e.of_corner(c as usize), group);
        }
    }

    #[test]
    fn same_direction_twice_is_not_interior() {
        // Two faces using 0 -> 1 in the same direction (misoriented).
        let tris = [[0, 1, 2], [0, 1, 3]];
        let e = Edges::new(&tris);
        assert_eq!(e.corners(0), &[0, 3]);
        assert_eq!(e.mate(0), None);
    }
}
