//! The bytes of a glTF document's buffers (§3.6.1): the GLB file's BIN
//! chunk, a `data:` URI holding base64 (RFC 2397, RFC 4648 §4), or a file
//! named by a relative URI (RFC 3986, percent-encoded), resolved against
//! the folder of the `.gltf` file.
//!
//! Only the buffers that the primitives to be read use are loaded.
//! External files are read as input files are (see `io::source`): only
//! regular files, and within one byte budget for the document and all of
//! its files together, [`Limits::max_input_bytes`], so that a thousand
//! buffers naming one large file cannot read it a thousand times.
//! URIs with a scheme other than `data:` (`http:`, `file:`) and absolute
//! paths are refused: a mesh file should not make its reader fetch from
//! the network or from anywhere on the disk. `..` is allowed, since
//! shared buffers in a sibling folder are common.
//!
//! The base64 and percent decoders are written here rather than taken
//! from the `gltf` crate's `import` feature, which also brings in image
//! codecs and reads external files without bounds.

use super::super::source::Source;
use crate::{Error, FormatError, Limits, Malformed};
use std::ops::Deref;
use std::path::Path;

/// The loaded bytes of one buffer.
pub(super) enum Data<'a> {
    /// The GLB file's BIN chunk.
    Bin(&'a [u8]),
    /// Decoded from a `data:` URI.
    Decoded(Vec<u8>),
    /// An external file.
    File(Source),
}

impl Deref for Data<'_> {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        match self {
            Data::Bin(b) => b,
            Data::Decoded(v) => v,
            Data::File(s) => s,
        }
    }
}

/// The document's buffers, those needed loaded.
pub(super) struct Buffers<'a> {
    data: Vec<Option<Data<'a>>>,
}

/// Where the buffers come from.
pub(super) struct Origin<'a, 'p> {
    /// The GLB BIN chunk, if any.
    pub bin: Option<&'a [u8]>,
    /// The folder relative URIs are resolved against; `None` when the
    /// document was not read from a file.
    pub base: Option<&'p Path>,
    /// Short name of the format, for errors.
    pub format: &'static str,
}

impl<'a> Buffers<'a> {
    /// Loads the buffers whose `needed` flag is set. `spent` is the bytes
    /// of input read so far (the document itself).
    pub(super) fn load(
        doc: &::gltf::Document,
        needed: &[bool],
        origin: &Origin<'a, '_>,
        limits: &Limits,
        mut spent: u64,
    ) -> Result<Buffers<'a>, Error> {
        let bad = |what| Error::from(FormatError::new(origin.format, what));
        let mut data = Vec::with_capacity(needed.len());
        for buffer in doc.buffers() {
            if !needed.get(buffer.index()).copied().unwrap_or(false) {
                data.push(None);
                continue;
            }
            let bytes = match buffer.source() {
                ::gltf::buffer::Source::Bin => Data::Bin(origin.bin.ok_or_else(|| {
                    bad(Malformed::BadSyntax(
                        "a buffer refers to the BIN chunk, which the file does not have",
                    ))
                })?),
                ::gltf::buffer::Source::Uri(uri) => {
                    let d = fetch(uri, origin, limits, spent)?;
                    spent = spent.saturating_add(d.len() as u64);
                    d
                }
            };
            // A buffer may be longer than declared (a GLB BIN chunk is
            // padded to 4 bytes), never shorter.
            if bytes.len() < buffer.length() {
                return Err(bad(Malformed::Truncated));
            }
            data.push(Some(bytes));
        }
        Ok(Buffers { data })
    }

    /// The bytes of a buffer that was loaded.
    pub(super) fn get(&self, index: usize) -> &[u8] {
        self.data
            .get(index)
            .and_then(Option::as_deref)
            .expect("only needed buffers are read")
    }
}

/// The bytes a buffer's URI names.
fn fetch<'a>(
    uri: &str,
    origin: &Origin<'a, '_>,
    limits: &Limits,
    spent: u64,
) -> Result<Data<'a>, Error> {
    let bad = |what| Error::from(FormatError::new(origin.format, what));
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_media, text)) = rest.split_once(";base64,") else {
            return Err(bad(Malformed::Unsupported(
                "data: URIs that are not base64",
            )));
        };
        let bytes = base64(text.as_bytes())
            .ok_or_else(|| bad(Malformed::BadSyntax("a data: URI holds invalid base64")))?;
        return Ok(Data::Decoded(bytes));
    }
    // A scheme is letters, digits, '+', '-', '.' before a ':' (RFC 3986
    // §3.1); a ':' after a '/' belongs to a path.
    let first = uri.find(['/', ':']).map(|i| uri.as_bytes()[i]);
    if first == Some(b':') {
        return Err(bad(Malformed::Unsupported(
            "buffer URIs other than relative paths and data: URIs",
        )));
    }
    let path = percent_decode(uri)
        .ok_or_else(|| bad(Malformed::BadSyntax("a buffer URI has a bad %-escape")))?;
    if path.starts_with(['/', '\\']) || Path::new(&path).is_absolute() {
        return Err(bad(Malformed::Unsupported("absolute buffer paths")));
    }
    let Some(base) = origin.base else {
        return Err(bad(Malformed::Unsupported(
            "external buffers in a glTF file that is not read from a folder",
        )));
    };
    let path = base.join(path);
    let budget = Limits {
        max_input_bytes: limits.max_input_bytes.saturating_sub(spent),
        ..*limits
    };
    Source::open(&path, &budget)
        .map(Data::File)
        .map_err(|error| Error::ExternalFile {
            path,
            error: Box::new(error),
        })
}

/// Standard base64 (RFC 4648 §4) with optional `=` padding; `None` for
/// any other character or an impossible length.
fn base64(text: &[u8]) -> Option<Vec<u8>> {
    let text = text.strip_suffix(b"=").unwrap_or(text);
    let text = text.strip_suffix(b"=").unwrap_or(text);
    if text.len() % 4 == 1 {
        return None;
    }
    let mut out = Vec::new();
    out.try_reserve_exact(text.len() / 4 * 3 + 2).ok()?;
    let (mut acc, mut bits) = (0u32, 0u32);
    for &c in text {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        };
        acc = (acc << 6 | u32::from(v)) & 0xff_ffff;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    Some(out)
}

/// `%XX` escapes to bytes, the result as UTF-8; `None` for a bad escape.
fn percent_decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_rfc4648_vectors() {
        let cases: [(&str, &str); 7] = [
            ("", ""),
            ("Zg==", "f"),
            ("Zm8=", "fo"),
            ("Zm9v", "foo"),
            ("Zm9vYg==", "foob"),
            ("Zm9vYmE", "fooba"),
            ("Zm9vYmFy", "foobar"),
        ];
        for (text, plain) in cases {
            assert_eq!(base64(text.as_bytes()).unwrap(), plain.as_bytes(), "{text}");
        }
        let all: Vec<u8> = (0..=255).collect();
        let text = "AAECAwQFBgcICQoLDA0ODxAREhMUFRYXGBkaGxwdHh8gISIjJCUmJygpKissLS4vMDEyMzQ1Njc4OTo7PD0+P0BBQkNERUZHSElKS0xNTk9QUVJTVFVWV1hZWltcXV5fYGFiY2RlZmdoaWprbG1ub3BxcnN0dXZ3eHl6e3x9fn+AgYKDhIWGh4iJiouMjY6PkJGSk5SVlpeYmZqbnJ2en6ChoqOkpaanqKmqq6ytrq+wsbKztLW2t7i5uru8vb6/wMHCw8TFxsfIycrLzM3Oz9DR0tPU1dbX2Nna29zd3t/g4eLj5OXm5+jp6uvs7e7v8PHy8/T19vf4+fr7/P3+/w==";
        assert_eq!(base64(text.as_bytes()).unwrap(), all);
        for bad in ["Z", "Zm9vY", "Zm9v!", "Zm 9", "Zg==="] {
            assert!(base64(bad.as_bytes()).is_none(), "{bad}");
        }
    }

    #[test]
    fn percent_escapes() {
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert_eq!(percent_decode("plain.bin").unwrap(), "plain.bin");
        assert_eq!(percent_decode("%C3%A9.bin").unwrap(), "é.bin");
        for bad in ["%", "%2", "%zz", "%ff"] {
            assert!(percent_decode(bad).is_none(), "{bad}");
        }
    }
}
