//! Geometry coding (in progress).

pub mod lossless;
mod predict;
mod quantize;

pub use predict::{predict_multi, Prediction};
pub use quantize::{Quantizer, MAX_BITS, MIN_BITS};

#[cfg(test)]
mod tests;
