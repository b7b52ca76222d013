//! Laying one M′ triangle, the two steps the first triangle (`mod.rs`)
//! and every gate (`gate`) share (thesis §7.3; design notes §6 steps 3-6):
//! `circle` finds where the tip's circle, of radius L√3/2 in the gate's
//! bisecting plane, meets M, and `attempt` traces the paths of the
//! triangle's new edges and claims the region of M they bound (its
//! triangloid), up to [`MAX_REGION_AREA`].
//!
//! Invariants: `attempt` succeeds whole or changes no path and no claim
//! (splits of M stay: they change no triangloid); `circle` moves by
//! adjacency on M only (`walk`), within a walk bounded by M's face count
//! and 6 tip radii.

use super::path;
use super::region;
use super::state::Retiler;
use super::walk::{walk_to_radius, Plane, Walker};
use glam::DVec3;

/// The largest triangloid, in L² (an equilateral triangle is 0.43 L²).
pub(super) const MAX_REGION_AREA: f64 = 3.0;

impl Retiler<'_> {
    /// Builds triangle `tri` = (tip, GL, GR) as M′ triangle `id`: traces
    /// the paths of its `new` edges, then claims its triangloid. On any
    /// failure everything it marked is undone and `false` returned (splits
    /// of M stay: they change no triangloid).
    pub(super) fn attempt(&mut self, tri: [u32; 3], new: &[(u32, u32)], id: u32) -> bool {
        let mut made: Vec<(u32, u32)> = Vec::new();
        let mut ok = true;
        for &(a, b) in new {
            let (ma, mb) = (self.msample[a as usize], self.msample[b as usize]);
            let chain = path::find(&self.s, ma, mb, &mut self.scratch)
                .and_then(|pts| path::insert(&mut self.s, &pts));
            let Some(mut chain) = chain else {
                ok = false;
                break;
            };
            if chain[0] != self.msample[a.min(b) as usize] {
                chain.reverse();
            }
            self.paths.insert((a.min(b), a.max(b)), chain);
            made.push((a, b));
        }
        if ok {
            let mut boundary = Vec::new();
            for (a, b) in [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])] {
                boundary.extend(self.path_steps(a, b).map(|(x, _)| x));
            }
            let max_area = MAX_REGION_AREA * (self.slack * self.l).powi(2);
            match region::claim(&mut self.s, &boundary, id, max_area, &mut self.flood) {
                Ok(_) => {
                    for &(a, b) in &made {
                        self.adj[a as usize].push(b);
                        self.adj[b as usize].push(a);
                    }
                    return true;
                }
                Err(_) => region::release(&mut self.s, id, &mut self.flood),
            }
        }
        for (a, b) in made {
            let chain = self.paths.remove(&(a.min(b), a.max(b))).unwrap_or_default();
            path::unmark(&mut self.s, &chain);
        }
        false
    }

    /// Where the circle of radius L√3/2 around the midpoint of edge a–b,
    /// in `plane`, meets M: walking both ways from the crossing of the
    /// edge's path with the plane. Also returns that crossing (a face and
    /// the point), or `None` if the path does not cross the plane.
    #[allow(clippy::type_complexity)]
    pub(super) fn circle(
        &self,
        a: u32,
        b: u32,
        plane: Plane,
        centre: DVec3,
    ) -> ([Option<(DVec3, u32)>; 2], Option<(u32, DVec3)>) {
        // (The crossing is returned as the corner facing its edge.)
        let s = &self.s;
        // The path may cross the bisecting plane more than once; start
        // from the crossing nearest the circle's centre.
        let crossing = self
            .path_steps(a, b)
            .filter(|&(x, y)| {
                plane.positive(s.pos[x as usize]) != plane.positive(s.pos[y as usize])
            })
            .filter_map(|(x, y)| s.edge(x, y))
            .map(|c| (c, plane.crossing(s, c).1))
            .min_by(|a, b| {
                a.1.distance_squared(centre)
                    .total_cmp(&b.1.distance_squared(centre))
            });
        let Some((c, start)) = crossing else {
            return ([None, None], None);
        };
        let budget = s.face_count();
        let max_len = 6.0 * self.radius;
        let hits = [c, s.opp[c as usize]].map(|side| {
            let mut walker = Walker::across(s, plane, side, budget);
            walk_to_radius(&mut walker, start, centre, self.radius, max_len)
        });
        (hits, Some((c, start)))
    }
}
