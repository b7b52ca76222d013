//! What `swm info` shows of a mode-2 file's `HEAD` and `BASE`
//! (`crate::inspect`'s [`DisplacedInfo`]), read without decoding a level.

use crate::prelude::*;

pub use super::predict::Rule as Prediction;

/// What a displaced-subdivision (mode 2) file's `HEAD` and `BASE` say
/// (format-spec/07-displaced.md): read without decoding a level.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct DisplacedInfo {
    /// The prediction rule.
    pub rule: Prediction,
    /// Each level's quantization step, coarse to fine, in the mesh's
    /// units (the levels the encoder made: a cut file keeps them all).
    pub steps: Vec<f32>,
    /// Each level's bend `β` (0 where the level has none).
    pub bends: Vec<f32>,
    /// `BASE` holds a bare mode-0 body, not a whole mode-0 file.
    pub bare_base: bool,
    /// Bytes of `BASE`.
    pub base_bytes: usize,
}
