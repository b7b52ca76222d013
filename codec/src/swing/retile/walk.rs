//! Walking the intersection of a plane with M, one face at a time (thesis
//! §7.3: p2 on the sphere, p3/p4 and every tip on the circle, and the
//! approximate geodesics all follow a plane across the surface).
//!
//! Topology comes from vertex signs only: a vertex is on the positive side
//! when its signed distance is `>= 0`, so a zero counts as +0 and the
//! plane never passes *through* a vertex. Every face then has zero or two
//! crossed edges, and a walk entering a face through one crossed edge
//! leaves through the other: the sequence of faces is decided by signs,
//! never by comparing two computed crossing points. Crossing points are
//! only measured, to stop the walk.
//!
//! Walks move by adjacency only (no spatial index), so a self-intersecting
//! input cannot make them jump between sheets.

use super::surface::{face, next, prev, Surface};
use glam::DVec3;

/// An oriented plane: the points x with `(x − origin)·normal = 0`.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    pub origin: DVec3,
    pub normal: DVec3,
}

impl Plane {
    #[inline]
    pub fn positive(&self, p: DVec3) -> bool {
        (p - self.origin).dot(self.normal) >= 0.0
    }

    /// Where the edge facing corner `c` crosses the plane, as the
    /// parameter from v(next c) to v(prev c) and the point.
    pub fn crossing(&self, s: &Surface, c: u32) -> (f64, DVec3) {
        let (y, z) = (s.p(next(c)), s.p(prev(c)));
        let dy = (y - self.origin).dot(self.normal);
        let dz = (z - self.origin).dot(self.normal);
        let t = if dy == dz {
            0.5
        } else {
            (dy / (dy - dz)).clamp(0.0, 1.0)
        };
        (t, y + (z - y) * t)
    }

    /// The edge facing `c` has one endpoint on each side.
    #[inline]
    pub fn crosses(&self, s: &Surface, c: u32) -> bool {
        self.positive(s.p(next(c))) != self.positive(s.p(prev(c)))
    }
}

/// One crossed edge of a walk.
#[derive(Clone, Copy, Debug)]
pub struct Step {
    /// Corner facing the crossed edge, in the face being left.
    pub corner: u32,
    /// The crossing point.
    pub point: DVec3,
}

/// The other crossed edge of the face of `entry` (a corner facing the
/// edge the walk came in through).
pub fn exit(s: &Surface, plane: &Plane, entry: u32) -> Option<u32> {
    let f = face(entry);
    Surface::corners(f)
        .into_iter()
        .find(|&k| k != entry && plane.crosses(s, k))
}

/// The faces at vertex `a` from which a walk along `plane` can leave `a`:
/// for each, the corner at `a` (the crossed edge faces it) and the
/// crossing point. A walk from `a` enters such a face at `a` itself.
pub fn leave_vertex(s: &Surface, plane: &Plane, a: u32) -> Vec<(u32, DVec3)> {
    s.fan(a)
        .filter(|&k| plane.crosses(s, k))
        .map(|k| (k, plane.crossing(s, k).1))
        .collect()
}

/// A walk state: the corner facing the edge just crossed, seen from the
/// face about to be entered (`None` before the first step).
pub struct Walker<'a> {
    pub s: &'a Surface,
    pub plane: Plane,
    /// Corner, in the current face, facing the edge we entered by.
    pub entry: u32,
    /// Faces still allowed (a closed walk ends instead of looping).
    pub budget: usize,
}

impl<'a> Walker<'a> {
    /// Starts in the face across the edge facing `c`, having crossed it.
    pub fn across(s: &'a Surface, plane: Plane, c: u32, budget: usize) -> Walker<'a> {
        Walker {
            s,
            plane,
            entry: s.opp[c as usize],
            budget,
        }
    }

    /// The current face.
    pub fn face(&self) -> u32 {
        face(self.entry)
    }

    /// Leaves the current face; returns the crossed edge, and moves into
    /// the face beyond it. `None` when the budget is spent or the plane
    /// does not cross the face twice (only possible at the start).
    pub fn step(&mut self) -> Option<Step> {
        if self.budget == 0 {
            return None;
        }
        self.budget -= 1;
        self.s.tick(1);
        let out = exit(self.s, &self.plane, self.entry)?;
        let (_, point) = self.plane.crossing(self.s, out);
        self.entry = self.s.opp[out as usize];
        Some(Step { corner: out, point })
    }
}

/// Walks from `start` (a point of the current face of `w`) until the
/// polyline first leaves the ball of `radius` around `centre`, having been
/// inside it (a start outside — a path far from its chord — first walks
/// in). Returns the point and the face holding it.
pub fn walk_to_radius(
    w: &mut Walker<'_>,
    start: DVec3,
    centre: DVec3,
    radius: f64,
    max_length: f64,
) -> Option<(DVec3, u32)> {
    let r2 = radius * radius;
    let mut from = start;
    let mut inside = from.distance_squared(centre) < r2;
    let mut length = 0.0;
    loop {
        let f = w.face();
        let step = w.step()?;
        let to = step.point;
        let out = to.distance_squared(centre) >= r2;
        if inside && out {
            return Some((segment_sphere(from, to, centre, r2), f));
        }
        inside |= !out;
        length += from.distance(to);
        if length > max_length {
            return None;
        }
        from = to;
    }
}

/// The point of segment `a..b` at squared distance `r2` from `c`, given
/// `a` inside and `b` outside (the larger root of the quadratic).
fn segment_sphere(a: DVec3, b: DVec3, c: DVec3, r2: f64) -> DVec3 {
    let d = b - a;
    let m = a - c;
    let qa = d.length_squared();
    if qa == 0.0 {
        return b;
    }
    let qb = m.dot(d);
    let qc = m.length_squared() - r2;
    let disc = (qb * qb - qa * qc).max(0.0);
    let s = ((-qb + disc.sqrt()) / qa).clamp(0.0, 1.0);
    a + d * s
}
