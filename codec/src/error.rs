//! Errors, split by cause: I/O, an input that is not a regular file,
//! malformed data, bad parameter, limit exceeded, topology the encoder
//! cannot handle, unsupported version.
//!
//! Errors carry data, never formatted strings, so callers can match on
//! them; `Display` gives the one-line message the CLI prints after the
//! file name.

use core::fmt;

/// Everything that can go wrong in this crate.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading or writing failed at the operating-system level.
    #[cfg(feature = "std")]
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// An input path names something other than a regular file (a FIFO,
    /// a device, a directory), which is refused rather than read.
    #[error("{0}")]
    Input(#[from] InputError),
    /// The data is malformed or corrupt.
    #[error("{0}")]
    Format(#[from] FormatError),
    /// A caller-supplied option is out of range.
    #[error("{0}")]
    Parameter(#[from] ParameterError),
    /// The input asks for more than the [`Limits`](crate::Limits) allow.
    #[error("{0}")]
    LimitExceeded(#[from] LimitError),
    /// The input's topology cannot be handled (e.g. a non-orientable surface).
    #[error("{0}")]
    Topology(#[from] TopologyError),
    /// An attribute stream of an [`AttributedMesh`](crate::AttributedMesh)
    /// breaks its invariants (see `AttributedMesh::validate`).
    #[error("{0}")]
    Attribute(#[from] AttributeError),
    /// The file needs a newer decoder: a newer major version, or a mode,
    /// critical section or required flag this version does not know.
    #[error("{0}")]
    Unsupported(#[from] UnsupportedError),
    /// SwingWrapper retiling found no edge length that works.
    #[error("{0}")]
    Retile(#[from] RetileError),
    /// A file the input refers to could not be read (a glTF buffer's
    /// external `.bin` file): `error` is why, `path` is that file as
    /// resolved against the input's folder.
    #[cfg(feature = "std")]
    #[error("{}: {error}", path.display())]
    ExternalFile {
        /// The referenced file.
        path: std::path::PathBuf,
        /// Why it could not be read: I/O, not a regular file, too long.
        error: Box<Error>,
    },
    /// No file of the requested size can represent the mesh.
    #[error("{0}")]
    Size(#[from] SizeError),
    /// No file within the size cap meets the requested error bound.
    #[error("{0}")]
    ErrorBound(#[from] ErrorBoundError),
}

/// An error bound ([`SwingTarget::MaxError`](crate::SwingTarget)) that no
/// file the encoder can make meets (within the size cap, when one is
/// given).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorBoundError {
    /// The bound asked for: L2 relative to the input's bounding-box
    /// diagonal.
    pub requested: f64,
    /// The lowest error measured, on the largest file tried.
    pub lowest: f64,
    /// That file's size in bytes.
    pub bytes: u64,
}

impl fmt::Display for ErrorBoundError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "no file meets an L2 error of {:.3} x 1e-4 of the diagonal: the closest, {} bytes, measured {:.3}",
            self.requested * 1e4,
            self.bytes,
            self.lowest * 1e4
        )
    }
}

impl core::error::Error for ErrorBoundError {}

/// The requested size is below the smallest file the encoder can make
/// of the mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SizeError {
    /// The size asked for (or the cap), in bytes.
    pub requested: u64,
    /// The smallest file that represents the mesh, in bytes.
    pub smallest: u64,
}

impl fmt::Display for SizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "no file of {} bytes can hold this mesh: the smallest possible is {} bytes",
            self.requested, self.smallest
        )
    }
}

impl core::error::Error for SizeError {}

/// Why one SwingWrapper retiling run failed; every case means "the edge
/// length L is too large for this part of the shape".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RetileFailure {
    /// The sphere of radius L around p1 does not meet the walk (p2).
    NoSecondVertex,
    /// The circle of the first edge does not meet M (p3).
    NoThirdVertex,
    /// No tip, snap or closing triangle works at the gate of M′ triangle
    /// `triangle`.
    NoTip {
        /// Triangles made before.
        triangle: u32,
    },
    /// More triangles than the area can hold: the front does not close.
    Runaway,
    /// The loops closed but `faces` faces of M were never claimed.
    Uncovered {
        /// Faces of M (after splits) left over.
        faces: u32,
    },
    /// The input is empty or L is not a positive finite number.
    BadInput,
    /// The encoder's [`EncodeLimits`](crate::EncodeLimits) were reached
    /// (the encode fails with the [`LimitError`]).
    Limit,
}

impl fmt::Display for RetileFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RetileFailure::NoSecondVertex => write!(f, "no second vertex at distance L"),
            RetileFailure::NoThirdVertex => write!(f, "no first triangle"),
            RetileFailure::NoTip { triangle } => {
                write!(f, "no valid triangle after {triangle} triangles")
            }
            RetileFailure::Runaway => write!(f, "the retiling front does not close"),
            RetileFailure::Uncovered { faces } => {
                write!(f, "{faces} faces of the surface were not covered")
            }
            RetileFailure::BadInput => write!(f, "empty mesh or invalid edge length"),
            RetileFailure::Limit => write!(f, "the encoder's limits were reached"),
        }
    }
}

/// No SwingWrapper retiling of the input succeeded.
#[derive(Clone, Debug, PartialEq)]
pub struct RetileError {
    /// Runs made.
    pub attempts: u32,
    /// Runs that retiled the surface (their files did not fit the cap).
    pub successes: u32,
    /// The smallest edge length tried.
    pub smallest_edge_length: f64,
    /// Why the last run failed (`None` if every run succeeded but none
    /// fitted the size cap).
    pub failure: Option<RetileFailure>,
}

impl fmt::Display for RetileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.failure {
            Some(why) if self.successes == 0 => write!(
                f,
                "SwingWrapper retiling failed at every edge length tried ({} runs, down to {:.4e}): {why}",
                self.attempts, self.smallest_edge_length
            ),
            Some(why) => write!(
                f,
                "no SwingWrapper retiling fits ({} runs, {} retiled but too large, down to edge length {:.4e}; last failure: {why})",
                self.attempts, self.successes, self.smallest_edge_length
            ),
            None => write!(
                f,
                "no SwingWrapper retiling fits the size cap ({} runs, {} retiled, down to edge length {:.4e})",
                self.attempts, self.successes, self.smallest_edge_length
            ),
        }
    }
}

impl core::error::Error for RetileError {}

/// Where in a file a problem was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Location {
    /// 1-based line of a text file.
    Line(u64),
    /// 0-based byte offset of a binary file.
    Byte(u64),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte {b}"),
        }
    }
}

/// Malformed or corrupt data: what is wrong, in which format, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FormatError {
    /// Short name of the format ("PLY", "OBJ", "OFF", "STL", "SWM").
    pub format: &'static str,
    /// What is wrong.
    pub what: Malformed,
    /// Where, when known.
    pub at: Option<Location>,
}

impl FormatError {
    /// A new error without a location.
    pub fn new(format: &'static str, what: Malformed) -> Self {
        FormatError {
            format,
            what,
            at: None,
        }
    }

    /// The same error, located.
    pub fn at(mut self, at: Location) -> Self {
        self.at = Some(at);
        self
    }
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "malformed {} file", self.format)?;
        if let Some(at) = self.at {
            write!(f, " at {at}")?;
        }
        write!(f, ": {}", self.what)
    }
}

impl core::error::Error for FormatError {}

/// What is wrong with one attribute stream of an
/// [`AttributedMesh`](crate::AttributedMesh); `stream` is its index in
/// `AttributedMesh::streams`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum AttributeError {
    /// The stream's dimension is not one its kind allows (normals 3,
    /// texture coordinates 2 or 3, colours 3 or 4, generic 1 to 4).
    Dims {
        /// The stream.
        stream: u32,
        /// Its `dims`.
        dims: u8,
    },
    /// The value array's length is not a multiple of `dims`.
    ValueCount {
        /// The stream.
        stream: u32,
        /// Its number of floats.
        floats: u64,
        /// Its `dims`.
        dims: u8,
    },
    /// A value is NaN or infinite.
    NonFinite {
        /// The stream.
        stream: u32,
        /// The 0-based value (not float) index.
        value: u64,
    },
    /// The stream does not have one index triple per triangle.
    CornerCount {
        /// The stream.
        stream: u32,
        /// Its number of triples.
        triples: u64,
        /// The mesh's number of triangles.
        faces: u64,
    },
    /// A corner refers to a value the stream does not have.
    IndexOutOfRange {
        /// The stream.
        stream: u32,
        /// The index.
        index: u32,
        /// The stream's number of values.
        values: u64,
    },
    /// Two streams have the same kind.
    DuplicateKind {
        /// The second of the two.
        stream: u32,
    },
}

impl fmt::Display for AttributeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            AttributeError::Dims { stream, dims } => {
                write!(f, "attribute stream {stream}: {dims} components is not allowed for its kind")
            }
            AttributeError::ValueCount { stream, floats, dims } => write!(
                f,
                "attribute stream {stream}: {floats} floats is not a whole number of {dims}-component values"
            ),
            AttributeError::NonFinite { stream, value } => {
                write!(f, "attribute stream {stream}: value {value} is not finite")
            }
            AttributeError::CornerCount { stream, triples, faces } => write!(
                f,
                "attribute stream {stream}: {triples} index triples for {faces} triangles"
            ),
            AttributeError::IndexOutOfRange { stream, index, values } => write!(
                f,
                "attribute stream {stream}: index {index} out of range ({values} values)"
            ),
            AttributeError::DuplicateKind { stream } => {
                write!(f, "attribute stream {stream}: an earlier stream has the same kind")
            }
        }
    }
}

impl core::error::Error for AttributeError {}

/// What is malformed.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Malformed {
    /// The file holds no data at all.
    Empty,
    /// The data ends before what the header or syntax promised.
    Truncated,
    /// Bytes follow the end of the data where none may.
    TrailingData,
    /// The header is not valid; the text says which rule was broken.
    BadHeader(&'static str),
    /// A token that should be a number is not one.
    BadNumber,
    /// A line or record does not follow the syntax; the text says which rule.
    BadSyntax(&'static str),
    /// A declared count cannot fit in the bytes that follow it.
    CountTooLarge {
        /// What was counted ("vertex", "face", ...).
        element: &'static str,
        /// The count the file declares.
        declared: u64,
        /// The most the rest of the file could hold.
        possible: u64,
    },
    /// A face refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The index as written in the file: 1-based or negative
        /// (relative) in OBJ, 0-based in the other formats.
        index: i64,
        /// Number of vertices available.
        vertices: u64,
    },
    /// A coordinate is NaN or infinite.
    NonFinite {
        /// 0-based vertex index.
        vertex: u64,
    },
    /// A face has fewer than three vertices.
    FaceTooSmall {
        /// Its vertex count.
        count: u64,
    },
    /// The file names a feature this reader does not support.
    Unsupported(&'static str),
    /// The file does not start with the format's magic bytes: it is not a
    /// file of this format at all.
    BadMagic,
    /// The checksum stored in the file differs from the one its bytes give:
    /// the file is damaged or truncated.
    ChecksumMismatch {
        /// The checksum the file stores.
        stored: u32,
        /// The checksum computed over the file's bytes.
        computed: u32,
    },
    /// A section tag is not four ASCII letters.
    BadSectionTag {
        /// The tag's bytes as written.
        tag: [u8; 4],
    },
    /// A critical section appears more than once.
    DuplicateSection {
        /// The repeated tag.
        tag: [u8; 4],
    },
    /// A section's declared length runs past the end of the section data.
    SectionOutOfBounds {
        /// The section's tag.
        tag: [u8; 4],
        /// The byte offset where the section would end (exclusive).
        end: u64,
        /// The byte offset where section data must end (where the checksum starts).
        limit: u64,
    },
    /// A section the file's mode needs is absent.
    MissingSection {
        /// The missing tag.
        tag: [u8; 4],
    },
    /// A count the header declares differs from what the data holds.
    CountMismatch {
        /// What was counted, plural ("vertices", "triangles").
        element: &'static str,
        /// The count the header declares.
        declared: u64,
        /// The count the data holds.
        found: u64,
    },
    /// The text is UTF-16 (a byte-order mark or NUL bytes between
    /// characters); the readers take ASCII or UTF-8.
    Utf16,
    /// The bytes are binary data, not text of this format.
    Binary,
    /// A glTF mesh primitive draws something other than triangles:
    /// points (mode 0) or lines (modes 1 to 3). Triangles, strips and
    /// fans (modes 4 to 6) are read.
    UnsupportedPrimitive {
        /// The primitive's `mode`, as in the file.
        mode: u32,
    },
}

impl fmt::Display for Malformed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Malformed::Empty => write!(f, "the file is empty"),
            Malformed::Truncated => write!(f, "the file is truncated"),
            Malformed::TrailingData => write!(f, "unexpected data after the end"),
            Malformed::BadHeader(why) => write!(f, "bad header: {why}"),
            Malformed::BadNumber => write!(f, "not a valid number"),
            Malformed::BadSyntax(why) => write!(f, "{why}"),
            Malformed::CountTooLarge { element, declared, possible } => write!(
                f,
                "declares {declared} {element} elements but the rest of the file can hold at most {possible}"
            ),
            Malformed::IndexOutOfRange { index, vertices } => {
                write!(f, "vertex index {index} is out of range (the mesh has {vertices} vertices)")
            }
            Malformed::NonFinite { vertex } => write!(f, "vertex {vertex} has a NaN or infinite coordinate"),
            Malformed::FaceTooSmall { count } => write!(f, "a face has {count} vertices; at least 3 are needed"),
            Malformed::Unsupported(what) => write!(f, "unsupported: {what}"),
            Malformed::BadMagic => write!(f, "it does not start with the magic bytes, so it is not a file of this format"),
            Malformed::ChecksumMismatch { stored, computed } => write!(
                f,
                "checksum mismatch (stored {stored:#010x}, computed {computed:#010x}): the file is damaged or truncated"
            ),
            Malformed::BadSectionTag { tag } => {
                write!(f, "section tag \"{}\" is not four ASCII letters", tag.escape_ascii())
            }
            Malformed::DuplicateSection { tag } => {
                write!(f, "critical section \"{}\" appears more than once", tag.escape_ascii())
            }
            Malformed::SectionOutOfBounds { tag, end, limit } => write!(
                f,
                "section \"{}\" would end at byte {end}, past the end of the section data at byte {limit}",
                tag.escape_ascii()
            ),
            Malformed::MissingSection { tag } => {
                write!(f, "the required section \"{}\" is missing", tag.escape_ascii())
            }
            Malformed::CountMismatch { element, declared, found } => write!(
                f,
                "the header declares {declared} {element} but the data holds {found}"
            ),
            Malformed::Utf16 => write!(f, "UTF-16 text is not supported; save the file as UTF-8"),
            Malformed::Binary => write!(f, "binary data, not a text file of this format"),
            Malformed::UnsupportedPrimitive { mode } => {
                let name = match mode {
                    0 => "POINTS",
                    1 => "LINES",
                    2 => "LINE_LOOP",
                    3 => "LINE_STRIP",
                    _ => "unknown",
                };
                write!(f, "a mesh primitive has mode {mode} ({name}); only triangles, triangle strips and fans are read")
            }
        }
    }
}

/// A caller-supplied option is out of range or meaningless.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ParameterError {
    /// The file extension names no supported mesh format.
    UnknownExtension,
    /// A caller-provided output buffer cannot hold the decoded mesh.
    BufferTooSmall {
        /// Which buffer: `"positions"` or `"indices"`.
        buffer: &'static str,
        /// Elements it needs.
        needed: u64,
        /// Elements it has.
        given: u64,
    },
    /// The format can be written but not read. Not produced any more
    /// (GLB is read since glTF input came); kept so that code matching
    /// on it still compiles.
    WriteOnly {
        /// Short name of the format.
        format: &'static str,
    },
    /// The format can be read but not written (`.gltf`, whose buffers
    /// would need a second file or base64: write `.glb` instead).
    ReadOnly {
        /// Short name of the format.
        format: &'static str,
    },
    /// The file would be larger than its format can describe (GLB stores
    /// lengths as 32-bit numbers).
    FileTooLarge {
        /// Short name of the format.
        format: &'static str,
        /// Bytes the file would take.
        bytes: u64,
        /// Most bytes a file of the format can take.
        max: u64,
    },
    /// An option that must be a positive finite number is not (zero,
    /// negative, infinite or NaN).
    NotPositive {
        /// The option's name.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A numeric option is outside its range (`f64::MAX` or infinity
    /// for a side without bound).
    OutOfRange {
        /// The option's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
    },
    /// An option that the chosen mode has no use for.
    NotApplicable {
        /// The option's name.
        name: &'static str,
        /// The mode.
        mode: &'static str,
    },
    /// An option only a method that keeps no attribute streams takes,
    /// given for an input that has some (an edge length asks for
    /// SwingWrapper).
    KeepsNoAttributes {
        /// The option's name.
        name: &'static str,
        /// The method it asks for, as the command line names it.
        method: &'static str,
    },
}

impl fmt::Display for ParameterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParameterError::UnknownExtension => {
                write!(
                    f,
                    "unknown mesh format (expected .obj, .ply, .off, .stl, .gltf or .glb)"
                )
            }
            ParameterError::BufferTooSmall {
                buffer,
                needed,
                given,
            } => write!(
                f,
                "the {buffer} buffer holds {given} elements, the decoded mesh needs {needed}"
            ),
            ParameterError::WriteOnly { format } => {
                write!(f, "{format} files can be written but not read")
            }
            ParameterError::ReadOnly { format } => write!(
                f,
                "{format} files can be read but not written (write .glb for glTF)"
            ),
            ParameterError::FileTooLarge { format, bytes, max } => write!(
                f,
                "the {format} file would take {bytes} bytes, more than the {max} the format allows"
            ),
            ParameterError::OutOfRange {
                name,
                value,
                min,
                max,
            } => {
                // Plain words for an unbounded side, never a 309-digit
                // f64::MAX.
                let (low, high) = (*min > f64::MIN, *max < f64::MAX);
                match (low, high) {
                    (true, true) => write!(f, "{name} = {value}: must be between {min} and {max}"),
                    (true, false) => write!(
                        f,
                        "{name} = {value}: must be a finite number of at least {min}"
                    ),
                    (false, true) => {
                        write!(f, "{name} = {value}: must be a number of at most {max}")
                    }
                    (false, false) => write!(f, "{name} = {value}: must be a finite number"),
                }
            }
            ParameterError::NotPositive { name, value } => {
                write!(f, "{name} = {value}: must be a positive finite number")
            }
            ParameterError::NotApplicable { name, mode } => {
                write!(f, "the {mode} mode takes no {name}")
            }
            ParameterError::KeepsNoAttributes { name, method } => write!(
                f,
                "an {name} asks for the {method} method, which keeps no attribute streams: \
                 ask for a size to keep them, or force it (--mode {method}) to drop them"
            ),
        }
    }
}

impl core::error::Error for ParameterError {}

/// What kind of file an input path names, when it is not a regular file
/// (symbolic links are followed: this is the kind of their target).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FileKind {
    /// A directory.
    Directory,
    /// A FIFO (named pipe): reading it could block or never end.
    Fifo,
    /// A character device such as `/dev/zero`: reading it could never end.
    CharDevice,
    /// A block device.
    BlockDevice,
    /// A Unix domain socket.
    Socket,
    /// Anything else that is not a regular file.
    Other,
}

impl fmt::Display for FileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FileKind::Directory => "a directory",
            FileKind::Fifo => "a FIFO (named pipe)",
            FileKind::CharDevice => "a character device",
            FileKind::BlockDevice => "a block device",
            FileKind::Socket => "a socket",
            FileKind::Other => "a special file",
        })
    }
}

/// An input path that is refused before anything is read from it.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum InputError {
    /// The path names something other than a regular file: its length is
    /// unknown or unbounded, or opening and reading it could block.
    NotARegularFile {
        /// What it is.
        kind: FileKind,
    },
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::NotARegularFile { kind } => {
                write!(f, "{kind}, not a regular file; only regular files are read")
            }
        }
    }
}

impl core::error::Error for InputError {}

/// What a [`LimitError`] counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Limited {
    /// Vertices.
    Vertices,
    /// Faces (triangles).
    Faces,
    /// Bytes of memory.
    AllocBytes,
    /// Elementary steps of the encoder's searches ([`EncodeLimits`](crate::EncodeLimits)).
    Work,
    /// Milliseconds of encoding time ([`EncodeLimits`](crate::EncodeLimits)).
    Milliseconds,
    /// Bytes of an input file.
    InputBytes,
}

/// The input needs more than the [`Limits`](crate::Limits) (or, when
/// encoding, the [`EncodeLimits`](crate::EncodeLimits)) allow.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LimitError {
    /// What was counted.
    pub what: Limited,
    /// How many were requested.
    pub requested: u64,
    /// The limit in force.
    pub limit: u64,
}

impl fmt::Display for LimitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.what {
            Limited::Vertices => "vertices",
            Limited::Faces => "faces",
            Limited::AllocBytes => "bytes of memory",
            Limited::Work => "steps of retiling work",
            Limited::Milliseconds => "milliseconds",
            Limited::InputBytes => {
                // `requested` is a lower bound when the file was cut off
                // while read (it grew, or its length was not known).
                return write!(
                    f,
                    "the file holds at least {} bytes, more than the input limit of {}",
                    self.requested, self.limit
                );
            }
        };
        write!(
            f,
            "needs {} {what}, more than the limit of {}",
            self.requested, self.limit
        )
    }
}

impl core::error::Error for LimitError {}

/// Input whose topology the library cannot handle.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum TopologyError {
    /// A connected component cannot be oriented consistently (Möbius-like).
    NonOrientable {
        /// Index of the component, in order of its first face.
        component: u32,
        /// A face where the orientation conflict was found.
        face: u32,
    },
    /// The mesh has no triangles left (after cleaning, if any).
    NoTriangles,
    /// The corner table requires a manifold mesh and this one is not.
    NonManifold {
        /// Edges shared by more than two faces or by two faces of the same direction.
        edges: u64,
        /// Vertices whose faces form more than one fan.
        vertices: u64,
    },
    /// Not produced any more (the SwingWrapper mode takes holes,
    /// handles and several components since format 1.0's HOLE and REST
    /// sections); kept so that code matching on it still compiles.
    NotASphere {
        /// Boundary edges.
        boundary_edges: u64,
        /// Connected components.
        components: u32,
        /// Handles (of the whole mesh, holes closed).
        genus: i64,
    },
}

impl fmt::Display for TopologyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TopologyError::NonOrientable { component, face } => write!(
                f,
                "component {component} is not orientable (orientation conflict at face {face})"
            ),
            TopologyError::NoTriangles => write!(f, "the mesh has no triangles"),
            TopologyError::NonManifold { edges, vertices } => write!(
                f,
                "the mesh is not manifold ({edges} non-manifold edges, {vertices} non-manifold vertices)"
            ),
            TopologyError::NotASphere {
                boundary_edges,
                components,
                genus,
            } => write!(
                f,
                "SwingWrapper mode cannot retile handles yet; this mesh has genus {genus} ({components} components, {boundary_edges} boundary edges; the lossless mode takes it)"
            ),
        }
    }
}

impl core::error::Error for TopologyError {}

/// The file needs a decoder newer than this one.
///
/// Names both versions: the file's, and the newest this decoder was
/// written for. A decoder reads every file of its own major version that
/// uses only features it knows, so `feature` says what it tripped on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnsupportedError {
    /// What the file uses that this decoder does not know.
    pub feature: UnsupportedFeature,
    /// The file's major version.
    pub major: u8,
    /// The file's minor version.
    pub minor: u8,
    /// The major version this decoder implements.
    pub supported_major: u8,
    /// The minor version this decoder implements.
    pub supported_minor: u8,
}

/// What an [`UnsupportedError`] tripped on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum UnsupportedFeature {
    /// A different major version (newer, or 0, which was never released).
    Version,
    /// An unknown coding mode.
    Mode(u8),
    /// An unknown critical section.
    CriticalSection([u8; 4]),
    /// Required flag bits this decoder does not know.
    RequiredFlags(u16),
    /// A section tag code of the compact framing (format 1.1) that this
    /// decoder does not know: a tag a later version registered, which may
    /// be critical.
    SectionCode(u8),
}

impl fmt::Display for UnsupportedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (ma, mi, sa, si) = (
            self.major,
            self.minor,
            self.supported_major,
            self.supported_minor,
        );
        match self.feature {
            UnsupportedFeature::Version => write!(
                f,
                "the file is .swm version {ma}.{mi}, which this decoder (version {sa}.{si}) cannot read"
            ),
            UnsupportedFeature::Mode(m) => write!(
                f,
                "the file (.swm version {ma}.{mi}) uses coding mode {m}, unknown to this decoder (version {sa}.{si})"
            ),
            UnsupportedFeature::CriticalSection(tag) => write!(
                f,
                "the file (.swm version {ma}.{mi}) has a critical section \"{}\" unknown to this decoder (version {sa}.{si})",
                tag.escape_ascii()
            ),
            UnsupportedFeature::RequiredFlags(bits) => write!(
                f,
                "the file (.swm version {ma}.{mi}) sets required flags {bits:#06x} unknown to this decoder (version {sa}.{si})"
            ),
            UnsupportedFeature::SectionCode(c) => write!(
                f,
                "the file (.swm version {ma}.{mi}) has a section with tag code {c}, unknown to this decoder (version {sa}.{si})"
            ),
        }
    }
}

impl core::error::Error for UnsupportedError {}
