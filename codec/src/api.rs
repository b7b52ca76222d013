//! The public entry points: [`encode`], [`decode`] and [`inspect`]. This
//! module is the facade only: the options are in `options`, the encoder
//! (its methods, chooser and effort levels) in `encoder`, the decode
//! table in `decoder` (ARCHITECTURE.md draws the layers).

use crate::options::DecodeOptions;
use crate::{Error, Limits, TriMesh};

pub use crate::decoder::FileInfo;
pub use crate::displaced::{DisplacedInfo, Prediction};
pub use crate::lossless::LosslessStats;
pub use crate::swing::SwingStats;

#[cfg(feature = "encoder")]
pub use crate::encoder::stats::{
    Attempt, AttributeReport, AttributesDropped, Candidate, CandidateFailure, Check,
    DisplacedStats, EncodeStats, Encoded, HintReport, Measured, Method, MethodStats, Origin,
    PieceOutcome, PieceReport, RateReport, SimplifiedStats, SwingReport, TexcoordError,
};
#[cfg(feature = "encoder")]
pub use crate::encoder::stats::{CHECK_SAMPLES, FAST_CHECK_SAMPLES};
#[cfg(feature = "encoder")]
pub use crate::options::{
    AttributeQuantization, Effort, EncodeMode, EncodeOptions, ErrorBound, SwingTarget, SwingTuning,
    AUTO_SAMPLES, DEFAULT_ANGLE_BITS,
};

#[cfg(feature = "encoder")]
/// Cleans and encodes a mesh. Deterministic: the same mesh and options
/// give the same bytes, at any thread count.
///
/// # Errors
/// A bad option ([`Error::Parameter`]), an input the cleaning cannot
/// make a surface of, a request below the smallest file
/// ([`Error::Size`]) or an error bound no file meets
/// ([`Error::ErrorBound`]), the encoder's limits.
pub fn encode(mesh: &TriMesh, options: &EncodeOptions) -> Result<Encoded, Error> {
    crate::encoder::encode(mesh, options)
}

#[cfg(feature = "encoder")]
/// Encodes a mesh with its attribute streams (normals, texture
/// coordinates, colours, generic), each quantized as
/// `options.attributes` says and coded with its seams in the section
/// `ATTR` (format 1.2), in any mode whose file can carry them: the
/// lossless mode, the simplified mode, displaced subdivision (normals,
/// colours and generic streams, resampled at its vertices) and the
/// automatic mode, which then weighs only the methods that carry them
/// (the simplified method: a simplification that never collapses across
/// a seam, `simplify::attributed`, coded losslessly; the size budget
/// counts the `ATTR` bytes). A mode that names SwingWrapper, or
/// displaced subdivision for texture coordinates, drops them. What was kept, what was dropped and why, and
/// the texture coordinates' error, are in
/// [`EncodeStats::attributes`](crate::EncodeStats). A mesh without
/// streams gives the same bytes as [`encode`]. Deterministic, as
/// [`encode`].
///
/// # Errors
/// As [`encode`], and an invalid mesh or stream
/// ([`AttributedMesh::validate`](crate::AttributedMesh::validate)).
pub fn encode_attributed(
    mesh: &crate::AttributedMesh,
    options: &EncodeOptions,
) -> Result<Encoded, Error> {
    crate::encoder::encode_attributed(mesh, options)
}

/// Decodes a `.swm` file with its attribute streams: those of its
/// `ATTR` section (format 1.2: a lossless file's, or a displaced file's
/// over its finest level), none for a file without one. The mesh is
/// [`decode`]'s plain mesh (vertex and value order are the decoder's);
/// corners at one vertex share a value exactly when they did in the
/// encoder's input. The file's post-processing hint is not followed,
/// since Sharpen&Bend changes the mesh the streams were coded over; and
/// post-processing asked for by name (`options.sharpen` on,
/// `bend_steps` above 0) is run, and the mesh then comes without its
/// streams, as [`decode`] gives it (`swm decode` warns). A decode
/// stopped at a coarser level (`max_level`) has no streams either.
/// Hostile bytes are handled as by [`decode`].
pub fn decode_attributed(
    bytes: &[u8],
    options: &DecodeOptions,
) -> Result<crate::AttributedMesh, Error> {
    crate::decoder::decode_attributed(bytes, options)
}

/// Decodes a `.swm` file. Every byte is treated as hostile: a malformed
/// file gives an error, never a panic, and nothing beyond `options.limits`
/// is allocated.
pub fn decode(bytes: &[u8], options: &DecodeOptions) -> Result<TriMesh, Error> {
    crate::decoder::decode(bytes, options)
}

/// Reads a file's header and connectivity (CLERS histogram included),
/// without decoding geometry (except in a SwingWrapper file whose
/// symbols are in `CLRF`: they are read in a pass that places the
/// vertices).
pub fn inspect(bytes: &[u8], limits: &Limits) -> Result<FileInfo, Error> {
    crate::decoder::inspect(bytes, limits)
}
