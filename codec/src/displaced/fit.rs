//! The encoder's choice of each new vertex's offset along its predicted
//! normal: where the normal line meets the input nearest the predicted
//! point, within a reach; where it misses, a defined fallback.
//!
//! Source: normal meshes (Guskov, Vidimče, Sweldens & Schröder, 2000),
//! whose "piercing" step moves each new vertex along its normal to the
//! original surface, and the oracle (the nearest crossing within
//! two mean edges; 0.5-11% of bunny's new vertices missed, near its
//! holes). Beyond them: a far crossing whose line starts on the input is
//! another sheet's, and falls back as a miss (`on_another_sheet`).
//!
//! Invariants: each offset depends only on its frame and the input, so
//! the offsets of a level are computed in parallel and are the same at
//! any thread count (the nearest-point fallback uses a fresh search
//! state for every query, so no earlier query steers its ties).

use super::predict::Frame;
use crate::metrics::{NearestScratch, Surface};
use rayon::prelude::*;

/// What an offset is when the normal line misses the input within reach.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fallback {
    /// The input's nearest point, projected on the normal.
    Nearest,
    /// No offset: the vertex stays at its prediction. Measured no
    /// better (BENCHMARKS.md); kept for the ablation test.
    #[cfg_attr(not(test), allow(dead_code))]
    Zero,
}

/// The input, ready for both queries: one tree answers the line
/// crossings and the nearest points (`metrics::bvh::crossing`).
pub(crate) struct Target<'a> {
    pub surface: &'a Surface,
}

/// The offset along its normal of each frame's vertex, in the mesh's
/// units; `reach` bounds a crossing's distance; `misses` counts the
/// frames that fell back.
pub(crate) fn offsets(
    frames: &[Frame],
    target: &Target<'_>,
    reach: f64,
    fallback: Fallback,
    facing: bool,
) -> (Vec<f64>, usize) {
    let found: Vec<(f64, bool)> = frames
        .par_iter()
        .with_min_len(1024)
        .map_init(Vec::new, |stack, f| {
            if f.normal == [0.0; 3] {
                return (0.0, false);
            }
            match target
                .surface
                .nearest_crossing(f.point, f.normal, reach, facing, stack)
            {
                Some(t) if t.abs() > FAR * reach => {
                    let near = nearest(f, target);
                    match near.is_some_and(|q| on_another_sheet(f, t, q)) {
                        true => (fallen_back(f, fallback, || near), true),
                        false => (t, false),
                    }
                }
                Some(t) => (t, false),
                None => (fallen_back(f, fallback, || nearest(f, target)), true),
            }
        })
        .collect();
    let misses = found.iter().filter(|x| x.1).count();
    (found.into_iter().map(|x| x.0).collect(), misses)
}

/// A crossing further than this share of the reach (a quarter of the
/// level's mean edge) is checked against the input's nearest point.
const FAR: f64 = 0.125;
/// A far crossing whose line starts within this share of its distance
/// from the input (`on_another_sheet`) is taken for another sheet's.
const SHEET: f64 = 0.1;

/// Whether the crossing at `t` belongs to another sheet than the one the
/// predicted point lies on: the input's nearest point `q` is within
/// `SHEET · |t|` of the point, yet the line meets the input only `t`
/// away. Where the line slips past an open boundary (a rim, a spout's
/// mouth) or a region whose faces point the other way, it meets a sheet
/// of another part; the teapot's lid and body made Hausdorff 170 (1e-4
/// of the diagonal) of it at 8 b/v, and L2 31 instead of 13 at 2 b/v
/// (BENCHMARKS.md, "Another sheet"). The miss's fallback serves such a
/// vertex instead, from the same nearest point: one query, only for far
/// crossings.
fn on_another_sheet(f: &Frame, t: f64, q: [f64; 3]) -> bool {
    let d2: f64 = (0..3)
        .map(|k| (q[k] - f.point[k]) * (q[k] - f.point[k]))
        .sum();
    d2 < (SHEET * t) * (SHEET * t)
}

/// The input's point nearest the frame's (a fresh search state, so no
/// earlier query steers its ties).
fn nearest(f: &Frame, target: &Target<'_>) -> Option<[f64; 3]> {
    let mut scratch = NearestScratch::default();
    let (_, q, _) = target.surface.nearest_point(f.point, None, &mut scratch)?;
    Some(q)
}

/// A missed vertex's offset by `fallback`; `near` gives the input's
/// nearest point, asked only by the fallback that needs it.
fn fallen_back(f: &Frame, fallback: Fallback, near: impl FnOnce() -> Option<[f64; 3]>) -> f64 {
    match fallback {
        Fallback::Zero => 0.0,
        Fallback::Nearest => match near() {
            Some(q) => (0..3).map(|k| (q[k] - f.point[k]) * f.normal[k]).sum(),
            None => 0.0,
        },
    }
}

/// The scalar nearest `offset / step`, within the format's range.
pub(crate) fn quantize(offset: f64, step: f32) -> i32 {
    let max = f64::from(super::scalars::MAX_SCALAR);
    let q = (offset / f64::from(step)).round();
    if q.is_finite() {
        q.clamp(-max, max) as i32
    } else {
        0
    }
}
