//! The swm decoder as a WebAssembly module (issue 24), for the hand-kept
//! JavaScript glue in `web/src/swm.js`. Built for `wasm32-unknown-unknown`
//! by `web/scripts/build.mjs` (the workspace's `wasm` profile, then
//! binaryen's `wasm-opt`).
//!
//! Why not the C ABI crate (`codec/ffi`): its options struct carries `u64`
//! fields that JavaScript can only write as `BigInt`s through a
//! `DataView`, its error message sits in a thread-local behind a second
//! call, and it has no allocator a host can call. Here the options are
//! plain arguments (limits as `f64`, JavaScript's number) and one flat
//! struct of 32-bit fields carries the mesh, the error and the file's
//! mode and version.
//!
//! `std` is linked (constriction enables its own `std` on every hosted
//! target, wasm32 included); the `wasm` profile's `panic = "abort"` makes
//! a panic a trap.
//!
//! The contract with the glue:
//! - The host copies a file into memory from [`swm_alloc`], calls
//!   [`swm_decode`], reads the returned [`Output`] (32-bit fields on
//!   wasm32, in declaration order), copies the arrays out and releases
//!   everything with [`swm_output_free`] and [`swm_free`].
//! - A file arriving in pieces: [`swm_stream_new`], then
//!   [`swm_stream_push`] per piece (each `Output` is an error, a newly
//!   completed level of a displaced file, or empty), [`swm_stream_finish`]
//!   for the whole mesh, and [`swm_stream_free`].
//! - A decoding error is an `Output` with a non-zero `status` and a UTF-8
//!   message; only a bug traps (`unreachable`), after which the glue
//!   discards the instance, since its heap may be mid-update.
//! - Every byte of the input is hostile: the library guarantees errors,
//!   never panics, and nothing allocated beyond the limits passed in.

#![deny(unsafe_op_in_unsafe_fn)]

extern crate alloc;

use alloc::alloc::Layout;
use alloc::boxed::Box;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::ptr;

use swm::{DecodeOptions, Error, Limits, StreamDecoder, TriMesh};

/// Success.
pub const STATUS_OK: u32 = 0;
/// An option out of range (a negative or non-numeric limit).
pub const STATUS_ARGUMENT: u32 = 1;
/// The bytes are not a valid `.swm` file.
pub const STATUS_FORMAT: u32 = 2;
/// The file needs more than the limits allow.
pub const STATUS_LIMIT: u32 = 3;
/// A newer format version or an unknown mode.
pub const STATUS_UNSUPPORTED: u32 = 4;
/// An error of no other kind.
pub const STATUS_INTERNAL: u32 = 6;

/// Alignment of [`swm_alloc`]'s blocks: enough for every element type
/// the glue places in them.
const ALIGN: usize = 8;

/// What [`swm_decode`] hands to the host. The pointers stay valid until
/// [`swm_output_free`].
#[repr(C)]
#[derive(Debug)]
pub struct Output {
    /// `STATUS_OK` or one of the `STATUS_*` errors.
    pub status: u32,
    /// UTF-8 error message (empty on success).
    pub message: *const u8,
    /// Its length in bytes.
    pub message_len: usize,
    /// `3 * vertex_count` floats.
    pub positions: *const f32,
    /// Vertices of the decoded mesh.
    pub vertex_count: usize,
    /// `3 * triangle_count` vertex indices, counter-clockwise from outside.
    pub indices: *const u32,
    /// Triangles of the decoded mesh.
    pub triangle_count: usize,
    /// `3 * vertex_count` floats of unit vertex normals when asked for,
    /// NULL otherwise.
    pub normals: *const f32,
    /// The file's mode: its code in the file (`swm::Mode::code`: 0
    /// lossless, 1 SwingWrapper).
    pub mode: u32,
    /// Format version of the file, major.
    pub major: u32,
    /// Format version of the file, minor.
    pub minor: u32,
    /// The subdivision level of a displaced file's mesh handed out by
    /// [`swm_stream_push`]; -1 for a whole file's decode.
    pub level: i32,
    /// `attribute_count` stream descriptors (a lossless file's `ATTR`;
    /// NULL when there are none). With streams the mesh is split at
    /// seams (`AttributedMesh::split_vertices`), so each stream has a
    /// value per vertex, as a vertex buffer wants.
    pub attributes: *const Attribute,
    /// Number of streams.
    pub attribute_count: usize,
}

/// One attribute stream of an [`Output`]: 32-bit fields, in this order.
#[repr(C)]
#[derive(Debug)]
pub struct Attribute {
    /// 1 normals, 2 texture coordinates, 3 colours, 4 generic (the C
    /// ABI's `SWM_ATTRIBUTE_*`); 0 a kind this module does not name.
    pub kind: u32,
    /// The set (`TEXCOORD_n`, `COLOR_n`) or the generic stream's number.
    pub set: u32,
    /// Floats per vertex, 1 to 4.
    pub dims: u32,
    /// `dims * vertex_count` floats.
    pub values: *const f32,
}

/// The `Output` and what its pointers point into. `repr(C)` with `out`
/// first, so a pointer to it is a pointer to its `Output`.
#[repr(C)]
struct Owned {
    out: Output,
    _mesh: TriMesh,
    _normals: Vec<[f32; 3]>,
    _streams: Vec<swm::AttributeStream>,
    _attributes: Vec<Attribute>,
    _message: String,
}

/// A block of `len` bytes (8-aligned) for the host to fill, or NULL when
/// memory is exhausted. `len` 0 gives a valid, empty block.
#[no_mangle]
pub extern "C" fn swm_alloc(len: usize) -> *mut u8 {
    match Layout::from_size_align(len.max(1), ALIGN) {
        // SAFETY: the layout's size is non-zero.
        Ok(layout) => unsafe { alloc::alloc::alloc(layout) },
        Err(_) => ptr::null_mut(),
    }
}

/// Releases a block from [`swm_alloc`]; NULL is ignored.
///
/// # Safety
/// `p` is NULL or came from `swm_alloc(len)` and was not freed since.
#[no_mangle]
pub unsafe extern "C" fn swm_free(p: *mut u8, len: usize) {
    if p.is_null() {
        return;
    }
    if let Ok(layout) = Layout::from_size_align(len.max(1), ALIGN) {
        // SAFETY: the caller promises `p` came from `swm_alloc` with this
        // length, hence this layout.
        unsafe { alloc::alloc::dealloc(p, layout) }
    }
}

/// Decodes `len` bytes at `data`. `sharpen`: negative follows the file's
/// post-processing hint, 0 off, positive on; `bend_steps`: negative
/// follows the hint, otherwise the steps (`swm::DecodeOptions`, whose
/// `None` is the negative value here); `normals` is a boolean (non-zero:
/// on); `max_level`: the most subdivision levels of a displaced (mode 2)
/// file to decode, 0 its base mesh, negative (or above 255) every level
/// (`DecodeOptions::max_level`'s `None`). The limits are
/// `swm::Limits` as numbers, the host's native type (a JavaScript number
/// holds every integer up to 2^53; larger values saturate). Never NULL:
/// memory exhausted inside the decoder aborts, which traps on wasm32 and
/// makes the glue replace the instance.
///
/// # Safety
/// `data` points to `len` readable bytes, or `len` is 0.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn swm_decode(
    data: *const u8,
    len: usize,
    sharpen: i32,
    bend_steps: i32,
    normals: u32,
    max_vertices: f64,
    max_faces: f64,
    max_alloc_bytes: f64,
    max_level: i32,
) -> *mut Output {
    let bytes = if len == 0 || data.is_null() {
        &[][..]
    } else {
        // SAFETY: the caller promises `len` readable bytes at `data`.
        unsafe { core::slice::from_raw_parts(data, len) }
    };
    let limits = [max_vertices, max_faces, max_alloc_bytes];
    let owned = match options(sharpen, bend_steps, limits, max_level) {
        Some(options) => decode(bytes, &options, normals != 0),
        None => failure(
            STATUS_ARGUMENT,
            "a limit is not a non-negative number".to_string(),
        ),
    };
    Box::into_raw(Box::new(owned)).cast()
}

/// Releases an [`Output`] and its arrays; NULL is ignored.
///
/// # Safety
/// `out` is NULL or came from [`swm_decode`] and was not freed since.
#[no_mangle]
pub unsafe extern "C" fn swm_output_free(out: *mut Output) {
    if !out.is_null() {
        // SAFETY: `out` is the first field of an `Owned` that
        // `swm_decode` boxed.
        drop(unsafe { Box::from_raw(out.cast::<Owned>()) });
    }
}

/// A file decoded as its bytes arrive ([`swm_stream_new`]): the library's
/// `StreamDecoder`, which hands out each level of a displaced file once
/// its chunk is in, and the last level handed to the host.
pub struct Stream {
    /// `None` once a push failed: the stream is dead.
    decoder: Option<StreamDecoder>,
    normals: bool,
    shown: Option<usize>,
}

/// A stream decoder with [`swm_decode`]'s options; NULL when a limit is
/// not a non-negative number. Released by [`swm_stream_free`].
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn swm_stream_new(
    sharpen: i32,
    bend_steps: i32,
    normals: u32,
    max_vertices: f64,
    max_faces: f64,
    max_alloc_bytes: f64,
    max_level: i32,
) -> *mut Stream {
    let limits = [max_vertices, max_faces, max_alloc_bytes];
    let Some(options) = options(sharpen, bend_steps, limits, max_level) else {
        return ptr::null_mut();
    };
    Box::into_raw(Box::new(Stream {
        decoder: Some(StreamDecoder::new(options)),
        normals: normals != 0,
        shown: None,
    }))
}

/// Adds `len` bytes at `data` to the stream. The [`Output`] is an error
/// (and the stream dead), or the finest level of a displaced file that
/// the bytes so far complete when it is finer than the last one handed
/// out (its `level` field says which), or else an empty mesh with
/// `level` -1: nothing new yet. Never NULL.
///
/// # Safety
/// `stream` came from [`swm_stream_new`] and was not freed since; `data`
/// points to `len` readable bytes, or `len` is 0.
#[no_mangle]
pub unsafe extern "C" fn swm_stream_push(
    stream: *mut Stream,
    data: *const u8,
    len: usize,
) -> *mut Output {
    // SAFETY: the caller promises a live stream.
    let s = unsafe { &mut *stream };
    let bytes = if len == 0 || data.is_null() {
        &[][..]
    } else {
        // SAFETY: the caller promises `len` readable bytes at `data`.
        unsafe { core::slice::from_raw_parts(data, len) }
    };
    let owned = match s.decoder.take().map(|d| d.push(bytes)) {
        None => failure(STATUS_ARGUMENT, "the stream failed before".to_string()),
        Some(Err(e)) => failure(status_of(&e), message(&e)),
        Some(Ok(d)) => {
            let fresh = match (d.level(), d.header()) {
                (Some((level, mesh)), Some(header)) if s.shown.is_none_or(|l| level > l) => {
                    s.shown = Some(level);
                    let level = i32::try_from(level).unwrap_or(i32::MAX);
                    Some(owned(mesh.clone(), &header, s.normals, level))
                }
                _ => None,
            };
            s.decoder = Some(d);
            fresh.unwrap_or_else(nothing)
        }
    };
    Box::into_raw(Box::new(owned)).cast()
}

/// The whole file's mesh once every byte is in (what [`swm_decode`]
/// gives for them), or the error of a file that is cut short or damaged.
/// The stream stays to be freed. Never NULL.
///
/// # Safety
/// `stream` came from [`swm_stream_new`] and was not freed since.
#[no_mangle]
pub unsafe extern "C" fn swm_stream_finish(stream: *mut Stream) -> *mut Output {
    // SAFETY: the caller promises a live stream.
    let s = unsafe { &mut *stream };
    let owned = match s.decoder.take() {
        None => failure(STATUS_ARGUMENT, "the stream failed before".to_string()),
        Some(d) => {
            let header = d.header();
            match (d.finish(), header) {
                (Ok(mesh), Some(header)) => owned(mesh, &header, s.normals, -1),
                (Err(e), _) => failure(status_of(&e), message(&e)),
                (Ok(_), None) => failure(STATUS_INTERNAL, "no header".to_string()),
            }
        }
    };
    Box::into_raw(Box::new(owned)).cast()
}

/// Releases a stream; NULL is ignored.
///
/// # Safety
/// `stream` is NULL or came from [`swm_stream_new`] and was not freed
/// since.
#[no_mangle]
pub unsafe extern "C" fn swm_stream_free(stream: *mut Stream) {
    if !stream.is_null() {
        // SAFETY: the caller promises it came from `swm_stream_new`.
        drop(unsafe { Box::from_raw(stream) });
    }
}

/// An `Output` with nothing in it: a push that completed no new level.
fn nothing() -> Owned {
    let mut o = failure(STATUS_OK, String::new());
    o.out.message = ptr::null();
    o
}

/// `DecodeOptions` from [`swm_decode`]'s arguments; `None` when a limit
/// is NaN or negative.
fn options(
    sharpen: i32,
    bend_steps: i32,
    limits: [f64; 3],
    max_level: i32,
) -> Option<DecodeOptions> {
    Some(DecodeOptions {
        limits: self::limits(limits[0], limits[1], limits[2])?,
        sharpen: (sharpen >= 0).then_some(sharpen > 0),
        bend_steps: u32::try_from(bend_steps).ok(),
        max_level: u8::try_from(max_level).ok(),
    })
}

/// `Limits` from host numbers; `None` for NaN or a negative value.
fn limits(vertices: f64, faces: f64, alloc_bytes: f64) -> Option<Limits> {
    // `as` saturates: +inf and values beyond u64 become u64::MAX.
    let count = |x: f64| (x >= 0.0).then_some(x as u64);
    Some(Limits {
        max_vertices: count(vertices)?,
        max_faces: count(faces)?,
        max_alloc_bytes: count(alloc_bytes)?,
        ..Limits::default()
    })
}

fn decode(bytes: &[u8], options: &DecodeOptions, with_normals: bool) -> Owned {
    let result = swm::decode_attributed(bytes, options).and_then(|decoded| {
        // The file was parsed and checked by `decode_attributed`; this
        // second parse (one CRC pass over the file) only reads the
        // header's version and mode, through the public container API.
        let header = swm::container::parse_container(bytes, &options.limits)?.header;
        Ok((decoded, header))
    });
    match result {
        Ok((decoded, header)) => {
            // Without streams the split is the identity: skip its sort.
            let decoded = match decoded.streams.is_empty() {
                true => decoded,
                false => decoded.split_vertices(),
            };
            let mut o = owned(decoded.mesh, &header, with_normals, -1);
            o.attach(decoded.streams);
            o
        }
        Err(e) => failure(status_of(&e), message(&e)),
    }
}

impl Owned {
    /// Hands the streams out through `out.attributes`.
    fn attach(&mut self, streams: Vec<swm::AttributeStream>) {
        self._attributes = streams
            .iter()
            .map(|s| {
                let (kind, set) = match s.kind {
                    swm::AttributeKind::Normal => (1, 0),
                    swm::AttributeKind::TexCoord(n) => (2, n.into()),
                    swm::AttributeKind::Color(n) => (3, n.into()),
                    swm::AttributeKind::Generic(n) => (4, n.into()),
                    _ => (0, 0),
                };
                Attribute {
                    kind,
                    set,
                    dims: s.dims.into(),
                    values: s.values.as_ptr(),
                }
            })
            .collect();
        // As in `owned`: moving the vectors keeps their heap buffers.
        self._streams = streams;
        if !self._attributes.is_empty() {
            self.out.attributes = self._attributes.as_ptr();
            self.out.attribute_count = self._attributes.len();
        }
    }
}

/// A decoded mesh as an [`Output`] and what it points into.
fn owned(mesh: TriMesh, header: &swm::container::Header, with_normals: bool, level: i32) -> Owned {
    let normals = if with_normals {
        swm::vertex_normals(&mesh)
    } else {
        Vec::new()
    };
    let out = Output {
        status: STATUS_OK,
        message: ptr::null(),
        message_len: 0,
        positions: mesh.positions.as_ptr().cast(),
        vertex_count: mesh.positions.len(),
        indices: mesh.triangles.as_ptr().cast(),
        triangle_count: mesh.triangles.len(),
        normals: if with_normals {
            normals.as_ptr().cast()
        } else {
            ptr::null()
        },
        mode: header.mode.code().into(),
        major: header.major.into(),
        minor: header.minor.into(),
        level,
        attributes: ptr::null(),
        attribute_count: 0,
    };
    // Moving the vectors into `Owned` moves their headers, not their heap
    // buffers, so the pointers above stay valid.
    Owned {
        out,
        _mesh: mesh,
        _normals: normals,
        _streams: Vec::new(),
        _attributes: Vec::new(),
        _message: String::new(),
    }
}

fn failure(status: u32, message: String) -> Owned {
    Owned {
        out: Output {
            status,
            message: message.as_ptr(),
            message_len: message.len(),
            positions: ptr::null(),
            vertex_count: 0,
            indices: ptr::null(),
            triangle_count: 0,
            normals: ptr::null(),
            mode: 0,
            major: 0,
            minor: 0,
            level: -1,
            attributes: ptr::null(),
            attribute_count: 0,
        },
        _mesh: TriMesh::default(),
        _normals: Vec::new(),
        _streams: Vec::new(),
        _attributes: Vec::new(),
        _message: message,
    }
}

/// The error's message, as `e.to_string()` words it for every error a
/// decode can give, without linking the `Display` of the encoder's, the
/// file system's and the options' errors: with them `core`'s float
/// formatting and `std::io::Error`'s descriptions came in, 14 KB of the
/// module gzipped (BENCHMARKS.md, "Web"). An option out of range, which the
/// module's own options never are, is worded without its value.
fn message(e: &Error) -> String {
    use swm::ParameterError as P;
    match e {
        Error::Format(f) => f.to_string(),
        Error::LimitExceeded(l) => l.to_string(),
        Error::Unsupported(u) => u.to_string(),
        Error::Parameter(P::OutOfRange { name, .. } | P::NotPositive { name, .. }) => {
            let mut m = String::from(*name);
            m.push_str(" is out of its range");
            m
        }
        Error::Parameter(_) => String::from("an argument is out of its range"),
        _ => String::from(
            "internal error: the decoder gave an error of the encoder or the file system",
        ),
    }
}

fn status_of(e: &Error) -> u32 {
    match e {
        Error::Format(_) => STATUS_FORMAT,
        Error::LimitExceeded(_) => STATUS_LIMIT,
        Error::Unsupported(_) => STATUS_UNSUPPORTED,
        Error::Parameter(_) => STATUS_ARGUMENT,
        _ => STATUS_INTERNAL,
    }
}

#[cfg(test)]
mod tests;
