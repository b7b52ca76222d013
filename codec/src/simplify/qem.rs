//! Greedy quadric edge collapse with optimal vertex placement, recorded
//! once and replayed to any face count.
//!
//! Source: Garland & Heckbert, "Surface simplification using quadric
//! error metrics" (SIGGRAPH 1997): every vertex carries the sum of the
//! area-weighted squared-distance quadrics of the input planes around it;
//! the edge whose merged quadric has the smallest minimum is collapsed
//! first, to the point of that minimum. Rules beyond the paper (each
//! measured or needed for a manifold result):
//! - the minimum is regularised toward the edge's midpoint
//!   (`(A + eps I) v = -b + eps m`, `eps` = [`REGULARISE`] x trace A):
//!   on a plane or a crease, where `A` is singular, the collapse lands on
//!   the plane or crease line nearest the midpoint instead of anywhere;
//!   a minimum further than the edge's length from the midpoint is
//!   distrusted and the best of the two ends and the midpoint taken;
//! - ties (flat regions, where every collapse costs nothing) go to the
//!   shorter edge ([`SHORT_EDGE`]), which keeps flat parts from
//!   collapsing into slivers;
//! - a boundary edge adds the quadric of the plane through it
//!   perpendicular to its face, weighted [`BOUNDARY_WEIGHT`] x its
//!   length squared, so holes keep their outline;
//! - a collapse is refused when it would make the mesh non-manifold (the
//!   link condition, except that a hole of three edges may close; an
//!   interior edge between two boundary vertices), turn
//!   a triangle over or to zero area, leave a vertex of valence below
//!   three (two on a boundary), or give a vertex more than [`MAX_VALENCE`]
//!   neighbours (or than its ends had, when one had more). A refused edge is tried again when a collapse next
//!   changes the neighbourhood of one of its ends.
//!
//! Why not meshoptimizer (the simplifier before issue 20's CAD work):
//! `meshopt_simplifyWithUpdate` chooses its collapses with the vertices
//! at their old positions and moves them afterwards; on fandisk it kept
//! about twice the L2 of a greedy collapse placed at the quadric's
//! minimum (BENCHMARKS, "Quadric collapse").
//!
//! Invariants: the input is an oriented manifold (what `clean` returns)
//! and stays one after every collapse; the collapse order depends only on
//! the mesh (the heap orders ties by vertex index), so the sequence and
//! every replay are deterministic. [`Collapses::replay`] to `k` collapses
//! gives exactly the mesh the greedy loop held after its `k`-th collapse:
//! a face dies only when it holds both ends of a collapsed edge, and every
//! other face follows its vertices through the recorded merges.

use super::heap::Heap;
use crate::TriMesh;
use alloc::vec;
use alloc::vec::Vec;

/// Pull of the midpoint on the quadric's minimum, relative to the
/// quadric's trace: small enough to leave any real constraint alone,
/// large enough to pin the directions a plane or a crease leaves free.
const REGULARISE: f64 = 1e-6;
/// Weight of an edge's squared length in its cost, relative to the
/// quadric's trace: decides only between collapses that cost (almost)
/// nothing.
const SHORT_EDGE: f64 = 1e-6;
/// Weight of a boundary edge's perpendicular plane, per squared length
/// (a face's own plane weighs its area, about 0.43 of its edge squared).
const BOUNDARY_WEIGHT: f64 = 10.0;
/// Most neighbours a vertex may get from a collapse: bounds the work of
/// each validity check, and fans that wide are no good to the coder.
const MAX_VALENCE: usize = 48;

/// `v^T A v + 2 b.v + c`, `A` symmetric (xx, xy, xz, yy, yz, zz).
#[derive(Clone, Copy, Default, Debug)]
struct Quadric {
    a: [f64; 6],
    b: [f64; 3],
    c: f64,
}

impl Quadric {
    /// Squared distance to the plane `n.v + d = 0` (`n` unit), times `w`.
    fn plane(n: [f64; 3], d: f64, w: f64) -> Quadric {
        let [x, y, z] = n;
        Quadric {
            a: [
                w * x * x,
                w * x * y,
                w * x * z,
                w * y * y,
                w * y * z,
                w * z * z,
            ],
            b: [w * d * x, w * d * y, w * d * z],
            c: w * d * d,
        }
    }

    fn add(&mut self, o: &Quadric) {
        for i in 0..6 {
            self.a[i] += o.a[i];
        }
        for i in 0..3 {
            self.b[i] += o.b[i];
        }
        self.c += o.c;
    }

    fn eval(&self, p: [f64; 3]) -> f64 {
        let [xx, xy, xz, yy, yz, zz] = self.a;
        let [x, y, z] = p;
        xx * x * x
            + yy * y * y
            + zz * z * z
            + 2.0 * (xy * x * y + xz * x * z + yz * y * z)
            + 2.0 * (self.b[0] * x + self.b[1] * y + self.b[2] * z)
            + self.c
    }

    fn trace(&self) -> f64 {
        self.a[0] + self.a[3] + self.a[5]
    }

    /// The minimum of `eval(v) + eps |v - m|^2`, by Cramer's rule; `None`
    /// when the system is singular (no area, no pull).
    fn minimize(&self, m: [f64; 3], eps: f64) -> Option<[f64; 3]> {
        let [xx, xy, xz, yy, yz, zz] = self.a;
        let (xx, yy, zz) = (xx + eps, yy + eps, zz + eps);
        let r = [
            eps * m[0] - self.b[0],
            eps * m[1] - self.b[1],
            eps * m[2] - self.b[2],
        ];
        let det = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
        if !det.is_finite() || det.abs() <= 1e-300 {
            return None;
        }
        let x = (r[0] * (yy * zz - yz * yz) - xy * (r[1] * zz - yz * r[2])
            + xz * (r[1] * yz - yy * r[2]))
            / det;
        let y = (xx * (r[1] * zz - yz * r[2]) - r[0] * (xy * zz - yz * xz)
            + xz * (xy * r[2] - r[1] * xz))
            / det;
        let z = (xx * (yy * r[2] - r[1] * yz) - xy * (xy * r[2] - r[1] * xz)
            + r[0] * (xy * yz - yy * xz))
            / det;
        let v = [x, y, z];
        v.iter().all(|c| c.is_finite()).then_some(v)
    }
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn normal(p: [[f64; 3]; 3]) -> [f64; 3] {
    cross(sub(p[1], p[0]), sub(p[2], p[0]))
}

/// One collapse: `gone` merged into `keep`, which moves to `pos`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Step {
    pub keep: u32,
    pub gone: u32,
    pub pos: [f32; 3],
    /// Faces left after this collapse.
    pub faces_after: u32,
}

/// The greedy collapse sequence of one mesh.
#[derive(Clone, Debug)]
pub struct Collapses {
    pub(super) faces: u32,
    pub(super) steps: Vec<Step>,
}

/// The normalised frame collapses are computed in: `(p − centre) ·
/// scale`, of unit diagonal for the whole mesh.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    centre: [f64; 3],
    scale: f64,
}

impl Frame {
    /// The frame of unit diagonal around `mesh`'s box centre.
    pub(super) fn of(mesh: &TriMesh) -> Frame {
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for p in &mesh.positions {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i] as f64);
                hi[i] = hi[i].max(p[i] as f64);
            }
        }
        if mesh.positions.is_empty() {
            return Frame {
                centre: [0.0; 3],
                scale: 1.0,
            };
        }
        let d = sub(hi, lo);
        let diag = dot(d, d).sqrt();
        let scale = if diag > 0.0 && diag.is_finite() {
            1.0 / diag
        } else {
            1.0
        };
        Frame {
            centre: [
                0.5 * (lo[0] + hi[0]),
                0.5 * (lo[1] + hi[1]),
                0.5 * (lo[2] + hi[2]),
            ],
            scale,
        }
    }
}

/// A heap entry: the edge (`a`, `b`) as it was when both ends had these
/// stamps; the cost is an `f64`'s bits (non-negative, so they order as
/// the numbers do). Two entries with the same cost and ends are either
/// the same entry twice or at most one of them is current (the stamps
/// differ), so any correct min-heap pops the current ones in the same
/// sequence.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Entry {
    cost: u64,
    a: u32,
    b: u32,
    sa: u32,
    sb: u32,
}

pub(super) struct State {
    pos: Vec<[f64; 3]>,
    quadric: Vec<Quadric>,
    tris: Vec<[u32; 3]>,
    /// Live faces around each vertex (empty once the vertex is gone).
    around: Vec<Vec<u32>>,
    boundary: Vec<bool>,
    alive: Vec<bool>,
    /// Bumped whenever a vertex's position or quadric changes.
    stamp: Vec<u32>,
    /// A collapse of one of its edges was refused since it last changed.
    retry: Vec<bool>,
    heap: Heap<Entry>,
    faces: u32,
    /// Maps the normalised frame back to the input's.
    centre: [f64; 3],
    scale: f64,
    /// Vertices never collapsed nor moved (empty: none).
    locked: Vec<bool>,
}

impl Collapses {
    /// Collapses `mesh` (an oriented manifold) greedily until `floor`
    /// faces are left or no collapse is allowed.
    pub fn run(mesh: &TriMesh, floor: u32) -> Collapses {
        let mut s = State::new(mesh, Frame::of(mesh), None);
        let mut steps = Vec::new();
        greedy(&mut s, floor, |step, _| steps.push(step));
        Collapses {
            faces: mesh.face_count() as u32,
            steps,
        }
    }

    /// The mesh after the fewest collapses that leave at most `target`
    /// faces (all of them, when the sequence stops above `target`), with
    /// the vertex indices of `mesh` (unused ones included).
    pub fn replay(&self, mesh: &TriMesh, target: u32) -> TriMesh {
        let k = if self.faces <= target {
            0
        } else {
            // `faces_after` falls along the sequence.
            let k = self.steps.partition_point(|s| s.faces_after > target);
            (k + 1).min(self.steps.len())
        };
        let mut parent: Vec<u32> = (0..mesh.vertex_count() as u32).collect();
        let mut positions = mesh.positions.clone();
        for s in &self.steps[..k] {
            parent[s.gone as usize] = s.keep;
            positions[s.keep as usize] = s.pos;
        }
        // Every merge points at a vertex still alive at that step, which
        // may merge later: follow the chain, halving it as we go.
        let mut find = |mut v: u32| {
            while parent[v as usize] != v {
                let up = parent[parent[v as usize] as usize];
                parent[v as usize] = up;
                v = up;
            }
            v
        };
        let mut triangles = Vec::with_capacity(mesh.face_count());
        for t in &mesh.triangles {
            let t = t.map(&mut find);
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                triangles.push(t);
            }
        }
        TriMesh::new(positions, triangles)
    }
}

/// Collapses greedily until `floor` faces are left or no collapse is
/// allowed, handing each collapse and its cost to `record` in order.
pub(super) fn greedy(s: &mut State, floor: u32, mut record: impl FnMut(Step, f64)) {
    let mut ring = Vec::new();
    let mut scratch = Vec::new();
    while s.faces > floor {
        let Some(e) = s.heap.pop() else {
            break;
        };
        if !s.current(&e) {
            continue;
        }
        let (a, b) = (e.a as usize, e.b as usize);
        let (_, v) = s.candidate(a, b);
        if !s.allowed(a, b, v, &mut ring, &mut scratch) {
            s.retry[a] = true;
            s.retry[b] = true;
            continue;
        }
        s.collapse(a, b, v, &mut ring);
        let step = Step {
            keep: a as u32,
            gone: b as u32,
            pos: s.output(v),
            faces_after: s.faces,
        };
        record(step, f64::from_bits(e.cost));
        // Stale entries past half the live edges (about 3/2 per
        // face): drop them. Stale is for good (vertices never come
        // back, stamps only grow), so the current entries, and the
        // order they pop in, stay as they were; the queue stays
        // short and most pops find a current entry (on bunny-1m 1.2
        // million pops instead of 5.6 million, 10 s to 5.4 s).
        if 2 * s.heap.len() > 3 * (3 * s.faces as usize / 2 + 64) {
            let mut heap = core::mem::replace(&mut s.heap, Heap::with_capacity(0));
            heap.retain(|e| s.current(e));
            s.heap = heap;
        }
    }
}

impl State {
    /// The state of `mesh` in `frame`; the vertices `locked` marks
    /// (when given) are never collapsed nor moved.
    pub(super) fn new(mesh: &TriMesh, frame: Frame, locked: Option<Vec<bool>>) -> State {
        let n = mesh.vertex_count();
        // A frame of unit diagonal around the box centre: costs compare
        // across meshes and the regularisation's scale is the mesh's.
        let Frame { centre, scale } = frame;
        let pos: Vec<[f64; 3]> = mesh
            .positions
            .iter()
            .map(|p| {
                let q = [p[0] as f64, p[1] as f64, p[2] as f64];
                let d = sub(q, centre);
                [d[0] * scale, d[1] * scale, d[2] * scale]
            })
            .collect();
        let mut quadric = vec![Quadric::default(); n];
        let mut around = vec![Vec::new(); n];
        for (f, t) in mesh.triangles.iter().enumerate() {
            let p = t.map(|v| pos[v as usize]);
            let nrm = normal(p);
            let len = dot(nrm, nrm).sqrt();
            if len > 0.0 {
                let u = [nrm[0] / len, nrm[1] / len, nrm[2] / len];
                let q = Quadric::plane(u, -dot(u, p[0]), 0.5 * len);
                for &v in t {
                    quadric[v as usize].add(&q);
                }
            }
            for &v in t {
                around[v as usize].push(f as u32);
            }
        }
        // Boundary edges: a directed edge whose reverse no face has.
        let mut directed: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * mesh.face_count());
        for (f, t) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                directed.push((t[i], t[(i + 1) % 3], f as u32));
            }
        }
        directed.sort_unstable();
        let mut boundary = vec![false; n];
        for &(u, v, f) in &directed {
            if directed
                .binary_search_by(|e| (e.0, e.1).cmp(&(v, u)))
                .is_ok()
            {
                continue;
            }
            boundary[u as usize] = true;
            boundary[v as usize] = true;
            let (pu, pv) = (pos[u as usize], pos[v as usize]);
            let t = mesh.triangles[f as usize];
            let nrm = normal(t.map(|w| pos[w as usize]));
            let e = sub(pv, pu);
            let m = cross(e, nrm);
            let len = dot(m, m).sqrt();
            if len > 0.0 {
                let m = [m[0] / len, m[1] / len, m[2] / len];
                let q = Quadric::plane(m, -dot(m, pu), BOUNDARY_WEIGHT * dot(e, e));
                quadric[u as usize].add(&q);
                quadric[v as usize].add(&q);
            }
        }
        let mut s = State {
            pos,
            quadric,
            tris: mesh.triangles.clone(),
            around,
            boundary,
            alive: vec![true; n],
            stamp: vec![0; n],
            retry: vec![false; n],
            heap: Heap::with_capacity(3 * mesh.face_count() / 2),
            faces: mesh.face_count() as u32,
            centre,
            scale,
            locked: locked.unwrap_or_default(),
        };
        let mut ring = Vec::new();
        for v in 0..n {
            s.ring(v, &mut ring);
            for &w in &ring {
                if w as usize > v {
                    s.push(v, w as usize);
                }
            }
        }
        s
    }

    fn output(&self, v: [f64; 3]) -> [f32; 3] {
        let inv = 1.0 / self.scale;
        [
            (v[0] * inv + self.centre[0]) as f32,
            (v[1] * inv + self.centre[1]) as f32,
            (v[2] * inv + self.centre[2]) as f32,
        ]
    }

    /// The distinct neighbours of `v`, in face order.
    fn ring(&self, v: usize, out: &mut Vec<u32>) {
        out.clear();
        for &f in &self.around[v] {
            for &w in &self.tris[f as usize] {
                if w as usize != v && !out.contains(&w) {
                    out.push(w);
                }
            }
        }
    }

    /// Cost and target position of collapsing edge (`a`, `b`).
    fn candidate(&self, a: usize, b: usize) -> (f64, [f64; 3]) {
        let mut q = self.quadric[a];
        q.add(&self.quadric[b]);
        let (pa, pb) = (self.pos[a], self.pos[b]);
        let m = [
            0.5 * (pa[0] + pb[0]),
            0.5 * (pa[1] + pb[1]),
            0.5 * (pa[2] + pb[2]),
        ];
        let e = sub(pa, pb);
        let e2 = dot(e, e);
        let tr = q.trace();
        let solved = q
            .minimize(m, REGULARISE * tr)
            .filter(|&v| dot(sub(v, m), sub(v, m)) <= e2);
        let v = solved.unwrap_or_else(|| {
            let mut best = (q.eval(pa), pa);
            for p in [pb, m] {
                let c = q.eval(p);
                if c < best.0 {
                    best = (c, p);
                }
            }
            best.1
        });
        let cost = q.eval(v).max(0.0) + SHORT_EDGE * tr * e2;
        (if cost.is_finite() { cost } else { f64::MAX }, v)
    }

    /// Whether `e` is the edge as it is now (both ends alive, neither
    /// changed since it was pushed).
    fn current(&self, e: &Entry) -> bool {
        let (a, b) = (e.a as usize, e.b as usize);
        self.alive[a] && self.alive[b] && self.stamp[a] == e.sa && self.stamp[b] == e.sb
    }

    fn push(&mut self, a: usize, b: usize) {
        if !self.locked.is_empty() && (self.locked[a] || self.locked[b]) {
            return;
        }
        let (cost, _) = self.candidate(a, b);
        self.heap.push(Entry {
            cost: cost.to_bits(),
            a: a as u32,
            b: b as u32,
            sa: self.stamp[a],
            sb: self.stamp[b],
        });
    }

    /// Whether collapsing `b` into `a` at `v` keeps the mesh a manifold
    /// without flipped, zero-area or over-connected faces.
    fn allowed(
        &self,
        a: usize,
        b: usize,
        v: [f64; 3],
        ring: &mut Vec<u32>,
        other: &mut Vec<u32>,
    ) -> bool {
        // The faces on the edge, and the vertices opposite it.
        let mut opposite = [u32::MAX; 2];
        let mut shared = 0;
        for &f in &self.around[a] {
            let t = self.tris[f as usize];
            if t.contains(&(b as u32)) {
                if shared == 2 {
                    return false;
                }
                opposite[shared] = t
                    .iter()
                    .copied()
                    .find(|&w| w != a as u32 && w != b as u32)
                    .unwrap_or(u32::MAX);
                shared += 1;
            }
        }
        if shared == 0 || (shared == 2 && self.boundary[a] && self.boundary[b]) {
            return false;
        }
        // Link condition: the ends share no neighbour but the opposite
        // ones, or the third corner of a hole of three edges that the
        // collapse closes (a, b and w all on it: w-a and w-b become one
        // interior edge). Without that exception a tube's open end stops
        // the collapses at three vertices per loop.
        self.ring(a, ring);
        self.ring(b, other);
        let (mut common, mut closing) = (0, 0);
        for &w in ring.iter() {
            if other.contains(&w) {
                if opposite[..shared].contains(&w) {
                    common += 1;
                } else if shared == 1
                    && self.boundary_edge(a, w as usize)
                    && self.boundary_edge(b, w as usize)
                {
                    closing += 1;
                } else {
                    return false;
                }
            }
        }
        // A hub above the cap (a rebuilt fan) may lose spokes, never gain.
        let cap = MAX_VALENCE.max(ring.len()).max(other.len());
        if common != shared || ring.len() + other.len() - common - closing - 2 > cap {
            return false;
        }
        // An opposite vertex loses a neighbour: keep it a proper fan.
        let mut fan = Vec::new();
        for &c in &opposite[..shared] {
            self.ring(c as usize, &mut fan);
            if fan.len() <= if self.boundary[c as usize] { 2 } else { 3 } {
                return false;
            }
        }
        // Every face that survives keeps its side and some area.
        for (end, other_end) in [(a, b), (b, a)] {
            for &f in &self.around[end] {
                let t = self.tris[f as usize];
                if t.contains(&(other_end as u32)) {
                    continue;
                }
                let old = t.map(|w| self.pos[w as usize]);
                let new = t.map(|w| {
                    if w as usize == end {
                        v
                    } else {
                        self.pos[w as usize]
                    }
                });
                let (n0, n1) = (normal(old), normal(new));
                let d = dot(n0, n1);
                if d.is_nan() || d <= 0.0 || dot(n1, n1) <= 1e-24 * dot(n0, n0) {
                    return false;
                }
            }
        }
        true
    }

    /// Whether edge (`u`, `w`) has one face.
    fn boundary_edge(&self, u: usize, w: usize) -> bool {
        let faces = self.around[u].iter();
        faces
            .filter(|&&f| self.tris[f as usize].contains(&(w as u32)))
            .count()
            == 1
    }

    /// Whether `v` has an edge with one face.
    fn on_boundary(&self, v: usize) -> bool {
        self.around[v].iter().any(|&f| {
            let t = self.tris[f as usize];
            t.iter()
                .any(|&w| w as usize != v && self.boundary_edge(v, w as usize))
        })
    }

    /// Merges `b` into `a` at `v`.
    fn collapse(&mut self, a: usize, b: usize, v: [f64; 3], ring: &mut Vec<u32>) {
        self.pos[a] = v;
        let qb = self.quadric[b];
        self.quadric[a].add(&qb);
        self.boundary[a] |= self.boundary[b];
        self.alive[b] = false;
        self.stamp[a] = self.stamp[a].wrapping_add(1);
        self.retry[a] = false;
        for f in core::mem::take(&mut self.around[b]) {
            let t = &mut self.tris[f as usize];
            if t.contains(&(a as u32)) {
                let t = *t;
                for &w in &t {
                    if w as usize != b {
                        self.around[w as usize].retain(|&g| g != f);
                    }
                }
                self.faces -= 1;
            } else {
                for w in t.iter_mut() {
                    if *w as usize == b {
                        *w = a as u32;
                    }
                }
                self.around[a].push(f);
            }
        }
        self.ring(a, ring);
        let neighbours = core::mem::take(ring);
        // A collapse that closed a hole of three edges leaves `a` and the
        // hole's third corner interior (or on another hole): look again.
        if self.boundary[a] {
            self.boundary[a] = self.on_boundary(a);
            for &w in &neighbours {
                if self.boundary[w as usize] {
                    self.boundary[w as usize] = self.on_boundary(w as usize);
                }
            }
        }
        for &w in &neighbours {
            let w = w as usize;
            self.push(a, w);
            if self.retry[w] {
                self.retry[w] = false;
                let mut second = Vec::new();
                self.ring(w, &mut second);
                for &x in &second {
                    self.push(w, x as usize);
                }
            }
        }
        *ring = neighbours;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::CornerId;

    #[test]
    fn regularised_minimum_of_one_plane_is_the_midpoint_projected() {
        let q = Quadric::plane([0.0, 0.0, 1.0], -1.0, 1.0);
        let v = q.minimize([0.3, -0.2, 5.0], 1e-6).unwrap();
        assert!((v[0] - 0.3).abs() < 1e-9 && (v[1] + 0.2).abs() < 1e-9);
        assert!((v[2] - 1.0).abs() < 1e-4);
    }

    #[test]
    fn every_replay_is_a_closed_manifold_near_the_sphere() {
        let m = crate::mesh::test_shapes::uv_sphere(24, 16);
        let c = Collapses::run(&m, 4);
        let last = c.steps.last().unwrap().faces_after;
        assert!(last <= 8, "stopped at {last}");
        for target in [m.face_count() as u32, 400, 100, 20, 4] {
            let r = c.replay(&m, target);
            let faces = r.face_count() as u32;
            assert!(faces <= target.max(last), "{faces} for {target}");
            // Each collapse removes at most two faces.
            assert!(faces + 1 >= target.max(last), "{faces} for {target}");
            let cleaned = crate::clean(&r, &Default::default()).unwrap();
            let report = &cleaned.report;
            assert_eq!(cleaned.mesh.face_count(), r.face_count(), "target {target}");
            assert_eq!(report.non_manifold_edges + report.non_manifold_vertices, 0);
            let t = &cleaned.table;
            assert!((0..t.corner_count()).all(|c| !t.is_boundary(CornerId(c as u32))));
            // Vertices stay near the unit sphere (the quadric's minimum
            // cuts corners, never far).
            if target >= 100 {
                for p in &cleaned.mesh.positions {
                    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                    assert!((0.9..1.1).contains(&r), "{r}");
                }
            }
        }
    }
}
