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
//!
//! Steps 3 and 4 read the fixed framing or the compact one (`compact`),
//! as the flags say; the checks on each entry are the same.

use super::compact::{self, Scan};
use super::crc::crc32;
use super::header::{
    at, check_version_and_flags, malformed, unsupported, Framing, Header, CRC_LEN, FLAG_COMPACT,
    FORMAT_MAJOR, MAGIC, MIN_FRAME_LEN, MIN_LEN, TABLE_ENTRY_LEN,
};
use super::tag::KNOWN_CRITICAL;
use super::{Tag, UnsupportedFeature};
use crate::{Error, Limits, Malformed};
use byteorder::{ByteOrder, LittleEndian as LE};

/// A parsed container: the header and borrowed section payloads
/// (zero-copy; nothing is allocated).
#[derive(Clone, Copy, Debug)]
pub struct Container<'a> {
    /// The fixed header, checked against the limits.
    pub header: Header,
    /// The section table's entries, in the header's framing.
    table: &'a [u8],
    /// Number of entries.
    count: usize,
    /// File offset of `table` (where the section-table errors point).
    table_offset: usize,
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
            header: self.header,
            table: self.table,
            left: self.count,
            data: self.data,
            offset: self.data_offset,
        }
    }

    /// Number of sections.
    pub fn section_count(&self) -> usize {
        self.count
    }

    /// Bytes of the file before the first payload: preamble, header and
    /// section table (what the framing costs, with the CRC's four).
    pub fn frame_len(&self) -> usize {
        self.data_offset
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
            .ok_or_else(|| malformed(Malformed::MissingSection { tag: tag.0 }, self.table_offset))
    }
}

/// Iterator over a container's sections in file order.
#[derive(Clone, Debug)]
pub struct Sections<'a> {
    header: Header,
    table: &'a [u8],
    left: usize,
    data: &'a [u8],
    offset: usize,
}

impl<'a> Iterator for Sections<'a> {
    type Item = Section<'a>;

    fn next(&mut self) -> Option<Section<'a>> {
        if self.left == 0 {
            return None;
        }
        // The parser checked every entry; `?` and `get` keep this
        // panic-free anyway.
        let (tag, len, table) = if self.header.framing() == Framing::Compact {
            match compact::read_entry(self.table, 0, &self.header).ok()? {
                Scan::Done(e) => (e.tag, e.len as usize, &self.table[e.end..]),
                Scan::Need(_) => return None,
            }
        } else {
            let (entry, table) = self.table.split_first_chunk::<TABLE_ENTRY_LEN>()?;
            let tag = Tag([entry[0], entry[1], entry[2], entry[3]]);
            (tag, LE::read_u32(&entry[4..]) as usize, table)
        };
        let bytes = self.data.get(..len)?;
        let section = Section {
            tag,
            offset: self.offset,
            bytes,
        };
        self.table = table;
        self.left -= 1;
        self.data = &self.data[len..];
        self.offset += len;
        Some(section)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for Sections<'_> {}

/// Checks what every 1.x file has at the same place before its layout can
/// differ: the major version, then the required flags (one of which
/// selects the framing), then the file's length against the framing's
/// smallest file. Returns the flags. `bytes` holds at least
/// [`MIN_FRAME_LEN`] bytes.
fn check_preamble(bytes: &[u8]) -> Result<u16, Error> {
    let flags = check_version_and_flags(bytes)?;
    let min = if flags & FLAG_COMPACT != 0 {
        compact::MIN_COMPACT_LEN
    } else {
        MIN_LEN
    };
    if bytes.len() < min {
        return Err(malformed(Malformed::Truncated, bytes.len()));
    }
    Ok(flags)
}

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

    let flags = check_preamble(bytes)?;
    let frame = if flags & FLAG_COMPACT != 0 {
        match compact::read_head(&bytes[..crc_at], limits)? {
            Scan::Done(h) => Frame {
                header: h.header,
                count: h.count,
                table: h.table,
            },
            // The header runs into the CRC.
            Scan::Need(_) => return Err(malformed(Malformed::Truncated, crc_at)),
        }
    } else {
        let header = Header::read(bytes, limits)?;
        let count = usize::from(LE::read_u16(&bytes[at::SECTION_COUNT..]));
        if table_end(bytes) > crc_at {
            // The table alone runs into the CRC.
            return Err(malformed(Malformed::Truncated, at::SECTION_COUNT));
        }
        Frame {
            header,
            count,
            table: at::TABLE,
        }
    };
    framed(bytes, crc_at, frame)
}

/// The sections of a bare mode-0 body (format 1.2, mode 2's `BASE` when
/// its `HEAD` says so): its head ([`compact::read_bare_head`]: vertex and
/// triangle counts, section count; the version and component count are
/// `enclosing`'s), then its table and payloads checked as a compact
/// file's, the payloads filling the body exactly. Errors are located
/// within `body` (the caller moves them to the section's offset). The
/// enclosing file's CRC covers the body: it has none of its own.
/// [`write_bare`](super::write_bare) is the mirror.
pub(crate) fn parse_bare<'a>(
    body: &'a [u8],
    enclosing: &Header,
    limits: &Limits,
) -> Result<Container<'a>, Error> {
    let h = compact::read_bare_head(body, enclosing, limits)?;
    let frame = Frame {
        header: h.header,
        count: h.count,
        table: h.table,
    };
    framed(body, body.len(), frame)
}

/// The container whose checked header `frame` gives, its table and
/// payloads in `bytes` before `crc_at` (the CRC's offset, or the end of
/// a bare body): every entry checked, and the payloads filling the space
/// up to `crc_at` exactly.
fn framed(bytes: &[u8], crc_at: usize, frame: Frame) -> Result<Container<'_>, Error> {
    // The table's end: known from the count in the fixed framing; in the
    // compact one, found by reading the entries once (checking each alone:
    // codes, tags, criticality, duplicates) before their lengths are
    // added up from it.
    let table_end = if frame.header.framing() == Framing::Compact {
        let mut scan = TableCheck::unbounded(&frame.header);
        let mut pos = frame.table;
        for _ in 0..frame.count {
            pos = scan.entry(&bytes[..crc_at], pos, &frame.header)?;
        }
        pos
    } else {
        frame.table + TABLE_ENTRY_LEN * frame.count
    };
    let mut table = TableCheck {
        base: Some(table_end),
        limit: crc_at as u64,
        ..TableCheck::unbounded(&frame.header)
    };
    let mut pos = frame.table;
    for _ in 0..frame.count {
        pos = table.entry(&bytes[..crc_at], pos, &frame.header)?;
    }
    debug_assert_eq!(pos, table_end);
    let end = pos as u64 + table.payload;
    if end != crc_at as u64 {
        // Bytes between the last payload and the CRC belong to no section.
        return Err(malformed(Malformed::TrailingData, end as usize));
    }
    Ok(Container {
        header: frame.header,
        table: &bytes[frame.table..pos],
        count: frame.count,
        table_offset: frame.table,
        data: &bytes[pos..crc_at],
        data_offset: pos,
    })
}

/// A checked header, its section count and where its table starts.
struct Frame {
    header: Header,
    count: usize,
    table: usize,
}

/// The checks on the section table's entries, one entry at a time, for
/// either framing: tags, criticality, duplicates, and that the payloads
/// stay before the CRC. The stream decoder runs it as the table arrives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TableCheck {
    compact: bool,
    seen_critical: u16,
    /// Sum of the lengths so far.
    pub(crate) payload: u64,
    /// Where the table ends, when known; otherwise the end of the entry
    /// being checked stands in for it, a lower bound.
    base: Option<usize>,
    /// The most the table and payloads may reach: the CRC's offset, or
    /// `u64::MAX` while the file's length is not known.
    limit: u64,
}

impl TableCheck {
    /// A check for a file whose length is not known yet.
    pub(crate) fn unbounded(header: &Header) -> Self {
        TableCheck {
            compact: header.framing() == Framing::Compact,
            seen_critical: 0,
            payload: 0,
            base: None,
            limit: u64::MAX,
        }
    }

    /// Checks the entry at `pos` of a table that `bytes` holds whole and
    /// returns the offset after it.
    fn entry(&mut self, bytes: &[u8], pos: usize, header: &Header) -> Result<usize, Error> {
        match self.try_entry(bytes, pos, header)? {
            Scan::Done(next) => Ok(next),
            // The table runs into the CRC.
            Scan::Need(_) => Err(malformed(Malformed::Truncated, pos)),
        }
    }

    /// Checks the entry at `pos` if `bytes` holds it: the offset after it,
    /// or the prefix length needed to go on.
    pub(crate) fn try_entry(
        &mut self,
        bytes: &[u8],
        pos: usize,
        header: &Header,
    ) -> Result<Scan<usize>, Error> {
        let (tag, len, len_at, next) = if self.compact {
            match compact::read_entry(bytes, pos, header)? {
                Scan::Done(e) => (e.tag, e.len, e.len_at, e.end),
                Scan::Need(n) => return Ok(Scan::Need(n)),
            }
        } else {
            let Some(entry) = bytes.get(pos..pos + TABLE_ENTRY_LEN) else {
                return Ok(Scan::Need(pos + TABLE_ENTRY_LEN));
            };
            let tag = Tag([entry[0], entry[1], entry[2], entry[3]]);
            if !tag.is_valid() {
                return Err(malformed(Malformed::BadSectionTag { tag: tag.0 }, pos));
            }
            (
                tag,
                LE::read_u32(&entry[4..]),
                pos + 4,
                pos + TABLE_ENTRY_LEN,
            )
        };
        if tag.is_critical() {
            let Some(k) = KNOWN_CRITICAL.iter().position(|&t| t == tag) else {
                let feature = UnsupportedFeature::CriticalSection(tag.0);
                return Err(unsupported(feature, header.major, header.minor));
            };
            if self.seen_critical & (1 << k) != 0 {
                return Err(malformed(Malformed::DuplicateSection { tag: tag.0 }, pos));
            }
            self.seen_critical |= 1 << k;
        }
        // u64: a u32 length added to the sum cannot overflow.
        self.payload += u64::from(len);
        let end = self.base.unwrap_or(next) as u64 + self.payload;
        if end > self.limit {
            return Err(malformed(
                Malformed::SectionOutOfBounds {
                    tag: tag.0,
                    end,
                    limit: self.limit,
                },
                len_at,
            ));
        }
        Ok(Scan::Done(next))
    }
}

/// Where the section table ends, from the section count of a 1.x fixed
/// header (`bytes` holds at least `at::TABLE` bytes).
pub(crate) fn table_end(bytes: &[u8]) -> usize {
    at::TABLE + TABLE_ENTRY_LEN * usize::from(LE::read_u16(&bytes[at::SECTION_COUNT..]))
}

/// The length a 1.x file declares: its section table's end, the sections'
/// lengths and the CRC; `None` while the table is not all in `bytes`.
/// Unverified: the CRC vouches for it only once the whole file is in.
/// Reads either framing (a compact table entry by entry, so this is
/// linear in the table); allocates nothing.
pub(crate) fn declared_len(bytes: &[u8]) -> Option<u64> {
    let mut payload = 0u64;
    let end = declared_sections(bytes, |_, len| payload += u64::from(len))?;
    Some(end as u64 + payload + CRC_LEN as u64)
}

/// Calls `each` with every section's tag and length in file order (the
/// payloads follow the table back to back) and returns where the table
/// ends; `None` while the table is not all in `bytes` (`each` may have
/// seen some entries). Unverified, as [`declared_len`]: the stream
/// decoder reads sections by it before the CRC is in.
pub(crate) fn declared_sections(bytes: &[u8], mut each: impl FnMut(Tag, u32)) -> Option<usize> {
    let flags = LE::read_u16(bytes.get(at::FLAGS..at::MODE)?);
    if flags & FLAG_COMPACT == 0 {
        bytes.get(..at::TABLE)?;
        let table = bytes.get(at::TABLE..table_end(bytes))?;
        for e in table.chunks_exact(TABLE_ENTRY_LEN) {
            each(Tag([e[0], e[1], e[2], e[3]]), LE::read_u32(&e[4..]));
        }
        return Some(at::TABLE + table.len());
    }
    let Ok(Scan::Done(h)) = compact::read_head(bytes, &Limits::UNLIMITED) else {
        return None;
    };
    let mut pos = h.table;
    for _ in 0..h.count {
        let Ok(Scan::Done(e)) = compact::read_entry(bytes, pos, &h.header) else {
            return None;
        };
        each(e.tag, e.len);
        pos = e.end;
    }
    Some(pos)
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
    if bytes[at::MAJOR] != FORMAT_MAJOR || bytes.len() < compact::MIN_COMPACT_LEN {
        return None;
    }
    let end = usize::try_from(declared_len(bytes)?).ok()?;
    if end >= bytes.len() {
        return None;
    }
    let crc_at = end - CRC_LEN;
    (LE::read_u32(&bytes[crc_at..end]) == crc32(&bytes[..crc_at])).then_some(end)
}

/// Locates an error found inside a section whose payload starts at file
/// offset `offset` (a file nested in `BASE` or `REST` counts from its
/// own start): an offset within the payload moves by `offset`, an
/// unlocated error is put at the payload's start.
pub(crate) fn in_section(offset: usize) -> impl Fn(Error) -> Error {
    move |e| match e {
        Error::Format(mut f) => {
            let inner = match f.at {
                Some(crate::Location::Byte(b)) => b,
                _ => 0,
            };
            f.at = Some(crate::Location::Byte(inner.saturating_add(offset as u64)));
            Error::Format(f)
        }
        other => other,
    }
}
