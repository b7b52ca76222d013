//! Writing the frame: header, section table, payloads, CRC-32, in the
//! framing the header's flags name (fixed, or format 1.1's compact one:
//! `compact`).
//!
//! The writer frames whatever sections it is given, in the order given,
//! and writes the header's fields as they are (so an encoder can pin an
//! older minor version, and tests can forge newer ones). It checks only
//! what would make the frame unreadable.

use crate::prelude::*;

use super::crc::crc32;
use super::header::{at, put_u16, put_u32, Framing, Header, CRC_LEN, MIN_LEN, TABLE_ENTRY_LEN};
use super::{compact, Tag};
use crate::{Error, ParameterError};

/// The exact size in bytes of the container [`write_container`] makes of
/// these sections under `header` (saturating at `usize::MAX`).
pub fn container_len(header: &Header, sections: &[(Tag, &[u8])]) -> usize {
    let payload = sections
        .iter()
        .fold(0usize, |n, (_, s)| n.saturating_add(s.len()));
    let frame = match header.framing() {
        Framing::Fixed => MIN_LEN.saturating_add(TABLE_ENTRY_LEN.saturating_mul(sections.len())),
        Framing::Compact => {
            compact::frame_len(header, sections.iter().map(|(t, s)| (*t, s.len()))) + CRC_LEN
        }
    };
    frame.saturating_add(payload)
}

/// Frames `sections` under `header` into a new buffer.
///
/// Fails with [`Error::Parameter`] when there are more than 65,535
/// sections or one is longer than `u32::MAX` bytes.
///
/// # Panics
/// If a tag is not four ASCII letters, or a critical tag appears twice:
/// both are mistakes in the calling code, never in the data.
pub fn write_container(header: &Header, sections: &[(Tag, &[u8])]) -> Result<Vec<u8>, Error> {
    let mut out = Vec::new();
    write_container_into(header, sections, &mut out)?;
    Ok(out)
}

/// Appends the container to `out` (caller-owned output) and returns the
/// number of bytes appended, [`container_len`]`(header, sections)`. On error `out`
/// is left unchanged. Errors and panics as [`write_container`].
pub fn write_container_into(
    header: &Header,
    sections: &[(Tag, &[u8])],
    out: &mut Vec<u8>,
) -> Result<usize, Error> {
    check_sections(sections)?;
    let start = out.len();
    out.reserve(container_len(header, sections));
    match header.framing() {
        Framing::Fixed => {
            header.write(out);
            debug_assert_eq!(out.len() - start, at::SECTION_COUNT);
            // Lengths and count were checked above; the casts cannot truncate.
            put_u16(out, sections.len() as u16);
            for (tag, bytes) in sections {
                out.extend_from_slice(&tag.0);
                put_u32(out, bytes.len() as u32);
            }
        }
        Framing::Compact => {
            header.write_preamble(out);
            compact::write_head(header, sections.len(), out);
            for (tag, bytes) in sections {
                compact::write_entry(*tag, bytes.len(), out);
            }
        }
    }
    for (_, bytes) in sections {
        out.extend_from_slice(bytes);
    }
    let crc = crc32(&out[start..]);
    put_u32(out, crc);
    debug_assert_eq!(out.len() - start, container_len(header, sections));
    Ok(out.len() - start)
}

/// The bare body of a mode-0 file of `header` made of `sections` (format
/// 1.2, mode 2's `BASE` when its `HEAD` says so): `varu V`, `varu T`,
/// `varu n`, the compact framing's entries, the payloads. No preamble,
/// mode, component count or CRC: the enclosing file has them (its
/// component count must be `header`'s). The mirror of
/// [`parse_bare`](super::parse_bare). Errors and panics as
/// [`write_container`].
#[cfg(feature = "encoder")]
pub(crate) fn write_bare(header: &Header, sections: &[(Tag, &[u8])]) -> Result<Vec<u8>, Error> {
    check_sections(sections)?;
    let mut out = Vec::new();
    for v in [header.vertex_count, header.triangle_count] {
        crate::varint::put(&mut out, v.into());
    }
    crate::varint::put(&mut out, sections.len() as u64);
    for (tag, bytes) in sections {
        compact::write_entry(*tag, bytes.len(), &mut out);
    }
    for (_, bytes) in sections {
        out.extend_from_slice(bytes);
    }
    Ok(out)
}

fn check_sections(sections: &[(Tag, &[u8])]) -> Result<(), Error> {
    if sections.len() > usize::from(u16::MAX) {
        return Err(out_of_range("section count", sections.len(), u16::MAX.into()).into());
    }
    for (i, (tag, bytes)) in sections.iter().enumerate() {
        assert!(
            tag.is_valid(),
            "section tag {tag:?} is not four ASCII letters"
        );
        assert!(
            !tag.is_critical() || sections[..i].iter().all(|(t, _)| t != tag),
            "critical section {tag} given twice"
        );
        if bytes.len() as u64 > u64::from(u32::MAX) {
            return Err(out_of_range("section length", bytes.len(), u32::MAX.into()).into());
        }
    }
    Ok(())
}

fn out_of_range(name: &'static str, value: usize, max: u64) -> ParameterError {
    ParameterError::OutOfRange {
        name,
        value: value as f64,
        min: 0.0,
        max: max as f64,
    }
}
