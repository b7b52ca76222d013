//! Unsigned LEB128 integers (the `varu` type of format-spec/00-conventions.md):
//! 7 bits per byte, low group first, at most 10 bytes.

use crate::prelude::*;
use crate::{FormatError, Malformed};

/// Appends `v` as a varu.
pub fn put(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

/// A cursor over a byte slice that reads varus and single bytes.
pub struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

fn truncated() -> FormatError {
    FormatError::new("SWM", Malformed::Truncated)
}

impl<'a> Reader<'a> {
    /// Reads from the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Reader { bytes, pos: 0 }
    }

    /// Reads one varu; rejects encodings longer than 10 bytes or above 2^64.
    pub fn varu(&mut self) -> Result<u64, FormatError> {
        let mut v = 0u64;
        for i in 0..10 {
            let b = *self.bytes.get(self.pos).ok_or_else(truncated)?;
            self.pos += 1;
            if i == 9 && b > 1 {
                return Err(FormatError::new("SWM", Malformed::BadNumber));
            }
            v |= ((b & 0x7f) as u64) << (7 * i);
            if b < 0x80 {
                return Ok(v);
            }
        }
        Err(FormatError::new("SWM", Malformed::BadNumber))
    }

    /// Reads one byte.
    pub fn u8(&mut self) -> Result<u8, FormatError> {
        let b = *self.bytes.get(self.pos).ok_or_else(truncated)?;
        self.pos += 1;
        Ok(b)
    }

    /// Reads four bytes as a little-endian f32.
    pub fn f32(&mut self) -> Result<f32, FormatError> {
        let b = self
            .bytes
            .get(self.pos..self.pos + 4)
            .ok_or_else(truncated)?;
        self.pos += 4;
        Ok(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// Bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// Fails unless every byte was read.
    pub fn end(&self) -> Result<(), FormatError> {
        if self.remaining() == 0 {
            Ok(())
        } else {
            Err(FormatError::new("SWM", Malformed::TrailingData))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roundtrip_and_limits() {
        let mut out = Vec::new();
        let values = [0u64, 1, 127, 128, 300, u32::MAX as u64, u64::MAX];
        for &v in &values {
            put(&mut out, v);
        }
        let mut r = Reader::new(&out);
        for &v in &values {
            assert_eq!(r.varu().unwrap(), v);
        }
        r.end().unwrap();
        assert!(Reader::new(&[0x80; 11]).varu().is_err());
        assert!(
            Reader::new(&[0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x02])
                .varu()
                .is_err()
        );
        assert!(Reader::new(&[0x80]).varu().is_err());
    }
}
