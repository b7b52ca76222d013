//! The options of [`encode`](crate::encode) and [`decode`](crate::decode):
//! plain types at the bottom of the crate, which every encoder and
//! decoder module may import and which import nothing of theirs (the
//! layers are drawn in ARCHITECTURE.md).

#[cfg(feature = "encoder")]
use crate::CleanOptions;
use crate::Limits;

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
    /// whose file fits the size (module `simplify`).
    Simplified {
        /// A size or a rate; an edge length is refused (this method has
        /// none).
        target: SwingTarget,
        /// A size in bytes never to exceed. Default none.
        max_bytes: Option<u64>,
    },
    /// Displaced subdivision (mode 2, format 1.2): a quadric-simplified
    /// base coded losslessly, levels of 1-to-4 subdivision, one quantized
    /// scalar per new vertex along its predicted normal; the base's size
    /// and the level count chosen to fit the size.
    Displaced {
        /// A size or a rate; an edge length or an error bound is refused.
        target: SwingTarget,
        /// A size in bytes never to exceed. Default none.
        max_bytes: Option<u64>,
    },
    /// The methods of [`EncodeOptions::effort`]'s level at the same size
    /// (at [`Effort::Max`]: SwingWrapper, [`Simplified`](EncodeMode::Simplified),
    /// [`Displaced`](EncodeMode::Displaced) and a method per component),
    /// each decoded and measured against
    /// the cleaned input with the encoder's own distance (L2,
    /// [`AUTO_SAMPLES`] area-uniform samples each way; with texture
    /// coordinates or colours, plus their error: 1e-4 of the diagonal per
    /// RMS texel of a 1024² texture and per RMS 8-bit colour step); the
    /// lower error wins, and a method that fails (or whose nearest file misses the
    /// size by more than 3%) drops out. With an edge length, the SwingWrapper file's size is
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
    /// Bits per vertex of the input mesh as given to `encode`, its
    /// vertices counted by position
    /// ([`TriMesh::distinct_positions`](crate::TriMesh::distinct_positions)).
    BitsPerVertex(f64),
    /// The edge length L itself, in the mesh's units.
    EdgeLength(f64),
    /// The smallest file whose L2 distance to the input, as the encoder
    /// measures it, is at most this bound ([`EncodeMode::Auto`] and
    /// [`EncodeMode::Simplified`] only).
    MaxError(ErrorBound),
}

#[cfg(feature = "encoder")]
/// An error bound for [`SwingTarget::MaxError`]: the symmetric L2
/// (root mean square) surface distance between the input and the
/// decoded file, as `swm distance` reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ErrorBound {
    /// Relative to the input's bounding-box diagonal (`2e-4`: the
    /// "x 1e-4 of the diagonal" figure 2).
    Relative(f64),
    /// In the mesh's units.
    Absolute(f64),
}

#[cfg(feature = "encoder")]
/// How hard the encoder works, as Draco's compression levels and zstd's
/// levels let a user say it: each level is a set of candidate methods
/// and a work budget for the automatic mode's chooser
/// (`encoder::effort`). The work of every level grows at most linearly
/// with the input's triangles and the output's bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Effort {
    /// The simplified method alone, with a short search (one
    /// quantization predicted from the face count, no distance
    /// measured): about the time of a lossless encode plus one quadric
    /// simplification.
    Fast,
    /// The simplified method with its lean search (the full search's
    /// climb over quantizations, each measured, with fewer probes per
    /// size search; `--mode lossless` with a size keeps the full one),
    /// and SwingWrapper where its retiling fits the level's work budget
    /// (small outputs); the chooser measures both.
    #[default]
    Default,
    /// Every method with its whole search: SwingWrapper's rate control,
    /// crease and hint trials, the simplified method, and a method per
    /// component. Files are those the automatic mode wrote before effort
    /// levels existed.
    Max,
}

#[cfg(feature = "encoder")]
impl Effort {
    /// The level's name, as `swm encode --effort` takes it.
    pub fn name(self) -> &'static str {
        match self {
            Effort::Fast => "fast",
            Effort::Default => "default",
            Effort::Max => "max",
        }
    }
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
    /// How hard the encoder works for a smaller error at the same size:
    /// which methods [`EncodeMode::Auto`] weighs and how far each
    /// searches. Default: [`Effort::Default`].
    pub effort: Effort,
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
    /// Find where each vertex of a lossy file came from
    /// (`EncodeStats::origins`: a face of the input and barycentric
    /// coordinates per decoded vertex, what attributes are resampled
    /// from). Default `false`: on a file of a million vertices it is a
    /// million nearest-point queries.
    pub origins: bool,
    /// Quantization of the attribute streams a lossless encode of an
    /// [`AttributedMesh`](crate::AttributedMesh) keeps
    /// ([`encode_attributed`](crate::encode_attributed)). Default:
    /// Draco's defaults, see [`AttributeQuantization`].
    pub attributes: AttributeQuantization,
    /// Keep an input's normals in a lossy file wherever the size allows
    /// them (`encode_attributed`): by default normals that follow the
    /// geometry (within `encoder::smooth::SMOOTH_NORMAL_DEGREES` RMS of
    /// its own) are not coded, as a decoder recomputes them from the
    /// decoded surface, and others are dropped where they cost the
    /// surface more than they give at the size asked for
    /// ([`AttributesDropped::CostlyNormals`](crate::AttributesDropped));
    /// the report says so. Default `false`.
    pub keep_smooth_normals: bool,
    /// When the size asked for (a `Bytes` or `BitsPerVertex` target) is
    /// below the smallest file the mode can write, write that smallest
    /// file instead of failing with [`Error::Size`](crate::Error::Size);
    /// [`EncodeStats::smallest_instead`](crate::EncodeStats) then says
    /// what was asked. The second search runs in the same encode (the
    /// cleaning, the reference surface and the collapse sequence are made
    /// once). A cap (`max_bytes`) below that smallest file still fails.
    /// An input with attribute streams
    /// ([`encode_attributed`](crate::encode_attributed)) below its
    /// smallest file both with them and without is encoded again once,
    /// at the size of the smallest file that keeps them. Default `false`
    /// (`swm encode --or-smallest`).
    pub or_smallest: bool,
}

#[cfg(feature = "encoder")]
/// Quantization bits per attribute kind, as Draco's `draco_encoder`
/// takes them (`-qn`, `-qt`, `-qg`; `swm encode --qn --qt --qg`), with
/// its defaults. Normals are quantized on the octahedron (two
/// coordinates of `normal_bits` each); texture coordinates, colours and
/// generic streams per component on a grid over the stream's bounding
/// box, the same step on every component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AttributeQuantization {
    /// Bits per octahedral coordinate of a normal, 4..=16. Default 8
    /// (the decoded normal within 1° of the input's).
    pub normal_bits: u8,
    /// Bits per texture coordinate, 2..=24. Default 10 (a step of
    /// 1/1023 of the coordinates' extent: a texel of a 1024² texture
    /// over a [0, 1] chart).
    pub texcoord_bits: u8,
    /// Bits per colour component, 2..=24. Default 8.
    pub color_bits: u8,
    /// Bits per component of a generic stream, 2..=24. Default 8.
    pub generic_bits: u8,
}

#[cfg(feature = "encoder")]
impl Default for AttributeQuantization {
    fn default() -> Self {
        AttributeQuantization {
            normal_bits: 8,
            texcoord_bits: 10,
            color_bits: 8,
            generic_bits: 8,
        }
    }
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
    /// for decoders to follow (module `post::hint`); where
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
/// choice, module `post::hint`) in every field left `None`; a file
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
    /// Decode at most this many subdivision levels of a displaced
    /// (mode 2) file: `Some(0)` gives its base mesh, `Some(l)` the mesh
    /// of level `l` (`T0 · 4^l` triangles), bit for bit what the file cut
    /// after `l` levels ([`cut_levels`](crate::cut_levels)) decodes to.
    /// A value above the file's level count decodes every level. Default
    /// `None`: every level. Ignored by modes 0 and 1, which have no
    /// levels.
    pub max_level: Option<u8>,
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

    /// Whether post-processing is asked for by name (EdgeSharpener on,
    /// or Bender steps), whatever the file's hint. Such a mesh is not the
    /// one a file's attribute streams were coded over, so
    /// [`decode_attributed`](crate::decode_attributed) gives it without
    /// them; every front door applies this one rule.
    pub fn post_processing_asked(&self) -> bool {
        self.sharpen == Some(true) || self.bend_steps.is_some_and(|b| b > 0)
    }
}
