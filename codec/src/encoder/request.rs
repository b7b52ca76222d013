//! A request's numbers, checked: bytes from a size or a rate, a positive
//! edge length. Shared by every method so that a rate means the same
//! bytes to each of them.

use crate::options::SwingTarget;
use crate::{Error, ParameterError};

/// Bytes a rate of `bpv` bits per vertex gives `vertices` input vertices.
pub(crate) fn bytes_for(bpv: f64, vertices: usize) -> u64 {
    ((bpv * vertices as f64 / 8.0).round() as u64).max(1)
}

/// A positive finite option, or the error that names it.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::from(ParameterError::NotPositive { name, value }))
    }
}

/// The byte budget of a size or rate request for a method that has no
/// edge length: the size asked for (or the rate's), never above the cap.
/// An edge length or an error bound is refused (`mode` names the method
/// in the error).
pub(crate) fn budget(
    target: SwingTarget,
    vertices: usize,
    max_bytes: Option<u64>,
    mode: &'static str,
) -> Result<u64, Error> {
    let b = match target {
        SwingTarget::Bytes(b) => positive("size", b as f64)? as u64,
        SwingTarget::BitsPerVertex(bpv) => bytes_for(positive("bits per vertex", bpv)?, vertices),
        SwingTarget::EdgeLength(_) => {
            return Err(ParameterError::NotApplicable {
                name: "edge length",
                mode,
            }
            .into())
        }
        SwingTarget::MaxError(_) => {
            return Err(ParameterError::NotApplicable {
                name: "error bound",
                mode,
            }
            .into())
        }
    };
    Ok(max_bytes.map_or(b, |cap| b.min(cap)))
}
