//! The hole mask: which retiled triangles the decoder drops so that each
//! boundary loop of the input comes back (design notes §6, ambiguity iii).
//!
//! A triangle is a hole candidate when most of its triangloid lies on one
//! hole's patch (`fill`). Taking the candidates as they come could leave
//! a hole in pieces, a pinched ring or two holes sharing a vertex, and the
//! decoded mesh would then have the wrong number of boundary loops or a
//! non-manifold vertex. So each hole's region is *grown* from its most
//! covered triangle, one triangle at a time, and a triangle joins only if
//! the region stays a disk:
//!
//! ```text
//!   shares one edge with the region, and its third vertex is not on the
//!   region (else the boundary would touch itself):       joins
//!   shares two edges (fills a notch):                     joins
//!   shares three edges (would close the surface):         never
//! ```
//!
//! and none of its vertices belongs to another hole's region. Each hole
//! then removes one disk, vertex-disjoint from the others, from a closed
//! surface: the decoded mesh is manifold with exactly one boundary loop
//! per surviving hole. A hole whose patch holds no triangle free of other
//! regions is lost and counted.

use super::surface::NONE;
use crate::{CornerId, CornerTable};
use std::collections::VecDeque;

/// Share of a triangle's triangloid on a patch that makes it a candidate.
const CANDIDATE_SHARE: f64 = 0.5;

/// Per retiled triangle: the hole whose patch covers most of its
/// triangloid (or `NONE`) and that share of its area (0 to 1).
pub type Cover = (u32, f64);

/// The mask of one closed component: per triangle, dropped or not; and
/// how many of the `holes` got no region at all. Hole `first` (the one
/// whose loop started the retiling, `boundary`) is grown before the
/// others, so that its fan is never cut short by a neighbour's region.
pub fn grow(
    table: &CornerTable,
    cover: &[Cover],
    holes: u32,
    first: Option<u32>,
) -> (Vec<bool>, u32) {
    let nf = table.face_count();
    let mut region = vec![NONE; nf];
    let mut vertex_hole = vec![NONE; table.vertex_count()];
    let mut lost = 0;
    let mut queue = VecDeque::new();
    let order = first
        .into_iter()
        .chain((0..holes).filter(|&h| Some(h) != first));
    for h in order {
        let seed = (0..nf)
            .filter(|&t| cover[t].0 == h && cover[t].1 > 0.0)
            .filter(|&t| {
                corners(t)
                    .iter()
                    .all(|&c| free_for(&vertex_hole, table, c, h))
            })
            .max_by(|&a, &b| cover[a].1.total_cmp(&cover[b].1).then(b.cmp(&a)));
        let Some(seed) = seed else {
            lost += 1;
            continue;
        };
        join(table, seed, h, &mut region, &mut vertex_hole);
        queue.clear();
        queue.extend(neighbours(table, seed));
        while let Some(t) = queue.pop_front() {
            if region[t] != NONE || cover[t].0 != h || cover[t].1 < CANDIDATE_SHARE {
                continue;
            }
            if !keeps_disk(table, t, h, &region, &vertex_hole) {
                continue;
            }
            join(table, t, h, &mut region, &mut vertex_hole);
            queue.extend(neighbours(table, t));
        }
    }
    (region.iter().map(|&r| r != NONE).collect(), lost)
}

fn corners(t: usize) -> [CornerId; 3] {
    let c = 3 * t as u32;
    [CornerId(c), CornerId(c + 1), CornerId(c + 2)]
}

fn neighbours(table: &CornerTable, t: usize) -> [usize; 3] {
    corners(t).map(|c| table.opposite(c).face().idx())
}

fn free_for(vertex_hole: &[u32], table: &CornerTable, c: CornerId, h: u32) -> bool {
    let o = vertex_hole[table.vertex(c).idx()];
    o == NONE || o == h
}

fn join(table: &CornerTable, t: usize, h: u32, region: &mut [u32], vertex_hole: &mut [u32]) {
    region[t] = h;
    for c in corners(t) {
        vertex_hole[table.vertex(c).idx()] = h;
    }
}

/// Whether region `h` stays a disk, vertex-disjoint from the other
/// regions, when triangle `t` joins it (see the module comment).
fn keeps_disk(table: &CornerTable, t: usize, h: u32, region: &[u32], vertex_hole: &[u32]) -> bool {
    if !corners(t)
        .iter()
        .all(|&c| free_for(vertex_hole, table, c, h))
    {
        return false;
    }
    // Corner c faces the edge shared with the triangle across it.
    let shared: Vec<CornerId> = corners(t)
        .into_iter()
        .filter(|&c| region[table.opposite(c).face().idx()] == h)
        .collect();
    match shared.len() {
        1 => vertex_hole[table.vertex(shared[0]).idx()] != h,
        2 => true,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An octahedron: 8 faces around 6 vertices.
    fn octahedron() -> CornerTable {
        let (p, f) = crate::edgebreaker::tests_support::octahedron();
        CornerTable::new(&f, p.len()).unwrap()
    }

    /// V − E + F of the masked triangles (1 for a disk).
    fn euler(table: &CornerTable, mask: &[bool]) -> i64 {
        let faces: Vec<usize> = (0..mask.len()).filter(|&t| mask[t]).collect();
        let mut verts: Vec<u32> = faces
            .iter()
            .flat_map(|&t| corners(t).map(|c| table.vertex(c).0))
            .collect();
        verts.sort_unstable();
        verts.dedup();
        // Interior edges are counted from both sides, boundary edges once.
        let halves = 3 * faces.len() as i64;
        let interior = faces
            .iter()
            .flat_map(|&t| corners(t))
            .filter(|&c| mask[table.opposite(c).face().idx()])
            .count() as i64;
        let edges = halves - interior / 2;
        verts.len() as i64 - edges + faces.len() as i64
    }

    #[test]
    fn a_full_cover_grows_one_disk_and_leaves_a_surface() {
        let table = octahedron();
        let cover = vec![(0, 1.0); 8];
        let (mask, lost) = grow(&table, &cover, 1, None);
        assert_eq!(lost, 0);
        assert!(mask.iter().any(|&m| !m), "{mask:?}");
        assert_eq!(euler(&table, &mask), 1, "{mask:?}");
        let rest: Vec<bool> = mask.iter().map(|&m| !m).collect();
        assert_eq!(euler(&table, &rest), 1, "{mask:?}");
    }

    #[test]
    fn two_holes_never_share_a_vertex() {
        let table = octahedron();
        // Hole 0 covers the top four faces, hole 1 the bottom four.
        let cover: Vec<Cover> = (0..8).map(|t| (u32::from(t >= 4), 0.9)).collect();
        let (mask, lost) = grow(&table, &cover, 2, None);
        // Hole 0 takes the top fan, whose rim is every vertex but the
        // bottom one: no bottom face is free of it, and hole 1 is lost.
        assert_eq!(lost, 1);
        assert_eq!(mask, [true, true, true, true, false, false, false, false]);
    }

    #[test]
    fn an_uncovered_hole_is_lost() {
        let table = octahedron();
        let (mask, lost) = grow(&table, &[(NONE, 0.0); 8], 1, None);
        assert_eq!(lost, 1);
        assert!(mask.iter().all(|&m| !m));
    }
}
