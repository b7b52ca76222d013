//! An error target (`swm encode --max-error E`, [`SwingTarget::MaxError`]):
//! the smallest file whose measured L2 distance to the input is at most
//! E, found by running the chooser at a few sizes. No peer offers this for
//! a whole codec (Draco has none; meshoptimizer's `target_error` bounds
//! one simplification, not the file).
//!
//! The search is a secant on ln L2 against ln bytes (L2 falls about as
//! 1/bytes for both retiling and simplification, the prior slope −1),
//! inside a bracket [too coarse or too small, meets E] that every probe
//! narrows, bisecting (in log) when the secant leaves it. It stops when
//! the bracket is within [`PRECISION`], or after [`MAX_PROBES`] probes,
//! with the smallest file that met the bound.
//!
//! The search runs on the chooser's own measure (the reference surface,
//! [`AUTO_SAMPLES`](crate::AUTO_SAMPLES) area-uniform samples each way),
//! aiming [`MARGIN`] under E; its answer is then measured as
//! `swm distance` measures it (Metro's samples against the input as
//! given, [`Job::metro`](super::method::Job::metro)), and when that is
//! above E the aim is lowered by the ratio of the two measures and the
//! search goes on from the probes it has ([`ROUNDS`] at most). Metro's
//! vertex and edge samples weigh the chords of a coarse mesh, so its L2
//! is 5-10% above the area-uniform one on simplified scans.
//!
//! Invariants: every probe is a deterministic chooser run, so the file
//! depends only on the input, E and the options; the work is at most
//! [`ROUNDS`] x [`MAX_PROBES`] chooser runs (in practice 5-9) sharing one
//! collapse sequence and one reference surface, and [`ROUNDS`] Metro
//! measures; the file is never above the cap.

use super::choose::{choose, Chosen};
use super::effort::Entry;
use super::method::{Ask, Job};
use super::request::{bytes_for, positive};
use crate::options::{ErrorBound, SwingTarget};
use crate::{Error, ErrorBoundError};

/// The aim is this much under the bound: the spread of two 30,000-sample
/// measures of the same pair of surfaces is about 1% (BENCHMARKS.md,
/// "Error target").
pub const MARGIN: f64 = 1.02;
/// The search stops when the smallest size known to meet the bound is
/// within this ratio of the largest known not to.
const PRECISION: f64 = 1.02;
/// Chooser runs at most.
const MAX_PROBES: usize = 12;
/// The first probe's rate, in bits per input vertex: mid-range on the
/// corpus at the errors archives ask for (1e-4 to 1e-3 of the diagonal).
const FIRST_BPV: f64 = 2.0;

/// A probed size and what it gave: the chooser's file and its L2 by the
/// chooser's measure, or `None` when no file is that small.
struct Probe {
    bytes: u64,
    file: Option<(Chosen, f64)>,
}

/// Calibration rounds at most: after each, the answer is measured as
/// `swm distance` measures it and, when that is above the bound, the aim
/// is lowered by the ratio of the two measures.
const ROUNDS: usize = 3;

/// The smallest file of the chooser over `list` whose L2 relative to the
/// input's diagonal is at most `bound`, never above `max_bytes`.
pub(crate) fn smallest_within(
    job: &Job<'_, '_>,
    bound: ErrorBound,
    max_bytes: Option<u64>,
    list: &[Entry],
) -> Result<Chosen, Error> {
    let diagonal = job.input_diagonal();
    let e = match bound {
        ErrorBound::Relative(r) => positive("max error", r)?,
        ErrorBound::Absolute(a) => positive("max error", a)? / diagonal,
    };
    // Above the whole mesh at the finest quantization nothing improves
    // (the simplified method returns that mesh); never above the cap.
    // The simplifier's whole-mesh file: its connectivity, coded here,
    // serves every later quantization's file of the simplified method.
    let finest = *crate::simplify::QPS.end();
    let whole = job.simplifier().whole_file(finest)?.0.len() as u64;
    let ceiling = max_bytes.map_or(whole, |cap| cap.min(whole)).max(1);
    let mut probes: Vec<Probe> = Vec::new();
    let mut aim = e / MARGIN;
    let mut closest: Option<(u64, f64)> = None;
    for _ in 0..ROUNDS {
        let Some(i) = search(job, aim, max_bytes, list, ceiling, &mut probes)? else {
            break;
        };
        let (chosen, cheap) = probes[i].file.as_ref().expect("a file met the aim");
        let metro = job.metro(&chosen.bytes)?;
        if closest.is_none_or(|(_, l)| metro < l) {
            closest = Some((chosen.bytes.len() as u64, metro));
        }
        if metro <= e {
            let Probe { file, .. } = probes.swap_remove(i);
            return Ok(file.expect("a file met the aim").0);
        }
        // The two measures differ by the sampling (Metro's vertices and
        // edges weigh the chords of a coarse mesh): aim lower by their
        // ratio, a little more than it says.
        aim = e * (cheap / metro) / MARGIN;
    }
    // Nothing met it: the closest file tried says how far.
    let (bytes, lowest) = match closest {
        Some(c) => c,
        None => probes
            .iter()
            .filter_map(|p| p.file.as_ref().map(|f| (p.bytes, f.1)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((ceiling, f64::INFINITY)),
    };
    Err(ErrorBoundError {
        requested: e,
        lowest,
        bytes,
    }
    .into())
}

/// The bracketed search for `aim` by the chooser's measure, reusing and
/// extending `probes`; the index of the smallest probe that meets it, or
/// `None` when none does up to `ceiling`.
fn search(
    job: &Job<'_, '_>,
    aim: f64,
    max_bytes: Option<u64>,
    list: &[Entry],
    ceiling: u64,
    probes: &mut Vec<Probe>,
) -> Result<Option<usize>, Error> {
    let meets = |p: &Probe| p.file.as_ref().is_some_and(|f| f.1 <= aim);
    // The index of the smallest probe that meets the aim.
    let smallest_meeting = |probes: &[Probe]| {
        (0..probes.len())
            .filter(|&i| meets(&probes[i]))
            .min_by_key(|&i| probes[i].bytes)
    };
    let mut next = match probes.is_empty() {
        true => Some(bytes_for(FIRST_BPV, job.input_vertices).clamp(1, ceiling)),
        false => None,
    };
    for _ in 0..MAX_PROBES {
        if let Some(bytes) = next {
            let ask = Ask {
                target: SwingTarget::Bytes(bytes),
                max_bytes,
            };
            let probe = match choose(job, ask, list) {
                Ok(chosen) => {
                    let l2 = l2_of(job, &chosen)?;
                    Probe {
                        bytes,
                        file: Some((chosen, l2)),
                    }
                }
                // No file below the smallest: everything under it is out.
                Err(Error::Size(s)) => Probe {
                    bytes: s.smallest.saturating_sub(1).max(bytes),
                    file: None,
                },
                Err(e) => return Err(e),
            };
            probes.push(probe);
        }
        // `lo`: the largest size known not to meet the aim; `hi`: the
        // smallest known to.
        let lo = probes.iter().filter(|p| !meets(p)).map(|p| p.bytes).max();
        let hi = smallest_meeting(probes).map(|i| (i, probes[i].bytes));
        if let (Some(l), Some((i, h))) = (lo, hi) {
            if h as f64 <= l as f64 * PRECISION {
                return Ok(Some(i));
            }
        }
        if hi.is_none() && lo.is_some_and(|l| l >= ceiling) {
            return Ok(None);
        }
        let fitted: Vec<(f64, f64)> = probes
            .iter()
            .filter_map(|p| p.file.as_ref().map(|f| ((p.bytes as f64).ln(), f.1.ln())))
            .collect();
        let mut guess = guess(&fitted, aim, lo, hi.map(|h| h.1), ceiling);
        // A line that rounds onto an end of a bracket still wider than
        // `PRECISION` (two probes nearly level: the slope clamped at its
        // flattest, bunny at E = 5e-4 stopped 7% wide) gives way to the
        // bracket's log midpoint; only a bracket with no size left inside
        // ends the search.
        let ends = |g: u64| Some(g) == lo || Some(g) == hi.map(|h| h.1);
        if ends(guess) {
            if let (Some(l), Some((_, h))) = (lo, hi) {
                guess = ((l as f64 * h as f64).sqrt().round() as u64).clamp(1, ceiling);
            }
            if ends(guess) {
                return Ok(hi.map(|h| h.0));
            }
        }
        next = Some(guess);
    }
    Ok(smallest_meeting(probes))
}

/// The measured L2 of the chooser's file (its candidate's, or measured
/// now when the chooser had a lone candidate and measured nothing).
fn l2_of(job: &Job<'_, '_>, chosen: &Chosen) -> Result<f64, Error> {
    let method = chosen.stats.method();
    let known = chosen
        .candidates
        .iter()
        .find(|c| c.method == method)
        .and_then(|c| c.outcome.as_ref().ok())
        .and_then(|m| m.l2_relative);
    match known {
        Some(l2) => Ok(l2),
        None => job.measure(&chosen.bytes),
    }
}

/// The next size to probe: where the line through the two measured
/// probes nearest the aim (or through the one, at slope −1) meets it,
/// kept strictly inside the bracket (its log midpoint when the line
/// leaves it) and within [1, `ceiling`].
fn guess(fitted: &[(f64, f64)], aim: f64, lo: Option<u64>, hi: Option<u64>, ceiling: u64) -> u64 {
    let target = aim.ln();
    let mut near: Vec<&(f64, f64)> = fitted.iter().collect();
    near.sort_by(|a, b| (a.1 - target).abs().total_cmp(&(b.1 - target).abs()));
    let line = match near[..] {
        [a, b, ..] if (a.0 - b.0).abs() > 1e-9 => {
            let slope = ((a.1 - b.1) / (a.0 - b.0)).clamp(-3.0, -0.3);
            Some((a.0 + (target - a.1) / slope).exp())
        }
        [a, ..] => Some((a.0 + (a.1 - target)).exp()),
        [] => None,
    };
    let (lo_f, hi_f) = (
        lo.map_or(1.0, |l| l as f64),
        hi.map_or(ceiling as f64 * 1.0001, |h| h as f64),
    );
    let inside = |x: f64| x > lo_f && x < hi_f;
    let x = match line {
        Some(x) if x.is_finite() && inside(x) => x,
        _ if lo.is_none() => (hi_f / 2.0).max(1.0),
        _ if hi.is_none() => (lo_f * 2.0).min(ceiling as f64),
        _ => (lo_f * hi_f).sqrt(),
    };
    (x.round() as u64).clamp(1, ceiling)
}
