//! The automatic mode: SwingWrapper or simplify-then-lossless, whichever
//! the encoder itself measures closer to the input at the same size
//! (issue 20, "method per piece", here per file).
//!
//! Retiling wins where the surface is smooth and the rate low enough that
//! its regular sampling and one-angle vertices pay; quadric
//! simplification wins on sharp-edged (CAD) parts and at rates where an
//! adaptive mesh beats a uniform one. Neither is known in advance, so
//! both are made and measured:
//!
//! ```text
//!  cleaned input ──► SwingWrapper at the target ──► file A (or a failure)
//!        │                                             │ its size, when the
//!        │                                             ▼ target is an L
//!        └──────► simplified at the same budget ──► file B (or "too small")
//!                                                       │
//!  decode A, B ──► L2 to the cleaned input (AUTO_SAMPLES each way) ──► the lower
//! ```
//!
//! Invariants: both candidates answer the same request (size or rate,
//! under the same cap); a SwingWrapper encode that fails (no edge length
//! retiles, or the encoder's limits stop it, or its nearest file misses
//! the size by more than rate control's 3%) falls back to the simplified
//! file rather than failing the encode; when neither fits, the error
//! names the smaller of their smallest files; the choice depends only on
//! deterministic figures (seeded samples summed in a fixed order), so
//! the bytes never depend on the thread count. A tie goes to
//! SwingWrapper.

use crate::api::{
    encode_simplified, encode_swing, simplified_budget, Candidate, EncodeOptions, Encoded, Method,
    MethodChoice, SwingFailure, SwingTarget, AUTO_SAMPLES,
};
use crate::metrics::{DistanceOptions, Surface};
use crate::simplify::Simplifier;
use crate::{Error, TriMesh};

/// [`EncodeMode::Auto`](crate::EncodeMode::Auto).
pub(crate) fn encode(
    mesh: &TriMesh,
    options: &EncodeOptions,
    target: SwingTarget,
    max_bytes: Option<u64>,
) -> Result<Encoded, Error> {
    let cleaned = crate::clean(mesh, &options.clean)?;
    let vertices = mesh.vertex_count();
    // Both candidates are measured against the simplifier's reference:
    // the cleaned input, or the same surface with its high-valence fans
    // rebuilt (`Simplifier::new`).
    let s = Simplifier::new(&cleaned.mesh);
    let reference = Surface::new(s.reference())?;
    let retile = || encode_swing(&cleaned, vertices, options, target, None, max_bytes);
    let simplify = |budget| encode_simplified(cleaned.report.clone(), &s, budget, &reference);
    // With a size or a rate the two candidates are independent and run
    // side by side (each is deterministic, so the bytes do not depend on
    // the threads); with an edge length the simplified one waits for the
    // retiled file's size.
    let (swing, budget, simplified) = match target {
        SwingTarget::EdgeLength(_) => {
            // No retiling at this L: no size to give the simplified file,
            // so the retiling's error stands.
            let swing = retile()?;
            let budget = swing.bytes.len() as u64;
            (Ok(swing), budget, simplify(budget))
        }
        t => {
            let budget = simplified_budget(t, vertices, max_bytes)?;
            let (swing, simplified) = rayon::join(retile, || simplify(budget));
            (swing, budget, simplified)
        }
    };
    let swing = match swing {
        Ok(e) => Ok(e),
        Err(Error::Retile(e)) => Err(SwingFailure::Retile(e)),
        Err(Error::LimitExceeded(e)) => Err(SwingFailure::Limit(e)),
        Err(e) => return Err(e),
    };
    // A retiled file more than the tolerance over the request is no
    // answer to it (rate control keeps the nearest file it made). With an
    // edge length the budget is its size, so it never is.
    let over =
        |e: &Encoded| e.bytes.len() as f64 > budget as f64 * (1.0 + crate::retile::rate::TOLERANCE);
    let simplified = match simplified {
        Ok(e) => Some(e),
        Err(Error::Size(e)) => match &swing {
            // Nothing that small: SwingWrapper's file stands alone...
            Ok(w) if !over(w) => None,
            // ... unless it missed the size too: the smaller of the two
            // smallest files is what the request must allow.
            Ok(w) => {
                return Err(crate::SizeError {
                    requested: e.requested,
                    smallest: e.smallest.min(w.bytes.len() as u64),
                }
                .into())
            }
            Err(_) => return Err(e.into()),
        },
        Err(e) => return Err(e),
    };
    // Both exist: an oversized retiled file does not compete.
    let swing = match swing {
        Ok(w) if simplified.is_some() && over(&w) => Err(SwingFailure::Oversized {
            bytes: w.bytes.len() as u64,
        }),
        other => other,
    };
    let measure = |e: &Encoded| -> Result<Candidate, Error> {
        let decoded = crate::decode(&e.bytes, &Default::default())?;
        let d = crate::metrics::distance_between(
            &reference,
            &Surface::new(&decoded)?,
            &DistanceOptions::area_uniform(AUTO_SAMPLES),
        )?;
        Ok(Candidate {
            bytes: e.bytes.len() as u64,
            l2_relative: d.l2_relative(),
        })
    };
    let swing_candidate = match &swing {
        Ok(e) => Some(measure(e)?),
        Err(_) => None,
    };
    // The simplified file was measured while its qp was chosen, against
    // the same reference with the same samples.
    let simplified_candidate = simplified.as_ref().and_then(|e| {
        e.stats.simplified.map(|s| Candidate {
            bytes: e.bytes.len() as u64,
            l2_relative: s.l2_relative,
        })
    });
    let chosen = match (swing_candidate, simplified_candidate) {
        (Some(a), Some(b)) if b.l2_relative < a.l2_relative => Method::Simplified,
        (Some(_), _) => Method::Swing,
        (None, _) => Method::Simplified,
    };
    let choice = MethodChoice {
        chosen,
        swing: swing_candidate,
        swing_failure: swing.as_ref().err().cloned(),
        simplified: simplified_candidate,
    };
    let mut encoded = match (chosen, swing, simplified) {
        (Method::Swing, Ok(e), _) => e,
        (_, _, Some(e)) => e,
        // Unreachable by the match above: a method is chosen only with
        // its file. Kept total rather than panicking.
        (_, Err(f), None) => return Err(failure_error(f)),
        (_, Ok(e), None) => e,
    };
    encoded.stats.choice = Some(choice);
    Ok(encoded)
}

/// The error a failed SwingWrapper candidate would have given alone.
fn failure_error(f: SwingFailure) -> Error {
    match f {
        SwingFailure::Retile(e) => e.into(),
        SwingFailure::Limit(e) => e.into(),
        // Not built from an error: only set when the simplified file
        // exists, so never returned.
        SwingFailure::Oversized { bytes } => crate::SizeError {
            requested: bytes,
            smallest: bytes,
        }
        .into(),
    }
}
