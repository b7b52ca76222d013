//! What [`encode`](crate::encode) reports: the method that wrote the
//! file with its own figures (one variant per method, [`MethodStats`]),
//! and every candidate the chooser weighed ([`Candidate`]). A new method
//! adds a variant here and nothing else to the report.

use crate::{CleanReport, LimitError, LosslessStats, RetileError, SizeError, SwingStats};

pub use super::swing::hint::HintReport;
pub use crate::swing::retile::compose::{PieceOutcome, PieceReport};
pub use crate::swing::retile::rate::{Attempt, RateReport};

/// A coding method of the encoder.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Method {
    /// The input's own triangles, positions quantized (mode 0).
    Lossless,
    /// Quadric simplification, then the lossless mode (mode 0).
    Simplified,
    /// SwingWrapper retiling (mode 1).
    Swing,
    /// Each component by the method measured closer at its share of the
    /// size: a SwingWrapper file (mode 1) whose `REST` holds the
    /// simplified components.
    Mixed,
    /// Displaced subdivision (mode 2): a simplified base, levels of
    /// subdivision, one scalar per new vertex.
    Displaced,
}

impl Method {
    /// Its name in reports and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Lossless => "lossless",
            Method::Simplified => "simplified",
            Method::Swing => "swing",
            Method::Mixed => "mixed",
            Method::Displaced => "displaced",
        }
    }
}

/// What the simplified method kept.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SimplifiedStats {
    /// Faces of the cleaned input.
    pub input_faces: u64,
    /// Faces of the simplified mesh written.
    pub faces: u64,
    /// Its bits per coordinate.
    pub qp: u8,
    /// The decoded file's L2 distance to the cleaned input, relative to
    /// its bounding-box diagonal, as the encoder measured it to choose
    /// `qp` ([`AUTO_SAMPLES`](crate::AUTO_SAMPLES) samples each way);
    /// `None` when the search measured nothing ([`Effort::Fast`](crate::Effort)).
    pub l2_relative: Option<f64>,
}

/// What the displaced-subdivision method made.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct DisplacedStats {
    /// Faces of the base mesh.
    pub base_faces: u64,
    /// Subdivision levels.
    pub levels: u8,
    /// Bits per coordinate of the base.
    pub qp: u8,
    /// Bytes of the base's lossless file (`BASE`).
    pub base_bytes: u64,
    /// Bytes of each level's scalars, coarse to fine.
    pub level_bytes: Vec<u64>,
    /// New vertices of each level whose normal line missed the input
    /// within reach (placed by the fallback).
    pub misses: Vec<u64>,
    /// The file's L2 distance to the cleaned input over its diagonal, as
    /// the method measured it ([`AUTO_SAMPLES`](crate::AUTO_SAMPLES)
    /// samples each way).
    pub l2_relative: Option<f64>,
}

/// The figures of a SwingWrapper file (also of a mixed one, whose
/// simplified components sit in its `REST`).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SwingReport {
    /// Its sections, counts and regularity.
    pub stats: SwingStats,
    /// How rate control chose the edge length.
    pub rate: RateReport,
    /// What happened to each connected component of the cleaned input,
    /// in order.
    pub pieces: Vec<PieceReport>,
    /// What the encoder measured for the post-processing hint, and what
    /// it recommends (`None` when the hint was not measured).
    pub hint: Option<HintReport>,
}

/// The method that wrote a file, with its own figures.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum MethodStats {
    /// The lossless mode at a given quantization.
    Lossless(LosslessStats),
    /// Simplified, then the lossless mode.
    Simplified {
        /// The lossless file's figures.
        lossless: LosslessStats,
        /// What simplification kept.
        simplified: SimplifiedStats,
    },
    /// SwingWrapper.
    Swing(SwingReport),
    /// A method per component, in a SwingWrapper file.
    Mixed(SwingReport),
    /// Displaced subdivision.
    Displaced(DisplacedStats),
}

impl MethodStats {
    /// Which method this is.
    pub fn method(&self) -> Method {
        match self {
            MethodStats::Lossless(_) => Method::Lossless,
            MethodStats::Simplified { .. } => Method::Simplified,
            MethodStats::Swing(_) => Method::Swing,
            MethodStats::Mixed(_) => Method::Mixed,
            MethodStats::Displaced(_) => Method::Displaced,
        }
    }
}

/// Why a candidate of the chooser made no file it could weigh.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum CandidateFailure {
    /// No edge length retiled the surface (within the size cap).
    Retile(RetileError),
    /// The encoder's limits (or the effort level's work budget) stopped
    /// it.
    Limit(LimitError),
    /// Its smallest file is larger than the request.
    TooSmall(SizeError),
    /// Its nearest file missed the requested size by more than rate
    /// control's 3% (it was `bytes` long) while another candidate fits.
    Oversized {
        /// Its size.
        bytes: u64,
    },
    /// Not tried: the whole cleaned mesh at the finest quantization of
    /// the simplified method (16 bits) fits the request, and no retiling
    /// comes near its error (a request far above what the mesh needs,
    /// such as 100 MB for a 13,000-vertex part, would only make the
    /// retiler work at an edge length far below the input's).
    Unneeded {
        /// The size of that whole-mesh file.
        whole_bytes: u64,
    },
    /// Not tried at this effort level: its predicted work is above the
    /// level's budget for this input and size.
    OverBudget {
        /// The work predicted, in `unit`.
        predicted: u64,
        /// The level's budget, in `unit`.
        budget: u64,
        /// What the method counts its work in ("steps of retiling",
        /// "bytes of file").
        unit: &'static str,
        /// How a user runs it anyway ("--effort max tries it").
        instead: &'static str,
    },
    /// Not tried: the input has attribute streams (texture coordinates,
    /// normals, colours) and this method's file cannot carry them
    /// (per-component files carry none; SwingWrapper and displaced files
    /// no texture coordinates, one value per vertex); a method that keeps
    /// them coded it.
    DropsAttributes,
    /// The method has nothing to add for this input: a method per
    /// component on a mesh of one component, or one whose components all
    /// chose the same method (the file would be another candidate's).
    NotApplicable,
}

impl core::fmt::Display for CandidateFailure {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CandidateFailure::Retile(e) => write!(f, "{e}"),
            CandidateFailure::Limit(e) => write!(f, "{e}"),
            CandidateFailure::TooSmall(e) => write!(f, "{e}"),
            CandidateFailure::Oversized { bytes } => write!(
                f,
                "its nearest file, {bytes} bytes, missed the size by more than 3%"
            ),
            CandidateFailure::Unneeded { whole_bytes } => write!(
                f,
                "not tried: the whole mesh at 16 bits per coordinate fits in {whole_bytes} bytes"
            ),
            CandidateFailure::OverBudget {
                predicted,
                budget,
                unit,
                instead,
            } => write!(
                f,
                "not tried at this effort: about {predicted} {unit} predicted, above the level's {budget} ({instead})"
            ),
            CandidateFailure::NotApplicable => write!(f, "nothing to add for this mesh"),
            CandidateFailure::DropsAttributes => write!(
                f,
                "not tried: its file cannot carry the input's texture coordinates, normals or colours"
            ),
        }
    }
}

/// One candidate of the chooser, as measured by the encoder.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Candidate {
    /// Its method.
    pub method: Method,
    /// Its file's size and measured error, or why there is none.
    pub outcome: Result<Measured, CandidateFailure>,
}

/// A candidate file's size and error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    /// Its file size.
    pub bytes: u64,
    /// Its L2 distance to the cleaned input, relative to the input's
    /// bounding-box diagonal; `None` for a lone candidate, which the
    /// chooser does not measure ([`Effort::Fast`](crate::Effort)).
    pub l2_relative: Option<f64>,
}

/// What [`encode`](crate::encode) learnt while encoding.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct EncodeStats {
    /// What cleaning changed in the input.
    pub clean: CleanReport,
    /// The method that wrote the file, with its figures.
    pub method: MethodStats,
    /// Every candidate the automatic mode weighed, in the order of its
    /// list (empty when the mode named one method).
    pub candidates: Vec<Candidate>,
    /// The file as decoded, measured against the input: the error to
    /// report (`None` in the lossless mode, whose file keeps every
    /// triangle and moves each vertex by at most half a quantization
    /// step).
    pub check: Option<Check>,
    /// For each vertex of the file as decoded plainly (no
    /// post-processing), the face of the input and the barycentric
    /// coordinates it stands for (`provenance`): what attributes are
    /// resampled from. Empty unless `EncodeOptions::origins` asks for it,
    /// and in the lossless mode, whose vertices are the input's own.
    pub origins: Vec<Origin>,
    /// What became of the input's attribute streams
    /// ([`encode_attributed`](crate::encode_attributed)): empty for an
    /// input without any.
    pub attributes: AttributeReport,
    /// The request the file could not meet, when
    /// [`EncodeOptions::or_smallest`](crate::EncodeOptions) wrote the
    /// smallest file instead: the size asked for and that smallest size.
    pub smallest_instead: Option<crate::SizeError>,
}

/// What an encode did with the input's attribute streams (issue 47):
/// which the file carries, which it does not and why, and how far the
/// decoded texture coordinates are from the input's.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct AttributeReport {
    /// The streams the file carries (`ATTR`), in the input's order.
    pub kept: Vec<crate::AttributeKind>,
    /// The streams it does not carry.
    pub dropped: Vec<crate::AttributeKind>,
    /// Why, when some were dropped.
    pub dropped_because: Option<AttributesDropped>,
    /// The decoded texture coordinates measured against the input's
    /// (`metrics::texcoord`): a lossy file that keeps set 0.
    pub texcoord_error: Option<TexcoordError>,
}

/// Why an encode dropped the input's attribute streams.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum AttributesDropped {
    /// The mode named a method whose file cannot carry them
    /// (SwingWrapper; displaced subdivision, texture coordinates); the
    /// automatic mode runs only methods that can.
    Method(Method),
    /// The input's normals follow its geometry (within `rms_degrees`
    /// RMS, `encoder::smooth`): a decoder recomputes them from the
    /// decoded surface, so a lossy file does not code them
    /// (`EncodeOptions::keep_smooth_normals` keeps them).
    SmoothNormals {
        /// The RMS angle between the input's normals and its geometry's.
        rms_degrees: f32,
    },
    /// The size asked for is below the smallest file that keeps them:
    /// the file codes the surface alone.
    NoRoom {
        /// The smallest file with the streams, in bytes.
        smallest: u64,
    },
    /// The input's normals do not follow its geometry (creases, custom
    /// shading; `rms_degrees` RMS from its geometry's own), but at the
    /// size asked for they cost the surface more than they give: the
    /// file without them, its L2 plus their error weighed at
    /// `encoder::smooth::NORMAL_DEGREE_WEIGHT` (1e-4 of the diagonal a
    /// degree), is closer to the input than the file that kept them,
    /// whose L2 was `l2_kept` (`EncodeOptions::keep_smooth_normals`
    /// keeps them).
    CostlyNormals {
        /// The RMS angle between the input's normals and its geometry's.
        rms_degrees: f32,
        /// The relative L2 of the file that kept them.
        l2_kept: f32,
    },
}

impl core::fmt::Display for AttributesDropped {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AttributesDropped::Method(Method::Displaced) => write!(
                f,
                "the displaced method's file cannot carry texture coordinates"
            ),
            AttributesDropped::Method(m) => write!(
                f,
                "the {} method's file cannot carry per-corner attributes",
                m.name()
            ),
            AttributesDropped::NoRoom { smallest } => write!(
                f,
                "the size asked for is below the smallest file that keeps them ({smallest} bytes)"
            ),
            AttributesDropped::CostlyNormals { rms_degrees, l2_kept } => write!(
                f,
                "the normals ({rms_degrees:.1} degrees RMS off the geometry's) cost the surface more than they give at this size: with them its L2 was {:.2} x 1e-4 of the diagonal",
                l2_kept * 1e4
            ),
            AttributesDropped::SmoothNormals { rms_degrees } => write!(
                f,
                "the normals follow the geometry (within {rms_degrees:.1} degrees RMS): decoders recompute them from the decoded surface"
            ),
        }
    }
}

pub use crate::metrics::texcoord::TexcoordError;

impl EncodeStats {
    /// The method that wrote the file.
    pub fn chosen(&self) -> Method {
        self.method.method()
    }

    /// The lossless file's figures (lossless and simplified methods).
    pub fn lossless(&self) -> Option<&LosslessStats> {
        match &self.method {
            MethodStats::Lossless(l) | MethodStats::Simplified { lossless: l, .. } => Some(l),
            _ => None,
        }
    }

    /// What the simplified method kept, when it wrote the file.
    pub fn simplified(&self) -> Option<&SimplifiedStats> {
        match &self.method {
            MethodStats::Simplified { simplified, .. } => Some(simplified),
            _ => None,
        }
    }

    /// The SwingWrapper figures of a retiled (or mixed) file.
    pub fn swing_report(&self) -> Option<&SwingReport> {
        match &self.method {
            MethodStats::Swing(r) | MethodStats::Mixed(r) => Some(r),
            _ => None,
        }
    }

    /// [`SwingReport::stats`] of a retiled file.
    pub fn swing(&self) -> Option<&SwingStats> {
        self.swing_report().map(|r| &r.stats)
    }

    /// How rate control chose the edge length of a retiled file.
    pub fn rate(&self) -> Option<&RateReport> {
        self.swing_report().map(|r| &r.rate)
    }

    /// What the retiler did with each component (empty for mode 0).
    pub fn pieces(&self) -> &[PieceReport] {
        self.swing_report().map_or(&[], |r| &r.pieces)
    }

    /// The measured post-processing hint of a retiled file.
    pub fn hint(&self) -> Option<&HintReport> {
        self.swing_report().and_then(|r| r.hint.as_ref())
    }

    /// The chooser's candidate of `method`, when it weighed one.
    pub fn candidate(&self, method: Method) -> Option<&Candidate> {
        self.candidates.iter().find(|c| c.method == method)
    }
}

/// A `.swm` file and the statistics of its making.
#[derive(Clone, Debug, PartialEq)]
pub struct Encoded {
    /// The file.
    pub bytes: Vec<u8>,
    /// How it was made.
    pub stats: EncodeStats,
}

/// Metro's samples kept per side for the check (`encoder::check`):
/// about 0.3% standard error on the L2 of a simplified scan (measured in
/// BENCHMARKS.md, "The reported error").
pub const CHECK_SAMPLES: u64 = 60_000;

/// The check's samples per side at effort `fast`: about 0.5% standard
/// error, still well inside the 2% the reported error promises, for a
/// third of the check's queries (the check was a sixth of `fast`'s time
/// on the scans: BENCHMARKS.md, "Session 2026-12-06 (eighth)").
pub const FAST_CHECK_SAMPLES: u64 = 20_000;

/// The check's samples per side at `effort`.
pub(crate) fn check_samples(effort: crate::Effort) -> u64 {
    match effort {
        crate::Effort::Fast => FAST_CHECK_SAMPLES,
        _ => CHECK_SAMPLES,
    }
}

/// The file as decoded, measured against the input.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Check {
    /// Vertices of the decoded mesh.
    pub decoded_vertices: usize,
    /// Triangles of the decoded mesh.
    pub decoded_triangles: usize,
    /// The decoded surface's area over the input's.
    pub area_ratio: f64,
    /// Symmetric L2 distance to the input over the input's bounding-box
    /// diagonal, Metro's estimated from `CHECK_SAMPLES` of its samples a
    /// side (`FAST_CHECK_SAMPLES` at effort `fast`); `None` when the file
    /// decodes to no triangle.
    pub l2_relative: Option<f64>,
    /// The largest distance found among those samples (a lower bound of
    /// the Hausdorff distance) over the diagonal; `None` as above.
    pub hausdorff_relative: Option<f64>,
    /// Points measured on each side.
    pub samples: u64,
}

/// Where one decoded vertex came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Origin {
    /// A face of the input as given (index into its triangles).
    pub face: u32,
    /// Barycentric coordinates on that face, in its corner order.
    pub barycentric: [f32; 3],
}
