//! Effort levels (`swm encode --effort`, [`Effort`]): each is the list of
//! methods the automatic mode's chooser runs, in the order that breaks
//! ties, and the work budget of each, as Draco's compression levels and
//! zstd's levels let a user trade time for size.
//!
//! | level     | methods (first wins a tie)                         | work                       |
//! |-----------|----------------------------------------------------|----------------------------|
//! | `fast`    | simplified, quick search                           | one collapse sequence, two size searches |
//! | `default` | SwingWrapper (within [`swing_budget`]), simplified's lean climb, displaced subdivision (within [`displaced_budget`]) | + a retiling of small outputs, displaced files of low rates or small sizes |
//! | `max`     | mixed, SwingWrapper, simplified, displaced subdivision: every search | unbounded by the level |
//!
//! Invariants: `max` runs every method `default` runs, each with at least
//! `default`'s search, so the chooser's answer at `max` is never a
//! method `default` measured closer (until 2026-12-07 `max` was the
//! automatic mode as it was before levels existed and left the displaced
//! method out: bunny at 1 b/v got L2 4.49 in 6.4 s at `max` against 4.12
//! in 0.4 s at `default`); every level's work grows
//! at most linearly with the input's triangles and the output's bytes
//! (the simplified method's collapse sequence is made once and its size
//! searches replay it; a retiling under the level's budget is bounded by
//! one and a half times it (`Swing::work_limit`), counted in
//! deterministic steps, so the bytes never depend on the machine; the
//! displaced method runs only for files of at most one byte per seven
//! input triangles, or 3 KB on small inputs, whose bar is a constant
//! floor). The budgets and the predicted work are
//! measured figures (BENCHMARKS.md, "Effort levels").

use super::displaced::Displaced;
use super::method::CodingMethod;
use super::mixed::Mixed;
use super::simplified::Simplified;
use super::swing::Swing;
use crate::options::Effort;

/// One entry of an effort level's list: a method and the work budget it
/// gets (`None`: the caller's limits alone).
#[derive(Clone, Copy)]
pub(crate) struct Entry {
    /// The method.
    pub method: &'static dyn CodingMethod,
    /// Its budget in the retiler's steps, when the level bounds it.
    pub work: Option<u64>,
}

/// Retiling steps the `default` level always allows SwingWrapper: about a
/// third of a second of retiling on the machines measured (7-8 M steps
/// per second), the half-second floor of the level's time bar less the
/// simplified method's share on a small mesh.
const SWING_STEPS_FLOOR: u64 = 2_500_000;
/// And per triangle of the cleaned input: the level's time bar is a
/// multiple of Draco's encode, which is linear in the input, and the
/// simplified method already takes most of it (about 10 µs per input
/// triangle of the 15 the bar allows).
const SWING_STEPS_PER_FACE: u64 = 20;
/// Input triangles per byte of file up to which the `default` level runs
/// the displaced method (its files then cost at most one byte per seven
/// input triangles: bunny and horse at up to 2 b/v). Its work grows with
/// its file's bytes and the level's time bar with the input's triangles,
/// hence the ratio. Measured (BENCHMARKS.md, "Displaced subdivision joins
/// `default`" and "Session 2026-12-06 (eighth)"): up to 1 b/v it adds
/// 0.1-0.2 s of one core to the level's encode and wins on scans by
/// 12-15% of L2; at 2 b/v, since its rate control runs in two rounds,
/// 0.2-0.3 s for 14-18%; at 4-8 b/v still 0.4-0.7 s, which the level's
/// time bar does not leave. Small meshes have [`DISPLACED_BYTES_FLOOR`]
/// besides; on CAD parts it never won.
const DISPLACED_FACES_PER_BYTE: u64 = 7;

/// Bytes of file up to which the `default` level runs the displaced
/// method whatever the input's size: on a small mesh the level's time
/// bar is its half-second floor, not a multiple of the input. Measured
/// on the nine small meshes of the shared corpus at 4 and 8 b/v
/// (BENCHMARKS.md, "Session 2026-12-07 (seventh)", "a byte floor"):
/// every cell within its bar, 0.02-0.14 s more, and homer and the teapot
/// at 4 b/v 11-12% closer. At 4 KB the attributed meshes (beetle,
/// suzanne, alligator) went to 0.8-1.1 s.
const DISPLACED_BYTES_FLOOR: u64 = 3072;

/// The `default` level's budget for the displaced method, in bytes of
/// file, on an input of `faces` triangles.
pub(crate) fn displaced_budget(faces: usize) -> u64 {
    (faces as u64 / DISPLACED_FACES_PER_BYTE).max(DISPLACED_BYTES_FLOOR)
}

/// The `default` level's budget for SwingWrapper on an input of `faces`
/// triangles.
pub(crate) fn swing_budget(faces: usize) -> u64 {
    SWING_STEPS_FLOOR.saturating_add(SWING_STEPS_PER_FACE.saturating_mul(faces as u64))
}

/// The chooser's list at `effort` for an input of `faces` triangles.
pub(crate) fn methods(effort: Effort, faces: usize) -> Vec<Entry> {
    let entry = |method: &'static dyn CodingMethod, work| Entry { method, work };
    match effort {
        Effort::Fast => vec![entry(&Simplified::QUICK, None)],
        Effort::Default => vec![
            entry(&Swing::AUTO, Some(swing_budget(faces))),
            entry(&Simplified::LEAN, None),
            entry(&Displaced::DEFAULT, Some(displaced_budget(faces))),
        ],
        Effort::Max => vec![
            entry(&Mixed, None),
            entry(&Swing::AUTO, None),
            entry(&Simplified::FULL, None),
            entry(&Displaced::DEFAULT, None),
        ],
    }
}
