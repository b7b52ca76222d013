//! Decoding into buffers the caller owns: what a viewer needs to fill a
//! vertex and an index buffer (or memory it mapped from a GPU) directly.
//!
//! Two steps, as in meshoptimizer's and Draco's buffer APIs: [`decoded_len`]
//! reads the container's header (no decoding) and returns how many
//! vertices and triangles the decode may produce; the caller sizes its
//! buffers; [`decode_into`] fills them and returns the counts it wrote.
//!
//! Invariants:
//! - the counts [`decode_into`] returns never exceed [`decoded_len`]'s for
//!   the same bytes and options, and are equal when [`DecodedLen::exact`]
//!   says so; a buffer shorter than the bound is refused before decoding
//!   (`ParameterError::BufferTooSmall`), so the outcome never depends on
//!   how big the actual mesh happens to be;
//! - on any error the buffers' contents are unspecified but nothing is
//!   written past the slices.
//!
//! The bound, per step (E ≤ 3T edges for T triangles, each edge having a
//! triangle on one side at least):
//!
//! ```text
//! step                     vertices              triangles
//! container                V (+ V_rest)           T (+ T_rest)     exact unless HOLE or LOOP
//! EdgeSharpener            + E + T ≤ + 4T         ≤ 6T             (one vertex per blue edge and
//!                                                                   green face; a green face → 6)
//! each Bender step         + E ≤ + 3T             4T
//! ```

use crate::container::{parse_container, Container};
use crate::decoder::{decode_container, for_mode};
use crate::{DecodeOptions, Error, ParameterError, TriMesh};

/// How big the output of [`decode_into`] may be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct DecodedLen {
    /// Vertices, at most: `positions` needs three `f32` each.
    pub vertices: u64,
    /// Triangles, at most: `indices` needs three `u32` each.
    pub triangles: u64,
    /// The counts are exactly those of the decoded mesh: a lossless file,
    /// or a SwingWrapper file without a hole mask or loops (whose fans
    /// the decoder drops), decoded without Sharpen&Bend (which decide
    /// their growth from the geometry).
    pub exact: bool,
}

impl DecodedLen {
    /// `f32`s a positions (or normals) buffer needs: `3 × vertices`.
    pub fn position_floats(&self) -> u64 {
        self.vertices.saturating_mul(3)
    }

    /// `u32`s an index buffer needs: `3 × triangles`.
    pub fn index_count(&self) -> u64 {
        self.triangles.saturating_mul(3)
    }
}

/// Bounds on the mesh [`decode_into`] would write for `bytes` and
/// `options`, from the container's header alone (its checksum, section
/// table and counts are checked, against `options.limits` too).
///
/// # Errors
/// Whatever [`decode`](crate::decode) reports for a damaged container or a count above
/// the limits.
pub fn decoded_len(bytes: &[u8], options: &DecodeOptions) -> Result<DecodedLen, Error> {
    bounds(&parse_container(bytes, &options.limits)?, options)
}

/// [`decoded_len`] of a parsed container.
fn bounds(file: &Container<'_>, options: &DecodeOptions) -> Result<DecodedLen, Error> {
    let h = file.header;
    let (mut v, mut t) = (u64::from(h.vertex_count), u64::from(h.triangle_count));
    let mut exact = true;
    let (rv, rt, exact_counts) = (for_mode(h.mode).extra_counts)(file, &options.limits)?;
    v += rv;
    t += rt;
    exact &= exact_counts;
    // The header counts every level; `max_level` may stop before the
    // last (then a bound, not the count).
    if h.mode == crate::container::Mode::Displaced && options.max_level.is_some() {
        exact = false;
    }
    let post = crate::post::hint::resolve(file, options.sharpen, options.bend_steps);
    if post.sharpen {
        v = v.saturating_add(t.saturating_mul(4));
        t = t.saturating_mul(6);
        exact = false;
    }
    for _ in 0..post.bend_steps {
        if t == u64::MAX {
            break;
        }
        v = v.saturating_add(t.saturating_mul(3));
        t = t.saturating_mul(4);
        exact = false;
    }
    Ok(DecodedLen {
        vertices: v,
        triangles: t,
        exact,
    })
}

/// Decodes `bytes` into `positions` (`x y z` per vertex) and `indices`
/// (three per counter-clockwise triangle), with default options.
/// Returns the counts written; see [`decode_into_with`].
pub fn decode_into(
    bytes: &[u8],
    positions: &mut [f32],
    indices: &mut [u32],
) -> Result<DecodedLen, Error> {
    decode_into_with(bytes, &DecodeOptions::default(), positions, indices)
}

/// Decodes `bytes` with `options` into caller-provided buffers, which
/// must hold at least what [`decoded_len`] returns
/// ([`DecodedLen::position_floats`], [`DecodedLen::index_count`]).
/// Returns the counts written, with `exact: true`; the rest of the
/// buffers is left as it was.
///
/// # Errors
/// [`ParameterError::BufferTooSmall`] (before decoding) and everything
/// [`decode`](crate::decode) reports.
pub fn decode_into_with(
    bytes: &[u8],
    options: &DecodeOptions,
    positions: &mut [f32],
    indices: &mut [u32],
) -> Result<DecodedLen, Error> {
    // One parse (and CRC pass) serves the bound and the decode.
    let file = parse_container(bytes, &options.limits)?;
    let bound = bounds(&file, options)?;
    fits("positions", bound.position_floats(), positions.len())?;
    fits("indices", bound.index_count(), indices.len())?;
    let post = crate::post::hint::resolve(&file, options.sharpen, options.bend_steps);
    if file.header.mode == crate::container::Mode::Displaced && post.is_plain() {
        // The finest level straight into the buffers, not copied from a
        // mesh of its own (the largest one of the decode).
        let levels = options.max_level.map_or(usize::MAX, usize::from);
        let placed = crate::displaced::decode_levels_into(
            &file,
            &options.limits,
            levels,
            positions,
            indices,
        )?;
        return Ok(match placed {
            crate::displaced::Placed::Written(vertices, triangles) => DecodedLen {
                vertices: vertices as u64,
                triangles: triangles as u64,
                exact: true,
            },
            crate::displaced::Placed::Base(mesh) => copy_out(&mesh, positions, indices),
        });
    }
    let mesh = decode_container(&file, options)?;
    Ok(copy_out(&mesh, positions, indices))
}

fn fits(buffer: &'static str, needed: u64, given: usize) -> Result<(), Error> {
    if (given as u64) < needed {
        return Err(Error::Parameter(ParameterError::BufferTooSmall {
            buffer,
            needed,
            given: given as u64,
        }));
    }
    Ok(())
}

/// Copies the decoded mesh out; the bound checked above guarantees room.
fn copy_out(mesh: &TriMesh, positions: &mut [f32], indices: &mut [u32]) -> DecodedLen {
    let p = mesh.positions.as_flattened();
    let i = mesh.triangles.as_flattened();
    positions[..p.len()].copy_from_slice(p);
    indices[..i.len()].copy_from_slice(i);
    DecodedLen {
        vertices: mesh.positions.len() as u64,
        triangles: mesh.triangles.len() as u64,
        exact: true,
    }
}
