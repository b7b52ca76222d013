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
//! The bound is met against the encoder's own measure (the reference
//! surface, [`AUTO_SAMPLES`](crate::AUTO_SAMPLES) samples each way),
//! aiming [`MARGIN`] under E so that an independent measure with other
//! samples (`swm distance`) also finds the file within E.
//!
//! Invariants: every probe is a deterministic chooser run, so the file
//! depends only on the input, E and the options; the work is at most
//! [`MAX_PROBES`] chooser runs sharing one collapse sequence and one
//! reference surface; the file is never above the cap.

use super::choose::{choose, Chosen, Entry};
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

/// A probed size and what it gave.
struct Probe {
    bytes: u64,
    /// Its file's measured L2 (relative); `None`: no file that small.
    l2: Option<f64>,
}

/// The smallest file of the chooser over `list` whose L2 relative to the
/// input's diagonal is at most `bound`, never above `max_bytes`.
pub(crate) fn smallest_within(
    job: &Job<'_, '_>,
    bound: ErrorBound,
    max_bytes: Option<u64>,
    list: &[Entry],
) -> Result<Chosen, Error> {
    let diagonal = job.simplifier().reference().bbox_diagonal();
    let e = match bound {
        ErrorBound::Relative(r) => positive("max error", r)?,
        ErrorBound::Absolute(a) => positive("max error", a)? / diagonal,
    };
    let aim = e / MARGIN;
    // Above the whole mesh at the finest quantization nothing improves
    // (the simplified method returns that mesh); never above the cap.
    let c = job.cleaned;
    let finest = *crate::simplify::QPS.end();
    let whole = crate::lossless::encode(&c.table, &c.mesh, finest, job.options.framing)?
        .0
        .len() as u64;
    let ceiling = max_bytes.map_or(whole, |cap| cap.min(whole)).max(1);
    let run = |bytes: u64| -> Result<(Option<Chosen>, Probe), Error> {
        let ask = Ask {
            target: SwingTarget::Bytes(bytes),
            max_bytes,
        };
        match choose(job, ask, list) {
            Ok(chosen) => {
                let l2 = l2_of(job, &chosen)?;
                Ok((
                    Some(chosen),
                    Probe {
                        bytes,
                        l2: Some(l2),
                    },
                ))
            }
            Err(Error::Size(s)) => Ok((
                None,
                // No file below the smallest: everything under it is out.
                Probe {
                    bytes: s.smallest.saturating_sub(1).max(bytes),
                    l2: None,
                },
            )),
            Err(e) => Err(e),
        }
    };
    // `lo`: the largest size known not to meet the aim; `hi`: the
    // smallest known to, with its file.
    let mut lo: Option<Probe> = None;
    let mut hi: Option<(Probe, Chosen)> = None;
    let mut fitted: Vec<(f64, f64)> = Vec::new();
    let mut next = bytes_for(FIRST_BPV, job.input_vertices).clamp(1, ceiling);
    for _ in 0..MAX_PROBES {
        let (chosen, probe) = run(next)?;
        match (chosen, probe.l2) {
            (Some(chosen), Some(l2)) if l2 <= aim => {
                fitted.push(((probe.bytes as f64).ln(), l2.ln()));
                if hi.as_ref().is_none_or(|h| probe.bytes < h.0.bytes) {
                    hi = Some((probe, chosen));
                }
            }
            (_, l2) => {
                if let Some(l2) = l2 {
                    fitted.push(((probe.bytes as f64).ln(), l2.ln()));
                }
                if lo.as_ref().is_none_or(|l| probe.bytes > l.bytes) {
                    lo = Some(probe);
                }
            }
        }
        let (lo_b, hi_b) = (lo.as_ref().map(|l| l.bytes), hi.as_ref().map(|h| h.0.bytes));
        if let (Some(l), Some(h)) = (lo_b, hi_b) {
            if h as f64 <= l as f64 * PRECISION {
                break;
            }
        }
        if hi_b.is_none() && lo_b.is_some_and(|l| l >= ceiling) {
            break;
        }
        next = guess(&fitted, aim, lo_b, hi_b, ceiling);
        if Some(next) == lo_b || Some(next) == hi_b {
            break;
        }
    }
    match hi {
        Some((_, chosen)) => Ok(chosen),
        None => {
            // Nothing met it: the closest file tried says how far.
            let (bytes, lowest) = fitted
                .iter()
                .map(|&(b, l)| (b.exp().round() as u64, l.exp()))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((ceiling, f64::INFINITY));
            Err(ErrorBoundError {
                requested: e,
                lowest,
                bytes,
            }
            .into())
        }
    }
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
