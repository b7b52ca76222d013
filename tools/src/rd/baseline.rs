//! The `baseline`, `displaced` and `auto` configurations: the encoder's
//! simplify-then-lossless method (`swm::simplify`,
//! `EncodeMode::Simplified`, always with its full search), its
//! displaced-subdivision method (`EncodeMode::Displaced`) and its
//! automatic mode (`EncodeMode::Auto`, at the effort level the
//! configuration names: `auto` at `max`, `auto-default`, `auto-fast`),
//! each asked for the budget and capped at it, timed whole (search and
//! measurements included) and measured here with the row's samples.
//!
//! "Simplify, then lossless" is what a user does today without retiling
//! and the curve SwingWrapper must beat (thesis Table 7-3; the shared
//! corpus's "quadric simplification + Draco" figures). The search itself
//! lives in the library, so `swm encode --mode lossless --bpv R` and this
//! row are the same file.

use crate::error::CliError;
use crate::rd::measure::measure;
use crate::rd::table::Coded;
use std::time::Instant;

/// The simplified method at one budget; `None` if nothing fits it.
pub fn run(
    case: &crate::rd::case::Case,
    budget: u64,
    samples: u64,
) -> Result<Option<Coded>, CliError> {
    let mode = swm::EncodeMode::Simplified {
        target: swm::SwingTarget::Bytes(budget),
        max_bytes: Some(budget),
    };
    coded(case, mode, swm::Effort::Max, samples)
}

/// The displaced-subdivision method alone at one budget; `None` if
/// nothing fits it.
pub fn run_displaced(
    case: &crate::rd::case::Case,
    budget: u64,
    samples: u64,
) -> Result<Option<Coded>, CliError> {
    let mode = swm::EncodeMode::Displaced {
        target: swm::SwingTarget::Bytes(budget),
        max_bytes: Some(budget),
    };
    coded(case, mode, swm::Effort::Max, samples)
}

/// The automatic mode at one budget and effort level; `None` if nothing
/// fits it.
pub fn run_auto(
    case: &crate::rd::case::Case,
    budget: u64,
    effort: swm::Effort,
    samples: u64,
) -> Result<Option<Coded>, CliError> {
    let mode = swm::EncodeMode::Auto {
        target: swm::SwingTarget::Bytes(budget),
        max_bytes: Some(budget),
    };
    coded(case, mode, effort, samples)
}

/// Encodes (timed), decodes and measures; the row's `qp` is the
/// simplified or displaced file's quantization (the displaced file's
/// base's) or the SwingWrapper file's angle bits.
fn coded(
    case: &crate::rd::case::Case,
    mode: swm::EncodeMode,
    effort: swm::Effort,
    samples: u64,
) -> Result<Option<Coded>, CliError> {
    let options = swm::EncodeOptions {
        mode,
        effort,
        ..Default::default()
    };
    let start = Instant::now();
    let encoded = match swm::encode(&case.mesh, &options) {
        Ok(e) => e,
        Err(swm::Error::Size(_)) => return Ok(None),
        Err(e) => return Err(case.err(e)),
    };
    let encode_s = start.elapsed().as_secs_f64();
    let stats = &encoded.stats;
    let displaced = match &stats.method {
        swm::MethodStats::Displaced(d) => Some(d),
        _ => None,
    };
    let qp = match (stats.simplified(), stats.swing(), displaced) {
        (Some(s), _, _) => s.qp,
        (_, Some(s), _) => s.angle_bits,
        (_, _, Some(d)) => d.qp,
        _ => 0,
    };
    let mut coded = measure(
        case,
        qp,
        samples,
        &encoded.bytes,
        encode_s,
        &Default::default(),
    )?;
    let mixed = stats.chosen() == swm::Method::Mixed;
    coded.method = match (stats.simplified(), stats.swing()) {
        (Some(s), _) if s.faces >= s.input_faces => "whole",
        (Some(_), _) => "simplified",
        (_, Some(_)) if mixed => "mixed",
        (_, Some(_)) => "swing",
        _ if displaced.is_some() => "displaced",
        _ => "lossless",
    }
    .into();
    Ok(Some(coded))
}
