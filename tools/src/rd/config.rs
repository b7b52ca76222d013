//! The configurations an rd table compares, and the lossless one.
//!
//! A configuration turns (mesh, byte budget) into a `.swm` file that fits
//! the budget, or says that none does. Adding one (SwingWrapper,
//! SwingWrapper + Sharpen&Bend) is a variant here, its name, and the
//! function its `run` arm calls; [`finish`] does the timing and measuring
//! that every configuration shares.

use crate::rd::case::{encode, Case};
use crate::rd::table::Coded;
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
    /// "Simplify, then lossless" (thesis Table 7-3): quadric simplification
    /// (meshoptimizer) to the face count and qp (7..=14) with the lowest L2
    /// that fits.
    Baseline,
}

impl Config {
    /// Every configuration, in table order.
    pub const ALL: [Config; 2] = [Config::Lossless, Config::Baseline];

    /// The name used on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            Config::Lossless => "lossless",
            Config::Baseline => "baseline",
        }
    }

    /// The configuration a table names.
    pub fn from_name(name: &str) -> Option<Config> {
        Config::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Codes `case` into at most `budget` bytes; `None` if nothing fits.
    /// `samples`: face samples per direction of the final distance.
    pub fn run(self, case: &Case, budget: u64, samples: u64) -> Result<Option<Coded>, CliError> {
        match self {
            Config::Lossless => lossless(case, budget, samples),
            Config::Baseline => crate::rd::baseline::run(case, budget, samples),
        }
    }
}

/// The lossless mode at the largest qp that fits. File sizes fall with qp,
/// so the first fit from the top is the answer.
fn lossless(case: &Case, budget: u64, samples: u64) -> Result<Option<Coded>, CliError> {
    for qp in (swm::geometry::MIN_BITS..=swm::geometry::MAX_BITS).rev() {
        if case.lossless_size(qp)? <= budget {
            let coded = finish(case, qp, samples, || Ok(Cow::Borrowed(&case.mesh)))?;
            return Ok(Some(coded));
        }
    }
    Ok(None)
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
    let start = Instant::now();
    let decoded = swm::decode(&bytes, &swm::DecodeOptions::default()).map_err(|e| case.err(e))?;
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
