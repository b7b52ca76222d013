//! Snapping the new vertices onto the restored sharp edges and corners
//! (thesis §8.3, "Snapping the new vertices onto sharp features";
//! ALGORITHMS.md §7, which corrects the thesis's chamfer formula).
//!
//! Each endpoint A of a chamfer edge lies on the border of a smooth (red)
//! region; the plane through A normal to N, the normalized angle-weighted
//! sum of the normals of A's red triangles, extends that region. A
//! chamfer-edge vertex goes to the point of the line where A's and B's
//! planes meet that is nearest the edge's midpoint; a corner vertex goes
//! to the point where the three planes of its triangle's corners meet.
//!
//! ## The chamfer-edge formula
//!
//! Planes P: (X − A)·N = 0 and Q: (X − B)·M = 0, with |N| = |M| = 1 and
//! O = (A + B)/2. The line P∩Q has direction N×M; the point of it nearest
//! O is O plus a vector orthogonal to N×M, i.e. in the span of N and M:
//! X = O + αN + βM. Let a = AB·N, b = AB·M, c = N·M. Since X − A =
//! AB/2 + αN + βM and X − B = −AB/2 + αN + βM, the plane conditions read
//!
//! ```text
//!     α + cβ = −a/2          (X on P)
//!     cα + β =  b/2          (X on Q)
//! ```
//!
//! whose solution is α = −(a + cb) / (2(1 − c²)), β = (b + ca) / (2(1 − c²)).
//! (The thesis prints O + (h/k)·AB×(M×N) with h = AB·N and
//! k = 2(M·N)(AB·N) − 2(AB·M); that point lies on neither plane. On the
//! notes' example A = (−1,0,0), B = (0,0,−1), N = (0,0,1), M = (1,0,0)
//! the formula above gives (0,0,0), the printed one (−1,0,−1).)
//!
//! ## When a vertex stays where it was inserted
//!
//! * `1 − c² <` the parallel tolerance: the planes (nearly) coincide and
//!   the line is undefined or far away;
//! * `|det[N; M; S]| <` the coplanar tolerance for a corner: the three
//!   planes meet in a line, or not at all;
//! * `a·b ≥ 0`: for a convex edge B lies below A's plane (a < 0) and A
//!   below B's (b > 0); for a concave one a > 0 > b. Equal signs mean one
//!   side is convex and the other concave: the thesis's mixed chamfer,
//!   where the planes' intersection is not the edge that was lost;
//! * an endpoint's normal sum vanishes;
//! * (in `split`) an edge would get longer than the longest input edge;
//! * (in `split`, not in the thesis) the vertex would move farther than
//!   `max_snap_ratio` times its chamfer edge (see the parent module).

use glam::DVec3;

/// Why a vertex is not snapped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Refusal {
    /// `1 − c² <` the parallel tolerance.
    Parallel,
    /// `|det[N; M; S]| <` the coplanar tolerance.
    Coplanar,
    /// Concave and convex mixed (`a·b ≥ 0`).
    Mixed,
    /// A normal is zero.
    NoNormal,
    /// A new edge would be too long (decided by the caller).
    TooLong,
    /// The vertex would move too far (decided by the caller).
    TooFar,
}

/// The point of the intersection line of the plane through `a` normal to
/// `n` and the plane through `b` normal to `m` nearest `(a + b)/2`.
/// `n` and `m` are unit vectors or zero.
pub(super) fn snap_edge(
    a: DVec3,
    b: DVec3,
    n: DVec3,
    m: DVec3,
    parallel_tolerance: f64,
) -> Result<DVec3, Refusal> {
    if n == DVec3::ZERO || m == DVec3::ZERO {
        return Err(Refusal::NoNormal);
    }
    let ab = b - a;
    let (pa, pb, c) = (ab.dot(n), ab.dot(m), n.dot(m));
    let d = 1.0 - c * c;
    if d < parallel_tolerance || d <= 0.0 {
        return Err(Refusal::Parallel);
    }
    if pa * pb >= 0.0 {
        return Err(Refusal::Mixed);
    }
    let alpha = -(pa + c * pb) / (2.0 * d);
    let beta = (pb + c * pa) / (2.0 * d);
    Ok(0.5 * (a + b) + alpha * n + beta * m)
}

/// The intersection of the planes through `p[k]` normal to `n[k]`
/// (unit vectors or zero): the solution of W·N = A·N, W·M = B·M,
/// W·S = C·S, by Cramer's rule relative to the triangle's centroid (so
/// that the right-hand sides are small and lose no digits to the
/// translation).
pub(super) fn snap_corner(
    p: [DVec3; 3],
    n: [DVec3; 3],
    coplanar_tolerance: f64,
) -> Result<DVec3, Refusal> {
    if n.contains(&DVec3::ZERO) {
        return Err(Refusal::NoNormal);
    }
    let det = n[0].dot(n[1].cross(n[2]));
    if det.abs() < coplanar_tolerance || det == 0.0 {
        return Err(Refusal::Coplanar);
    }
    // Each pair of corners must bound a consistently convex or concave
    // chamfer, as for an edge (module docs).
    for k in 0..3 {
        let (i, j) = (k, (k + 1) % 3);
        let ab = p[j] - p[i];
        if ab.dot(n[i]) * ab.dot(n[j]) >= 0.0 {
            return Err(Refusal::Mixed);
        }
    }
    let o = (p[0] + p[1] + p[2]) / 3.0;
    let d = [0, 1, 2].map(|k| (p[k] - o).dot(n[k]));
    let w = d[0] * n[1].cross(n[2]) + d[1] * n[2].cross(n[0]) + d[2] * n[0].cross(n[1]);
    Ok(o + w / det)
}
