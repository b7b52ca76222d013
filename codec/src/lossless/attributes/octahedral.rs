//! Normals on the octahedron: quantization, dequantization, the
//! prediction from the decoded geometry, and the residual's frame.
//!
//! Sources: the octahedral parametrization of unit vectors of Meyer et
//! al., "On floating-point normal vectors" (EGSR 2010) and Cigolle et
//! al., "A survey of efficient representations for independent unit
//! vectors" (JCGT 2014); the residual taken after turning the
//! prediction into the inner diamond is Draco's
//! `PredictionSchemeNormalOctahedronTransform` (the "invert diamond"
//! step); the prediction from the area-weighted normals of the faces
//! around a vertex is Draco's `MeshPredictionSchemeGeometricNormal`. The
//! integer arithmetic and the handling of the square's border are this
//! project's own (format-spec/08-attributes.md).
//!
//! ```text
//!   (−H, H) ┌───────┬───────┐ (H, H)      a unit vector (x, y, z), S = |x|+|y|+|z|:
//!           │ ╲ z<0 │ z<0 ╱ │             z ≥ 0: (a, b) = H·(x, y)/S, inside the diamond
//!           │   ╲   │   ╱   │             z < 0: folded out, (a, b) = H·(sgn x·(1 − |y|/S),
//!           ├─────(0,0)─────┤                                          sgn y·(1 − |x|/S))
//!           │   ╱   │   ╲   │             every point of the square [−H, H]² is a direction;
//!           │ ╱ z<0 │ z<0 ╲ │             the diamond's edge |a| + |b| = H is the equator
//!           └───────┴───────┘
//! ```
//!
//! `H = 2^(qn−1) − 1`: with `qn` bits each coordinate takes one of the
//! `2H + 1 < 2^qn` values `−H..=H`.
//!
//! Invariants: [`dequantize`] uses only IEEE binary64 `+ − × ÷` and one
//! square root, each rounded once, so every decoder gets the same `f32`
//! bits; [`invert`] applied twice gives the same direction (not always
//! the same coordinates: on the square's border, `(H, b)` and `(H, −b)`
//! are one direction), which is all the decoder's output depends on.

/// The worst angle, in degrees, between a unit normal and its
/// octahedral quantization at 8 bits (0.92° measured over a dense sphere
/// in the tests below; the decoded normal is the quantized one).
#[cfg(test)]
pub(crate) const NORMAL_ANGLE_8_BITS: f64 = 1.0;

/// Fewest and most bits per octahedral coordinate.
pub(crate) const MIN_BITS: u8 = 4;
/// See [`MIN_BITS`].
pub(crate) const MAX_BITS: u8 = 16;

/// The largest coordinate, `H = 2^(bits−1) − 1`.
pub(crate) fn half(bits: u8) -> i64 {
    (1i64 << (bits - 1)) - 1
}

/// `sgn(x)` with `sgn(0) = +1`, as the fold needs it.
fn sign(x: i64) -> i64 {
    if x < 0 {
        -1
    } else {
        1
    }
}

#[cfg(feature = "encoder")]
/// The octahedral coordinates of the direction of `n` (encoder side,
/// binary64): the nearest grid point of its exact coordinates. A zero
/// or non-finite vector becomes `(0, 0)`, the +z axis.
pub(crate) fn quantize(n: [f32; 3], bits: u8) -> [i64; 2] {
    let h = half(bits) as f64;
    let [x, y, z] = n.map(f64::from);
    let s = x.abs() + y.abs() + z.abs();
    if !(s > 0.0 && s.is_finite()) {
        return [0, 0];
    }
    let (mut u, mut v) = (x / s, y / s);
    if z < 0.0 {
        let sx = if x < 0.0 { -1.0 } else { 1.0 };
        let sy = if y < 0.0 { -1.0 } else { 1.0 };
        (u, v) = ((1.0 - v.abs()) * sx, (1.0 - u.abs()) * sy);
    }
    let round = |t: f64| (crate::math::floor(t * h + 0.5) as i64).clamp(-(h as i64), h as i64);
    [round(u), round(v)]
}

/// The unit vector of octahedral coordinates `q` (decoder side): exact
/// binary64 steps, rounded once to `f32` per component. Must match every
/// decoder exactly (format-spec/08-attributes.md, Normals).
pub(crate) fn dequantize(q: [i64; 2], bits: u8) -> [f32; 3] {
    let h = half(bits) as f64;
    let (mut u, mut v) = (q[0] as f64 / h, q[1] as f64 / h);
    let z = 1.0 - u.abs() - v.abs();
    if z < 0.0 {
        let su = if u < 0.0 { -1.0 } else { 1.0 };
        let sv = if v < 0.0 { -1.0 } else { 1.0 };
        (u, v) = ((1.0 - v.abs()) * su, (1.0 - u.abs()) * sv);
    }
    let len = crate::math::sqrt(u * u + v * v + z * z);
    [(u / len) as f32, (v / len) as f32, (z / len) as f32]
}

/// Rounded division `n / d` (`d > 0`), halves away from zero.
fn div_round(n: i128, d: i128) -> i128 {
    if n >= 0 {
        (2 * n + d) / (2 * d)
    } else {
        -((-2 * n + d) / (2 * d))
    }
}

/// The octahedral coordinates of the direction of the integer vector
/// `n` (a sum of face normals), in integer arithmetic only: the
/// prediction both sides compute. The zero vector gives `(0, 0)`.
pub(crate) fn of_vector(n: [i128; 3], bits: u8) -> [i64; 2] {
    let h = i128::from(half(bits));
    let s = n[0].abs() + n[1].abs() + n[2].abs();
    if s == 0 {
        return [0, 0];
    }
    // |a| + |b| ≤ H + 1 after rounding; each alone is at most H.
    let a = div_round(h * n[0], s) as i64;
    let b = div_round(h * n[1], s) as i64;
    if n[2] < 0 {
        let h = h as i64;
        [sign(a) * (h - b.abs()), sign(b) * (h - a.abs())]
    } else {
        [a, b]
    }
}

/// Whether `q` lies outside the inner diamond (the lower hemisphere).
pub(crate) fn is_outer(q: [i64; 2], bits: u8) -> bool {
    q[0].abs() + q[1].abs() > half(bits)
}

/// The direction mirrored through the equator (`z → −z`), in octahedral
/// coordinates: swaps the inner diamond and the outer triangles. The
/// residual of a normal whose prediction lies outside is taken between
/// the two mirrored, so that near the prediction the map is continuous
/// (Draco's "invert diamond"). Must match the encoder exactly.
pub(crate) fn invert(q: [i64; 2], bits: u8) -> [i64; 2] {
    let h = half(bits);
    [sign(q[0]) * (h - q[1].abs()), sign(q[1]) * (h - q[0].abs())]
}

/// The face-normal sum (twice the area-weighted normal) of the
/// triangles `(c, n, p)` given by their three integer grid points.
pub(crate) fn face_normal(c: [i64; 3], n: [i64; 3], p: [i64; 3]) -> [i128; 3] {
    let e = [n[0] - c[0], n[1] - c[1], n[2] - c[2]].map(i128::from);
    let f = [p[0] - c[0], p[1] - c[1], p[2] - c[2]].map(i128::from);
    [
        e[1] * f[2] - e[2] * f[1],
        e[2] * f[0] - e[0] * f[2],
        e[0] * f[1] - e[1] * f[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angle(a: [f32; 3], b: [f32; 3]) -> f64 {
        let a = a.map(f64::from);
        let b = b.map(f64::from);
        let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        let lb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
        (dot / la / lb).clamp(-1.0, 1.0).acos().to_degrees()
    }

    /// The worst angle of quantizing at `bits` over a dense sphere.
    pub(crate) fn worst_angle(bits: u8) -> f64 {
        let mut worst = 0f64;
        for i in 0..200 {
            for j in 0..400 {
                let th = std::f64::consts::PI * (i as f64 + 0.5) / 200.0;
                let ph = 2.0 * std::f64::consts::PI * j as f64 / 400.0;
                let n = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()].map(|x| x as f32);
                worst = worst.max(angle(n, dequantize(quantize(n, bits), bits)));
            }
        }
        worst
    }

    #[test]
    fn quantization_error_is_a_fraction_of_a_degree_at_8_bits() {
        let w = worst_angle(8);
        assert!(w < NORMAL_ANGLE_8_BITS, "{w}");
        assert!(worst_angle(12) < w / 10.0);
    }

    #[test]
    fn inverting_twice_keeps_the_direction() {
        for bits in [4u8, 8] {
            let h = half(bits);
            for a in -h..=h {
                for b in -h..=h {
                    let q = [a, b];
                    let back = invert(invert(q, bits), bits);
                    assert_eq!(dequantize(back, bits), dequantize(q, bits), "{q:?}");
                    let m = dequantize(invert(q, bits), bits);
                    let d = dequantize(q, bits);
                    assert!(
                        (m[2] + d[2]).abs() < 1e-6 && (m[0] - d[0]).abs() < 1e-6,
                        "{q:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn integer_directions_match_the_float_ones() {
        for n in [
            [3i128, -4, 5],
            [0, 0, -7],
            [1, 1, 0],
            [-2, 5, -9],
            [0, 0, 0],
        ] {
            let f = n.map(|x| x as f32);
            let q = of_vector(n, 8);
            let r = quantize(f, 8);
            assert!(
                (q[0] - r[0]).abs() <= 1 && (q[1] - r[1]).abs() <= 1,
                "{n:?} {q:?} {r:?}"
            );
        }
    }
}
