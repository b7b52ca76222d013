//! The quick search of effort `fast`: two size searches and a few
//! samples instead of the climb's four to six searches and large
//! measures ([`super::best_fit`]).
//!
//! 1. The fit at [`START_QP`] (coarser until something fits).
//! 2. A second quantization, chosen by a model of the error (or, where
//!    the model stays within a step, by the face-count rule "qp = log2 F
//!    − 2.5"), fitted when it is two or more steps away; the one of lower
//!    L2 against the reference with [`QUICK_SAMPLES`] samples each way is
//!    kept.
//!
//! The model (beyond the sources; the face-count rule alone, fitted on
//! scans, left every CAD part at qp 10: fandisk's L2 at 8 b/v was 14
//! times the climb's, and larger than at 4 b/v):
//!
//! ```text
//!   L2(q, F)² ≈ e_s(F)² + e_q(q)²
//!   e_q(q) = step(q) / √24      a coordinate rounded to a grid of step Δ
//!                               moves its vertex along the normal by Δ/√12
//!                               (RMS), the surface between interpolated
//!                               vertices by √½ of that
//!   e_s(F) = e_s1 · F1 / F      chord error of a smooth surface ∝ area per face
//!   bits/face(q) = b1 + 1.5 (q − q1)    three coordinates one bit longer,
//!                                       two faces per vertex
//!   F(q) = 8 B / bits/face(q)
//! ```
//!
//! `e_s1` comes from the first fit's measured L2 less its modeled
//! quantization error, and never counts as less than a quarter of that
//! error (2,000 samples cannot tell a smaller share from none, and a part
//! exact at any face count would otherwise be sent to the finest grid
//! with a handful of faces). The quantization of least modeled L2 is
//! the second one; the measure decides between the two fits.
//!
//! When the whole mesh fits at the first quantization, the finest
//! quantization whose whole file still fits is found by bisection, then
//! weighed against a simplified mesh two steps finer (a quarter of the
//! whole file's rounding error, for about a quarter fewer faces), when
//! the face-count rule for the whole mesh is at least that fine, the
//! whole file's grid step is at least a sixteenth of the mean edge, and
//! the input has at most `WHOLE_ALTERNATIVE_FACES` faces:
//! at 8 b/v a whole scan at qp 10 had 1.6-4 times the error of a
//! simplification at qp 12-13 (bunny, horse). The face-count rule's own
//! grid (qp 14 on both) measured 1.20 and 0.58 against 0.94 and 0.57 at
//! two steps.
//!
//! Invariants: every file returned fits the budget; the result depends
//! only on the mesh and the budget, never on the thread count.

use super::faces::{
    fit_faces, predicted_qp, refitted, search_faces, whole_estimate, Fit, Probing, Whole,
};
use super::simplifier::{file_distance, Simplifier, QPS, QUICK_SAMPLES, START_QP};
use crate::metrics::Surface;
use crate::Error;

/// The least share of the first fit's modeled quantization error that
/// its simplification error is taken to be (see the module docs).
const MIN_SIMPLIFICATION_SHARE: f64 = 0.25;

/// Inputs above this many faces keep their whole file when it fits: the
/// simplification it would be weighed against costs a pass of
/// meshoptimizer over the whole input (about 1 µs a face), which fits
/// fast's 0.3 s floor below this count (bunny at 8 b/v: 278 ms, horse
/// 286 ms) and not its 2x-Draco bar above it (bunny-1m at 4 b/v: 3.2 s
/// against 2.4 s, and its whole file at qp 12 won: L2 0.34 against about
/// 0.4 for meshoptimizer's 173k faces at qp 14).
const WHOLE_ALTERNATIVE_FACES: u32 = 100_000;

/// Bits per face each step of quantization adds: one bit for each of
/// three coordinates of a vertex, two faces per vertex.
const BITS_PER_STEP: f64 = 1.5;

/// The quick search (see the module docs); `None` when nothing fits.
pub fn quick_fit<'r>(
    s: &Simplifier<'_>,
    budget: u64,
    reference: &(dyn Fn() -> Result<&'r Surface, Error> + Sync),
) -> Result<Option<Fit>, Error> {
    let mut start = START_QP;
    let first = loop {
        match search_faces(s, start, budget, None, Whole::Encode, Probing::Quick)? {
            Some(fit) => break fit,
            None if start == *QPS.start() => return Ok(None),
            None => start -= 1,
        }
    };
    // (The reference is asked for where it is used: it may still be in
    // the making beside this search, `encoder::simplified`.)
    // (With attribute streams, their error weighed beside it.)
    let l2 = |f: &Fit| -> Result<f64, Error> {
        let d = file_distance(&f.bytes, reference()?, QUICK_SAMPLES)?.l2();
        Ok(d + s.attribute_error(&f.bytes)?)
    };
    if first.faces >= s.faces() {
        return whole_first(s, first, budget, &l2).map(Some);
    }
    // The model's quantization where it moves two steps or more, else
    // the face-count rule's: the model counts every byte as paid per
    // face, so on a file of a few dozen faces, whose header is a fifth
    // of it, it sees too little gain in a coarser grid (woody at 2 b/v:
    // 30 faces at qp 10 against 57 at qp 6, 1.4 times the L2).
    let model = Model::new(s, &first, l2(&first)?, budget).best_qp();
    let by_faces = predicted_qp(first.faces);
    let qp = match model.abs_diff(first.qp) > 1 {
        true => model,
        false => by_faces,
    };
    if qp.abs_diff(first.qp) <= 1 {
        return Ok(Some(refitted(s, first, budget)?));
    }
    let whole = second_whole(s, &first, qp, budget)?;
    // The first fit's refit and its measure run beside the second
    // search, which needs only its face count and slope.
    let (first, second) = rayon::join(
        || -> Result<(Fit, f64), Error> {
            let first = refitted(s, first.clone(), budget)?;
            let l2_first = l2(&first)?;
            Ok((first, l2_first))
        },
        || fit_faces(s, qp, budget, Some(&first), whole, Probing::Quick),
    );
    let (first, l2_first) = first?;
    Ok(Some(match second? {
        Some(second) if l2(&second)? <= l2_first => second,
        _ => first,
    }))
}

/// What the second size search knows of the whole mesh's file at `qp`:
/// over the budget without coding it when the first fit's whole file
/// shows it so (a million triangles take half a second to code).
fn second_whole(s: &Simplifier<'_>, first: &Fit, qp: u8, budget: u64) -> Result<Whole, Error> {
    let whole = s.whole_bytes(first.qp)?.len() as u64;
    let vertices = s.mesh.positions.len() as u64;
    Ok(Whole::estimated(whole, first.qp, qp, vertices, budget))
}

/// The whole mesh fits at `first.qp`: the finest quantization whose
/// whole file still fits, or a simplification at a finer one.
fn whole_first(
    s: &Simplifier<'_>,
    first: Fit,
    budget: u64,
    l2: &(dyn Fn(&Fit) -> Result<f64, Error> + Sync),
) -> Result<Fit, Error> {
    // A finer grid makes a larger file, so the finest whole file that
    // fits is searched from the size model's guess (`whole_estimate`,
    // close above the measured grid): one file to confirm the guess and
    // one to show the next grid over, where a bisection from the first
    // fit's grid coded three (horse at 8 b/v; the same answer, sizes
    // growing with the grid).
    let vertices = s.mesh.positions.len() as u64;
    let guess = (first.qp + 1..=*QPS.end())
        .take_while(|&qp| {
            whole_estimate(first.bytes.len() as u64, first.qp, qp, vertices) <= budget
        })
        .last()
        .unwrap_or(first.qp + 1);
    let (mut lo, mut hi) = (first, *QPS.end() + 1);
    let mut next = guess.min(*QPS.end());
    while lo.qp < next && next < hi {
        let bytes = s.whole_bytes(next)?;
        if bytes.len() as u64 <= budget {
            lo = Fit {
                qp: next,
                bytes,
                stats: None,
                ..lo
            };
            next += 1;
        } else {
            hi = next;
            next -= 1;
        }
    }
    let whole = lo;
    // Two steps finer than the whole file (see the module docs), where
    // the face-count rule is that fine and the grid shows on the edges.
    let qp = whole.qp + 2;
    if s.faces() > WHOLE_ALTERNATIVE_FACES
        || predicted_qp(s.faces()) < qp
        || qp > *QPS.end()
        || !rounding_shows(s, whole.qp)
    {
        return Ok(whole);
    }
    let over = whole_estimate(whole.bytes.len() as u64, whole.qp, qp, vertices).max(budget + 1);
    let (simplified, l2_whole) = rayon::join(
        || fit_faces(s, qp, budget, None, Whole::Over(over), Probing::Quick),
        || l2(&whole),
    );
    let Some(simplified) = simplified? else {
        return Ok(whole);
    };
    Ok(if l2(&simplified)? < l2_whole? {
        simplified
    } else {
        whole
    })
}

/// What the model takes of the first fit.
struct Figures {
    qp: u8,
    faces: f64,
    bytes: f64,
    /// Its measured L2 (absolute).
    l2: f64,
}

/// Whether the grid at `qp` is coarse enough against the mesh's edges for
/// a simplification at a finer grid to have a chance: its step at least
/// a sixteenth of the mean edge. Measured: bunny's and horse's whole files
/// at 8 b/v (qp 10, edges 9.7 and 5.5 steps long) lost to a
/// simplification two steps finer (L2 1.24 against 0.94, 1.46 against
/// 0.57); bunny-1m's (qp 14, edges 38 steps long) won, after a search
/// that took its encode from 2.1 to 7.5 s of work.
fn rounding_shows(s: &Simplifier<'_>, qp: u8) -> bool {
    let m = s.mesh;
    let step = grid_step(grid_side(m), qp);
    let (mut sum, mut n) = (0.0f64, 0u64);
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (
                m.positions[t[k] as usize],
                m.positions[t[(k + 1) % 3] as usize],
            );
            let d: f64 = (0..3).map(|i| (a[i] as f64 - b[i] as f64).powi(2)).sum();
            sum += d.sqrt();
            n += 1;
        }
    }
    n > 0 && step * 16.0 * n as f64 >= sum
}

/// The side of the cube the lossless mode quantizes `mesh` on: its
/// bounding box's largest side (0 for an empty mesh).
fn grid_side(mesh: &crate::TriMesh) -> f64 {
    mesh.bbox().map_or(0.0, |(lo, hi)| (hi - lo).max_element())
}

/// One step of the grid of side `side` at `qp` bits, as
/// `geometry::Quantizer::step` takes it.
fn grid_step(side: f64, qp: u8) -> f64 {
    side / ((1u64 << qp) - 1) as f64
}

/// The error model of the module's docs, calibrated on the first fit.
struct Model {
    /// The first fit's quantization, faces and bits per face.
    qp: u8,
    faces: f64,
    bits_per_face: f64,
    /// Its simplification error (absolute, as the distance measures).
    simplification: f64,
    /// The side of the quantization grid's cube.
    range: f64,
    /// Faces of the input: a fit has fewer.
    full: f64,
    /// Bits of the budget.
    budget_bits: f64,
}

impl Model {
    fn new(s: &Simplifier<'_>, first: &Fit, l2: f64, budget: u64) -> Model {
        let range = grid_side(s.mesh);
        let figures = Figures {
            qp: first.qp,
            faces: first.faces.max(1) as f64,
            bytes: first.bytes.len() as f64,
            l2,
        };
        Model::calibrated(figures, range, s.faces() as f64, budget as f64)
    }

    /// The model of a first fit's `figures`, for a grid of side `range`,
    /// an input of `full` faces and a budget of `budget` bytes.
    fn calibrated(figures: Figures, range: f64, full: f64, budget: f64) -> Model {
        let mut model = Model {
            qp: figures.qp,
            faces: figures.faces,
            bits_per_face: 8.0 * figures.bytes / figures.faces,
            simplification: 0.0,
            range,
            full,
            budget_bits: 8.0 * budget,
        };
        let quantization = model.quantization(figures.qp);
        model.simplification = (figures.l2 * figures.l2 - quantization * quantization)
            .max(0.0)
            .sqrt()
            .max(MIN_SIMPLIFICATION_SHARE * quantization);
        model
    }

    /// The modeled quantization error at `qp`.
    fn quantization(&self, qp: u8) -> f64 {
        grid_step(self.range, qp) / 24f64.sqrt()
    }

    /// The modeled squared L2 of the fit at `qp`, or `None` where the
    /// budget would hold the whole mesh (not a simplification).
    fn error2(&self, qp: u8) -> Option<f64> {
        let steps = qp as f64 - self.qp as f64;
        let bits = (self.bits_per_face + BITS_PER_STEP * steps).max(BITS_PER_STEP);
        let faces = self.budget_bits / bits;
        if faces >= self.full {
            return None;
        }
        let simplification = self.simplification * self.faces / faces.max(1.0);
        let quantization = self.quantization(qp);
        Some(simplification * simplification + quantization * quantization)
    }

    /// The quantization of least modeled error (the coarser on a tie).
    fn best_qp(&self) -> u8 {
        let mut best = (self.qp, self.error2(self.qp).unwrap_or(f64::INFINITY));
        for qp in QPS {
            if let Some(e) = self.error2(qp) {
                if e < best.1 || (e == best.1 && qp < best.0) {
                    best = (qp, e);
                }
            }
        }
        best.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rounding's modeled error at qp 10 on a grid of side 1.
    fn rounding_10() -> f64 {
        1.0 / 1023.0 / 24f64.sqrt()
    }

    /// The model of a first fit at qp 10 of `faces` faces and
    /// `bits_per_face` that filled the budget, measured at `l2`.
    fn model(l2: f64, bits_per_face: f64, faces: f64) -> Model {
        let figures = Figures {
            qp: 10,
            faces,
            bytes: bits_per_face * faces / 8.0,
            l2,
        };
        Model::calibrated(figures, 1.0, 1e6, bits_per_face * faces / 8.0)
    }

    #[test]
    fn a_part_whose_error_is_rounding_goes_to_a_finer_grid() {
        // fandisk at 8 b/v: 5,906 faces at 8.7 bits each, its L2 all but
        // qp 10's rounding. The climb takes qp 15 with 3,214 faces.
        for l2 in [0.9 * rounding_10(), rounding_10(), 1.05 * rounding_10()] {
            let qp = model(l2, 8.7, 5906.0).best_qp();
            assert!((12..=14).contains(&qp), "{qp}");
        }
    }

    #[test]
    fn a_scan_whose_chords_dominate_stays_at_the_first_grid() {
        // bunny at 2 b/v: 6,530 faces at 10.8 bits, L2 2.6 times qp 10's
        // rounding.
        let m = model(2.6 * rounding_10(), 10.8, 6530.0);
        assert_eq!(m.best_qp(), 10);
    }

    #[test]
    fn a_coarser_grid_when_chords_dominate_further() {
        let m = model(8.0 * rounding_10(), 10.8, 6530.0);
        assert!(m.best_qp() < 10, "{}", m.best_qp());
    }

    #[test]
    fn the_finest_grid_is_not_taken_when_it_leaves_no_faces() {
        // A part exact at any count, with a hundred faces' budget.
        let qp = model(rounding_10(), 8.0, 100.0).best_qp();
        assert!((11..*QPS.end()).contains(&qp), "{qp}");
    }
}
