//! The compact framing of format 1.1 (`format-spec/01-container.md`,
//! "Compact framing"): the same header fields and section table as the
//! fixed framing, written with varints and one-byte tag codes.
//!
//! A file that sets the required flag bit 0 ([`FLAG_COMPACT`](super::header::FLAG_COMPACT)) lays out
//! everything between its flags and its first payload this way:
//!
//! ```text
//!  0      4     5     6       8      9
//!  | magic | major | minor | flags | mode | varu V | varu T | varu C | varu n |
//!  | n entries: code u8 [tag bytes[4] when code = 0] varu length | payloads | CRC-32 |
//! ```
//!
//! Why: the fixed framing spends 23 bytes on its header, 8 per section and
//! 4 on the CRC, 59 bytes for a four-section file; at 1 bit per vertex a
//! 500-vertex mesh has 63 bytes in all (issue 20, "small files"). Compact
//! framing spends 8 + 5 + 2 per section + 4, about 25 bytes, on the same
//! facts. The magic, version, flags and trailing CRC stay where every
//! version keeps them, so a decoder still checks the CRC and names the
//! version before it reads anything else, and a 1.0 decoder rejects the
//! file as *unsupported* (an unknown required flag) rather than
//! misreading it.
//!
//! Invariants: every varu is in its shortest form (a longer one is
//! malformed), so a file has one framing byte string; the parser reads a
//! prefix and says how much more it needs, never reading past the bytes
//! it was given, so the stream decoder and the whole-file parser share it;
//! nothing here allocates.

use crate::prelude::*;

use super::header::{malformed, read_mode, unsupported, Header};
use super::tag::Tag;
use super::UnsupportedFeature;
use crate::varint::Reader;
use crate::{Error, Limits, Malformed};

/// Offset of the mode byte, the first byte the framings lay out
/// differently after it.
pub(crate) const MODE_AT: usize = 8;

/// Smallest compact file: preamble, mode, three one-byte counts, a
/// one-byte section count, the CRC.
pub(crate) const MIN_COMPACT_LEN: usize = MODE_AT + 1 + 3 + 1 + super::header::CRC_LEN;

/// Registered tags and their codes: code `k` (1..=17) is `CODES[k − 1]`
/// (15, 16 and 17, `BASE`, `DISP` and `ATTR`, registered by format 1.2).
/// Code 0 announces a literal four-byte tag; codes 18–255 are reserved
/// for tags later versions register, and a decoder that meets one cannot
/// tell whether the section is critical, so it rejects the file as
/// unsupported.
pub(crate) const CODES: [Tag; 17] = [
    Tag::HEAD,
    Tag::CLRS,
    Tag::TOPO,
    Tag::GEOM,
    Tag::HOLE,
    Tag::REST,
    Tag::DENS,
    Tag::CLRF,
    Tag::META,
    Tag::LOOP,
    Tag::POST,
    Tag::RADS,
    Tag::GEOF,
    Tag::CLRD,
    Tag::BASE,
    Tag::DISP,
    Tag::ATTR,
];

/// The one-byte code of a registered tag.
pub(crate) fn code_of(tag: Tag) -> Option<u8> {
    CODES.iter().position(|&t| t == tag).map(|k| k as u8 + 1)
}

/// The result of reading a prefix: done, or the prefix length at which
/// reading can go on (at least one byte more than was given).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scan<T> {
    Done(T),
    Need(usize),
}

/// Reads the shortest-form varu at `*pos`, at most `max`. `Ok(None)`: the
/// prefix ends inside it.
fn varu(bytes: &[u8], pos: &mut usize, max: u64) -> Result<Option<u64>, Error> {
    let start = *pos;
    let rest = bytes.get(start..).unwrap_or_default();
    let mut reader = Reader::new(rest);
    match reader.varu() {
        Ok(v) => {
            let len = rest.len() - reader.remaining();
            // More bytes than the value needs (a last group of zero after
            // the first) is not the shortest form.
            if len != varu_len(v) || v > max {
                return Err(malformed(Malformed::BadNumber, start));
            }
            *pos = start + len;
            Ok(Some(v))
        }
        Err(e) if e.what == Malformed::Truncated => Ok(None),
        Err(_) => Err(malformed(Malformed::BadNumber, start)),
    }
}

/// The header fields of a compact file and where its table starts.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CompactHead {
    pub header: Header,
    /// Number of section table entries.
    pub count: usize,
    /// Offset of the first entry.
    pub table: usize,
}

/// Reads and checks the header of a compact file (its flags set
/// [`FLAG_COMPACT`](super::header::FLAG_COMPACT), its magic, version and required flags were checked):
/// mode, counts against `limits` and each other, section count.
pub(crate) fn read_head(bytes: &[u8], limits: &Limits) -> Result<Scan<CompactHead>, Error> {
    let (major, minor, flags) = (bytes[4], bytes[5], u16::from_le_bytes([bytes[6], bytes[7]]));
    let Some(&code) = bytes.get(MODE_AT) else {
        return Ok(Scan::Need(MODE_AT + 1));
    };
    let mode = read_mode(code, major, minor)?;
    let mut pos = MODE_AT + 1;
    let mut at = [0usize; 3];
    let mut counts = [0u32; 3];
    for (k, c) in counts.iter_mut().enumerate() {
        at[k] = pos;
        match count(bytes, &mut pos, k, limits)? {
            Some(v) => *c = v,
            None => return Ok(Scan::Need(bytes.len() + 1)),
        }
    }
    let header = Header {
        major,
        minor,
        flags,
        mode,
        vertex_count: counts[0],
        triangle_count: counts[1],
        component_count: counts[2],
    };
    super::header::check_counts(&header, [at[0], at[1], at[2]])?;
    let Some(count) = varu(bytes, &mut pos, u16::MAX.into())? else {
        return Ok(Scan::Need(bytes.len() + 1));
    };
    Ok(Scan::Done(CompactHead {
        header,
        count: count as usize,
        table: pos,
    }))
}

/// Reads and checks the head of a bare mode-0 body (format 1.2: mode 2's
/// `BASE` when its `HEAD` says so, format-spec/07-displaced.md): `varu V`,
/// `varu T`, `varu n`, then the entries as in a compact file. The version
/// and the component count are the enclosing file's, the mode is 0 and
/// the framing compact; the counts are checked against `limits` and each
/// other as a compact file's. The body is whole: a body that ends inside
/// its head is truncated.
pub(crate) fn read_bare_head(
    bytes: &[u8],
    enclosing: &Header,
    limits: &Limits,
) -> Result<CompactHead, Error> {
    let mut pos = 0;
    let mut counts = [0u32; 2];
    let mut at = [0usize; 3];
    for (k, c) in counts.iter_mut().enumerate() {
        at[k] = pos;
        *c = count(bytes, &mut pos, k, limits)?
            .ok_or_else(|| malformed(Malformed::Truncated, bytes.len()))?;
    }
    at[2] = pos;
    let header = Header {
        major: enclosing.major,
        minor: enclosing.minor,
        flags: super::header::FLAG_COMPACT,
        mode: super::header::Mode::Lossless,
        vertex_count: counts[0],
        triangle_count: counts[1],
        component_count: enclosing.component_count,
    };
    super::header::check_counts(&header, at)?;
    let Some(count) = varu(bytes, &mut pos, u16::MAX.into())? else {
        return Err(malformed(Malformed::Truncated, bytes.len()));
    };
    Ok(CompactHead {
        header,
        count: count as usize,
        table: pos,
    })
}

/// Reads header count `k` (0: vertices, 1: triangles, 2: components) at
/// `*pos`, a shortest-form varu of at most 2^32 − 1, and checks it
/// against `limits` as soon as it is known, as the fixed framing does
/// once its header is in. `Ok(None)`: the prefix ends inside it.
fn count(bytes: &[u8], pos: &mut usize, k: usize, limits: &Limits) -> Result<Option<u32>, Error> {
    let Some(v) = varu(bytes, pos, u32::MAX.into())? else {
        return Ok(None);
    };
    match k {
        0 => limits.check_vertices(v)?,
        1 => limits.check_faces(v)?,
        _ => {}
    }
    Ok(Some(v as u32))
}

/// One section table entry of a compact file.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Entry {
    pub tag: Tag,
    pub len: u32,
    /// Offset of its length.
    pub len_at: usize,
    /// Offset of the byte after the entry.
    pub end: usize,
}

/// Reads the entry at `pos`. Checks what the entry alone can show: a
/// reserved code (*unsupported*), a literal tag that is not four letters,
/// a length that is not a shortest-form varu of at most 2^32 − 1.
/// Criticality, duplicates and bounds are the caller's, as for the fixed
/// framing.
pub(crate) fn read_entry(bytes: &[u8], pos: usize, header: &Header) -> Result<Scan<Entry>, Error> {
    let need = || Ok(Scan::Need(bytes.len() + 1));
    let Some(&code) = bytes.get(pos) else {
        return need();
    };
    let (tag, mut p) = match code {
        0 => {
            let Some(b) = bytes.get(pos + 1..pos + 5) else {
                return need();
            };
            let tag = Tag([b[0], b[1], b[2], b[3]]);
            if !tag.is_valid() {
                return Err(malformed(Malformed::BadSectionTag { tag: tag.0 }, pos + 1));
            }
            (tag, pos + 5)
        }
        c if usize::from(c) <= CODES.len() => (CODES[usize::from(c) - 1], pos + 1),
        c => {
            let feature = UnsupportedFeature::SectionCode(c);
            return Err(unsupported(feature, header.major, header.minor));
        }
    };
    let len_at = p;
    let Some(len) = varu(bytes, &mut p, u32::MAX.into())? else {
        return need();
    };
    Ok(Scan::Done(Entry {
        tag,
        len: len as u32,
        len_at,
        end: p,
    }))
}

/// Appends the compact header: mode, counts, section count (the preamble
/// is the caller's).
pub(crate) fn write_head(header: &Header, sections: usize, out: &mut Vec<u8>) {
    out.push(header.mode.code());
    for v in [
        header.vertex_count,
        header.triangle_count,
        header.component_count,
    ] {
        crate::varint::put(out, v.into());
    }
    crate::varint::put(out, sections as u64);
}

/// Appends one compact table entry.
pub(crate) fn write_entry(tag: Tag, len: usize, out: &mut Vec<u8>) {
    match code_of(tag) {
        Some(c) => out.push(c),
        None => {
            out.push(0);
            out.extend_from_slice(&tag.0);
        }
    }
    crate::varint::put(out, len as u64);
}

/// Bytes of a varu.
pub(crate) fn varu_len(v: u64) -> usize {
    (64 - (v | 1).leading_zeros() as usize).div_ceil(7)
}

/// Bytes of the compact header and table for these counts and sections.
pub(crate) fn frame_len(header: &Header, sections: impl Iterator<Item = (Tag, usize)>) -> usize {
    let counts = [
        header.vertex_count,
        header.triangle_count,
        header.component_count,
    ];
    let mut n = MODE_AT + 1 + counts.iter().map(|&c| varu_len(c.into())).sum::<usize>();
    let mut k = 0u64;
    for (tag, len) in sections {
        k += 1;
        n += 1 + if code_of(tag).is_some() { 0 } else { 4 } + varu_len(len as u64);
    }
    n + varu_len(k)
}
