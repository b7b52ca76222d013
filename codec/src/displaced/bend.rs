//! The encoder's choice of a level's bend (format-spec/07-displaced.md,
//! "Bend"): one factor a level that moves every new vertex's predicted
//! point along its normal by `−bend` times its *lift*, the normal part
//! of the stencil's step from the edge's midpoint (`predict::bent`).
//!
//! Why: Loop's stencil is approximating. On a convex patch it puts the
//! new vertex below the surface by a share of the curvature across the
//! edge, the same share its lift measures, so a level's scalars lean
//! against their lifts (on the shared corpus's files, 60-88% of nonzero
//! scalars have the sign opposite to their lift's). The interpolating
//! midpoint (bend 1) overshoots the other way, and the butterfly's
//! negative wing weights amplify a scan's noise (BENCHMARKS.md,
//! "Displaced subdivision (issue 46), first measurements"). A factor
//! fitted per level, by least squares of the offsets against the lifts,
//! is the linear predictor between them that the level's own data asks
//! for, sent as one byte: measured 0.4-0.55 on first levels, 0.2-0.3 on
//! second ones. The fit, half of it or none is kept, whichever codes the
//! level smallest ([`choose`]); `write` leaves the finest level of a
//! file of several unbent (the decoder's placement cost).
//!
//! Invariants: a code of 0 leaves every frame and offset as they were
//! (files before bends), and so does any code on an edge that is not
//! interior; an applied bend moves each frame with exactly
//! the decoder's operations (`predict::bent`), so encoder and decoder
//! place the same bits; each offset still names the same point on the
//! same normal line (only its origin moved), so no line query is made
//! again.

use super::predict::{self, Frame};
use super::subdivide::Edges;
use super::BEND_UNIT;
use crate::TriMesh;

/// Offsets further than this many steps from their prediction (a line
/// that crossed another sheet, or a fallback's nearest point) do not
/// vote: they are not the lean of a smooth patch.
const VOTE_STEPS: f64 = 16.0;

/// The midpoint of edge `e`'s ends when it is interior (the edges a
/// bend moves; the others predict their midpoint, a lift of 0).
fn mid(e: usize, edges: &Edges, mesh: &TriMesh) -> Option<[f64; 3]> {
    predict::interior_midpoint(e, edges, &mesh.triangles, &mesh.positions)
}

/// Each frame's lift from its edge's midpoint (0 where the edge is not
/// interior).
pub(crate) fn lifts(frames: &[Frame], edges: &Edges, mesh: &TriMesh) -> Vec<f64> {
    frames
        .iter()
        .enumerate()
        .map(|(e, f)| mid(e, edges, mesh).map_or(0.0, |m| predict::lift(f, m)))
        .collect()
}

/// The bend code (`code · BEND_UNIT`) that best predicts the offsets
/// `t` from their `lifts` (least squares over the voting edges), or 0.
fn least_squares(lifts: &[f64], t: &[f64], step: f32) -> i8 {
    let cap = VOTE_STEPS * f64::from(step);
    let (mut tl, mut ll) = (0.0f64, 0.0f64);
    for (&lift, &t) in lifts.iter().zip(t) {
        if t.abs() <= cap {
            tl += t * lift;
            ll += lift * lift;
        }
    }
    if ll.is_nan() || ll <= 0.0 {
        return 0;
    }
    let code = (-tl / ll / BEND_UNIT).round();
    if code.is_finite() {
        code.clamp(f64::from(i8::MIN), f64::from(i8::MAX)) as i8
    } else {
        0
    }
}

/// The level's code: of the least-squares fit, half of it and none, the
/// one whose scalars `bytes` codes smallest (ties to the smaller code:
/// the least decoding work). Least squares weighs the largest offsets
/// most, the coder the smallest: on a bumpy sphere with one level the
/// fit (2.0) cost 17% more bytes than none.
pub(crate) fn choose(lifts: &[f64], t: &[f64], step: f32, bytes: impl Fn(&[f64]) -> usize) -> i8 {
    let fitted = least_squares(lifts, t, step);
    let mut best = (bytes(t), 0i8);
    for code in [fitted / 2, fitted] {
        if code == 0 {
            continue;
        }
        let bend = f64::from(code) * BEND_UNIT;
        let moved: Vec<f64> = t.iter().zip(lifts).map(|(&t, &l)| t + bend * l).collect();
        let b = bytes(&moved);
        if b < best.0 {
            best = (b, code);
        }
    }
    best.1
}

/// `frames` bent by `code` and the offsets `t` from their moved points.
pub(crate) fn apply(
    mut frames: Vec<Frame>,
    edges: &Edges,
    mesh: &TriMesh,
    mut t: Vec<f64>,
    code: i8,
) -> (Vec<Frame>, Vec<f64>) {
    if code == 0 {
        return (frames, t);
    }
    let bend = f64::from(code) * BEND_UNIT;
    for (e, (f, t)) in frames.iter_mut().zip(&mut t).enumerate() {
        let Some(mid) = mid(e, edges, mesh) else {
            continue;
        };
        let moved = predict::bent(f, mid, bend);
        // The same point on the same line, from the moved origin.
        *t -= (0..3)
            .map(|k| (moved.point[k] - f.point[k]) * f.normal[k])
            .sum::<f64>();
        *f = moved;
    }
    (frames, t)
}
