//! Reading accessors (glTF 2.0 §3.6.2): the positions and indices of a
//! mesh primitive, from the bytes of their buffer views.
//!
//! ```text
//! buffer      |......[ bufferView ...................... ]......|
//! view                 offset |elem|...stride...|elem|...|elem|
//!                              0                1         count-1
//! ```
//!
//! Element `i` starts at `view.offset + accessor.offset + i * stride`,
//! where `stride` is the view's `byteStride` or, without one, the element
//! size. An accessor without a bufferView is all zeros. A sparse accessor
//! then replaces the elements its (strictly increasing, but we do not need
//! it) indices name by the values that follow them, both tightly packed.
//!
//! Invariants: every offset and length is computed with checked
//! arithmetic and checked against the view, and every view against its
//! buffer, before a byte is read; the element count is checked against
//! the [`Limits`] before anything is allocated. So a hostile accessor
//! gives an error, never a panic or a huge allocation. This is why the
//! `gltf` crate's own reader (feature `utils`) is not used: it subtracts
//! before it checks and trusts the component type.

use super::buffers::Buffers;
use crate::{Error, FormatError, Limits, Malformed};
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::Accessor;

/// What reading an accessor needs besides the accessor.
pub(super) struct Context<'b, 'a> {
    pub buffers: &'b Buffers<'a>,
    pub limits: &'b Limits,
    pub format: &'static str,
}

impl Context<'_, '_> {
    fn bad(&self, what: Malformed) -> Error {
        FormatError::new(self.format, what).into()
    }
}

/// Marks, in `needed`, the buffers that reading `a` touches.
pub(super) fn mark_buffers(a: &Accessor, needed: &mut [bool]) {
    let mut mark = |view: ::gltf::buffer::View| {
        if let Some(n) = needed.get_mut(view.buffer().index()) {
            *n = true;
        }
    };
    if let Some(view) = a.view() {
        mark(view);
    }
    if let Some(sparse) = a.sparse() {
        mark(sparse.indices().view());
        mark(sparse.values().view());
    }
}

/// The positions of a POSITION accessor, which §3.7.2.1 requires to be
/// float VEC3 (quantized positions need KHR_mesh_quantization, which
/// files must list as required, and which is refused before this).
pub(super) fn positions(a: &Accessor, cx: &Context) -> Result<Vec<[f32; 3]>, Error> {
    if a.dimensions() != Dimensions::Vec3 || a.data_type() != DataType::F32 || a.normalized() {
        return Err(cx.bad(Malformed::Unsupported(
            "POSITION accessors that are not float VEC3",
        )));
    }
    cx.limits.check_vertices(a.count() as u64)?;
    read(a, cx, 12, [0.0; 3], |b| {
        let f = |k: usize| f32::from_le_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
        [f(0), f(4), f(8)]
    })
}

/// The values of a NORMAL, TEXCOORD_n or COLOR_n accessor, `dims`
/// floats each (the accessor's type must have `dims` components, one of
/// `allowed`): float components as they are, normalized integer ones
/// decoded as §3.11 says (`c / 255`, `c / 65535`, `max(c / 127, -1)`,
/// `max(c / 32767, -1)`). Integers that are not normalized need
/// KHR_mesh_quantization, which is refused before this.
pub(super) fn floats(
    a: &Accessor,
    cx: &Context,
    allowed: &[usize],
) -> Result<(usize, Vec<f32>), Error> {
    let dims = match a.dimensions() {
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        _ => 0,
    };
    if !allowed.contains(&dims) {
        return Err(cx.bad(Malformed::Unsupported(
            "an attribute accessor of an unexpected type",
        )));
    }
    let ty = a.data_type();
    if ty == DataType::U32 {
        return Err(cx.bad(Malformed::BadSyntax(
            "an attribute of unsigned int components",
        )));
    }
    if ty != DataType::F32 && !a.normalized() {
        return Err(cx.bad(Malformed::Unsupported(
            "integer attributes that are not normalized (KHR_mesh_quantization)",
        )));
    }
    cx.limits.check_vertices(a.count() as u64)?;
    let width = ty.size();
    let component = move |b: &[u8]| -> f32 {
        match ty {
            DataType::U8 => f32::from(b[0]) / 255.0,
            DataType::I8 => (f32::from(b[0] as i8) / 127.0).max(-1.0),
            DataType::U16 => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
            DataType::I16 => (f32::from(i16::from_le_bytes([b[0], b[1]])) / 32767.0).max(-1.0),
            DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            // 32-bit integers are not attribute component types (§3.6.2.2).
            DataType::U32 => f32::NAN,
        }
    };
    let elements = read(a, cx, dims * width, [0.0f32; 4], |b| {
        let mut v = [0.0; 4];
        for (k, c) in v.iter_mut().take(dims).enumerate() {
            *c = component(&b[k * width..]);
        }
        v
    })?;
    let mut out = Vec::new();
    out.try_reserve_exact(elements.len() * dims)
        .map_err(|_| Error::Io(std::io::ErrorKind::OutOfMemory.into()))?;
    out.extend(elements.iter().flat_map(|v| v[..dims].iter().copied()));
    Ok((dims, out))
}

/// The vertex indices of a primitive: unsigned scalars (§3.7.2.1).
pub(super) fn indices(a: &Accessor, cx: &Context) -> Result<Vec<u32>, Error> {
    if a.dimensions() != Dimensions::Scalar {
        return Err(cx.bad(Malformed::BadSyntax("indices that are not scalars")));
    }
    // A strip or fan of n indices has n - 2 triangles, a list n / 3.
    cx.limits
        .check_faces((a.count() as u64).saturating_sub(2))?;
    match a.data_type() {
        DataType::U8 => read(a, cx, 1, 0, |b| u32::from(b[0])),
        DataType::U16 => read(a, cx, 2, 0, |b| u32::from(u16::from_le_bytes([b[0], b[1]]))),
        DataType::U32 => read(a, cx, 4, 0, |b| {
            u32::from_le_bytes([b[0], b[1], b[2], b[3]])
        }),
        _ => Err(cx.bad(Malformed::BadSyntax(
            "indices that are not unsigned integers",
        ))),
    }
}

/// The `count` elements of `a`, each `size` bytes decoded by `decode`.
fn read<T: Copy>(
    a: &Accessor,
    cx: &Context,
    size: usize,
    zero: T,
    decode: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, Error> {
    let count = a.count();
    let bytes = (count as u64).saturating_mul(core::mem::size_of::<T>() as u64);
    cx.limits.check_alloc(bytes)?;
    let mut out = Vec::new();
    out.try_reserve_exact(count)
        .map_err(|_| Error::Io(std::io::ErrorKind::OutOfMemory.into()))?;
    match a.view() {
        Some(view) => {
            let stride = view.stride().unwrap_or(size);
            if stride < size {
                return Err(cx.bad(Malformed::BadSyntax(
                    "a bufferView's byteStride is smaller than its elements",
                )));
            }
            let data = elements(cx, view, a.offset(), stride, size, count)?;
            out.extend((0..count).map(|i| decode(&data[i * stride..])));
        }
        None => out.resize(count, zero),
    }
    if let Some(sparse) = a.sparse() {
        let n = sparse.count();
        let indices = sparse.indices();
        let width = indices.index_type().size();
        let at = elements(cx, indices.view(), indices.offset(), width, width, n)?;
        let values = sparse.values();
        let new = elements(cx, values.view(), values.offset(), size, size, n)?;
        for k in 0..n {
            let b = &at[k * width..];
            let i = match width {
                1 => usize::from(b[0]),
                2 => usize::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
            };
            let slot = out.get_mut(i).ok_or_else(|| {
                cx.bad(Malformed::BadSyntax(
                    "a sparse accessor's index is past its count",
                ))
            })?;
            *slot = decode(&new[k * size..]);
        }
    }
    Ok(out)
}

/// The bytes of `count` elements of `size` bytes, `stride` apart, from
/// `offset` into `view`: a slice that starts at the first element and
/// ends with the last one, so that element `i` is at `i * stride`.
fn elements<'d>(
    cx: &Context<'d, '_>,
    view: ::gltf::buffer::View,
    offset: usize,
    stride: usize,
    size: usize,
    count: usize,
) -> Result<&'d [u8], Error> {
    let buffer = cx.buffers.get(view.buffer().index());
    let view_bytes = view
        .offset()
        .checked_add(view.length())
        .and_then(|end| {
            buffer
                .get(view.offset()..end)
                .filter(|_| end <= view.buffer().length())
        })
        .ok_or_else(|| cx.bad(Malformed::BadSyntax("a bufferView runs past its buffer")))?;
    if count == 0 {
        return Ok(&[]);
    }
    (count - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(size))
        .and_then(|n| n.checked_add(offset))
        .and_then(|end| view_bytes.get(offset..end))
        .ok_or_else(|| cx.bad(Malformed::BadSyntax("an accessor runs past its bufferView")))
}
