//! The size search for one quantization: the largest face count of the
//! collapse sequence whose mode-0 file at that qp fits a byte budget
//! (step 1 of the module's search, [`super`]).
//!
//! Size grows with the face count almost linearly, so the search is a
//! secant on log size against log faces inside a bracket [fits, does not
//! fit], bisecting when the secant creeps. Invariants: every file it
//! returns fits the budget; its probes depend only on the mesh, the qp,
//! the budget and the previous qp's answer (deterministic).

use super::simplifier::{Simplifier, MIN_FACES, QPS};
use crate::lossless::LosslessStats;
use crate::{Error, TriMesh};

/// The search stops when fitting and non-fitting face counts are this
/// close, relative to the face count...
const PRECISION: f64 = 0.005;
/// ... or when a fitting file fills this much of the budget: sizes jitter
/// by a few tenths of a percent between neighbouring face counts, so
/// chasing the last percent costs probes and buys noise.
const FILL: f64 = 0.99;
/// Effort `fast`'s fill: rate control's tolerance. On horse at 4 b/v
/// both of its size searches stop a probe earlier.
const QUICK_FILL: f64 = 0.97;

/// How a size search spends its probes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Probing {
    /// From the previous qp's face count, to [`FILL`] (effort `max`).
    Full,
    /// From the face count the previous fit predicts, to [`FILL`]
    /// (effort `default`).
    Lean,
    /// As `Lean`, to [`QUICK_FILL`] (effort `fast`).
    Quick,
}

impl Probing {
    fn lean(self) -> bool {
        self != Probing::Full
    }

    fn fill(self) -> f64 {
        match self {
            Probing::Quick => QUICK_FILL,
            _ => FILL,
        }
    }
}
/// A bound the search never meets in practice (bisection over 2^32 face
/// counts takes about 25 probes); if it did, the best fit so far stands.
const MAX_PROBES: usize = 64;

/// The best face count found for one qp.
#[derive(Clone, Debug)]
pub struct Fit {
    /// Bits per coordinate.
    pub qp: u8,
    /// Faces asked of the simplifier.
    pub faces: u32,
    /// The simplified mesh.
    pub mesh: TriMesh,
    /// Its mode-0 file.
    pub bytes: Vec<u8>,
    /// That file's figures, when it was coded from `mesh` (not for the
    /// whole mesh's files, whose figures the simplifier keeps): the
    /// method returns them without coding the winner again.
    pub stats: Option<LosslessStats>,
    /// d log(size) / d log(faces) near the answer: the next qp's search
    /// extrapolates with it.
    pub(super) slope: f64,
}

/// A probed face count and its file size.
#[derive(Clone, Copy)]
struct Probe {
    faces: u32,
    size: u64,
}

impl Probe {
    fn ln(self) -> (f64, f64) {
        ((self.faces as f64).ln(), (self.size as f64).ln())
    }
}

/// Log-log slope between two probes, kept in a sane range so that a noisy
/// pair cannot throw the next probe far away.
fn slope(a: Probe, b: Probe) -> f64 {
    let ((fa, sa), (fb, sb)) = (a.ln(), b.ln());
    if (fa - fb).abs() < 1e-12 {
        return 1.0;
    }
    ((sa - sb) / (fa - fb)).clamp(0.5, 1.5)
}

/// The face count at which the line through `p` with log-log `slope`
/// reaches `size`.
fn aim(p: Probe, slope: f64, size: f64) -> f64 {
    let (f, s) = p.ln();
    (f + (size.ln() - s) / slope).exp()
}

/// The largest face count (within [`PRECISION`], or filling [`FILL`] of
/// the budget) whose file at `qp` fits `budget`; `None` when even
/// `MIN_FACES` faces do not fit.
///
/// `whole` says whether the whole mesh's file at `qp` is made or known
/// to be over the budget. The full search (`lean` false) starts from the
/// previous qp's face count; the lean one from the face count the
/// previous fit predicts at this qp ([`predicted_faces`]), and it keeps
/// aiming with its slope while the whole mesh bounds the bracket. Both
/// refit the answer to the input ([`refitted`]).
pub fn fit_faces(
    s: &Simplifier<'_>,
    qp: u8,
    budget: u64,
    prev: Option<&Fit>,
    whole: Whole,
    probing: Probing,
) -> Result<Option<Fit>, Error> {
    // The answer refitted to the input: once per qp, not per probe (the
    // lean search too: ranking fits as simplified chose worse qps, 4%
    // more L2 over spot, cheburashka, homer and teapot).
    match search_faces(s, qp, budget, prev, whole, probing)? {
        Some(fit) => Ok(Some(refitted(s, fit, budget)?)),
        None => Ok(None),
    }
}

/// [`fit_faces`] before its refit: the same face count, slope and qp (a
/// refit moves vertices, never the count), so a later search may start
/// from it while the refit runs beside it (`climb::quick_fit`).
pub(super) fn search_faces(
    s: &Simplifier<'_>,
    qp: u8,
    budget: u64,
    prev: Option<&Fit>,
    whole: Whole,
    probing: Probing,
) -> Result<Option<Fit>, Error> {
    let (lean, fill) = (probing.lean(), probing.fill());
    let full = s.faces();
    let budget_f = budget as f64;
    let model_guess = model_faces(qp, 0.98 * budget_f) * s.first_probe_factor();
    // The first probe is the previous qp's face count (the lean search
    // moves it as the prediction says; its replay is a linear pass; the
    // answer's mesh is refitted, the probes are not); without one, the
    // loop's first guess. (None on a mesh too small to simplify, which
    // returns below before probing.)
    let from_prev = prev
        .filter(|p| p.faces < full && full > MIN_FACES)
        .map(|p| {
            if lean {
                predicted_faces(p, qp, budget_f, full, fill)
            } else {
                p.faces
            }
        });
    // The lean search's first probe, made beside the whole mesh's file.
    let mut ahead: Option<(u32, TriMesh)> = None;
    let full_size = match whole {
        Whole::Over(size) => size.max(budget.saturating_add(1)),
        Whole::Encode => {
            // The lean search's first probe comes from the model or the
            // previous fit, never from the whole mesh's file: where that
            // file is unlikely to fit (a budget under 1.5 bits per face:
            // bunny-1m's whole file takes 1.55 at qp 10 and 1.36 at qp 8,
            // and 1.0 at 2 b/v once kept it off this path), the probe is
            // simplified beside it, and dropped if it does fit. The same
            // probes either way; on two cores the whole file's time (0.5 s
            // on a million triangles) leaves the wall clock; where the
            // whole file does fit, the wasted probe costs its simplification
            // less that time.
            let ahead_pays = budget.saturating_mul(16) < 3 * full as u64;
            let full_bytes = if lean && ahead_pays && full > MIN_FACES {
                let faces = from_prev
                    .unwrap_or_else(|| (model_guess.round() as u32).clamp(MIN_FACES, full - 1));
                // The long task first: the file is the one left to steal.
                let (mesh, bytes) = rayon::join(|| s.simplify(faces), || s.whole_bytes(qp));
                ahead = Some((faces, mesh));
                bytes?
            } else {
                s.whole_bytes(qp)?
            };
            if full_bytes.len() as u64 <= budget {
                return Ok(Some(Fit {
                    qp,
                    faces: full,
                    mesh: s.mesh.clone(),
                    bytes: full_bytes,
                    stats: None,
                    slope: 1.0,
                }));
            }
            full_bytes.len() as u64
        }
    };
    // Face counts below this clean to nothing (a simplification of only
    // zero-area faces): they neither fit nor overflow, they are out.
    let mut degenerate_below = MIN_FACES;
    if full <= MIN_FACES {
        return Ok(None);
    }
    // `hi`: the fewest faces known not to fit; `lo`: the most known to fit.
    let mut hi = Probe {
        faces: full,
        size: full_size,
    };
    let mut lo: Option<(Probe, TriMesh, Vec<u8>, LosslessStats)> = None;
    // Simplified probes only: the unsimplified mesh is far cheaper per
    // face than any simplification, so slopes through it mislead.
    let mut probes: Vec<Probe> = Vec::new();
    let mut last_fitted: Option<bool> = None;
    let mut slope_down = prev.map_or(1.0, |p| p.slope);
    let mut guess = if lean {
        model_guess
    } else {
        aim(hi, slope_down, 0.98 * budget_f)
    };
    let mut made = ahead.or_else(|| from_prev.map(|faces| (faces, s.simplify(faces))));
    for _ in 0..MAX_PROBES {
        let (faces, mesh) = match made.take() {
            Some(made) => made,
            None => {
                let floor = lo
                    .as_ref()
                    .map_or(MIN_FACES, |l| l.0.faces + 1)
                    .max(degenerate_below);
                if floor >= hi.faces {
                    break;
                }
                let faces = (guess.round() as u32).clamp(floor, hi.faces - 1);
                (faces, s.simplify(faces))
            }
        };
        let Some((bytes, stats)) = s.code(faces, &mesh, qp)? else {
            degenerate_below = degenerate_below.max(faces + 1).max(2 * faces);
            continue;
        };
        let probe = Probe {
            faces,
            size: bytes.len() as u64,
        };
        let fits = probe.size <= budget;
        let same_side = last_fitted == Some(fits);
        last_fitted = Some(fits);
        probes.push(probe);
        if fits {
            lo = Some((probe, mesh, bytes, stats));
        } else if faces <= MIN_FACES {
            return Ok(None);
        } else {
            hi = probe;
        }
        let Some((l, ..)) = &lo else {
            // Nothing fits yet: extrapolate down from `hi` along the slope
            // of the last two probes (both too big), aiming a little under
            // the budget so that the next probe fits.
            if let [.., a, b] = probes[..] {
                slope_down = slope(a, b);
            }
            guess = aim(hi, slope_down, 0.98 * budget_f);
            continue;
        };
        let narrow = (hi.faces - l.faces) as f64 <= (l.faces as f64 * PRECISION).max(1.0);
        if narrow || l.size as f64 >= fill * budget_f {
            break;
        }
        let band = (1.0 + fill) / 2.0 * budget_f;
        guess = if lean && hi.faces >= full {
            // Only the whole mesh above, whose slopes mislead: the lean
            // search aims along its last two probes (both fit), or the
            // previous qp's slope after one.
            let k = match probes[..] {
                [.., a, b] => slope(a, b),
                _ => slope_down,
            };
            aim(*l, k, band)
        } else if same_side {
            // Two probes on the same side: the secant is creeping.
            (l.faces as f64 * hi.faces as f64).sqrt()
        } else {
            // Aim inside the accepted band, not at its edge.
            aim(*l, slope(*l, hi), band)
        };
    }
    let Some((l, mesh, bytes, stats)) = lo else {
        return Ok(None);
    };
    let fit = {
        // The widest pair gives the steadiest slope for the next qp.
        let far = probes
            .iter()
            .copied()
            .filter(|p| p.faces != l.faces)
            .max_by(|a, b| {
                let d = |p: &Probe| (p.faces as f64 / l.faces as f64).ln().abs();
                d(a).total_cmp(&d(b))
            });
        let slope = far.map_or(1.0, |p| slope(l, p));
        Fit {
            qp,
            faces: l.faces,
            mesh,
            bytes,
            stats: Some(stats),
            slope,
        }
    };
    Ok(Some(fit))
}

/// Bits per face of a simplified mesh's file at `qp`, as a first guess
/// where no simplification has been coded yet: connectivity and the
/// residuals of half a vertex per face, about 1.5 bits per face for each
/// bit of the grid beyond the first four that prediction saves (bunny:
/// 14.3 bits per face at qp 14, 10.9 at 12, 9.0 at 11). The whole mesh
/// is far cheaper per face, so a guess through it lands far over.
fn model_bits_per_face(qp: u8) -> f64 {
    (1.5 * qp as f64 - 6.0).max(4.0)
}

/// The face count whose file at `qp` fills `size` bytes by
/// [`model_bits_per_face`].
fn model_faces(qp: u8, size: f64) -> f64 {
    8.0 * size / model_bits_per_face(qp)
}

/// The face count whose file at `qp` the previous qp's fit `p` predicts
/// in the middle of the accepted band: its file's size moved to `qp` as
/// [`whole_estimate`] moves a whole mesh's (within a few tenths of a
/// percent on bunny between neighbouring qps), then along its slope.
fn predicted_faces(p: &Fit, qp: u8, budget: f64, full: u32, fill: f64) -> u32 {
    let size = whole_estimate(
        p.bytes.len() as u64,
        p.qp,
        qp,
        p.mesh.positions.len() as u64,
    );
    let at = Probe {
        faces: p.faces,
        size: size.max(1),
    };
    let faces = aim(at, p.slope, (1.0 + fill) / 2.0 * budget);
    (faces.round() as u32).clamp(MIN_FACES, full - 1)
}

/// `fit` refitted to the input ([`Simplifier::refit`]) when its file
/// still fits `budget` (moving the vertices changes the residuals a
/// little), as it is otherwise; the whole mesh is never moved.
pub(super) fn refitted(s: &Simplifier<'_>, fit: Fit, budget: u64) -> Result<Fit, Error> {
    if fit.faces >= s.faces() {
        return Ok(fit);
    }
    let mut mesh = fit.mesh.clone();
    s.refit(&mut mesh);
    Ok(match s.code(fit.faces, &mesh, fit.qp)? {
        Some((bytes, stats)) if bytes.len() as u64 <= budget => Fit {
            mesh,
            bytes,
            stats: Some(stats),
            ..fit
        },
        _ => fit,
    })
}

/// What a size search knows of the whole mesh's file at its qp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Whole {
    /// Nothing: it is made (or taken from the simplifier's cache), and
    /// returned when it fits.
    Encode,
    /// It is over the budget, at about this size: the search's bracket
    /// starts there without coding it (the lean climb, from a coarser
    /// qp's whole file; [`whole_estimate`]).
    Over(u64),
}

/// A whole-mesh file estimated at this much over the budget is taken as
/// over it: the estimate is a lower bound below the qp it starts from
/// and within a few percent above it.
const WHOLE_MARGIN: f64 = 1.05;

impl Whole {
    /// What a search at `qp` knows of the whole mesh's file from its
    /// `size` at `from` ([`whole_estimate`] over `vertices`): over the
    /// budget when the estimate says so by [`WHOLE_MARGIN`], else to be
    /// made.
    pub(super) fn estimated(size: u64, from: u8, qp: u8, vertices: u64, budget: u64) -> Whole {
        let estimate = whole_estimate(size, from, qp, vertices);
        if estimate as f64 > WHOLE_MARGIN * budget as f64 {
            Whole::Over(estimate)
        } else {
            Whole::Encode
        }
    }
}

/// The quantization the bits-per-face model predicts for a
/// simplification of `faces` faces, log2 F − 2.5, within [`QPS`]: where
/// the climb starts, and `fast`'s rule where its error model stays.
pub(super) fn predicted_qp(faces: u32) -> u8 {
    let predicted = ((faces.max(1) as f64).log2() - 2.5).round() as i64;
    predicted.clamp(*QPS.start() as i64, *QPS.end() as i64) as u8
}

/// The whole mesh's file size at `qp` estimated from its `size` at `from`:
/// one more bit per coordinate costs about one more bit per coordinate of
/// each of `vertices` (parallelogram residuals double), a little less at
/// coarse grids, where residuals are near zero. So the estimate is a
/// lower bound below `from` and close above it.
pub(super) fn whole_estimate(size: u64, from: u8, qp: u8, vertices: u64) -> u64 {
    let bits = 3 * vertices;
    if qp >= from {
        size.saturating_add((qp - from) as u64 * bits / 8)
    } else {
        size.saturating_sub((from - qp) as u64 * bits / 8)
    }
}
