//! Parsing the frame: every check a decoder makes before it touches a
//! section's contents, in a fixed order, with no allocation.
//!
//! Order (format-spec/01-container.md, "Decoding procedure"):
//! 1. magic (anything else is not an `.swm` file);
//! 2. CRC-32 of everything before the last four bytes, so that no damaged
//!    byte is ever interpreted (the magic, major, minor and trailing CRC
//!    sit in the same place in every version, which is what allows the
//!    checksum to come before the version);
//! 3. version, flags, mode, counts against [`Limits`] and each other;
//! 4. the section table: tags, criticality, duplicates, lengths, and that
//!    the payloads exactly fill the space up to the CRC.

use super::crc::crc32;
use super::header::{at, malformed, Header, CRC_LEN, MIN_FRAME_LEN, MIN_LEN, TABLE_ENTRY_LEN};
use super::tag::KNOWN_CRITICAL;
use super::{Tag, UnsupportedError, UnsupportedFeature, FORMAT_MAJOR, FORMAT_MINOR, MAGIC};
use crate::{Error, Limits, Malformed};
use byteorder::{ByteOrder, LittleEndian as LE};

/// A parsed container: the header and borrowed section payloads
/// (zero-copy; nothing is allocated).
#[derive(Clone, Copy, Debug)]
pub struct Container<'a> {
    /// The fixed header, checked against the limits.
    pub header: Header,
    /// The section table's entries.
    table: &'a [u8],
    /// All payloads, in table order.
    data: &'a [u8],
    /// File offset of `data`.
    data_offset: usize,
}

/// One section of a parsed container.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Section<'a> {
    /// Its tag.
    pub tag: Tag,
    /// File offset of its first payload byte (for locating errors found
    /// inside it).
    pub offset: usize,
    /// Its payload.
    pub bytes: &'a [u8],
}

impl Section<'_> {
    /// Is the tag defined by the format version this crate implements?
    /// An unknown section is always ancillary: the parser rejects unknown
    /// critical ones.
    pub fn is_known(&self) -> bool {
        self.tag.is_known()
    }
}

impl<'a> Container<'a> {
    /// Every section, in file order, unknown ancillary ones included.
    pub fn sections(&self) -> Sections<'a> {
        Sections {
            table: self.table,
            data: self.data,
            offset: self.data_offset,
        }
    }

    /// Number of sections.
    pub fn section_count(&self) -> usize {
        self.table.len() / TABLE_ENTRY_LEN
    }

    /// The first section with this tag.
    pub fn find(&self, tag: Tag) -> Option<Section<'a>> {
        self.sections().find(|s| s.tag == tag)
    }

    /// The payload of the first section with this tag.
    pub fn section(&self, tag: Tag) -> Option<&'a [u8]> {
        self.find(tag).map(|s| s.bytes)
    }

    /// The section with this tag, or [`Malformed::MissingSection`]. For
    /// mode decoders: which sections a mode needs is the mode's business,
    /// not the container's.
    pub fn require(&self, tag: Tag) -> Result<Section<'a>, Error> {
        self.find(tag)
            .ok_or_else(|| malformed(Malformed::MissingSection { tag: tag.0 }, at::SECTION_COUNT))
    }
}

/// Iterator over a container's sections in file order.
#[derive(Clone, Debug)]
pub struct Sections<'a> {
    table: &'a [u8],
    data: &'a [u8],
    offset: usize,
}

impl<'a> Iterator for Sections<'a> {
    type Item = Section<'a>;

    fn next(&mut self) -> Option<Section<'a>> {
        let (entry, table) = self.table.split_first_chunk::<TABLE_ENTRY_LEN>()?;
        let tag = Tag([entry[0], entry[1], entry[2], entry[3]]);
        let len = LE::read_u32(&entry[4..]) as usize;
        // The parser checked every length; `get` keeps this panic-free anyway.
        let bytes = self.data.get(..len)?;
        let section = Section {
            tag,
            offset: self.offset,
            bytes,
        };
        self.table = table;
        self.data = &self.data[len..];
        self.offset += len;
        Some(section)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.table.len() / TABLE_ENTRY_LEN;
        (n, Some(n))
    }
}

impl ExactSizeIterator for Sections<'_> {}

/// Parses and checks a whole `.swm` file held in memory.
///
/// Errors, in the order they are checked:
/// - [`Malformed::Empty`], or [`Malformed::BadMagic`] when the file does
///   not start with `"SWM\0"` ([`Malformed::Truncated`] if it is a
///   shorter prefix of it);
/// - [`Malformed::ChecksumMismatch`] when the stored CRC-32 differs from
///   the computed one — any damage, including truncation — or
///   [`Malformed::TrailingData`] when a valid container is followed by
///   extra bytes;
/// - [`Error::Unsupported`] for another major version, unknown required
///   flags or an unknown mode;
/// - [`Error::LimitExceeded`] when the counts exceed `limits`;
/// - [`Malformed::BadHeader`] for inconsistent counts;
/// - per section in table order: [`Malformed::BadSectionTag`],
///   [`Error::Unsupported`] for an unknown critical tag,
///   [`Malformed::DuplicateSection`], [`Malformed::SectionOutOfBounds`];
/// - [`Malformed::TrailingData`] when the payloads stop short of the CRC.
///
/// Errors are located ([`Location::Byte`](crate::Location::Byte)) at the
/// offending field.
pub fn parse_container<'a>(bytes: &'a [u8], limits: &Limits) -> Result<Container<'a>, Error> {
    check_magic(bytes)?;
    if bytes.len() < MIN_FRAME_LEN {
        return Err(malformed(Malformed::Truncated, bytes.len()));
    }
    let crc_at = bytes.len() - CRC_LEN;
    let stored = LE::read_u32(&bytes[crc_at..]);
    let computed = crc32(&bytes[..crc_at]);
    // Fuzz builds (cargo-fuzz sets `--cfg fuzzing`) skip the checksum:
    // otherwise nearly every mutation dies here and the fuzzer never
    // reaches the section and payload parsers behind it.
    if stored != computed && !cfg!(fuzzing) {
        if let Some(end) = valid_prefix_len(bytes) {
            return Err(malformed(Malformed::TrailingData, end));
        }
        return Err(malformed(
            Malformed::ChecksumMismatch { stored, computed },
            crc_at,
        ));
    }

    let header = Header::read(bytes, limits)?;

    let table_end = table_end(bytes);
    if table_end > crc_at {
        // The table alone runs into the CRC.
        return Err(malformed(Malformed::Truncated, at::SECTION_COUNT));
    }
    let table = &bytes[at::TABLE..table_end];
    let mut end = table_end as u64;
    let mut seen_critical = 0u8;
    for (i, entry) in table.chunks_exact(TABLE_ENTRY_LEN).enumerate() {
        let entry_at = at::TABLE + i * TABLE_ENTRY_LEN;
        let tag = Tag([entry[0], entry[1], entry[2], entry[3]]);
        if !tag.is_valid() {
            return Err(malformed(Malformed::BadSectionTag { tag: tag.0 }, entry_at));
        }
        if tag.is_critical() {
            let Some(k) = KNOWN_CRITICAL.iter().position(|&t| t == tag) else {
                return Err(UnsupportedError {
                    feature: UnsupportedFeature::CriticalSection(tag.0),
                    major: header.major,
                    minor: header.minor,
                    supported_major: FORMAT_MAJOR,
                    supported_minor: FORMAT_MINOR,
                }
                .into());
            };
            if seen_critical & (1 << k) != 0 {
                return Err(malformed(
                    Malformed::DuplicateSection { tag: tag.0 },
                    entry_at,
                ));
            }
            seen_critical |= 1 << k;
        }
        // u64: a u32 length added to a usize offset cannot overflow.
        end += u64::from(LE::read_u32(&entry[4..]));
        if end > crc_at as u64 {
            return Err(malformed(
                Malformed::SectionOutOfBounds {
                    tag: tag.0,
                    end,
                    limit: crc_at as u64,
                },
                entry_at + 4,
            ));
        }
    }
    if end != crc_at as u64 {
        // Bytes between the last payload and the CRC belong to no section.
        return Err(malformed(Malformed::TrailingData, end as usize));
    }
    Ok(Container {
        header,
        table,
        data: &bytes[table_end..crc_at],
        data_offset: table_end,
    })
}

/// Where the section table ends, from the section count of a 1.x fixed
/// header (`bytes` holds at least `at::TABLE` bytes).
pub(crate) fn table_end(bytes: &[u8]) -> usize {
    at::TABLE + TABLE_ENTRY_LEN * usize::from(LE::read_u16(&bytes[at::SECTION_COUNT..]))
}

/// The length a 1.x file declares: its section table's end, the sections'
/// lengths and the CRC; `None` while the table is not all in `bytes`.
/// Unverified: the CRC vouches for it only once the whole file is in.
pub(crate) fn declared_len(bytes: &[u8]) -> Option<u64> {
    let table = bytes.get(at::TABLE..table_end(bytes))?;
    let payload: u64 = table
        .chunks_exact(TABLE_ENTRY_LEN)
        .map(|e| u64::from(LE::read_u32(&e[4..])))
        .sum();
    Some((at::TABLE + table.len()) as u64 + payload + CRC_LEN as u64)
}

/// The magic, or the error every reader of `.swm` bytes gives for it.
pub(crate) fn check_magic(bytes: &[u8]) -> Result<(), Error> {
    if bytes.is_empty() {
        return Err(malformed(Malformed::Empty, 0));
    }
    let n = bytes.len().min(MAGIC.len());
    if bytes[..n] != MAGIC[..n] {
        return Err(malformed(Malformed::BadMagic, 0));
    }
    if n < MAGIC.len() {
        return Err(malformed(Malformed::Truncated, n));
    }
    Ok(())
}

/// When the checksum fails: does a valid 1.x container end *before* the
/// end of `bytes`? Its length is implied by the (unverified) section
/// table and only trusted if the CRC found there verifies, which a
/// damaged file passes with probability 2^-32. This lets a decoder say
/// "extra bytes after the file" instead of "damaged" for a good file
/// followed by garbage. Reads only; allocates nothing.
fn valid_prefix_len(bytes: &[u8]) -> Option<usize> {
    if bytes[at::MAJOR] != FORMAT_MAJOR || bytes.len() < MIN_LEN {
        return None;
    }
    let end = usize::try_from(declared_len(bytes)?).ok()?;
    if end >= bytes.len() {
        return None;
    }
    let crc_at = end - CRC_LEN;
    (LE::read_u32(&bytes[crc_at..end]) == crc32(&bytes[..crc_at])).then_some(end)
}
