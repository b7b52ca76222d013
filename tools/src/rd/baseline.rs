//! The baseline configuration: "simplify, then lossless" — what a user
//! does today without retiling, and the curve SwingWrapper must beat.
//!
//! Sources: thesis Table 7-3 (Garland–Heckbert quadric simplification,
//! then Edgebreaker with quantized positions; Attene 2004, §7.4) and the
//! shared corpus's "quadric simplification + Draco" figures (MeshLab's
//! quadric edge collapse with optimal placement, then Draco, keeping the
//! best pair of face count and quantization in 7..14 bits). Here the
//! simplifier is meshoptimizer's (`meshopt_simplifyWithUpdate`, quadric
//! error with optimal vertex placement, Garland & Heckbert 1997) and the
//! coder is swm's lossless mode.
//!
//! For a byte budget B:
//! 1. for each qp in 7..=14, find the largest face count whose file fits
//!    B. File size grows with the face count almost linearly, a little
//!    less than linearly at low counts (coarser meshes predict worse), so
//!    the search is a secant on log size against log faces inside a
//!    bracket [fits, does not fit], falling back to bisection when the
//!    secant stalls; it stops when the bracket is within 0.5% of the face
//!    count or the file fills 99% of the budget. The previous qp's answer is the next qp's first probe (its
//!    simplification is already made), so after qp 7 a search costs about
//!    two simplifications;
//! 2. decode each qp's file and measure its L2 against the input with a
//!    tenth of the samples (quantization error included: that is what the
//!    qp trades against faces); keep the lowest, the smaller qp on a tie;
//! 3. make the winner again, timed, and measure it with all the samples.
//!
//! meshoptimizer is asked for a face count with an error limit it cannot
//! reach, so the count alone decides; it may stop a few faces short where
//! topology forbids collapses. The input is welded first (`swm::clean`):
//! meshoptimizer treats vertices split along seams as borders and would
//! refuse to collapse across them.

use crate::rd::case::{encode, Case};
use crate::rd::config::finish;
use crate::rd::table::Coded;
use crate::CliError;
use rayon::prelude::*;
use std::borrow::Cow;
use std::collections::HashMap;
use std::ops::RangeInclusive;
use std::sync::{Arc, Mutex};
use swm::TriMesh;

/// Quantizations tried (those of the shared corpus's peer figures).
pub const QPS: RangeInclusive<u8> = 7..=14;
/// Fewer faces than a tetrahedron's make no surface worth measuring.
const MIN_FACES: u32 = 4;
/// The search stops when fitting and non-fitting face counts are this
/// close, relative to the face count...
const PRECISION: f64 = 0.005;
/// ... or when a fitting file fills this much of the budget: sizes jitter
/// by a few tenths of a percent between neighbouring face counts, so
/// chasing the last percent costs probes and buys noise.
const FILL: f64 = 0.99;
/// A bound the search never meets in practice (bisection over 2^32 face
/// counts takes about 25 probes); if it did, the best fit so far stands.
const MAX_PROBES: usize = 64;

/// The input, welded and ready for meshoptimizer, plus the sizes of the
/// unsimplified mesh (the same for every rate).
pub struct Simplifier {
    welded: TriMesh,
    indices: Vec<u32>,
    full_sizes: Mutex<HashMap<u8, u64>>,
}

impl Simplifier {
    /// Welds `mesh` (merges coincident vertices, drops degenerate faces).
    pub fn new(mesh: &TriMesh) -> Result<Simplifier, swm::Error> {
        let welded = swm::clean(mesh, &swm::CleanOptions::default())?.mesh;
        let indices = welded.triangles.iter().flatten().copied().collect();
        Ok(Simplifier {
            welded,
            indices,
            full_sizes: Mutex::new(HashMap::new()),
        })
    }

    /// Faces of the welded input.
    pub fn faces(&self) -> u32 {
        self.welded.triangles.len() as u32
    }

    /// The input simplified to at most `target` faces (the input itself
    /// when it has no more). Deterministic.
    pub fn simplify(&self, target: u32) -> TriMesh {
        if target >= self.faces() {
            return self.welded.clone();
        }
        let mut indices = self.indices.clone();
        let mut positions = self.welded.positions.clone();
        let n = meshopt::simplify_with_update(
            &mut indices,
            &mut positions,
            &mut [],
            &[],
            0,
            None,
            3 * target as usize,
            f32::MAX,
            meshopt::SimplifyOptions::None,
            None,
        );
        compact(&positions, &indices[..n])
    }

    /// File size of the unsimplified input at `qp`.
    fn full_size(&self, qp: u8) -> Result<u64, swm::Error> {
        if let Some(&n) = self.full_sizes.lock().expect("cache lock").get(&qp) {
            return Ok(n);
        }
        let n = encode(&self.welded, qp)?.len() as u64;
        self.full_sizes.lock().expect("cache lock").insert(qp, n);
        Ok(n)
    }
}

/// Keeps the vertices `indices` use, renumbered in order of first use.
fn compact(positions: &[[f32; 3]], indices: &[u32]) -> TriMesh {
    let mut remap = vec![u32::MAX; positions.len()];
    let mut out = TriMesh {
        positions: Vec::new(),
        triangles: Vec::with_capacity(indices.len() / 3),
    };
    for t in indices.chunks_exact(3) {
        let tri = [t[0], t[1], t[2]].map(|v| {
            let slot = &mut remap[v as usize];
            if *slot == u32::MAX {
                *slot = out.positions.len() as u32;
                out.positions.push(positions[v as usize]);
            }
            *slot
        });
        out.triangles.push(tri);
    }
    out
}

/// The best face count found for one qp.
struct Fit {
    qp: u8,
    faces: u32,
    mesh: Arc<TriMesh>,
    bytes: Vec<u8>,
    /// d log(size) / d log(faces) near the answer: the next qp's search
    /// extrapolates with it.
    slope: f64,
}

/// The baseline at one budget; `None` if no qp fits even a tetrahedron.
pub fn run(case: &Case, budget: u64, samples: u64) -> Result<Option<Coded>, CliError> {
    let mut fits: Vec<Fit> = Vec::new();
    for qp in QPS {
        let prev = fits.last();
        if let Some(fit) = fit_faces(case, qp, budget, prev).map_err(|e| case.err(e))? {
            fits.push(fit);
        }
    }
    let candidate_samples = candidate_samples(samples);
    let scored: Vec<(f64, &Fit)> = if fits.len() == 1 {
        vec![(0.0, &fits[0])]
    } else {
        fits.par_iter()
            .map(|fit| {
                let decoded = swm::decode(&fit.bytes, &swm::DecodeOptions::default())
                    .map_err(|e| case.err(e))?;
                Ok((case.distance(&decoded, candidate_samples)?.0, fit))
            })
            .collect::<Result<_, CliError>>()?
    };
    // The first minimum: the smaller qp wins a tie.
    let Some(&(_, best)) = scored.iter().reduce(|a, b| if b.0 < a.0 { b } else { a }) else {
        return Ok(None);
    };
    let simplifier = &case.simplifier;
    let coded = finish(case, best.qp, samples, || {
        Ok(Cow::Owned(simplifier.simplify(best.faces)))
    })?;
    debug_assert_eq!(
        coded.bytes,
        best.bytes.len() as u64,
        "simplification is deterministic"
    );
    Ok(Some(coded))
}

/// Face samples per direction when comparing the qps' candidates.
fn candidate_samples(samples: u64) -> u64 {
    (samples / 10).max(samples.min(1_000))
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
/// [`MIN_FACES`] faces do not fit.
fn fit_faces(
    case: &Case,
    qp: u8,
    budget: u64,
    prev: Option<&Fit>,
) -> Result<Option<Fit>, swm::Error> {
    let s = &case.simplifier;
    let full = s.faces();
    let full_size = s.full_size(qp)?;
    if full_size <= budget {
        let mesh = Arc::new(s.simplify(full));
        let bytes = encode(&mesh, qp)?;
        return Ok(Some(Fit {
            qp,
            faces: full,
            mesh,
            bytes,
            slope: 1.0,
        }));
    }
    if full <= MIN_FACES {
        return Ok(None);
    }
    let budget_f = budget as f64;
    // `hi`: the fewest faces known not to fit; `lo`: the most known to fit.
    let mut hi = Probe {
        faces: full,
        size: full_size,
    };
    let mut lo: Option<(Probe, Arc<TriMesh>, Vec<u8>)> = None;
    // Simplified probes only: the unsimplified mesh is far cheaper per
    // face than any simplification, so slopes through it mislead.
    let mut probes: Vec<Probe> = Vec::new();
    let mut last_fitted: Option<bool> = None;
    let mut slope_down = prev.map_or(1.0, |p| p.slope);
    let mut guess = aim(hi, slope_down, 0.98 * budget_f);
    // The first probe is the previous qp's answer: its simplification is made.
    let mut made = prev
        .filter(|p| p.faces < full)
        .map(|p| (p.faces, p.mesh.clone()));
    for _ in 0..MAX_PROBES {
        let (faces, mesh) = match made.take() {
            Some(made) => made,
            None => {
                let floor = lo.as_ref().map_or(MIN_FACES, |l| l.0.faces + 1);
                let faces = (guess.round() as u32).clamp(floor, hi.faces - 1);
                (faces, Arc::new(s.simplify(faces)))
            }
        };
        let bytes = encode(&mesh, qp)?;
        let probe = Probe {
            faces,
            size: bytes.len() as u64,
        };
        let fits = probe.size <= budget;
        let same_side = last_fitted == Some(fits);
        last_fitted = Some(fits);
        probes.push(probe);
        if fits {
            lo = Some((probe, mesh, bytes));
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
        if narrow || l.size as f64 >= FILL * budget_f {
            break;
        }
        guess = if same_side {
            // Two probes on the same side: the secant is creeping.
            (l.faces as f64 * hi.faces as f64).sqrt()
        } else {
            // Aim inside the accepted band, not at its edge.
            aim(*l, slope(*l, hi), (1.0 + FILL) / 2.0 * budget_f)
        };
    }
    Ok(lo.map(|(l, mesh, bytes)| {
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
            slope,
        }
    }))
}
