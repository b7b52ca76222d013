//! Mode 2 (format 1.2), displaced subdivision: a base mesh coded by the
//! lossless mode, `L` levels of regular 1-to-4 subdivision, and for each
//! new vertex one quantized scalar that moves it from its predicted point
//! along its predicted normal (normative text:
//! format-spec/07-displaced.md).
//!
//! Sources: displaced subdivision surfaces (Lee, Moreton & Hoppe, 2000)
//! and normal meshes (Guskov, Vidimče, Sweldens & Schröder, 2000): a
//! coarse base, regular refinement, one scalar per vertex along a normal;
//! their coders (Khodakovsky & Guskov, 2003) and MPEG's V-DMC code the
//! scalars level by level, coarse to fine, as here.
//!
//! Sections:
//! * `HEAD`: `u8 rule` (bits 0-6: 0 Loop, 1 butterfly; bit 7: bends
//!   follow), `u8 K` (levels, 1..=8), `K × f32 step` (each finite and
//!   positive), then with bit 7 `K × i8 bend` (sixteenths: each level's
//!   predicted points moved along their normals against the stencil's
//!   lift, `predict::bent`, fitted by the encoder's `bend`);
//! * `BASE`: a complete mode-0 file (its own frame and CRC), the level-0
//!   mesh;
//! * `DISP`: up to `K` chunks, coarse to fine, each `varu length` and that
//!   many bytes of one level's range-coded scalars (`scalars`).
//!
//! The decoded level count `L` is the number of chunks in `DISP`; the
//! header's triangle count must be the base's times `4^L` and is checked
//! before anything is subdivided, so the container's triangle limit
//! bounds every allocation (a hostile header cannot ask for `4^K` of
//! anything). Dropping the last chunks (and fixing the header's counts
//! and the CRC, [`cut_levels`]) gives the file of a coarser level.
//! Decoding into the caller's buffers ([`decode_levels_into`]) places and
//! splits the last level straight into them.
//!
//! One concern per file: `subdivide` (the split and the order of new
//! vertices), `predict` (rules, bends, normal, placement), `scalars` (the
//! chunks' coding), `finer` (a level's edges, and its scalars' contexts,
//! from the level above), `info` (what `swm info` shows of a file);
//! encoder side: `fit` (the scalars against the input), `bend` (each
//! level's bend) and `write` (the file).

#[cfg(feature = "encoder")]
pub(crate) mod bend;
mod finer;
#[cfg(feature = "encoder")]
pub(crate) mod fit;
mod info;
pub(crate) mod predict;
pub(crate) mod scalars;
pub(crate) mod subdivide;
#[cfg(all(test, feature = "encoder"))]
mod tests;
#[cfg(feature = "encoder")]
pub(crate) mod write;

use crate::container::{
    check_count_fits, in_section, parse_container, Container, Header, Mode, Tag,
};
use crate::prelude::*;
use crate::varint::Reader;
use crate::{Error, FormatError, Limits, Malformed, TriMesh};
pub use info::{DisplacedInfo, Prediction};
use predict::Rule;
use subdivide::Edges;

/// Most subdivision levels a file may declare: 4^8 triangles per base
/// triangle already exceeds any useful refinement.
pub(crate) const MAX_LEVELS: usize = 8;

pub(crate) fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// `HEAD`'s rule byte: bit 7 says that one bend code a level follows
/// the steps (`predict::bent`); bit 6 that `BASE` is bare (its mode-0
/// sections without a frame of their own); bits 0-5 are the rule.
const BENDS_FOLLOW: u8 = 0x80;
/// `HEAD`'s rule byte: `BASE` holds a bare mode-0 body
/// (`container::parse_bare`), not a whole file. Beyond the first 1.2
/// files (format-spec/07-displaced.md, "BASE"): the nested file's
/// preamble, mode, component count and CRC repeat the enclosing file's or
/// are covered by it, 14-16 bytes a file, 3-8% of the method's files at
/// 0.5 b/v on meshes of 3,000-7,000 vertices (BENCHMARKS.md, "Session
/// 2026-12-07 (seventh)").
const BARE_BASE: u8 = 0x40;
/// The rule's bits of the rule byte.
const RULE_BITS: u8 = 0x3F;
/// A bend code's unit: the bend is `code / 16` (−8 to 7.9375).
pub(crate) const BEND_UNIT: f64 = 1.0 / 16.0;

/// `HEAD`'s contents.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Head {
    pub rule: Rule,
    /// The quantization step of each level, coarse to fine.
    pub steps: Vec<f32>,
    /// Each level's bend code (`code · BEND_UNIT`), or none (all 0, and
    /// the rule byte's bit 7 clear: files before bends).
    pub bends: Vec<i8>,
    /// `BASE` is a bare mode-0 body (bit 6; clear: a whole mode-0 file,
    /// as in files before bare bases).
    pub bare: bool,
}

impl Head {
    #[cfg(feature = "encoder")]
    pub fn write(&self) -> Vec<u8> {
        let bent = self.bends.iter().any(|&b| b != 0);
        let flag = if bent { BENDS_FOLLOW } else { 0 };
        let flag = flag | if self.bare { BARE_BASE } else { 0 };
        let mut out = vec![self.rule.code() | flag, self.steps.len() as u8];
        for s in &self.steps {
            out.extend_from_slice(&s.to_le_bytes());
        }
        if bent {
            out.extend(self.bends.iter().map(|&b| b as u8));
        }
        out
    }

    fn read(bytes: &[u8]) -> Result<Head, Error> {
        let mut r = Reader::new(bytes);
        let byte = r.u8()?;
        let rule = Rule::from_code(byte & RULE_BITS).ok_or(bad("unknown prediction rule"))?;
        let k = r.u8()? as usize;
        if !(1..=MAX_LEVELS).contains(&k) {
            return Err(bad("level count outside 1..=8"));
        }
        let mut steps = Vec::with_capacity(k);
        for _ in 0..k {
            let s = r.f32()?;
            if !(s.is_finite() && s > 0.0) {
                return Err(bad("a step that is not finite and positive"));
            }
            steps.push(s);
        }
        let mut bends = vec![0i8; k];
        if byte & BENDS_FOLLOW != 0 {
            for b in &mut bends {
                *b = r.u8()? as i8;
            }
        }
        r.end()?;
        let bare = byte & BARE_BASE != 0;
        Ok(Head {
            rule,
            steps,
            bends,
            bare,
        })
    }

    /// Level `l`'s stencil (`l` below the level count).
    pub(crate) fn stencil(&self, l: usize) -> predict::Stencil {
        predict::Stencil {
            rule: self.rule,
            bend: f64::from(self.bends.get(l).copied().unwrap_or(0)) * BEND_UNIT,
        }
    }
}

/// The parsed sections of a mode-2 file, counts checked.
struct Parsed<'a> {
    head: Head,
    base: Container<'a>,
    /// One slice per decoded level.
    chunks: Vec<&'a [u8]>,
}

/// `HEAD` and `BASE` (its payload at file offset `base_at`), checked
/// against the outer header's counts as far as they go without `DISP`.
fn head_and_base<'a>(
    head: &[u8],
    base: &'a [u8],
    base_at: usize,
    header: &Header,
    limits: &Limits,
) -> Result<(Head, Container<'a>), Error> {
    let head = Head::read(head)?;
    let base = match head.bare {
        true => crate::container::parse_bare(base, header, limits),
        false => parse_container(base, limits),
    }
    .map_err(in_section(base_at))?;
    if base.header.mode != Mode::Lossless {
        return Err(bad("BASE does not hold a lossless (mode 0) file"));
    }
    let bh = &base.header;
    if header.component_count != bh.component_count || header.vertex_count < bh.vertex_count {
        return Err(bad("counts disagree with the base's"));
    }
    Ok((head, base))
}

fn parse<'a>(file: &Container<'a>, limits: &Limits) -> Result<Parsed<'a>, Error> {
    let (h, b) = (file.require(Tag::HEAD)?, file.require(Tag::BASE)?);
    let (head, base) = head_and_base(h.bytes, b.bytes, b.offset, &file.header, limits)?;
    let d = file.require(Tag::DISP)?;
    let mut r = Reader::new(d.bytes);
    let mut chunks = Vec::new();
    while r.remaining() > 0 {
        if chunks.len() == head.steps.len() {
            return Err(bad("DISP has more levels than HEAD"));
        }
        let len = r.varu()?;
        let at = d.bytes.len() - r.remaining();
        let end = (len as usize)
            .checked_add(at)
            .filter(|&e| e <= d.bytes.len() && len <= usize::MAX as u64)
            .ok_or(bad("a DISP chunk runs past its section"))?;
        chunks.push(&d.bytes[at..end]);
        r = Reader::new(&d.bytes[end..]);
    }
    // The header's counts against the base's, before any allocation:
    // the container checked the header's triangles against the limits.
    let (h, bh) = (&file.header, &base.header);
    let expected = u64::from(bh.triangle_count)
        .checked_shl(2 * chunks.len() as u32)
        .filter(|&t| t >> (2 * chunks.len()) == u64::from(bh.triangle_count));
    if expected != Some(u64::from(h.triangle_count)) {
        let declared = u64::from(h.triangle_count);
        return Err(crate::lossless::mismatch(
            "triangles",
            declared,
            expected.unwrap_or(u64::MAX),
        ));
    }
    Ok(Parsed { head, base, chunks })
}

/// One level up: the positions of the new vertices (appended) and the
/// triangles of the split. `frames` and `qs` hold one frame and one
/// scalar per edge. The encoder's closed loop (`write`); the decoder
/// places a level in one pass (`predict::place_level`), to the same bits.
#[cfg(feature = "encoder")]
pub(crate) fn refine(
    positions: &mut Vec<[f32; 3]>,
    triangles: &[[u32; 3]],
    edges: &Edges,
    frames: &[predict::Frame],
    step: f32,
    qs: &[i32],
) -> Result<Vec<[u32; 3]>, Error> {
    let n = positions.len();
    positions.reserve(qs.len());
    for (f, &q) in frames.iter().zip(qs) {
        positions.push(predict::place(f, q, step).ok_or(bad("a displaced vertex is not finite"))?);
    }
    Ok(subdivide::split(triangles, edges, n as u32))
}

/// Decodes at most `max_levels` of the file's levels (a parsed
/// container; `usize::MAX` for all): what the file cut after that many
/// decodes to, since each level reads only its own chunk.
pub(crate) fn decode_levels(
    file: &Container<'_>,
    limits: &Limits,
    max_levels: usize,
) -> Result<TriMesh, Error> {
    let p = parse(file, limits)?;
    let base = crate::lossless::decode(&p.base, limits)?;
    let mut r = Refiner::new(p.head, base, &file.header);
    for chunk in p.chunks.iter().take(max_levels) {
        r.refine(chunk)?;
    }
    let found = r.mesh.positions.len() as u64;
    if max_levels >= p.chunks.len() && found != r.caps.0 {
        return Err(crate::lossless::mismatch("vertices", r.caps.0, found));
    }
    Ok(r.mesh)
}

/// What [`decode_levels_into`] did with the caller's buffers.
pub(crate) enum Placed {
    /// The last level is in them: its vertex and triangle counts.
    Written(usize, usize),
    /// No level was decoded: the base, for the caller to copy.
    Base(TriMesh),
}

/// [`decode_levels`] into the caller's `positions` and `indices`, which
/// hold at least the header's counts: the last level is written there
/// directly (`Refiner::refine_into`).
pub(crate) fn decode_levels_into(
    file: &Container<'_>,
    limits: &Limits,
    max_levels: usize,
    positions: &mut [f32],
    indices: &mut [u32],
) -> Result<Placed, Error> {
    let p = parse(file, limits)?;
    let base = crate::lossless::decode(&p.base, limits)?;
    let mut r = Refiner::new(p.head, base, &file.header);
    let caps = r.caps;
    let chunks = &p.chunks[..max_levels.min(p.chunks.len())];
    let placed = match chunks.split_last() {
        Some((last, coarser)) => {
            for chunk in coarser {
                r.refine(chunk)?;
            }
            let (vertices, triangles) = r.refine_into(last, positions, indices)?;
            Placed::Written(vertices, triangles)
        }
        None => Placed::Base(r.mesh),
    };
    let vertices = match &placed {
        Placed::Written(v, _) => *v,
        Placed::Base(mesh) => mesh.positions.len(),
    };
    if max_levels >= p.chunks.len() && vertices as u64 != caps.0 {
        return Err(crate::lossless::mismatch(
            "vertices",
            caps.0,
            vertices as u64,
        ));
    }
    Ok(placed)
}

/// A buffer of [`decode_levels_into`] too short for what it decodes
/// (the caller sizes them by the header, so only a bug reaches this).
fn short() -> Error {
    bad("a level larger than its buffers")
}

/// A decode one level at a time, coarse to fine: `decode_levels`, and
/// the stream decoder as each level's chunk arrives. Holds the mesh so
/// far and the scalars of its last level (the next level's contexts).
#[derive(Debug)]
pub(crate) struct Refiner {
    head: Head,
    /// The outer header's vertex and triangle counts: no level exceeds
    /// them (a stream's levels are decoded before `DISP` is all in).
    caps: (u64, u64),
    mesh: TriMesh,
    /// The last level's scalars, and the first vertex it made.
    below: Vec<i32>,
    first: usize,
    level: usize,
    /// The last level's edges and the triangles it split, from which the
    /// next level's edges are derived (`finer`) when one comes.
    split: Option<(Edges, Vec<[u32; 3]>)>,
}

impl Refiner {
    fn new(head: Head, base: TriMesh, header: &Header) -> Refiner {
        Refiner {
            head,
            caps: (header.vertex_count.into(), header.triangle_count.into()),
            first: base.positions.len(),
            mesh: base,
            below: Vec::new(),
            level: 0,
            split: None,
        }
    }

    /// From the payloads of `HEAD` and `BASE` (at file offset
    /// `base_at`) of a file with this header: the level-0 mesh.
    pub(crate) fn start(
        head: &[u8],
        base: &[u8],
        base_at: usize,
        header: &Header,
        limits: &Limits,
    ) -> Result<Refiner, Error> {
        let (head, base) = head_and_base(head, base, base_at, header, limits)?;
        Ok(Refiner::new(
            head,
            crate::lossless::decode(&base, limits)?,
            header,
        ))
    }

    /// Levels decoded so far (0: the base).
    pub(crate) fn level(&self) -> usize {
        self.level
    }

    /// The mesh of the last level decoded.
    pub(crate) fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// The next level from its chunk (`DISP`'s next, without its length).
    pub(crate) fn refine(&mut self, chunk: &[u8]) -> Result<(), Error> {
        let (edges, qs, step) = self.scalars(chunk)?;
        let mesh = &mut self.mesh;
        self.first = mesh.positions.len();
        let (tris, stencil) = (&mesh.triangles, self.head.stencil(self.level));
        predict::place_level(&edges, tris, &mut mesh.positions, stencil, step, &qs)
            .ok_or(bad("a displaced vertex is not finite"))?;
        let fine = subdivide::split(&mesh.triangles, &edges, self.first as u32);
        let coarse = core::mem::replace(&mut mesh.triangles, fine);
        self.split = Some((edges, coarse));
        self.below = qs;
        self.level += 1;
        Ok(())
    }

    /// The last level from its chunk, written into `positions` (`x y
    /// z` per vertex) and `indices` (three per triangle) instead of a new
    /// mesh: no copy of the finest level, the largest. Returns the
    /// vertex and triangle counts written; a buffer too short for them
    /// is an error (the caller checked the header's counts, which bound
    /// them).
    fn refine_into(
        mut self,
        chunk: &[u8],
        positions: &mut [f32],
        indices: &mut [u32],
    ) -> Result<(usize, usize), Error> {
        let (edges, qs, step) = self.scalars(chunk)?;
        let (old, tris) = (&self.mesh.positions, &self.mesh.triangles);
        let vertices = old.len() + edges.len();
        let (kept, new) = positions
            .get_mut(..3 * vertices)
            .ok_or_else(short)?
            .split_at_mut(3 * old.len());
        kept.copy_from_slice(old.as_flattened());
        let stencil = self.head.stencil(self.level);
        predict::place_into(&edges, tris, old, new, stencil, step, &qs)
            .ok_or(bad("a displaced vertex is not finite"))?;
        let out = indices.get_mut(..12 * tris.len()).ok_or_else(short)?;
        subdivide::split_into(tris, &edges, old.len() as u32, out);
        Ok((vertices, 4 * tris.len()))
    }

    /// The next level's edges, after the checks that bound it, and its
    /// scalars decoded from `chunk`, with its step.
    fn scalars(&mut self, chunk: &[u8]) -> Result<(Edges, Vec<i32>, f32), Error> {
        let Some(&step) = self.head.steps.get(self.level) else {
            return Err(bad("DISP has more levels than HEAD"));
        };
        if 4 * self.mesh.triangles.len() as u64 > self.caps.1 {
            return Err(bad("more triangles than the header's"));
        }
        let mesh = &self.mesh;
        // Derived from the level above when it allows (a third of the
        // sort's time), with the contexts of its scalars; else sorted.
        let below = &self.below;
        let derived = self
            .split
            .take()
            .and_then(|(e, t)| finer::finer(&e, &t, self.first as u32, below));
        let (edges, contexts) = match derived {
            Some(d) => d,
            None => {
                let edges = Edges::new(&mesh.triangles);
                let contexts = scalars::contexts(&edges, &mesh.triangles, self.first, below);
                (edges, contexts)
            }
        };
        check_count_fits(
            "scalar",
            edges.len() as u64,
            chunk.len(),
            scalars::MIN_BITS.0,
            scalars::MIN_BITS.1,
        )?;
        if mesh.positions.len() as u64 + edges.len() as u64 > self.caps.0 {
            return Err(bad("more vertices than the header's"));
        }
        let mut qs = core::mem::take(&mut self.below);
        scalars::decode_level(chunk, &contexts, &mut qs)?;
        Ok((edges, qs, step))
    }
}

/// The bytes of each level's chunk, the base's quantization bits and
/// what `HEAD` and `BASE` say (for `inspect`).
pub(crate) fn levels_and_qp(
    file: &Container<'_>,
    limits: &Limits,
) -> Result<(Vec<usize>, u8, DisplacedInfo), Error> {
    let p = parse(file, limits)?;
    let info = DisplacedInfo {
        rule: p.head.rule,
        steps: p.head.steps.clone(),
        bends: p
            .head
            .bends
            .iter()
            .map(|&b| (f64::from(b) * BEND_UNIT) as f32)
            .collect(),
        bare_base: p.head.bare,
        base_bytes: file.find(Tag::BASE).map_or(0, |s| s.bytes.len()),
    };
    let qp = p
        .base
        .section(Tag::HEAD)
        .and_then(|h| h.first().copied())
        .unwrap_or(0);
    // As strict as `decode` about the header's vertex count (issue 18):
    // the base is decoded, and each level adds one vertex per edge.
    let base = crate::lossless::decode(&p.base, limits)?;
    let found = vertices_after(&base, p.chunks.len());
    let declared = u64::from(file.header.vertex_count);
    if found != declared {
        return Err(crate::lossless::mismatch("vertices", declared, found));
    }
    Ok((p.chunks.iter().map(|c| c.len()).collect(), qp, info))
}

/// The vertices of `base` after `levels` levels: each level adds one per
/// edge (`subdivide::Edges`), and a level's edges are twice the last's
/// plus three per triangle (each edge split in two, three inside each
/// triangle) when no triangle repeats a vertex; otherwise the levels'
/// connectivity is split and counted.
fn vertices_after(base: &TriMesh, levels: usize) -> u64 {
    let mut v = base.positions.len() as u64;
    let repeats = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    if base.triangles.iter().any(repeats) {
        let mut triangles = base.triangles.clone();
        for _ in 0..levels {
            let edges = Edges::new(&triangles);
            triangles = subdivide::split(&triangles, &edges, v as u32);
            v += edges.len() as u64;
        }
        return v;
    }
    let mut e = Edges::new(&base.triangles).len() as u64;
    let mut t = base.triangles.len() as u64;
    for _ in 0..levels {
        v = v.saturating_add(e);
        e = e.saturating_mul(2).saturating_add(t.saturating_mul(3));
        t = t.saturating_mul(4);
    }
    v
}

/// The same file with only its first `levels` levels: its `DISP` cut
/// after that many chunks, its header's counts those of the coarser mesh
/// (decoded here to count its vertices), its CRC recomputed. What a
/// decoder that stops at a level boundary holds.
pub fn cut_levels(bytes: &[u8], levels: usize, limits: &Limits) -> Result<Vec<u8>, Error> {
    let file = parse_container(bytes, limits)?;
    if file.header.mode != Mode::Displaced {
        return Err(bad("not a displaced-subdivision (mode 2) file"));
    }
    let p = parse(&file, limits)?;
    let keep = levels.min(p.chunks.len());
    let mesh = decode_levels(&file, limits, keep)?;
    let mut disp = Vec::new();
    for c in &p.chunks[..keep] {
        crate::varint::put(&mut disp, c.len() as u64);
        disp.extend_from_slice(c);
    }
    // `ATTR` is coded over the finest level's mesh: a coarser file has
    // none (format-spec/08-attributes.md).
    let owned: Vec<(Tag, Vec<u8>)> = file
        .sections()
        .filter(|s| s.tag != Tag::ATTR || keep == p.chunks.len())
        .map(|s| {
            (
                s.tag,
                if s.tag == Tag::DISP {
                    disp.clone()
                } else {
                    s.bytes.to_vec()
                },
            )
        })
        .collect();
    let refs: Vec<(Tag, &[u8])> = owned.iter().map(|(t, b)| (*t, b.as_slice())).collect();
    let mut header = file.header;
    header.vertex_count = mesh.positions.len() as u32;
    header.triangle_count = mesh.triangles.len() as u32;
    crate::container::write_container(&header, &refs)
}
