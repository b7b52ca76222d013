//! Rate control: the edge length L that makes the file the requested size
//! (thesis §7.4; design notes §5 "L from a target size").
//!
//! The start is the thesis's estimate L₀ = √(16A/(√3·S)), S in bits, which
//! assumes 4 bits per equilateral triangle. Then, since the triangle count
//! goes as 1/L², each run rescales L by √(O/S) (O the size obtained), a
//! secant step on log L against log size, bracketed by the best runs on
//! either side of the target. A run that fails (some gate found no valid
//! triangle) is retried at L nudged by a fraction of a percent: failures
//! are not monotonic in L (measured on horse: runs fail and succeed
//! alternately over a few percent of L), so they cannot bracket a binary
//! search the way the thesis's "largest L that works" search assumed.
//!
//! The result is the run nearest the request among those within
//! `max_bytes`; it lands within `TOLERANCE` of the request unless no run
//! could (reported, never silent).

use super::{retile, Failure, RetileOptions};
use crate::swing::{Retiled, SwingStats};
use crate::{CornerTable, Error, TriMesh};

/// Relative size error accepted without further runs.
pub const TOLERANCE: f64 = 0.03;
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
}

/// A finished encoding.
pub struct Chosen {
    pub bytes: Vec<u8>,
    pub stats: SwingStats,
    pub report: RateReport,
}

fn run(
    mesh: &TriMesh,
    table: &CornerTable,
    l: f64,
    bits: u8,
) -> Result<Result<(Vec<u8>, SwingStats), Failure>, Error> {
    let opt = RetileOptions {
        edge_length: l,
        angle_bits: bits,
        start_vertex: None,
    };
    match retile(mesh, table, &opt) {
        Ok(r) => Ok(Ok(write(&r)?)),
        Err(f) => Ok(Err(f)),
    }
}

fn write(r: &Retiled) -> Result<(Vec<u8>, SwingStats), Error> {
    crate::swing::write(r)
}

/// Encodes at the given L; if it fails, at the largest L below it that
/// works (found by small steps down, then bisection).
pub fn at_length(mesh: &TriMesh, table: &CornerTable, l: f64, bits: u8) -> Result<Chosen, Error> {
    let mut attempts = Vec::new();
    let (mut good, mut bad): (Option<(f64, Vec<u8>, SwingStats)>, f64) = (None, f64::INFINITY);
    let mut next = l;
    for _ in 0..MAX_RUNS {
        match run(mesh, table, next, bits)? {
            Ok((bytes, stats)) => {
                attempts.push(Attempt {
                    edge_length: next,
                    outcome: Ok(bytes.len() as u64),
                });
                let done = next == l;
                good = Some((next, bytes, stats));
                if done {
                    break;
                }
            }
            Err(f) => {
                attempts.push(Attempt {
                    edge_length: next,
                    outcome: Err(f),
                });
                bad = next;
            }
        }
        // Bisect on log L between the largest success and the smallest
        // failure; without a success yet, step down by 2% (whether a run
        // fails changes abruptly with L, so a slightly smaller L usually
        // works, while halving would give away most of the rate).
        next = match &good {
            Some((g, ..)) if bad / g < 1.02 => break,
            Some((g, ..)) => (g * bad).sqrt(),
            None => bad * 0.98,
        };
        if next < l / 2.0 {
            break;
        }
    }
    let (edge_length, bytes, stats) = good.ok_or_else(|| infeasible(&attempts))?;
    Ok(Chosen {
        bytes,
        stats,
        report: RateReport {
            requested_bytes: None,
            edge_length,
            reduced: edge_length != l,
            within_tolerance: true,
            attempts,
        },
    })
}

/// Encodes to about `target` bytes, never more than `max_bytes`.
pub fn at_size(
    mesh: &TriMesh,
    table: &CornerTable,
    target: u64,
    max_bytes: Option<u64>,
    bits: u8,
) -> Result<Chosen, Error> {
    // A cap below the target is the real target.
    let target = max_bytes.map_or(target, |cap| target.min(cap));
    let area = mesh.area();
    let s_bits = 8.0 * target as f64;
    let mut l = (16.0 * area / (3f64.sqrt() * s_bits)).sqrt();
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
    let mut best: Option<(f64, Vec<u8>, SwingStats)> = None;
    let score = |size: u64| {
        if size > cap {
            f64::INFINITY
        } else {
            (size as f64 / target as f64).ln().abs()
        }
    };
    // `wanted` is the L the search asks for; after failures the run is
    // made at `wanted` nudged by ±0.6%, ±1.2%, …: whether a run fails
    // changes abruptly and unpredictably with L (one gate somewhere meets
    // a pinched front), so failures say nothing about larger or smaller
    // L and must not bracket the search.
    let mut wanted = l;
    let mut fails = 0u32;
    for _ in 0..MAX_RUNS {
        match run(mesh, table, l, bits)? {
            Ok((bytes, stats)) => {
                fails = 0;
                let size = bytes.len() as u64;
                attempts.push(Attempt {
                    edge_length: l,
                    outcome: Ok(size),
                });
                let better = best
                    .as_ref()
                    .is_none_or(|(_, b, _)| score(size) < score(b.len() as u64));
                if better {
                    best = Some((l, bytes, stats));
                }
                if (size as f64 - target as f64).abs() <= TOLERANCE * target as f64 && size <= cap {
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
                wanted = next;
                l = next;
            }
            Err(f) => {
                attempts.push(Attempt {
                    edge_length: l,
                    outcome: Err(f),
                });
                fails += 1;
                // Four failures in a row around one L: the shape is too
                // thin for it (the thesis's failure case); look 10% lower.
                if fails % 4 == 0 {
                    wanted *= 0.9;
                }
                let k = f64::from(fails % 4);
                let sign = if fails % 2 == 1 { -1.0 } else { 1.0 };
                l = wanted * (1.0 + sign * 0.006 * k);
            }
        }
    }
    let (edge_length, bytes, stats) = best
        .filter(|(_, b, _)| b.len() as u64 <= cap)
        .ok_or_else(|| infeasible(&attempts))?;
    let size = bytes.len() as f64;
    let first_failed = attempts.first().is_some_and(|a| a.outcome.is_err());
    Ok(Chosen {
        report: RateReport {
            requested_bytes: Some(target),
            edge_length,
            reduced: first_failed,
            within_tolerance: (size - target as f64).abs() <= TOLERANCE * target as f64,
            attempts,
        },
        bytes,
        stats,
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
