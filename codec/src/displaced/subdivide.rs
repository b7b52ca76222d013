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

use crate::prelude::*;

/// Past this many corners, a vertex's bucket is sorted by a general sort
/// rather than by insertion.
const SMALL_BUCKET: usize = 32;

/// The edges of a triangle list.
pub(crate) struct Edges {
    /// Corners (`3f + k`), grouped by edge, each group in corner order.
    corners: Vec<u32>,
    /// Edge `e`'s corners are `corners[start[e]..start[e + 1]]`.
    start: Vec<u32>,
    /// The edge of each corner.
    of_corner: Vec<u32>,
}

impl Edges {
    /// The edges of `triangles` (each corner a vertex below 2^32 − 1).
    ///
    /// The order of the sort by `(lo, hi, corner)`, made in linear time:
    /// corners are counted into one bucket per `lo` (in corner order),
    /// and each bucket, a vertex's few edges, is ordered by `(hi,
    /// corner)` (insertion for the usual handful, a general sort past
    /// [`SMALL_BUCKET`], so a hostile fan stays `n log n`). Memory: about
    /// 24 bytes per corner and 4 per vertex.
    pub fn new(triangles: &[[u32; 3]]) -> Edges {
        let corners = 3 * triangles.len();
        let vertices = triangles
            .iter()
            .flatten()
            .max()
            .map_or(0, |&v| v as usize + 1);
        let ends = |c: usize| {
            let t = triangles[c / 3];
            let (a, b) = (t[c % 3], t[(c + 1) % 3]);
            (a.min(b), a.max(b))
        };
        // Bucket starts by lo, then (hi, corner) scattered in corner order.
        let mut at = vec![0u32; vertices + 1];
        for c in 0..corners {
            at[ends(c).0 as usize + 1] += 1;
        }
        for v in 0..vertices {
            at[v + 1] += at[v];
        }
        let mut keyed = vec![(0u32, 0u32); corners];
        let mut next = at.clone();
        for c in 0..corners {
            let (lo, hi) = ends(c);
            let slot = &mut next[lo as usize];
            keyed[*slot as usize] = (hi, c as u32);
            *slot += 1;
        }
        for v in 0..vertices {
            let bucket = &mut keyed[at[v] as usize..at[v + 1] as usize];
            if bucket.len() > SMALL_BUCKET {
                crate::sort::sort_unstable(bucket);
            } else {
                for i in 1..bucket.len() {
                    let mut j = i;
                    while j > 0 && bucket[j - 1] > bucket[j] {
                        bucket.swap(j - 1, j);
                        j -= 1;
                    }
                }
            }
        }
        let mut start = Vec::new();
        let mut of_corner = vec![0u32; corners];
        let mut list = Vec::with_capacity(corners);
        for v in 0..vertices {
            let (first, end) = (at[v] as usize, at[v + 1] as usize);
            for i in first..end {
                let (hi, c) = keyed[i];
                if i == first || keyed[i - 1].0 != hi {
                    start.push(list.len() as u32);
                }
                of_corner[c as usize] = start.len() as u32 - 1;
                list.push(c);
            }
        }
        start.push(corners as u32);
        Edges {
            corners: list,
            start,
            of_corner,
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

    /// The edge of corner `c`.
    pub fn of_corner(&self, c: usize) -> usize {
        self.of_corner[c] as usize
    }

    /// The corner across edge `e` from corner `c` when `e` is interior
    /// and manifold (two corners of opposite directions); `None`
    /// otherwise.
    pub fn across(&self, e: usize, c: u32, triangles: &[[u32; 3]]) -> Option<u32> {
        match *self.corners(e) {
            [x, y] if interior(x, y, triangles) => Some(if x == c { y } else { x }),
            _ => None,
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
    for (f, &[a, b, c]) in triangles.iter().enumerate() {
        let m = |k: usize| vertex_count + edges.of_corner(3 * f + k) as u32;
        let (m0, m1, m2) = (m(0), m(1), m(2));
        out.extend_from_slice(&[[a, m0, m2], [m0, b, m1], [m2, m1, c], [m0, m1, m2]]);
    }
    out
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
        assert_eq!(e.across(1, 2, &tris), Some(3));
        assert_eq!(e.across(0, 0, &tris), None, "boundary");
        let t = split(&tris, &e, 4);
        assert_eq!(t.len(), 8);
        assert_eq!(t[3], [4, 7, 5], "middle of the first face");
        assert_eq!(t[7], [5, 8, 6]);
    }

    #[test]
    fn the_order_is_the_sort_by_key_and_corner() {
        // A fan of 40 triangles around vertex 0 (one bucket past
        // SMALL_BUCKET) plus a strip, in a scrambled vertex numbering.
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
        assert_eq!(e.across(0, 0, &tris), None);
    }
}
