//! The public entry points: [`encode`], [`decode`] and [`inspect`], with
//! their options and statistics. Modes live in their own modules; this one
//! only validates options and dispatches.

use crate::container::{parse_container, Mode};
#[cfg(feature = "encoder")]
use crate::{CleanOptions, CleanReport, ParameterError};
use crate::{Error, Limits, TriMesh};

pub use crate::lossless::LosslessStats;
pub use crate::swing::SwingStats;

#[cfg(feature = "encoder")]
pub use crate::retile::compose::{PieceOutcome, PieceReport};
#[cfg(feature = "encoder")]
pub use crate::retile::rate::{Attempt, RateReport};

#[cfg(feature = "encoder")]
/// Which codec an encoder uses.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum EncodeMode {
    /// Keep the input's triangles; quantize positions to `qp` bits.
    Lossless {
        /// Bits per coordinate, 6..=24. Default 12.
        qp: u8,
    },
    /// SwingWrapper: retile into near-equilateral triangles of edge L,
    /// one quantized dihedral angle per vertex.
    Swing {
        /// What to aim at: a size, a rate or an edge length.
        target: SwingTarget,
        /// Bits per dihedral angle K, 4..=12. `None` (what `swm encode`
        /// does without `--angle-bits`): [`DEFAULT_ANGLE_BITS`] for a given
        /// edge length; for a size or a rate, chosen by rate control (6,
        /// or 5 when the 6-bit file's angles spread so widely that the
        /// sampling, not the angles, limits the error).
        angle_bits: Option<u8>,
        /// A size in bytes never to exceed. Default none.
        max_bytes: Option<u64>,
    },
    /// Quadric simplification, then the lossless mode: the largest face
    /// count and the quantization (7..=14 bits) of lowest measured error
    /// whose file fits the size ([`simplify`](crate::simplify)).
    Simplified {
        /// A size or a rate; an edge length is refused (this method has
        /// none).
        target: SwingTarget,
        /// A size in bytes never to exceed. Default none.
        max_bytes: Option<u64>,
    },
    /// SwingWrapper and [`Simplified`](EncodeMode::Simplified) at the same
    /// size, each decoded and measured against the cleaned input with the
    /// encoder's own distance (L2, [`AUTO_SAMPLES`] area-uniform samples
    /// each way); the lower error wins, and a SwingWrapper encode that
    /// fails (or whose nearest file misses the size by more than 3%)
    /// falls back. With an edge length, the SwingWrapper file's size is
    /// the size both get. A size below both methods' smallest files is an
    /// [`Error::Size`](crate::Error::Size) naming the smaller.
    Auto {
        /// What to aim at.
        target: SwingTarget,
        /// A size in bytes never to exceed. Default none.
        max_bytes: Option<u64>,
    },
}

#[cfg(feature = "encoder")]
/// Area-uniform face samples per direction with which the automatic mode
/// and the simplified method's choice of quantization measure their
/// candidates: enough to tell apart errors 2-3% apart on the corpus.
pub const AUTO_SAMPLES: u64 = 30_000;

#[cfg(feature = "encoder")]
/// A method of the encoder, as [`EncodeMode::Auto`] chooses between them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Method {
    /// SwingWrapper retiling (mode 1).
    Swing,
    /// Quadric simplification, then the lossless mode (mode 0).
    Simplified,
    /// Each component by the method measured closer at its share of the
    /// size: a SwingWrapper file (mode 1) whose `REST` holds the
    /// simplified components.
    Mixed,
}

#[cfg(feature = "encoder")]
/// One candidate of the automatic mode, as measured by the encoder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Its file size.
    pub bytes: u64,
    /// Its L2 distance to the cleaned input, relative to the input's
    /// bounding-box diagonal.
    pub l2_relative: f64,
}

#[cfg(feature = "encoder")]
/// How [`EncodeMode::Auto`] chose.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MethodChoice {
    /// The method of the file written.
    pub chosen: Method,
    /// The SwingWrapper candidate; `None` when its encode failed.
    pub swing: Option<Candidate>,
    /// Why the SwingWrapper encode failed.
    pub swing_failure: Option<SwingFailure>,
    /// The simplified candidate; `None` when nothing fits the size.
    pub simplified: Option<Candidate>,
    /// The candidate with a method per component; `None` for a mesh of
    /// one component, or when every measured component chose the same
    /// method (the file would be one of the two above), or when its
    /// encode failed.
    pub mixed: Option<Candidate>,
}

#[cfg(feature = "encoder")]
/// Why the SwingWrapper candidate of [`EncodeMode::Auto`] is missing.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SwingFailure {
    /// No edge length retiled the surface (within the size cap).
    Retile(crate::RetileError),
    /// The encoder's limits stopped the retiling.
    Limit(crate::LimitError),
    /// The nearest retiled file missed the requested size by more than
    /// 3% (it was `bytes` long) while the simplified file fits.
    Oversized {
        /// Its size.
        bytes: u64,
    },
    /// Not tried: the whole cleaned mesh at the finest quantization of the
    /// simplified method (16 bits) fits the request, and no retiling comes
    /// near its error (a request far above what the mesh needs, such as
    /// 100 MB for a 13,000-vertex part, would only make the retiler work
    /// at an edge length far below the input's).
    Unneeded {
        /// The size of that whole-mesh file.
        whole_bytes: u64,
    },
}

#[cfg(feature = "encoder")]
impl core::fmt::Display for SwingFailure {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SwingFailure::Retile(e) => write!(f, "{e}"),
            SwingFailure::Limit(e) => write!(f, "{e}"),
            SwingFailure::Oversized { bytes } => write!(
                f,
                "its nearest file, {bytes} bytes, missed the size by more than 3%"
            ),
            SwingFailure::Unneeded { whole_bytes } => write!(
                f,
                "not tried: the whole mesh at 16 bits per coordinate fits in {whole_bytes} bytes"
            ),
        }
    }
}

#[cfg(feature = "encoder")]
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
    /// `qp` ([`AUTO_SAMPLES`] samples each way).
    pub l2_relative: f64,
}

#[cfg(feature = "encoder")]
/// The angle bits K of a SwingWrapper encode at a given edge length when
/// none is given: the edge length fixes the triangles, so the angles get
/// the precision that keeps their error well under the retiling's (a
/// size or a rate instead lets rate control choose, see
/// [`EncodeMode::Swing`]).
pub const DEFAULT_ANGLE_BITS: u8 = 8;

#[cfg(feature = "encoder")]
/// What the SwingWrapper encoder aims at; the edge length L follows.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SwingTarget {
    /// A file size in bytes, met within 3%.
    Bytes(u64),
    /// Bits per vertex of the input mesh (as given to `encode`).
    BitsPerVertex(f64),
    /// The edge length L itself, in the mesh's units.
    EdgeLength(f64),
}

#[cfg(feature = "encoder")]
impl Default for EncodeMode {
    fn default() -> Self {
        EncodeMode::Lossless { qp: 12 }
    }
}

#[cfg(feature = "encoder")]
/// Options for [`encode`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EncodeOptions {
    /// The codec and its parameters. Default: lossless, 12 bits.
    pub mode: EncodeMode,
    /// How the input is cleaned first. Default: everything on.
    pub clean: CleanOptions,
    /// Caps on the encoder's work, memory and time. Default: see
    /// [`EncodeLimits`].
    pub limits: crate::EncodeLimits,
    /// Encoder-side choices of the SwingWrapper mode. Default: all on.
    pub swing: SwingTuning,
    /// How the file's header and section table are laid out. Default:
    /// [`Framing::Compact`](crate::container::Framing::Compact) (format
    /// 1.1: about 30 bytes fewer per file, 34 per nested remainder);
    /// `Framing::Fixed` writes 1.0's layout, for decoders older than 1.1
    /// (with `SwingTuning::front_contexts` off, the whole file is then
    /// 1.0).
    pub framing: crate::container::Framing,
}

#[cfg(feature = "encoder")]
/// Choices of the SwingWrapper encoder, each switchable to measure what
/// it buys (BENCHMARKS.md, issue 19's ablation). Every decoder of the
/// format reads the result: approximating tips only change which angle
/// codes are sent, and adaptive density adds a `DENS` section (format
/// 1.1) only when some edge length differs from the base.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SwingTuning {
    /// Aim each new vertex off the surface by the offset that cancels the
    /// mean chord error of the triangles around it (about H·L²/8 along
    /// the normal, H the mean curvature at the scale of L), rather than
    /// on the surface as the thesis does. Default `true`.
    pub approximate_tips: bool,
    /// Choose each tip's angle code, among those near the aimed one, by
    /// the two-sided distance between its triangle and the surface the
    /// triangle covers, instead of the code nearest the aim (`retile::fit`;
    /// issue 19, "error-aware geometry"). Default `true`.
    pub fit_tips: bool,
    /// Let the edge length follow the shape: shorter where the surface
    /// bends, is thin or creased, longer where it is flat (L ∝ κ^(−1/3)
    /// for the curvature κ at the scale of L; the file then carries one
    /// level step per vertex in a `DENS` section, format 1.1). Default
    /// `false`: on the shared corpus it does not yet pay for its section
    /// everywhere (BENCHMARKS.md, "Adaptive sampling").
    pub adaptive_density: bool,
    /// Code the CLERS symbols with the shape of the front at each gate as
    /// context (`CLRF`, format 1.1): about a fifth as many bits for the
    /// connectivity. `false` writes `CLRS` as format 1.0 does, for
    /// decoders older than 1.1. Default `true`.
    pub front_contexts: bool,
    /// On a component with holes, start the retiling on its longest
    /// boundary loop (a fan over the hole, its points coded in a `LOOP`
    /// section, format 1.1) instead of inside, where the front crosses
    /// every hole's patch with triangles the decoder then drops. Default
    /// `true`: on open surfaces it keeps the boundary exact to the angle
    /// precision and spends the file on the surface (BENCHMARKS.md,
    /// "Starting on a boundary loop").
    pub loop_start: bool,
    /// Decode the file plain, sharpened, and sharpened and bent once,
    /// measure each against the input, and record the best in the file
    /// (the ancillary `post` section, written only when it is not plain)
    /// for decoders to follow ([`crate::post::hint`]); where
    /// EdgeSharpener helps, also retile with every tip on the surface
    /// (as `approximate_tips` and `fit_tips` off) and keep the file
    /// closer to the input after its hint. Default `true`.
    pub post_hint: bool,
    /// Where the input has sharp edges, also try tips on them: a tip
    /// whose gate's bisecting plane crosses a crease near its circle sits
    /// on the crossing, off the circle by a radius code (`RADS`, format
    /// 1.1; `retile::crease`), so the retiled mesh has edges along the
    /// crease instead of chamfering it. Only where the input's creases
    /// (edges turning by more than 45°) total at least its bounding-box
    /// diagonal: then a size or rate request with `post_hint` on is
    /// encoded both ways and the file that decodes closer after its hint
    /// is kept (`crate::hinted`); an edge-length request, or one without
    /// the hint, uses them. Default `true`.
    pub crease_tips: bool,
}

#[cfg(feature = "encoder")]
impl Default for SwingTuning {
    fn default() -> Self {
        SwingTuning {
            approximate_tips: true,
            fit_tips: true,
            adaptive_density: false,
            front_contexts: true,
            loop_start: true,
            crease_tips: true,
            post_hint: true,
        }
    }
}

/// Options for [`decode`].
///
/// Post-processing follows the file's hint (the encoder's measured
/// choice, [`crate::post::hint`]) in every field left `None`; a file
/// without a hint decodes plain.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DecodeOptions {
    /// Caps on what the file may make the decoder allocate (Bender's
    /// output included).
    pub limits: Limits,
    /// Run EdgeSharpener on the decoded mesh: restore the sharp edges and
    /// corners that retiling chamfered (thesis §8.3). Default `None`:
    /// as the file's hint says (off without one).
    pub sharpen: Option<bool>,
    /// Bender steps after that (crease-preserving butterfly subdivision,
    /// thesis §8.4); each multiplies the triangles by four. Without
    /// sharpening, no edge is kept sharp. Default `None`: as the file's
    /// hint says (0 without one).
    pub bend_steps: Option<u32>,
}

impl DecodeOptions {
    /// Plain decoding whatever the file's hint: neither EdgeSharpener
    /// nor Bender.
    pub fn plain() -> Self {
        DecodeOptions {
            sharpen: Some(false),
            bend_steps: Some(0),
            ..Default::default()
        }
    }
}

#[cfg(feature = "encoder")]
/// What [`encode`] learnt while encoding.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct EncodeStats {
    /// What cleaning changed in the input.
    pub clean: CleanReport,
    /// Figures of a lossless-mode file.
    pub lossless: Option<LosslessStats>,
    /// Figures of a SwingWrapper file.
    pub swing: Option<SwingStats>,
    /// How a SwingWrapper encoder chose its edge length.
    pub rate: Option<RateReport>,
    /// What a SwingWrapper encoder did with each connected component of
    /// the cleaned input, in order (empty in the lossless mode).
    pub pieces: Vec<PieceReport>,
    /// What the simplified method kept (when it wrote the file).
    pub simplified: Option<SimplifiedStats>,
    /// How the automatic mode chose the method.
    pub choice: Option<MethodChoice>,
    /// What the encoder measured for the post-processing hint of a
    /// SwingWrapper file, and what it recommends.
    pub hint: Option<crate::post::hint::HintReport>,
}

#[cfg(feature = "encoder")]
/// A `.swm` file and the statistics of its making.
#[derive(Clone, Debug, PartialEq)]
pub struct Encoded {
    /// The file.
    pub bytes: Vec<u8>,
    /// How it was made.
    pub stats: EncodeStats,
}

#[cfg(feature = "encoder")]
/// Cleans and encodes a mesh. Deterministic: the same mesh and options
/// give the same bytes.
pub fn encode(mesh: &TriMesh, options: &EncodeOptions) -> Result<Encoded, Error> {
    match options.mode {
        EncodeMode::Lossless { qp } => {
            if !(crate::geometry::MIN_BITS..=crate::geometry::MAX_BITS).contains(&qp) {
                return Err(ParameterError::OutOfRange {
                    name: "qp",
                    value: qp as f64,
                    min: crate::geometry::MIN_BITS as f64,
                    max: crate::geometry::MAX_BITS as f64,
                }
                .into());
            }
            let cleaned = crate::clean(mesh, &options.clean)?;
            let (bytes, lossless, _) =
                crate::lossless::encode(&cleaned.table, &cleaned.mesh, qp, options.framing)?;
            Ok(Encoded {
                bytes,
                stats: EncodeStats {
                    clean: cleaned.report,
                    lossless: Some(lossless),
                    swing: None,
                    rate: None,
                    pieces: Vec::new(),
                    simplified: None,
                    choice: None,
                    hint: None,
                },
            })
        }
        EncodeMode::Swing {
            target,
            angle_bits,
            max_bytes,
        } => {
            let cleaned = crate::clean(mesh, &options.clean)?;
            let n = mesh.vertex_count();
            encode_swing(&cleaned, n, options, target, angle_bits, max_bytes)
        }
        EncodeMode::Simplified { target, max_bytes } => {
            let cleaned = crate::clean(mesh, &options.clean)?;
            let budget = simplified_budget(target, mesh.vertex_count(), max_bytes)?;
            let s = crate::simplify::Simplifier::new(&cleaned.mesh, options.framing);
            let reference = crate::metrics::Surface::new(s.reference())?;
            encode_simplified(cleaned.report, &s, budget, &reference)
        }
        EncodeMode::Auto { target, max_bytes } => {
            crate::auto::encode(mesh, options, target, max_bytes)
        }
    }
}

#[cfg(feature = "encoder")]
/// Bytes the requested size or rate gives `vertices` input vertices.
fn bytes_for(bpv: f64, vertices: usize) -> u64 {
    ((bpv * vertices as f64 / 8.0).round() as u64).max(1)
}

#[cfg(feature = "encoder")]
/// A positive finite option, or the error that names it.
fn positive(name: &'static str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::from(ParameterError::NotPositive { name, value }))
    }
}

#[cfg(feature = "encoder")]
/// The byte budget of the simplified method: the size asked for (or the
/// rate's), never above the cap. An edge length is refused.
pub(crate) fn simplified_budget(
    target: SwingTarget,
    vertices: usize,
    max_bytes: Option<u64>,
) -> Result<u64, Error> {
    let b = match target {
        SwingTarget::Bytes(b) => positive("size", b as f64)? as u64,
        SwingTarget::BitsPerVertex(bpv) => bytes_for(positive("bits per vertex", bpv)?, vertices),
        SwingTarget::EdgeLength(_) => {
            return Err(ParameterError::NotApplicable {
                name: "edge length",
                mode: "simplified",
            }
            .into())
        }
    };
    Ok(max_bytes.map_or(b, |cap| b.min(cap)))
}

#[cfg(feature = "encoder")]
/// The simplified method at `budget` bytes: the file of lowest measured
/// error against `reference` (the cleaned input) among the quantizations.
pub(crate) fn encode_simplified(
    clean: CleanReport,
    s: &crate::simplify::Simplifier<'_>,
    budget: u64,
    reference: &crate::metrics::Surface,
) -> Result<Encoded, Error> {
    let Some((fit, l2_relative)) = crate::simplify::best_fit(s, budget, reference, AUTO_SAMPLES)?
    else {
        return Err(crate::SizeError {
            requested: budget,
            smallest: crate::simplify::smallest_bytes(s)?,
        }
        .into());
    };
    // The winner's figures, from the same deterministic encode.
    let cleaned = crate::clean(&fit.mesh, &CleanOptions::default())?;
    let (bytes, lossless, _) =
        crate::lossless::encode(&cleaned.table, &cleaned.mesh, fit.qp, s.framing())?;
    debug_assert_eq!(bytes, fit.bytes, "lossless encoding is deterministic");
    Ok(Encoded {
        bytes,
        stats: EncodeStats {
            clean,
            lossless: Some(lossless),
            swing: None,
            rate: None,
            pieces: Vec::new(),
            simplified: Some(SimplifiedStats {
                input_faces: s.faces() as u64,
                faces: cleaned.mesh.triangles.len() as u64,
                qp: fit.qp,
                l2_relative,
            }),
            choice: None,
            hint: None,
        },
    })
}

#[cfg(feature = "encoder")]
pub(crate) fn encode_swing(
    cleaned: &crate::Cleaned,
    input_vertices: usize,
    options: &EncodeOptions,
    target: SwingTarget,
    angle_bits: Option<u8>,
    max_bytes: Option<u64>,
) -> Result<Encoded, Error> {
    use crate::swing::{MAX_ANGLE_BITS, MIN_ANGLE_BITS};
    if let Some(angle_bits) = angle_bits.filter(|k| !(MIN_ANGLE_BITS..=MAX_ANGLE_BITS).contains(k))
    {
        return Err(ParameterError::OutOfRange {
            name: "angle bits",
            value: angle_bits as f64,
            min: MIN_ANGLE_BITS as f64,
            max: MAX_ANGLE_BITS as f64,
        }
        .into());
    }
    let request = swing_request(target, input_vertices, angle_bits, max_bytes)?;
    let pieces = crate::retile::fill::pieces(&cleaned.mesh, &cleaned.table)?;
    encode_swing_pieces(&pieces, &cleaned.mesh, &cleaned.report, options, request)
}

#[cfg(feature = "encoder")]
/// What a SwingWrapper encode must answer, its numbers checked: bytes
/// from a size or a rate over `input_vertices` vertices, or an edge
/// length.
pub(crate) fn swing_request(
    target: SwingTarget,
    input_vertices: usize,
    angle_bits: Option<u8>,
    max_bytes: Option<u64>,
) -> Result<crate::hinted::Request, Error> {
    Ok(crate::hinted::Request {
        target: match target {
            SwingTarget::EdgeLength(l) => Err(positive("edge length", l)?),
            SwingTarget::Bytes(b) => Ok(positive("size", b as f64)? as u64),
            SwingTarget::BitsPerVertex(bpv) => {
                Ok(bytes_for(positive("bits per vertex", bpv)?, input_vertices))
            }
        },
        max_bytes,
        angle_bits,
    })
}

#[cfg(feature = "encoder")]
/// [`encode_swing`] of the components `pieces` (some of them perhaps
/// marked to be kept simplified, `Piece::keep`) of `input`, the cleaned
/// mesh the post-processing hint is measured against.
pub(crate) fn encode_swing_pieces(
    pieces: &[crate::retile::fill::Piece],
    input: &TriMesh,
    clean: &CleanReport,
    options: &EncodeOptions,
    request: crate::hinted::Request,
) -> Result<Encoded, Error> {
    let (angle_bits, max_bytes) = (request.angle_bits, request.max_bytes);
    use crate::retile::rate;
    // Tips on creases where the input has enough of them: tried against
    // the plain retiling for a size request whose hint is measured (the
    // measure decides), used outright otherwise.
    let creased =
        options.swing.crease_tips && crate::retile::crease_length(pieces) >= input.bbox_diagonal();
    let measured = options.swing.post_hint && request.target.is_ok();
    let budget = crate::retile::Budget::new(options.limits);
    let knobs = rate::Knobs {
        angle_bits: angle_bits.unwrap_or(DEFAULT_ANGLE_BITS),
        approximate_tips: options.swing.approximate_tips,
        fit_tips: options.swing.fit_tips,
        adaptive_density: options.swing.adaptive_density,
        front_contexts: options.swing.front_contexts,
        loop_start: options.swing.loop_start,
        crease_tips: creased && !measured,
        framing: options.framing,
    };
    let mut chosen = request.run(pieces, knobs, &budget, None)?;
    let mut hint = None;
    if options.swing.post_hint {
        let (c, h) = crate::hinted::finish(
            pieces,
            input,
            chosen,
            knobs,
            request,
            creased && measured,
            &budget,
        )?;
        chosen = c;
        hint = Some(h);
    }
    if let Some(cap) = max_bytes {
        if chosen.bytes.len() as u64 > cap {
            return Err(crate::RetileError {
                attempts: chosen.report.attempts.len() as u32,
                successes: chosen
                    .report
                    .attempts
                    .iter()
                    .filter(|a| a.outcome.is_ok())
                    .count() as u32,
                smallest_edge_length: chosen.report.edge_length,
                failure: None,
            }
            .into());
        }
    }
    Ok(Encoded {
        bytes: chosen.bytes,
        stats: EncodeStats {
            clean: clean.clone(),
            lossless: None,
            swing: Some(chosen.stats),
            rate: Some(chosen.report),
            pieces: chosen.pieces,
            simplified: None,
            choice: None,
            hint,
        },
    })
}

/// Decodes a `.swm` file. Every byte is treated as hostile: a malformed
/// file gives an error, never a panic, and nothing beyond `options.limits`
/// is allocated.
pub fn decode(bytes: &[u8], options: &DecodeOptions) -> Result<TriMesh, Error> {
    decode_container(&parse_container(bytes, &options.limits)?, options)
}

/// [`decode`] of a container already parsed (and checked) with
/// `options.limits`.
pub(crate) fn decode_container(
    file: &crate::container::Container<'_>,
    options: &DecodeOptions,
) -> Result<TriMesh, Error> {
    let mesh = match file.header.mode {
        Mode::Lossless => crate::lossless::decode(file, &options.limits)?,
        Mode::Swing => crate::swing::decode(file, &options.limits)?,
    };
    let post = crate::post::hint::resolve(file, options.sharpen, options.bend_steps);
    sharpen_and_bend(mesh, post, &options.limits)
}

/// The decoder's optional post-processing: EdgeSharpener, then Bender
/// with the edges it tagged.
fn sharpen_and_bend(
    mesh: TriMesh,
    post: crate::post::hint::PostProcessing,
    limits: &Limits,
) -> Result<TriMesh, Error> {
    if post.is_plain() {
        return Ok(mesh);
    }
    let (mesh, sharp) = if post.sharpen {
        let s = crate::post::sharpen::sharpen(&mesh, &Default::default())?;
        (s.mesh, s.sharp)
    } else {
        (mesh, crate::post::SharpEdges::default())
    };
    let mesh = if post.bend_steps == 0 {
        mesh
    } else {
        crate::post::bend::bend(&mesh, &sharp, post.bend_steps, limits)?.mesh
    };
    // A hostile file can place vertices near f32's limit (L about 1e38);
    // snaps and stencils there overflow to infinity. The caller gets an
    // error, never a mesh with non-finite positions.
    mesh.validate()?;
    Ok(mesh)
}

/// What `swm info` shows of a `.swm` file, read without decoding geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct FileInfo {
    /// Format version (major, minor).
    pub version: (u8, u8),
    /// How its header and section table are laid out.
    pub framing: crate::container::Framing,
    /// Bytes that are not section payload: preamble, header, section
    /// table and CRC (what the framing costs).
    pub frame_bytes: usize,
    /// The codec that wrote it.
    pub mode: Mode,
    /// Quantization bits (lossless mode; 0 in other modes).
    pub qp: u8,
    /// Figures common to every mode (counts, CLERS histogram, sections),
    /// as the encoder reports them.
    pub stats: LosslessStats,
    /// The SwingWrapper figures (edge length, angle bits, regularity,
    /// bits per triangle of connectivity and geometry); `None` for other
    /// modes.
    pub swing: Option<SwingStats>,
    /// The encoder's post-processing hint (what a default decode runs),
    /// when the file has one this version understands.
    pub post: Option<crate::post::hint::PostProcessing>,
}

/// Reads a file's header and connectivity (CLERS histogram included),
/// without decoding geometry (except in a SwingWrapper file whose
/// symbols are in `CLRF`: they are read in a pass that places the
/// vertices).
pub fn inspect(bytes: &[u8], limits: &Limits) -> Result<FileInfo, Error> {
    let file = parse_container(bytes, limits)?;
    let h = &file.header;
    let sections = file.sections().map(|s| (s.tag.0, s.bytes.len()));
    let (qp, stats, swing) = match h.mode {
        Mode::Lossless => {
            let (q, conn, dummies, table) = crate::lossless::read_connectivity(&file, limits)?;
            // As strict as `decode` about the counts (issue 18): the
            // connectivity is decoded and checked against the header.
            crate::lossless::decode_topology(&file, &conn, &dummies, table)?;
            let stats = LosslessStats::new(h, &conn, dummies.len(), sections, bytes.len());
            (q.bits, stats, None)
        }
        Mode::Swing => {
            let (conn, swing) = crate::swing::inspect(&file, limits, bytes.len())?;
            let stats = LosslessStats::new(h, &conn, 0, sections, bytes.len());
            (0, stats, Some(swing))
        }
    };
    Ok(FileInfo {
        version: (h.major, h.minor),
        framing: h.framing(),
        frame_bytes: file.frame_len() + 4,
        mode: h.mode,
        qp,
        stats,
        swing,
        post: crate::post::hint::read(&file),
    })
}
