//! `CLRF` (format 1.1): the CLERS symbols of a SwingWrapper file coded
//! in one forward pass that rebuilds the vertices as it goes, so that
//! each symbol's model is chosen by the shape of the front at its gate
//! (format-spec/05-swing.md, "CLRF").
//!
//! Why: the retiler decides a gate's label from the decoded geometry
//! around it (an ear where the front's angle at GL or GR is sharp, a C
//! where both are wide; `retile::gate`), so the decoder can predict it
//! from the same geometry. Measured on horse, bunny and spot retiled at
//! 1-2 b/v: 0.14-0.20 bits per symbol with the two angles' quadrants
//! as context against 0.76-0.80 with the previous symbol (`CLRS`), a
//! fifth to a quarter of a typical file (BENCHMARKS.md, "Front
//! contexts").
//!
//! The pass ([`run`]) walks the symbols in Edgebreaker order over the
//! front of [`super::front::Loops`]: per gate, the context, then the
//! symbol; a C takes its angle code from `GEOM` (and its level from
//! `DENS`), with the contexts those streams already use, and its tip is
//! placed by [`super::angle::Frame`] exactly as `rebuild_positions`
//! places it; an S names its tip's node. The encoder runs the same pass
//! over the symbols it knows ([`encode`]), so both sides see the same
//! contexts by construction. The pass also builds each symbol's
//! triangle (tip, GL, GR) off the front (`Loops::built`) and, in the
//! decoder ([`decode`]), reads its `HOLE` bit with the context of the
//! triangles across its edges, so a `CLRF` file decodes in this one
//! pass: no corner table, no Spirale Reversi, no second walk (issue 22;
//! the same mesh as connectivity decoding gives on every file swm
//! writes, which the encoder checks before it keeps `CLRF`).
//!
//! Stream: one range-coded stream (03-entropy.md) of, per symbol, the
//! symbol in `SYM[ctx]` (16 adaptive models over C, L, E, R, S); after
//! an S, its tip node as z = (nodes made so far − 1 − node): the bit
//! length ℓ of z in the adaptive model `SPLIT` (33 symbols), then the
//! ℓ − 1 bits below the leading one, raw (two chunks above 16 bits).

use crate::prelude::*;

use super::angle::{first_edge_length, push_point, tip_radius, AngleTable, Frame, Hinge};
use super::front::{Built, Loops, CONTEXTS};
use super::{chain, density, hole, residual, stretch};
use crate::edgebreaker::Symbol;
#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{AdaptiveModel, ContextModel, Decoder};
use crate::lossless::mismatch;
use crate::{Error, FormatError, Malformed};

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// Symbols of the `SPLIT` model: bit lengths 0…32.
const SPLIT_LENGTHS: u32 = 33;

/// What the pass asks for, in order: the decoder reads it from the
/// streams, the encoder from the retiled mesh (and records the contexts).
pub(super) trait Source {
    /// The symbol of the next gate, whose context is `ctx`.
    fn symbol(&mut self, ctx: usize) -> Result<Symbol, Error>;
    /// The node of the tip of the S that builds triangle `t` at gate `gr`.
    fn split(&mut self, loops: &Loops, gr: u32, t: usize) -> Result<u32, Error>;
    /// The angle code of C tip `tip` on the gate `gl`, `gr`.
    fn code(&mut self, tip: usize, gl: usize, gr: usize) -> Result<u32, Error>;
    /// Its level (`None` in a file without `DENS`).
    fn level(&mut self, tip: usize, gl: usize, gr: usize) -> Result<Option<i8>, Error>;
    /// Its radius code (0 in a file without `RADS`); `behind` is the
    /// previous tip.
    fn stretch(&mut self, tip: usize, gl: usize, gr: usize, behind: usize) -> Result<i32, Error>;
    /// The tip was placed on GL, GR with previous tip P (vertex numbers).
    fn placed(&mut self, _gate: [u32; 3]) {}
    /// Triangle number `t` was built: its vertices and earlier
    /// neighbours (`first` for a component's first triangle, which has
    /// none).
    fn triangle(&mut self, _t: u32, _built: &Built, _first: bool) -> Result<(), Error> {
        Ok(())
    }
}

/// Checks that a triangle of the pass has three distinct vertices: a
/// front that names one vertex twice (a hostile stream) cannot build a
/// triangle on it.
fn distinct(b: &Built) -> Result<(), Error> {
    let [a, l, r] = b.tri;
    if a == l || a == r || l == r {
        return Err(bad("a triangle of the forward pass repeats a vertex"));
    }
    Ok(())
}

/// The forward pass over `symbols` symbols of a mesh of `vertices`
/// vertices whose components start with the triangles `first`; returns
/// the positions it placed. The caller has checked both counts against
/// the limits.
pub(super) fn run(
    src: &mut impl Source,
    first: &[[[f64; 3]; 3]],
    bits: u8,
    vertices: usize,
    symbols: usize,
    mut points: Option<&mut chain::Points<'_>>,
) -> Result<Vec<[f64; 3]>, Error> {
    let angles = AngleTable::new(bits);
    let r = first
        .first()
        .map_or(0.0, |f| tip_radius(first_edge_length(f)));
    let mut x: Vec<[f64; 3]> = Vec::with_capacity(vertices);
    let mut loops = Loops::default();
    let mut stack: Vec<(u32, u32)> = Vec::new();
    let mut done = 0usize;
    for (k, f) in first.iter().enumerate() {
        let base = x.len();
        if base + 3 > vertices {
            return Err(mismatch("vertices", vertices as u64, base as u64 + 3));
        }
        for p in f {
            push_point(&mut x, *p)?;
        }
        if let Some(p) = points.as_deref_mut() {
            p.start(k as u32, f)?;
        }
        let v = |i: usize| (base + i) as u32;
        let t0 = (k + done) as u32;
        let mut gate = Some(loops.start([v(0), v(1), v(2)], t0));
        let built = Built {
            tri: [v(0), v(1), v(2)],
            parent: t0,
            sides: [None, None],
        };
        src.triangle(t0, &built, true)?;
        while let Some(gr) = gate {
            if done == symbols {
                return Err(bad("the symbols end before the component closes"));
            }
            let gl = loops.gate(gr)?;
            let ctx = loops.context(gr, &x);
            // Triangles so far: each component's first, then one per symbol.
            let t = k + 1 + done;
            let tn = t as u32;
            done += 1;
            // The triangle a symbol builds is read off the front before
            // the front moves, and handed on once the move's checks passed.
            let symbol = src.symbol(ctx)?;
            let (built, next) = match symbol {
                Symbol::C => {
                    let tip = x.len();
                    if tip >= vertices {
                        // At least one more vertex than declared.
                        return Err(mismatch("vertices", vertices as u64, tip as u64 + 1));
                    }
                    let (vl, vr) = (loops.vertex(gl) as usize, loops.vertex(gr) as usize);
                    let behind = loops.behind(gr) as usize;
                    // Started before the angle, level and radius code are
                    // read: its dependent square roots and divisions then
                    // run beside their entropy decoding (`Hinge`).
                    let hinge = Hinge::new(x[vl], x[vr], x[behind]);
                    let q = src.code(tip, vl, vr)?;
                    if q >= angles.codes() {
                        return Err(bad("angle code out of range"));
                    }
                    let rk = match src.level(tip, vl, vr)? {
                        Some(l) => r * density::ratio(l),
                        None => r,
                    };
                    let rk = stretch::apply(bits, rk, src.stretch(tip, vl, vr, behind)?);
                    // A boundary loop's point (`chain`), else a swing tip.
                    let point = match points.as_deref_mut() {
                        Some(p) => p.tip(q, x[vl], x[vr], x[behind])?,
                        None => None,
                    };
                    match point {
                        Some(tip) => push_point(&mut x, tip)?,
                        None => {
                            let frame = Frame::on(&hinge, rk);
                            push_point(&mut x, frame.point(&angles, q))?;
                        }
                    }
                    src.placed([vl as u32, vr as u32, behind as u32]);
                    let built = loops.built(gr, Symbol::C, tip as u32);
                    (built, Some(loops.c(gr, tip as u32, tn)))
                }
                Symbol::L => {
                    let built = loops.built(gr, Symbol::L, 0);
                    (built, Some(loops.l(gr, tn)?))
                }
                Symbol::R => {
                    let built = loops.built(gr, Symbol::R, 0);
                    (built, Some(loops.r(gr, tn)?))
                }
                Symbol::S => {
                    let w = src.split(&loops, gr, t)?;
                    loops.check_s(gr, w)?;
                    let built = loops.built(gr, Symbol::S, w);
                    let (next, remembered) = loops.s(gr, w, tn)?;
                    stack.push(remembered);
                    (built, Some(next))
                }
                Symbol::E => {
                    let built = loops.built(gr, Symbol::E, 0);
                    loops.e(gr)?;
                    // Resume at the most recent gate still open.
                    let mut next = None;
                    while let Some((g, v)) = stack.pop() {
                        if !loops.consumed(g, v) {
                            next = Some(g);
                            break;
                        }
                    }
                    (built, next)
                }
            };
            distinct(&built)?;
            src.triangle(tn, &built, false)?;
            gate = next;
        }
    }
    if done != symbols {
        return Err(bad("more symbols than the components use"));
    }
    if x.len() != vertices {
        return Err(mismatch("vertices", vertices as u64, x.len() as u64));
    }
    Ok(x)
}

/// The models of the stream, fresh at its start.
struct Models {
    symbol: ContextModel,
    split: AdaptiveModel,
}

impl Models {
    fn new() -> Models {
        Models {
            symbol: ContextModel::new(CONTEXTS, 5),
            split: AdaptiveModel::new(SPLIT_LENGTHS),
        }
    }
}

/// What [`decode`] reads: the symbols, and each C tip's code and level
/// (those four only when asked to record them), the positions and the
/// triangles.
pub(super) struct Decoded {
    /// The number of C symbols (recorded or not).
    pub c_tips: usize,
    pub symbols: Vec<Symbol>,
    pub codes: Vec<u32>,
    /// `None` without `DENS`.
    pub levels: Option<Vec<i8>>,
    /// `None` without `RADS`.
    pub stretch: Option<Vec<i32>>,
    /// The positions the pass placed.
    pub positions: Vec<[f64; 3]>,
    /// The triangles the pass built, (tip, GL, GR) in order: the mesh.
    pub triangles: Vec<[u32; 3]>,
    /// `HOLE`'s bit per triangle, read in the pass (`None` without it).
    pub mask: Option<Vec<bool>>,
}

struct Reading<'a> {
    dec: Decoder<'a>,
    models: Models,
    geom: residual::Reader<'a>,
    dens: Option<density::Reader<'a>>,
    rads: Option<stretch::Reader<'a>>,
    hole: Option<hole::Reader<'a>>,
    /// Keep the symbols, codes, levels and radius codes (`inspect`, the
    /// encoder's check); decoding needs none of them.
    record: bool,
    out: Decoded,
}

impl Source for Reading<'_> {
    fn symbol(&mut self, ctx: usize) -> Result<Symbol, Error> {
        let code = self.dec.decode(self.models.symbol.get(ctx))?;
        let s = Symbol::from_code(code).ok_or(bad("CLERS code out of range"))?;
        if self.record {
            self.out.symbols.push(s);
        }
        Ok(s)
    }

    fn split(&mut self, loops: &Loops, _gr: u32, _t: usize) -> Result<u32, Error> {
        let l = self.dec.decode(&mut self.models.split)?;
        let z = match l {
            0 => 0u64,
            _ => {
                let below = l - 1;
                let low = if below > 16 {
                    let hi = self.dec.decode_bits(below - 16)?;
                    (u64::from(hi) << 16) | u64::from(self.dec.decode_bits(16)?)
                } else {
                    u64::from(self.dec.decode_bits(below)?)
                };
                (1u64 << below) | low
            }
        };
        let count = loops.count() as u64;
        if z >= count {
            return Err(bad("an S names a node not yet made"));
        }
        Ok((count - 1 - z) as u32)
    }

    fn code(&mut self, tip: usize, gl: usize, gr: usize) -> Result<u32, Error> {
        let q = self.geom.get(tip, gl, gr)?;
        self.out.c_tips += 1;
        if self.record {
            self.out.codes.push(q);
        }
        Ok(q)
    }

    fn triangle(&mut self, _t: u32, built: &Built, first: bool) -> Result<(), Error> {
        self.out.triangles.push(built.tri);
        match &mut self.hole {
            Some(h) => h.read_in_pass(built.parent, built.sides, first),
            None => Ok(()),
        }
    }

    fn level(&mut self, tip: usize, gl: usize, gr: usize) -> Result<Option<i8>, Error> {
        let Some(d) = &mut self.dens else {
            return Ok(None);
        };
        let l = d.get(tip, gl, gr)?;
        if let (true, Some(levels)) = (self.record, &mut self.out.levels) {
            levels.push(l);
        }
        Ok(Some(l))
    }

    fn stretch(&mut self, tip: usize, gl: usize, gr: usize, behind: usize) -> Result<i32, Error> {
        let Some(d) = &mut self.rads else {
            return Ok(0);
        };
        let j = d.get([tip, gl, gr, behind])?;
        if let (true, Some(out)) = (self.record, &mut self.out.stretch) {
            out.push(j);
        }
        Ok(j)
    }
}

/// Decodes `CLRF` (`bytes`) with `GEOM` (`geom`), `DENS` (`dens`),
/// `RADS` (`rads`) and `HOLE` (`hole`, each if the file has one),
/// keeping the symbols, codes, levels and radius codes when `record`:
/// `symbols` symbols, as `TOPO` counts them, of a mesh
/// of `vertices` vertices with angle bits `bits`, predicted code
/// `predicted` and first triangles `first`. Each stream must end exactly
/// where its encoder finished it.
#[allow(clippy::too_many_arguments)]
pub(super) fn decode(
    bytes: &[u8],
    geom: &[u8],
    dens: Option<&[u8]>,
    rads: Option<&[u8]>,
    hole: Option<&[u8]>,
    record: bool,
    first: &[[[f64; 3]; 3]],
    bits: u8,
    predicted: u32,
    vertices: usize,
    symbols: usize,
    mut points: Option<chain::Points<'_>>,
) -> Result<Decoded, Error> {
    let triangles = symbols.saturating_add(first.len());
    let mut src = Reading {
        dec: Decoder::new(bytes)?,
        models: Models::new(),
        geom: residual::Reader::new(geom, vertices, bits, predicted)?,
        dens: dens
            .map(|b| density::Reader::new(b, vertices))
            .transpose()?,
        rads: rads
            .map(|b| stretch::Reader::new(b, vertices, bits))
            .transpose()?,
        hole: hole.map(|b| hole::Reader::new(b, triangles)).transpose()?,
        record,
        out: Decoded {
            c_tips: 0,
            symbols: Vec::with_capacity(if record { symbols } else { 0 }),
            codes: Vec::new(),
            levels: dens.map(|_| Vec::new()),
            stretch: rads.map(|_| Vec::new()),
            positions: Vec::new(),
            triangles: Vec::with_capacity(triangles),
            mask: None,
        },
    };
    src.out.positions = run(&mut src, first, bits, vertices, symbols, points.as_mut())?;
    if let Some(p) = points {
        p.finish()?;
    }
    src.dec.finish()?;
    src.geom.finish()?;
    if let Some(d) = src.dens {
        d.finish()?;
    }
    if let Some(d) = src.rads {
        d.finish()?;
    }
    if let Some(h) = src.hole {
        src.out.mask = Some(h.finish()?);
    }
    Ok(src.out)
}

/// The encoder's side of the pass: the retiled mesh's own symbols,
/// codes and levels, with the contexts and split nodes it meets.
#[cfg(feature = "encoder")]
struct Replaying<'a> {
    symbols: &'a [Symbol],
    triangles: &'a [[u32; 3]],
    codes: &'a [u32],
    levels: Option<&'a [i8]>,
    stretch: Option<&'a [i32]>,
    /// Symbols used so far, and C tips placed so far (the index of the
    /// code and level the next C reads).
    at: (usize, usize),
    contexts: Vec<u8>,
    splits: Vec<u64>,
}

#[cfg(feature = "encoder")]
impl Source for Replaying<'_> {
    fn symbol(&mut self, ctx: usize) -> Result<Symbol, Error> {
        let s = *self
            .symbols
            .get(self.at.0)
            .ok_or(bad("fewer symbols than the pass needs"))?;
        self.at.0 += 1;
        self.contexts.push(ctx as u8);
        Ok(s)
    }

    /// The tip's node: the first with the tip's vertex walking the gate's
    /// loop forward from the vertex after next(GL) (an S), else any live
    /// node of it on another loop (an S\*).
    fn split(&mut self, loops: &Loops, gr: u32, t: usize) -> Result<u32, Error> {
        let w = self
            .triangles
            .get(t)
            .ok_or(bad("an S without its triangle"))?[0];
        let gl = loops.next(gr);
        let (stop, mut n) = (loops.prev(gr), loops.next(loops.next(gl)));
        let mut found = None;
        for _ in 0..loops.count() {
            if n == stop || n == gr {
                break;
            }
            if loops.vertex(n) == w {
                found = Some(n);
                break;
            }
            n = loops.next(n);
        }
        let excluded = [gr, gl, loops.next(gl), stop];
        let node = found
            .or_else(|| {
                (0..loops.count() as u32)
                    .find(|&k| loops.is_alive(k) && loops.vertex(k) == w && !excluded.contains(&k))
            })
            .ok_or(bad("an S whose tip is on no loop"))?;
        self.splits
            .push((loops.count() - 1) as u64 - u64::from(node));
        Ok(node)
    }

    fn code(&mut self, _tip: usize, _gl: usize, _gr: usize) -> Result<u32, Error> {
        let q = *self
            .codes
            .get(self.at.1)
            .ok_or(bad("fewer angle codes than C tips"))?;
        Ok(q)
    }

    fn level(&mut self, _tip: usize, _gl: usize, _gr: usize) -> Result<Option<i8>, Error> {
        match self.levels {
            Some(l) => Ok(Some(
                *l.get(self.at.1).ok_or(bad("fewer levels than C tips"))?,
            )),
            None => Ok(None),
        }
    }

    fn stretch(&mut self, _tip: usize, _gl: usize, _gr: usize, _: usize) -> Result<i32, Error> {
        match self.stretch {
            Some(j) => Ok(*j
                .get(self.at.1)
                .ok_or(bad("fewer radius codes than C tips"))?),
            None => Ok(0),
        }
    }

    /// A C tip is placed once its code and level were read: the next C
    /// reads the next ones.
    fn placed(&mut self, _gate: [u32; 3]) {
        self.at.1 += 1;
    }
}

/// Codes the symbols of a retiled mesh as `CLRF`: the pass over
/// `symbols` with the triangles in creation order (tip first), the C
/// tips' `codes`, `levels` (`None`: no `DENS`) and radius codes
/// `stretch` (`None`: no `RADS`), as the decoder will
/// meet them. Fails when the pass cannot follow the mesh (the caller then
/// writes `CLRS`).
#[cfg(feature = "encoder")]
#[allow(clippy::too_many_arguments)]
pub(super) fn encode(
    symbols: &[Symbol],
    triangles: &[[u32; 3]],
    codes: &[u32],
    levels: Option<&[i8]>,
    stretch: Option<&[i32]>,
    first: &[[[f64; 3]; 3]],
    bits: u8,
    vertices: usize,
    mut points: Option<chain::Points<'_>>,
) -> Result<Vec<u8>, Error> {
    let mut src = Replaying {
        symbols,
        triangles,
        codes,
        levels,
        stretch,
        at: (0, 0),
        contexts: Vec::with_capacity(symbols.len()),
        splits: Vec::new(),
    };
    run(
        &mut src,
        first,
        bits,
        vertices,
        symbols.len(),
        points.as_mut(),
    )?;
    if let Some(p) = points {
        p.finish()?;
    }
    let mut enc = Encoder::new();
    let mut models = Models::new();
    let mut splits = src.splits.iter();
    for (&s, &ctx) in symbols.iter().zip(&src.contexts) {
        enc.encode(models.symbol.get(usize::from(ctx)), s as u32);
        if s == Symbol::S {
            let &z = splits.next().ok_or(bad("an S without its node"))?;
            let l = u64::BITS - z.leading_zeros();
            enc.encode(&mut models.split, l);
            if l > 1 {
                let below = l - 1;
                let low = z & ((1u64 << below) - 1);
                if below > 16 {
                    enc.encode_bits((low >> 16) as u32, below - 16);
                    enc.encode_bits((low & 0xFFFF) as u32, 16);
                } else {
                    enc.encode_bits(low as u32, below);
                }
            }
        }
    }
    Ok(enc.finish())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_that_repeats_a_vertex_is_refused() {
        let built = |tri| Built {
            tri,
            parent: 0,
            sides: [None, None],
        };
        assert!(distinct(&built([4, 5, 6])).is_ok());
        for tri in [[4, 4, 6], [4, 5, 4], [4, 6, 6]] {
            assert!(distinct(&built(tri)).is_err(), "{tri:?}");
        }
    }

    /// Each symbol's triangle, its parent and its earlier neighbours, as
    /// the pass reads them off the front (a tetrahedron: C, R, E).
    #[test]
    fn the_front_names_the_triangles_the_symbols_build() {
        let mut f = Loops::default();
        let g = f.start([0, 1, 2], 0);
        // Gate 2 → 0: a C builds (3, 0, 2), its parent the first triangle.
        let b = f.built(g, Symbol::C, 3);
        assert_eq!((b.tri, b.parent, b.sides), ([3, 0, 2], 0, [None, None]));
        let g = f.c(g, 3, 1);
        // Loop 0 → 1 → 2 → 3 → 0; gate 2 → 3: an R closes (1, 3, 2) on
        // the first triangle's edge 1 → 2.
        let b = f.built(g, Symbol::R, 0);
        assert_eq!((b.tri, b.parent, b.sides), ([1, 3, 2], 1, [Some(0), None]));
        let g = f.r(g, 2).unwrap();
        // Loop 0 → 1 → 3 → 0: an E closes (0, 3, 1) on three earlier
        // triangles.
        let b = f.built(g, Symbol::E, 0);
        assert_eq!(b.tri, [0, 3, 1]);
        assert_eq!(b.parent, 2);
        assert_eq!(b.sides, [Some(1), Some(0)]);
        assert!(distinct(&b).is_ok());
    }
}
