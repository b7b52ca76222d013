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
    /// Memory: about 28 bytes per corner while sorting.
    pub fn new(triangles: &[[u32; 3]]) -> Edges {
        let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
        for (f, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                keyed.push((key, 3 * f as u32 + k as u32));
            }
        }
        // Corners are unique, so the pairs are, and any sort gives this
        // order.
        crate::sort::sort_unstable(&mut keyed);
        let mut start = Vec::new();
        let mut of_corner = vec![0u32; keyed.len()];
        let mut corners = Vec::with_capacity(keyed.len());
        for (i, &(key, c)) in keyed.iter().enumerate() {
            if i == 0 || keyed[i - 1].0 != key {
                start.push(i as u32);
            }
            of_corner[c as usize] = start.len() as u32 - 1;
            corners.push(c);
        }
        start.push(keyed.len() as u32);
        Edges {
            corners,
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
    fn same_direction_twice_is_not_interior() {
        // Two faces using 0 -> 1 in the same direction (misoriented).
        let tris = [[0, 1, 2], [0, 1, 3]];
        let e = Edges::new(&tris);
        assert_eq!(e.corners(0), &[0, 3]);
        assert_eq!(e.across(0, 0, &tris), None);
    }
}
