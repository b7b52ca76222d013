//! The public entry points: [`encode`], [`decode`] and [`inspect`], with
//! their options and statistics. Modes live in their own modules; this one
//! only validates options and dispatches.

use crate::container::{parse_container, Mode};
#[cfg(feature = "encoder")]
use crate::{CleanOptions, CleanReport, ParameterError};
use crate::{Error, Limits, TriMesh};

pub use crate::lossless::LosslessStats;

#[cfg(feature = "encoder")]
/// Which codec an encoder uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum EncodeMode {
    /// Keep the input's triangles; quantize positions to `qp` bits.
    Lossless {
        /// Bits per coordinate, 6..=24. Default 12.
        qp: u8,
    },
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
}

/// Options for [`decode`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DecodeOptions {
    /// Caps on what the file may make the decoder allocate.
    pub limits: Limits,
}

#[cfg(feature = "encoder")]
/// What [`encode`] learnt while encoding.
#[derive(Clone, Debug, PartialEq)]
pub struct EncodeStats {
    /// What cleaning changed in the input.
    pub clean: CleanReport,
    /// Mode-specific figures.
    pub lossless: LosslessStats,
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
            let (bytes, lossless, _) = crate::lossless::encode(&cleaned.table, &cleaned.mesh, qp)?;
            Ok(Encoded {
                bytes,
                stats: EncodeStats {
                    clean: cleaned.report,
                    lossless,
                },
            })
        }
    }
}

/// Decodes a `.swm` file. Every byte is treated as hostile: a malformed
/// file gives an error, never a panic, and nothing beyond `options.limits`
/// is allocated.
pub fn decode(bytes: &[u8], options: &DecodeOptions) -> Result<TriMesh, Error> {
    let file = parse_container(bytes, &options.limits)?;
    match file.header.mode {
        Mode::Lossless => crate::lossless::decode(&file, &options.limits),
        // SwingWrapper files are defined by the format but not decoded yet.
        other => Err(crate::error::UnsupportedError {
            feature: crate::error::UnsupportedFeature::Mode(other.code()),
            major: file.header.major,
            minor: file.header.minor,
            supported_major: crate::container::FORMAT_MAJOR,
            supported_minor: crate::container::FORMAT_MINOR,
        }
        .into()),
    }
}

/// What `swm info` shows of a `.swm` file, read without decoding geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct FileInfo {
    /// Format version (major, minor).
    pub version: (u8, u8),
    /// The codec that wrote it.
    pub mode: Mode,
    /// Quantization bits (lossless mode).
    pub qp: u8,
    /// Figures, as the encoder reports them.
    pub stats: LosslessStats,
}

/// Reads a file's header and connectivity (CLERS histogram included).
pub fn inspect(bytes: &[u8], limits: &Limits) -> Result<FileInfo, Error> {
    let file = parse_container(bytes, limits)?;
    let h = &file.header;
    let (q, conn, dummies) = crate::lossless::read_connectivity(&file, limits)?;
    let sections = file.sections().map(|s| (s.tag.0, s.bytes.len()));
    Ok(FileInfo {
        version: (h.major, h.minor),
        mode: h.mode,
        qp: q.bits,
        stats: LosslessStats::new(h, &conn, dummies.len(), sections, bytes.len()),
    })
}
