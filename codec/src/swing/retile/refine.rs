//! Refining M to the run's scale before retiling: longest-edge bisection
//! (Rivara's LEPP algorithm, "New longest-edge algorithms for the
//! refinement and/or improvement of unstructured triangulations", 1997)
//! until no edge of M is longer than [`MAX_EDGE`]·L.
//!
//! Why (new in swm; the thesis assumes an input finer than M′): the
//! retiler's paths, walks and floods take their bounds from distances
//! between points of M. On input triangles many L across, and above all
//! on long thin ones (a fanned polygon's spokes, a CAD part's strips), a
//! face's centroid lies far from every point a path really passes, so
//! the fallback path search (`path::dijkstra`) stops at its length bound
//! and a gate in the middle of an empty plane finds no path to its own
//! tip. Measured on a flat 100,000-gon at the default rate (L = 0.0118,
//! unit radius): 30 of 32 runs failed that way, 96 s and 0.95 GB; the
//! same disk triangulated evenly at L/2 retiled in 3 runs with none
//! failing. Refined here: 3 runs, none failing, 9.3 s and 0.59 GB.
//!
//! [`MAX_EDGE`] = 4: at 2, 4 and 8 the polygon retiles in 3 runs; at 2
//! the fandisk rows at 4 and 8 b/v of the shared table move (L2 1-2%
//! better, the sharpened Hausdorff 5-17% worse), at 4 no shared row of
//! fandisk or spot moves and of the generated table only the plane
//! patch at 8 b/v (its hole patch's wall has the long edges; retiling
//! noise of the flat patch's rim, ±10% over nearby L).
//!
//! ```text
//!   f's longest edge e, neighbour g across e:
//!   e is g's longest too (a terminal edge)   → split e at its midpoint
//!   otherwise                                → refine g's longest first
//!          x                    x
//!         / \                  /|\
//!        / f \                / | \
//!       y--e--z      →       y--w--z      (w the midpoint of e)
//!        \ g /                \ | /
//!         \ /                  \|/
//!          x'                   x'
//! ```
//!
//! Invariants:
//! * the geometry of M is unchanged: every new vertex is the midpoint of
//!   an edge, every new face lies in its parent's plane and inherits its
//!   normal and patch (`Surface::split_edge`);
//! * M stays a closed oriented manifold (a split cuts both faces of its
//!   edge, so no vertex hangs);
//! * each split halves the longest edge of the two faces it cuts, and the
//!   smallest angle of a face is at least half the smallest it started
//!   with (Rivara's bound), so slivers are not made thinner;
//! * a mesh whose edges are all at most `MAX_EDGE`·L is not touched, so
//!   ordinary scans at ordinary rates retile as before;
//! * work is linear in the faces added: a LEPP only climbs to longer
//!   edges, and every step ends in a split or in a face that is done.
//!
//! Order: faces are visited from a stack, longest edges compared as
//! (squared length, then the edge's vertex pair), so the result depends
//! on the input alone.

use super::surface::{face, next, prev, Surface};
use super::Failure;

/// The longest edge M may keep, in L.
pub const MAX_EDGE: f64 = 4.0;

/// Splits between two calls of the caller's check.
const CHECK_EVERY: usize = 4096;

/// Splits the edges of `s` by LEPP bisection until none is longer than
/// `limit`, or `max_splits` were made (the retiler then meets what is
/// left as it would have met the input); returns the number of edges
/// split. `check` sees the surface every [`CHECK_EVERY`] splits and
/// ends the refinement with its error (the encoder's limits).
pub fn refine(
    s: &mut Surface,
    limit: f64,
    max_splits: usize,
    mut check: impl FnMut(&Surface) -> Result<(), Failure>,
) -> Result<usize, Failure> {
    if !(limit.is_finite() && limit > 0.0) {
        return Ok(0);
    }
    let limit2 = limit * limit;
    let mut stack: Vec<u32> = (0..s.face_count() as u32)
        .rev()
        .filter(|&f| key(s, longest(s, f)).0 > limit2)
        .collect();
    let mut splits = 0;
    while let Some(f) = stack.pop() {
        // Refine f until its longest edge is short enough; each pass
        // follows the LEPP from f to a terminal edge and splits it.
        loop {
            let c = longest(s, f);
            if key(s, c).0 <= limit2 {
                break;
            }
            if splits >= max_splits {
                return Ok(splits);
            }
            let mut k = c;
            let terminal = loop {
                let o = s.opp[k as usize];
                let kg = longest(s, face(o));
                if kg == o {
                    break k;
                }
                k = kg;
            };
            let o = s.opp[terminal as usize];
            let (fa, fb) = (face(terminal), face(o));
            s.split_edge(terminal, 0.5);
            splits += 1;
            s.tick(1);
            if splits.is_multiple_of(CHECK_EVERY) {
                check(s)?;
            }
            // The two faces split in place may still be long, and so may
            // the two new ones (the last two faces).
            let n = s.face_count() as u32;
            stack.extend([fa, fb, n - 2, n - 1].into_iter().filter(|&g| g != f));
        }
    }
    Ok(splits)
}

/// The corner of face `f` facing its longest edge (see `key`).
fn longest(s: &Surface, f: u32) -> u32 {
    Surface::corners(f)
        .into_iter()
        .max_by(|&a, &b| {
            let (ka, kb) = (key(s, a), key(s, b));
            ka.0.total_cmp(&kb.0).then(ka.1.cmp(&kb.1))
        })
        .unwrap_or(3 * f)
}

/// The edge facing corner `c`: squared length, and its vertex pair in
/// order, the same seen from either face, so "longest" is a strict total
/// order on edges and a LEPP never cycles.
fn key(s: &Surface, c: u32) -> (f64, (u32, u32)) {
    let (a, b) = (s.v[next(c) as usize], s.v[prev(c) as usize]);
    let d = s.pos[a as usize].distance_squared(s.pos[b as usize]);
    (d, (a.min(b), a.max(b)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A closed tetrahedron with unit legs: its edges (1 and √2) are
    /// long against a limit of 0.1.
    fn tetrahedron() -> Surface {
        let pos = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        let tris = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let table = crate::CornerTable::new(&tris, 4).unwrap();
        let opp: Vec<u32> = table.opposites().iter().map(|c| c.0).collect();
        Surface::new(&pos, &tris, &opp)
    }

    fn min_angle(s: &Surface) -> f64 {
        (0..s.face_count() as u32)
            .flat_map(Surface::corners)
            .map(|c| {
                let (x, y, z) = (s.p(c), s.p(next(c)), s.p(prev(c)));
                (y - x).angle_between(z - x)
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn every_edge_ends_below_the_limit_and_the_surface_stays_closed() {
        let mut s = tetrahedron();
        let before = min_angle(&s);
        let splits = refine(&mut s, 0.1, usize::MAX, |_| Ok(())).unwrap();
        assert!(splits > 0);
        for c in 0..s.v.len() as u32 {
            assert!(key(&s, c).0.sqrt() <= 0.1 + 1e-12);
            let o = s.opp[c as usize];
            assert_eq!(s.opp[o as usize], c);
            assert_eq!(s.v[next(c) as usize], s.v[prev(o) as usize]);
        }
        // Area is kept (three right triangles and an equilateral one of
        // side √2), and so is the shape of the triangles (Rivara: at least
        // half the smallest angle).
        let area: f64 = (0..s.face_count() as u32)
            .map(|f| s.double_area(f) / 2.0)
            .sum();
        assert!((area - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-9, "{area}");
        assert!(min_angle(&s) >= before / 2.0 - 1e-9);
    }

    #[test]
    fn splits_stop_at_the_bound() {
        let mut s = tetrahedron();
        assert_eq!(refine(&mut s, 1e-6, 100, |_| Ok(())), Ok(100));
        assert_eq!(s.face_count(), 4 + 2 * 100);
        // The caller's check ends it too, with its error.
        let mut s = tetrahedron();
        let mut seen = 0;
        let out = refine(&mut s, 1e-6, usize::MAX, |s| {
            seen = s.face_count();
            Err(Failure::Limit)
        });
        assert_eq!(out, Err(Failure::Limit));
        assert_eq!(seen, 4 + 2 * CHECK_EVERY);
    }

    #[test]
    fn a_fine_mesh_is_left_alone() {
        let mut s = tetrahedron();
        assert_eq!(refine(&mut s, 1.5, usize::MAX, |_| Ok(())), Ok(0));
        assert_eq!(s.face_count(), 4);
    }
}
