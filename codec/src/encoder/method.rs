//! The seam every coding method implements ([`CodingMethod`]), after
//! Draco's encoder/decoder factories: a method is one module under
//! `encoder/` that turns a job and a request into a file with its
//! figures, and the choosers above (`choose` per file, `mixed` per
//! component) take a list of them. Methods never call a chooser; rate
//! control (`retile::rate`), the post-processing hint (`post::hint`) and
//! the distance measure (`metrics`, [`Job::measure`]) are services they
//! call.
//!
//! ```text
//!   api::encode ─► encoder::encode ─► choose (a list of methods, by effort)
//!                                     │            │
//!                        forced mode ─┘            ▼
//!                         Lossless  Simplified  Swing  Mixed   (CodingMethod)
//!                              │        │         │      │
//!          services:  lossless::encode, simplify, retile::rate, post::hint, metrics
//! ```
//!
//! Adding a method: one module implementing [`CodingMethod`], one variant
//! of [`Method`] and of [`MethodStats`](super::MethodStats), and one line
//! in an effort level's list (`effort`).

use super::stats::{Method, MethodStats};
use crate::metrics::Surface;
use crate::options::{EncodeOptions, SwingTarget};
use crate::simplify::Simplifier;
use crate::{Cleaned, Error};
use std::sync::OnceLock;

/// What the methods of one encode share, each made on first use: the
/// simplifier of the cleaned input (its collapse sequence made once for
/// every method that simplifies) and the surface every candidate is
/// measured against (the cleaned input, or the same surface with its
/// high-valence fans rebuilt, [`Simplifier::reference`]).
pub(crate) struct Services<'a> {
    /// The mesh as the caller gave it.
    input: &'a crate::TriMesh,
    cleaned: &'a Cleaned,
    framing: crate::container::Framing,
    /// Simplify with meshoptimizer (effort `fast`).
    quick: bool,
    simplifier: OnceLock<Simplifier<'a>>,
    /// `None` when the reference makes no surface (the error is made
    /// again for each caller: `Error` is not `Clone`).
    reference: OnceLock<Option<Surface>>,
    /// The input as given, as `swm distance` measures against it.
    given: OnceLock<Surface>,
    /// The cleaned input's attribute streams (one triple per cleaned
    /// face; empty without any) and their quantization: only methods
    /// that carry them run ([`CodingMethod::carries_attributes`]).
    streams: &'a [crate::AttributeStream],
    quantization: crate::AttributeQuantization,
}

impl<'a> Services<'a> {
    /// How the input's attribute streams are quantized.
    pub fn quantization(&self) -> crate::AttributeQuantization {
        self.quantization
    }

    /// Nothing made yet; `quick`: the simplifier is meshoptimizer's
    /// (effort `fast`) rather than the quadric collapse sequence.
    pub fn new(
        input: &'a crate::TriMesh,
        cleaned: &'a Cleaned,
        framing: crate::container::Framing,
        quick: bool,
    ) -> Services<'a> {
        Services {
            input,
            cleaned,
            framing,
            quick,
            simplifier: OnceLock::new(),
            reference: OnceLock::new(),
            given: OnceLock::new(),
            streams: &[],
            quantization: crate::AttributeQuantization::default(),
        }
    }

    /// The same services for an input with attribute `streams` (the
    /// cleaning's, `clean_attributed`), quantized as `quantization` says.
    pub fn with_attributes(
        self,
        streams: &'a [crate::AttributeStream],
        quantization: crate::AttributeQuantization,
    ) -> Services<'a> {
        Services {
            streams,
            quantization,
            ..self
        }
    }
}

/// Effort `fast` simplifies with meshoptimizer above this many faces and
/// with swm's own collapse up to it. meshoptimizer keeps a subset of the
/// input's vertices where they were, which at a few hundred faces costs
/// far more error than collapses placed at each quadric's minimum: on
/// the shared table's meshes of 1,000-13,000 faces, fast's geometric-mean
/// L2 fell to 0.79x with the own engine (teapot 1 b/v 43.8 -> 20.7,
/// beetle 2 b/v 153 -> 69; woody 1 b/v, 11 faces, rose 44 -> 102). Its
/// collapse sequence costs about 2.5 µs a face, 50 ms at this count, a
/// sixth of fast's 0.3 s floor; meshoptimizer's pass is about 4x cheaper,
/// which is what the larger inputs need. An input with attribute streams
/// is simplified by meshoptimizer with them at every effort and size
/// (`simplify::attributed`: the collapse sequence knows no seams).
pub(crate) const QUICK_ENGINE_FACES: usize = 20_000;

/// One encode's input and the services its methods share.
#[derive(Clone, Copy)]
pub(crate) struct Job<'a, 's> {
    /// The cleaned input.
    pub cleaned: &'a Cleaned,
    /// Distinct positions of the mesh as given (what bits per vertex
    /// count, [`TriMesh::distinct_positions`](crate::TriMesh::distinct_positions)).
    pub input_vertices: usize,
    /// The caller's options (the chooser may lower a candidate's limits).
    pub options: &'a EncodeOptions,
    /// The shared services.
    pub services: &'a Services<'s>,
}

impl<'a, 's> Job<'a, 's> {
    /// The simplifier of the cleaned input.
    pub fn simplifier(&self) -> &'a Simplifier<'s> {
        let s = self.services;
        s.simplifier.get_or_init(|| {
            let mesh = &s.cleaned.mesh;
            match s.quick && mesh.face_count() > QUICK_ENGINE_FACES {
                true => Simplifier::quick(mesh, s.framing),
                false => Simplifier::new(mesh, s.framing),
            }
            .of_cleaned(s.cleaned)
            .with_attributes(s.streams, s.quantization)
        })
    }

    /// The cleaned input's attribute streams (empty without any).
    pub fn streams(&self) -> &'s [crate::AttributeStream] {
        self.services.streams
    }

    /// The bounding-box diagonal of the input as given (what relative
    /// errors are relative to, as `swm distance` reports them).
    pub fn input_diagonal(&self) -> f64 {
        self.services.input.bbox_diagonal()
    }

    /// The mesh as the caller gave it.
    pub fn services_input(&self) -> &'s crate::TriMesh {
        self.services.input
    }

    /// The surface every candidate is measured against. Made once: a
    /// second caller waits for the first (the simplified method builds
    /// it beside its first search, `simplified::encode_at`).
    pub fn reference(&self) -> Result<&'a Surface, Error> {
        let mesh = self.simplifier().reference();
        // Effort `fast` queries it a few thousand times besides the
        // check's: on a large input the quick tree (on a million
        // triangles 0.2 s of work instead of 0.75 s). The other levels
        // measure many candidates against it.
        let how = match self.services.quick {
            true => crate::metrics::Build::for_queries(
                mesh.face_count(),
                super::stats::check_samples(self.options.effort)
                    + 3 * crate::simplify::QUICK_SAMPLES,
            ),
            false => crate::metrics::Build::Sah,
        };
        let made = self
            .services
            .reference
            .get_or_init(|| Surface::with_build(mesh, how).ok());
        match made {
            Some(r) => Ok(r),
            None => Err(Surface::with_build(mesh, how)
                .err()
                .expect("the same mesh fails again")),
        }
    }

    /// [`reference`](Self::reference) when it is exactly
    /// `Surface::new(&cleaned.mesh)` (the same triangles, the same tree,
    /// so the same samples and distances to the bit), for a service that
    /// would otherwise build that surface again (SwingWrapper's hint:
    /// on horse a tree over 97k triangles per encode); `None` when it is
    /// not (a quick tree at `fast`, or fans rebuilt for the simplifier).
    pub fn cleaned_surface(&self) -> Result<Option<&'a Surface>, Error> {
        if self.services.quick || !self.simplifier().measures_against_its_mesh() {
            return Ok(None);
        }
        self.reference().map(Some)
    }

    /// The L2 distance between the input as given and what the file
    /// `bytes` decodes to, relative to the input's diagonal, as
    /// `swm distance` measures it (Metro's samples: every vertex, points
    /// along every edge, ten per face of the larger mesh). Several times
    /// the cost of [`Job::measure`]; the error target checks its answer
    /// with it.
    pub fn metro(&self, bytes: &[u8]) -> Result<f64, Error> {
        let s = self.services;
        let given = match s.given.get() {
            Some(g) => g,
            None => {
                let made = Surface::new(s.input)?;
                s.given.get_or_init(|| made)
            }
        };
        let decoded = crate::decoder::decode(bytes, &Default::default())?;
        let d =
            crate::metrics::distance_between(given, &Surface::new(&decoded)?, &Default::default())?;
        Ok(d.l2_relative())
    }

    /// The L2 distance of the file `bytes` to the reference, relative to
    /// its diagonal, with the chooser's samples
    /// ([`AUTO_SAMPLES`](crate::AUTO_SAMPLES)).
    pub fn measure(&self, bytes: &[u8]) -> Result<f64, Error> {
        let d = crate::simplify::file_distance(bytes, self.reference()?, crate::AUTO_SAMPLES)?;
        Ok(d.l2_relative())
    }
}

/// What a method is asked for: a size, a rate or an edge length, and a
/// cap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ask {
    /// The target.
    pub target: SwingTarget,
    /// Never more than this many bytes.
    pub max_bytes: Option<u64>,
}

/// A method's file, before the chooser weighs it.
pub(crate) struct Made {
    /// The file.
    pub bytes: Vec<u8>,
    /// The method's figures.
    pub stats: MethodStats,
    /// Its L2 relative to [`Job::reference`] when the method measured it
    /// already with the chooser's samples (the simplified method does,
    /// to choose its quantization).
    pub l2_relative: Option<f64>,
    /// It holds the whole cleaned mesh: short of the request, there is
    /// nothing more to code.
    pub whole: bool,
    /// For each vertex of the file decoded plainly, the vertex of the
    /// job's reference mesh ([`Simplifier::reference`]) it stands for
    /// (`u32::MAX`: not known), where the method knows it and the caller
    /// asked for origins (`EncodeOptions::origins`): where
    /// `provenance` starts. `None`: the nearest point serves.
    pub seeds: Option<Vec<u32>>,
}

/// A coding method. Deterministic: the same job and ask give the same
/// bytes at any thread count.
pub(crate) trait CodingMethod: Sync {
    /// Which method it is.
    fn method(&self) -> Method;

    /// Whether it still runs when the whole mesh at the finest
    /// quantization fits the request (a retiling would then work far
    /// below the input's edge length and come nowhere near that file).
    fn runs_when_whole_fits(&self) -> bool {
        false
    }

    /// Whether its file carries the input's attribute streams (`ATTR`,
    /// format 1.2). An input with streams is coded only by methods that
    /// do: the others are recorded as not tried
    /// ([`CandidateFailure::DropsAttributes`](super::stats::CandidateFailure)).
    fn carries_attributes(&self, _streams: &[crate::AttributeStream]) -> bool {
        false
    }

    /// Whether it can answer an edge-length request (and so give the
    /// others their size).
    fn takes_edge_length(&self) -> bool {
        false
    }

    /// The work it predicts for `ask` (whose budget is `bytes`), in
    /// [`work_unit`](Self::work_unit), for an effort level's budget;
    /// `None` when it has no work to bound.
    fn predicted_work(&self, _job: &Job<'_, '_>, _ask: Ask, _bytes: u64) -> Option<u64> {
        None
    }

    /// What [`predicted_work`](Self::predicted_work) and an effort
    /// level's budget for this method count.
    fn work_unit(&self) -> &'static str {
        "steps of retiling"
    }

    /// The limit on the retiler's work (`EncodeLimits::max_work`) it
    /// runs under when an effort level gives it `budget`; `None`: the
    /// budget only decides whether it runs.
    fn work_limit(&self, _budget: u64) -> Option<u64> {
        None
    }

    /// How a user runs it when an effort level's budget leaves it out.
    fn run_anyway(&self) -> &'static str {
        "--effort max tries it"
    }

    /// Its file for `ask`; `Ok(None)` when it has nothing to add for this
    /// input (the chooser records it as not applicable).
    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error>;
}
