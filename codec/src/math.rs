//! Real functions that work without `std`.
//!
//! `core` has no `sqrt`, `sin`, `acos`... for `f32`/`f64`; the `libm`
//! crate does. Two rules keep decoded output the same in every build:
//! - `sqrt` and `floor` are exact in IEEE 754 (correctly rounded), so the
//!   hardware instruction (`std`) and `libm` give the same bits; `std`
//!   keeps the instruction for speed.
//! - Transcendental functions have no such guarantee: `libm` is used in
//!   every build, so a `no_std` viewer and the CLI bend and sharpen to the
//!   same bits. The plain decode uses none of them (format spec,
//!   00-conventions.md "Arithmetic"); only the post-processing, whose
//!   results format-spec/06-post.md defines with these functions (and
//!   whose golden hashes tests/golden.rs pins), and the encoder do.

/// The square root, correctly rounded.
#[inline]
pub(crate) fn sqrt(x: f64) -> f64 {
    #[cfg(feature = "std")]
    return x.sqrt();
    #[cfg(not(feature = "std"))]
    return libm::sqrt(x);
}

/// The largest integer not above `x` (exact).
#[inline]
pub(crate) fn floor(x: f64) -> f64 {
    #[cfg(feature = "std")]
    return x.floor();
    #[cfg(not(feature = "std"))]
    return libm::floor(x);
}

pub(crate) use libm::{atan2, cos, sin};
