//! Entropy coding: adaptive frequency models over constriction's range
//! coder.
//!
//! * [`AdaptiveModel`]: counts per symbol (start 1, +1 per symbol, halved
//!   past [`COUNT_LIMIT`]), coded from a quantized table rebuilt every
//!   16, 32, ..., 1024 updates (see [Models](#models) below).
//! * [`ContextModel`]: one adaptive model per context (e.g. the previous
//!   CLERS symbol).
//! * [`Encoder`] / [`Decoder`]: the range coder; decode order is encode
//!   order. Raw bits go through the same coder with a uniform model.
//!
//! # Models
//!
//! A model's state after `i` symbols depends only on those `i` symbols,
//! through [`AdaptiveModel`]'s single update function that both sides
//! call: the encoder after encoding a symbol, the decoder after decoding
//! it. Everything that shapes the bitstream ([`PRECISION`],
//! [`COUNT_LIMIT`], the rebuild schedule, the quantization rule) is a
//! constant here and part of the format.
//!
//! ```
//! use swm::entropy::{ContextModel, Decoder, Encoder};
//!
//! let symbols = [0u32, 1, 1, 0, 4, 3, 2, 1];
//! let mut enc = Encoder::new();
//! let mut model = ContextModel::new(5, 5);
//! let mut prev = 0;
//! for &s in &symbols {
//!     enc.encode(model.get(prev), s);
//!     prev = s as usize;
//! }
//! enc.encode_bits(0xABCDE, 20);
//! let bytes = enc.finish();
//!
//! let mut dec = Decoder::new(&bytes)?;
//! let mut model = ContextModel::new(5, 5);
//! let mut prev = 0;
//! for &s in &symbols {
//!     let got = dec.decode(model.get(prev))?;
//!     assert_eq!(got, s);
//!     prev = got as usize;
//! }
//! assert_eq!(dec.decode_bits(20)?, 0xABCDE);
//! dec.finish()?;
//! # Ok::<(), swm::Error>(())
//! ```

mod coder;
mod model;

pub use coder::{Decoder, Encoder, MAX_RAW_BITS};
pub use model::{
    AdaptiveModel, ContextModel, Table, COUNT_LIMIT, FIRST_REBUILD_INTERVAL, MAX_REBUILD_INTERVAL,
    MAX_SYMBOLS, MIN_SYMBOLS, PRECISION,
};

#[cfg(test)]
mod tests;
