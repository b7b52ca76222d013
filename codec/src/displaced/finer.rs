//! The next level's edges from this level's, without a sort: the same
//! [`Edges`] that [`Edges::new`] makes of [`split`](super::subdivide::split)'s
//! triangles, in the order the format fixes (format-spec/07-displaced.md,
//! "Subdivision"), made by two counting passes over this level's edges
//! and faces instead of two radix passes over the next level's corners
//! (four times as many).
//!
//! Every edge of the split mesh is one of two kinds (the figure of
//! [`super::subdivide`]; `V` this level's vertex count, edge `e`'s new
//! vertex `V + e`):
//!
//! ```text
//!   half of edge e = {lo, hi}:  {lo, V+e} and {hi, V+e}
//!        (its corners: the half of each of e's corners at that end)
//!   inside face f, edges e0 e1 e2 (of its corners 0, 1, 2):
//!        {V+e0, V+e2}  corners 12f+1 (m0 -> m2) and 12f+11 (m2 -> m0)
//!        {V+e0, V+e1}  corners 12f+5 (m1 -> m0) and 12f+9  (m0 -> m1)
//!        {V+e1, V+e2}  corners 12f+6 (m2 -> m1) and 12f+10 (m1 -> m2)
//! ```
//!
//! Sorted by `(lo, hi)`, the halves come first (their `lo` is an old
//! vertex, below `V`), by vertex and then by edge; then the inner edges,
//! by their lower edge and then their higher. So the halves are a
//! counting sort of each edge under both its ends, in edge order, and the
//! inner edges a counting sort of each face's three pairs under the lower
//! edge, each bucket (at most four pairs: an edge has at most two faces)
//! ordered by the higher edge.
//!
//! The same construction gives the contexts of the next level's scalars
//! (`scalars`' rule) without reading a triangle: a half's one parent
//! (the vertex new on this level) is its edge's, `V + e`, and an inner
//! edge's two parents are those of its two edges.
//!
//! Invariants: the result is [`Edges::new`] of the split triangles, field
//! for field, and its contexts are `scalars::contexts` of them (tests
//! compare both). Only for a level whose every edge has
//! one or two corners in distinct faces, whose faces have three distinct
//! vertices, and no two of whose faces share two edges (each of those
//! would give an edge of the next level more corners than this
//! construction lists); otherwise `None`, and the caller sorts.

use super::scalars::{capped_length, context};
use super::subdivide::{corner_vertices, Edges, NONE};
use crate::prelude::*;

/// The edges of `split(tris, edges, vertex_count)` and the contexts of
/// their scalars (`qs` holds this level's, one per edge), or `None` for
/// a level this construction does not cover (see the module's docs).
pub(crate) fn finer(
    edges: &Edges,
    tris: &[[u32; 3]],
    vertex_count: u32,
    qs: &[i32],
) -> Option<(Edges, Vec<u8>)> {
    let v = vertex_count as usize;
    let ec = edges.len();
    if qs.len() != ec {
        return None;
    }
    // Each edge's scalar's share of its children's contexts.
    let lens: Vec<u8> = qs.iter().map(|&q| capped_length(q)).collect();
    if tris
        .iter()
        .any(|t| t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
        return None;
    }
    // Half ids `2e + side` (0 at `lo`, 1 at `hi`) must fit a `u32`.
    if ec > (u32::MAX / 2) as usize {
        return None;
    }
    // Each edge's ends, and the fine corners of its halves, read from its
    // triangles once here, in edge order, rather than twice in the
    // buckets' order below.
    let mut ends = Vec::with_capacity(ec);
    let mut made = Vec::with_capacity(ec);
    for e in 0..ec {
        let cs = edges.corners(e);
        if cs.len() > 2 || (cs.len() == 2 && cs[0] / 3 == cs[1] / 3) {
            return None;
        }
        let [a, b, _] = corner_vertices(cs[0], tris);
        if a.max(b) as usize >= v {
            return None;
        }
        let (lo, hi) = (a.min(b), a.max(b));
        ends.push((lo, hi));
        let mated = cs.len() == 2 && edges.mate(cs[0]) == Some(cs[1]);
        let mut h = Made {
            at: [[NONE; 2]; 2],
            corners: cs.len() as u8,
            mated,
        };
        for (i, &c) in cs.iter().enumerate() {
            let (f, k) = (c / 3, (c % 3) as usize);
            // A mate runs the other way; a second corner that is not
            // one (same direction) is read.
            let from = match i {
                0 => a,
                _ if mated => b,
                _ => tris[f as usize][k],
            };
            // The half at the corner's start keeps its leaving piece.
            let (leaving, arriving) = (12 * f + [0, 4, 8][k], 12 * f + [3, 7, 2][k]);
            let at_lo = from == lo;
            h.at[0][i] = if at_lo { leaving } else { arriving };
            h.at[1][i] = if at_lo { arriving } else { leaving };
        }
        made.push(h);
    }
    let corners = 12 * tris.len();
    let halves = 2 * ec;
    let fine_edges = halves + 3 * tris.len();
    let mut list = Vec::with_capacity(corners);
    let mut start = Vec::with_capacity(fine_edges + 1);
    let mut of_corner = vec![0u32; corners];
    let mut mate = vec![NONE; corners];
    let mut contexts = Vec::with_capacity(fine_edges);

    // The halves: each edge under both its ends, in edge order.
    let mut at = vec![0u32; v + 1];
    for &(lo, hi) in &ends {
        at[lo as usize + 1] += 1;
        at[hi as usize + 1] += 1;
    }
    for i in 0..v {
        at[i + 1] += at[i];
    }
    let mut under = vec![0u32; halves];
    for (e, &(lo, hi)) in ends.iter().enumerate() {
        for (side, x) in [lo, hi].into_iter().enumerate() {
            under[at[x as usize] as usize] = 2 * e as u32 + side as u32;
            at[x as usize] += 1;
        }
    }
    // The buckets follow one another, in vertex order.
    for &h in &under {
        let (e, side) = ((h / 2) as usize, (h % 2) as usize);
        let id = start.len() as u32;
        start.push(list.len() as u32);
        contexts.push(context(1, lens[e]));
        let m = &made[e];
        let fine = &m.at[side][..usize::from(m.corners)];
        for &c in fine {
            list.push(c);
            of_corner[c as usize] = id;
        }
        if m.mated {
            mate[fine[0] as usize] = fine[1];
            mate[fine[1] as usize] = fine[0];
        }
    }

    // The inner edges: each face's three pairs under their lower edge.
    let of = edges.of_corners();
    let pairs = |f: usize| {
        let [e0, e1, e2] = [of[3 * f], of[3 * f + 1], of[3 * f + 2]];
        let f = 12 * f as u32;
        [
            (e0, e2, f + 1, f + 11),
            (e0, e1, f + 5, f + 9),
            (e1, e2, f + 6, f + 10),
        ]
    };
    let mut at = vec![0u32; ec + 1];
    for f in 0..tris.len() {
        for (a, b, ..) in pairs(f) {
            at[a.min(b) as usize + 1] += 1;
        }
    }
    for i in 0..ec {
        at[i + 1] += at[i];
    }
    let mut inner = vec![(0u32, 0u32, 0u32); 3 * tris.len()];
    for f in 0..tris.len() {
        for (a, b, x, y) in pairs(f) {
            let slot = &mut at[a.min(b) as usize];
            inner[*slot as usize] = (a.max(b), x, y);
            *slot += 1;
        }
    }
    let mut first = 0;
    for (lo, &end) in at[..ec].iter().enumerate() {
        let bucket = &mut inner[first..end as usize];
        // At most four pairs, from faces in increasing order: a stable
        // insertion sort by the higher edge keeps the corners in order.
        for i in 1..bucket.len() {
            let mut j = i;
            while j > 0 && bucket[j - 1].0 > bucket[j].0 {
                bucket.swap(j - 1, j);
                j -= 1;
            }
        }
        if bucket.windows(2).any(|w| w[0].0 == w[1].0) {
            return None;
        }
        for &(hi, x, y) in bucket.iter() {
            let id = start.len() as u32;
            start.push(list.len() as u32);
            contexts.push(context(2, lens[lo].max(lens[hi as usize])));
            list.extend([x, y]);
            of_corner[x as usize] = id;
            of_corner[y as usize] = id;
            mate[x as usize] = y;
            mate[y as usize] = x;
        }
        first = end as usize;
    }
    start.push(list.len() as u32);
    Some((Edges::from_parts(list, start, of_corner, mate), contexts))
}

/// The halves of one edge of this level: the fine corners of the half
/// at its `lo` (`at[0]`) and at its `hi` (`at[1]`), one per corner of
/// the edge, in its corner order.
struct Made {
    at: [[u32; 2]; 2],
    /// The edge's corners: 1 or 2.
    corners: u8,
    /// Its two corners are mates (interior), and so are each half's.
    mated: bool,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::displaced::subdivide::split;

    fn same(a: &Edges, b: &Edges) {
        assert_eq!(a.len(), b.len());
        for e in 0..a.len() {
            assert_eq!(a.corners(e), b.corners(e), "edge {e}");
        }
        assert_eq!(a.of_corners(), b.of_corners());
        for c in 0..a.of_corners().len() as u32 {
            assert_eq!(a.mate(c), b.mate(c), "corner {c}");
        }
    }

    /// Two levels down from meshes with boundaries, scrambled vertex
    /// numbers and an edge used twice in one direction: the sorted
    /// edges, field for field.
    #[test]
    fn the_next_level_is_the_sort_of_the_split() {
        let sphere = crate::mesh::test_shapes::uv_sphere(9, 7);
        let mut open = sphere.triangles.clone();
        open.truncate(open.len() - 11);
        let scrambled: Vec<[u32; 3]> = sphere
            .triangles
            .iter()
            .map(|t| t.map(|v| (v * 17) % sphere.vertex_count() as u32))
            .collect();
        let misoriented = vec![[0, 1, 2], [0, 1, 3], [1, 2, 4]];
        for tris in [sphere.triangles.clone(), open, scrambled, misoriented] {
            let mut tris = tris;
            let mut n = tris.iter().flatten().max().map_or(0, |&v| v + 1);
            let mut edges = Edges::new(&tris);
            for level in 0..2 {
                let fine = split(&tris, &edges, n);
                let qs: Vec<i32> = (0..edges.len() as i32)
                    .map(|e| (e * 7 + level) % 11 - 5)
                    .collect();
                let (derived, contexts) = finer(&edges, &tris, n, &qs).expect("a clean level");
                let sorted = Edges::new(&fine);
                same(&derived, &sorted);
                let wanted = crate::displaced::scalars::contexts(&sorted, &fine, n as usize, &qs);
                assert_eq!(contexts, wanted);
                n += edges.len() as u32;
                tris = fine;
                edges = sorted;
            }
        }
    }

    /// A level the construction does not cover gives `None`.
    #[test]
    fn unclean_levels_are_left_to_the_sort() {
        for tris in [
            vec![[0, 1, 2], [0, 2, 1], [0, 1, 2]],
            vec![[0, 1, 1], [1, 2, 3]],
            vec![[0, 1, 2], [0, 2, 1]],
        ] {
            let n = tris.iter().flatten().max().map_or(0, |&v| v + 1);
            let edges = Edges::new(&tris);
            let qs = vec![0; edges.len()];
            assert!(finer(&edges, &tris, n, &qs).is_none(), "{tris:?}");
        }
    }
}
