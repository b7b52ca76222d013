//! The cost `fit` minimizes over a C's angle codes (issue 19): the
//! squared distance between a candidate triangle T = (tip, GL, GR) and
//! the region of M its triangloid claims, both ways: over the region's
//! vertices (M → T) and over [`FIT_POINTS`] of T (T → M). The formula,
//! and why both directions, are in `fit`.
//!
//! Why a file of its own: `Region` is scratch the run keeps from one C
//! to the next (`state::Retiler::fit_region`), so it lies below the
//! run's state, while `fit`'s descent is a method of the run, above it.
//!
//! Invariants: the work is O(region faces) per cost. The forward term
//! measures each region vertex once (not once per face that holds it)
//! and adds the same terms in the same order, so the codes are bit for
//! bit those of the per-corner sum (issue 22); the backward term starts
//! each point's search at the face nearest to it at the previous cost
//! and skips the faces whose bounding ball is farther than the best so
//! far, which finds the same minimum (`Region::nearest_face`).

use super::marks::{grow_zeroed, Marks};
use super::surface::Surface;
use crate::metrics::{distance2, triangle_distance2_f64};
use glam::DVec3;

/// Where the triangle is sampled for its distance to M, as barycentric
/// weights of (tip, GL, GR).
const FIT_POINTS: [[f64; 3]; 7] = [
    [1.0, 0.0, 0.0],
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.5],
    [0.5, 0.0, 0.5],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];

/// The region of a fit: its faces' corners, and each corner as one of
/// the region's distinct vertices, so that the forward term measures
/// each vertex once however many region faces hold it (about six).
#[derive(Default)]
pub(super) struct Region {
    /// Per face, its three corners.
    faces: Vec<[[f64; 3]; 3]>,
    /// Per face, its corners as indices into `points`.
    index: Vec<[u32; 3]>,
    /// The distinct vertices of the region.
    points: Vec<[f64; 3]>,
    /// The surface vertices already in `points`...
    seen: Marks,
    /// ... and, per surface vertex in `seen`, its index there.
    slot: Vec<u32>,
    /// Scratch of the forward term: d(p, T)² per point.
    dist: Vec<f64>,
    /// Per face, a ball holding it: its centroid and the distance to its
    /// farthest corner.
    balls: Vec<([f64; 3], f64)>,
    /// Per sample point of T, the face nearest to it at the last cost:
    /// where the backward term starts its search.
    nearest: [usize; FIT_POINTS.len()],
}

impl Region {
    /// Takes the faces `faces` of `s`.
    pub(super) fn fill(&mut self, s: &Surface, faces: &[u32]) {
        self.faces.clear();
        self.index.clear();
        self.points.clear();
        self.balls.clear();
        self.nearest = [0; FIT_POINTS.len()];
        self.seen.clear(s.vertex_count());
        grow_zeroed(&mut self.slot, s.vertex_count());
        for &f in faces {
            let corners = Surface::corners(f);
            let face = corners.map(|c| s.p(c).to_array());
            let centre = [0, 1, 2].map(|a| (face[0][a] + face[1][a] + face[2][a]) / 3.0);
            let radius = face
                .iter()
                .map(|p| distance2(*p, centre))
                .fold(0.0, f64::max)
                .sqrt();
            self.balls.push((centre, radius));
            self.faces.push(face);
            let index = corners.map(|c| {
                let v = s.v[c as usize];
                if !self.seen.insert(v) {
                    return self.slot[v as usize];
                }
                let i = self.points.len() as u32;
                self.points.push(s.p(c).to_array());
                self.slot[v as usize] = i;
                i
            });
            self.index.push(index);
        }
    }

    /// The cost of `fit`'s module header for triangle `t` = (tip, GL, GR).
    /// The forward sum adds the same terms in the same order (face by
    /// face, corner by corner) as one distance per face corner would, so
    /// the result is bit for bit the same.
    pub(super) fn two_sided(&mut self, t: [DVec3; 3]) -> f64 {
        let tri = t.map(|v| v.to_array());
        self.dist.clear();
        self.dist
            .extend(self.points.iter().map(|&p| triangle_distance2_f64(p, &tri)));
        let mut forward = 0.0;
        for face in &self.index {
            for &i in face {
                forward += self.dist[i as usize];
            }
        }
        let mut backward = 0.0;
        for (j, w) in FIT_POINTS.iter().enumerate() {
            let x = (t[0] * w[0] + t[1] * w[1] + t[2] * w[2]).to_array();
            backward += self.nearest_face(j, x);
        }
        forward / (3 * self.faces.len()) as f64 + backward / FIT_POINTS.len() as f64
    }
}

impl Region {
    /// min over the region's faces of d(x, face)², for sample point `j`:
    /// the same value as trying every face, found by starting from the
    /// face nearest at the last cost (T moves by one code between costs)
    /// and skipping every face whose ball is farther than that. A ball of
    /// radius r at distance D bounds the face's distance from below by
    /// D − r; a face is skipped only when that bound, less a relative
    /// margin far above rounding, is still above the best so far, so it
    /// could not have been strictly nearer and the minimum is the
    /// exhaustive one bit for bit.
    fn nearest_face(&mut self, j: usize, x: [f64; 3]) -> f64 {
        let start = self.nearest[j].min(self.faces.len() - 1);
        let mut best = triangle_distance2_f64(x, &self.faces[start]);
        let mut arg = start;
        let mut reach = best.sqrt();
        for (i, (face, &(centre, radius))) in self.faces.iter().zip(&self.balls).enumerate() {
            if i == start {
                continue;
            }
            let bound = radius + reach;
            if distance2(x, centre) * (1.0 - SKIP_MARGIN) > bound * bound {
                continue;
            }
            let d = triangle_distance2_f64(x, face);
            if d < best {
                (best, arg) = (d, i);
                reach = best.sqrt();
            }
        }
        self.nearest[j] = arg;
        best
    }
}

/// Relative margin of the backward term's skip test (see
/// [`Region::nearest_face`]): rounding moves the squared distances by a
/// few units in 10^16.
const SKIP_MARGIN: f64 = 1e-9;
