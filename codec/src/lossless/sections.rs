//! The lossless mode's small sections, each writer beside its reader
//! (they must match exactly): `HEAD` (the quantizer), `TOPO` (the
//! Edgebreaker events), `CLRS` (the CLERS symbols with the previous one
//! as context) and `CLRD` (the same symbols in Spirale Reversi's order,
//! in the decoder's own contexts). The SwingWrapper mode writes and reads
//! its `TOPO` and `CLRS` with the same functions.

use crate::prelude::*;

#[cfg(feature = "encoder")]
use crate::edgebreaker::Side;
use crate::edgebreaker::{self, Connectivity, Symbol};
#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{ContextModel, Decoder};
use crate::geometry::Quantizer;
#[cfg(feature = "encoder")]
use crate::varint;
use crate::varint::Reader;
use crate::CornerTable;
use crate::{Error, FormatError, Malformed};

/// A malformed lossless file (here so that `super` and this module share
/// it without importing each other).
pub(super) fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

// --- HEAD: written and read side by side; must match exactly. ---

#[cfg(feature = "encoder")]
pub(super) fn write_head(q: &Quantizer) -> Vec<u8> {
    let mut out = vec![q.bits];
    for x in q.origin.iter().chain([&q.range]) {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out
}

pub(super) fn read_head(bytes: &[u8]) -> Result<Quantizer, Error> {
    let mut r = Reader::new(bytes);
    let bits = r.u8()?;
    let origin = [r.f32()?, r.f32()?, r.f32()?];
    let range = r.f32()?;
    r.end()?;
    if !(crate::geometry::MIN_BITS..=crate::geometry::MAX_BITS).contains(&bits) {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadHeader("quantization bits out of range"),
        )));
    }
    // Every dequantized point lies between origin and origin + range,
    // which must stay finite in f32.
    let inside = origin
        .iter()
        .all(|&o| o.is_finite() && ((o as f64 + range as f64) as f32).is_finite());
    if !inside || !range.is_finite() || range < 0.0 {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadHeader("quantization grid is not finite"),
        )));
    }
    Ok(Quantizer {
        origin,
        range,
        bits,
    })
}

// --- TOPO writer (reader above, in read_topology). ---

#[cfg(feature = "encoder")]
pub(crate) fn write_topo(conn: &Connectivity, dummies: &[u32]) -> Vec<u8> {
    let mut out = Vec::new();
    varint::put(&mut out, conn.symbols.len() as u64);
    varint::put(&mut out, dummies.len() as u64);
    for (i, &d) in dummies.iter().enumerate() {
        let gap = if i == 0 {
            d as u64
        } else {
            (d - dummies[i - 1] - 1) as u64
        };
        varint::put(&mut out, gap);
    }
    varint::put(&mut out, conn.splits.len() as u64);
    for (i, e) in conn.splits.iter().enumerate() {
        let gap = if i == 0 {
            e.split as u64
        } else {
            (e.split - conn.splits[i - 1].split - 1) as u64
        };
        varint::put(&mut out, gap);
        varint::put(&mut out, (e.source - e.split - 1) as u64);
        out.push(match e.side {
            Side::Right => 0,
            Side::Left => 1,
        });
    }
    out
}

// --- CLRS: the previous symbol is the context; must match exactly. ---

#[cfg(feature = "encoder")]
pub(crate) fn write_clers(symbols: &[Symbol]) -> Vec<u8> {
    let mut enc = Encoder::new();
    let mut model = ContextModel::new(5, 5);
    let mut prev = Symbol::C;
    for &s in symbols {
        enc.encode(model.get(prev as usize), s as u32);
        prev = s;
    }
    enc.finish()
}

pub(super) fn read_clers(bytes: &[u8], count: usize) -> Result<Vec<Symbol>, Error> {
    let mut dec = Decoder::new(bytes)?;
    let mut model = ContextModel::new(5, 5);
    let mut prev = Symbol::C;
    let mut out = Vec::with_capacity(count);
    for _ in 0..count {
        let code = dec.decode(model.get(prev as usize))?;
        prev = Symbol::from_code(code).ok_or(bad("CLERS code out of range"))?;
        out.push(prev);
    }
    // The stream must end exactly where the encoder finished it.
    dec.finish()?;
    Ok(out)
}

// --- CLRD (1.1): written and read side by side; must match exactly. ---
//
// The symbols in the order Spirale Reversi asks for them (components
// last to first, each from its last symbol to its first), each in the
// model of its decoder state (`edgebreaker::decode_from`'s contexts: the
// corners built around the active gate's two vertices). Before the
// stream, the symbol counts of components K−1 … 1 as varus (component 0
// has the rest): read backwards, a component's end cannot be told from
// its symbols.

#[cfg(feature = "encoder")]
/// `CLRD` for `conn`, whose symbols had the contexts `contexts` (from
/// `edgebreaker::decode_recording`).
pub(super) fn write_clrd(conn: &Connectivity, contexts: &[u8]) -> Result<Vec<u8>, Error> {
    let ranges = conn
        .component_ranges()
        .ok_or(bad("connectivity symbols do not match the component count"))?;
    let mut out = Vec::new();
    for &(start, end) in ranges.iter().skip(1).rev() {
        varint::put(&mut out, (end - start) as u64);
    }
    let mut enc = Encoder::new();
    let mut models = ContextModel::new(edgebreaker::CONTEXTS, 5);
    let order = ranges
        .iter()
        .rev()
        .flat_map(|&(start, end)| (start..end).rev());
    for (i, &ctx) in order.zip(contexts) {
        enc.encode(models.get(ctx as usize), conn.symbols[i] as u32);
    }
    out.extend_from_slice(&enc.finish());
    Ok(out)
}

/// The symbols of `CLRD`, decoded while Spirale Reversi asks for them.
struct Streamed<'a> {
    dec: Decoder<'a>,
    models: ContextModel,
}

impl edgebreaker::SymbolSource for Streamed<'_> {
    const CONTEXTS: bool = true;
    fn symbol(&mut self, _i: usize, ctx: usize) -> Result<Symbol, FormatError> {
        let code = self
            .dec
            .decode(self.models.get(ctx))
            .map_err(format_error)?;
        Symbol::from_code(code).ok_or(FormatError::new(
            "SWM",
            Malformed::BadSyntax("CLERS code out of range"),
        ))
    }
}

/// The format error inside an entropy decoder's error.
fn format_error(e: Error) -> FormatError {
    match e {
        Error::Format(f) => f,
        _ => FormatError::new("SWM", Malformed::BadSyntax("invalid entropy-coded data")),
    }
}

/// Reads `CLRD` for `conn` (its `TOPO` read, `count` symbols): fills
/// `conn.symbols` and returns the closed mesh's corner table, which
/// decoding the symbols has built.
pub(super) fn read_clrd(
    bytes: &[u8],
    conn: &mut Connectivity,
    count: usize,
) -> Result<CornerTable, FormatError> {
    let mut r = Reader::new(bytes);
    let components = conn.components as usize;
    let malformed = |why| FormatError::new("SWM", Malformed::BadSyntax(why));
    // A varu takes a byte at least: checked before sizing anything by K.
    if components.saturating_sub(1) > r.remaining() {
        return Err(malformed("more component lengths than CLRD holds"));
    }
    let mut counts = vec![0u64; components];
    let mut rest = count as u64;
    for k in (1..components).rev() {
        let n = r.varu()?;
        rest = rest
            .checked_sub(n)
            .ok_or(malformed("component lengths exceed the symbol count"))?;
        counts[k] = n;
    }
    if let Some(first) = counts.first_mut() {
        *first = rest;
    } else if count != 0 {
        return Err(malformed("symbols without a component"));
    }
    let ranges = edgebreaker::ranges_of(&counts, count)
        .ok_or(malformed("component lengths do not add up"))?;
    let stream = &bytes[bytes.len() - r.remaining()..];
    let mut src = Streamed {
        dec: Decoder::new(stream).map_err(format_error)?,
        models: ContextModel::new(edgebreaker::CONTEXTS, 5),
    };
    let mut symbols = Vec::new();
    let table = edgebreaker::decode_from(conn, &ranges, &mut src, &mut symbols)?;
    // The stream must end exactly where the encoder finished it.
    src.dec.finish().map_err(format_error)?;
    conn.symbols = symbols;
    Ok(table)
}
