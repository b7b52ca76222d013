//! The configurations an rd table compares, and the lossless one.
//!
//! A configuration turns (mesh, byte budget) into a `.swm` file that fits
//! the budget, or says that none does, that its encoder gave up, or that
//! it does not take the mesh at all. Adding one is a variant here, its
//! name, and the function its `run` arm calls; [`measure`] does the timing and measuring that every
//! configuration shares.

use crate::rd::case::{encode, swing_options, Case};
use crate::rd::table::{Coded, Outcome};
use crate::CliError;
use std::borrow::Cow;
use std::time::Instant;
use swm::TriMesh;

/// A way of coding a mesh into a byte budget. Rows sort in this order.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Config {
    /// swm's lossless mode alone: the input's triangles, at the largest qp
    /// (6..=24) whose file fits.
    Lossless,
    /// "Simplify, then lossless" (thesis Table 7-3): quadric edge collapse
    /// (swm's own) to the face count and qp (6..=16) with the lowest L2
    /// that fits (`swm encode --mode lossless --size B`).
    Baseline,
    /// `swm encode`'s default: SwingWrapper or `baseline`, whichever the
    /// encoder measures closer (`--mode auto`).
    Auto,
    /// SwingWrapper as `swm encode` runs it by default, asked for the
    /// budget and capped at it, decoded as `swm decode` does by default
    /// (following the file's post-processing hint).
    Swing,
    /// The `swing` file decoded plain, whatever its hint says.
    #[value(name = "swing-plain")]
    SwingPlain,
    /// `swing` with every tip on the input surface, as the thesis places
    /// them (the ablation of approximating tips).
    #[value(name = "swing-on-surface")]
    SwingOnSurface,
    /// `swing` with the edge length following the shape (adaptive
    /// sampling, `swm encode --adaptive`; not yet the default).
    #[value(name = "swing-adaptive")]
    SwingAdaptive,
    /// The `swing` file decoded with EdgeSharpener (no extra bits).
    #[value(name = "swing+sharpen")]
    SwingSharpen,
    /// The `swing` file decoded with EdgeSharpener and one Bender step.
    #[value(name = "swing+sharpen+bend")]
    SwingSharpenBend,
}

impl Config {
    /// Every configuration, in table order.
    pub const ALL: [Config; 9] = [
        Config::Lossless,
        Config::Baseline,
        Config::Auto,
        Config::Swing,
        Config::SwingPlain,
        Config::SwingOnSurface,
        Config::SwingAdaptive,
        Config::SwingSharpen,
        Config::SwingSharpenBend,
    ];

    /// What `swm rd` runs without `--configs`: all but the ablation rows.
    pub fn default_set() -> Vec<Config> {
        Config::ALL
            .into_iter()
            .filter(|&c| !matches!(c, Config::SwingOnSurface | Config::SwingAdaptive))
            .collect()
    }

    /// The name used on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            Config::Lossless => "lossless",
            Config::Baseline => "baseline",
            Config::Auto => "auto",
            Config::Swing => "swing",
            Config::SwingPlain => "swing-plain",
            Config::SwingOnSurface => "swing-on-surface",
            Config::SwingAdaptive => "swing-adaptive",
            Config::SwingSharpen => "swing+sharpen",
            Config::SwingSharpenBend => "swing+sharpen+bend",
        }
    }

    /// How the decoder post-processes this configuration's files.
    fn decode_options(self) -> swm::DecodeOptions {
        let (sharpen, bend_steps) = match self {
            Config::SwingPlain => (Some(false), Some(0)),
            Config::SwingSharpen => (Some(true), Some(0)),
            Config::SwingSharpenBend => (Some(true), Some(1)),
            // The file's hint (the decoder's default).
            _ => (None, None),
        };
        swm::DecodeOptions {
            sharpen,
            bend_steps,
            ..Default::default()
        }
    }

    /// What this configuration asks of the SwingWrapper encoder.
    fn tuning(self) -> swm::SwingTuning {
        swm::SwingTuning {
            approximate_tips: self != Config::SwingOnSurface,
            fit_tips: self != Config::SwingOnSurface,
            adaptive_density: self == Config::SwingAdaptive,
            front_contexts: true,
            loop_start: true,
            crease_tips: true,
            post_hint: true,
        }
    }

    /// The configuration a table names.
    pub fn from_name(name: &str) -> Option<Config> {
        Config::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Codes `case` into at most `budget` bytes.
    /// `samples`: face samples per direction of the final distance.
    pub fn run(self, case: &Case, budget: u64, samples: u64) -> Result<Outcome, CliError> {
        let coded = match self {
            Config::Lossless => lossless(case, budget, samples)?,
            Config::Baseline => crate::rd::baseline::run(case, budget, samples)?,
            Config::Auto => crate::rd::baseline::run_auto(case, budget, samples)?,
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

/// Makes the chosen mesh again (timed with the encode), encodes it at
/// `qp`, decodes the file (timed) and measures the decoded mesh against
/// the reference. Searches run on cached results; the times here are those
/// of one clean pass.
pub fn finish<'a>(
    case: &'a Case,
    qp: u8,
    samples: u64,
    make: impl FnOnce() -> Result<Cow<'a, TriMesh>, CliError>,
) -> Result<Coded, CliError> {
    let start = Instant::now();
    let mesh = make()?;
    let bytes = encode(&mesh, qp).map_err(|e| case.err(e))?;
    let encode_s = start.elapsed().as_secs_f64();
    measure(case, qp, samples, &bytes, encode_s, &Default::default())
}

/// Decodes a file made in `encode_s` seconds (timed) and measures the
/// decoded mesh against the reference. `qp` is the row's quantization
/// figure; `options` says how to decode (post-processing included in the
/// decode time). The method is left empty for the caller to name.
pub fn measure(
    case: &Case,
    qp: u8,
    samples: u64,
    bytes: &[u8],
    encode_s: f64,
    options: &swm::DecodeOptions,
) -> Result<Coded, CliError> {
    let start = Instant::now();
    let decoded = swm::decode(bytes, options).map_err(|e| case.err(e))?;
    let decode_s = start.elapsed().as_secs_f64();
    let (l2_rel, hausdorff_rel) = case.distance(&decoded, samples)?;
    Ok(Coded {
        bytes: bytes.len() as u64,
        faces: decoded.triangles.len() as u64,
        qp,
        l2_rel,
        hausdorff_rel,
        encode_s,
        decode_s,
        method: String::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::Config;
    use clap::ValueEnum;

    /// The command line and the tables must spell configurations alike.
    #[test]
    fn names_match_the_command_line() {
        for c in Config::ALL {
            let v = c.to_possible_value().expect("visible");
            assert_eq!(v.get_name(), c.name());
            assert_eq!(Config::from_name(c.name()), Some(c));
        }
        assert_eq!(Config::ALL.len(), Config::value_variants().len());
    }
}
