//! The GLB container (glTF 2.0 §4.4): split into its JSON and BIN chunks.
//!
//! ```text
//! header  magic "glTF" | version 2 | length          12 bytes, u32 LE
//! chunk   length | type ("JSON", "BIN\0", other) | data (length bytes)
//! ```
//!
//! The first chunk must be JSON; a BIN chunk, if any, comes second;
//! chunks of other types are skipped, as §4.4.3.1 asks of readers. Bytes
//! after the header's `length` are not part of the file and are ignored.
//!
//! Invariant: every length is checked against the bytes that remain
//! before it is used, so no length field can make a slice out of range.

use crate::{Error, FormatError, Location, Malformed, ParameterError};

pub(super) const MAGIC: &[u8; 4] = b"glTF";
pub(super) const VERSION: u32 = 2;
pub(super) const CHUNK_JSON: &[u8; 4] = b"JSON";
pub(super) const CHUNK_BIN: &[u8; 4] = b"BIN\0";
/// The file header: magic, version, total length.
pub(super) const HEADER_LEN: u64 = 12;
/// A chunk header: length, type.
pub(super) const CHUNK_HEADER_LEN: u64 = 8;

pub(super) const FORMAT: &str = "GLB";

/// The length of a GLB file whose JSON chunk holds `json` bytes and
/// whose BIN chunk, if any, `bin` (each padded to 4 here); an error when
/// it does not fit the header's u32 length field (4 GiB). What both GLB
/// writers put in the header, checked the same way.
pub(super) fn glb_length(json: u64, bin: Option<u64>) -> Result<u32, Error> {
    let chunk = |n: u64| CHUNK_HEADER_LEN.saturating_add(n.div_ceil(4).saturating_mul(4));
    let total = HEADER_LEN
        .saturating_add(chunk(json))
        .saturating_add(bin.map_or(0, chunk));
    u32::try_from(total).map_err(|_| {
        Error::Parameter(ParameterError::FileTooLarge {
            format: FORMAT,
            bytes: total,
            max: u32::MAX.into(),
        })
    })
}

/// The chunks of a GLB file.
pub(super) struct Chunks<'a> {
    pub json: &'a [u8],
    pub bin: Option<&'a [u8]>,
}

/// Whether `bytes` start as a GLB file does (a `.gltf` file is JSON text,
/// which cannot start with these letters).
pub(super) fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

fn error(what: Malformed, at: u64) -> Error {
    FormatError::new(FORMAT, what).at(Location::Byte(at)).into()
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Splits a GLB file (which starts with [`MAGIC`]) into its chunks.
pub(super) fn split(bytes: &[u8]) -> Result<Chunks<'_>, Error> {
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return Err(error(Malformed::Truncated, bytes.len() as u64));
    };
    if version != VERSION {
        // Version 1 is the binary glTF 1.0 extension, a different format.
        let what = Malformed::Unsupported("GLB versions other than 2 (glTF 2.0)");
        return Err(error(what, 4));
    }
    if u64::from(length) < HEADER_LEN {
        let what = Malformed::BadHeader("the file length is shorter than the header");
        return Err(error(what, 8));
    }
    let Some(file) = bytes.get(..length as usize) else {
        return Err(error(Malformed::Truncated, bytes.len() as u64));
    };
    let mut at = HEADER_LEN as usize;
    let mut json = None;
    let mut bin = None;
    while at < file.len() {
        let (Some(len), Some(kind)) = (u32_at(file, at), file.get(at + 4..at + 8)) else {
            return Err(error(Malformed::Truncated, file.len() as u64));
        };
        let start = at + CHUNK_HEADER_LEN as usize;
        let Some(data) = file.get(start..start.saturating_add(len as usize)) else {
            return Err(error(Malformed::Truncated, file.len() as u64));
        };
        match (json.is_some(), kind) {
            (false, k) if k == CHUNK_JSON => json = Some(data),
            (false, _) => {
                let what = Malformed::BadSyntax("the first chunk is not the JSON chunk");
                return Err(error(what, at as u64 + 4));
            }
            (true, k) if k == CHUNK_BIN && bin.is_none() => bin = Some(data),
            // Unknown chunk types, and a second BIN chunk, are not ours.
            _ => {}
        }
        at = start + data.len();
    }
    match json {
        Some(json) => Ok(Chunks { json, bin }),
        None => Err(error(Malformed::Truncated, file.len() as u64)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(version: u32, chunks: &[(&[u8; 4], &[u8])]) -> Vec<u8> {
        let mut body = Vec::new();
        for (kind, data) in chunks {
            body.extend((data.len() as u32).to_le_bytes());
            body.extend(*kind);
            body.extend(*data);
        }
        let mut out = MAGIC.to_vec();
        out.extend(version.to_le_bytes());
        out.extend((12 + body.len() as u32).to_le_bytes());
        out.extend(body);
        out
    }

    fn malformed(bytes: &[u8]) -> (Malformed, Option<Location>) {
        match split(bytes) {
            Err(Error::Format(e)) => (e.what, e.at),
            Err(e) => panic!("{e:?}"),
            Ok(_) => panic!("accepted"),
        }
    }

    #[test]
    fn chunks_are_found_and_unknown_ones_skipped() {
        let bytes = glb(
            2,
            &[(b"JSON", b"{}  "), (b"BIN\0", b"abcd"), (b"XTRA", b"zz")],
        );
        let c = split(&bytes).unwrap();
        assert_eq!((c.json, c.bin), (&b"{}  "[..], Some(&b"abcd"[..])));
        let json_only = glb(2, &[(b"JSON", b"{}  ")]);
        assert_eq!(split(&json_only).unwrap().bin, None);
        // Bytes past the header's length are not part of the file.
        let mut longer = bytes.clone();
        longer.extend(b"junk");
        assert_eq!(split(&longer).unwrap().bin, Some(&b"abcd"[..]));
    }

    #[test]
    fn every_truncation_is_an_error() {
        let bytes = glb(2, &[(b"JSON", b"{}  "), (b"BIN\0", b"abcd")]);
        for cut in 0..bytes.len() {
            let what = malformed(&bytes[..cut]).0;
            assert_eq!(what, Malformed::Truncated, "cut at {cut}");
        }
    }

    #[test]
    fn bad_headers() {
        let mut short = glb(2, &[(b"JSON", b"{}  ")]);
        short[8..12].copy_from_slice(&3u32.to_le_bytes());
        assert!(matches!(malformed(&short).0, Malformed::BadHeader(_)));
        let v1 = glb(1, &[(b"JSON", b"{}  ")]);
        assert!(matches!(malformed(&v1).0, Malformed::Unsupported(_)));
        let bin_first = glb(2, &[(b"BIN\0", b"abcd"), (b"JSON", b"{}  ")]);
        assert_eq!(malformed(&bin_first).1, Some(Location::Byte(16)));
        // A chunk length that would overflow a usize on 32-bit targets.
        let mut huge = glb(2, &[(b"JSON", b"{}  ")]);
        huge[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        assert_eq!(malformed(&huge).0, Malformed::Truncated);
    }
}
