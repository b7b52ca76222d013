//! Rate control: the edge length L that makes the file the requested size
//! (thesis §7.4; design notes §5 "L from a target size"), in few runs
//! (issue 22: each run is a whole retiling).
//!
//! The thesis starts from L₀ = √(16A/(√3·S)), S in bits, which assumes 4
//! bits per equilateral triangle; files here take 1.3-2.3, so the first
//! run assumes [`FIRST_BITS_PER_TRIANGLE`] = 2 (beyond the thesis). Size
//! is then modelled as a power of L, ln size against ln L: from the run
//! nearest the aim along a slope (the prior [`SLOPE`] = 1.8 until two
//! runs measure one), and by interpolation between the nearest runs on
//! either side of the aim once both exist. A search after another for the
//! same request (coarser angles, other tips, the hint's few bytes less)
//! starts where the earlier search's model meets the request, with its
//! measured slope ([`Prior`]), so it usually needs two runs. Measured on the corpus at 0.5-8 b/v
//! (BENCHMARKS.md, "Rate control in few runs").
//!
//! The size does not always answer L: below the header and the parts
//! kept losslessly no L reaches a request, and tiny files move in steps
//! of bytes. The search stops, with the nearest file, when twice a step
//! moved the size away from the aim, or when the model asks for an L
//! already run.
//!
//! A run that fails (some gate found no valid triangle) is retried from
//! the next flattest start vertex, first at the same L and then at L 3%,
//! 6%, 12% either side of it and 24%, 48%, … above: failures are not
//! monotonic in L (measured on horse: runs fail and succeed alternately
//! over a few percent of L), so they cannot bracket a binary search the
//! way the thesis's "largest L that works" search assumed. A model step
//! is moved off any L where a run failed (it would fail again).
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
    /// Where a later search for the same request starts.
    pub prior: Prior,
    pub stats: SwingStats,
    pub report: RateReport,
    /// What happened to each component.
    pub pieces: Vec<PieceReport>,
    /// Per vertex of the file decoded plainly, a vertex of the cleaned
    /// input at the face of the input its tip was fitted in (`NONE`: not
    /// known; the list may end before `REST`'s vertices): where
    /// `encoder::provenance` starts.
    pub seeds: Vec<u32>,
}

/// One written file: bytes, figures, each component's fate, and its
/// seeds ([`Chosen::seeds`]).
type Run = (Vec<u8>, SwingStats, Vec<PieceReport>, Vec<u32>);

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
            let seeds = c.decoded_seeds();
            let (bytes, stats) = crate::swing::write(
                &c.retiled,
                if knobs.front_contexts {
                    crate::swing::Clers::Smaller
                } else {
                    crate::swing::Clers::Plain
                },
                knobs.framing,
            )?;
            Ok(Ok((bytes, stats, c.report, seeds)))
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
            Ok((bytes, stats, report, seeds)) => {
                attempts.push(Attempt {
                    edge_length: next,
                    outcome: Ok(bytes.len() as u64),
                });
                return Ok(Chosen {
                    prior: Prior {
                        edge_length: next,
                        angle_bits: knobs.angle_bits,
                        slope: SLOPE,
                    },
                    bytes,
                    stats,
                    pieces: report,
                    seeds,
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

/// Encodes to about `target` bytes, never more than `max_bytes`; from
/// `prior` (an earlier search for about the same size) when given.
pub fn at_size(
    pieces: &[Piece],
    target: u64,
    max_bytes: Option<u64>,
    knobs: Knobs,
    budget: &Budget,
    prior: Option<Prior>,
) -> Result<Chosen, Error> {
    let start = prior.map(|p| p.start(knobs.angle_bits));
    search(pieces, target, max_bytes, knobs, budget, start, None)
}

/// [`at_size`] with the angle bits chosen here: [`AUTO_ANGLE_BITS`]`[0]`
/// first, then `[1]` when the first file's angles spread over
/// [`SPREAD_BITS_PER_ANGLE`] or more, or when no file could be made with
/// the first: the coarser angles then cost less than the sampling error
/// they add, and the bits they save buy triangles. When the first file
/// falls short of the size (runs failed at the finer L it needed), one
/// bit more per angle is tried from its L, and the file nearer the size
/// is kept. Measured on six corpus meshes at 0.5-8 b/v, BENCHMARKS.md
/// "Angle bits chosen by rate control". A coarser file that misses the
/// size the first met gives way to the first. Each search after the first
/// starts from the one before ([`Prior`]), as does the first from
/// `prior` when given.
pub fn at_size_auto(
    pieces: &[Piece],
    target: u64,
    max_bytes: Option<u64>,
    tuning: Knobs,
    budget: &Budget,
    prior: Option<Prior>,
) -> Result<Chosen, Error> {
    let knobs = |angle_bits| Knobs {
        angle_bits,
        ..tuning
    };
    let [fine, coarse] = AUTO_ANGLE_BITS;
    let start = prior.map(|p| p.start(fine));
    // The first search leaves after its first file when that file's
    // angles already spread clearly past the threshold: the coarser
    // angles will be chosen whatever L the search lands on.
    let leave = Some(SPREAD_BITS_PER_ANGLE + EARLY_MARGIN);
    let first = search(pieces, target, max_bytes, knobs(fine), budget, start, leave);
    let (hint, earlier) = match &first {
        // At the same size, one bit less per angle buys about 1/0.91² as
        // many triangles (measured).
        Ok(c) if bits_per_angle(&c.stats) >= SPREAD_BITS_PER_ANGLE => {
            (Some(c.prior.start(coarse)), c.report.attempts.clone())
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
                Some(Start {
                    l: c.report.edge_length,
                    slope: c.prior.slope,
                }),
                None,
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
    let second = search(pieces, target, max_bytes, knobs(coarse), budget, hint, None);
    // A first search that left early did not look for its own file: where
    // the coarser angles' search missed, it is finished now, from where it
    // left.
    let missed = !second.as_ref().is_ok_and(|c| c.report.within_tolerance);
    let mut earlier = earlier;
    if let (true, Ok(f)) = (missed, &first) {
        if !f.report.within_tolerance {
            let start = Start {
                l: f.prior.edge_length,
                slope: f.prior.slope,
            };
            let resumed = search(
                pieces,
                target,
                max_bytes,
                knobs(fine),
                budget,
                Some(start),
                None,
            );
            // Every run of the three searches, in order, is reported.
            earlier.extend(
                second
                    .iter()
                    .flat_map(|c| c.report.attempts.iter().cloned()),
            );
            if let Ok(r) = &resumed {
                earlier.extend(r.report.attempts.iter().cloned());
            }
            let with_all = |mut c: Chosen| {
                c.report.attempts = earlier.clone();
                finish_report(c, budget)
            };
            return match (resumed, second) {
                (Err(e), _) if !matches!(e, Error::Retile(_)) => Err(e),
                (Ok(f), _) if f.report.within_tolerance => Ok(with_all(f)),
                (_, Ok(c)) => Ok(with_all(c)),
                (Ok(f), Err(_)) => Ok(with_all(f)),
                (Err(_), Err(e)) => Err(e),
            };
        }
    }
    match second {
        // The coarser angles' file missed the size the finer one met.
        Ok(c)
            if !c.report.within_tolerance
                && first.as_ref().is_ok_and(|f| f.report.within_tolerance) =>
        {
            let mut f = first?;
            f.report.attempts = [earlier, c.report.attempts].concat();
            Ok(finish_report(f, budget))
        }
        Ok(c) => Ok(after(earlier, c, budget)),
        // A limit ends the encode; otherwise the first file stands.
        Err(e) if first.is_err() || !matches!(e, Error::Retile(_)) => Err(e),
        Err(_) => first,
    }
}

/// How far past [`SPREAD_BITS_PER_ANGLE`] a first file's angles must
/// spread for [`at_size_auto`] to switch to coarser angles without
/// landing the finer search (its files' bits per angle move by less than
/// this between the first run and the landed one on the corpus).
const EARLY_MARGIN: f64 = 0.25;

/// `c` reporting the whole encode's work and memory.
fn finish_report(mut c: Chosen, budget: &Budget) -> Chosen {
    c.report.work = budget.used();
    c.report.peak_memory_bytes = budget.peak_memory();
    c
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

/// Size against edge length near the request, from runs already made
/// for it: where a later search (other angle bits, other tips, a few
/// bytes less) starts, so that it needs about two runs instead of a
/// whole search from the thesis's estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prior {
    /// The edge length at which the runs' size model meets the request
    /// (the chosen file's L, moved along the slope by how far that file
    /// missed the request).
    pub edge_length: f64,
    /// Its angle bits.
    pub angle_bits: u8,
    /// −d ln(size) / d ln(L) measured between runs, or [`SLOPE`].
    pub slope: f64,
}

impl Prior {
    /// Where a search with `angle_bits` starts: one bit less per angle
    /// buys about 1/0.91² as many triangles at the same size (measured,
    /// BENCHMARKS.md "Angle bits chosen by rate control").
    fn start(&self, angle_bits: u8) -> Start {
        let bits = f64::from(self.angle_bits) - f64::from(angle_bits);
        Start {
            l: self.edge_length * 0.91f64.powf(bits),
            slope: self.slope,
        }
    }
}

/// Where a search starts, and the slope it assumes until it measures one.
#[derive(Clone, Copy, Debug)]
struct Start {
    l: f64,
    slope: f64,
}

/// The slope −d ln(size)/d ln(L) assumed before two runs measure it: the
/// triangle count goes as 1/L², but coarser triangles cost more bits
/// each (their dihedral angles spread wider), and the header and the
/// parts kept losslessly do not shrink at all (measured 1.4–1.9 between
/// runs on the corpus at 0.5–8 b/v).
pub const SLOPE: f64 = 1.8;
/// Bits per retiled triangle the first run of a search assumes (the
/// thesis's estimate assumes 4; corpus files at 0.5–8 b/v take 1.3–2.3,
/// more only where the header or lossless parts dominate a tiny file).
const FIRST_BITS_PER_TRIANGLE: f64 = 2.0;

/// The search of [`at_size`], from `start` when given, else from the
/// thesis's estimate at [`FIRST_BITS_PER_TRIANGLE`].
///
/// Each run after the first steps to where the size model through the
/// runs so far meets the aim: between the nearest runs on either side of
/// it once there are both (interpolating ln size against ln L), else
/// from the nearest run along the slope last measured between two runs
/// (or the prior's). The search stops early, with the nearest file, where
/// size does not answer L: twice a step towards the aim moved the size
/// away from it (the header and parts kept losslessly make tiny requests
/// unreachable), or the model asks for an L already run.
fn search(
    pieces: &[Piece],
    target: u64,
    max_bytes: Option<u64>,
    knobs: Knobs,
    budget: &Budget,
    start: Option<Start>,
    leave_at: Option<f64>,
) -> Result<Chosen, Error> {
    // A cap below the target is the real target.
    let target = max_bytes.map_or(target, |cap| target.min(cap));
    let area: f64 = pieces.iter().map(|p| p.area).sum();
    let s_bits = 8.0 * target as f64;
    let Start { mut l, slope } = start.unwrap_or_else(|| Start {
        l: (4.0 * area / (3f64.sqrt() * s_bits / FIRST_BITS_PER_TRIANGLE)).sqrt(),
        slope: SLOPE,
    });
    let cap = max_bytes.unwrap_or(u64::MAX);
    // With the cap at the target, aim a little below it so that a run
    // lands inside [target − 3%, target].
    let aim = if cap <= target {
        (1.0 - TOLERANCE / 2.0) * target as f64
    } else {
        target as f64
    };
    let l_max = pieces
        .iter()
        .map(|p| p.mesh.bbox_diagonal())
        .fold(0.0, f64::max);
    let l_max = if l_max > 0.0 { l_max } else { f64::INFINITY };
    let mut attempts = Vec::new();
    // Successful runs: (L, size).
    let mut done: Vec<(f64, u64)> = Vec::new();
    let mut measured: Option<f64> = None;
    let mut stalls = 0u32;
    let mut best: Option<(f64, Run)> = None;
    let score = |size: u64| {
        if size > cap {
            f64::INFINITY
        } else {
            (size as f64 / target as f64).ln().abs()
        }
    };
    let off = |size: u64| (size as f64 / aim).ln();
    // Whether a run fails changes abruptly and unpredictably with L and
    // with the start vertex (one gate somewhere meets a pinched front), so
    // failures say nothing about larger or smaller L and must not bracket
    // the search: a failed run is retried at the same L from the next
    // flattest start vertex, an independent trial.
    let mut fails = 0u32;
    let mut failing_from: Option<f64> = None;
    let mut left = false;
    for _ in 0..MAX_RUNS {
        match run(pieces, l, knobs, fails, budget)? {
            Ok(file) => {
                fails = 0;
                failing_from = None;
                let size = file.0.len() as u64;
                attempts.push(Attempt {
                    edge_length: l,
                    outcome: Ok(size),
                });
                // The caller's angle bits are already known to be wrong:
                // this file tells where the next search starts.
                let found = within_tolerance(size, target) && size <= cap;
                if !found && leave_at.is_some_and(|b| bits_per_angle(&file.1) >= b) {
                    left = true;
                    best = Some((l, file));
                    break;
                }
                let better = best
                    .as_ref()
                    .is_none_or(|(_, b)| score(size) < score(b.0.len() as u64));
                if better {
                    best = Some((l, file));
                }
                if found {
                    break;
                }
                // A step towards the aim that moved the size away from it
                // (not one that overshot it).
                if let Some(&(lp, sp)) = done.last() {
                    let away = off(size) * off(sp) > 0.0 && off(size).abs() > off(sp).abs();
                    if away && (l / lp).ln().abs() > 0.01 {
                        stalls += 1;
                    }
                    // Sizes jitter by a few percent between close L: only
                    // runs far enough apart measure a slope.
                    let p = (sp as f64 / size as f64).ln() / (l / lp).ln();
                    if (l / lp).ln().abs() > SLOPE_SPAN && (0.7..=3.0).contains(&p) {
                        measured = Some(p);
                    }
                }
                done.push((l, size));
                if stalls >= 2 {
                    break;
                }
                // No piece is retiled beyond its own size: all are kept
                // losslessly there, and larger L change nothing.
                let next = next_length(&done, aim, measured.unwrap_or(slope)).min(l_max);
                // The model asks for a retiling already made: nothing left
                // to learn.
                if already_run(&done, next) {
                    break;
                }
                // Nor again where a run failed: its start vertices would
                // fail as before (a search on bunny-1m once alternated
                // between a failing L and the one 3% below it).
                l = clear_of(next, &attempts);
            }
            Err(f) => {
                attempts.push(Attempt {
                    edge_length: l,
                    outcome: Err(f),
                });
                fails += 1;
                // Retry from the next flattest start vertex, and after the
                // first retry also at another L, alternately below and
                // above where the failures began by doubling steps (−3%,
                // +3%, −6%, +6%, −12%, …): failures come and go over a few
                // percent of L, a thin part of the shape (the thesis's
                // failure case) needs a smaller L, a cap may forbid one,
                // and a first estimate can start deep in a failing range.
                let base = *failing_from.get_or_insert(l);
                if fails >= 2 {
                    let n = fails - 1;
                    let magnitude = FAIL_STEP * 2f64.powi(n.div_ceil(2) as i32 - 1);
                    // Down by at most FAIL_DOWN: a retiling's cost grows
                    // as 1/L², and a far smaller L overshoots the size.
                    l = if n % 2 == 1 {
                        base * (1.0 - magnitude.min(FAIL_DOWN))
                    } else {
                        base * (1.0 + magnitude)
                    };
                }
            }
        }
    }
    let slope = measured.unwrap_or(slope);
    let (edge_length, (bytes, stats, pieces, seeds)) = best
        .filter(|(_, b)| left || b.0.len() as u64 <= cap)
        .ok_or_else(|| infeasible(&attempts))?;
    let first_failed = attempts.first().is_some_and(|a| a.outcome.is_err());
    // The prior is where the model puts the target, not the file's L:
    // an early leave or a landing off-centre says which way to go.
    let size = bytes.len() as f64;
    Ok(Chosen {
        prior: Prior {
            edge_length: edge_length * (size / target as f64).powf(1.0 / slope),
            angle_bits: knobs.angle_bits,
            slope,
        },
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
        seeds,
    })
}

/// The next L to run: where ln size, as a function of ln L through the
/// runs `done`, meets ln `aim`. Between the nearest runs on either side
/// of the aim when both exist and size falls with L between them; else
/// from the run nearest the aim with `slope`.
fn next_length(done: &[(f64, u64)], aim: f64, slope: f64) -> f64 {
    let off = |s: u64| (s as f64 / aim).ln();
    // The run nearest the aim among those `keep` accepts; on a tie (small
    // files come in steps of a few bytes) the latest.
    let nearest = |keep: &dyn Fn(u64) -> bool| {
        done.iter()
            .filter(|&&(_, s)| keep(s))
            .fold(None, |best: Option<(f64, u64)>, &(l, s)| match best {
                Some(b) if off(b.1).abs() < off(s).abs() => Some(b),
                _ => Some((l, s)),
            })
    };
    let ran = |l: f64| already_run(done, l);
    if let (Some((ls, ss)), Some((ll, sl))) =
        (nearest(&|s| off(s) < 0.0), nearest(&|s| off(s) >= 0.0))
    {
        // Small file at the larger L: interpolate on the log-log chord,
        // or halve the bracket where that gives an L already run.
        if ls > ll {
            let t = off(sl) / (off(sl) - off(ss));
            let next = (ll.ln() + t * (ls / ll).ln()).exp();
            return if ran(next) { (ls * ll).sqrt() } else { next };
        }
    }
    // From the nearest run; where that asks for an L already run (sizes
    // jitter by a few percent between close L, as much as is left to
    // correct), a step twice or three times as long draws a new retiling.
    let (l, s) = nearest(&|_| true).expect("a run was made");
    (1..=3)
        .map(|k| l * (s as f64 / aim).powf(f64::from(k) / slope))
        .find(|&next| !ran(next))
        .unwrap_or(l)
}

/// Step of L between retries after failures, relative.
const FAIL_STEP: f64 = 0.03;
/// The most a retry after failures lowers L, relative.
const FAIL_DOWN: f64 = 0.12;

/// `l`, or the nearest of l·(1 ± k·1.5%), k = 1, 2, …, that lies
/// farther than [`FAILED_NEAR`] (relative) from every L tried that failed.
fn clear_of(l: f64, attempts: &[Attempt]) -> f64 {
    let failed = |x: f64| {
        attempts
            .iter()
            .any(|a| a.outcome.is_err() && (x / a.edge_length).ln().abs() < FAILED_NEAR)
    };
    (0..=8)
        .flat_map(|k| [1.0 + 0.015 * f64::from(k), 1.0 - 0.015 * f64::from(k)])
        .map(|f| l * f)
        .find(|&x| !failed(x))
        .unwrap_or(l)
}

/// How near (|ln L|) a failed run's L a new run is not made.
const FAILED_NEAR: f64 = 0.005;

/// Least |ln L| between two runs for their sizes to measure a slope.
const SLOPE_SPAN: f64 = 0.04;

/// Whether a successful run of `done` was made at `l` (within [`REPEAT`]).
fn already_run(done: &[(f64, u64)], l: f64) -> bool {
    done.iter().any(|&(ld, _)| (l / ld).ln().abs() < REPEAT)
}

/// Edge lengths closer than this (relative) count as the same run.
const REPEAT: f64 = 0.002;

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_step_never_lands_on_an_edge_length_that_failed() {
        let failed = |l| Attempt {
            edge_length: l,
            outcome: Err(Failure::Runaway),
        };
        let ok = |l| Attempt {
            edge_length: l,
            outcome: Ok(100),
        };
        // A successful run there does not count: only failures repel.
        assert_eq!(clear_of(1.0, &[ok(1.0)]), 1.0);
        let attempts = [failed(1.0), failed(1.015), ok(0.97)];
        let l = clear_of(1.001, &attempts);
        assert!(
            attempts
                .iter()
                .filter(|a| a.outcome.is_err())
                .all(|a| (l / a.edge_length).ln().abs() >= FAILED_NEAR),
            "{l}"
        );
        assert!((l / 1.001).ln().abs() < 0.04, "{l} moved too far");
    }
}
