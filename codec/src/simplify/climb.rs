//! The search over quantizations (steps 2 and 3 of the module's search,
//! [`super`]): which qp's size fit ([`fit_faces`]) is closest to the
//! input. The full search climbs from a predicted qp and measures each
//! fit; the quick one (effort `fast`) fits two and ranks them with a few
//! samples.
//!
//! Invariants: every file returned fits the budget; the result depends
//! only on the mesh and the budget (the distance's samples are seeded and
//! summed in a fixed order), never on the thread count.

use super::faces::{fit_faces, predicted_qp, Fit, Probing, Whole};

/// The climb's probing.
fn probing(lean: bool) -> Probing {
    if lean {
        Probing::Lean
    } else {
        Probing::Full
    }
}
use super::simplifier::{file_distance, Simplifier, MIN_FACES, ON_SIZE_SLACK, QPS, START_QP};
use crate::metrics::{Surface, SurfaceDistance};

/// A fit's measure: its distance to the input, and the error the climb
/// weighs, its L2 plus the attribute error of an input with streams
/// ([`Simplifier::attribute_error`]; `simplify::attributed`'s weights).
#[derive(Clone, Copy)]
struct Scored {
    distance: SurfaceDistance,
    weighed: f64,
}
use crate::Error;
use rayon::prelude::*;

/// How [`best_fit`] spends its work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Climb {
    /// Every qp's answer refitted, coded and measured with this many
    /// samples per direction as it comes (effort `max`, the
    /// per-component chooser): the search as it was before effort levels.
    Full(u64),
    /// Effort `default`'s: the same climb with less work per fit, which
    /// leaves the choice within a few percent of the full one's
    /// (BENCHMARKS.md, "Effort levels"): measures take [`LEAN_SAMPLES`];
    /// each size search starts where the previous qp's fit predicts
    /// (`faces::predicted_faces`), so it needs one or two probes instead
    /// of three or four; and a whole-mesh file that another qp's shows
    /// far over the budget is not made ([`Whole::Over`]).
    Lean,
}

/// Samples per direction of the lean climb's measures: as many as the
/// full climb's. With 10,000 the default level's geometric-mean L2 over
/// the shared table rose 7.8% (alligator at 4 and 8 b/v and woody at 8,
/// whose files are all but exact: their few large errors need many
/// samples to rank neighbouring quantizations), and saved about 2% of
/// the time.
pub const LEAN_SAMPLES: u64 = 30_000;

/// The fit of lowest measured L2 against `reference` over [`QPS`] (plus,
/// for an input with attribute streams, their error weighed as
/// `simplify::attributed` says), and its L2 relative to the reference's
/// diagonal; `None` when no qp fits even `MIN_FACES` faces in `budget`
/// bytes.
///
/// The error is unimodal in qp (coarser positions against fewer faces),
/// so the search climbs from a predicted qp instead of trying all of
/// them: a first fit at [`START_QP`] gives the face count F, the best qp
/// is near `log2 F − 2.5` (measured on the shared corpus: `log2 F` minus
/// 2.4 to 2.9 on scans, up to 1.4 above on CAD parts), and the climb
/// moves one qp at a time while the error falls, about four fits in all
/// instead of nine. [`Climb`] says how much each fit costs.
pub fn best_fit<'r>(
    s: &Simplifier<'_>,
    budget: u64,
    reference: &(dyn Fn() -> Result<&'r Surface, Error> + Sync),
    climb: Climb,
) -> Result<Option<(Fit, f64)>, Error> {
    let lean = climb == Climb::Lean;
    let samples = match climb {
        Climb::Full(samples) => samples,
        Climb::Lean => LEAN_SAMPLES,
    };
    let measure = |fit: &Fit| -> Result<Scored, Error> {
        let distance = file_distance(&fit.bytes, reference()?, samples)?;
        let weighed = distance.l2() + s.attribute_error(&fit.bytes)?;
        Ok(Scored { distance, weighed })
    };
    let measure: &(dyn Fn(&Fit) -> Result<Scored, Error> + Sync) = &measure;
    let mut tried = Climbed::default();
    // The first fit; coarser qps until something fits.
    let mut start = START_QP;
    while tried.fit(s, start, budget, lean)?.is_none() {
        if start == *QPS.start() {
            return Ok(None);
        }
        start -= 1;
    }
    let score = |qp: u8, tried: &mut Climbed| -> Result<Option<f64>, Error> {
        tried.fit(s, qp, budget, lean)?;
        tried.measure(qp, measure)
    };
    let faces = tried
        .fits
        .iter()
        .find_map(|t| t.fit.as_ref().map(|f| f.faces))
        .unwrap_or(MIN_FACES);
    let mut qp = predicted_qp(faces);
    // The start is measured even where the climb does not come back to
    // it: error is not always unimodal in qp on CAD parts (the generated
    // fandisk at 1 b/v: best at qp 10, worse at 9 than at 8).
    if lean {
        tried.first_pair(s, start, qp, budget, &measure)?;
    } else {
        score(start, &mut tried)?;
    }
    let inf = f64::INFINITY;
    let mut best = score(qp, &mut tried)?.unwrap_or(inf);
    // Climb: the direction whose neighbour is better, while it improves.
    for step in [-1i8, 1] {
        loop {
            let next = qp as i16 + step as i16;
            if !(*QPS.start() as i16..=*QPS.end() as i16).contains(&next) {
                break;
            }
            let e = score(next as u8, &mut tried)?.unwrap_or(inf);
            if e < best {
                best = e;
                qp = next as u8;
            } else {
                break;
            }
        }
    }
    // The first minimum in qp order: the smaller qp wins a tie. A fit
    // that lands within rate control's tolerance of the budget (or holds
    // the whole mesh, when nothing more is there to code) is preferred
    // to one further below it, the request's size being part of the
    // answer, unless the short one's error is lower by more than
    // ON_SIZE_SLACK (a cube exact at 32 faces is not traded for a worse
    // file that fills the last two bytes).
    let mut measured: Vec<(Fit, Scored)> = tried
        .fits
        .into_iter()
        .filter_map(|t| Some((t.fit?, t.distance?)))
        .collect();
    measured.sort_by_key(|(f, _)| f.qp);
    let in_band = |f: &Fit| {
        f.faces >= s.faces()
            || f.bytes.len() as f64 >= (1.0 - crate::swing::retile::rate::TOLERANCE) * budget as f64
    };
    let lowest = |fits: Vec<(Fit, Scored)>| {
        fits.into_iter()
            .reduce(|a, b| if b.1.weighed < a.1.weighed { b } else { a })
    };
    let (band, short): (Vec<_>, Vec<_>) = measured.into_iter().partition(|(f, _)| in_band(f));
    let best = match (lowest(band), lowest(short)) {
        (Some(b), Some(s)) if b.1.weighed > ON_SIZE_SLACK * s.1.weighed => Some(s),
        (Some(b), _) => Some(b),
        (None, s) => s,
    };
    Ok(best.map(|(fit, d)| (fit, d.distance.l2_relative())))
}

/// One qp's size fit and, once measured, its distance to the input.
struct Tried {
    qp: u8,
    /// `None`: nothing fits at that qp.
    fit: Option<Fit>,
    distance: Option<Scored>,
}

/// The fits of one climb, in the order made.
#[derive(Default)]
struct Climbed {
    fits: Vec<Tried>,
    /// Whole-mesh file sizes this climb made that were over the budget,
    /// by qp (the lean climb estimates the others' from them).
    over: Vec<(u8, u64)>,
}

impl Climbed {
    /// The fit at `qp`, made once. Its search's first probe comes from
    /// the last fit made (the full climb) or from the simplification
    /// nearest in qp (the lean one).
    fn fit(
        &mut self,
        s: &Simplifier<'_>,
        qp: u8,
        budget: u64,
        lean: bool,
    ) -> Result<Option<&Fit>, Error> {
        if let Some(i) = self.fits.iter().position(|t| t.qp == qp) {
            return Ok(self.fits[i].fit.as_ref());
        }
        let (whole, prev) = if lean {
            // A simplification rather than the whole mesh (whose size
            // predicts nothing of theirs), the finer on a tie.
            let nearest = self
                .fits
                .iter()
                .filter_map(|t| t.fit.as_ref())
                .min_by_key(|f| {
                    let whole = f.faces >= s.faces();
                    (whole, (f.qp as i16 - qp as i16).abs(), u8::MAX - f.qp)
                });
            (self.whole(s, qp, budget), nearest)
        } else {
            let last = self.fits.iter().rev().find_map(|t| t.fit.as_ref());
            (Whole::Encode, last)
        };
        let fit = fit_faces(s, qp, budget, prev, whole, probing(lean))?;
        self.record(s, qp, whole, fit, lean)?;
        Ok(self.fits.last().and_then(|t| t.fit.as_ref()))
    }

    /// Keeps the fit made at `qp` with `whole`, and for the lean climb
    /// (the only reader of `over`) what it showed of the whole mesh's
    /// file.
    fn record(
        &mut self,
        s: &Simplifier<'_>,
        qp: u8,
        whole: Whole,
        fit: Option<Fit>,
        lean: bool,
    ) -> Result<(), Error> {
        let over = fit.as_ref().map_or(true, |f| f.faces < s.faces());
        if lean && whole == Whole::Encode && over {
            // The whole mesh's file was made (the simplifier keeps it)
            // and is over the budget.
            self.over.push((qp, s.whole_bytes(qp)?.len() as u64));
        }
        self.fits.push(Tried {
            qp,
            fit,
            distance: None,
        });
        Ok(())
    }

    /// The lean climb's first steps, which it always takes: the fits at
    /// the predicted `qp` and the one below, both from the `start`'s fit,
    /// beside the start's measure; then both measured side by side. On
    /// two cores they take about the time of one (the climb is otherwise
    /// a chain, each fit starting from the last); the work and the
    /// result are the same on one.
    fn first_pair(
        &mut self,
        s: &Simplifier<'_>,
        start: u8,
        qp: u8,
        budget: u64,
        measure: &(dyn Fn(&Fit) -> Result<Scored, Error> + Sync),
    ) -> Result<(), Error> {
        let below = qp.checked_sub(1).filter(|q| QPS.contains(q));
        let todo: Vec<(u8, Whole)> = [Some(qp), below]
            .into_iter()
            .flatten()
            .filter(|q| self.fits.iter().all(|t| t.qp != *q))
            .map(|q| (q, self.whole(s, q, budget)))
            .collect();
        let from = self
            .fits
            .iter()
            .find(|t| t.qp == start)
            .and_then(|t| t.fit.as_ref());
        let (made, first) = rayon::join(
            || {
                todo.par_iter()
                    .map(|&(q, whole)| fit_faces(s, q, budget, from, whole, Probing::Lean))
                    .collect::<Vec<_>>()
            },
            || from.map(measure).transpose(),
        );
        let first = first?;
        if let Some(t) = self.fits.iter_mut().find(|t| t.qp == start) {
            t.distance = first;
        }
        for (&(q, whole), fit) in todo.iter().zip(made) {
            self.record(s, q, whole, fit?, true)?;
        }
        let pair: Vec<u8> = [Some(qp), below].into_iter().flatten().collect();
        let measured: Vec<Option<Scored>> = pair
            .par_iter()
            .map(|q| {
                let t = self.fits.iter().find(|t| t.qp == *q);
                match t.and_then(|t| t.fit.as_ref().filter(|_| t.distance.is_none())) {
                    Some(fit) => measure(fit).map(Some),
                    None => Ok(None),
                }
            })
            .collect::<Result<_, Error>>()?;
        for (q, d) in pair.iter().zip(measured) {
            if let (Some(t), Some(d)) = (self.fits.iter_mut().find(|t| t.qp == *q), d) {
                t.distance = Some(d);
            }
        }
        Ok(())
    }

    /// The lean climb's knowledge of the whole mesh's file at `qp`: over
    /// the budget when the estimate from the nearest qp whose file this
    /// climb made says so ([`Whole::estimated`]). Only this climb's own
    /// files count, so the bytes never depend on what another search
    /// sharing the simplifier made first.
    fn whole(&self, s: &Simplifier<'_>, qp: u8, budget: u64) -> Whole {
        let nearest = self
            .over
            .iter()
            .min_by_key(|(q, _)| (*q as i16 - qp as i16).abs());
        let Some(&(from, size)) = nearest else {
            return Whole::Encode;
        };
        Whole::estimated(size, from, qp, s.mesh.positions.len() as u64, budget)
    }

    /// The L2 of the fit at `qp` (made before), measured once; `None`
    /// when nothing fits there.
    fn measure(
        &mut self,
        qp: u8,
        measure: &dyn Fn(&Fit) -> Result<Scored, Error>,
    ) -> Result<Option<f64>, Error> {
        let Some(t) = self.fits.iter_mut().find(|t| t.qp == qp) else {
            return Ok(None);
        };
        let Some(fit) = &t.fit else {
            return Ok(None);
        };
        if t.distance.is_none() {
            t.distance = Some(measure(fit)?);
        }
        Ok(t.distance.as_ref().map(|d| d.weighed))
    }
}
