//! The simplified method: quadric simplification of the cleaned input,
//! then the lossless mode (`crate::simplify`): the largest face count and
//! the quantization of lowest measured error whose file fits the budget.
//!
//! Three searches ([`Search`]): the full one climbs over quantizations
//! and measures each file against the input (`simplify::best_fit`); the
//! lean one (effort `default`) climbs alike at about half the work
//! (`simplify::Climb::Lean`); the quick one (effort `fast`) fits two
//! quantizations, the start and the one its face count predicts, and
//! ranks them with a few samples (`simplify::quick_fit`). All return a
//! file that fits the budget.

use super::method::{Ask, CodingMethod, Job, Made};
use super::stats::{Method, MethodStats, SimplifiedStats};
use crate::simplify::Climb;
use crate::Error;

/// How far the simplified method searches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Search {
    /// Every promising quantization, each file refitted and measured.
    Full,
    /// The same climb, ranking fits as simplified with fewer samples.
    Lean,
    /// The predicted quantization only, nothing measured.
    Quick,
}

/// The simplified method.
pub(crate) struct Simplified {
    /// Its search.
    pub search: Search,
}

impl Simplified {
    /// The full search (effort `max`).
    pub const FULL: Simplified = Simplified {
        search: Search::Full,
    };
    /// The lean search (effort `default`).
    pub const LEAN: Simplified = Simplified {
        search: Search::Lean,
    };
    /// The quick search (effort `fast`).
    pub const QUICK: Simplified = Simplified {
        search: Search::Quick,
    };
}

impl CodingMethod for Simplified {
    fn method(&self) -> Method {
        Method::Simplified
    }

    fn runs_when_whole_fits(&self) -> bool {
        true
    }

    fn carries_attributes(&self, _streams: &[crate::AttributeStream]) -> bool {
        true
    }

    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error> {
        let budget =
            super::request::budget(ask.target, job.input_vertices, ask.max_bytes, "simplified")?;
        encode_at(job, budget, self.search).map(Some)
    }
}

/// The simplified file at `budget` bytes.
pub(crate) fn encode_at(job: &Job<'_, '_>, budget: u64, search: Search) -> Result<Made, Error> {
    let s = job.simplifier();
    let reference = || job.reference();
    // The reference surface (a tree over the whole input) is built beside
    // the search's first fit, which does not need it: on two cores its
    // time leaves the wall clock (the bytes are the same either way).
    let (made, found) = rayon::join(
        || job.reference().map(drop),
        || -> Result<_, Error> {
            Ok(match search {
                Search::Full | Search::Lean => {
                    let climb = match search {
                        Search::Lean => Climb::Lean,
                        _ => Climb::Full(crate::AUTO_SAMPLES),
                    };
                    crate::simplify::best_fit(s, budget, &reference, climb)?
                        .map(|(fit, l2)| (fit, Some(l2)))
                }
                Search::Quick => {
                    crate::simplify::quick_fit(s, budget, &reference)?.map(|fit| (fit, None))
                }
            })
        },
    );
    made?;
    let found = found?;
    let Some((fit, l2_relative)) = found else {
        return Err(crate::SizeError {
            requested: budget,
            smallest: crate::simplify::smallest_bytes(s)?,
        }
        .into());
    };
    // The winner's figures, from the same deterministic encode (the
    // whole mesh's were kept when its file was made: on a million
    // triangles a cleaning and an encode, half a second, not repeated).
    let (bytes, lossless, seeds) = if fit.faces >= s.faces() {
        let (bytes, lossless) = s.whole_file(fit.qp)?;
        (bytes, lossless, None)
    } else if let (Some(lossless), false) = (fit.stats.clone(), job.options.origins) {
        // The search coded this file already (on bunny-1m at 2 b/v the
        // winner's cleaning and encode, 65 ms, are not repeated).
        (fit.bytes.clone(), lossless, None)
    } else {
        let (bytes, lossless, source, cleaned) = s.file(fit.faces, &fit.mesh, fit.qp)?;
        let seeds = job
            .options
            .origins
            .then(|| seeds(s, fit.faces, &fit.mesh, &cleaned, &source));
        (bytes, lossless, seeds)
    };
    debug_assert_eq!(bytes, fit.bytes, "lossless encoding is deterministic");
    let simplified = SimplifiedStats {
        input_faces: s.faces() as u64,
        faces: lossless.triangles,
        qp: fit.qp,
        l2_relative,
    };
    Ok(Made {
        bytes,
        whole: simplified.faces >= simplified.input_faces,
        stats: MethodStats::Simplified {
            lossless,
            simplified,
        },
        l2_relative,
        seeds,
    })
}

/// For each vertex of a simplification's file as decoded (`source`: the
/// cleaned mesh's vertex each decoded vertex is), the reference vertex
/// that the simplification kept for it (`Simplifier::sources`).
/// `made` is `Simplifier::simplify(target)`, refitted or not (a refit
/// keeps vertex numbers); cleaning moves no vertex, so a cleaned vertex
/// is `made`'s vertex at its position.
pub(crate) fn seeds(
    s: &crate::simplify::Simplifier<'_>,
    target: u32,
    made: &crate::TriMesh,
    cleaned: &crate::TriMesh,
    source: &[u32],
) -> Vec<u32> {
    let sources = s.sources(target);
    let made = crate::mesh::clean::PositionIndex::new(&made.positions);
    source
        .iter()
        .map(|&c| {
            let v = made.find(cleaned.positions.get(c as usize)?)?;
            sources.get(v as usize).copied()
        })
        .map(|seed| seed.unwrap_or(u32::MAX))
        .collect()
}
