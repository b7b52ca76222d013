//! Mesh file readers and writers: Wavefront OBJ, PLY, OFF and STL, and
//! glTF 2.0, read as `.gltf` (JSON with external or embedded buffers) or
//! `.glb` (binary) and written as `.glb`.
//!
//! Readers return the *raw* mesh of a file: positions as written
//! (converted to `f32`), polygons fan-triangulated as (v0, vi, vi+1), no
//! vertex merging and no dropping of degenerate faces; cleaning is the
//! job of `clean` (feature `encoder`). A glTF scene is merged into one
//! mesh, each node's transform applied (see `gltf`). What every reader
//! guarantees on success:
//! - every position is finite and every index is in range, so the result
//!   passes [`TriMesh::validate`];
//! - nothing was allocated because a file said so before that count was
//!   checked against the [`Limits`] and against what the rest of the file
//!   could hold;
//! - a file without vertices and without faces is an error
//!   ([`Malformed::Empty`]), not an empty mesh.
//!
//! No reader panics or loops forever on any input; errors say where
//! (line of a text file, byte of a binary one) whenever that is known.
//!
//! Writers produce files these readers read back to the same mesh, bit for
//! bit: OBJ and OFF with shortest round-trip decimals, PLY as binary
//! little-endian, STL as binary (which cannot share vertices, so it keeps
//! positions but not the indexing). GLB gets the positions bit for bit, the
//! triangles, and angle-weighted unit normals for shading. [`write_mesh`]
//! replaces its target only once the whole file is written.
//!
//! Files are read only if they are regular files no longer than
//! [`Limits::max_input_bytes`]: a FIFO, a device such as `/dev/zero` or a
//! directory is refused before anything is read ([`InputError`](crate::InputError)).
//! The external buffers of a `.gltf` file are read the same way, within
//! the same byte budget as the file that names them.
//! Outputs go through an exclusive, unpredictably named temporary file
//! that is renamed into place; [`discard_unfinished`] removes those of
//! writes in progress, for programs that end on a signal.
//!
//! The `TriMesh` readers keep positions and faces only. What else a file
//! carried that is dropped (texture coordinates, normals, colours) is
//! reported by [`read_mesh_with_report`] and
//! [`read_mesh_bytes_with_report`], so that programs can say so
//! ([`Attributes`]). [`read_attributed_mesh_with`] and
//! [`read_attributed_mesh_bytes`] keep them too, as the streams of an
//! [`AttributedMesh`] (the same mesh, bit for bit, and each attribute
//! with its own per-corner indices), under the same guarantees and
//! limits; an attribute a file gets wrong (a non-finite value, an index
//! out of range, one that not every face has) is dropped and reported,
//! never an error, so attributes never make a readable file unreadable.
//! [`write_attributed_mesh`] writes them in every format that has a
//! convention for them, and reports what a format cannot hold
//! ([`WriteReport`]).
//!
//! One file per format; `source` maps or reads input files, `output`
//! writes output files, `text` holds the ASCII scanning the text formats
//! share, `attributes` the reports of what was dropped or not written,
//! `builder` the mesh and streams a reader builds under the limits.

mod attributes;
mod builder;
mod gltf;
mod obj;
mod off;
mod output;
mod ply;
mod source;
mod stl;
mod text;

use crate::{AttributedMesh, Error, FormatError, Limits, Malformed, ParameterError, TriMesh};
pub use attributes::{Attributes, ReadReport, WriteReport};
pub use gltf::scene_codec::{
    decode_scene, scene_info, SceneDecoded, SceneFormat, ScenePrimitive, SCENE_EXTENSION,
};
#[cfg(feature = "encoder")]
pub use gltf::scene_codec::{
    encode_scene, Coded, PrimitiveOutcome, PrimitiveReport, SceneEncoded, SceneOptions,
    SceneReport, Uncoded,
};
pub use output::discard_unfinished;
use output::write_atomic;
use std::io::{BufWriter, Write};
use std::ops::Deref;
use std::path::Path;

/// What every reader is: the bytes of a whole file, the folder it was
/// read from (for files that name other files), and whether to read
/// attribute streams, to its raw mesh and the vertex attributes it
/// dropped.
type Reader =
    fn(&[u8], Option<&Path>, &Limits, bool) -> Result<(AttributedMesh, Attributes), Error>;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshFormat {
    /// Wavefront OBJ (text).
    Obj,
    /// Stanford PLY (ASCII or binary).
    Ply,
    /// Geomview OFF (text).
    Off,
    /// STL (ASCII or binary).
    Stl,
    /// glTF 2.0 binary (`.glb`).
    Glb,
    /// glTF 2.0 JSON (`.gltf`), its buffers in other files or embedded
    /// as base64 `data:` URIs: read, not written (write `.glb`).
    Gltf,
}

impl MeshFormat {
    /// The format a file name's extension names, ignoring case.
    pub fn from_path(path: &Path) -> Result<MeshFormat, Error> {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        [
            ("obj", MeshFormat::Obj),
            ("ply", MeshFormat::Ply),
            ("off", MeshFormat::Off),
            ("stl", MeshFormat::Stl),
            ("glb", MeshFormat::Glb),
            ("gltf", MeshFormat::Gltf),
        ]
        .into_iter()
        .find(|(name, _)| ext.eq_ignore_ascii_case(name))
        .map(|(_, format)| format)
        .ok_or(Error::Parameter(ParameterError::UnknownExtension))
    }

    /// The format a short name names, ignoring case: `obj`, `ply`, `off`,
    /// `stl`, `glb` or `gltf`, as the file extensions (for data without
    /// a file name, such as a pipe).
    pub fn from_name(name: &str) -> Result<MeshFormat, Error> {
        MeshFormat::from_path(Path::new(&format!("x.{name}")))
    }

    /// Short upper-case name: "OBJ", "PLY", "OFF", "STL", "GLB" or "GLTF".
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Obj => "OBJ",
            MeshFormat::Ply => "PLY",
            MeshFormat::Off => "OFF",
            MeshFormat::Stl => "STL",
            MeshFormat::Glb => "GLB",
            MeshFormat::Gltf => "GLTF",
        }
    }

    /// Whether this crate reads the format (every format is read).
    pub fn is_readable(self) -> bool {
        true
    }

    /// Whether this crate writes the format (all but `.gltf`).
    pub fn is_writable(self) -> bool {
        self != MeshFormat::Gltf
    }

    /// The format's reader.
    fn reader(self) -> Reader {
        // Only glTF files name other files; the other readers need no folder.
        match self {
            MeshFormat::Obj => |b, _, l, keep| obj::read(b, l, keep),
            MeshFormat::Ply => |b, _, l, keep| ply::read(b, l, keep),
            MeshFormat::Off => |b, _, l, keep| off::read(b, l, keep),
            // STL has no vertex attributes.
            MeshFormat::Stl => |b, _, l, _| stl::read(b, l),
            // One reader for both: it tells them apart by the GLB magic.
            MeshFormat::Glb | MeshFormat::Gltf => gltf::read,
        }
    }
}

/// The whole content of a file, as [`read_mesh_with`] gets it, with the
/// default [`Limits`]. For inputs other than meshes, e.g. `.swm` files.
pub fn read_file(path: &Path) -> Result<impl Deref<Target = [u8]>, Error> {
    read_file_with(path, &Limits::default())
}

/// The whole content of a file, as [`read_mesh_with`] gets it: only a
/// regular file is read (symbolic links are followed), anything else is
/// [`InputError::NotARegularFile`](crate::InputError::NotARegularFile);
/// a file longer than `limits.max_input_bytes` is a [`LimitError`] (of
/// [`Limited::InputBytes`]) before anything is read. Files of 1 MiB or
/// more are memory-mapped, smaller ones read into memory.
///
/// As with [`read_mesh_with`], if another process truncates a mapped file
/// while the bytes are in use, the operating system may kill this one
/// (`SIGBUS`); use `std::fs::read` when that matters.
pub fn read_file_with(path: &Path, limits: &Limits) -> Result<impl Deref<Target = [u8]>, Error> {
    source::Source::open(path, limits)
}

/// Reads a mesh file, its format given by the extension, with the default
/// [`Limits`].
pub fn read_mesh(path: &Path) -> Result<TriMesh, Error> {
    read_mesh_with(path, &Limits::default())
}

/// Reads a mesh file, its format given by the extension.
///
/// Only a regular file no longer than `limits.max_input_bytes` is read
/// (see [`read_file_with`]). Files of 1 MiB or more are memory-mapped: if another process truncates
/// the file while it is read, the operating system may kill this one
/// (`SIGBUS`). Read the bytes yourself and call [`read_mesh_bytes`] when
/// that matters.
pub fn read_mesh_with(path: &Path, limits: &Limits) -> Result<TriMesh, Error> {
    read_mesh_as(path, MeshFormat::from_path(path)?, limits)
}

/// [`read_mesh_with`] for a file of the given format, whatever its name
/// says (for names without an extension).
pub fn read_mesh_as(path: &Path, format: MeshFormat, limits: &Limits) -> Result<TriMesh, Error> {
    read_mesh_with_report(path, Some(format), limits).map(|(mesh, _)| mesh)
}

/// [`read_mesh_as`] (or [`read_mesh_with`] when `format` is `None`: the
/// extension says), with a report of what the file carried that the mesh
/// does not keep.
pub fn read_mesh_with_report(
    path: &Path,
    format: Option<MeshFormat>,
    limits: &Limits,
) -> Result<(TriMesh, ReadReport), Error> {
    let format = match format {
        Some(f) => f,
        None => MeshFormat::from_path(path)?,
    };
    let bytes = source::Source::open(path, limits)?;
    // A `.gltf` file's external buffers are beside it.
    let folder = path.parent().unwrap_or(Path::new(""));
    read_bytes_in(&bytes, format, Some(folder), limits, false).map(|(m, r)| (m.mesh, r))
}

/// [`read_mesh_with_report`] with the vertex attributes the file carries:
/// normals, texture coordinates and colours, each an
/// [`AttributeStream`](crate::AttributeStream) of per-corner indices
/// (OBJ's `vt` and `vn` keep their own indexing; PLY and glTF per-vertex
/// values index like the positions). The mesh is the one
/// [`read_mesh_with_report`] returns, bit for bit; the report lists what
/// the file carried that the streams still do not keep (an attribute
/// that not every face or primitive has, a non-finite value, tangents
/// are not read).
///
/// What each format gives: OBJ `vt` (2 components, 3 when a `w` is
/// given), `vn` and `v x y z r g b` colours; PLY vertex `nx ny nz`,
/// `u v` / `s t` / `texture_u texture_v`, `red green blue [alpha]`
/// (integers scaled to 0..1) and the face `texcoord` list; OFF's `N`,
/// `C` and `ST` vertex values; glTF `NORMAL`, `TEXCOORD_n` and `COLOR_0`
/// (normalized integers decoded as §3.11 says), normals turned with each
/// node's transform. All within the same [`Limits`].
pub fn read_attributed_mesh_with(
    path: &Path,
    format: Option<MeshFormat>,
    limits: &Limits,
) -> Result<(AttributedMesh, ReadReport), Error> {
    let format = match format {
        Some(f) => f,
        None => MeshFormat::from_path(path)?,
    };
    let bytes = source::Source::open(path, limits)?;
    let folder = path.parent().unwrap_or(Path::new(""));
    read_bytes_in(&bytes, format, Some(folder), limits, true)
}

/// [`read_attributed_mesh_with`] from the bytes of a file (see
/// [`read_mesh_bytes`] for `.gltf` files).
pub fn read_attributed_mesh_bytes(
    bytes: &[u8],
    format: MeshFormat,
    limits: &Limits,
) -> Result<(AttributedMesh, ReadReport), Error> {
    read_bytes_in(bytes, format, None, limits, true)
}

/// Reads a mesh from the bytes of a file. A `.gltf` file must then hold
/// its buffers (as `data:` URIs): external ones cannot be found without
/// the file's folder, and are refused ([`Malformed::Unsupported`]).
pub fn read_mesh_bytes(
    bytes: &[u8],
    format: MeshFormat,
    limits: &Limits,
) -> Result<TriMesh, Error> {
    read_mesh_bytes_with_report(bytes, format, limits).map(|(mesh, _)| mesh)
}

/// [`read_mesh_bytes`] with a report of what the file carried that the
/// mesh does not keep.
pub fn read_mesh_bytes_with_report(
    bytes: &[u8],
    format: MeshFormat,
    limits: &Limits,
) -> Result<(TriMesh, ReadReport), Error> {
    read_bytes_in(bytes, format, None, limits, false).map(|(m, r)| (m.mesh, r))
}

/// [`read_mesh_bytes`] for a file in `folder`, with its attribute
/// streams if `keep`.
fn read_bytes_in(
    bytes: &[u8],
    format: MeshFormat,
    folder: Option<&Path>,
    limits: &Limits,
    keep: bool,
) -> Result<(AttributedMesh, ReadReport), Error> {
    let read = format.reader();
    let empty = || Error::Format(FormatError::new(format.name(), Malformed::Empty));
    if text::is_blank(bytes) {
        return Err(empty());
    }
    let (mesh, dropped) = read(bytes, folder, limits, keep)?;
    if mesh.mesh.positions.is_empty() && mesh.mesh.triangles.is_empty() {
        return Err(empty());
    }
    Ok((mesh, ReadReport { dropped }))
}

/// Writes a mesh file, its format given by the extension; `.gltf` is
/// refused ([`ParameterError::ReadOnly`]), before anything is created.
///
/// The mesh is written to a temporary file next to `path`, created
/// exclusively under an unpredictable name (`.{name}.XXXXXX.tmp`, never
/// following a symbolic link), flushed to disk, and renamed over `path`
/// only when complete, so `path` holds either its old content or the
/// whole new file; on an error the temporary file is removed. The rename
/// replaces whatever entry `path` is: a symbolic link at `path` is
/// replaced, not followed. A `path` that exists and is not a file (a
/// device such as `/dev/null`, a FIFO) is written to in place instead,
/// since a rename would replace the device itself. An invalid mesh (see
/// [`TriMesh::validate`]) is refused before anything is created.
pub fn write_mesh(path: &Path, mesh: &TriMesh) -> Result<(), Error> {
    write_mesh_as(path, MeshFormat::from_path(path)?, mesh)
}

/// [`write_mesh`] in the given format, whatever the name says.
pub fn write_mesh_as(path: &Path, format: MeshFormat, mesh: &TriMesh) -> Result<(), Error> {
    writable(format)?;
    mesh.validate()?;
    write_atomic(path, |file| write_mesh_to(file, format, mesh))
}

/// Writes `bytes` (e.g. a `.swm` file) to `path` the way [`write_mesh`]
/// does: complete or not at all.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_atomic(path, |file| Ok(file.write_all(bytes)?))
}

/// Writes a mesh in `format` to `w` (buffered here; no need to pass a
/// `BufWriter`). OBJ, PLY and OFF keep the mesh exactly; STL is written
/// as binary STL, three corners per triangle; GLB keeps positions and
/// triangles and adds unit vertex normals (a mesh without triangles gives
/// a GLB file whose scene has no mesh). `.gltf` is not written
/// ([`ParameterError::ReadOnly`]).
pub fn write_mesh_to<W: Write>(w: W, format: MeshFormat, mesh: &TriMesh) -> Result<(), Error> {
    writable(format)?;
    mesh.validate()?;
    let mut w = BufWriter::with_capacity(1 << 16, w);
    match format {
        MeshFormat::Obj => obj::write(&mut w, mesh)?,
        MeshFormat::Ply => ply::write(&mut w, mesh)?,
        MeshFormat::Off => off::write(&mut w, mesh)?,
        MeshFormat::Stl => stl::write(&mut w, mesh)?,
        MeshFormat::Glb => gltf::write(&mut w, mesh)?,
        MeshFormat::Gltf => unreachable!("refused by `writable`"),
    }
    w.flush()?;
    Ok(())
}

/// Writes a mesh with its attributes, the format given by the extension
/// (see [`write_attributed_mesh_to`]), complete or not at all as
/// [`write_mesh`] does. An invalid mesh ([`AttributedMesh::validate`]) is
/// refused before anything is created.
pub fn write_attributed_mesh(path: &Path, mesh: &AttributedMesh) -> Result<WriteReport, Error> {
    write_attributed_mesh_as(path, MeshFormat::from_path(path)?, mesh)
}

/// [`write_attributed_mesh`] in the given format, whatever the name says.
pub fn write_attributed_mesh_as(
    path: &Path,
    format: MeshFormat,
    mesh: &AttributedMesh,
) -> Result<WriteReport, Error> {
    writable(format)?;
    mesh.validate()?;
    let mut report = WriteReport::default();
    write_atomic(path, |file| {
        report = write_attributed_mesh_to(file, format, mesh)?;
        Ok(())
    })?;
    Ok(report)
}

/// Writes a mesh with its attributes in `format` to `w`; the report says
/// which attributes the format could not hold and were left out.
///
/// - OBJ: `vt` (texture set 0), `vn` and `f v/vt/vn` with each stream's
///   own indices, so seams are written as they are; RGB colour set 0 on
///   the `v` lines (a position with several colours is written once per
///   colour);
/// - PLY (binary) and OFF: one vertex per distinct position and values
///   ([`AttributedMesh::split_vertices`]) with normals, texture set 0 of
///   2 components and colour set 0 (PLY `uchar` when every colour is an
///   8-bit value, `float` otherwise);
/// - GLB: split vertices with NORMAL (unit; computed as [`write_mesh_to`]
///   does when the mesh has none), TEXCOORD_n (2 components) and
///   COLOR_n;
/// - STL: no attributes.
///
/// A mesh without streams gives the bytes [`write_mesh_to`] gives.
pub fn write_attributed_mesh_to<W: Write>(
    w: W,
    format: MeshFormat,
    mesh: &AttributedMesh,
) -> Result<WriteReport, Error> {
    writable(format)?;
    mesh.validate()?;
    let mut w = BufWriter::with_capacity(1 << 16, w);
    let unwritten = match format {
        MeshFormat::Obj => obj::write_attributed(&mut w, mesh)?,
        MeshFormat::Ply => ply::write_attributed(&mut w, mesh)?,
        MeshFormat::Off => off::write_attributed(&mut w, mesh)?,
        MeshFormat::Stl => {
            stl::write(&mut w, &mesh.mesh)?;
            mesh.streams.iter().fold(Attributes::default(), |a, s| {
                a.union(Attributes::of(s.kind))
            })
        }
        MeshFormat::Glb => gltf::write_attributed(&mut w, mesh)?,
        MeshFormat::Gltf => unreachable!("refused by `writable`"),
    };
    w.flush()?;
    Ok(WriteReport { unwritten })
}

/// [`ParameterError::ReadOnly`] for a format that is not written.
fn writable(format: MeshFormat) -> Result<(), Error> {
    if format.is_writable() {
        return Ok(());
    }
    let format = format.name();
    Err(Error::Parameter(ParameterError::ReadOnly { format }))
}

/// A mesh of `../shared/corpus` for the unit tests; `None`, after a
/// reported skip, when the corpus is not beside the repository.
#[cfg(test)]
pub(crate) fn shared_corpus_mesh(name: &str) -> Option<TriMesh> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/corpus")
        .join(name);
    if !path.is_file() {
        crate::test_skip::skip("../shared/corpus not found");
        return None;
    }
    Some(read_mesh(&path).unwrap())
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_attributes;
