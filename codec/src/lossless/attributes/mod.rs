//! Vertex attributes in the lossless mode (format 1.2): the critical
//! section `ATTR`, one range-coded chunk per stream of an
//! [`AttributedMesh`](crate::AttributedMesh), coded after the positions
//! and predicted from them (format-spec/08-attributes.md).
//!
//! Modules, one step each, in layers (each uses only those listed after
//! it): `encode` (the encoder's quantization of the input streams),
//! `stream` (seams, shared values, the coding loop, encoder beside
//! decoder), `predict` (the rules: constrained multi-parallelograms,
//! Draco's portable texture-coordinate projection, the geometric normal),
//! `spec` (a stream's header), `frame` (the mesh the streams are coded
//! over), `octahedral` (normals on the octahedron), `residual` (the
//! residual coder).
//!
//! Payload of `ATTR`:
//!
//! ```text
//! varu n                                     streams, 1..=MAX_STREAMS
//! n × { u8 kind  varu set  u8 dims  u8 bits  u8 flags
//!       [f32 origin[dims]  f32 range]        (every kind but normals)
//!       varu length }                        bytes of the stream's chunk
//! n × chunk                                  exactly filling the payload
//! ```
//!
//! Invariants: the decoded streams have one triple per decoded triangle;
//! corners at one vertex share a value exactly when they shared one in
//! the input (values shared by corners of different vertices are
//! repeated, one per vertex); every value is finite.

#[cfg(feature = "encoder")]
mod encode;
mod frame;
mod octahedral;
pub(crate) mod over_mesh;
mod predict;
mod residual;
mod spec;
mod stream;
#[cfg(test)]
pub(crate) mod tests;

use crate::prelude::*;

#[cfg(feature = "encoder")]
pub(crate) use encode::encode;
pub(crate) use frame::Frame;
#[cfg(feature = "encoder")]
pub(crate) use frame::NONE;
pub(crate) use spec::inspect;
pub use spec::AttributeInfo;

use crate::{AttributeStream, Error, Limits};
use spec::bad;

/// Decodes `ATTR` over `frame`: the streams, with one triple per real
/// face of the table in order (the decoded mesh's triangles).
pub(crate) fn decode(
    bytes: &[u8],
    frame: &Frame<'_>,
    limits: &Limits,
) -> Result<Vec<AttributeStream>, Error> {
    let specs = spec::read_specs(bytes)?;
    let corners = frame.table.corner_count() as u64;
    // While a stream decodes: a group and a flag per corner, up to a
    // value (4 u64) per corner and its floats, about 64 bytes per
    // corner; what each decoded stream keeps (its triples and floats),
    // at most 24 more per corner.
    let streams = specs.len() as u64;
    limits.check_alloc(corners.saturating_mul(64 + 24 * streams))?;
    let mut out = Vec::with_capacity(specs.len());
    for (spec, chunk) in specs {
        let (group, values) = stream::decode(frame, &spec, chunk)?;
        let d = spec.coded_dims();
        let mut floats = Vec::with_capacity(values.len());
        for q in values.chunks_exact(d) {
            spec.dequantize(q, &mut floats);
        }
        let mut triples = Vec::with_capacity(frame.real.len());
        for t in frame.real_faces() {
            let g = [group[3 * t], group[3 * t + 1], group[3 * t + 2]];
            // Every vertex of a real face is decoded, so every corner
            // has its group; checked all the same.
            if g.contains(&frame::NONE) {
                return Err(bad("a corner has no attribute value"));
            }
            triples.push(g);
        }
        out.push(AttributeStream::new(spec.kind, spec.dims, floats, triples));
    }
    Ok(out)
}
