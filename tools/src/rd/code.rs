//! Running a configuration: [`Config::run`] codes one case at one
//! budget, with the lossless and SwingWrapper configurations here and the
//! library's simplified and automatic modes in `baseline`.
//!
//! Kept apart from `config`, which only names the configurations, so that
//! the table can store a `Config` without importing the code that runs it.

use crate::error::CliError;
use crate::rd::baseline;
use crate::rd::case::{swing_options, Case};
use crate::rd::config::Config;
use crate::rd::measure::{finish, measure};
use crate::rd::table::{Coded, Outcome};
use std::borrow::Cow;

impl Config {
    /// Codes `case` into at most `budget` bytes.
    /// `samples`: face samples per direction of the final distance.
    pub fn run(self, case: &Case, budget: u64, samples: u64) -> Result<Outcome, CliError> {
        let coded = match self {
            Config::Lossless => lossless(case, budget, samples)?,
            Config::Baseline => baseline::run(case, budget, samples)?,
            Config::Displaced => baseline::run_displaced(case, budget, samples)?,
            Config::Auto | Config::AutoDefault | Config::AutoFast => {
                let effort = self
                    .effort()
                    .expect("the automatic configurations name a level");
                baseline::run_auto(case, budget, effort, samples)?
            }
            Config::Swing
            | Config::SwingPlain
            | Config::SwingOnSurface
            | Config::SwingAdaptive
            | Config::SwingSharpen
            | Config::SwingSharpenBend => {
                return swing(case, budget, samples, self.tuning(), &self.decode_options())
            }
        };
        Ok(coded.map_or(Outcome::Infeasible, Outcome::Coded))
    }
}

/// The lossless mode at the largest qp that fits. File sizes fall with qp,
/// so the first fit from the top is the answer.
fn lossless(case: &Case, budget: u64, samples: u64) -> Result<Option<Coded>, CliError> {
    for qp in (swm::geometry::MIN_BITS..=swm::geometry::MAX_BITS).rev() {
        if case.lossless_size(qp)? <= budget {
            let mut coded = finish(case, qp, samples, || Ok(Cow::Borrowed(&case.mesh)))?;
            coded.method = "lossless".into();
            return Ok(Some(coded));
        }
    }
    Ok(None)
}

/// SwingWrapper asked for `budget` bytes with `budget` as its cap, so
/// the file lands within 3% below the budget when the rate control
/// manages, and never above it; otherwise exactly what `swm encode` does
/// by default (angle bits chosen by rate control, reported in the row's
/// `qp` column, and `tuning`, which is the default except for ablation
/// rows). The encoder's own
/// errors become the row's status: a mesh the mode does not take is
/// `n/a`; a [`swm::RetileError`] where some retiling worked but no file it
/// made fitted the cap is `infeasible`; one where every retiling broke
/// down is `failed`. Every other error (a file that does not decode) stops
/// the run. `post` is how the file is decoded (Sharpen&Bend or not).
fn swing(
    case: &Case,
    budget: u64,
    samples: u64,
    tuning: swm::SwingTuning,
    post: &swm::DecodeOptions,
) -> Result<Outcome, CliError> {
    let cell = case.swing_file(budget, tuning);
    let error = match cell.get().expect("swing_file fills its cell") {
        Ok((bytes, encode_s)) => {
            // The angle bits rate control chose, as the file says.
            let info = swm::inspect(bytes, &swm::Limits::default()).map_err(|e| case.err(e))?;
            let bits = info.swing.map_or(0, |s| s.angle_bits);
            let mut coded = measure(case, bits, samples, bytes, *encode_s, post)?;
            coded.method = "swing".into();
            return Ok(Outcome::Coded(coded));
        }
        Err(e) => e,
    };
    Ok(match error {
        swm::Error::Topology(e @ swm::TopologyError::NotASphere { .. }) => {
            Outcome::NotApplicable { why: e.to_string() }
        }
        swm::Error::Retile(e) if e.successes > 0 => Outcome::Infeasible,
        e @ swm::Error::Retile(_) => Outcome::Failed { why: e.to_string() },
        // Anything else is a bug that stops the run; the cache holds the
        // error by reference, so encode again (deterministically) to own it.
        _ => {
            return match swm::encode(&case.mesh, &swing_options(budget, tuning)) {
                Err(e) => Err(case.err(e)),
                Ok(_) => Ok(Outcome::Failed {
                    why: "the encoder failed, then succeeded on the same input".into(),
                }),
            };
        }
    })
}
