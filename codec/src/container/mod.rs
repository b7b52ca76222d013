//! The `.swm` container, format versions 1.0 and 1.1: the framing every
//! coding mode writes into (normative text: `format-spec/01-container.md`).
//!
//! ```text
//! "SWM\0" major minor flags | mode vertices triangles components | n | n × (tag, length) | payloads | CRC-32
//! ```
//!
//! Two framings write these fields: the fixed one of 1.0 (`u32` counts,
//! eight-byte entries) and 1.1's compact one (flag bit 0: varints and
//! one-byte tag codes), which makes a small file mostly payload.
//!
//! The container knows nothing about how a section is coded. It frames
//! sections, checks the frame, and refuses a file before anything sized by
//! the file is allocated: parsing allocates nothing at all and hands out
//! borrowed slices of the input.
//!
//! Sources:
//! - Critical versus ancillary sections follow PNG's chunk naming
//!   convention (PNG specification, 3rd ed., §5.4 "Chunk naming
//!   conventions"): an upper-case first letter marks a section a decoder
//!   must understand, a lower-case one a section it may skip.
//! - The checksum is the CRC-32 of zlib and PNG (ISO 3309 / ITU-T V.42,
//!   reflected polynomial `0xEDB88320`), as in RFC 1952 §8 and the PNG
//!   specification's sample CRC code (Annex D).
//! - Versioning follows meshoptimizer's rule (decode every version up to
//!   one's own) and image-png's `Limits` for untrusted input.
//!
//! One concern per file: `crc` (checksum), `tag` (section names and the
//! 1.0 registry), `header` (magic, format version, flags, fixed fields
//! and limit checks),
//! `write` and `read` (the frame), `compact` (the compact framing's
//! fields), `count` (the "count cannot fit" rule),
//! `meta` (the `meta` key/value section).

mod compact;
mod count;
mod crc;
mod header;
mod meta;
mod read;
mod tag;
mod write;

#[cfg(test)]
mod tests;
#[cfg(all(test, feature = "encoder"))]
mod tests_bare;
#[cfg(test)]
mod tests_compact;

/// Rewrites the trailing CRC so that a mutation reaches the decoder
/// proper instead of stopping at the checksum (mode tests).
#[cfg(all(test, feature = "encoder"))]
pub(crate) fn fix_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crc32(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

/// A copy of `bytes` with one to four random bytes overwritten (never in
/// the CRC) and the CRC fixed (mode tests).
#[cfg(all(test, feature = "encoder"))]
pub(crate) fn overwrite_randomly(bytes: &[u8], rng: &mut crate::mesh::test_rng::Rng) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for _ in 0..1 + rng.next_u64() % 4 {
        let at = (rng.next_u64() % (b.len() as u64 - 4)) as usize;
        b[at] = rng.next_u64() as u8;
    }
    fix_crc(&mut b);
    b
}

/// Asserts that `decode` refuses every copy of `bytes` with one bit
/// flipped and, when `cuts`, every proper prefix of it (mode tests).
#[cfg(all(test, feature = "encoder"))]
pub(crate) fn assert_damage_refused<T, E>(
    bytes: &[u8],
    cuts: bool,
    decode: impl Fn(&[u8]) -> Result<T, E>,
) {
    if cuts {
        for cut in 0..bytes.len() {
            assert!(decode(&bytes[..cut]).is_err(), "prefix {cut} decoded");
        }
    }
    for bit in 0..bytes.len() * 8 {
        let mut b = bytes.to_vec();
        b[bit / 8] ^= 1 << (bit % 8);
        assert!(decode(&b).is_err(), "bit {bit} flipped and still decoded");
    }
}

/// Rebuilds `bytes` with one section's payload replaced, keeping a valid
/// frame and CRC: the mode tests use it to feed decoders lying sections.
#[cfg(all(test, feature = "encoder"))]
pub(crate) fn with_section(bytes: &[u8], tag: Tag, payload: &[u8]) -> Vec<u8> {
    let file = parse_container(bytes, &crate::Limits::default()).unwrap();
    let owned: Vec<(Tag, Vec<u8>)> = file
        .sections()
        .map(|s| {
            let b = if s.tag == tag { payload } else { s.bytes };
            (s.tag, b.to_vec())
        })
        .collect();
    let refs: Vec<(Tag, &[u8])> = owned.iter().map(|(t, b)| (*t, b.as_slice())).collect();
    write_container(&file.header, &refs).unwrap()
}

/// The same file in the other framing (same sections, same version
/// otherwise): tests compare what each framing costs and check that
/// decoders read both alike.
#[cfg(all(test, feature = "encoder"))]
pub(crate) fn reframe(bytes: &[u8], framing: Framing) -> Vec<u8> {
    let file = parse_container(bytes, &crate::Limits::default()).unwrap();
    let refs: Vec<(Tag, &[u8])> = file.sections().map(|s| (s.tag, s.bytes)).collect();
    write_container(&file.header.with_framing(framing), &refs).unwrap()
}

pub use crate::error::{UnsupportedError, UnsupportedFeature};
pub(crate) use compact::{read_head as read_compact_head, Scan};
pub use count::check_count_fits;
pub use crc::{crc32, Crc32};
pub(crate) use header::check_version_and_flags;
pub(crate) use header::{malformed, MIN_LEN};
pub use header::{
    Framing, Header, Mode, FLAGS_OPTIONAL, FLAGS_REQUIRED, FLAG_COMPACT, FORMAT_MAJOR,
    FORMAT_MINOR, KNOWN_FLAGS, MAGIC,
};
pub use meta::{meta_entries, write_meta, MetaEntries, MetaEntry};
pub(crate) use read::{
    check_magic, declared_len, declared_sections, in_section, parse_bare, table_end, TableCheck,
};
pub use read::{parse_container, Container, Section, Sections};
pub use tag::Tag;
pub(crate) use tag::KNOWN_CRITICAL;
#[cfg(feature = "encoder")]
pub(crate) use write::write_bare;
pub use write::{container_len, write_container, write_container_into};
