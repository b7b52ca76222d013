//! The displaced-subdivision method (mode 2, `crate::displaced`): a
//! quadric simplification of the input to `B` faces (refitted to the
//! input, boundaries kept by the collapse's own rules) as the base, `k`
//! levels of subdivision, one scalar per new vertex.
//!
//! Rate control: for each level count `k` in [`LEVELS`], a first guess of
//! `B` from a cost model (bits per base face, bits per new vertex; for
//! `k` > 1 from the file of `k − 1`), then at most [`TRIALS`] files, each
//! `B` moved by a secant on log size against log faces ([`search`]; the
//! second file of `k` uses the exponent the files of `k − 1` showed). The
//! file of each `k` nearest the budget without passing it is measured
//! with the chooser's distance and the closest to the input wins. A `k`
//! whose first file, measured and its error carried to the budget
//! ([`RATE_EXPONENT`]), is clearly worse than the best so far
//! ([`GIVE_UP`]) is not searched, and neither are larger ones (error
//! against `k` was unimodal in every cell measured). No loop runs until
//! convergence: at most `|LEVELS| × TRIALS` files, 4.2 on average over
//! bunny and horse at 0.5-8 b/v (6.3 before the last two rules).
//!
//! Invariant: everything input-sized is made once per encode and shared
//! (the collapse sequence, the reference tree); a file costs its base's
//! replay, refit and coding, and one line query per new vertex.

use super::method::{Ask, CodingMethod, Job, Made};
use super::stats::{DisplacedStats, Method, MethodStats};
use crate::displaced::fit::{Fallback, Target};
use crate::displaced::predict::Rule;
use crate::displaced::write::{write, Plan, Settings, Written};
use crate::{Error, SizeError};

/// Level counts tried.
const LEVELS: [usize; 3] = [1, 2, 3];
/// Files per level count.
const TRIALS: usize = 6;
/// Rate control's tolerance: a file within this fraction under the
/// budget stops the trials.
const TOLERANCE: f64 = 0.03;
/// What a base face costs with one level more, over what the file of
/// one level fewer predicts: the coarser levels' steps halve (one bit
/// more per scalar) and a smaller base costs more per face. Measured
/// 1.25-1.35 on bunny and horse at 0.5-8 b/v.
const NEXT_LEVEL_COST: f64 = 1.3;
/// Fewer base faces than this make no surface worth refining.
const MIN_BASE_FACES: u32 = 8;
/// The exponent of a file's size against its base faces that the first
/// level count's second file assumes; later level counts start from the
/// exponent their predecessor's files showed. Measured 0.60-0.87 (bunny
/// at 8 b/v, bunny-1m at 1 b/v, one to three levels).
const SLOPE: f64 = 0.85;
/// How error falls with a file's size near the budget (L2 ∝
/// bytes^−exponent): the error of a first file off the budget is carried
/// to the budget with it. Measured on bunny over 0.5-8 b/v: 0.83-0.87.
const RATE_EXPONENT: f64 = 0.85;
/// A level count whose first file's error, carried to the budget, is
/// more than this fraction above the best level count's is not searched.
const GIVE_UP: f64 = 0.10;

/// The displaced-subdivision method and its settings.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Displaced {
    pub settings: Settings,
}

impl Displaced {
    /// The settings measured best (BENCHMARKS.md, "Displaced
    /// subdivision (issue 46), first measurements").
    pub const DEFAULT: Displaced = Displaced {
        settings: Settings {
            rule: Rule::Loop,
            step_scale: 1.0 / 32.0,
            step_decay: 1.0,
            snap_base: false,
            reach_scale: 2.0,
            fallback: Fallback::Nearest,
            facing: true,
            qp: None,
            qp_slack: 1.0,
        },
    };
}

impl CodingMethod for Displaced {
    fn method(&self) -> Method {
        Method::Displaced
    }

    /// Its work grows with its files' size (one line query per new
    /// vertex, 4.2 files a cell), so the budget is counted in bytes.
    fn predicted_work(&self, _job: &Job<'_, '_>, _ask: Ask, bytes: u64) -> Option<u64> {
        Some(bytes)
    }

    fn work_unit(&self) -> &'static str {
        "bytes of file"
    }

    fn run_anyway(&self) -> &'static str {
        "--mode displaced forces it"
    }

    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error> {
        let budget =
            super::request::budget(ask.target, job.input_vertices, ask.max_bytes, "displaced")?;
        let s = job.simplifier();
        // The reference tree answers the measures' nearest points and the
        // fitting's line crossings alike (no tree of its own for the
        // lines: on bunny-1m 0.1 GB less at the peak, a build less).
        let target = Target {
            surface: job.reference()?,
        };
        let file = |faces: u32, levels: usize, qp: Option<u8>| -> Result<Written, Error> {
            let mut base = s.simplify(faces);
            s.refit(&mut base);
            let mut plan = self.plan(levels, job);
            plan.settings.qp = qp;
            let mut w = write(&base, &target, &plan)?;
            w.base_target = faces;
            Ok(w)
        };
        // The error of a file against the input, as the chooser measures
        // it (the reconstruction is the decoded file, bit for bit: no need
        // to decode it again). Its tree answers only the forward samples'
        // queries (30,000): the Morton build, a tenth of the SAH's time
        // (bunny and horse at 1 and 8 b/v: the same files, 8-13% less CPU
        // in three of four cells, +3% in one).
        let measure = |w: &Written| -> Result<f64, Error> {
            let how = crate::metrics::Build::Morton;
            Ok(crate::metrics::distance_between(
                target.surface,
                &crate::metrics::Surface::with_build(&w.mesh, how)?,
                &crate::metrics::DistanceOptions::area_uniform(crate::AUTO_SAMPLES),
            )?
            .l2_relative())
        };
        let mut smallest = u64::MAX;
        // Each level count's file and its error (the file's mesh dropped
        // once measured).
        let mut found: Vec<(f64, Written, usize)> = Vec::new();
        // Exponent of size against base faces, from the last level
        // count's files.
        let mut slope = SLOPE;
        for levels in LEVELS {
            // The previous level count's file predicts this one's faces.
            let guess = found
                .last()
                .map_or_else(|| first_guess(budget, levels), |f| next_guess(budget, &f.1));
            let best = found.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
            // A level count whose first file, its error carried to the
            // budget, is clearly worse than the best so far is not searched.
            let promising = |w: &Written| -> Result<bool, Error> {
                if !best.is_finite() {
                    return Ok(true);
                }
                let l2 = measure(w)?;
                let carried = l2 * (w.bytes.len() as f64 / budget as f64).powf(RATE_EXPONENT);
                Ok(carried <= best * (1.0 + GIVE_UP))
            };
            let searched = search(
                budget,
                levels,
                guess,
                s.faces(),
                self.settings.qp,
                slope,
                &mut smallest,
                &file,
                &promising,
            )?;
            slope = searched.slope.unwrap_or(slope);
            // Error against level count was unimodal in every cell
            // measured (bunny and horse, 0.5-8 b/v): once a level more
            // is worse, more levels are not tried (81 files -> 63 over
            // those ten cells, the same files chosen).
            if searched.abandoned {
                break;
            }
            let Some(mut w) = searched.fitting else {
                continue;
            };
            let l2 = measure(&w)?;
            w.mesh = crate::TriMesh::default();
            let worse = found.last().is_some_and(|f| f.0 < l2);
            found.push((l2, w, levels));
            if worse {
                break;
            }
        }
        // The closest; but a file within rate control's 3% of the budget
        // beats a shorter one unless 5% worse (the chooser's rule).
        let on_size = |w: &Written| w.bytes.len() as f64 >= budget as f64 * (1.0 - TOLERANCE);
        let closest = |on: bool| {
            (0..found.len())
                .filter(|&i| !on || on_size(&found[i].1))
                .min_by(|&a, &b| found[a].0.total_cmp(&found[b].0))
        };
        let pick = match (closest(true), closest(false)) {
            (Some(a), Some(b)) if found[a].0 <= crate::simplify::ON_SIZE_SLACK * found[b].0 => {
                Some(a)
            }
            (_, b) => b,
        };
        let Some((l2, w, levels)) = pick.map(|i| found.swap_remove(i)) else {
            return Err(SizeError {
                requested: budget,
                smallest,
            }
            .into());
        };
        let stats = DisplacedStats {
            base_faces: w.base_faces as u64,
            levels: levels as u8,
            qp: w.qp,
            base_bytes: w.base_bytes as u64,
            level_bytes: w.level_bytes.iter().map(|&b| b as u64).collect(),
            misses: w.misses.iter().map(|&m| m as u64).collect(),
            l2_relative: Some(l2),
        };
        // The base's vertices stand for the survivors of its collapses;
        // the levels' vertices descend from their edges' ends
        // (`provenance`).
        let seeds = match job.options.origins {
            true => Some(self.base_seeds(job, w.base_target, w.qp, levels)?),
            false => None,
        };
        Ok(Some(Made {
            bytes: w.bytes,
            stats: MethodStats::Displaced(stats),
            l2_relative: Some(l2),
            // The whole input as the base: short of the request, there
            // is nothing more to code.
            whole: w.base_faces >= s.faces() as usize,
            seeds,
        }))
    }
}

impl Displaced {
    /// The seed of each base vertex of the file whose base was simplified
    /// to `target` faces and coded at `qp` (in the decoder's order, as
    /// `write` codes it): the simplified method's rule.
    fn base_seeds(
        &self,
        job: &Job<'_, '_>,
        target: u32,
        qp: u8,
        levels: usize,
    ) -> Result<Vec<u32>, Error> {
        let s = job.simplifier();
        let mut base = s.simplify(target);
        s.refit(&mut base);
        let cleaned = crate::clean(&base, &crate::CleanOptions::default())?;
        let framing = self.plan(levels, job).framing;
        let (_, _, source) = crate::lossless::encode(&cleaned.table, &cleaned.mesh, qp, framing)?;
        Ok(super::simplified::seeds(
            s,
            target,
            &base,
            &cleaned.mesh,
            &source,
        ))
    }

    fn plan(&self, levels: usize, job: &Job<'_, '_>) -> Plan {
        Plan {
            levels,
            settings: self.settings,
            framing: job.options.framing,
        }
    }
}

/// What [`search`] found for one level count.
struct Searched {
    /// The largest file within the budget, if any.
    fitting: Option<Written>,
    /// The exponent of size against faces between its last two files.
    slope: Option<f64>,
    /// The first file was judged not worth searching on from.
    abandoned: bool,
}

/// The largest file of `levels` levels found within `budget` in at most
/// [`TRIALS`] files. The first file's quantization (its rule's, unless
/// `qp` fixes it) stays for the others, so that size grows smoothly with
/// the faces: the rule's steps made it jump by a fifth between
/// neighbouring face counts. Each next face count comes from a secant on
/// log size against log faces: between the largest file that fits and
/// the smallest that does not once both are known (their geometric mean
/// when the secant leaves the bracket), before that from the last file
/// with the last two files' exponent (`slope`, the previous level
/// count's, after the first), aiming 1% under the budget. A first file
/// off the budget that `promising` rejects ends the search.
#[allow(clippy::too_many_arguments)]
fn search(
    budget: u64,
    levels: usize,
    guess: u32,
    input_faces: u32,
    qp: Option<u8>,
    slope: f64,
    smallest: &mut u64,
    file: &dyn Fn(u32, usize, Option<u8>) -> Result<Written, Error>,
    promising: &dyn Fn(&Written) -> Result<bool, Error>,
) -> Result<Searched, Error> {
    let most = input_faces.max(MIN_BASE_FACES);
    let aim = (budget as f64 * (1.0 - TOLERANCE / 3.0)).ln();
    let mut faces = guess;
    let mut qp = qp;
    let mut found = Searched {
        fitting: None,
        slope: None,
        abandoned: false,
    };
    // (ln faces, ln size) of the largest fitting and smallest
    // oversized files, and of the last file.
    let (mut under, mut over, mut last): (
        Option<(f64, f64)>,
        Option<(f64, f64)>,
        Option<(f64, f64)>,
    ) = (None, None, None);
    let slope_of = |a: (f64, f64), b: (f64, f64)| (b.1 - a.1) / (b.0 - a.0);
    for trial in 0..TRIALS {
        let f = faces.clamp(MIN_BASE_FACES, most);
        let w = file(f, levels, qp)?;
        qp = Some(w.qp);
        let size = w.bytes.len() as u64;
        *smallest = (*smallest).min(size);
        let point = ((f as f64).ln(), (size as f64).ln());
        let fits = size <= budget;
        let done = fits && (size as f64 >= budget as f64 * (1.0 - TOLERANCE) || f >= most);
        if trial == 0 && !done && !promising(&w)? {
            found.abandoned = true;
            return Ok(found);
        }
        if let Some(l) = last {
            let s = slope_of(l, point);
            if s.is_finite() && s > 0.0 {
                found.slope = Some(s.clamp(0.3, 3.0));
            }
        }
        if fits {
            if under.is_none_or(|u| point.0 > u.0) {
                under = Some(point);
            }
            if found
                .fitting
                .as_ref()
                .is_none_or(|b| b.bytes.len() < w.bytes.len())
            {
                found.fitting = Some(w);
            }
            if done {
                break;
            }
        } else if over.is_none_or(|o| point.0 < o.0) {
            over = Some(point);
        }
        let next = match (under, over) {
            (Some(u), Some(o)) => {
                let x = o.0 + (aim - o.1) / slope_of(u, o);
                if x > u.0 && x < o.0 {
                    x
                } else {
                    0.5 * (u.0 + o.0)
                }
            }
            _ => point.0 + (aim - point.1) / found.slope.unwrap_or(slope),
        };
        last = Some(point);
        faces = next.exp().round().clamp(1.0, u32::MAX as f64) as u32;
        if faces == f {
            break;
        }
    }
    Ok(found)
}

/// Base faces whose file with one level more than `w`'s is about
/// `budget` bytes, from `w`'s own costs: its base's and each level's
/// bytes per base face, and the new finest level at its finest level's
/// bytes per scalar (a level has four times the scalars of the one
/// below), times [`NEXT_LEVEL_COST`].
fn next_guess(budget: u64, w: &Written) -> u32 {
    let faces = w.base_faces.max(1) as f64;
    let levels: f64 = w.level_bytes.iter().map(|&b| b as f64).sum();
    let finest = w.level_bytes.last().copied().unwrap_or(0) as f64;
    let per_face = NEXT_LEVEL_COST * (w.base_bytes as f64 + levels + 4.0 * finest) / faces;
    let aim = budget as f64 * (1.0 - TOLERANCE / 3.0);
    (aim / per_face).round().clamp(1.0, u32::MAX as f64) as u32
}

/// Base faces whose file is about `budget` bytes at `levels` levels: a
/// base face costs about 10 bits (a vertex of the lossless mode, about
/// 20 bits, per two faces), a new vertex about 1.5 bits, and `k` levels
/// add about `B/2 · (4^k − 1)` vertices.
fn first_guess(budget: u64, levels: usize) -> u32 {
    let per_face = 10.0 + 0.75 * ((1u64 << (2 * levels)) - 1) as f64;
    (8.0 * budget as f64 / per_face)
        .round()
        .min(u32::MAX as f64) as u32
}
