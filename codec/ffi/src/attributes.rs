//! Attribute streams over the C ABI: [`swm_decode_attributed`] and
//! [`swm_attributed_mesh_free`].
//!
//! The arrays are in the split (GPU) form of
//! `swm::AttributedMesh::split_vertices`: one vertex per distinct
//! position and values, so each stream has `dims` floats per vertex of
//! the mesh and the mesh's indices serve every stream, as a vertex
//! buffer wants. A viewer binds `positions`, `normals`, `uv`, `colors`
//! alike. (The per-corner form of the Rust API would need one index
//! buffer per stream, which no GPU draws from.)

use std::ffi::c_int;
use std::ptr;

use crate::{
    decode_options, fail, guard, inputs, leak, succeed, swm_decode_options, swm_mesh, unleak,
    EMPTY, SWM_ERROR_ARGUMENT,
};

/// `swm_attribute.kind`: shading normals, 3 floats per vertex.
pub const SWM_ATTRIBUTE_NORMAL: u32 = 1;
/// `swm_attribute.kind`: texture coordinate set `set`, 2 (or 3) floats.
pub const SWM_ATTRIBUTE_TEXCOORD: u32 = 2;
/// `swm_attribute.kind`: vertex colour set `set`, RGB or RGBA in 0..1.
pub const SWM_ATTRIBUTE_COLOR: u32 = 3;
/// `swm_attribute.kind`: application-defined stream number `set`, 1 to 4
/// floats.
pub const SWM_ATTRIBUTE_GENERIC: u32 = 4;

/// One attribute stream of a [`swm_attributed_mesh`], per vertex.
#[repr(C)]
#[derive(Debug)]
pub struct swm_attribute {
    /// What the values are: one of the `SWM_ATTRIBUTE_*` constants; a
    /// newer library may add kinds, which a viewer should skip.
    pub kind: u32,
    /// The set number (glTF `TEXCOORD_n`, `COLOR_n`; the generic stream's
    /// number); 0 for normals.
    pub set: u32,
    /// Floats per vertex, 1 to 4.
    pub dims: u32,
    /// `dims * vertex_count` floats, vertex by vertex.
    pub values: *mut f32,
}

/// A decoded mesh with its attribute streams; everything belongs to the
/// library until [`swm_attributed_mesh_free`].
#[repr(C)]
#[derive(Debug)]
pub struct swm_attributed_mesh {
    /// Positions, indices and (with `swm_decode_options.normals`)
    /// computed normals, as `swm_decode_with` gives them, but in the split
    /// form: a position on a seam comes once per side.
    pub mesh: swm_mesh,
    /// `attribute_count` streams in the file's order; NULL when there are
    /// none (a file without attributes decodes as `swm_decode_with`).
    pub attributes: *mut swm_attribute,
    /// Number of streams.
    pub attribute_count: usize,
}

const EMPTY_ATTRIBUTED: swm_attributed_mesh = swm_attributed_mesh {
    mesh: EMPTY,
    attributes: ptr::null_mut(),
    attribute_count: 0,
};

/// The C kind and set of a stream kind; `None` for a kind this ABI has
/// no constant for yet (`AttributeKind` is non-exhaustive): such a stream
/// is left out rather than given a number a later version may reuse.
fn kind_of(kind: swm::AttributeKind) -> Option<(u32, u32)> {
    Some(match kind {
        swm::AttributeKind::Normal => (SWM_ATTRIBUTE_NORMAL, 0),
        swm::AttributeKind::TexCoord(n) => (SWM_ATTRIBUTE_TEXCOORD, n.into()),
        swm::AttributeKind::Color(n) => (SWM_ATTRIBUTE_COLOR, n.into()),
        swm::AttributeKind::Generic(n) => (SWM_ATTRIBUTE_GENERIC, n.into()),
        _ => return None,
    })
}

/// Decodes with `*opts` (NULL: the defaults) into `*out`, attribute
/// streams included (those of the file's `ATTR` section, in a lossless,
/// SwingWrapper or displaced file; none otherwise, nor for a displaced
/// file decoded to a coarser level). A file with streams is not post-processed (Sharpen&Bend
/// would change the triangles the values belong to). Returns `SWM_OK`
/// or an error code (message: `swm_last_error`); on failure `*out` is
/// zeroed, so freeing it is always safe.
///
/// # Safety
/// `data` points to `len` readable bytes (anything when `len` is 0);
/// `opts` is NULL or valid; `out` points to a writable
/// `swm_attributed_mesh`.
#[no_mangle]
pub unsafe extern "C" fn swm_decode_attributed(
    data: *const u8,
    len: usize,
    opts: *const swm_decode_options,
    out: *mut swm_attributed_mesh,
) -> c_int {
    if out.is_null() {
        return fail(SWM_ERROR_ARGUMENT, "swm_decode_attributed: out is NULL");
    }
    // SAFETY: `out` is non-NULL and the caller promises it is writable.
    unsafe { out.write(EMPTY_ATTRIBUTED) };
    // SAFETY: the caller's promises about `data`, `len` and `opts`.
    let (bytes, opts) = match unsafe { inputs(data, len, opts) } {
        Ok(x) => x,
        Err(code) => return code,
    };
    let result = guard(|| {
        let decoded = swm::decode_attributed(bytes, &decode_options(&opts))?;
        // Without streams the split is the identity: skip its sort.
        let decoded = match decoded.streams.is_empty() {
            true => decoded,
            false => decoded.split_vertices(),
        };
        let normals = opts.normals.then(|| swm::vertex_normals(&decoded.mesh));
        Ok((decoded, normals))
    });
    let (decoded, normals) = match result {
        Ok(x) => x,
        Err(code) => return code,
    };
    let streams: Vec<swm_attribute> = decoded
        .streams
        .into_iter()
        .filter_map(|s| {
            let (kind, set) = kind_of(s.kind)?;
            Some(swm_attribute {
                kind,
                set,
                dims: s.dims.into(),
                values: leak(s.values),
            })
        })
        .collect();
    let m = swm_attributed_mesh {
        mesh: swm_mesh {
            vertex_count: decoded.mesh.positions.len(),
            triangle_count: decoded.mesh.triangles.len(),
            positions: leak(decoded.mesh.positions).cast(),
            indices: leak(decoded.mesh.triangles).cast(),
            normals: normals.map_or(ptr::null_mut(), |n| leak(n).cast()),
        },
        attribute_count: streams.len(),
        attributes: leak(streams),
    };
    // SAFETY: as above.
    unsafe { out.write(m) };
    succeed()
}

/// Releases everything a [`swm_decode_attributed`] handed over and zeroes
/// `*m`. NULL, a zeroed mesh and a mesh already freed are accepted.
///
/// # Safety
/// `m` is NULL or points to a `swm_attributed_mesh` that is zeroed or was
/// filled by this library and not modified since.
#[no_mangle]
pub unsafe extern "C" fn swm_attributed_mesh_free(m: *mut swm_attributed_mesh) {
    if m.is_null() {
        return;
    }
    // SAFETY: the caller promises `m` is valid and unmodified.
    let mut whole = unsafe { m.replace(EMPTY_ATTRIBUTED) };
    let vertices = whole.mesh.vertex_count;
    if !whole.attributes.is_null() {
        // SAFETY: `attributes` came from `leak` of exactly
        // `attribute_count` streams, each `values` from `leak` of
        // `dims * vertex_count` floats.
        unsafe {
            let streams = std::slice::from_raw_parts(whole.attributes, whole.attribute_count);
            for s in streams {
                unleak(s.values, s.dims as usize * vertices);
            }
            unleak(whole.attributes, whole.attribute_count);
        }
    }
    // SAFETY: the mesh part was filled as `swm_decode_with` fills one.
    unsafe { crate::swm_mesh_free(&mut whole.mesh) };
}
