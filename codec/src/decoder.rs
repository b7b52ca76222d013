//! One decode table (after Draco's decoder factory): the container's
//! mode selects a [`ModeDecoder`], which gives that mode's decode, its
//! inspection and the counts its sections add to the header's. `decode`,
//! `inspect`, the buffer bounds (`buffers`) and the streaming decoder
//! (`stream`, through `decode`) all go through [`for_mode`]; a new mode
//! is one new entry here and its own module. (The stream decoder also
//! shows a displaced file's levels as they arrive, through
//! `displaced::Refiner`.)
//!
//! After the mode's decode, the optional post-processing (EdgeSharpener,
//! then Bender with the edges it tagged) is common to every mode.

use crate::container::{parse_container, Container, Mode};
use crate::options::DecodeOptions;
use crate::prelude::*;
use crate::{Error, Limits, LosslessStats, SwingStats, TriMesh};

/// What the inspection of one mode reads without decoding geometry.
pub(crate) struct Inspected {
    /// Quantization bits (0 where the mode has none).
    pub qp: u8,
    /// Counts, CLERS histogram and sections.
    pub stats: LosslessStats,
    /// The SwingWrapper figures, for mode 1.
    pub swing: Option<SwingStats>,
    /// Bytes of each subdivision level's chunk, for mode 2.
    pub levels: Vec<usize>,
    /// `HEAD` and `BASE`'s figures, for mode 2.
    pub displaced: Option<crate::displaced::DisplacedInfo>,
}

/// One mode's decoder.
pub(crate) struct ModeDecoder {
    /// The mesh of a checked container (before the common
    /// post-processing; `options.max_level` is mode 2's).
    pub decode: fn(&Container<'_>, &DecodeOptions) -> Result<TriMesh, Error>,
    /// Its figures without geometry; `usize` is the file's length.
    pub inspect: fn(&Container<'_>, &Limits, usize) -> Result<Inspected, Error>,
    /// Vertices and triangles its sections add to the header's counts,
    /// and whether the total is exact (no mask that may drop some).
    pub extra_counts: fn(&Container<'_>, &Limits) -> Result<(u64, u64, bool), Error>,
}

/// Mode 0: the input's own connectivity and quantized positions.
static LOSSLESS: ModeDecoder = ModeDecoder {
    decode: |file, options| crate::lossless::decode(file, &options.limits),
    inspect: |file, limits, len| {
        let (q, conn, dummies, table) = crate::lossless::read_connectivity(file, limits)?;
        // As strict as `decode` about the counts (issue 18): the
        // connectivity is decoded and checked against the header.
        crate::lossless::decode_topology(file, &conn, &dummies, table)?;
        let sections = file.sections().map(|s| (s.tag.0, s.bytes.len()));
        let mut stats = LosslessStats::new(&file.header, &conn, dummies.len(), sections, len);
        if let Some(attr) = file.find(crate::container::Tag::ATTR) {
            stats.attributes = crate::lossless::attributes::inspect(attr.bytes)?;
        }
        Ok(Inspected {
            qp: q.bits,
            stats,
            swing: None,
            levels: Vec::new(),
            displaced: None,
        })
    },
    extra_counts: |_, _| Ok((0, 0, true)),
};

/// Mode 1: SwingWrapper.
static SWING: ModeDecoder = ModeDecoder {
    decode: |file, options| crate::swing::decode(file, &options.limits),
    inspect: |file, limits, len| {
        let (conn, swing) = crate::swing::inspect(file, limits, len)?;
        let sections = file.sections().map(|s| (s.tag.0, s.bytes.len()));
        let mut stats = LosslessStats::new(&file.header, &conn, 0, sections, len);
        if let Some(attr) = file.find(crate::container::Tag::ATTR) {
            stats.attributes = crate::lossless::attributes::inspect(attr.bytes)?;
        }
        Ok(Inspected {
            qp: 0,
            stats,
            swing: Some(swing),
            levels: Vec::new(),
            displaced: None,
        })
    },
    extra_counts: |file, limits| {
        let (v, t) = crate::swing::rest_counts(file, limits)?;
        // The hole mask's triangles and the loops' fans are dropped as
        // decoded: the header counts them.
        let exact = file.find(crate::container::Tag::HOLE).is_none()
            && file.find(crate::container::Tag::LOOP).is_none();
        Ok((v, t, exact))
    },
};

/// Mode 2: displaced subdivision (format 1.2).
static DISPLACED: ModeDecoder = ModeDecoder {
    decode: |file, options| {
        let levels = options.max_level.map_or(usize::MAX, usize::from);
        crate::displaced::decode_levels(file, &options.limits, levels)
    },
    inspect: |file, limits, len| {
        let (levels, qp, displaced) = crate::displaced::levels_and_qp(file, limits)?;
        let h = &file.header;
        let mut stats = LosslessStats {
            vertices: h.vertex_count.into(),
            triangles: h.triangle_count.into(),
            components: h.component_count.into(),
            sections: file.sections().map(|s| (s.tag.0, s.bytes.len())).collect(),
            file_bytes: len,
            ..Default::default()
        };
        if let Some(attr) = file.find(crate::container::Tag::ATTR) {
            stats.attributes = crate::lossless::attributes::inspect(attr.bytes)?;
        }
        Ok(Inspected {
            qp,
            stats,
            swing: None,
            levels,
            displaced: Some(displaced),
        })
    },
    extra_counts: |_, _| Ok((0, 0, true)),
};

/// The decoder of `mode`.
pub(crate) fn for_mode(mode: Mode) -> &'static ModeDecoder {
    match mode {
        Mode::Lossless => &LOSSLESS,
        Mode::Swing => &SWING,
        Mode::Displaced => &DISPLACED,
    }
}

/// [`crate::decode`].
pub(crate) fn decode(bytes: &[u8], options: &DecodeOptions) -> Result<TriMesh, Error> {
    decode_container(&parse_container(bytes, &options.limits)?, options)
}

/// [`crate::decode`] of a container already parsed (and checked) with
/// `options.limits`.
pub(crate) fn decode_container(
    file: &Container<'_>,
    options: &DecodeOptions,
) -> Result<TriMesh, Error> {
    let mesh = (for_mode(file.header.mode).decode)(file, options)?;
    mesh_only(file, mesh, options)
}

/// The mesh-only decode's end, after the mode's decode gave `mesh`: it
/// skips `ATTR`'s chunks but reads its stream headers as `inspect` does
/// (a file one of them refuses, the other refuses too), then runs the
/// post-processing.
fn mesh_only(
    file: &Container<'_>,
    mesh: TriMesh,
    options: &DecodeOptions,
) -> Result<TriMesh, Error> {
    if let Some(attr) = file.find(crate::container::Tag::ATTR) {
        crate::lossless::attributes::inspect(attr.bytes)?;
    }
    let post = crate::post::hint::resolve(file, options.sharpen, options.bend_steps);
    sharpen_and_bend(mesh, post, &options.limits)
}

/// [`crate::decode_attributed`].
pub(crate) fn decode_attributed(
    bytes: &[u8],
    options: &DecodeOptions,
) -> Result<crate::AttributedMesh, Error> {
    let file = parse_container(bytes, &options.limits)?;
    // Post-processing asked for by name changes the mesh the streams
    // were coded over: it is run, and the streams are left out.
    if options.post_processing_asked() {
        return decode_container(&file, options).map(Into::into);
    }
    if let Some(attr) = file.find(crate::container::Tag::ATTR) {
        match file.header.mode {
            Mode::Lossless => return crate::lossless::decode_attributed(&file, &options.limits),
            // Over the plain decode of every level (format-spec/08, "Over
            // a decoded mesh"): a decode stopped at a coarser level
            // (`max_level`) has no attributes, and as for mode 0 the
            // streams come with the mesh they were coded over.
            Mode::Displaced => {
                let mesh = (for_mode(file.header.mode).decode)(&file, options)?;
                if mesh.positions.len() as u64 == u64::from(file.header.vertex_count) {
                    return crate::lossless::attributes::over_mesh::decode(
                        attr.bytes,
                        mesh,
                        &options.limits,
                    );
                }
                return mesh_only(&file, mesh, options).map(Into::into);
            }
            // Over the plain decode (format-spec/08, "Over a decoded
            // mesh"): the file's hint is not followed, as for mode 0.
            Mode::Swing => {
                let mesh = (for_mode(file.header.mode).decode)(&file, options)?;
                return crate::lossless::attributes::over_mesh::decode(
                    attr.bytes,
                    mesh,
                    &options.limits,
                );
            }
        }
    }
    decode_container(&file, options).map(Into::into)
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
    /// The attribute streams of a lossless file's `ATTR` (format 1.2),
    /// in file order; empty without one.
    pub attributes: Vec<crate::AttributeInfo>,
    /// A displaced-subdivision (mode 2) file's levels, coarse to fine:
    /// the bytes of each level's `DISP` chunk (the file cut after `l` of
    /// them, [`cut_levels`](crate::cut_levels), decodes to level `l`).
    /// Empty for other modes.
    pub levels: Vec<usize>,
    /// A displaced-subdivision file's prediction, steps, bends and base;
    /// `None` for other modes.
    pub displaced: Option<crate::displaced::DisplacedInfo>,
}

/// [`crate::inspect`].
pub(crate) fn inspect(bytes: &[u8], limits: &Limits) -> Result<FileInfo, Error> {
    let file = parse_container(bytes, limits)?;
    let h = &file.header;
    let seen = (for_mode(h.mode).inspect)(&file, limits, bytes.len())?;
    let attributes = seen.stats.attributes.clone();
    Ok(FileInfo {
        version: (h.major, h.minor),
        framing: h.framing(),
        frame_bytes: file.frame_len() + 4,
        mode: h.mode,
        qp: seen.qp,
        stats: seen.stats,
        swing: seen.swing,
        post: crate::post::hint::read(&file),
        attributes,
        levels: seen.levels,
        displaced: seen.displaced,
    })
}
