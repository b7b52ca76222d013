//! The public entry points: [`encode`], [`decode`] and [`inspect`]. This
//! module is the facade only: the options are in `options`, the encoder
//! (its methods, chooser and effort levels) in `encoder`, the decode
//! table in `decoder` (ARCHITECTURE.md draws the layers).

use crate::options::DecodeOptions;
use crate::{Error, Limits, TriMesh};

pub use crate::decoder::FileInfo;
pub use crate::lossless::LosslessStats;
pub use crate::swing::SwingStats;

#[cfg(feature = "encoder")]
pub use crate::encoder::stats::CHECK_SAMPLES;
#[cfg(feature = "encoder")]
pub use crate::encoder::stats::{
    Attempt, Candidate, CandidateFailure, Check, DisplacedStats, EncodeStats, Encoded, HintReport,
    Measured, Method, MethodStats, Origin, PieceOutcome, PieceReport, RateReport, SimplifiedStats,
    SwingReport,
};
#[cfg(feature = "encoder")]
pub use crate::options::{
    Effort, EncodeMode, EncodeOptions, ErrorBound, SwingTarget, SwingTuning, AUTO_SAMPLES,
    DEFAULT_ANGLE_BITS,
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
