//! A displaced-subdivision (mode 2) file decoded level by level as it
//! arrives: its levels are stored coarse to fine, each in its own chunk
//! (format-spec/07-displaced.md), so the base mesh can be shown once
//! `HEAD` and `BASE` are in, and each finer level once its chunk is.
//!
//! The section table, known before any payload, says where `HEAD`,
//! `BASE` and `DISP` lie; each chunk's length prefix says where the next
//! level ends. Each level is decoded by the same [`Refiner`] as a whole
//! decode, so level `l` is bit for bit what `decode` gives with
//! `max_level: Some(l)`. Nothing here is vouched for by the file's CRC,
//! which comes last: `BASE` carries its own (checked by its parse), a
//! damaged chunk fails here or at `finish`.
//!
//! The work is done when the buffered bytes complete a section or a
//! chunk, whatever the cuts: the same bytes give the same levels and the
//! same first error.

use crate::container::{declared_sections, Header, Mode, Tag};
use crate::displaced::{bad, Refiner};
use crate::prelude::*;
use crate::varint::Reader;
use crate::{DecodeOptions, Error, TriMesh};

/// Longest `varu`: a chunk's length prefix is read once this many bytes
/// (or the rest of `DISP`) are in, so its outcome never depends on cuts.
const VARU_MAX: usize = 10;

/// Where a mode-2 file's sections lie, and the decode so far.
#[derive(Debug)]
pub(super) struct Levels {
    header: Header,
    /// File offsets of the payloads: `HEAD`, `BASE`, `DISP` (start, end).
    head: (usize, usize),
    base: (usize, usize),
    disp: (usize, usize),
    /// Levels to decode at most (`DecodeOptions::max_level`).
    max: usize,
    /// The decode once `HEAD` and `BASE` are in.
    refiner: Option<Refiner>,
    /// File offset of the next chunk's length prefix.
    next: usize,
}

impl Levels {
    /// The layout of a file whose header and whole section table `buf`
    /// holds; `None` unless it is a mode-2 file with the three sections
    /// (a file without them is refused by `finish`).
    pub(super) fn new(header: Header, buf: &[u8], options: &DecodeOptions) -> Option<Levels> {
        if header.mode != Mode::Displaced {
            return None;
        }
        let mut spans = Vec::new();
        let table_end = declared_sections(buf, |tag, len| spans.push((tag, len as usize)))?;
        let mut at = table_end;
        let mut find = [None; 3];
        for (tag, len) in spans {
            let k = [Tag::HEAD, Tag::BASE, Tag::DISP]
                .iter()
                .position(|&t| t == tag);
            if let Some(k) = k {
                // The first of each, as `Container::find`.
                find[k] = find[k].or(Some((at, at.checked_add(len)?)));
            }
            at = at.checked_add(len)?;
        }
        let [Some(head), Some(base), Some(disp)] = find else {
            return None;
        };
        Some(Levels {
            header,
            head,
            base,
            disp,
            max: options.max_level.map_or(usize::MAX, usize::from),
            refiner: None,
            next: disp.0,
        })
    }

    /// The finest level decoded so far and its mesh.
    pub(super) fn current(&self) -> Option<(usize, &TriMesh)> {
        self.refiner.as_ref().map(|r| (r.level(), r.mesh()))
    }

    /// Decodes every level that the bytes in `buf` (a prefix of the file)
    /// complete.
    pub(super) fn advance(&mut self, buf: &[u8], options: &DecodeOptions) -> Result<(), Error> {
        let n = buf.len();
        let refiner = match &mut self.refiner {
            Some(r) => r,
            None if n < self.head.1.max(self.base.1) => return Ok(()),
            None => self.refiner.insert(Refiner::start(
                &buf[self.head.0..self.head.1],
                &buf[self.base.0..self.base.1],
                self.base.0,
                &self.header,
                &options.limits,
            )?),
        };
        while refiner.level() < self.max && self.next < self.disp.1 {
            let prefix_end = self.disp.1.min(self.next + VARU_MAX);
            if n < prefix_end {
                return Ok(());
            }
            let mut r = Reader::new(&buf[self.next..prefix_end]);
            let len = r.varu()?;
            let start = prefix_end - r.remaining();
            let end = usize::try_from(len)
                .ok()
                .and_then(|len| start.checked_add(len))
                .filter(|&end| end <= self.disp.1)
                .ok_or(bad("a DISP chunk runs past its section"))?;
            if n < end {
                return Ok(());
            }
            refiner.refine(&buf[start..end])?;
            self.next = end;
        }
        Ok(())
    }
}
