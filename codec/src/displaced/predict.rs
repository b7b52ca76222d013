//! Where each new vertex of a subdivision level starts and which way its
//! scalar moves it: the prediction rule on the decoded coarser level and
//! the predicted normal (format-spec/07-displaced.md, "Prediction").
//!
//! Sources: Loop's edge rule (C. Loop, "Smooth subdivision surfaces based
//! on triangles", 1987: 3/8 of the edge's ends, 1/8 of the two opposite
//! vertices), and the interpolating butterfly (Dyn, Levin & Gregory, "A
//! butterfly subdivision scheme for surface interpolatory with tension
//! control", 1990, with w = 0: 1/2, 1/8 and −1/16 of the four wings).
//! Both are applied to new vertices only: old vertices keep their
//! decoded positions (the scheme is interpolating either way), as in
//! displaced subdivision surfaces and normal meshes, where the scalar
//! absorbs what the smoothing of old vertices would do.
//!
//! Fallbacks: an edge that is not interior and manifold (one corner, or
//! two of the same direction, or more) predicts its midpoint; the
//! butterfly predicts Loop's point when one of its four wings is missing
//! (a wing edge on a boundary or non-manifold).
//!
//! The normal is the sum of the cross products `(p1 − p0) × (p2 − p0)` of
//! the triangles around the edge, in corner order, divided by its length;
//! a zero (or non-finite) sum gives no normal, and the vertex stays at
//! its prediction whatever its scalar.
//!
//! Arithmetic (must match the encoder exactly; every operation is one
//! IEEE 754 binary64 operation, in the order written, never fused):
//! coordinates are read from `f32` to `f64`, and a new position is
//! rounded to `f32` once, at the end.
//!
//! The decoder frames and places a level's new vertices in one pass
//! ([`place_level`]): each frame is used as soon as it is made, so none is
//! stored (48 bytes an edge), and the new positions are written into the
//! level's grown position array. Interior edges and wings come from the
//! edges' precomputed mates ([`Edges::mate`]), one read each. Only the
//! order of memory accesses differs from [`frame`] then [`place`]; every
//! floating-point operation is the same, in the same order.

use super::subdivide::{corner_vertices, Edges};
use crate::prelude::*;

/// The prediction rule of a file (`HEAD`'s `rule` byte). Public as
/// `swm::Prediction`, in what `swm::inspect` says of a file
/// (`DisplacedInfo`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Rule {
    /// Loop's edge rule (byte 0).
    Loop,
    /// The 8-point butterfly (byte 1).
    Butterfly,
}

impl Rule {
    /// Its name in `swm info`'s report: `"loop"` or `"butterfly"`.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Loop => "loop",
            Rule::Butterfly => "butterfly",
        }
    }

    /// Its byte.
    #[cfg(feature = "encoder")]
    pub(crate) fn code(self) -> u8 {
        match self {
            Rule::Loop => 0,
            Rule::Butterfly => 1,
        }
    }

    /// The rule a byte names.
    pub(crate) fn from_code(b: u8) -> Option<Rule> {
        match b {
            0 => Some(Rule::Loop),
            1 => Some(Rule::Butterfly),
            _ => None,
        }
    }
}

/// A new vertex before its scalar: its predicted point and the unit
/// direction its scalar moves it along (all zero when there is none).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame {
    pub point: [f64; 3],
    pub normal: [f64; 3],
}

fn at(p: &[[f32; 3]], v: u32) -> [f64; 3] {
    p[v as usize].map(f64::from)
}

/// The frame of edge `e`'s new vertex under `stencil`: its rule's
/// point, moved by the level's bend when the edge is interior
/// ([`bent`]), and its normal.
/// `crosses` holds each triangle's [`cross`].
///
/// The order of its parts is the fastest measured (4% for the whole
/// decode over computing the normal whole, test and divisions, before
/// the stencil, or after it): the normal's reads and root, then the
/// stencil's reads, then the test and the divisions. Any order computes
/// the same values.
#[inline(always)]
pub(crate) fn frame(
    e: usize,
    edges: &Edges,
    tris: &[[u32; 3]],
    pos: &[[f32; 3]],
    crosses: &[[f64; 3]],
    stencil: Stencil,
) -> Frame {
    let sum = normal_sum(edges.corners(e), crosses);
    let len2 = length2(sum);
    let (point, mid) = point(e, edges, tris, pos, stencil.rule);
    let f = Frame {
        point,
        normal: unit(sum, len2, crate::math::sqrt(len2)),
    };
    match mid {
        Some(mid) if stencil.bend != 0.0 => bent(&f, mid, stencil.bend),
        _ => f,
    }
}

/// A level's prediction: the file's rule and the level's bend (0 for
/// none, see [`bent`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Stencil {
    pub rule: Rule,
    pub bend: f64,
}

impl Stencil {
    /// The rule alone, no bend.
    #[cfg(any(test, feature = "encoder"))]
    pub(crate) fn plain(rule: Rule) -> Stencil {
        Stencil { rule, bend: 0.0 }
    }
}

/// The midpoint of an edge's ends.
#[inline(always)]
fn midpoint(pa: [f64; 3], pb: [f64; 3]) -> [f64; 3] {
    core::array::from_fn(|k| 0.5 * (pa[k] + pb[k]))
}

/// The midpoint of edge `e`'s ends when the edge is interior (the edges
/// a bend moves), else `None`.
#[cfg(feature = "encoder")]
pub(crate) fn interior_midpoint(
    e: usize,
    edges: &Edges,
    tris: &[[u32; 3]],
    pos: &[[f32; 3]],
) -> Option<[f64; 3]> {
    let first = edges.first_corner(e);
    edges.mate(first)?;
    let [a, b, _] = corner_vertices(first, tris);
    Some(midpoint(at(pos, a), at(pos, b)))
}

/// How far along its normal the stencil moved a frame's point from its
/// edge's midpoint `mid`: `((n0·d0 + n1·d1) + n2·d2)` with `d = point −
/// mid`.
#[inline(always)]
pub(crate) fn lift(f: &Frame, mid: [f64; 3]) -> f64 {
    let d: [f64; 3] = core::array::from_fn(|k| f.point[k] - mid[k]);
    (f.normal[0] * d[0] + f.normal[1] * d[1]) + f.normal[2] * d[2]
}

/// A frame whose point is moved along its normal by `s = −bend · lift`:
/// `point + normal · s`, coordinate by coordinate. A smoothing stencil's
/// lift is a fixed share of the surface's curvature across the edge
/// (Loop's shrinks a convex surface), so the scalars of a level lean
/// against it; one factor a level, fitted by the encoder, takes that
/// lean out of them (format-spec/07-displaced.md, "Bend").
#[inline(always)]
pub(crate) fn bent(f: &Frame, mid: [f64; 3], bend: f64) -> Frame {
    let s = -bend * lift(f, mid);
    Frame {
        point: core::array::from_fn(|k| f.point[k] + f.normal[k] * s),
        normal: f.normal,
    }
}

/// The predicted point of edge `e`'s new vertex (the rule's stencil, or
/// a fallback), and the midpoint of its ends when it is interior.
#[inline(always)]
fn point(
    e: usize,
    edges: &Edges,
    tris: &[[u32; 3]],
    pos: &[[f32; 3]],
    rule: Rule,
) -> ([f64; 3], Option<[f64; 3]>) {
    let first = edges.first_corner(e);
    let [a, b, c] = corner_vertices(first, tris);
    let (pa, pb) = (at(pos, a), at(pos, b));
    match edges.mate(first) {
        None => (midpoint(pa, pb), None),
        Some(second) => {
            let d = corner_vertices(second, tris)[2];
            let (pc, pd) = (at(pos, c), at(pos, d));
            let wings = match rule {
                Rule::Loop => None,
                Rule::Butterfly => wings(edges, tris, first, second),
            };
            let p = match wings {
                Some(w) => {
                    let w = w.map(|v| at(pos, v));
                    core::array::from_fn(|k| {
                        0.5 * (pa[k] + pb[k]) + 0.125 * (pc[k] + pd[k])
                            - 0.0625 * (((w[0][k] + w[1][k]) + w[2][k]) + w[3][k])
                    })
                }
                None => core::array::from_fn(|k| 0.375 * (pa[k] + pb[k]) + 0.125 * (pc[k] + pd[k])),
            };
            (p, Some(midpoint(pa, pb)))
        }
    }
}

/// The frames of every edge of a level, in edge order (what
/// [`place_level`] places without storing them).
#[cfg(test)]
pub(crate) fn frames(edges: &Edges, tris: &[[u32; 3]], pos: &[[f32; 3]], rule: Rule) -> Vec<Frame> {
    let crosses: Vec<[f64; 3]> = tris.iter().map(|t| cross(t, pos)).collect();
    (0..edges.len())
        .map(|e| frame(e, edges, tris, pos, &crosses, Stencil::plain(rule)))
        .collect()
}

/// One level's new vertices, appended to `pos` (the level's `n`
/// positions) in edge order: each edge's [`frame`] moved by its scalar
/// `qs[e]` of `step` ([`place`]), made and placed in one pass so no
/// frame is stored (48 bytes an edge otherwise written and read back).
/// The same bits as [`frame`] then [`place`]. `None` when a coordinate
/// is not finite; `pos` then holds `n` positions and some of the level's.
///
/// (Measured and dropped: framing a batch of 64 edges in three tight
/// loops, points and normal sums, then roots, then divisions and
/// placement, so that the roots and divisions of different edges
/// overlap: 2% slower than one edge at a time; the loop waits on its
/// random reads of positions and crosses more than on the root.)
pub(crate) fn place_level(
    edges: &Edges,
    tris: &[[u32; 3]],
    pos: &mut Vec<[f32; 3]>,
    stencil: Stencil,
    step: f32,
    qs: &[i32],
) -> Option<()> {
    let n = pos.len();
    pos.resize(n + qs.len(), [0.0; 3]);
    let (old, new) = pos.split_at_mut(n);
    place_into(edges, tris, old, new.as_flattened_mut(), stencil, step, qs)
}

/// [`place_level`] into `new` (`x y z` per new vertex, three floats per
/// edge) from the level's positions `old`: the decoder's last level is
/// placed straight into the caller's buffer.
pub(crate) fn place_into(
    edges: &Edges,
    tris: &[[u32; 3]],
    old: &[[f32; 3]],
    new: &mut [f32],
    stencil: Stencil,
    step: f32,
    qs: &[i32],
) -> Option<()> {
    debug_assert_eq!(qs.len(), edges.len());
    debug_assert_eq!(new.len(), 3 * qs.len());
    let crosses: Vec<[f64; 3]> = tris.iter().map(|t| cross(t, old)).collect();
    for (e, (slot, &q)) in new.chunks_exact_mut(3).zip(qs).enumerate() {
        let f = frame(e, edges, tris, old, &crosses, stencil);
        slot.copy_from_slice(&place(&f, q, step)?);
    }
    Some(())
}

/// The butterfly's wings: across the two other edges of each triangle of
/// the edge, the vertex opposite; `None` when one is missing.
fn wings(edges: &Edges, tris: &[[u32; 3]], first: u32, second: u32) -> Option<[u32; 4]> {
    let next = |c: u32| c - c % 3 + (c % 3 + 1) % 3;
    let wing = |c: u32| Some(corner_vertices(edges.mate(c)?, tris)[2]);
    let (f1, f2) = (next(first), next(second));
    Some([wing(f1)?, wing(next(f1))?, wing(f2)?, wing(next(f2))?])
}

/// A triangle's `(p1 − p0) × (p2 − p0)`, in its stored corner order.
pub(crate) fn cross(t: &[u32; 3], pos: &[[f32; 3]]) -> [f64; 3] {
    let (p0, p1, p2) = (at(pos, t[0]), at(pos, t[1]), at(pos, t[2]));
    let u = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
    let v = [p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]];
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

/// The sum of the crosses of the triangles around an edge, in corner
/// order: its normal before normalization.
#[inline(always)]
fn normal_sum(corners: &[u32], crosses: &[[f64; 3]]) -> [f64; 3] {
    let mut n = [0f64; 3];
    for &c in corners {
        let x = crosses[(c / 3) as usize];
        n[0] += x[0];
        n[1] += x[1];
        n[2] += x[2];
    }
    n
}

/// The squared length of a normal sum.
#[inline(always)]
fn length2(n: [f64; 3]) -> f64 {
    n[0] * n[0] + n[1] * n[1] + n[2] * n[2]
}

/// The unit normal from a normal sum `n`, its [`length2`] and that
/// one's root `len`; zero when the square is zero or not finite.
#[inline(always)]
fn unit(n: [f64; 3], len2: f64, len: f64) -> [f64; 3] {
    if !(len2 > 0.0 && len2.is_finite()) {
        return [0.0; 3];
    }
    n.map(|x| x / len)
}

/// The new vertex at `q` steps of `step` along its frame's normal,
/// rounded to `f32` (`None` when a coordinate is not finite: a hostile
/// step or scalar).
#[inline]
pub(crate) fn place(f: &Frame, q: i32, step: f32) -> Option<[f32; 3]> {
    let s = f64::from(q) * f64::from(step);
    let p: [f32; 3] = core::array::from_fn(|k| (f.point[k] + f.normal[k] * s) as f32);
    p.iter().all(|c| c.is_finite()).then_some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A regular hexagonal fan around vertex 0, z = 0 except vertex 0.
    fn fan() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let mut p = vec![[0.0, 0.0, 1.0]];
        for k in 0..6 {
            let a = core::f32::consts::PI / 3.0 * k as f32;
            p.push([a.cos(), a.sin(), 0.0]);
        }
        let t = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        (p, t)
    }

    #[test]
    fn boundary_edges_predict_their_midpoint_and_spokes_loop() {
        let (p, t) = fan();
        let e = Edges::new(&t);
        // Edge 0 is {0, 1}: a spoke, interior.
        let f = frames(&e, &t, &p, Rule::Loop)[0];
        let (a, b) = ([0.0, 0.0, 1.0], p[1].map(f64::from));
        let (c, d) = (p[2].map(f64::from), p[6].map(f64::from));
        for k in 0..3 {
            let want = 0.375 * (a[k] + b[k]) + 0.125 * (c[k] + d[k]);
            assert_eq!(f.point[k], want);
        }
        // A rim edge is on the boundary: its midpoint.
        let rim = (0..e.len()).find(|&i| e.corners(i).len() == 1).unwrap();
        let f = frames(&e, &t, &p, Rule::Butterfly)[rim];
        assert_eq!(f.point[2], 0.0);
        let len: f64 = f.normal.iter().map(|x| x * x).sum();
        assert!((len - 1.0).abs() < 1e-12 && f.normal[2] > 0.0);
        // A spoke's butterfly has wings on the rim: missing, so Loop's.
        let g = frames(&e, &t, &p, Rule::Butterfly)[0];
        assert_eq!(g.point, frames(&e, &t, &p, Rule::Loop)[0].point);
    }

    #[test]
    fn a_hostile_step_places_nothing() {
        let f = Frame {
            point: [0.0; 3],
            normal: [1.0, 0.0, 0.0],
        };
        assert_eq!(place(&f, 3, 0.5), Some([1.5, 0.0, 0.0]));
        assert_eq!(place(&f, 1 << 20, f32::MAX), None);
    }
}
