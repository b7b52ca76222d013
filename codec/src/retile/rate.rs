//! Rate control: the edge length L that makes the file the requested size
//! (thesis §7.4; design notes §5 "L from a target size").
//!
//! The start is the thesis's estimate L₀ = √(16A/(√3·S)), S in bits, which
//! assumes 4 bits per equilateral triangle. Then, since the triangle count
//! goes as 1/L², each run rescales L by √(O/S) (O the size obtained), a
//! secant step on log L against log size, bracketed by the best runs on
//! either side of the target. A run that fails (some gate found no valid
//! triangle) is retried at the same L from the next flattest start
//! vertex: failures are not monotonic in L (measured on horse: runs fail
//! and succeed alternately over a few percent of L), so they cannot
//! bracket a binary search the way the thesis's "largest L that works"
//! search assumed; four failures in a row at one L step it down.
//!
//! The result is the run nearest the request among those within
//! `max_bytes`; it lands within `TOLERANCE` of the request unless no run
//! could (reported, never silent).

use super::compose::{retile_pieces, PieceReport};
use super::fill::Piece;
use super::{Budget, Failure, RetileOptions};
use crate::swing::SwingStats;
use crate::Error;

/// Relative size error accepted without further runs.
pub const TOLERANCE: f64 = 0.03;

/// Whether a file of `size` bytes answers a request for `target`: within
/// [`TOLERANCE`] of it either way.
pub fn within_tolerance(size: u64, target: u64) -> bool {
    (size as f64 - target as f64).abs() <= TOLERANCE * target as f64
}
/// Runs at most (each is a full retiling).
const MAX_RUNS: usize = 16;

/// One retiling run of the search.
#[derive(Clone, Debug, PartialEq)]
pub struct Attempt {
    /// The edge length tried.
    pub edge_length: f64,
    /// The file size obtained, or why the run failed.
    pub outcome: Result<u64, Failure>,
}

/// How the edge length was chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct RateReport {
    /// The requested size in bytes (`None` when L was given).
    pub requested_bytes: Option<u64>,
    /// The edge length of the file written.
    pub edge_length: f64,
    /// Every run, in order.
    pub attempts: Vec<Attempt>,
    /// The requested L (or the first estimate) failed and a smaller one
    /// was used.
    pub reduced: bool,
    /// The size is within the tolerance of the request (always true when
    /// L was given).
    pub within_tolerance: bool,
    /// Steps of retiling work over every run (what
    /// [`EncodeLimits::max_work`](crate::EncodeLimits) caps).
    pub work: u64,
    /// The most bytes a run's working surface and output held (what
    /// [`EncodeLimits::max_memory_bytes`](crate::EncodeLimits) caps).
    pub peak_memory_bytes: u64,
}

/// What every run of one encode shares besides L.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Knobs {
    /// Bits per dihedral angle K.
    pub angle_bits: u8,
    /// [`RetileOptions::approximate_tips`].
    pub approximate_tips: bool,
    /// [`RetileOptions::fit_tips`].
    pub fit_tips: bool,
    /// [`RetileOptions::adaptive_density`].
    pub adaptive_density: bool,
    /// [`SwingTuning::front_contexts`](crate::SwingTuning).
    pub front_contexts: bool,
    /// [`SwingTuning::loop_start`](crate::SwingTuning).
    pub loop_start: bool,
    /// [`RetileOptions::crease_tips`].
    pub crease_tips: bool,
    /// [`EncodeOptions::framing`](crate::EncodeOptions).
    pub framing: crate::container::Framing,
}

/// A finished encoding.
pub struct Chosen {
    pub bytes: Vec<u8>,
    pub stats: SwingStats,
    pub report: RateReport,
    /// What happened to each component.
    pub pieces: Vec<PieceReport>,
}

/// One written file: bytes, figures, and each component's fate.
type Run = (Vec<u8>, SwingStats, Vec<PieceReport>);

/// One run; a run stopped by the encoder's limits ends the encode.
fn run(
    pieces: &[Piece],
    l: f64,
    knobs: Knobs,
    start_rank: u32,
    budget: &Budget,
) -> Result<Result<Run, Failure>, Error> {
    let opt = RetileOptions {
        edge_length: l,
        angle_bits: knobs.angle_bits,
        start_vertex: None,
        start_rank,
        start_by_shape: false,
        approximate_tips: knobs.approximate_tips,
        fit_tips: knobs.fit_tips,
        adaptive_density: knobs.adaptive_density,
        last_resort: false,
        loop_start: knobs.loop_start,
        crease_tips: knobs.crease_tips,
    };
    match retile_pieces(pieces, &opt, budget) {
        Ok(c) => {
            let (bytes, stats) = crate::swing::write(
                &c.retiled,
                if knobs.front_contexts {
                    crate::swing::Clers::Smaller
                } else {
                    crate::swing::Clers::Plain
                },
                knobs.framing,
            )?;
            Ok(Ok((bytes, stats, c.report)))
        }
        Err(Failure::Limit) => Err(budget.error().map_or(
            Error::from(crate::error::RetileError {
                attempts: 1,
                successes: 0,
                smallest_edge_length: l,
                failure: Some(Failure::Limit),
            }),
            Error::from,
        )),
        Err(f) => Ok(Err(f)),
    }
}

/// Encodes at the given L; if four runs from different start vertices
/// fail, at the first L below it, in steps of 2%, where one works.
pub fn at_length(pieces: &[Piece], l: f64, knobs: Knobs, budget: &Budget) -> Result<Chosen, Error> {
    let mut attempts = Vec::new();
    let mut next = l;
    let mut fails = 0u32;
    for _ in 0..MAX_RUNS {
        match run(pieces, next, knobs, fails % 4, budget)? {
            Ok((bytes, stats, report)) => {
                attempts.push(Attempt {
                    edge_length: next,
                    outcome: Ok(bytes.len() as u64),
                });
                return Ok(Chosen {
                    bytes,
                    stats,
                    pieces: report,
                    report: RateReport {
                        requested_bytes: None,
                        edge_length: next,
                        reduced: next != l,
                        within_tolerance: true,
                        work: budget.used(),
                        peak_memory_bytes: budget.peak_memory(),
                        attempts,
                    },
                });
            }
            Err(f) => {
                attempts.push(Attempt {
                    edge_length: next,
                    outcome: Err(f),
                });
                fails += 1;
                if fails.is_multiple_of(4) {
                    next *= 0.98;
                }
            }
        }
    }
    Err(infeasible(&attempts))
}

/// Encodes to about `target` bytes, never more than `max_bytes`.
pub fn at_size(
    pieces: &[Piece],
    target: u64,
    max_bytes: Option<u64>,
    knobs: Knobs,
    budget: &Budget,
) -> Result<Chosen, Error> {
    search(pieces, target, max_bytes, knobs, budget, None)
}

/// [`at_size`] with the angle bits chosen here: [`AUTO_ANGLE_BITS`]`[0]`
/// first, then `[1]` when the first file's angles spread over
/// [`SPREAD_BITS_PER_ANGLE`] or more, or when no file could be made with
/// the first: the coarser angles then cost less than the sampling error
/// they add, and the bits they save buy triangles. When the first file
/// falls short of the size (runs failed at the finer L it needed), one
/// bit more per angle is tried from its L, and the file nearer the size
/// is kept. Measured on six corpus meshes at 0.5-8 b/v, BENCHMARKS.md
/// "Angle bits chosen by rate control".
pub fn at_size_auto(
    pieces: &[Piece],
    target: u64,
    max_bytes: Option<u64>,
    tuning: Knobs,
    budget: &Budget,
) -> Result<Chosen, Error> {
    let knobs = |angle_bits| Knobs {
        angle_bits,
        ..tuning
    };
    let [fine, coarse] = AUTO_ANGLE_BITS;
    let first = search(pieces, target, max_bytes, knobs(fine), budget, None);
    let (hint, earlier) = match &first {
        // At the same size, one bit less per angle buys about 1/0.91² as
        // many triangles (measured).
        Ok(c) if bits_per_angle(&c.stats) >= SPREAD_BITS_PER_ANGLE => {
            (Some(0.91 * c.report.edge_length), c.report.attempts.clone())
        }
        Ok(c) if c.report.within_tolerance || c.bytes.len() as u64 > target => return first,
        // Short of the size: runs failed at the finer L it asked for. The
        // bytes left over buy finer angles, and the search draws new
        // retilings.
        Ok(c) => {
            let finer = search(
                pieces,
                target,
                max_bytes,
                knobs(fine + 1),
                budget,
                Some(c.report.edge_length),
            );
            return match (first, finer) {
                (Ok(a), Ok(b)) if nearer(&b, &a, target) => Ok(after(a.report.attempts, b, budget)),
                (_, Err(e)) if !matches!(e, Error::Retile(_)) => Err(e),
                (a, _) => a,
            };
        }
        Err(Error::Retile(_)) => (None, Vec::new()),
        Err(_) => return first,
    };
    match search(pieces, target, max_bytes, knobs(coarse), budget, hint) {
        Ok(c) => Ok(after(earlier, c, budget)),
        // A limit ends the encode; otherwise the first file stands.
        Err(e) if first.is_err() || !matches!(e, Error::Retile(_)) => Err(e),
        Err(_) => first,
    }
}

/// `c`, found by a second search, reporting the first search's runs
/// (`earlier`) before its own and the whole encode's work and memory.
fn after(mut earlier: Vec<Attempt>, mut c: Chosen, budget: &Budget) -> Chosen {
    earlier.append(&mut c.report.attempts);
    c.report.attempts = earlier;
    c.report.work = budget.used();
    c.report.peak_memory_bytes = budget.peak_memory();
    c
}

/// `a` is nearer the target than `b` (both within the cap).
fn nearer(a: &Chosen, b: &Chosen, target: u64) -> bool {
    let off = |c: &Chosen| (c.bytes.len() as f64 / target as f64).ln().abs();
    off(a) < off(b)
}

/// Geometry bits per C angle of a file.
fn bits_per_angle(stats: &SwingStats) -> f64 {
    let angles = stats.clers[0].max(1) as f64;
    stats.geometry_bits_per_triangle * stats.triangles as f64 / angles
}

/// The angle bits [`at_size_auto`] tries, in order.
pub const AUTO_ANGLE_BITS: [u8; 2] = [6, 5];
/// Geometry bits per angle of a 6-bit file from which 5 bits do better:
/// the dihedral angles vary so much from triangle to triangle that the
/// sampling error, not the angle precision, sets the distortion.
pub const SPREAD_BITS_PER_ANGLE: f64 = 3.2;

/// The search of [`at_size`], from `start` when given, else from the
/// thesis's estimate.
fn search(
    pieces: &[Piece],
    target: u64,
    max_bytes: Option<u64>,
    knobs: Knobs,
    budget: &Budget,
    start: Option<f64>,
) -> Result<Chosen, Error> {
    // A cap below the target is the real target.
    let target = max_bytes.map_or(target, |cap| target.min(cap));
    let area: f64 = pieces.iter().map(|p| p.area).sum();
    let s_bits = 8.0 * target as f64;
    let mut l = start.unwrap_or_else(|| (16.0 * area / (3f64.sqrt() * s_bits)).sqrt());
    let cap = max_bytes.unwrap_or(u64::MAX);
    // With the cap at the target, aim a little below it so that a run
    // lands inside [target − 3%, target].
    let aim = if cap <= target {
        (1.0 - TOLERANCE / 2.0) * target as f64
    } else {
        target as f64
    };
    let mut attempts = Vec::new();
    // Brackets from successful runs: (L, size) of the nearest runs below
    // and above the aim in size.
    let mut small: Option<(f64, u64)> = None; // size < aim: L too large
    let mut large: Option<(f64, u64)> = None; // size > aim: L too small
    let mut best: Option<(f64, Run)> = None;
    let score = |size: u64| {
        if size > cap {
            f64::INFINITY
        } else {
            (size as f64 / target as f64).ln().abs()
        }
    };
    // Whether a run fails changes abruptly and unpredictably with L and
    // with the start vertex (one gate somewhere meets a pinched front), so
    // failures say nothing about larger or smaller L and must not bracket
    // the search: a failed run is retried at the same L from the next
    // flattest start vertex, an independent trial.
    let mut fails = 0u32;
    let mut failing_from: Option<f64> = None;
    for _ in 0..MAX_RUNS {
        match run(pieces, l, knobs, fails, budget)? {
            Ok(done) => {
                fails = 0;
                failing_from = None;
                let size = done.0.len() as u64;
                attempts.push(Attempt {
                    edge_length: l,
                    outcome: Ok(size),
                });
                let better = best
                    .as_ref()
                    .is_none_or(|(_, b)| score(size) < score(b.0.len() as u64));
                if better {
                    best = Some((l, done));
                }
                if within_tolerance(size, target) && size <= cap {
                    break;
                }
                if (size as f64) < aim {
                    small = Some((l, size));
                } else {
                    large = Some((l, size));
                }
                // Size ~ 1/L²: rescale, then keep inside the brackets.
                let mut next = l * (size as f64 / aim).sqrt();
                if let (Some((ls, _)), Some((ll, _))) = (small, large) {
                    if !(next > ll && next < ls) {
                        next = (ls * ll).sqrt();
                    }
                }
                l = next;
            }
            Err(f) => {
                attempts.push(Attempt {
                    edge_length: l,
                    outcome: Err(f),
                });
                fails += 1;
                // Four failures in a row at one L: move away from where
                // the failures began, alternately down and up by growing
                // steps (−5%, +5%, −10%, +10%, …): a thin part of the shape
                // (the thesis's failure case) needs a smaller L, but a cap
                // may forbid one.
                let base = *failing_from.get_or_insert(l);
                if fails.is_multiple_of(4) {
                    let n = fails / 4;
                    let magnitude = 0.05 * f64::from(n.div_ceil(2));
                    let sign = if n % 2 == 1 { -1.0 } else { 1.0 };
                    l = base * (1.0 + sign * magnitude);
                }
            }
        }
    }
    let (edge_length, (bytes, stats, pieces)) = best
        .filter(|(_, b)| b.0.len() as u64 <= cap)
        .ok_or_else(|| infeasible(&attempts))?;
    let first_failed = attempts.first().is_some_and(|a| a.outcome.is_err());
    Ok(Chosen {
        report: RateReport {
            requested_bytes: Some(target),
            edge_length,
            reduced: first_failed,
            within_tolerance: within_tolerance(bytes.len() as u64, target),
            work: budget.used(),
            peak_memory_bytes: budget.peak_memory(),
            attempts,
        },
        bytes,
        stats,
        pieces,
    })
}

fn infeasible(attempts: &[Attempt]) -> Error {
    let last = attempts.last();
    crate::error::RetileError {
        attempts: attempts.len() as u32,
        successes: attempts.iter().filter(|a| a.outcome.is_ok()).count() as u32,
        smallest_edge_length: attempts
            .iter()
            .map(|a| a.edge_length)
            .fold(f64::INFINITY, f64::min),
        failure: last.and_then(|a| a.outcome.err()),
    }
    .into()
}
