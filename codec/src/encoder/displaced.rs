//! The displaced-subdivision method (mode 2, `crate::displaced`): a
//! quadric simplification of the input to `B` faces (refitted to the
//! input, boundaries kept by the collapse's own rules) as the base, `k`
//! levels of subdivision, one scalar per new vertex.
//!
//! Rate control: for each level count `k` in [`LEVELS`], a first guess of
//! `B` from a cost model (bits per base face, bits per new vertex), then
//! at most [`TRIALS`] files, each `B` moved by a secant on log size
//! against log faces ([`search`]); the file of each `k` nearest the
//! budget without passing it is measured with the chooser's distance and
//! the closest to the input wins. No loop runs until convergence: at most
//! `|LEVELS| × TRIALS` files.

use super::method::{Ask, CodingMethod, Job, Made};
use super::stats::{DisplacedStats, Method, MethodStats};
use crate::displaced::fit::{Fallback, Target};
use crate::displaced::predict::Rule;
use crate::displaced::write::{write, Plan, Settings, Written};
use crate::metrics::ray::Lines;
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

    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error> {
        let budget =
            super::request::budget(ask.target, job.input_vertices, ask.max_bytes, "displaced")?;
        let s = job.simplifier();
        let reference = s.reference();
        let (lines, surface) = rayon::join(
            || Lines::new(&reference.positions, &reference.triangles),
            || job.reference(),
        );
        let target = Target {
            lines: &lines,
            surface: surface?,
        };
        let file = |faces: u32, levels: usize, qp: Option<u8>| -> Result<Written, Error> {
            let mut base = s.simplify(faces);
            s.refit(&mut base);
            let mut plan = self.plan(levels, job);
            plan.settings.qp = qp;
            write(&base, &target, &plan)
        };
        let mut smallest = u64::MAX;
        // Each level count's file and its error.
        let mut found: Vec<(f64, Written, usize)> = Vec::new();
        for levels in LEVELS {
            // The previous level count's file predicts this one's faces.
            let guess = found
                .last()
                .map_or_else(|| first_guess(budget, levels), |f| next_guess(budget, &f.1));
            let fitting = search(
                budget,
                levels,
                guess,
                s.faces(),
                self.settings.qp,
                &mut smallest,
                &file,
            )?;
            let Some(w) = fitting else {
                continue;
            };
            // The reconstruction is the decoded file, bit for bit: no
            // need to decode it again to measure it.
            let l2 = crate::metrics::distance_between(
                target.surface,
                &crate::metrics::Surface::new(&w.mesh)?,
                &crate::metrics::DistanceOptions::area_uniform(crate::AUTO_SAMPLES),
            )?
            .l2_relative();
            // Error against level count was unimodal in every cell
            // measured (bunny and horse, 0.5-8 b/v): once a level more
            // is worse, more levels are not tried (81 files -> 63 over
            // those ten cells, the same files chosen).
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
        Ok(Some(Made {
            bytes: w.bytes,
            stats: MethodStats::Displaced(stats),
            l2_relative: Some(l2),
            // The whole input as the base: short of the request, there
            // is nothing more to code.
            whole: w.base_faces >= s.faces() as usize,
            seeds: None,
        }))
    }
}

impl Displaced {
    fn plan(&self, levels: usize, job: &Job<'_, '_>) -> Plan {
        Plan {
            levels,
            settings: self.settings,
            framing: job.options.framing,
        }
    }
}

/// The largest file of `levels` levels found within `budget` in at most
/// [`TRIALS`] files (`None` when none fits). The first file's
/// quantization (its rule's, unless `qp` fixes it) stays for the others,
/// so that size grows smoothly with the faces: the rule's steps made it
/// jump by a fifth between neighbouring face counts. Each next face
/// count comes from a secant on log size against log faces: between the
/// largest file that fits and the smallest that does not once both are
/// known (their geometric mean when the secant leaves the bracket),
/// before that from the last file with the last two files' exponent (1
/// after the first), aiming 1% under the budget.
fn search(
    budget: u64,
    levels: usize,
    guess: u32,
    input_faces: u32,
    qp: Option<u8>,
    smallest: &mut u64,
    file: &dyn Fn(u32, usize, Option<u8>) -> Result<Written, Error>,
) -> Result<Option<Written>, Error> {
    let most = input_faces.max(MIN_BASE_FACES);
    let aim = (budget as f64 * (1.0 - TOLERANCE / 3.0)).ln();
    let mut faces = guess;
    let mut qp = qp;
    let mut fitting: Option<Written> = None;
    // (ln faces, ln size) of the largest fitting and smallest
    // oversized files, and of the last file.
    let (mut under, mut over, mut last): (
        Option<(f64, f64)>,
        Option<(f64, f64)>,
        Option<(f64, f64)>,
    ) = (None, None, None);
    for _ in 0..TRIALS {
        let f = faces.clamp(MIN_BASE_FACES, most);
        let w = file(f, levels, qp)?;
        qp = Some(w.qp);
        let size = w.bytes.len() as u64;
        *smallest = (*smallest).min(size);
        let point = ((f as f64).ln(), (size as f64).ln());
        let fits = size <= budget;
        if fits {
            if under.is_none_or(|u| point.0 > u.0) {
                under = Some(point);
            }
            if fitting
                .as_ref()
                .is_none_or(|b| b.bytes.len() < w.bytes.len())
            {
                fitting = Some(w);
            }
            if size as f64 >= budget as f64 * (1.0 - TOLERANCE) || f >= most {
                break;
            }
        } else if over.is_none_or(|o| point.0 < o.0) {
            over = Some(point);
        }
        let slope = |a: (f64, f64), b: (f64, f64)| (b.1 - a.1) / (b.0 - a.0);
        let next = match (under, over) {
            (Some(u), Some(o)) => {
                let x = o.0 + (aim - o.1) / slope(u, o);
                if x > u.0 && x < o.0 {
                    x
                } else {
                    0.5 * (u.0 + o.0)
                }
            }
            _ => {
                let s = last.map_or(1.0, |l| slope(l, point));
                let s = if s.is_finite() {
                    s.clamp(0.3, 3.0)
                } else {
                    1.0
                };
                point.0 + (aim - point.1) / s
            }
        };
        last = Some(point);
        faces = next.exp().round().clamp(1.0, u32::MAX as f64) as u32;
        if faces == f {
            break;
        }
    }
    Ok(fitting)
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
