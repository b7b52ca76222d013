//! A method per component (issue 20, items 1 and 2): the automatic mode's
//! third candidate for a mesh of several components, where each one is
//! coded by SwingWrapper or by the simplified method, whichever the
//! encoder measures closer at that component's share of the size.
//!
//! The file needs nothing new: a mode-1 file already carries retiled
//! components in its body and, in `REST`, a mode-0 file whose mesh the
//! decoder appends (05-swing.md). Here `REST` holds the simplified
//! components (and any too small to retile), so the choice is recorded
//! per component by where it is coded.
//!
//! ```text
//!  components, by area ──► share b_i = F + (B − F)·area_i / area
//!        │ (the MEASURED largest)
//!        ├──► SwingWrapper alone at b_i ──► L2_i(swing)  ┐ lower wins
//!        └──► simplified alone at b_i  ──► L2_i(simpl.)  ┘
//!  simplified ones ──► REST, at their qp (their shares then moved by need)
//!  retiled ones, and the unmeasured rest ──► rate control on the whole
//!  file at B (REST included; a component too small to retile is kept whole)
//! ```
//!
//! The split of the size (item 2): each component's share follows its
//! area, as a uniform retiling's triangle count does, plus the frame a
//! file of its own would spend ([`FRAME`]); within the simplified part the
//! quadric collapse of each component keeps its faces where its error is,
//! and within the retiled part one edge length serves every component.
//! The file as a whole is rate controlled to the request (±3%, never
//! above `--max-size`), so the shares decide only which method serves
//! each component and the simplified components' sizes.
//!
//! Invariants: the choice depends only on the mesh and the request (each
//! per-component encode is deterministic, the measures are seeded, and
//! the parallel trials are collected in component order); the trials
//! split the encoder's work and time limits between them (a trial that
//! runs out only loses its retiled candidate); a component
//! neither method can code alone at its share is left to the file's own
//! rule (retiled, or kept whole when too small for the edge length).

use super::method::{Ask, CodingMethod, Job, Made};
use super::stats::{Method, MethodStats};
use crate::metrics::Surface;
use crate::options::{EncodeOptions, SwingTarget};
use crate::simplify::{best_fit, file_distance, Climb, Simplifier};
use crate::swing::retile::fill::Piece;
use crate::{Error, TriMesh};
use rayon::prelude::*;

/// Components measured one by one, the largest by area; smaller ones
/// follow the file's own rule, retiled or, too small for the edge length,
/// kept whole (a file of thousands of parts would otherwise pay thousands
/// of trials).
pub const MEASURED: usize = 16;
/// Bytes a file of its own spends on frame and header, added to each
/// component's share for its trial encodes.
const FRAME: u64 = 40;
/// Face samples per direction for a component's two trial files (a
/// tenth of the file's own measure: the trials only rank two methods).
const TRIAL_SAMPLES: u64 = 10_000;

/// What the trials decided for one component.
enum Verdict {
    /// Retile it; its trial's absolute L2.
    Swing(f64),
    /// Keep this simplification.
    Simplified(Fit),
    /// Neither trial made a file: leave it to the file's own rule.
    Open,
}

/// A component's simplified file at some size.
struct Fit {
    mesh: TriMesh,
    qp: u8,
    /// Absolute L2 to the component.
    l2: f64,
    /// The size it was fitted to.
    bytes: u64,
}

/// Halvings and doublings tried on a simplified component's share.
const MOVES: usize = 6;

/// A measured component with what both of its phases use: its
/// simplifier (whose collapse sequence, made once, serves every size
/// tried) and the surface its candidates are measured against.
struct Measured<'a> {
    index: usize,
    piece: &'a Piece,
    simplifier: Simplifier<'a>,
    surface: Surface,
}

/// The per-component chooser, as a candidate of the per-file one.
pub(crate) struct Mixed;

impl CodingMethod for Mixed {
    fn method(&self) -> Method {
        Method::Mixed
    }

    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error> {
        let budget =
            super::request::budget(ask.target, job.input_vertices, ask.max_bytes, "mixed")?;
        Ok(encode(job, budget, ask.max_bytes)?
            .map(|file| file.made(job.options.origins, MethodStats::Mixed)))
    }
}

/// The mixed file for `budget` bytes, or `None` when the mesh has one
/// component or every measured component chose the same method.
fn encode(
    job: &Job<'_, '_>,
    budget: u64,
    max_bytes: Option<u64>,
) -> Result<Option<super::swing::SwingFile>, Error> {
    let (cleaned, options) = (job.cleaned, job.options);
    let mut pieces = crate::swing::retile::fill::pieces(&cleaned.mesh, &cleaned.table)?;
    if pieces.len() < 2 {
        return Ok(None);
    }
    let areas: Vec<f64> = pieces.iter().map(|p| p.original.area()).collect();
    let total: f64 = areas.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return Ok(None);
    }
    let share = |i: usize| {
        let body = budget.saturating_sub(FRAME) as f64 * areas[i] / total;
        FRAME + body.floor() as u64
    };
    // The largest components, ties to the lower index.
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| areas[b].total_cmp(&areas[a]).then(a.cmp(&b)));
    order.truncate(MEASURED);
    // The trials share the encoder's work and time bounds with the final
    // encode: each gets its part, so that all of them together stay
    // within about twice what one encode may take.
    let parts = order.len() as u64 + 1;
    let trial_options = EncodeOptions {
        limits: crate::EncodeLimits {
            max_work: options.limits.max_work / parts,
            max_milliseconds: options.limits.max_milliseconds.map(|ms| ms / parts),
            ..options.limits
        },
        ..options.clone()
    };
    let measured: Vec<Measured<'_>> = order
        .par_iter()
        .map(|&index| {
            let piece = &pieces[index];
            let simplifier = Simplifier::new(&piece.original, options.framing);
            let surface = Surface::new(simplifier.reference())?;
            Ok(Measured {
                index,
                piece,
                simplifier,
                surface,
            })
        })
        .collect::<Result<_, Error>>()?;
    let mut verdicts: Vec<Verdict> = measured
        .par_iter()
        .map(|m| trial(m, share(m.index), &trial_options))
        .collect::<Result<_, _>>()?;
    // The retiled part's gain per byte: a retiling's L2 falls as 1/bytes
    // (bytes grow as the triangle count, 1/L^2, and the error as L^2), so
    // its area-weighted squared error D falls at 2 D / bytes.
    let (mut d_swing, mut b_swing) = (0.0, 0u64);
    for (m, v) in measured.iter().zip(&verdicts) {
        if let Verdict::Swing(l2) = v {
            d_swing += areas[m.index] * l2 * l2;
            b_swing += share(m.index);
        }
    }
    let any_simplified = verdicts.iter().any(|v| matches!(v, Verdict::Simplified(_)));
    if b_swing == 0 || !any_simplified {
        return Ok(None);
    }
    let gain = 2.0 * d_swing / b_swing as f64;
    // Each simplified component's share moves by halvings (or doublings)
    // while the error it adds per byte given up is below the retiled
    // part's gain per byte (or the error it saves per byte taken is
    // above it): a flat part exact at a few faces gives its share away.
    let resized: Vec<Option<Fit>> = measured
        .par_iter()
        .zip(&verdicts)
        .map(|(m, v)| match v {
            Verdict::Simplified(f) => resize(m, f, areas[m.index], gain, budget),
            _ => Ok(None),
        })
        .collect::<Result<_, _>>()?;
    for (v, r) in verdicts.iter_mut().zip(resized) {
        if let Some(f) = r {
            *v = Verdict::Simplified(f);
        }
    }
    let kept: Vec<(usize, Fit)> = measured
        .iter()
        .zip(verdicts)
        .filter_map(|(m, v)| match v {
            Verdict::Simplified(f) => Some((m.index, f)),
            _ => None,
        })
        .collect();
    drop(measured);
    for (i, f) in kept {
        pieces[i].keep = Some((f.mesh, f.qp));
    }
    let request = super::swing::request(
        SwingTarget::Bytes(budget),
        job.input_vertices,
        None,
        max_bytes.or(Some(budget)),
    )?;
    let encoded = super::swing::encode_pieces(&pieces, &cleaned.mesh, options, request, None)?;
    Ok(Some(encoded))
}

/// Both methods on one component alone at `bytes`, measured against it.
fn trial(m: &Measured<'_>, bytes: u64, options: &EncodeOptions) -> Result<Verdict, Error> {
    let simplified = fit_at(m, bytes)?;
    let alone = crate::clean(&m.piece.original, &options.clean)?;
    // A retiling that fails or misses the share is no candidate.
    let ask = Ask {
        target: SwingTarget::Bytes(bytes),
        max_bytes: Some(bytes),
    };
    let swing =
        match super::swing::encode(&alone, alone.mesh.vertex_count(), options, ask, None, None) {
            Ok(file) => Some(file_distance(&file.bytes, &m.surface, TRIAL_SAMPLES)?.l2()),
            Err(Error::Retile(_) | Error::LimitExceeded(_) | Error::Size(_)) => None,
            Err(e) => return Err(e),
        };
    Ok(match (swing, simplified) {
        (Some(w), Some(f)) if f.l2 < w => Verdict::Simplified(f),
        (Some(w), _) => Verdict::Swing(w),
        (None, Some(f)) => Verdict::Simplified(f),
        (None, None) => Verdict::Open,
    })
}

/// A better share for a simplified component than `fit`'s, by the
/// marginal rule above; `None` when `fit` stands.
fn resize(
    m: &Measured<'_>,
    fit: &Fit,
    area: f64,
    gain: f64,
    budget: u64,
) -> Result<Option<Fit>, Error> {
    let d = |f: &Fit| area * f.l2 * f.l2;
    let mut best: Option<Fit> = None;
    // Smaller while giving bytes away costs less than they buy.
    for _ in 0..MOVES {
        let at = best.as_ref().unwrap_or(fit);
        let Some(f) = fit_at(m, at.bytes / 2)? else {
            break;
        };
        let saved = (at.bytes - f.bytes) as f64;
        if saved <= 0.0 || (d(&f) - d(at)) / saved >= gain {
            break;
        }
        best = Some(f);
    }
    if best.is_some() {
        return Ok(best);
    }
    // Larger while the bytes taken save more than they cost elsewhere.
    for _ in 0..MOVES {
        let at = best.as_ref().unwrap_or(fit);
        if at.bytes >= budget / 2 {
            break;
        }
        let Some(f) = fit_at(m, 2 * at.bytes)? else {
            break;
        };
        let taken = (f.bytes - at.bytes.min(f.bytes)) as f64;
        if taken <= 0.0 || (d(at) - d(&f)) / taken <= gain {
            break;
        }
        best = Some(f);
    }
    Ok(best)
}

/// The simplified method's best file of one component at `bytes`: its
/// mesh (before quantization), qp and absolute L2; `None` when nothing
/// fits.
fn fit_at(m: &Measured<'_>, bytes: u64) -> Result<Option<Fit>, Error> {
    let diagonal = m.simplifier.reference().bbox_diagonal();
    let Some((fit, l2_relative)) = best_fit(
        &m.simplifier,
        bytes,
        &|| Ok(&m.surface),
        Climb::Full(TRIAL_SAMPLES),
    )?
    else {
        return Ok(None);
    };
    // What its file codes: the simplification cleaned (as the lossless
    // mode cleans it), so that REST's corner table takes it as it is.
    let mesh = crate::clean(&fit.mesh, &crate::CleanOptions::default())?.mesh;
    Ok(Some(Fit {
        mesh,
        qp: fit.qp,
        l2: l2_relative * diagonal,
        bytes: fit.bytes.len() as u64,
    }))
}
