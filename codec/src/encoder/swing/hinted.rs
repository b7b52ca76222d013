//! SwingWrapper files made for the post-processing their decoder will
//! run (issue 21; beyond the thesis, whose encoder ignores the decoder's
//! EdgeSharpener): the measured hint ([`crate::post::hint`]), and the
//! choice of where tips aim when EdgeSharpener is worth running.
//!
//! Why the aim matters: EdgeSharpener extends the planes of the smooth
//! regions through their vertices. Tips aimed on the surface (the
//! thesis's retiling) lie on those planes, so the chamfer's planes meet
//! on the lost crease; tips aimed off the surface by the chord offset and
//! fitted to the region they cover (`retile::offset`, `retile::fit`)
//! round the chamfer into several shallow edges and tilt the planes, and
//! EdgeSharpener then restores little (fandisk at 4 b/v: L2 6.58 → 6.32
//! sharpened from fitted tips, 7.72 → 3.10 from tips on the surface, ×
//! 1e-4 of the diagonal). On smooth scans fitted tips are 7-8% better
//! and EdgeSharpener does not help. So:
//!
//! ```text
//!  file A (the options' tips) ──► hint A
//!  file A′ (A's tips, and tips on creases) ──► hint A′     input creased?
//!         the lower L2 after its hint is A (A on a tie) ◄──┘
//!                                  │
//!                                  └─ EdgeSharpener helps? ──no──► A
//!                                                 │ yes
//!  file B (tips on the surface, A's crease choice, same request) ──► hint B
//!                                                 ▼
//!               the lower L2 after each one's hint (A on a tie)
//! ```
//!
//! Tips on creases (`retile::crease`, `RADS`) are tried only where the
//! caller allows them and the input's creases total at least its
//! bounding-box diagonal (`encoder::swing::encode_pieces`); they cost bytes
//! (a radius code per crease tip) and on coarse retilings of rounded
//! parts can place tips on creases too small to matter, so the measure
//! decides, as for the aim.
//!
//! File B is tried at rate control's angle bits and then, while that
//! lowers the error, with one more ([`MORE_ANGLE_BITS`] at most): rate
//! control chooses the bits for fitted tips decoded plain, and the flat
//! sides' planes EdgeSharpener extends want finer angles.
//!
//! Invariants: both files answer the same request (size or rate, cap);
//! an edge-length request is the caller's retiling and is not second-
//! guessed (only its hint is measured); the choice depends only on
//! deterministic measures (seeded samples), never on the thread count;
//! the hint's bytes count against the request like any other section.

use super::hint::{self, HintReport};
use crate::metrics::Surface;
use crate::options::AUTO_SAMPLES;
use crate::post::hint::{payload, PostProcessing};
use crate::swing::retile::rate::{self, Chosen, Knobs, Prior};
use crate::swing::retile::{fill::Piece, Budget};
use crate::{Error, TriMesh};

/// Angle bits tried above rate control's choice for tips on the surface.
/// Rate control picks the bits by the angles' spread, for fitted tips
/// and plain decoding; after EdgeSharpener the flat sides' planes need
/// finer angles (fandisk, L2 after sharpening at the same size, 1e-4 of
/// the diagonal: 4 b/v 3.10 / 2.52 / 2.58 and 8 b/v 1.50 / 1.05 / 0.85
/// at 6 / 7 / 8 bits; at 2 b/v 6 bits stays best, 8.29 / 8.75 / 11.2).
pub(crate) const MORE_ANGLE_BITS: u8 = 2;

/// What the file must answer: a byte budget (from a size or a rate) or
/// an edge length, with the cap and the angle bits asked for.
#[derive(Clone, Copy)]
pub(crate) struct Request {
    /// `Ok(bytes)` for a size or rate, `Err(l)` for an edge length.
    pub target: Result<u64, f64>,
    /// Never more than this many bytes.
    pub max_bytes: Option<u64>,
    /// The angle bits asked for (`None`: rate control chooses).
    pub angle_bits: Option<u8>,
}

impl Request {
    /// Rate control's file for this request with `knobs`; its search
    /// starts from `prior`, an earlier file's, when given.
    pub fn run(
        &self,
        pieces: &[Piece],
        knobs: Knobs,
        budget: &Budget,
        prior: Option<Prior>,
    ) -> Result<Chosen, Error> {
        self.run_at(pieces, knobs, budget, 0, prior)
    }

    /// The same for `less` bytes fewer (budget and cap).
    fn run_at(
        &self,
        pieces: &[Piece],
        knobs: Knobs,
        budget: &Budget,
        less: u64,
        prior: Option<Prior>,
    ) -> Result<Chosen, Error> {
        let cap = self.max_bytes.map(|c| c.saturating_sub(less));
        match self.target {
            Err(l) => rate::at_length(pieces, l, knobs, budget),
            Ok(b) => {
                let b = b.saturating_sub(less).max(1);
                match self.angle_bits {
                    Some(_) => rate::at_size(pieces, b, cap, knobs, budget, prior),
                    None => rate::at_size_auto(pieces, b, cap, knobs, budget, prior),
                }
            }
        }
    }

    /// The largest file that answers a size request: within rate
    /// control's tolerance above it, and never over the cap.
    pub(crate) fn limit(&self, b: u64) -> u64 {
        let tolerated = (b as f64 * (1.0 + rate::TOLERANCE)).floor() as u64;
        self.max_bytes.map_or(tolerated, |cap| cap.min(tolerated))
    }
}

/// `first` (made with `knobs` for `request`) with its measured hint; for
/// a size or rate request where EdgeSharpener helps and tips were aimed
/// off the surface, also the file with tips on the surface, keeping the
/// better (module docs).
#[allow(clippy::too_many_arguments)]
pub(crate) fn finish(
    pieces: &[Piece],
    input: &TriMesh,
    first: Chosen,
    knobs: Knobs,
    request: Request,
    creases: bool,
    budget: &Budget,
    reference: Option<&Surface>,
) -> Result<(Chosen, HintReport), Error> {
    // `reference` is `Surface::new(input)` when the caller has it.
    let made;
    let reference = match reference {
        Some(r) => r,
        None => {
            made = Surface::new(input)?;
            &made
        }
    };
    let (a, hint_a) = hinted(pieces, first, knobs, request, budget, reference)?;
    let first_len = a.bytes.len() as u64;
    let fits = |c: &Chosen| match request.target {
        Ok(t) => c.bytes.len() as u64 <= request.limit(t).max(first_len),
        Err(_) => true,
    };
    let mut best = (a, hint_a);
    // Tips on creases (`creases`: the input has enough of them to matter):
    // the same request once more, kept if it decodes closer after its
    // hint.
    let knobs = if creases && request.target.is_ok() {
        let with = Knobs {
            crease_tips: true,
            ..knobs
        };
        let prior = Some(best.0.prior);
        match try_file(pieces, with, request, budget, reference, prior)? {
            Some((b, mut h)) if fits(&b) && h.l2_after() < best.1.l2_after() => {
                h.crease_tips = true;
                best = (b, h);
                with
            }
            _ => knobs,
        }
    } else {
        knobs
    };
    let fitted = knobs.approximate_tips || knobs.fit_tips;
    if !best.1.chosen.sharpen || !fitted || request.target.is_err() {
        return Ok(best);
    }
    let on_surface = Knobs {
        approximate_tips: false,
        fit_tips: false,
        ..knobs
    };
    // Rate control's angle bits first; then, when the caller left them
    // to it, one more at a time while that lowers the error, up to
    // MORE_ANGLE_BITS more.
    let mut k0: Option<u8> = None;
    for k in 0..=MORE_ANGLE_BITS {
        let attempt = match (k, k0) {
            (0, _) => request,
            (_, Some(k0))
                if request.angle_bits.is_none() && k0 + k <= crate::swing::MAX_ANGLE_BITS =>
            {
                Request {
                    angle_bits: Some(k0 + k),
                    ..request
                }
            }
            _ => break,
        };
        let knobs = Knobs {
            angle_bits: attempt.angle_bits.unwrap_or(on_surface.angle_bits),
            ..on_surface
        };
        // A retiling that fails with this aim leaves the best so far.
        let b = match attempt.run(pieces, knobs, budget, Some(best.0.prior)) {
            Ok(b) => b,
            Err(Error::Retile(_) | Error::Size(_)) => continue,
            Err(e) => return Err(e),
        };
        k0.get_or_insert(b.stats.angle_bits);
        let (b, mut hint_b) = hinted(pieces, b, knobs, attempt, budget, reference)?;
        if fits(&b) && hint_b.l2_after() < best.1.l2_after() {
            hint_b.tips_on_surface = true;
            hint_b.crease_tips = knobs.crease_tips;
            best = (b, hint_b);
        } else if k > 0 {
            // Finer angles stopped paying: coarser sampling costs more
            // from here on.
            break;
        }
    }
    Ok(best)
}

/// Rate control's file for `request` with `knobs`, hinted; `None` when
/// no retiling answers it.
fn try_file(
    pieces: &[Piece],
    knobs: Knobs,
    request: Request,
    budget: &Budget,
    reference: &Surface,
    prior: Option<Prior>,
) -> Result<Option<(Chosen, HintReport)>, Error> {
    match request.run(pieces, knobs, budget, prior) {
        Ok(b) => hinted(pieces, b, knobs, request, budget, reference).map(Some),
        Err(Error::Retile(_) | Error::Size(_)) => Ok(None),
        Err(e) => Err(e),
    }
}

/// `chosen` with its hint measured and written. The hint's few bytes
/// count against the request. When they push a file past the tolerance
/// or the cap (and the plain file was within: a rate control that missed
/// by itself is not the hint's doing), the file is made again for that
/// many bytes fewer and its own hint measured; it replaces the plain file
/// only if it decodes closer after its hint (at low rates the coarser
/// retiling can cost more than the post-processing buys). Under a cap the
/// hinted file cannot meet, the file goes without a hint.
fn hinted(
    pieces: &[Piece],
    chosen: Chosen,
    knobs: Knobs,
    request: Request,
    budget: &Budget,
    reference: &Surface,
) -> Result<(Chosen, HintReport), Error> {
    let report = hint::recommend(&chosen.bytes, reference, AUTO_SAMPLES)?;
    let with = hint::with_hint(&chosen.bytes, report.chosen)?;
    let extra = (with.len() - chosen.bytes.len()) as u64;
    let fits = |n: usize| match request.target {
        Ok(b) => n as u64 <= request.limit(b),
        Err(_) => request.max_bytes.is_none_or(|cap| n as u64 <= cap),
    };
    // The plain file as it is: its figures already describe it.
    let plain = |chosen: Chosen, mut report: HintReport| {
        report.chosen = PostProcessing::PLAIN;
        (chosen, report)
    };
    if report.chosen.is_plain() || fits(with.len()) || !fits(chosen.bytes.len()) {
        // No hint, or it fits, or the plain file missed by itself: the
        // hint goes in unless a cap forbids it.
        if request.max_bytes.is_some_and(|cap| with.len() as u64 > cap) {
            return Ok(plain(chosen, report));
        }
        let mut chosen = chosen;
        chosen.bytes = with;
        return Ok((noted(chosen, report.chosen, request), report));
    }
    let again = match request.run_at(pieces, knobs, budget, extra, Some(chosen.prior)) {
        Ok(c) => c,
        Err(Error::Retile(_) | Error::Size(_)) => return Ok(plain(chosen, report)),
        Err(e) => return Err(e),
    };
    let second = hint::recommend(&again.bytes, reference, AUTO_SAMPLES)?;
    let bytes = hint::with_hint(&again.bytes, second.chosen)?;
    if second.chosen.is_plain() || !fits(bytes.len()) || second.l2_after() >= report.plain_l2 {
        return Ok(plain(chosen, report));
    }
    let mut again = again;
    again.bytes = bytes;
    // The report answers the request, not the redo's.
    again.report.requested_bytes = chosen.report.requested_bytes;
    Ok((noted(again, second.chosen, request), second))
}

/// The figures of a file that now carries the hint `post`.
fn noted(mut chosen: Chosen, post: PostProcessing, request: Request) -> Chosen {
    if !post.is_plain() {
        let payload = payload(post).len();
        chosen
            .stats
            .sections
            .push((crate::container::Tag::POST.0, payload));
        chosen.stats.file_bytes = chosen.bytes.len();
        if let Ok(b) = request.target {
            chosen.report.within_tolerance = rate::within_tolerance(chosen.bytes.len() as u64, b);
        }
    }
    chosen
}
