//! Approximate geodesic paths between two vertices of M, and their
//! insertion into M as chains of edges (thesis §7.3, "Computation of
//! geodesic paths"; design notes §6 step 7).
//!
//! 1. Plane walk: the plane through A and B parallel to n_A + n_B, walked
//!    from A in the direction of B, until a face holds B. It fails on an
//!    owned face, a path edge, a vertex already on a path, or a walk
//!    longer than 4|AB|.
//! 2. Shortening: up to ten sweeps (fewer once the points settle); each
//!    interior point slides along its edge
//!    to the minimum of |P_{i−1}X| + |XP_{i+1}| (unfold the two faces of
//!    the edge into one plane, intersect, clamp).
//! 3. Fallback when the walk fails: Dijkstra over the free faces of M,
//!    crossing edges at their midpoints, then shortening (the Thesis's
//!    exact method is replaced by this, as the design notes allow).
//!
//! Invariant of a path handed to `insert`: consecutive points share a
//! face of M; interior points are free (no sample, no path edge at them);
//! no edge is crossed twice (a plane meets a segment once).

use super::marks::{grow_zeroed, Marks};
use super::surface::{face, next, prev, Surface, NONE};
use super::walk::{leave_vertex, Plane, Walker};
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// One point of a path on M.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Point {
    /// A vertex of M.
    Vertex(u32),
    /// A point inside the edge between two vertices, at `a + t(b − a)`.
    Edge { a: u32, b: u32, t: f64 },
}

/// Sweeps of the shortening step (thesis: "a finite number (10)").
const SWEEPS: usize = 10;
/// A sweep that moves no point by more than this share of its edge ends
/// the shortening.
const SETTLED: f64 = 1e-3;
/// Points closer than this share of the edge to an end snap to it.
const END_SNAP: f64 = 1e-6;

/// Finds a path from vertex `a` to vertex `b` through unowned faces.
pub fn find(s: &Surface, a: u32, b: u32, scratch: &mut Scratch) -> Option<Vec<Point>> {
    if a == b {
        return None;
    }
    if let Some(mut pts) = plane_walk(s, a, b) {
        shorten(s, &mut pts);
        return Some(pts);
    }
    dijkstra(s, a, b, scratch)
}

fn point_pos(s: &Surface, p: Point) -> DVec3 {
    match p {
        Point::Vertex(v) => s.pos[v as usize],
        Point::Edge { a, b, t } => {
            let (pa, pb) = (s.pos[a as usize], s.pos[b as usize]);
            pa + (pb - pa) * t
        }
    }
}

fn free(s: &Surface, v: u32) -> bool {
    s.sample[v as usize] == NONE && s.on_path[v as usize] == 0
}

fn plane_walk(s: &Surface, a: u32, b: u32) -> Option<Vec<Point>> {
    let (pa, pb) = (s.pos[a as usize], s.pos[b as usize]);
    let ab = pb - pa;
    let normal = ab.cross(s.vertex_normal(a) + s.vertex_normal(b));
    if normal.length_squared() <= 1e-24 * ab.length_squared() * ab.length_squared() {
        return None;
    }
    let plane = Plane { origin: pa, normal };
    // Leave `a` through the unowned face whose crossing advances most
    // towards `b`; a face already holding `b` ends the path at once.
    for k in s.fan(a) {
        if s.owner[face(k) as usize] == NONE
            && (s.v[next(k) as usize] == b || s.v[prev(k) as usize] == b)
            && !s.path[if s.v[next(k) as usize] == b {
                prev(k)
            } else {
                next(k)
            } as usize]
        {
            return Some(vec![Point::Vertex(a), Point::Vertex(b)]);
        }
    }
    let (k, _) = leave_vertex(s, &plane, a)
        .into_iter()
        .filter(|&(k, x)| s.owner[face(k) as usize] == NONE && (x - pa).dot(ab) > 0.0)
        .max_by(|p, q| (p.1 - pa).dot(ab).total_cmp(&(q.1 - pa).dot(ab)))?;
    let limit = 4.0 * ab.length();
    let mut pts = vec![Point::Vertex(a)];
    let mut walker = Walker::across(s, plane, k, s.face_count());
    let mut from = pa;
    let mut length = 0.0;
    let mut crossed = k;
    loop {
        // `crossed` faces the edge just left; record the crossing.
        if s.path[crossed as usize] {
            return None;
        }
        let (t, x) = plane.crossing(s, crossed);
        let (ea, eb) = (s.v[next(crossed) as usize], s.v[prev(crossed) as usize]);
        pts.push(Point::Edge { a: ea, b: eb, t });
        length += from.distance(x);
        from = x;
        if length > limit {
            return None;
        }
        let f = walker.face();
        if s.owner[f as usize] != NONE {
            return None;
        }
        if Surface::corners(f).iter().any(|&c| s.v[c as usize] == b) {
            pts.push(Point::Vertex(b));
            return Some(pts);
        }
        crossed = walker.step()?.corner;
    }
}

/// The minimiser along edge (a, b) of |p − x| + |x − q|, p and q lying in
/// the two faces at the edge: unfold q's face into p's plane.
fn best_t(pa: DVec3, pb: DVec3, p: DVec3, q: DVec3) -> f64 {
    let d = pb - pa;
    let len = d.length();
    if len == 0.0 {
        return 0.5;
    }
    let e = d / len;
    let (px, qx) = ((p - pa).dot(e), (q - pa).dot(e));
    let py = (p - pa - e * px).length();
    let qy = (q - pa - e * qx).length();
    let x = if py + qy == 0.0 {
        0.5 * (px + qx)
    } else {
        px + (qx - px) * py / (py + qy)
    };
    (x / len).clamp(0.0, 1.0)
}

fn shorten(s: &Surface, pts: &mut [Point]) {
    for _ in 0..SWEEPS {
        // Stop early once a sweep moves no point by more than this share
        // of its edge: further sweeps would not change the path's faces.
        let mut moved = 0.0f64;
        for i in 1..pts.len().saturating_sub(1) {
            if let Point::Edge { a, b, t: old } = pts[i] {
                let (pa, pb) = (s.pos[a as usize], s.pos[b as usize]);
                let p = point_pos(s, pts[i - 1]);
                let q = point_pos(s, pts[i + 1]);
                let t = best_t(pa, pb, p, q);
                // Ends stay off the edge's vertices unless those are free:
                // the path must not touch another path or a sample.
                let lo = if free(s, a) { 0.0 } else { END_SNAP };
                let hi = if free(s, b) { 1.0 } else { 1.0 - END_SNAP };
                let t = t.clamp(lo, hi);
                moved = moved.max((t - old).abs());
                pts[i] = Point::Edge { a, b, t };
            }
        }
        if moved < SETTLED {
            break;
        }
    }
}

/// Reusable Dijkstra buffers: `dist` and `from` hold for the vertices
/// in `seen`, so they need no clearing.
#[derive(Default)]
pub struct Scratch {
    seen: Marks,
    dist: Vec<f64>,
    from: Vec<u32>,
}

impl Scratch {
    pub fn begin(&mut self, n: usize) {
        // Read only where `seen` says they were written: zero is as good
        // a start as any, and costs no memory where never written.
        grow_zeroed(&mut self.dist, n);
        grow_zeroed(&mut self.from, n);
        self.seen.clear(n);
    }

    pub fn get(&self, v: u32) -> Option<f64> {
        self.seen.contains(v).then(|| self.dist[v as usize])
    }

    /// Records `d` for `v` if it improves; returns whether it did.
    pub fn relax(&mut self, v: u32, d: f64, from: u32) -> bool {
        let i = v as usize;
        if !self.seen.insert(v) && self.dist[i] <= d {
            return false;
        }
        self.dist[i] = d;
        self.from[i] = from;
        true
    }

    pub fn from(&self, v: u32) -> u32 {
        self.from[v as usize]
    }
}

/// A heap entry ordered by smallest distance first, ties by vertex id.
#[derive(PartialEq)]
pub struct Near(pub f64, pub u32);

impl Eq for Near {}

impl PartialOrd for Near {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Near {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// Dijkstra over the faces of M: from the free faces at `a` to a free
/// face at `b`, across edges that are not path edges, between face
/// centroids. The path crosses each chosen edge at its midpoint and is
/// then shortened; unlike a walk along edges it passes corridors one face
/// wide, whose vertices all lie on paths already.
fn dijkstra(s: &Surface, a: u32, b: u32, scratch: &mut Scratch) -> Option<Vec<Point>> {
    scratch.begin(s.face_count());
    let centroid = |f: u32| {
        let [c0, c1, c2] = Surface::corners(f);
        (s.p(c0) + s.p(c1) + s.p(c2)) / 3.0
    };
    let pa = s.pos[a as usize];
    let mut heap = BinaryHeap::new();
    for k in s.fan(a) {
        let f = face(k);
        if s.owner[f as usize] == NONE {
            let d = pa.distance(centroid(f));
            if scratch.relax(f, d, NONE) {
                heap.push(Near(d, f));
            }
        }
    }
    // A path much longer than the chord is of no use to a triangloid;
    // the bound also keeps a hopeless search from flooding all of M.
    let limit = 4.0 * pa.distance(s.pos[b as usize]);
    let mut end = None;
    while let Some(Near(d, f)) = heap.pop() {
        s.tick(1);
        if d > limit {
            break;
        }
        if scratch.get(f) != Some(d) {
            continue;
        }
        if Surface::corners(f).iter().any(|&c| s.v[c as usize] == b) {
            end = Some(f);
            break;
        }
        let here = centroid(f);
        for c in Surface::corners(f) {
            let g = face(s.opp[c as usize]);
            if s.path[c as usize] || s.owner[g as usize] != NONE {
                continue;
            }
            let nd = d + here.distance(centroid(g));
            if scratch.relax(g, nd, c) {
                heap.push(Near(nd, g));
            }
        }
    }
    let mut f = end?;
    // Walk back: `from` of a face is the corner, in the previous face,
    // facing the edge crossed into it.
    let mut pts = vec![Point::Vertex(b)];
    loop {
        let c = scratch.from(f);
        if c == NONE {
            break;
        }
        let (ea, eb) = (s.v[next(c) as usize], s.v[prev(c) as usize]);
        pts.push(Point::Edge {
            a: ea,
            b: eb,
            t: 0.5,
        });
        f = face(c);
    }
    pts.push(Point::Vertex(a));
    pts.reverse();
    shorten(s, &mut pts);
    Some(pts)
}

/// Inserts a path into M: splits the crossed edges and marks the chain of
/// edges from the first to the last point as path edges. Returns the
/// chain's vertices, or `None` if the points do not form a chain (the
/// caller treats that as a failed triangloid).
pub fn insert(s: &mut Surface, pts: &[Point]) -> Option<Vec<u32>> {
    let mut chain: Vec<u32> = Vec::with_capacity(pts.len());
    let ok = insert_into(s, pts, &mut chain);
    if !ok {
        unmark(s, &chain);
    }
    (ok && chain.len() >= 2).then_some(chain)
}

fn insert_into(s: &mut Surface, pts: &[Point], chain: &mut Vec<u32>) -> bool {
    // Membership in the chain, in O(1): a path across a finely split
    // region has thousands of points.
    let mut seen: std::collections::HashSet<u32> =
        std::collections::HashSet::with_capacity(pts.len());
    for (i, &p) in pts.iter().enumerate() {
        let last = i + 1 == pts.len();
        let v = match p {
            Point::Vertex(v) => v,
            Point::Edge { a, b, t } => {
                let Some(c) = s.edge(a, b) else {
                    return false;
                };
                if s.path[c as usize] {
                    return false;
                }
                // `edge` may name the edge from either side; measure t
                // from v(next c).
                let t = if s.v[next(c) as usize] == a {
                    t
                } else {
                    1.0 - t
                };
                let (y, z) = (s.v[next(c) as usize], s.v[prev(c) as usize]);
                if t <= END_SNAP && free(s, y) {
                    y
                } else if t >= 1.0 - END_SNAP && free(s, z) {
                    z
                } else {
                    s.split_edge(c, t.clamp(END_SNAP, 1.0 - END_SNAP))
                }
            }
        };
        if chain.last() == Some(&v) {
            continue;
        }
        if (i > 0 || last) && seen.contains(&v) {
            return false;
        }
        if let Some(&u) = chain.last() {
            let Some(c) = s.edge(u, v) else {
                return false;
            };
            if s.path[c as usize] {
                return false;
            }
            s.set_path(c);
        }
        seen.insert(v);
        chain.push(v);
    }
    true
}

/// Clears the path flags of a chain made by `insert` (its splits stay).
pub fn unmark(s: &mut Surface, chain: &[u32]) {
    for w in chain.windows(2) {
        if let Some(c) = s.edge(w[0], w[1]) {
            s.clear_path(c);
        }
    }
}
