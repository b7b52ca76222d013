//! ASCII scanning shared by the text readers (PLY ascii, OFF, STL ascii,
//! and the OBJ pre-scan): a cursor that hands out whitespace-separated
//! tokens and lines while counting lines, and number parsers for tokens.
//!
//! Invariants: the cursor never indexes past the end of its bytes, every
//! loop advances by at least one byte, and the line counter is the 1-based
//! line the cursor is on, so errors can say where.
//! Floats go through the standard library's correctly rounded parser, so a
//! shortest round-trip decimal written by our writers reads back bit-exactly.
//!
//! Lines end in `\n` (Unix), `\r\n` (Windows) or a lone `\r` (classic Mac
//! OS, which old exporters still write): every reader takes all three,
//! through [`split_line`] and the cursor's line count.

/// A cursor over ASCII text.
pub(super) struct Text<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u64,
}

impl<'a> Text<'a> {
    /// A cursor at the start of `bytes`, which is line `first_line`.
    pub(super) fn new(bytes: &'a [u8], first_line: u64) -> Self {
        Text {
            bytes,
            pos: 0,
            line: first_line,
        }
    }

    /// The 1-based line the cursor is on (after [`Text::token`], the
    /// token's line).
    pub(super) fn line(&self) -> u64 {
        self.line
    }

    /// Bytes not yet consumed.
    pub(super) fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// Moves past whitespace, counting lines (`\n`, `\r\n` or `\r` each
    /// end one).
    pub(super) fn skip_space(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            let crlf = b == b'\r' && self.bytes.get(self.pos + 1) == Some(&b'\n');
            if b == b'\n' || (b == b'\r' && !crlf) {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token, or `None` at the end.
    pub(super) fn token(&mut self) -> Option<&'a [u8]> {
        self.skip_space();
        let bytes = self.bytes;
        let start = self.pos;
        while let Some(&b) = bytes.get(self.pos) {
            if b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
        (self.pos > start).then(|| &bytes[start..self.pos])
    }

    /// The rest of the current line without its terminator (`\n`,
    /// `\r\n` or `\r`) and that line's number; `None` at the end of the
    /// text. The cursor moves to the start of the next line.
    pub(super) fn next_line(&mut self) -> Option<(u64, &'a [u8])> {
        let rest = self.bytes.get(self.pos..).filter(|r| !r.is_empty())?;
        let number = self.line;
        let (line, after) = split_line(rest);
        if after.len() < rest.len() - line.len() {
            self.line += 1;
        }
        self.pos = self.bytes.len() - after.len();
        Some((number, line))
    }

    /// Skips the rest of the current line (after a token).
    pub(super) fn skip_line(&mut self) {
        let _ = self.next_line();
    }

    /// The offset of the cursor in the bytes.
    pub(super) fn pos(&self) -> usize {
        self.pos
    }
}

/// The first line of `bytes` without its terminator, and the bytes after
/// that terminator: `\n`, `\r\n` or a lone `\r`. Without one, the whole
/// of `bytes` is the line and nothing follows.
pub(super) fn split_line(bytes: &[u8]) -> (&[u8], &[u8]) {
    match bytes.iter().position(|&b| b == b'\n' || b == b'\r') {
        Some(n) => {
            let end = if bytes[n] == b'\r' && bytes.get(n + 1) == Some(&b'\n') {
                n + 2
            } else {
                n + 1
            };
            (&bytes[..n], &bytes[end..])
        }
        None => (bytes, &[]),
    }
}

/// The whitespace-separated tokens of one line.
pub(super) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> + Clone {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// Why `bytes` cannot be the text of a text format, if they cannot:
/// UTF-16 (a byte-order mark, or NUL bytes between characters, as UTF-16
/// puts them before or after every ASCII character), or binary data (any
/// other NUL byte). Text never holds a NUL, so only the start is looked
/// at; without this check such files read as text without a single
/// statement, and were reported "empty".
pub(super) fn not_text(bytes: &[u8]) -> Option<crate::Malformed> {
    if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
        return Some(crate::Malformed::Utf16);
    }
    let head = &bytes[..bytes.len().min(4096)];
    let nuls = |parity: usize| {
        head.iter()
            .skip(parity)
            .step_by(2)
            .filter(|&&b| b == 0)
            .count()
    };
    let (even, odd) = (nuls(0), nuls(1));
    if even + odd == 0 {
        return None;
    }
    // UTF-16 ASCII: one byte of each pair is NUL nearly always, the other
    // almost never.
    let pairs = head.len() / 2;
    let utf16 = pairs >= 2 && (even.max(odd) * 10 >= pairs * 9) && even.min(odd) * 10 <= pairs;
    Some(if utf16 {
        crate::Malformed::Utf16
    } else {
        crate::Malformed::Binary
    })
}

/// True when `bytes` holds nothing but ASCII whitespace.
pub(super) fn is_blank(bytes: &[u8]) -> bool {
    bytes.iter().all(u8::is_ascii_whitespace)
}

/// A decimal `f32`, correctly rounded (accepts `inf` and `nan`, which the
/// readers then reject as non-finite with a better message).
pub(super) fn parse_f32(token: &[u8]) -> Option<f32> {
    core::str::from_utf8(token).ok()?.parse().ok()
}

/// A decimal `f64`, correctly rounded.
pub(super) fn parse_f64(token: &[u8]) -> Option<f64> {
    core::str::from_utf8(token).ok()?.parse().ok()
}

/// A decimal integer with an optional sign; `None` on overflow or junk.
pub(super) fn parse_i64(token: &[u8]) -> Option<i64> {
    let (negative, digits) = match token.split_first()? {
        (b'-', rest) => (true, rest),
        (b'+', rest) => (false, rest),
        _ => (false, token),
    };
    if digits.is_empty() {
        return None;
    }
    // Accumulate negatively so that i64::MIN parses too.
    let mut value: i64 = 0;
    for &b in digits {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        value = value.checked_mul(10)?.checked_sub(i64::from(d))?;
    }
    if negative {
        Some(value)
    } else {
        value.checked_neg()
    }
}

/// A non-negative decimal integer.
pub(super) fn parse_u64(token: &[u8]) -> Option<u64> {
    let digits = token.strip_prefix(b"+").unwrap_or(token);
    if digits.is_empty() {
        return None;
    }
    let mut value: u64 = 0;
    for &b in digits {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        value = value.checked_mul(10)?.checked_add(u64::from(d))?;
    }
    Some(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers() {
        assert_eq!(parse_i64(b"0"), Some(0));
        assert_eq!(parse_i64(b"-17"), Some(-17));
        assert_eq!(parse_i64(b"+17"), Some(17));
        assert_eq!(parse_i64(b"-9223372036854775808"), Some(i64::MIN));
        assert_eq!(parse_i64(b"9223372036854775808"), None);
        assert_eq!(parse_i64(b"-"), None);
        assert_eq!(parse_i64(b"1.0"), None);
        assert_eq!(parse_u64(b"18446744073709551615"), Some(u64::MAX));
        assert_eq!(parse_u64(b"18446744073709551616"), None);
        assert_eq!(parse_u64(b"-1"), None);
    }

    #[test]
    fn cursor_counts_lines() {
        let mut t = Text::new(b"a b\r\n\n c\nlast line\n", 1);
        assert_eq!(t.token(), Some(&b"a"[..]));
        assert_eq!(t.token(), Some(&b"b"[..]));
        assert_eq!(t.line(), 1);
        assert_eq!(t.token(), Some(&b"c"[..]));
        assert_eq!(t.line(), 3);
        t.skip_line();
        assert_eq!(t.next_line(), Some((4, &b"last line"[..])));
        assert_eq!(t.line(), 5);
        assert_eq!(t.token(), None);
        assert_eq!(t.next_line(), None);
    }

    /// `\n`, `\r\n` and a lone `\r` end lines alike, for tokens and lines.
    #[test]
    fn every_line_ending_counts() {
        for eol in ["\n", "\r\n", "\r"] {
            let text = ["a b", "", " c", "last line", ""].join(eol);
            let mut t = Text::new(text.as_bytes(), 1);
            assert_eq!(t.token(), Some(&b"a"[..]), "{eol:?}");
            assert_eq!(t.token(), Some(&b"b"[..]));
            assert_eq!(t.line(), 1, "{eol:?}");
            assert_eq!(t.token(), Some(&b"c"[..]));
            assert_eq!(t.line(), 3, "{eol:?}");
            t.skip_line();
            assert_eq!(t.next_line(), Some((4, &b"last line"[..])), "{eol:?}");
            assert_eq!(t.line(), 5, "{eol:?}");
            assert_eq!(t.next_line(), None);
        }
        assert_eq!(split_line(b"a\r\r\nb"), (&b"a"[..], &b"\r\nb"[..]));
        assert_eq!(split_line(b"a"), (&b"a"[..], &b""[..]));
    }
}
