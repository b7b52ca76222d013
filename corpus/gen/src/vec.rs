//! Small `f64` vector helpers.
//!
//! The crate depends on nothing but `swm`; generators compute in `f64` and
//! round to the `f32` positions of [`swm::TriMesh`] only at the end, so
//! that equal inputs always round the same way (determinism) and that
//! nearby but distinct points stay distinct.

/// A point or vector in 3D.
pub(crate) type V3 = [f64; 3];

#[inline]
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline]
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline]
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
pub(crate) fn length(a: V3) -> f64 {
    dot(a, a).sqrt()
}

#[inline]
pub(crate) fn dist(a: V3, b: V3) -> f64 {
    length(sub(a, b))
}

/// `a` scaled to unit length, or the zero vector if `a` is (nearly) zero.
#[inline]
pub(crate) fn normalize(a: V3) -> V3 {
    let l = length(a);
    if l > 1e-300 {
        scale(a, 1.0 / l)
    } else {
        [0.0; 3]
    }
}

/// `a + t (b - a)`.
#[inline]
pub(crate) fn lerp(a: V3, b: V3, t: f64) -> V3 {
    add(a, scale(sub(b, a), t))
}

/// Twice the area vector of triangle `abc` (counter-clockwise normal).
#[inline]
pub(crate) fn tri_normal(a: V3, b: V3, c: V3) -> V3 {
    cross(sub(b, a), sub(c, a))
}

/// The angle between two vectors, in radians, via `atan2` (accurate for
/// angles near 0 and pi, unlike `acos` of a dot product).
#[inline]
pub(crate) fn angle(u: V3, v: V3) -> f64 {
    length(cross(u, v)).atan2(dot(u, v))
}

/// The smallest interior angle of triangle `abc`, in radians.
pub(crate) fn min_angle(a: V3, b: V3, c: V3) -> f64 {
    let aa = angle(sub(b, a), sub(c, a));
    let bb = angle(sub(c, b), sub(a, b));
    let cc = angle(sub(a, c), sub(b, c));
    aa.min(bb).min(cc)
}

/// Rounds a point to the `f32` storage of [`swm::TriMesh`].
#[inline]
pub(crate) fn to_f32(p: V3) -> [f32; 3] {
    [p[0] as f32, p[1] as f32, p[2] as f32]
}

/// Widens a stored position.
#[inline]
pub(crate) fn from_f32(p: [f32; 3]) -> V3 {
    [p[0] as f64, p[1] as f64, p[2] as f64]
}
