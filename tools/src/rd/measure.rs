//! The timing and measuring every configuration shares: decode a file
//! (timed), measure the decoded mesh against the case's input, and fill
//! a table row's figures.

use crate::error::CliError;
use crate::rd::case::{encode, Case};
use crate::rd::table::Coded;
use std::borrow::Cow;
use std::time::Instant;
use swm::TriMesh;

/// Makes the chosen mesh again (timed with the encode), encodes it at
/// `qp`, decodes the file (timed) and measures the decoded mesh against
/// the reference. Searches run on cached results; the times here are those
/// of one clean pass.
pub fn finish<'a>(
    case: &'a Case,
    qp: u8,
    samples: u64,
    make: impl FnOnce() -> Result<Cow<'a, TriMesh>, CliError>,
) -> Result<Coded, CliError> {
    let start = Instant::now();
    let mesh = make()?;
    let bytes = encode(&mesh, qp).map_err(|e| case.err(e))?;
    let encode_s = start.elapsed().as_secs_f64();
    measure(case, qp, samples, &bytes, encode_s, &Default::default())
}

/// Decodes a file made in `encode_s` seconds (timed) and measures the
/// decoded mesh against the reference. `qp` is the row's quantization
/// figure; `options` says how to decode (post-processing included in the
/// decode time). The method is left empty for the caller to name.
pub fn measure(
    case: &Case,
    qp: u8,
    samples: u64,
    bytes: &[u8],
    encode_s: f64,
    options: &swm::DecodeOptions,
) -> Result<Coded, CliError> {
    let start = Instant::now();
    let decoded = swm::decode(bytes, options).map_err(|e| case.err(e))?;
    let decode_s = start.elapsed().as_secs_f64();
    let (l2_rel, hausdorff_rel) = case.distance(&decoded, samples)?;
    Ok(Coded {
        bytes: bytes.len() as u64,
        faces: decoded.triangles.len() as u64,
        qp,
        l2_rel,
        hausdorff_rel,
        encode_s,
        decode_s,
        method: String::new(),
    })
}
