//! Decoding a `.swm` file that arrives in pieces (a network download, a
//! pipe): [`StreamDecoder`] takes the bytes as they come, rejects a file
//! as soon as its frame says it cannot be decoded, and decodes once the
//! last byte is in. It gives the mesh only, as `decode` does: a
//! lossless file's attribute streams (`ATTR`, format 1.2) are read by
//! `decode_attributed` on the whole file.
//!
//! The frame tells its own length: after the header and the section
//! table, `total = table end + Σ section lengths + 4` (format-spec
//! 01-container.md). So the decoder buffers exactly `total` bytes, checked
//! against `Limits::max_alloc_bytes` before it reserves them, and refuses
//! a byte past the end.
//!
//! ```text
//! bytes in   0    4       8              27        table end              total
//!            |magic| ver. |  fixed header  | table    |   payloads     | CRC |
//! checks:         ^ magic ^ version, flags ^ header   ^ length vs limits     ^ whole file:
//!                           (the framing)   (mode,                              `decode`
//!                                            counts vs limits)
//! ```
//!
//! In the compact framing (format 1.1) the header and the table have no
//! fixed length: after byte 8 the decoder reads them field by field as
//! they arrive (checking each count against the limits, and each table
//! entry as the whole-file parser does), and learns `total` when the last
//! entry is in. It keeps its place, so the work stays linear in the
//! table however the bytes are cut.
//!
//! A displaced-subdivision (mode 2) file is also decoded level by level
//! as it arrives (`levels`): [`StreamDecoder::level`] gives the base mesh
//! once its sections are in, then each finer level once its chunk is.
//!
//! Invariant: the outcome depends only on the bytes, never on how they
//! were cut into pieces. Each check runs when the buffered prefix reaches
//! its fixed length (a piece that crosses several of them is split at
//! each), so every cut sees the same prefixes. A file that [`decode`]
//! accepts whole, the stream accepts and decodes to the same mesh. A
//! damaged file can be refused earlier, and for a different reason, than
//! whole: the early checks read the header before the CRC can vouch for
//! it, which is the point of them (a header claiming a billion triangles
//! stops the download at byte 27).

mod levels;

use crate::prelude::*;

use crate::container::{
    check_magic, check_version_and_flags, declared_len, malformed, table_end, Header, Scan,
    TableCheck, FLAG_COMPACT, MAGIC, MIN_LEN,
};
use crate::{decode, DecodeOptions, Error, Malformed, TriMesh};

/// A `.swm` file being received; see the module documentation.
///
/// ```
/// # fn demo(pieces: &[&[u8]]) -> Result<swm::TriMesh, swm::Error> {
/// let mut stream = swm::StreamDecoder::new(swm::DecodeOptions::default());
/// for piece in pieces {
///     stream = stream.push(piece)?; // stops at the first sign of trouble
/// }
/// stream.finish()
/// # }
/// ```
///
/// A displaced-subdivision file shows its coarser levels before it is all
/// in:
///
/// ```
/// # fn show(_: usize, _: &swm::TriMesh) {}
/// # fn demo(pieces: &[&[u8]]) -> Result<swm::TriMesh, swm::Error> {
/// let mut stream = swm::StreamDecoder::new(swm::DecodeOptions::default());
/// let mut shown = None;
/// for piece in pieces {
///     stream = stream.push(piece)?;
///     if let Some((level, mesh)) = stream.level() {
///         if shown != Some(level) {
///             show(level, mesh); // the base, then each finer level
///             shown = Some(level);
///         }
///     }
/// }
/// stream.finish()
/// # }
/// ```
#[derive(Debug)]
pub struct StreamDecoder {
    options: DecodeOptions,
    buf: Vec<u8>,
    /// The file's length, once the section table is in.
    total: Option<usize>,
    /// A compact file's frame, once its flags are in.
    compact: Option<CompactFrame>,
    /// The header, once it is all in.
    header: Option<Header>,
    /// A displaced-subdivision file's levels, once its table is in.
    levels: Option<levels::Levels>,
}

/// Where reading a compact frame stands.
#[derive(Debug)]
struct CompactFrame {
    /// The buffer length at which reading goes on.
    need: usize,
    /// The header and the table's check, once the header is in.
    table: Option<(Header, TableCheck)>,
    /// The next entry's offset, and the entries left.
    pos: usize,
    left: usize,
}

/// The length of the preamble: magic, version, flags.
const PREAMBLE_LEN: usize = 8;

impl StreamDecoder {
    /// A decoder that will decode with `options` (and buffer no more than
    /// `options.limits.max_alloc_bytes`).
    pub fn new(options: DecodeOptions) -> Self {
        StreamDecoder {
            options,
            buf: Vec::new(),
            total: None,
            compact: None,
            header: None,
            levels: None,
        }
    }

    /// Bytes received so far.
    pub fn received(&self) -> usize {
        self.buf.len()
    }

    /// The file's length in bytes, known once its section table is in.
    pub fn expected_len(&self) -> Option<usize> {
        self.total
    }

    /// The file's header once its first bytes are in (its mode and
    /// format version), `None` before.
    pub fn header(&self) -> Option<Header> {
        self.header
            .or(self.compact.as_ref().and_then(|c| c.table.map(|t| t.0)))
    }

    /// The finest level decoded so far of a displaced-subdivision (mode 2)
    /// file, and its mesh: `(0, base)` once the `HEAD` and `BASE` sections
    /// are in, then `(l, mesh)` as soon as the chunk of level `l` is, up
    /// to `options.max_level`. Each is bit for bit what [`decode`] gives
    /// with `max_level: Some(l)` and no post-processing (Sharpen&Bend
    /// apply to [`finish`](Self::finish)'s mesh only). Unverified until
    /// `finish`: the file's CRC comes last. `None` before the base is in,
    /// and for other modes.
    pub fn level(&self) -> Option<(usize, &TriMesh)> {
        self.levels.as_ref().and_then(levels::Levels::current)
    }

    /// Takes the next piece of the file.
    ///
    /// # Errors
    /// As soon as the bytes so far show the file cannot decode: a wrong
    /// magic, an unsupported version, flags or mode, counts above the
    /// limits or inconsistent ([`decode`]'s errors for these), a file
    /// longer than `max_alloc_bytes` ([`Error::LimitExceeded`]), a byte
    /// past the file's end ([`Malformed::TrailingData`]), or, in a
    /// displaced-subdivision file, a base or level that does not decode.
    pub fn push(mut self, mut piece: &[u8]) -> Result<Self, Error> {
        while !piece.is_empty() {
            let Some(next) = self.next_check() else {
                let at = self.buf.len();
                return Err(malformed(Malformed::TrailingData, at));
            };
            let take = (next - self.buf.len()).min(piece.len());
            self.buf.extend_from_slice(&piece[..take]);
            piece = &piece[take..];
            if self.buf.len() == next {
                self.check(next)?;
            }
            if let Some(levels) = &mut self.levels {
                levels.advance(&self.buf, &self.options)?;
            }
        }
        Ok(self)
    }

    /// Decodes the file once every byte is in.
    ///
    /// # Errors
    /// [`Malformed::Empty`] or [`Malformed::Truncated`] if bytes are
    /// missing, then whatever [`decode`] reports.
    pub fn finish(self) -> Result<TriMesh, Error> {
        if self.buf.is_empty() {
            return Err(malformed(Malformed::Empty, 0));
        }
        if Some(self.buf.len()) != self.total {
            return Err(malformed(Malformed::Truncated, self.buf.len()));
        }
        decode(&self.buf, &self.options)
    }

    /// The buffer length at which the next check runs; `None` once the
    /// whole file is in.
    fn next_check(&self) -> Option<usize> {
        let n = self.buf.len();
        match self.total {
            Some(total) if n >= total => None,
            Some(total) => Some(total),
            None if n < MAGIC.len() => Some(MAGIC.len()),
            None if n < PREAMBLE_LEN => Some(PREAMBLE_LEN),
            None => match &self.compact {
                Some(c) => Some(c.need),
                None if n < MIN_LEN => Some(MIN_LEN),
                None => Some(table_end(&self.buf).max(MIN_LEN)),
            },
        }
    }

    /// The check for a prefix of length `len`.
    fn check(&mut self, len: usize) -> Result<(), Error> {
        if Some(len) == self.total {
            return Ok(());
        }
        if len == MAGIC.len() {
            return check_magic(&self.buf);
        }
        if len == PREAMBLE_LEN {
            let flags = check_version_and_flags(&self.buf)?;
            if flags & FLAG_COMPACT != 0 {
                self.compact = Some(CompactFrame {
                    need: PREAMBLE_LEN + 1,
                    table: None,
                    pos: 0,
                    left: 0,
                });
            }
            return Ok(());
        }
        let declared = if self.compact.is_some() {
            self.compact_step()?
        } else {
            if len == MIN_LEN {
                self.header = Some(Header::read(&self.buf, &self.options.limits)?);
            }
            declared_len(&self.buf)
        };
        if let Some(total) = declared {
            self.options.limits.check_alloc(total)?;
            let total = usize::try_from(total).map_err(|_| {
                Error::LimitExceeded(crate::LimitError {
                    what: crate::Limited::AllocBytes,
                    requested: total,
                    limit: usize::MAX as u64,
                })
            })?;
            // total ≥ table end + 4 ≥ the 27 bytes in hand.
            self.buf.reserve_exact(total - self.buf.len());
            self.total = Some(total);
            let header = self
                .header
                .or(self.compact.as_ref().and_then(|c| c.table.map(|t| t.0)));
            self.levels = header.and_then(|h| levels::Levels::new(h, &self.buf, &self.options));
        }
        Ok(())
    }
}

impl StreamDecoder {
    /// Reads as much of a compact frame as the buffer holds, from where
    /// the last step stopped: the file's length once the table is all in.
    fn compact_step(&mut self) -> Result<Option<u64>, Error> {
        let buf = &self.buf;
        let Some(c) = self.compact.as_mut() else {
            return Ok(None);
        };
        if c.table.is_none() {
            match crate::container::read_compact_head(buf, &self.options.limits)? {
                Scan::Done(h) => {
                    c.table = Some((h.header, TableCheck::unbounded(&h.header)));
                    c.pos = h.table;
                    c.left = h.count;
                }
                Scan::Need(n) => {
                    c.need = n;
                    return Ok(None);
                }
            }
        }
        let Some((header, check)) = c.table.as_mut() else {
            return Ok(None);
        };
        while c.left > 0 {
            match check.try_entry(buf, c.pos, header)? {
                Scan::Done(next) => {
                    c.pos = next;
                    c.left -= 1;
                }
                Scan::Need(n) => {
                    c.need = n;
                    return Ok(None);
                }
            }
        }
        Ok(Some(c.pos as u64 + check.payload + 4))
    }
}
