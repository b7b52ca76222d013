//! The ancillary `meta` section: key/value pairs about the file (which
//! encoder wrote it, with what settings) that no decoder needs.
//!
//! Each entry is `u8 key_len, bytes[key_len] key, u32 value_len,
//! bytes[value_len] value`, back to back until the section ends. Keys are
//! 1 to 255 printable ASCII characters without spaces; values are bytes,
//! UTF-8 text unless the key's definition says otherwise.

use crate::prelude::*;

use super::header::{put_u32, FORMAT_NAME};
use super::read::Section;
use crate::{FormatError, Location, Malformed};
use byteorder::{ByteOrder, LittleEndian as LE};

/// One key/value entry of a `meta` section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MetaEntry<'a> {
    /// The key: 1 to 255 printable ASCII characters, no spaces.
    pub key: &'a str,
    /// The value.
    pub value: &'a [u8],
}

impl MetaEntry<'_> {
    /// Is `key` a valid key: 1 to 255 bytes, each `!`..=`~`?
    pub fn is_valid_key(key: &str) -> bool {
        (1..=255).contains(&key.len()) && key.bytes().all(|b| b.is_ascii_graphic())
    }
}

/// The entries of a `meta` section, in order. After the first malformed
/// entry the iterator yields that error and stops.
pub fn meta_entries<'a>(section: &Section<'a>) -> MetaEntries<'a> {
    MetaEntries {
        rest: section.bytes,
        offset: section.offset,
        failed: false,
    }
}

/// Iterator over the entries of a `meta` section.
#[derive(Clone, Debug)]
pub struct MetaEntries<'a> {
    rest: &'a [u8],
    offset: usize,
    failed: bool,
}

impl<'a> Iterator for MetaEntries<'a> {
    type Item = Result<MetaEntry<'a>, FormatError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed || self.rest.is_empty() {
            return None;
        }
        let entry = self.entry();
        self.failed = entry.is_err();
        Some(entry)
    }
}

impl<'a> MetaEntries<'a> {
    fn entry(&mut self) -> Result<MetaEntry<'a>, FormatError> {
        let start = self.offset;
        let bad =
            |what, at: usize| FormatError::new(FORMAT_NAME, what).at(Location::Byte(at as u64));
        let key_len = usize::from(self.rest[0]);
        let key = self
            .rest
            .get(1..1 + key_len)
            .ok_or(bad(Malformed::Truncated, start))?;
        let key = core::str::from_utf8(key)
            .ok()
            .filter(|k| MetaEntry::is_valid_key(k))
            .ok_or(bad(
                Malformed::BadSyntax("a meta key must be 1 to 255 printable ASCII characters"),
                start,
            ))?;
        let len_at = 1 + key_len;
        let value_len = self
            .rest
            .get(len_at..len_at + 4)
            .map(LE::read_u32)
            .ok_or(bad(Malformed::Truncated, start + len_at))?;
        let value_at = len_at + 4;
        // u64 so that a huge length cannot wrap on 32-bit targets.
        let value_end = value_at as u64 + u64::from(value_len);
        if value_end > self.rest.len() as u64 {
            return Err(bad(Malformed::Truncated, start + len_at));
        }
        let value_end = value_end as usize;
        let value = &self.rest[value_at..value_end];
        self.rest = &self.rest[value_end..];
        self.offset += value_end;
        Ok(MetaEntry { key, value })
    }
}

/// Encodes entries as a `meta` section payload.
///
/// # Panics
/// If a key is not [valid](MetaEntry::is_valid_key) or a value is longer
/// than `u32::MAX` bytes; callers passing user-supplied keys check them
/// first.
pub fn write_meta(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut out = Vec::new();
    for (key, value) in entries {
        assert!(MetaEntry::is_valid_key(key), "invalid meta key {key:?}");
        let len = u32::try_from(value.len()).expect("meta value longer than u32::MAX bytes");
        out.push(key.len() as u8);
        out.extend_from_slice(key.as_bytes());
        put_u32(&mut out, len);
        out.extend_from_slice(value);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::container::Tag;

    fn section(bytes: &[u8]) -> Section<'_> {
        Section {
            tag: Tag::META,
            offset: 100,
            bytes,
        }
    }

    #[test]
    fn round_trip() {
        let bytes = write_meta(&[("generator", b"swm 0.1.0"), ("empty", b"")]);
        let got: Vec<_> = meta_entries(&section(&bytes))
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(
            got,
            [
                MetaEntry {
                    key: "generator",
                    value: b"swm 0.1.0"
                },
                MetaEntry {
                    key: "empty",
                    value: b""
                }
            ]
        );
        assert_eq!(meta_entries(&section(&[])).count(), 0);
    }

    #[test]
    fn every_truncation_fails_once() {
        let bytes = write_meta(&[("a", b"xyz"), ("bc", b"")]);
        let whole = bytes.len();
        // Entry boundaries: after "a" (1+1+4+3 = 9) and at the end.
        for n in 0..whole {
            let items: Vec<_> = meta_entries(&section(&bytes[..n])).collect();
            let errors = items.iter().filter(|r| r.is_err()).count();
            assert_eq!(errors, usize::from(n != 0 && n != 9), "prefix {n}");
            if errors == 1 {
                assert!(items.last().unwrap().is_err(), "the error comes last");
            }
        }
    }

    #[test]
    fn bad_keys() {
        for bytes in [
            &[0u8, 0, 0, 0, 0][..],
            b"\x02a \0\0\0\0",
            b"\x01\xff\0\0\0\0",
        ] {
            let mut it = meta_entries(&section(bytes));
            let err = it.next().unwrap().unwrap_err();
            assert!(matches!(err.what, Malformed::BadSyntax(_)), "{bytes:?}");
            assert_eq!(err.at, Some(Location::Byte(100)));
            assert!(it.next().is_none());
        }
        assert!(!MetaEntry::is_valid_key(""));
        assert!(!MetaEntry::is_valid_key(&"k".repeat(256)));
        assert!(MetaEntry::is_valid_key(&"k".repeat(255)));
    }

    #[test]
    fn lying_value_length() {
        let mut bytes = write_meta(&[("k", b"v")]);
        bytes[2..6].copy_from_slice(&u32::MAX.to_le_bytes());
        let err = meta_entries(&section(&bytes)).next().unwrap().unwrap_err();
        assert_eq!(err.what, Malformed::Truncated);
    }
}
