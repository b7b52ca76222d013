//! # swm — lossy mesh compression by SwingWrapper remeshing
//!
//! The library behind the `swm` tool: a triangle-mesh model with a corner
//! table, mesh I/O and cleaning, the Edgebreaker connectivity codec, the
//! SwingWrapper retiler, the `.swm` container and the Sharpen&Bend
//! post-processing ([`sharpen`], [`bend`]) of M. Attene's thesis *Surface
//! Remeshing and Applications* (2004), chapters 7 and 8.
//!
//! Features: `std` (default), `io` (file readers and writers), `encoder`
//! (cleaning of arbitrary input and the encoders), `metrics`. Without
//! them (`--no-default-features`) the crate is `#![no_std]` + `alloc` and
//! holds the whole decoder: every mode, Sharpen&Bend, vertex normals.
//!
//! `unsafe` is denied everywhere; the single exception is the memory map
//! of input files in `io::source`, which `memmap2` can only offer through
//! an `unsafe` constructor.
#![cfg_attr(not(feature = "std"), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]

extern crate alloc;

/// What `std`'s prelude gives and `core`'s does not: imported by every
/// module of the decoder path, so it builds with and without `std`.
mod prelude {
    pub(crate) use alloc::{boxed::Box, vec, vec::Vec};
}

mod api;
mod buffers;
pub mod container;
mod decoder;
mod displaced;
pub mod edgebreaker;
#[cfg(feature = "encoder")]
mod encoder;
pub mod entropy;
mod error;
pub mod geometry;
mod limits;
mod lossless;
mod math;
pub mod mesh;
#[cfg(feature = "metrics")]
pub mod metrics;
mod options;
pub mod post;
#[cfg(feature = "encoder")]
pub mod simplify;
mod sort;
mod stream;
mod swing;
#[cfg(all(test, feature = "std"))]
pub(crate) mod test_alloc;
#[cfg(all(test, feature = "std"))]
pub(crate) mod test_skip;
mod varint;

#[cfg(feature = "io")]
pub mod io;

#[cfg(feature = "encoder")]
pub use api::HintReport;
pub use api::{
    decode, decode_attributed, inspect, DisplacedInfo, FileInfo, LosslessStats, Prediction,
    SwingStats,
};
#[cfg(feature = "encoder")]
pub use api::{
    encode, encode_attributed, Attempt, AttributeQuantization, AttributeReport, AttributesDropped,
    Candidate, CandidateFailure, Check, DisplacedStats, Effort, EncodeMode, EncodeOptions,
    EncodeStats, Encoded, ErrorBound, Measured, Method, MethodStats, Origin, PieceOutcome,
    PieceReport, RateReport, SimplifiedStats, SwingReport, SwingTarget, SwingTuning, TexcoordError,
    AUTO_SAMPLES, CHECK_SAMPLES, DEFAULT_ANGLE_BITS, FAST_CHECK_SAMPLES,
};
pub use buffers::{decode_into, decode_into_with, decoded_len, DecodedLen};
pub use container::{Framing, Mode};
pub use displaced::cut_levels;
pub use error::{
    AttributeError, Error, ErrorBoundError, FileKind, FormatError, InputError, LimitError, Limited,
    Location, Malformed, ParameterError, RetileError, RetileFailure, SizeError, TopologyError,
};
#[cfg(feature = "encoder")]
pub use limits::EncodeLimits;
pub use limits::Limits;
pub use lossless::attributes::AttributeInfo;
pub use mesh::{
    vertex_normals, vertex_normals_into, AttributeKind, AttributeStream, AttributedMesh, CornerId,
    CornerTable, FaceId, MeshStats, TriMesh, VertexId,
};
pub use options::DecodeOptions;
pub use post::bend::{bend, Bent};
pub use post::hint::PostProcessing;
pub use post::sharpen::{sharpen, SharpenOptions, SharpenReport, Sharpened, Unmoved};
pub use post::SharpEdges;
pub use stream::StreamDecoder;

#[cfg(feature = "encoder")]
pub use mesh::clean::{
    clean, clean_attributed, clean_with_origins, CleanOptions, CleanReport, Cleaned, FaceOrigin,
};

/// Result type of this crate.
pub type Result<T, E = Error> = core::result::Result<T, E>;
