//! Geometry by dihedral angles: the exact arithmetic that turns a
//! quantized angle into a vertex (format-spec/05-swing.md, "The angle of a
//! C tip").
//!
//! Sources: M. Attene, *Surface Remeshing and Applications* (2004), §7:
//! every new vertex of a SwingWrapper mesh is the tip X of an isosceles
//! triangle of height r = L·√3/2 standing on a known gate (GL, GR), so it
//! lies on the circle of radius r around the gate's midpoint, in the
//! gate's bisecting plane, and one angle fixes it. The frame of that
//! circle and the anchoring of the quantization grid are this project's
//! (`../shared/design/ALGORITHMS.md` §5):
//!
//! ```text
//!            n (outward normal of the previous triangle)
//!            ^
//!            |      X(δ) = m + r·(cos δ·u − sin δ·n)
//!            |
//!   X(π) ----m----> u ---- T (previous tip)      δ = π: flat
//!            |                                  δ < π: convex edge
//!         X(π/2)                                δ > π: concave edge
//! ```
//!
//! Everything here that a decoder runs is `+ − × ÷` and `sqrt` on IEEE
//! binary64, rounded to nearest, in the order written (Rust never fuses a
//! multiply-add), and the cosine and sine of a quantized angle come from
//! fixed polynomials, not from the platform's `sin`/`cos`: so every
//! conforming decoder rebuilds the same bits. Must match the spec exactly.

use crate::prelude::*;

use crate::{Error, FormatError, Malformed};

/// Fewest angle bits a file may use.
pub const MIN_ANGLE_BITS: u8 = 4;
/// Most angle bits a file may use.
pub const MAX_ANGLE_BITS: u8 = 12;
/// √3/2, the tip height of an equilateral triangle of unit side, as the
/// binary64 literal the format names.
const HALF_SQRT_3: f64 = 0.866_025_403_784_438_6;

/// 2π as the binary64 value the format names, 6.283185307179586
/// (`0x401921FB54442D18`).
const TAU: f64 = core::f64::consts::TAU;

/// cos(π/4) = sin(π/4), correctly rounded: 0.7071067811865476
/// (`0x3FE6A09E667F3BCD`), so that the two halves of an octant meet
/// exactly.
const HALF_SQRT_2: f64 = core::f64::consts::FRAC_1_SQRT_2;

/// sin x = x + (x·z)·P(z), z = x², P(z) = Σ S[i]·z^i (Horner from the
/// last coefficient): the Taylor coefficients ±1/n!, n = 3, 5, …, 17, as
/// the nearest binary64. On [0, π/4] the first omitted term is below
/// 1e-19.
const SIN: [f64; 8] = [
    -1.666_666_666_666_666_6e-1,
    8.333_333_333_333_333e-3,
    -1.984_126_984_126_984e-4,
    2.755_731_922_398_589_3e-6,
    -2.505_210_838_544_172e-8,
    1.605_904_383_682_161_3e-10,
    -7.647_163_731_819_816e-13,
    2.811_457_254_345_520_6e-15,
];

/// cos x = 1 + z·Q(z), Q(z) = Σ C[i]·z^i: the coefficients ±1/n!,
/// n = 2, 4, …, 18.
const COS: [f64; 9] = [
    -0.5,
    4.166_666_666_666_666_4e-2,
    -1.388_888_888_888_889e-3,
    2.480_158_730_158_73e-5,
    -2.755_731_922_398_589e-7,
    2.087_675_698_786_81e-9,
    -1.147_074_559_772_972_5e-11,
    4.779_477_332_387_385e-14,
    -1.561_920_696_858_622_5e-16,
];

/// Horner's rule from the highest coefficient: p = c[last]; p = p·z + c[i].
fn horner(c: &[f64], z: f64) -> f64 {
    let (&last, rest) = c.split_last().expect("coefficients");
    rest.iter().rev().fold(last, |p, &k| p * z + k)
}

/// The square root, correctly rounded (IEEE 754 requires it of every
/// implementation; a `no_std` build must keep that property).
#[inline]
fn sqrt(x: f64) -> f64 {
    crate::math::sqrt(x)
}

/// Cosines and sines of the 2^K quantized angles qΔ, Δ = 2π/2^K.
///
/// Built by exact integer reduction to the first octant and fixed
/// polynomials there (see the module docs); symmetric exactly:
/// `cos(q) == cos(2^K − q)` and `sin(q) == −sin(2^K − q)`.
#[derive(Clone, Debug, PartialEq)]
pub struct AngleTable {
    bits: u8,
    cos: Vec<f64>,
    sin: Vec<f64>,
}

impl AngleTable {
    /// The table for `bits` angle bits.
    ///
    /// # Panics
    /// If `bits` is outside [`MIN_ANGLE_BITS`]`..=`[`MAX_ANGLE_BITS`]:
    /// callers check a value read from a file first.
    pub fn new(bits: u8) -> AngleTable {
        assert!(
            (MIN_ANGLE_BITS..=MAX_ANGLE_BITS).contains(&bits),
            "angle bits {bits} out of range"
        );
        let n = 1usize << bits;
        let (quarter, eighth) = (n / 4, n / 8);
        // Exact: a division by a power of two.
        let step = TAU / n as f64;
        // The first octant, j = 0 … n/8: x = j·Δ in [0, π/4].
        let octant: Vec<(f64, f64)> = (0..=eighth)
            .map(|j| {
                if j == eighth {
                    return (HALF_SQRT_2, HALF_SQRT_2);
                }
                let x = j as f64 * step;
                let z = x * x;
                let c = 1.0 + z * horner(&COS, z);
                let s = x + (x * z) * horner(&SIN, z);
                (c, s)
            })
            .collect();
        // The first quadrant by reflection about π/4.
        let first = |j: usize| -> (f64, f64) {
            if j <= eighth {
                octant[j]
            } else {
                let (c, s) = octant[quarter - j];
                (s, c)
            }
        };
        let mut cos = Vec::with_capacity(n);
        let mut sin = Vec::with_capacity(n);
        for q in 0..n {
            let (c, s) = first(q % quarter);
            let (c, s) = match q / quarter {
                0 => (c, s),
                1 => (-s, c),
                2 => (-c, -s),
                _ => (s, -c),
            };
            cos.push(c);
            sin.push(s);
        }
        AngleTable { bits, cos, sin }
    }

    /// Angle bits K (the retiler quantizes with it).
    #[cfg(any(test, feature = "encoder"))]
    pub fn bits(&self) -> u8 {
        self.bits
    }

    /// Number of codes, 2^K.
    pub fn codes(&self) -> u32 {
        1 << self.bits
    }

    /// cos(qΔ). Panics if `q >= 2^K`.
    #[inline]
    pub fn cos(&self, q: u32) -> f64 {
        self.cos[q as usize]
    }

    /// sin(qΔ). Panics if `q >= 2^K`.
    #[inline]
    pub fn sin(&self, q: u32) -> f64 {
        self.sin[q as usize]
    }
}

/// The code of the grid angle nearest `delta` (radians, any range): q =
/// round(δ/Δ) mod 2^K, the grid anchored at 0. A non-finite `delta` gives
/// code 0. Encoder side only: the decoder never measures an angle.
#[cfg(feature = "encoder")]
pub fn quantize(bits: u8, delta: f64) -> u32 {
    let n = 1i64 << bits;
    let steps = (delta / (TAU / n as f64)).round();
    // Saturating cast (NaN → 0); far-off angles only lose whole turns.
    let k = if steps.is_finite() {
        (steps % n as f64) as i64
    } else {
        0
    };
    k.rem_euclid(n) as u32
}

/// L = |X̂0 − X̂2|: the length of the first gate, the only length the
/// decoder knows.
pub fn first_edge_length(first: &[[f64; 3]; 3]) -> f64 {
    let d = sub(first[0], first[2]);
    sqrt(dot(d, d))
}

/// r = L·√3/2, the radius of every tip circle.
pub fn tip_radius(edge_length: f64) -> f64 {
    edge_length * HALF_SQRT_3
}

/// ((a·a') + (b·b')) + (c·c').
#[inline]
pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a × b, as `(a1·b2 − a2·b1, a2·b0 − a0·b2, a0·b1 − a1·b0)`.
#[inline]
pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// v / sqrt(v·v), one division per component.
#[inline]
fn normalize(v: [f64; 3]) -> [f64; 3] {
    let s = sqrt(dot(v, v));
    [v[0] / s, v[1] / s, v[2] / s]
}

/// `u` is degenerate when |u|² ≤ r²·2^−40 (|u| ≤ 2^−20·r), or NaN.
const DEGENERATE: f64 = 1.0 / (1u64 << 40) as f64;

/// The circle a C tip lies on: centre m, radius r, in the plane spanned
/// by u (towards the previous tip) and n (the previous triangle's outward
/// normal), both orthogonal to the gate direction e.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Midpoint of the gate.
    pub m: [f64; 3],
    /// Unit vector from m towards the previous tip, orthogonal to the gate.
    pub u: [f64; 3],
    /// u × e: the outward normal of the previous triangle (T, GR, GL).
    pub n: [f64; 3],
    /// Circle radius.
    pub r: f64,
}

/// The part of a [`Frame`] that its radius does not change: computed
/// from the gate and the previous tip alone, so the decoder can start
/// it (two square roots and six divisions in a dependent chain) as soon
/// as a symbol is a C, before it has read the angle code, level and
/// radius code that decide the tip (issue 22: the chain then overlaps
/// with their entropy decoding instead of following it). Same
/// operations, same order, same bits as computing the frame at once.
#[derive(Clone, Copy, Debug)]
pub struct Hinge {
    m: [f64; 3],
    e: [f64; 3],
    w: [f64; 3],
    /// normalize(w) and u × e, used unless w is degenerate for the radius.
    u: [f64; 3],
    n: [f64; 3],
}

impl Hinge {
    /// The hinge of the gate (gl, gr) whose previous tip is t.
    #[inline]
    pub fn new(gl: [f64; 3], gr: [f64; 3], t: [f64; 3]) -> Hinge {
        let m = [
            (gl[0] + gr[0]) * 0.5,
            (gl[1] + gr[1]) * 0.5,
            (gl[2] + gr[2]) * 0.5,
        ];
        let e = normalize(sub(gr, gl));
        let d = sub(t, m);
        let k = dot(d, e);
        let w = [d[0] - k * e[0], d[1] - k * e[1], d[2] - k * e[2]];
        // Computed even when the radius will call w degenerate (then
        // unused): a zero w only gives non-finite values here.
        let u = normalize(w);
        Hinge {
            m,
            e,
            w,
            u,
            n: cross(u, e),
        }
    }
}

impl Frame {
    /// The frame of the gate (gl, gr) whose previous tip is t. Never
    /// panics; hostile input (a zero-length gate, non-finite points) gives
    /// non-finite points, which `rebuild::rebuild_positions` rejects.
    ///
    /// Order of operations (must match the spec exactly):
    /// ```text
    /// m = (gl + gr)·0.5                     per axis: (gl[a] + gr[a]) * 0.5
    /// e = normalize(gr − gl)
    /// d = t − m;  k = d·e;  w = d − k·e     per axis: d[a] − (k * e[a])
    /// u = normalize(w), unless w·w ≤ (r·r)·2^−40 (or NaN): then
    ///     i = the axis of smallest |e[i]| (first on ties),
    ///     w = unit(i) − e[i]·e,  u = normalize(w)
    /// n = u × e                             per axis: (u[b]·e[c]) − (u[c]·e[b])
    /// ```
    pub fn new(gl: [f64; 3], gr: [f64; 3], t: [f64; 3], r: f64) -> Frame {
        Frame::on(&Hinge::new(gl, gr, t), r)
    }

    /// The frame of `hinge` with radius `r`: the hinge's `u` and `n`,
    /// or the fallback axis when `w` is degenerate for this radius.
    #[inline]
    pub fn on(hinge: &Hinge, r: f64) -> Frame {
        let (w, e) = (hinge.w, hinge.e);
        let (u, n) = if dot(w, w) > (r * r) * DEGENERATE {
            (hinge.u, hinge.n)
        } else {
            let mut i = 0;
            for a in 1..3 {
                if e[a].abs() < e[i].abs() {
                    i = a;
                }
            }
            let unit = |a: usize| if a == i { 1.0 } else { 0.0 };
            let u = normalize([
                unit(0) - e[i] * e[0],
                unit(1) - e[i] * e[1],
                unit(2) - e[i] * e[2],
            ]);
            (u, cross(u, e))
        };
        Frame {
            m: hinge.m,
            u,
            n,
            r,
        }
    }

    /// The tip of angle code q: m + r·(cos δ·u − sin δ·n), δ = qΔ, as
    /// per axis `m[a] + ((rc * u[a]) − (rs * n[a]))` with rc = r·cos δ,
    /// rs = r·sin δ. Panics if `q >= 2^K` (checked by the callers).
    pub fn point(&self, table: &AngleTable, q: u32) -> [f64; 3] {
        let rc = self.r * table.cos(q);
        let rs = self.r * table.sin(q);
        let (m, u, n) = (self.m, self.u, self.n);
        [
            m[0] + (rc * u[0] - rs * n[0]),
            m[1] + (rc * u[1] - rs * n[1]),
            m[2] + (rc * u[2] - rs * n[2]),
        ]
    }

    /// The dihedral angle δ of a point v about the gate, atan2(−d·n, d·u)
    /// with d = v − m, in (−π, π]. Encoder side (it uses `atan2`).
    #[cfg(feature = "encoder")]
    pub fn angle(&self, v: [f64; 3]) -> f64 {
        let d = sub(v, self.m);
        (-dot(d, self.n)).atan2(dot(d, self.u))
    }
}

/// Appends a point whose coordinates are finite and stay finite as f32.
pub(super) fn push_point(x: &mut Vec<[f64; 3]>, p: [f64; 3]) -> Result<(), Error> {
    if p.iter().all(|&c| (c as f32).is_finite()) {
        x.push(p);
        Ok(())
    } else {
        Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::NonFinite {
                vertex: x.len() as u64,
            },
        )))
    }
}
