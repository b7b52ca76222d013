//! The fixed part of a `.swm` file: magic, version, flags, coding mode and
//! the counts of the decoded mesh (`format-spec/01-container.md`,
//! "Preamble" and "Fixed header").
//!
//! Everything a decoder needs to refuse a file before allocating lives
//! here and is checked here: the version, the required flags, the mode,
//! and the counts against [`Limits`] and against each other. Mode-specific
//! parameters do not: they travel in the `HEAD` section, so this layout
//! stays the same for every mode.

use crate::prelude::*;

use super::{UnsupportedError, UnsupportedFeature};
use crate::{Error, FormatError, Limits, Location, Malformed};
use byteorder::{ByteOrder, LittleEndian as LE};

/// Major format version this crate writes and reads. A decoder rejects any
/// other major version.
pub const FORMAT_MAJOR: u8 = 1;

/// Minor format version this crate writes. A decoder reads newer minor
/// versions of its major version as long as they use no feature it does
/// not know (see `format-spec/versions.md`).
pub const FORMAT_MINOR: u8 = 2;

/// The four bytes every `.swm` file starts with.
pub const MAGIC: [u8; 4] = *b"SWM\0";

/// Format name in [`FormatError`](crate::FormatError)s.
pub(super) const FORMAT_NAME: &str = "SWM";

/// Byte offsets of the fixed fields. They never move within a major
/// version: later minor versions add sections, not header fields.
pub(crate) mod at {
    pub const MAJOR: usize = 4;
    pub const MINOR: usize = 5;
    pub const FLAGS: usize = 6;
    pub const MODE: usize = 8;
    pub const VERTEX_COUNT: usize = 9;
    pub const TRIANGLE_COUNT: usize = 13;
    pub const COMPONENT_COUNT: usize = 17;
    pub const SECTION_COUNT: usize = 21;
    /// First section table entry.
    pub const TABLE: usize = 23;
}

/// Bytes per section table entry: tag and length.
pub(crate) const TABLE_ENTRY_LEN: usize = 8;
/// Bytes of the trailing CRC-32.
pub(crate) const CRC_LEN: usize = 4;
/// Smallest file of *any* version: magic, major, minor, CRC. Every version
/// keeps these four in place so that the checksum can be verified before
/// the version is looked at.
pub(crate) const MIN_FRAME_LEN: usize = at::MINOR + 1 + CRC_LEN;
/// Smallest 1.x file: the fixed header, no sections, the CRC.
pub(crate) const MIN_LEN: usize = at::TABLE + CRC_LEN;

/// Flag bits a decoder must understand: one it does not know makes the
/// file [unsupported](UnsupportedFeature::RequiredFlags).
pub const FLAGS_REQUIRED: u16 = 0x00FF;
/// Flag bits a decoder may ignore when it does not know them.
pub const FLAGS_OPTIONAL: u16 = 0xFF00;
/// Flag bits defined by this format version: 1.1 defines bit 0, the
/// compact framing ([`FLAG_COMPACT`]).
pub const KNOWN_FLAGS: u16 = FLAG_COMPACT;

/// Required flag bit 0: the header's counts and the section table are in
/// the compact framing (format 1.1).
pub const FLAG_COMPACT: u16 = 0x0001;

/// How the sections encode the mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Mode {
    /// Code 0: the input's own connectivity (Edgebreaker) and quantized,
    /// parallelogram-predicted coordinates.
    Lossless,
    /// Code 1: SwingWrapper retiling, connectivity of the new mesh and one
    /// quantized dihedral angle per vertex.
    Swing,
    /// Code 2 (format 1.2): displaced subdivision, a lossless base mesh,
    /// levels of 1-to-4 subdivision and one quantized scalar per new
    /// vertex along its predicted normal (format-spec/07-displaced.md).
    Displaced,
}

impl Mode {
    /// The byte stored in the file.
    pub const fn code(self) -> u8 {
        match self {
            Mode::Lossless => 0,
            Mode::Swing => 1,
            Mode::Displaced => 2,
        }
    }

    /// The mode a stored byte names, if this version knows it.
    pub const fn from_code(code: u8) -> Option<Mode> {
        match code {
            0 => Some(Mode::Lossless),
            1 => Some(Mode::Swing),
            2 => Some(Mode::Displaced),
            _ => None,
        }
    }
}

/// The fixed header of a `.swm` file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// Major format version. A decoder reads only its own.
    pub major: u8,
    /// Minor format version. A decoder reads newer ones (skipping what it
    /// does not know, when it may).
    pub minor: u8,
    /// Flag bits; see [`FLAGS_REQUIRED`] and [`FLAGS_OPTIONAL`]. Zero in 1.0;
    /// 1.1 defines bit 0, the compact framing ([`Header::framing`]).
    pub flags: u16,
    /// How the sections encode the mesh.
    pub mode: Mode,
    /// Vertices of the decoded mesh.
    pub vertex_count: u32,
    /// Triangles of the decoded mesh.
    pub triangle_count: u32,
    /// Connected components of the decoded mesh.
    pub component_count: u32,
}

impl Header {
    /// A header of version [`FORMAT_MAJOR`].0 with no flags: a writer
    /// raises `minor` (at most to [`FORMAT_MINOR`]) only when the file
    /// uses a feature a later minor version added, so that every older
    /// decoder of the major version reads every file it can.
    pub fn new(mode: Mode, vertex_count: u32, triangle_count: u32, component_count: u32) -> Self {
        Header {
            major: FORMAT_MAJOR,
            minor: 0,
            flags: 0,
            mode,
            vertex_count,
            triangle_count,
            component_count,
        }
    }

    /// The same header with the framing `framing` (format 1.1 for the
    /// compact one: its flag bit is a 1.1 feature, so the minor version
    /// is raised to at least 1).
    pub fn with_framing(mut self, framing: Framing) -> Self {
        match framing {
            Framing::Fixed => self.flags &= !FLAG_COMPACT,
            Framing::Compact => {
                self.flags |= FLAG_COMPACT;
                self.minor = self.minor.max(1);
            }
        }
        self
    }

    /// How the header's counts and the section table are laid out.
    pub const fn framing(&self) -> Framing {
        if self.flags & FLAG_COMPACT != 0 {
            Framing::Compact
        } else {
            Framing::Fixed
        }
    }

    /// Appends magic, version and flags: the preamble every framing
    /// starts with.
    pub(crate) fn write_preamble(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&MAGIC);
        out.push(self.major);
        out.push(self.minor);
        put_u16(out, self.flags);
    }

    /// Appends the fixed framing's preamble, mode and counts (up to, not
    /// including, the section count).
    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        self.write_preamble(out);
        out.push(self.mode.code());
        put_u32(out, self.vertex_count);
        put_u32(out, self.triangle_count);
        put_u32(out, self.component_count);
    }

    /// Reads and checks the fixed framing's header of a file whose magic,
    /// CRC, version and flags were checked (`read::check_preamble`) and that
    /// does not set the compact flag. `bytes` holds at least [`MIN_LEN`]
    /// bytes.
    pub(crate) fn read(bytes: &[u8], limits: &Limits) -> Result<Header, Error> {
        let (major, minor) = (bytes[at::MAJOR], bytes[at::MINOR]);
        let flags = LE::read_u16(&bytes[at::FLAGS..]);
        let mode = read_mode(bytes[at::MODE], major, minor)?;
        let vertex_count = LE::read_u32(&bytes[at::VERTEX_COUNT..]);
        let triangle_count = LE::read_u32(&bytes[at::TRIANGLE_COUNT..]);
        let component_count = LE::read_u32(&bytes[at::COMPONENT_COUNT..]);
        limits.check_vertices(vertex_count.into())?;
        limits.check_faces(triangle_count.into())?;
        let header = Header {
            major,
            minor,
            flags,
            mode,
            vertex_count,
            triangle_count,
            component_count,
        };
        check_counts(
            &header,
            [at::VERTEX_COUNT, at::TRIANGLE_COUNT, at::COMPONENT_COUNT],
        )?;
        Ok(header)
    }
}

/// How a file lays out its header's counts and its section table (the
/// preamble, the payloads and the CRC are the same in both).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Framing {
    /// Format 1.0's layout: `u32` counts, a `u16` section count and eight
    /// bytes (tag, `u32` length) per section; 27 bytes and 8 per section.
    /// Readable by every 1.x decoder.
    Fixed,
    /// Format 1.1's compact layout (flag bit 0): varint counts and
    /// lengths, one-byte codes for registered tags; about 17 bytes and 2
    /// per section. The default of the encoder.
    #[default]
    Compact,
}

/// The major version, then the required flags; returns the flags.
/// `bytes` holds at least the eight bytes of the preamble.
pub(crate) fn check_version_and_flags(bytes: &[u8]) -> Result<u16, Error> {
    let (major, minor) = (bytes[at::MAJOR], bytes[at::MINOR]);
    if major != FORMAT_MAJOR {
        return Err(unsupported(UnsupportedFeature::Version, major, minor));
    }
    let flags = LE::read_u16(&bytes[at::FLAGS..]);
    let unknown_required = flags & FLAGS_REQUIRED & !KNOWN_FLAGS;
    if unknown_required != 0 {
        let feature = UnsupportedFeature::RequiredFlags(unknown_required);
        return Err(unsupported(feature, major, minor));
    }
    Ok(flags)
}

/// The error for a file of version `major.minor` that uses `feature`,
/// unknown to this decoder.
pub(crate) fn unsupported(feature: UnsupportedFeature, major: u8, minor: u8) -> Error {
    UnsupportedError {
        feature,
        major,
        minor,
        supported_major: FORMAT_MAJOR,
        supported_minor: FORMAT_MINOR,
    }
    .into()
}

/// The mode a file's mode byte names, or *unsupported* (both framings).
pub(crate) fn read_mode(code: u8, major: u8, minor: u8) -> Result<Mode, Error> {
    Mode::from_code(code).ok_or_else(|| unsupported(UnsupportedFeature::Mode(code), major, minor))
}

/// What any triangle mesh without unreferenced vertices satisfies. These
/// bound every count by the triangle count, so the limit on triangles
/// bounds all allocations sized by the header.
/// `at` locates the vertex, triangle and component counts for errors.
pub(crate) fn check_counts(header: &Header, at: [usize; 3]) -> Result<(), Error> {
    let (v, t, c) = (
        u64::from(header.vertex_count),
        u64::from(header.triangle_count),
        u64::from(header.component_count),
    );
    let [vertex_at, _, component_at] = at;
    if c > t {
        return Err(malformed(
            Malformed::BadHeader("more components than triangles"),
            component_at,
        ));
    }
    if t > 0 && c == 0 {
        return Err(malformed(
            Malformed::BadHeader("triangles but no component"),
            component_at,
        ));
    }
    if v > 3 * t {
        return Err(malformed(
            Malformed::BadHeader("more than three vertices per triangle"),
            vertex_at,
        ));
    }
    if t > 0 && v < 3 {
        return Err(malformed(
            Malformed::BadHeader("triangles but fewer than three vertices"),
            vertex_at,
        ));
    }
    Ok(())
}

/// A located container format error.
pub(crate) fn malformed(what: Malformed, at: usize) -> Error {
    FormatError::new(FORMAT_NAME, what)
        .at(Location::Byte(at as u64))
        .into()
}

pub(crate) fn put_u16(out: &mut Vec<u8>, v: u16) {
    let mut b = [0; 2];
    LE::write_u16(&mut b, v);
    out.extend_from_slice(&b);
}

pub(crate) fn put_u32(out: &mut Vec<u8>, v: u32) {
    let mut b = [0; 4];
    LE::write_u32(&mut b, v);
    out.extend_from_slice(&b);
}
