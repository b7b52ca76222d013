//! The `LOOP` section of the SwingWrapper mode (format 1.1): components
//! whose retiling starts on a boundary loop of the input instead of on a
//! first triangle inside it (format-spec/05-swing.md, "LOOP"; issue 20,
//! open surfaces).
//!
//! An open component used to be closed by a patch over each hole, retiled
//! like the rest and masked away: the masked triangles took up to three
//! quarters of a file (alligator, woody), and the kept triangles' border
//! was a zigzag at the scale of L across the hole's rim. A component that
//! starts on a loop instead begins with a *fan*: its first triangle is
//! (b0, b1, D), with b0 and b1 two consecutive points of the loop and D a
//! dummy vertex standing for the hole; its next `n − 2` C tips are the
//! other points of the loop, each on gate (previous point, D), and an R
//! closes the fan on b1. After that the front is the loop itself, and the
//! retiling grows away from it over the surface only.
//!
//! ```text
//!          b1 ─── b0 ─── x1 ─── x2 ─── …      the loop, in coding order
//!            ╲    |     ╱      ╱
//!             ╲   |    ╱    ╱              fan triangles (tip, GL, D),
//!              ╲  |   ╱  ╱                 masked by HOLE like a patch
//!                  D
//! ```
//!
//! A loop point is not a swing tip, but it is built like one: it lies at
//! the loop's step ρ = |b0 − b1| from GL, in a direction turned from the
//! loop's own (P → GL) by two angle codes,
//!
//! ```text
//!   t = (GL − P)/|GL − P|,  u = the part of D − GL across t, normalized,
//!   w = t × u
//!   X = GL + ρ·( cos b·(cos a·t + sin a·u) + sin b·w )
//! ```
//!
//! `a` turning within the fan's plane, `b` out of it, both on the 2^K
//! grid of the angles (`angle::AngleTable`, exact on every platform). A
//! smooth loop turns little per step, so both codes are near 0 and cost
//! little; the point's distance along the loop is not coded at all (any
//! point of the boundary serves). Each code goes as its zig-zag's bit
//! length (an adaptive model per angle) and the bits below the leading
//! one, raw. The C tips of a fan still have their code in `GEOM` (the
//! predicted code, which the decoder requires and ignores) and their
//! step in `DENS`, so those streams and `CLRF` walk every C tip as
//! before.
//!
//! Invariants: the encoder places loop points with [`place`], the
//! decoder's arithmetic (binary64, the angle table's exact cosines), so
//! the retiler's positions are the decoded ones bit for bit; a decoder
//! reads one pair of codes per loop point in coding order and checks
//! that every loop's points are C tips of its own component.

use crate::prelude::*;

#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{AdaptiveModel, Decoder};
use crate::{Error, FormatError, Malformed};

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

use super::angle::{cross, dot, sub, AngleTable};
use crate::math::sqrt;

/// The frame of a loop point: `t` along P → GL, `u` across it towards
/// D, `w = t × u`; `None` when GL = P.
fn frame(gl: [f64; 3], p: [f64; 3], d: [f64; 3]) -> Option<[[f64; 3]; 3]> {
    let t = sub(gl, p);
    let tl = sqrt(dot(t, t));
    if !(tl > 0.0 && tl.is_finite()) {
        return None;
    }
    let t = t.map(|c| c / tl);
    let across = |e: [f64; 3]| {
        let k = dot(e, t);
        let e = [e[0] - (k * t[0]), e[1] - (k * t[1]), e[2] - (k * t[2])];
        let el = sqrt(dot(e, e));
        (el > 0.0 && el.is_finite()).then(|| e.map(|c| c / el))
    };
    let u = across(sub(d, gl)).or_else(|| {
        // D on the line of P and GL: the coordinate axis least parallel
        // to t (lowest index on ties) instead.
        let m = t.map(f64::abs);
        let k = if m[0] <= m[1] && m[0] <= m[2] {
            0
        } else if m[1] <= m[2] {
            1
        } else {
            2
        };
        let mut e = [0.0; 3];
        e[k] = 1.0;
        across(e)
    })?;
    Some([t, u, cross(t, u)])
}

/// A loop point: at `rho` from GL, turned by codes `q = [a, b]`; `None`
/// when GL = P (no direction to turn from).
pub fn place(
    gl: [f64; 3],
    p: [f64; 3],
    d: [f64; 3],
    rho: f64,
    table: &AngleTable,
    q: [u32; 2],
) -> Option<[f64; 3]> {
    let [t, u, w] = frame(gl, p, d)?;
    let (ca, sa) = (table.cos(q[0]), table.sin(q[0]));
    let (cb, sb) = (table.cos(q[1]), table.sin(q[1]));
    let mut x = [0.0; 3];
    for i in 0..3 {
        let dir = (cb * ((ca * t[i]) + (sa * u[i]))) + (sb * w[i]);
        x[i] = gl[i] + (rho * dir);
    }
    Some(x)
}

/// The codes that place a loop point nearest `target` (encoder side):
/// the nearest codes of its two angles, then the best of their
/// neighbours by the distance of the placed point.
#[cfg(feature = "encoder")]
pub fn aim(
    gl: [f64; 3],
    p: [f64; 3],
    d: [f64; 3],
    rho: f64,
    table: &AngleTable,
    target: [f64; 3],
) -> Option<[u32; 2]> {
    let [t, u, w] = frame(gl, p, d)?;
    let v = sub(target, gl);
    let (vt, vu, vw) = (dot(v, t), dot(v, u), dot(v, w));
    let n = table.codes() as i64;
    let step = core::f64::consts::TAU / n as f64;
    let code = |angle: f64| (angle / step).round() as i64;
    let a = code(vu.atan2(vt));
    let b = code(vw.atan2((vt * vt + vu * vu).sqrt()));
    let mut best: Option<(f64, [u32; 2])> = None;
    for da in -1..=1 {
        for db in -1..=1 {
            let q = [(a + da).rem_euclid(n) as u32, (b + db).rem_euclid(n) as u32];
            let x = place(gl, p, d, rho, table, q)?;
            let e = (0..3).map(|i| (x[i] - target[i]).powi(2)).sum::<f64>();
            if best.is_none_or(|(bd, _)| e < bd) {
                best = Some((e, q));
            }
        }
    }
    best.map(|(_, q)| q)
}

/// The loop's step: |b0 − b1|, the first two vertices of its
/// component's first triangle.
pub fn step_of(first: &[[f64; 3]; 3]) -> f64 {
    let d = sub(first[0], first[1]);
    sqrt(dot(d, d))
}

/// The loops of a file: which components start on one, and its length.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Loops {
    /// (component, points), components strictly increasing, points ≥ 3.
    pub entries: Vec<(u32, u32)>,
}

impl Loops {
    /// The points of component `c`'s loop (0 without one).
    pub fn points(&self, c: u32) -> u32 {
        self.entries
            .binary_search_by_key(&c, |e| e.0)
            .map_or(0, |k| self.entries[k].1)
    }

    /// Loop points that are C tips: `n − 2` per loop.
    #[cfg(feature = "encoder")]
    pub fn tips(&self) -> u64 {
        self.entries.iter().map(|e| u64::from(e.1) - 2).sum()
    }
}

/// Writes `LOOP`: the entries, then the two codes of every loop point
/// (`codes`, in order) for a file of `bits` angle bits.
#[cfg(feature = "encoder")]
pub fn encode(loops: &Loops, codes: &[[u32; 2]], bits: u8) -> Result<Vec<u8>, Error> {
    if loops.tips() != codes.len() as u64 || loops.entries.is_empty() {
        return Err(bad("loop codes are not two per loop point"));
    }
    let mut out = Vec::new();
    crate::varint::put(&mut out, loops.entries.len() as u64);
    for &(c, n) in &loops.entries {
        crate::varint::put(&mut out, u64::from(c));
        crate::varint::put(&mut out, u64::from(n));
    }
    let n = 1u32 << bits;
    let mut enc = Encoder::new();
    let mut models = models(bits);
    for q in codes {
        for (a, &code) in q.iter().enumerate() {
            if code >= n {
                return Err(bad("a loop code out of range"));
            }
            // The code as a signed K-bit number, zig-zag mapped.
            let s = if code >= n / 2 {
                i64::from(code) - i64::from(n)
            } else {
                i64::from(code)
            };
            let z = if s >= 0 { 2 * s } else { -2 * s - 1 } as u32;
            let l = u32::BITS - z.leading_zeros();
            enc.encode(&mut models[a], l);
            if l >= 2 {
                enc.encode_bits(z & ((1 << (l - 1)) - 1), l - 1);
            }
        }
    }
    out.extend_from_slice(&enc.finish());
    Ok(out)
}

/// `LEN[0]` (the turn within the fan's plane) and `LEN[1]` (out of
/// it), over the lengths 0 … K.
fn models(bits: u8) -> [AdaptiveModel; 2] {
    [0; 2].map(|_| AdaptiveModel::new(u32::from(bits) + 1))
}

/// The residual stream of `LOOP`.
pub struct Reader<'a> {
    dec: Decoder<'a>,
    models: [AdaptiveModel; 2],
    n: u32,
}

/// Parses the entries of `LOOP` for a file of `components` components,
/// `vertices` vertices and `bits` angle bits, and opens its stream.
pub fn read(
    bytes: &[u8],
    components: u64,
    vertices: u64,
    bits: u8,
) -> Result<(Loops, Reader<'_>), Error> {
    let mut r = crate::varint::Reader::new(bytes);
    let m = r.varu().map_err(Error::Format)?;
    if m == 0 || m > components {
        return Err(bad("LOOP names no component, or more than there are"));
    }
    // Two bytes at least per entry: a hostile count cannot size the
    // allocation beyond the section's own length.
    if m > (r.remaining() / 2) as u64 {
        return Err(bad("LOOP is shorter than its entries"));
    }
    let mut entries = Vec::with_capacity(m as usize);
    let mut tips = 0u64;
    for _ in 0..m {
        let c = r.varu().map_err(Error::Format)?;
        let n = r.varu().map_err(Error::Format)?;
        if c >= components || entries.last().is_some_and(|&(p, _)| u64::from(p) >= c) {
            return Err(bad(
                "LOOP's components are not increasing and below the count",
            ));
        }
        if !(3..=vertices).contains(&n) {
            return Err(bad(
                "a loop has fewer than 3 points or more than the vertices",
            ));
        }
        tips += n - 2;
        if tips > vertices {
            return Err(bad("the loops have more points than the vertices"));
        }
        entries.push((c as u32, n as u32));
    }
    let rest = &bytes[bytes.len() - r.remaining()..];
    Ok((
        Loops { entries },
        Reader {
            dec: Decoder::new(rest)?,
            models: models(bits),
            n: 1 << bits,
        },
    ))
}

impl Reader<'_> {
    /// The two codes of the next loop point.
    pub fn get(&mut self) -> Result<[u32; 2], Error> {
        let mut q = [0u32; 2];
        for (a, v) in q.iter_mut().enumerate() {
            let l = self.dec.decode(&mut self.models[a])?;
            let z = match l {
                0 | 1 => l,
                _ => (1 << (l - 1)) | self.dec.decode_bits(l - 1)?,
            };
            let s = if z & 1 == 0 {
                i64::from(z >> 1)
            } else {
                -i64::from(z >> 1) - 1
            };
            *v = s.rem_euclid(i64::from(self.n)) as u32;
        }
        Ok(q)
    }

    /// Checks that the stream ends where its encoder finished it.
    pub fn finish(self) -> Result<(), Error> {
        self.dec.finish()
    }
}

/// The loop rule over the triangles of the decoded `table`, in order:
/// `f(fan, tip)` with `fan` set for a loop's fan (the first `n`
/// triangles of a loop component; fewer if it has fewer) and, for a C
/// triangle, `tip = Some(loop tip)` (one of its component's first
/// `n − 2` C tips, the rule [`Points`] places by). The numbering was
/// checked when the positions were rebuilt.
fn walk(
    triangles: impl Iterator<Item = [u32; 3]>,
    loops: &Loops,
    mut f: impl FnMut(bool, Option<bool>),
) {
    let (mut next, mut component) = (0usize, 0u32);
    let (mut fan, mut tips) = (0u32, 0u32);
    for tri in triangles {
        let tip = if tri[1] as usize >= next {
            fan = loops.points(component);
            tips = fan.saturating_sub(2);
            component += 1;
            next += 3;
            None
        } else if tri[0] as usize == next {
            next += 1;
            let on_loop = tips > 0;
            tips = tips.saturating_sub(1);
            Some(on_loop)
        } else {
            None
        };
        f(fan > 0, tip);
        fan = fan.saturating_sub(1);
    }
}

/// The triangles of the decoded `table`, in order.
fn table_triangles(table: &crate::CornerTable) -> impl Iterator<Item = [u32; 3]> + '_ {
    table
        .vertices()
        .chunks_exact(3)
        .map(|t| [t[0].idx() as u32, t[1].idx() as u32, t[2].idx() as u32])
}

/// Per triangle of `triangles` (a decoded mesh's, in order, as the
/// `CLRF` pass builds them): it belongs to a loop's fan, which the
/// decoder drops with its dummy vertex.
pub fn fans_of(triangles: &[[u32; 3]], loops: &Loops) -> Vec<bool> {
    let mut out = Vec::with_capacity(triangles.len());
    walk(triangles.iter().copied(), loops, |fan, _| out.push(fan));
    out
}

/// Per triangle of the decoded `table`: it belongs to a loop's fan, which
/// the decoder drops with its dummy vertex.
pub fn fans(table: &crate::CornerTable, loops: &Loops) -> Vec<bool> {
    let mut out = Vec::with_capacity(table.face_count());
    walk(table_triangles(table), loops, |fan, _| out.push(fan));
    out
}

/// Per C tip of the decoded `table`, in order: it is a loop point.
#[cfg(feature = "encoder")]
pub fn loop_tips(table: &crate::CornerTable, loops: &Loops) -> Vec<bool> {
    let mut out = Vec::new();
    walk(table_triangles(table), loops, |_, tip| out.extend(tip));
    out
}

/// Where the loop points' codes come from: the `LOOP` stream, or
/// (encoder) the retiler's list.
pub enum Residuals<'a> {
    Stream(Box<Reader<'a>>),
    #[cfg(feature = "encoder")]
    List(core::slice::Iter<'a, [u32; 2]>),
}

impl Residuals<'_> {
    fn get(&mut self) -> Result<[u32; 2], Error> {
        match self {
            Residuals::Stream(r) => r.get(),
            #[cfg(feature = "encoder")]
            Residuals::List(it) => it
                .next()
                .copied()
                .ok_or(bad("fewer loop codes than loop points")),
        }
    }
}

/// The loop points of a file, as the placing pass walks its components:
/// which C tips are loop points, and where each goes.
pub struct Points<'a> {
    loops: &'a Loops,
    left: u32,
    res: Residuals<'a>,
    table: AngleTable,
    predicted: u32,
    rho: f64,
}

impl<'a> Points<'a> {
    /// The points of `loops` in a file of `bits` angle bits (already
    /// checked) and predicted code `predicted`.
    pub fn new(loops: &'a Loops, res: Residuals<'a>, bits: u8, predicted: u32) -> Self {
        Points {
            loops,
            left: 0,
            res,
            table: AngleTable::new(bits),
            predicted,
            rho: 0.0,
        }
    }

    /// Component `c` starts with the first triangle `first`; the
    /// previous one must have placed all its loop points.
    pub fn start(&mut self, c: u32, first: &[[f64; 3]; 3]) -> Result<(), Error> {
        if self.left != 0 {
            return Err(bad("a component ends before its loop's points"));
        }
        self.left = self.loops.points(c).saturating_sub(2);
        if self.left > 0 {
            self.rho = step_of(first);
            if !(self.rho > 0.0 && self.rho.is_finite()) {
                return Err(bad("a loop's first two points coincide"));
            }
        }
        Ok(())
    }

    /// The position of the next C tip, whose angle code is `q`, on gate
    /// GL = `gl`, GR = `gr` with previous tip `p`, when it is a loop
    /// point.
    pub fn tip(
        &mut self,
        q: u32,
        gl: [f64; 3],
        gr: [f64; 3],
        p: [f64; 3],
    ) -> Result<Option<[f64; 3]>, Error> {
        if self.left == 0 {
            return Ok(None);
        }
        self.left -= 1;
        if q != self.predicted {
            return Err(bad("a loop point's angle code is not the predicted code"));
        }
        let codes = self.res.get()?;
        place(gl, p, gr, self.rho, &self.table, codes)
            .map(Some)
            .ok_or(bad("a loop point on its predecessor"))
    }

    /// Every loop placed all its points, and the codes end there.
    pub fn finish(self) -> Result<(), Error> {
        if self.left != 0 {
            return Err(bad("a component ends before its loop's points"));
        }
        match self.res {
            Residuals::Stream(r) => (*r).finish(),
            #[cfg(feature = "encoder")]
            Residuals::List(mut it) => match it.next() {
                Some(_) => Err(bad("more loop codes than loop points")),
                None => Ok(()),
            },
        }
    }
}

#[cfg(all(test, feature = "encoder"))]
mod tests {
    use super::*;

    fn loops(entries: &[(u32, u32)]) -> Loops {
        Loops {
            entries: entries.to_vec(),
        }
    }

    #[test]
    fn codes_round_trip_at_every_length() {
        let l = loops(&[(0, 5), (2, 4)]);
        let codes = [[0, 0], [1, 255], [128, 127], [200, 3], [64, 192]];
        let bytes = encode(&l, &codes, 8).unwrap();
        let (back, mut r) = read(&bytes, 3, 100, 8).unwrap();
        assert_eq!(back, l);
        for q in codes {
            assert_eq!(r.get().unwrap(), q);
        }
        r.finish().unwrap();
        assert!(encode(&l, &codes[..4], 8).is_err());
        assert!(encode(&l, &[[256, 0]; 5], 8).is_err());
    }

    #[test]
    fn entries_are_checked_before_use() {
        let bad = |bytes: &[u8], c: u64, v: u64| read(bytes, c, v, 8).is_err();
        assert!(bad(&[0], 3, 100), "no entry");
        assert!(
            bad(&[4, 0, 3, 1, 3, 2, 3, 3, 3], 3, 100),
            "more entries than components"
        );
        assert!(bad(&[2, 1, 3, 1, 3], 3, 100), "components not increasing");
        assert!(bad(&[1, 3, 3], 3, 100), "component out of range");
        assert!(bad(&[1, 0, 2], 3, 100), "a loop of two points");
        assert!(bad(&[1, 0, 101], 3, 100), "more points than vertices");
        assert!(
            bad(&[2, 0, 60, 1, 60], 3, 100),
            "points of all loops over the vertices"
        );
        assert!(bad(&[1, 0], 3, 100), "truncated");
        assert!(bad(&[3, 0, 3], 1 << 30, 100), "a count beyond the section");
    }

    #[test]
    fn a_point_is_a_step_from_gl_turned_by_its_codes() {
        let table = AngleTable::new(8);
        let (gl, p, d) = ([1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 5.0, 0.0]);
        // Code 0, 0: straight on.
        assert_eq!(place(gl, p, d, 2.0, &table, [0, 0]), Some([3.0, 0.0, 0.0]));
        // A quarter turn towards D, then out of the fan's plane.
        let x = place(gl, p, d, 2.0, &table, [64, 0]).unwrap();
        assert!(
            (x[0] - 1.0).abs() < 1e-12 && (x[1] - 2.0).abs() < 1e-12,
            "{x:?}"
        );
        let x = place(gl, p, d, 2.0, &table, [0, 64]).unwrap();
        assert!(
            (x[0] - 1.0).abs() < 1e-12 && (x[2] - 2.0).abs() < 1e-12,
            "{x:?}"
        );
        // D on the line: the axis least parallel to t stands in for it.
        assert!(place(gl, p, [5.0, 0.0, 0.0], 1.0, &table, [64, 0]).is_some());
        assert_eq!(place(gl, gl, d, 1.0, &table, [0, 0]), None);
        // aim finds the codes back.
        for q in [[3, 0], [250, 2], [40, 251]] {
            let target = place(gl, p, d, 2.0, &table, q).unwrap();
            assert_eq!(aim(gl, p, d, 2.0, &table, target), Some(q));
        }
    }

    #[test]
    fn points_take_the_first_tips_of_their_component_only() {
        let l = loops(&[(1, 4)]);
        let codes = [[0, 0], [0, 0]];
        let first = [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 1.0, 0.0]];
        let mut p = Points::new(&l, Residuals::List(codes.iter()), 6, 9);
        p.start(0, &first).unwrap();
        assert_eq!(p.tip(3, [0.0; 3], [0.0; 3], [0.0; 3]).unwrap(), None);
        p.start(1, &first).unwrap();
        let x = p.tip(9, first[0], first[2], first[1]).unwrap().unwrap();
        assert_eq!(x, [2.0, 0.0, 0.0]);
        // A loop point's code must be the predicted one.
        assert!(p.tip(8, [2.0, 0.0, 0.0], first[2], first[0]).is_err());
        // The component ends with a point left.
        let mut p = Points::new(&l, Residuals::List(codes.iter()), 6, 9);
        p.start(1, &first).unwrap();
        p.tip(9, first[0], first[2], first[1]).unwrap();
        assert!(p.start(2, &first).is_err());
        let mut p = Points::new(&l, Residuals::List(codes.iter()), 6, 9);
        p.start(1, &first).unwrap();
        p.tip(9, first[0], first[2], first[1]).unwrap();
        assert!(p.finish().is_err());
        // Coinciding b0 and b1.
        let mut p = Points::new(&l, Residuals::List(codes.iter()), 6, 9);
        assert!(p.start(1, &[[0.0; 3]; 3]).is_err());
    }
}
