//! Geometry coding for the lossless-connectivity mode: positions quantized
//! on a cubic grid, predicted from already decoded vertices, and the
//! prediction residuals entropy coded.
//!
//! Pipeline (each step one file):
//!
//! ```text
//!  f32 positions ──quantize──► grid points (bits per axis, cubic grid)
//!  corner table ──traverse──► coding order + a Prediction per vertex
//!  grid points, predictions ──lossless──► entropy-coded residuals
//! ```
//!
//! * [`quantize`](Quantizer): uniform quantization over the bounding box;
//!   decoded positions are within half a step of the originals.
//! * [`traverse`]: a max-prediction-degree order (Cohen-Or, Cohen & Irony
//!   2002), computed from connectivity alone, so encoder and decoder agree
//!   without sending it.
//! * [`Prediction`]: none, delta, the parallelogram rule of Touma &
//!   Gotsman (1998), or several parallelograms (Isenburg & Alliez 2002).
//! * [`lossless`]: wrap-around residuals (as in Draco), zig-zagged, coded
//!   as an adaptive bit length in a neighbourhood context plus mantissa;
//!   for several parallelograms the encoder also codes which subset to
//!   average (Draco's constrained multi-parallelogram idea).
//!
//! Independent of how connectivity is coded: the codec needs only a
//! corner table (or, at the lower level, a list of predictions whose
//! references precede the vertex), and treats both as untrusted when
//! decoding.
//!
//! Measured at the brief's settings, bits per vertex of the position
//! section alone (see `lossless` for the breakdown): Stanford bunny at 11
//! bits 7.8, horse at 12 bits 8.8.

pub mod lossless;
mod predict;
mod quantize;
mod traverse;

pub use predict::{average, Prediction, Predictions, MAX_SELECTABLE};
pub use quantize::{Quantizer, MAX_BITS, MIN_BITS};
pub use traverse::{
    traverse, traverse_except, traverse_visiting, Traversal, Visitor, MAX_PRIORITY,
};

#[cfg(test)]
mod tests;
