//! The displaced-subdivision method (mode 2, `crate::displaced`): a
//! quadric simplification of the input to `B` faces (refitted to the
//! input, boundaries kept by the collapse's own rules) as the base, `k`
//! levels of subdivision, one scalar per new vertex.
//!
//! Rate control, in two rounds:
//! 1. One file for each level count `k` in [`LEVELS`], its base faces
//!    `B` from a cost model (bits per base face, bits per new vertex; for
//!    `k` > 1 from the first file of `k − 1`), measured with the
//!    chooser's distance and its error carried to the budget
//!    ([`RATE_EXPONENT`]). A `k` whose carried error is clearly worse
//!    than the best so far ([`GIVE_UP`]) ends the round (error against
//!    `k` was unimodal in every cell measured), and so does a third `k`
//!    after two whose last level gained less than [`NEXT_LEVEL_GAIN`].
//! 2. The search of the best `k`, and of each other `k` whose first file
//!    was within [`SEARCH_BOTH`] of it, from that file: at most
//!    [`TRIALS`] files, each `B` moved by a secant on log size against
//!    log faces ([`search`]). The file of each `k` nearest the budget
//!    without passing it is measured (the first one's measure serves
//!    when it stands) and the closest to the input wins.
//!
//! Beyond the sources, measured (BENCHMARKS.md, "Session 2026-12-06
//! (eighth)"): searching every `k` and probing the next one's first file
//! made 4.2 files a cell over bunny and horse at 0.5-8 b/v, the level
//! count that loses searched to the budget as fully as the winner; the
//! two rounds spend 25-45% less CPU at 4-8 b/v, the chosen files within
//! ±2% L2 (the secant lands them at other sizes within the tolerance).
//! No loop runs until convergence: at most `|LEVELS| × TRIALS` files in
//! the searches (twice that with the other step's), then at most
//! [`PRECISION_TRIALS`] when the closest file is short of the budget.
//!
//! Steps from the error (beyond the sources, measured in BENCHMARKS.md,
//! "Steps from the error"): once a file is measured, no file's finest
//! step is finer than [`STEP_ERROR`] times the least error carried to the
//! budget so far. The first file, made with the edge rule alone, is made
//! again with that floor when its step was finer, and the floored file
//! replaces it only when its carried error is lower (else the edge rule
//! stays for the whole encode); the first file at the step not kept is
//! searched too when its carried error is within [`GIVE_UP`] of the best
//! (a first file far from the budget carries its error that roughly:
//! beetle at 2 b/v, L2 275 against 133), and so is the edge rule's when
//! a floored search ends with the whole input as its base and bytes to
//! spare; the closer file wins. Over the shared
//! corpus's twelve meshes at 0.5-8 b/v: 17 of 60 cells closer by 1-40%
//! (7-40% on spot, homer, cheburashka and cow at 0.5-2 b/v), none
//! further.
//!
//! With attributes, `resample::sized` asks for files at up to five
//! geometry budgets, each a few tenths from the last; every budget after
//! the first skips the first round and searches from the last budget's
//! chosen file ([`Start`]: its level count stands, a floored step is
//! asked again of its error carried to the budget, its faces are scaled
//! along its search's exponent). Beyond the sources, measured
//! (BENCHMARKS.md, "Session 2026-12-07 (seventh)"): a coloured bunny at
//! 1-2 b/v, `default`, about 40% less wall time.
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
/// Files at finer steps for a closest file short of the budget.
const PRECISION_TRIALS: usize = 3;
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

/// The error `l2` of a file of `bytes` carried to `budget` bytes
/// ([`RATE_EXPONENT`]).
fn carried_to(l2: f64, bytes: u64, budget: u64) -> f64 {
    l2 * (bytes as f64 / budget as f64).powf(RATE_EXPONENT)
}
/// A level count whose first file's error, carried to the budget, is
/// more than this fraction above the best level count's is not searched.
const GIVE_UP: f64 = 0.10;
/// Level counts searched besides the best one: those whose first file's
/// carried error is within this fraction of the best's (a tighter margin
/// than [`GIVE_UP`], which judges files as far as twice the budget).
/// Measured over the shared corpus at 0.5-8 b/v (BENCHMARKS.md,
/// "Session 2026-12-07 (seventh)"): in the 12 cells where two level
/// counts were searched, the one behind in the first round by more than
/// 3% (3.4-10%) stayed behind after both searches (by 0.9-53%); the one
/// reversal was within it (homer at 8 b/v: 2.7% behind, then 4.2%
/// ahead). Each search not made saves a file and a measure: a quarter of
/// the method's work on bunny and horse at 2-4 b/v.
const SEARCH_BOTH: f64 = 0.03;
/// A level count is tried after two others only when the last level
/// more cut the error by at least this fraction. One level more quarters
/// the base for the same bytes, so the gains shrink fast: measured on
/// bunny and horse at 2-8 b/v, two levels gained 6-27% over one, and
/// three were worse than two in every one of those cells (by 1-700%),
/// each probe a file of the most scalars and a measure: about a third
/// of the method's work at those rates.
const NEXT_LEVEL_GAIN: f64 = 0.30;
/// Bits of geometry per decoded vertex a displaced file spends, for the
/// first guess of a file with attributes (bunny at 2 b/v: 3.4, a base
/// and two levels; more with fewer levels).
const GEOMETRY_BITS: f64 = 4.0;
/// The floor of the finest step over the error expected of the file (L2,
/// carried to the budget). With a uniform quantizer the last bit of a
/// scalar is worth its cost where the squared error it removes, about
/// step²/12 over the vertex's share of the area, matches the slope of the
/// whole file's error against its bits (L2 ∝ bytes^−[`RATE_EXPONENT`]):
/// that puts the step at about two L2 on any mesh. The edge rule (`c`
/// times the mean edge) gives less than that on small meshes at low
/// rates, where the error is large against the edges. Measured best
/// ratios in a sweep of `c`: 1.7-3.0 on spot, homer and cheburashka at
/// 0.5-4 b/v; the edge rule's own on bunny and horse, 1.8-3.0
/// (BENCHMARKS.md, "Steps from the error").
const STEP_ERROR: f64 = 2.0;

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
            bend: true,
            bare_base: true,
            step_error: Some(STEP_ERROR),
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

    /// Normals, colours and generic streams, resampled at its vertices
    /// (`resample`); not texture coordinates.
    fn carries_attributes(&self, streams: &[crate::AttributeStream]) -> bool {
        super::resample::carries(streams)
    }

    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error> {
        let budget =
            super::request::budget(ask.target, job.input_vertices, ask.max_bytes, "displaced")?;
        if job.streams().is_empty() {
            return self.within(job, budget, None).map(|(made, _)| Some(made));
        }
        // With attributes: geometry and streams sized together, each
        // geometry budget after the first searched from the last file
        // (`Start`).
        let start = std::cell::RefCell::new(None);
        super::resample::sized(job, budget, ask.max_bytes, GEOMETRY_BITS, |geometry| {
            self.attributed(job, geometry, &start)
        })
    }
}

impl Displaced {
    /// [`within`](Self::within) at `geometry` bytes, from the last
    /// pass's file when there was one (`start`, which this pass's file
    /// replaces), its file carrying the job's streams (`resample`); `None`
    /// when its mesh makes no corner table.
    fn attributed(
        &self,
        job: &Job<'_, '_>,
        geometry: u64,
        start: &std::cell::RefCell<Option<Start>>,
    ) -> Result<Option<Made>, Error> {
        let last = start.borrow_mut().take();
        let (mut made, next) = self.within(job, geometry, last.as_ref())?;
        *start.borrow_mut() = Some(next);
        let seeds = made.seeds.take().unwrap_or_default();
        let Some(bytes) = super::resample::with_attributes(job, &made.bytes, Some(&seeds))? else {
            return Ok(None);
        };
        made.bytes = bytes;
        made.seeds = job.options.origins.then_some(seeds);
        Ok(Some(made))
    }

    /// Its file of geometry alone at about `budget` bytes, and what a
    /// search at a budget near it can start from. With a `start` (the
    /// file a budget near this one chose) the first round is not made: its
    /// level count stands, and one search runs from its faces scaled to
    /// the budget.
    fn within(
        &self,
        job: &Job<'_, '_>,
        budget: u64,
        start: Option<&Start>,
    ) -> Result<(Made, Start), Error> {
        let s = job.simplifier();
        // The reference tree answers the measures' nearest points and the
        // fitting's line crossings alike (no tree of its own for the
        // lines: on bunny-1m 0.1 GB less at the peak, a build less).
        let target = Target {
            surface: job.reference()?,
        };
        // A file of `faces` base faces and `levels` levels; `scale` times
        // the edge rule's step (1 but where the closest file is short of
        // the budget, below).
        let scaled = |faces: u32, levels: usize, qp: Option<u8>, step: Option<f64>, scale: f64| {
            let mut base = s.simplify(faces);
            s.refit(&mut base);
            let mut plan = self.plan(levels, job);
            plan.settings.qp = qp;
            plan.settings.step_scale *= scale;
            plan.step = step;
            let mut w = write(&base, &target, &plan)?;
            w.base_target = faces;
            Ok::<Written, Error>(w)
        };
        let file = |faces: u32, levels: usize, qp: Option<u8>, step: Option<f64>| {
            scaled(faces, levels, qp, step, 1.0)
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
        // First, one file of each level count, measured and its error
        // carried to the budget (`RATE_EXPONENT`).
        let mut firsts: Vec<First> = Vec::new();
        // The least carried error so far.
        let mut best = f64::INFINITY;
        // The finest step that error asks for (`STEP_ERROR`), in the
        // mesh's units; none before the first measure.
        let diagonal = target.surface.diagonal();
        let asked = |carried: f64| {
            self.settings
                .step_error
                .map(|k| k * carried * diagonal)
                .filter(|s| s.is_finite() && *s > 0.0)
        };
        let mut step: Option<f64> = None;
        let mut floor = true;
        if let Some(sd) = start {
            // Faces for the budget along the last search's exponent; its
            // error is measured only if the file stands (`settled`).
            let scale = (budget as f64 / sd.bytes.max(1) as f64).powf(1.0 / sd.slope);
            let faces = (sd.faces as f64 * scale)
                .round()
                .clamp(MIN_BASE_FACES as f64, s.faces().max(MIN_BASE_FACES) as f64)
                as u32;
            // A floored step is asked again of the error the last file's
            // carries to this budget, as the first round would.
            let given = sd
                .step
                .and_then(|_| asked(carried_to(sd.l2, sd.bytes, budget)));
            let w = file(faces, sd.levels, self.settings.qp, given)?;
            if given.is_none() {
                smallest = smallest.min(w.bytes.len() as u64);
            }
            firsts.push(First {
                levels: sd.levels,
                faces,
                w,
                l2: f64::NAN,
                carried: f64::NAN,
                step: given,
                other: None,
            });
        }
        for levels in LEVELS.into_iter().filter(|_| start.is_none()) {
            // After two level counts, one more only where the last level
            // still paid well (`NEXT_LEVEL_GAIN`).
            if let [.., ref before, ref last] = firsts[..] {
                if last.carried > (1.0 - NEXT_LEVEL_GAIN) * before.carried {
                    break;
                }
            }
            // The previous level count's file predicts this one's faces.
            let faces = firsts
                .last()
                .map_or_else(|| first_guess(budget, levels), |f| next_guess(budget, &f.w))
                .clamp(MIN_BASE_FACES, s.faces().max(MIN_BASE_FACES));
            let mut w = file(faces, levels, self.settings.qp, step)?;
            // Only the edge rule's files say how small a file can be: a
            // floored step depends on the budget, so a request at a
            // floored file's size would not make that file again.
            if step.is_none() {
                smallest = smallest.min(w.bytes.len() as u64);
            }
            let mut l2 = measure(&w)?;
            let carry = |w: &Written, l2: f64| carried_to(l2, w.bytes.len() as u64, budget);
            let mut carried = carry(&w, l2);
            let mut given = step;
            // The edge rule's file, when the floored one replaced it.
            let mut other = None;
            // The first file's step is the edge rule's: made again when
            // the step its error asks for is coarser (small meshes at low
            // rates: a quarter to half of it).
            if let (None, Some(want), true) = (step, asked(carried), floor) {
                if w.step < want {
                    let floored = file(faces, levels, self.settings.qp, Some(want))?;
                    let l2_floored = measure(&floored)?;
                    let carried_floored = carry(&floored, l2_floored);
                    if carried_floored < carried {
                        let mut edge_file = std::mem::replace(&mut w, floored);
                        // Only its size and quantization serve again.
                        edge_file.mesh = crate::TriMesh::default();
                        other = Some(Other {
                            w: edge_file,
                            l2,
                            carried,
                            step: None,
                        });
                        l2 = l2_floored;
                        carried = carried_floored;
                        given = Some(want);
                    } else {
                        let mut floored = floored;
                        floored.mesh = crate::TriMesh::default();
                        other = Some(Other {
                            w: floored,
                            l2: l2_floored,
                            carried: carried_floored,
                            step: Some(want),
                        });
                        floor = false;
                    }
                }
            }
            let before = best;
            best = best.min(carried);
            step = asked(best).filter(|_| floor);
            firsts.push(First {
                levels,
                faces,
                w,
                l2,
                carried,
                step: given,
                other,
            });
            // Error against level count was unimodal in every cell
            // measured (bunny and horse, 0.5-8 b/v): once a level more
            // is clearly worse, more levels are not tried.
            if carried > before * (1.0 + GIVE_UP) {
                break;
            }
        }
        // Then the search of the best level count and of any whose first
        // file was within `SEARCH_BOTH` of it, from that file.
        let mut found: Vec<Found> = Vec::new();
        // A search's file and its error (the first file, when it stood, is
        // measured already: `l2_first`), its mesh no longer needed.
        let settled = |searched: Searched, l2_first: f64| -> Result<_, Error> {
            let Some(mut w) = searched.fitting else {
                return Ok(None);
            };
            let l2 = match searched.first_fits && l2_first.is_finite() {
                true => l2_first,
                false => measure(&w)?,
            };
            w.mesh = crate::TriMesh::default();
            Ok(Some((l2, w, searched.slope)))
        };
        let mut slope = start.map_or(SLOPE, |sd| sd.slope);
        for first in firsts {
            if first.carried > best * (1.0 + SEARCH_BOTH) {
                continue;
            }
            let (levels, l2_first, given) = (first.levels, first.l2, first.step);
            let mut floored_smallest = u64::MAX;
            // The edge rule's files grow otherwise with their faces than
            // floored ones: a floored search's slope serves only its kind.
            let edge_slope = slope;
            let searched = search(
                budget,
                (first.faces, first.w),
                s.faces(),
                slope,
                match given {
                    None => &mut smallest,
                    Some(_) => &mut floored_smallest,
                },
                &|faces, qp| file(faces, levels, qp, given),
            )?;
            if given.is_none() {
                slope = searched.slope.unwrap_or(slope);
            }
            // The other step's first file (the edge rule's or the
            // floored one) is searched too where it could win: its
            // carried error within `GIVE_UP` of the best (a carry over a
            // first file twice the budget misjudges by that much: beetle
            // at 2 b/v, 5% apart, the edge rule's search landed on 25
            // faces at L2 275, the floored one on 50 at 124), or, for the
            // edge rule's, where the floored search fell short with the
            // whole input as its base: the error has no faces left to
            // fall with, and the bytes left buy precision (teapot at
            // 8 b/v: L2 8.8 floored, 2.5 with the edge rule).
            if let Some(o) = first.other {
                let close = o.carried <= best * (1.0 + GIVE_UP);
                if close || (searched.capped && o.step.is_none()) {
                    let mut other_smallest = u64::MAX;
                    // An edge-rule file's search takes the edge rule's
                    // slope and says how small a file can be; a floored
                    // one neither (as the main search's).
                    let (slope_of_other, smallest_of_other) = match o.step {
                        None => (edge_slope, &mut smallest),
                        Some(_) => (SLOPE, &mut other_smallest),
                    };
                    let again = search(
                        budget,
                        (first.faces, o.w),
                        s.faces(),
                        slope_of_other,
                        smallest_of_other,
                        &|faces, qp| file(faces, levels, qp, o.step),
                    )?;
                    if let Some((l2, w, sl)) = settled(again, o.l2)? {
                        found.push(Found {
                            l2,
                            w,
                            levels,
                            step: o.step,
                            slope: sl.unwrap_or(slope_of_other),
                        });
                    }
                }
            }
            if let Some((l2, w, sl)) = settled(searched, l2_first)? {
                found.push(Found {
                    l2,
                    w,
                    levels,
                    step: given,
                    slope: sl.unwrap_or(edge_slope),
                });
            }
        }
        // The closest file short of the budget (its search found no more
        // faces that fit: the whole input as its base, or a face count
        // the secant could not move from): the bytes left buy precision,
        // a finer edge-rule step (its scalars about `log2(1/scale)` bits
        // dearer each; then a secant on log size against log scale), at
        // most `PRECISION_TRIALS` files (the torus at 12 b/v: 2,035 bytes
        // of 2,304, 3,036 of its 3,072 faces, once bends made its scalars
        // cheaper).
        let on_size = |w: &Written| w.bytes.len() as f64 >= budget as f64 * (1.0 - TOLERANCE);
        let closest_of_all = (0..found.len()).min_by(|&a, &b| found[a].l2.total_cmp(&found[b].l2));
        let short = closest_of_all.filter(|&i| !on_size(&found[i].w));
        if let Some(i) = short {
            let (faces, levels, qp) = (found[i].w.base_target, found[i].levels, found[i].w.qp);
            let w0 = &found[i].w;
            let scalars = 1.5 * w0.base_faces as f64 * ((4f64).powi(levels as i32) - 1.0) / 3.0;
            let aim = budget as f64 * (1.0 - TOLERANCE / 3.0);
            let mut points = vec![(0.0f64, (w0.bytes.len() as f64).ln())];
            let mut ln_scale =
                -(aim - w0.bytes.len() as f64) * 8.0 / scalars.max(1.0) * std::f64::consts::LN_2;
            for _ in 0..PRECISION_TRIALS {
                if !(ln_scale.is_finite() && ln_scale < 0.0) {
                    break;
                }
                let w = scaled(faces, levels, Some(qp), None, ln_scale.exp())?;
                let size = w.bytes.len() as f64;
                points.push((ln_scale, size.ln()));
                if size <= budget as f64 {
                    let done = on_size(&w);
                    let l2 = measure(&w)?;
                    let mut w = w;
                    w.mesh = crate::TriMesh::default();
                    found.push(Found {
                        l2,
                        w,
                        levels,
                        step: None,
                        slope: SLOPE,
                    });
                    if done {
                        break;
                    }
                }
                let [.., a, b] = points[..] else { break };
                let slope = (b.1 - a.1) / (b.0 - a.0);
                if !(slope.is_finite() && slope < 0.0) {
                    break;
                }
                ln_scale = b.0 + (aim.ln() - b.1) / slope;
            }
        }
        // The closest; but a file within rate control's 3% of the budget
        // beats a shorter one unless 5% worse (the chooser's rule).
        let closest = |on: bool| {
            (0..found.len())
                .filter(|&i| !on || on_size(&found[i].w))
                .min_by(|&a, &b| found[a].l2.total_cmp(&found[b].l2))
        };
        let pick = match (closest(true), closest(false)) {
            (Some(a), Some(b)) if found[a].l2 <= crate::simplify::ON_SIZE_SLACK * found[b].l2 => {
                Some(a)
            }
            (_, b) => b,
        };
        let Some(Found {
            l2,
            w,
            levels,
            step: given,
            slope,
        }) = pick.map(|i| found.swap_remove(i))
        else {
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
        let seeds = match job.options.origins || !job.streams().is_empty() {
            true => Some(self.base_seeds(job, w.base_target, w.qp, levels)?),
            false => None,
        };
        let next = Start {
            levels,
            faces: w.base_target,
            l2,
            step: given,
            bytes: w.bytes.len() as u64,
            slope,
        };
        let made = Made {
            bytes: w.bytes,
            stats: MethodStats::Displaced(stats),
            l2_relative: Some(l2),
            // The whole input as the base: short of the request, there
            // is nothing more to code.
            whole: w.base_faces >= s.faces() as usize,
            seeds,
        };
        Ok((made, next))
    }

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
            step: None,
        }
    }
}

/// A level count's first file: its base faces, error and error carried
/// to the budget.
struct First {
    levels: usize,
    faces: u32,
    w: Written,
    l2: f64,
    carried: f64,
    /// Its finest step when given (`None`: the edge rule's).
    step: Option<f64>,
    /// The first file at the other step (the edge rule's when the
    /// floored step replaced it, the floored one when it did not).
    other: Option<Other>,
}

/// A file a search found, measured, its mesh dropped.
struct Found {
    l2: f64,
    w: Written,
    levels: usize,
    /// Its finest step when given (`None`: the edge rule's).
    step: Option<f64>,
    /// The exponent of size against faces its search found (or started
    /// with).
    slope: f64,
}

/// Where a search at a budget near a file's can start (the passes of a
/// file with attributes, `resample::sized`, whose geometry budgets move
/// by a few tenths): that file's level count, base faces, error and step,
/// its size, and the exponent of size against faces its search found.
/// Beyond the sources, measured (BENCHMARKS.md, "Session 2026-12-07
/// (seventh)").
struct Start {
    levels: usize,
    faces: u32,
    /// Its error.
    l2: f64,
    /// Its finest step when given (`None`: the edge rule's).
    step: Option<f64>,
    bytes: u64,
    slope: f64,
}

/// A level count's first file at the step it did not keep.
struct Other {
    w: Written,
    l2: f64,
    carried: f64,
    /// Its finest step when given (`None`: the edge rule's).
    step: Option<f64>,
}

/// What [`search`] found for one level count.
struct Searched {
    /// The largest file within the budget, if any.
    fitting: Option<Written>,
    /// The exponent of size against faces between its last two files.
    slope: Option<f64>,
    /// Whether `fitting` is the first file (measured already).
    first_fits: bool,
    /// Whether `fitting` has the whole input as its base and still falls
    /// short of the budget by more than the tolerance.
    capped: bool,
}

/// The largest file of one level count found within `budget` in at most
/// [`TRIALS`] files, the first one `first` (made from that many base
/// faces). Its quantization stays for the others, so that size grows
/// smoothly with the faces: the rule's steps made it jump by a fifth
/// between neighbouring face counts. Each next face count comes from a
/// secant on log size against log faces: between the largest file that
/// fits and the smallest that does not once both are known (their
/// geometric mean when the secant leaves the bracket), before that from
/// the last file with the last two files' exponent (`slope`, the
/// previous level count's, after the first), aiming 1% under the budget.
fn search(
    budget: u64,
    first: (u32, Written),
    input_faces: u32,
    slope: f64,
    smallest: &mut u64,
    file: &dyn Fn(u32, Option<u8>) -> Result<Written, Error>,
) -> Result<Searched, Error> {
    let most = input_faces.max(MIN_BASE_FACES);
    let aim = (budget as f64 * (1.0 - TOLERANCE / 3.0)).ln();
    let qp = Some(first.1.qp);
    let (mut faces, mut made) = (first.0, Some(first.1));
    let mut found = Searched {
        fitting: None,
        slope: None,
        first_fits: false,
        capped: false,
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
        let w = match made.take() {
            Some(w) => w,
            None => file(f, qp)?,
        };
        let size = w.bytes.len() as u64;
        *smallest = (*smallest).min(size);
        let point = ((f as f64).ln(), (size as f64).ln());
        let fits = size <= budget;
        let on_size = size as f64 >= budget as f64 * (1.0 - TOLERANCE);
        let done = fits && (on_size || f >= most);
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
                found.first_fits = trial == 0;
                found.capped = f >= most && !on_size;
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
