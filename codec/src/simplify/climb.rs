//! The search over quantizations (steps 2 and 3 of the module's search,
//! [`super`]): which qp's size fit ([`fit_faces`]) is closest to the
//! input. The full search climbs from a predicted qp and measures each
//! fit; the quick one (effort `fast`) fits two and ranks them with a few
//! samples.
//!
//! Invariants: every file returned fits the budget; the result depends
//! only on the mesh and the budget (the distance's samples are seeded and
//! summed in a fixed order), never on the thread count.

use super::faces::{fit_faces, Fit};
use super::{file_distance, Simplifier, MIN_FACES, ON_SIZE_SLACK, QPS, QUICK_SAMPLES, START_QP};
use crate::metrics::{Surface, SurfaceDistance};
use crate::Error;

/// The fit of lowest measured L2 against `reference` over [`QPS`], with
/// `samples` area-uniform face samples per direction, and that L2
/// relative to the reference's diagonal; `None` when no qp fits even
/// `MIN_FACES` faces in `budget` bytes.
///
/// The error is unimodal in qp (coarser positions against fewer faces),
/// so the search climbs from a predicted qp instead of trying all of
/// them: a first fit at [`START_QP`] gives the face count F, the best qp
/// is near `log2 F − 2.5` (measured on the shared corpus: `log2 F` minus
/// 2.4 to 2.9 on scans, up to 1.4 above on CAD parts), and the climb
/// moves one qp at a time while the error falls, about four fits in all
/// instead of nine.
pub fn best_fit<'r>(
    s: &Simplifier<'_>,
    budget: u64,
    reference: &dyn Fn() -> Result<&'r Surface, Error>,
    samples: u64,
) -> Result<Option<(Fit, f64)>, Error> {
    // Each qp tried, with its fit and that fit's distance to the
    // reference (`None`: nothing fits at that qp), in the order tried.
    type Tried = Vec<(u8, Option<(Fit, SurfaceDistance)>)>;
    let score = |qp: u8, tried: &mut Tried| -> Result<Option<f64>, Error> {
        if let Some((_, r)) = tried.iter().find(|(q, _)| *q == qp) {
            return Ok(r.as_ref().map(|r| r.1.l2()));
        }
        // The last fit made is the next search's first probe.
        let prev = tried
            .iter()
            .rev()
            .find_map(|(_, r)| r.as_ref().map(|r| &r.0));
        let scored = match fit_faces(s, qp, budget, prev)? {
            Some(fit) => {
                let d = file_distance(&fit.bytes, reference()?, samples)?;
                Some((fit, d))
            }
            None => None,
        };
        let l2 = scored.as_ref().map(|r| r.1.l2());
        tried.push((qp, scored));
        Ok(l2)
    };
    let mut tried = Tried::new();
    // The first fit; coarser qps until something fits.
    let mut start = START_QP;
    while score(start, &mut tried)?.is_none() {
        if start == *QPS.start() {
            return Ok(None);
        }
        start -= 1;
    }
    let faces = tried
        .iter()
        .find_map(|(_, r)| r.as_ref().map(|r| r.0.faces))
        .unwrap_or(MIN_FACES);
    let predicted = ((faces.max(1) as f64).log2() - 2.5).round() as i64;
    let mut qp = predicted.clamp(*QPS.start() as i64, *QPS.end() as i64) as u8;
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
    tried.sort_by_key(|(q, _)| *q);
    let in_band = |f: &Fit| {
        f.faces >= s.faces()
            || f.bytes.len() as f64 >= (1.0 - crate::retile::rate::TOLERANCE) * budget as f64
    };
    let lowest = |fits: Vec<(Fit, SurfaceDistance)>| {
        fits.into_iter()
            .reduce(|a, b| if b.1.l2() < a.1.l2() { b } else { a })
    };
    let (band, short): (Vec<_>, Vec<_>) = tried
        .into_iter()
        .filter_map(|(_, r)| r)
        .partition(|(f, _)| in_band(f));
    let best = match (lowest(band), lowest(short)) {
        (Some(b), Some(s)) if b.1.l2() > ON_SIZE_SLACK * s.1.l2() => Some(s),
        (Some(b), _) => Some(b),
        (None, s) => s,
    };
    Ok(best.map(|(fit, d)| (fit, d.l2_relative())))
}

/// The quick search of effort `fast`: the fit at [`START_QP`] (coarser
/// until something fits), then the fit at the quantization its face
/// count predicts (as [`best_fit`] starts its climb); the one of lower
/// L2 against `reference` with [`QUICK_SAMPLES`] samples each way is
/// kept. About two size searches instead of four to six, and two small
/// measures instead of four to six large ones. When the whole mesh fits, the
/// finest quantization whose whole-mesh file still fits. `None` when
/// nothing fits.
pub fn quick_fit<'r>(
    s: &Simplifier<'_>,
    budget: u64,
    reference: &dyn Fn() -> Result<&'r Surface, Error>,
) -> Result<Option<Fit>, Error> {
    let mut start = START_QP;
    let first = loop {
        match fit_faces(s, start, budget, None)? {
            Some(fit) => break fit,
            None if start == *QPS.start() => return Ok(None),
            None => start -= 1,
        }
    };
    // The whole mesh fits: the finest quantization whose whole-mesh file
    // still fits (nothing is simplified; only the grid can improve).
    if first.faces >= s.faces() {
        let mut best = first;
        for qp in best.qp + 1..=*QPS.end() {
            let bytes = s.whole_bytes(qp)?;
            if bytes.len() as u64 > budget {
                break;
            }
            best = Fit { qp, bytes, ..best };
        }
        return Ok(Some(best));
    }
    let predicted = ((first.faces.max(1) as f64).log2() - 2.5).round() as i64;
    let qp = predicted.clamp(*QPS.start() as i64, *QPS.end() as i64) as u8;
    if qp == first.qp {
        return Ok(Some(first));
    }
    let Some(second) = fit_faces(s, qp, budget, Some(&first))? else {
        return Ok(Some(first));
    };
    // The prediction holds on scans and misses on CAD parts, whose best
    // quantization is finer (alligator at 2 b/v: 6 predicted, 11 best);
    // a few samples tell the two fits apart at a fraction of a decode.
    let l2 = |f: &Fit| -> Result<f64, Error> {
        Ok(file_distance(&f.bytes, reference()?, QUICK_SAMPLES)?.l2())
    };
    Ok(Some(if l2(&second)? <= l2(&first)? {
        second
    } else {
        first
    }))
}
