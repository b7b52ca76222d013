//! The point of a triangle nearest to a given point, by the Voronoi-region
//! walk of Ericson, "Real-Time Collision Detection" (2005), §5.1.5: the
//! query falls in the region of a vertex, of an edge, or of the face, and
//! each case has a closed form.
//!
//! Degenerate triangles (zero area: a segment or a point) are surfaces of
//! measure zero but still real input: an edge region is taken only for an
//! edge of non-zero length (a zero-length edge passes its region test
//! trivially), and when the walk reaches the face case of a flat triangle
//! it falls back to the nearest of its three edges. The result is
//! always finite for finite input.
//!
//! Arithmetic is `f64` on `f32` corners, exactly converted.

/// A triangle's three corners.
pub type Tri = [[f32; 3]; 3];

#[inline(always)]
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn along(a: [f64; 3], d: [f64; 3], t: f64) -> [f64; 3] {
    [a[0] + d[0] * t, a[1] + d[1] * t, a[2] + d[2] * t]
}

#[inline(always)]
fn wide(p: [f32; 3]) -> [f64; 3] {
    [p[0] as f64, p[1] as f64, p[2] as f64]
}

/// `n / d` for `d > 0`, else 0 (a zero-length edge: any point of it will
/// do).
#[inline(always)]
fn ratio(n: f64, d: f64) -> f64 {
    if d > 0.0 {
        n / d
    } else {
        0.0
    }
}

/// The point of segment `ab` nearest to `p`.
fn on_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let ab = sub(b, a);
    let t = ratio(dot(sub(p, a), ab), dot(ab, ab)).clamp(0.0, 1.0);
    along(a, ab, t)
}

/// The point of triangle `t` nearest to `p`.
#[inline]
pub fn closest_point(p: [f64; 3], t: &Tri) -> [f64; 3] {
    closest_point_f64(p, &[wide(t[0]), wide(t[1]), wide(t[2])])
}

/// [`closest_point`] for a triangle of `f64` corners (the retiler's tip
/// fitting).
#[inline(always)]
pub fn closest_point_f64(p: [f64; 3], t: &[[f64; 3]; 3]) -> [f64; 3] {
    let (a, b, c) = (t[0], t[1], t[2]);
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let d1 = dot(ab, ap);
    let d2 = dot(ac, ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let d3 = dot(ab, bp);
    let d4 = dot(ac, bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
        return along(a, ab, ratio(d1, d1 - d3));
    }
    let cp = sub(p, c);
    let d5 = dot(ab, cp);
    let d6 = dot(ac, cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
        return along(a, ac, ratio(d2, d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0 {
        let w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
        return along(b, sub(c, b), w);
    }
    let sum = va + vb + vc;
    if sum > 0.0 && sum.is_finite() {
        let v = vb / sum;
        let w = vc / sum;
        return [
            a[0] + ab[0] * v + ac[0] * w,
            a[1] + ab[1] * v + ac[1] * w,
            a[2] + ab[2] * v + ac[2] * w,
        ];
    }
    // Flat triangle reached by rounding: the nearest of its edges.
    [
        on_segment(p, a, b),
        on_segment(p, b, c),
        on_segment(p, c, a),
    ]
    .into_iter()
    .min_by(|x, y| distance2(p, *x).total_cmp(&distance2(p, *y)))
    .unwrap_or(a)
}

/// Squared distance between two points.
#[inline(always)]
pub fn distance2(p: [f64; 3], q: [f64; 3]) -> f64 {
    let d = sub(p, q);
    dot(d, d)
}

/// Squared distance from `p` to triangle `t`.
#[inline]
pub fn triangle_distance2(p: [f64; 3], t: &Tri) -> f64 {
    distance2(p, closest_point(p, t))
}

/// [`triangle_distance2`] for a triangle of `f64` corners (the retiler's
/// tip fitting).
#[cfg(feature = "encoder")]
#[inline]
pub fn triangle_distance2_f64(p: [f64; 3], t: &[[f64; 3]; 3]) -> f64 {
    distance2(p, closest_point_f64(p, t))
}

/// Barycentric coordinates of `p` (a point on or near `t`) on `t`:
/// projected onto its plane, clamped to the triangle and summing to one;
/// a degenerate face gives its first corner.
#[cfg(feature = "encoder")]
pub fn barycentric(t: &[[f32; 3]; 3], p: [f64; 3]) -> [f32; 3] {
    let w = |q: [f32; 3]| q.map(|c| c as f64);
    let (a, b, c) = (w(t[0]), w(t[1]), w(t[2]));
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let (e0, e1, d) = (sub(b, a), sub(c, a), sub(p, a));
    let (d00, d01, d11) = (dot(e0, e0), dot(e0, e1), dot(e1, e1));
    let (d20, d21) = (dot(d, e0), dot(d, e1));
    let den = d00 * d11 - d01 * d01;
    if !(den > 0.0) || !den.is_finite() {
        return [1.0, 0.0, 0.0];
    }
    let v = ((d11 * d20 - d01 * d21) / den).max(0.0);
    let u = ((d00 * d21 - d01 * d20) / den).max(0.0);
    let (v, u) = if v + u > 1.0 {
        (v / (v + u), u / (v + u))
    } else {
        (v, u)
    };
    [(1.0 - v - u).max(0.0) as f32, v as f32, u as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Tri = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];

    #[test]
    fn every_region() {
        let d = |p: [f64; 3]| triangle_distance2(p, &T);
        // Face: straight above.
        assert_eq!(d([0.5, 0.5, 3.0]), 9.0);
        // Vertices.
        assert_eq!(d([-1.0, -1.0, 0.0]), 2.0);
        assert_eq!(d([3.0, -1.0, 0.0]), 2.0);
        assert_eq!(d([-1.0, 3.0, 0.0]), 2.0);
        // Edges ab, ac, bc.
        assert_eq!(d([1.0, -2.0, 0.0]), 4.0);
        assert_eq!(d([-2.0, 1.0, 0.0]), 4.0);
        assert_eq!(d([2.0, 2.0, 0.0]), 2.0);
        assert_eq!(closest_point([2.0, 2.0, 1.0], &T), [1.0, 1.0, 0.0]);
    }

    #[test]
    fn degenerate_triangles_stay_finite() {
        let segment: Tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert_eq!(triangle_distance2([1.5, 1.0, 0.0], &segment), 1.0);
        assert_eq!(triangle_distance2([3.0, 0.0, 0.0], &segment), 1.0);
        let point: Tri = [[1.0, 1.0, 1.0]; 3];
        assert_eq!(triangle_distance2([1.0, 1.0, 3.0], &point), 4.0);
        let doubled: Tri = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 3.0, 0.0]];
        assert_eq!(triangle_distance2([1.0, 2.0, 0.0], &doubled), 1.0);
    }

    #[test]
    fn matches_brute_force_on_random_points() {
        // The nearest point is no farther than a dense barycentric grid's
        // nearest point, and no nearer than it by more than the grid step.
        let mut rng = crate::mesh::test_rng::Rng(0x9e37_79b9_7f4a_7c15);
        let mut r = move || rng.unit() * 4.0 - 2.0;
        for _ in 0..200 {
            let t: Tri = core::array::from_fn(|_| core::array::from_fn(|_| r() as f32));
            let p = [r(), r(), r()];
            let exact = triangle_distance2(p, &t).sqrt();
            let n = 60;
            let mut grid = f64::INFINITY;
            for i in 0..=n {
                for j in 0..=n - i {
                    let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                    let q: [f64; 3] = core::array::from_fn(|k| {
                        t[0][k] as f64
                            + u * (t[1][k] as f64 - t[0][k] as f64)
                            + v * (t[2][k] as f64 - t[0][k] as f64)
                    });
                    grid = grid.min(distance2(p, q).sqrt());
                }
            }
            assert!(exact <= grid + 1e-12, "{exact} > {grid}");
            assert!(grid - exact < 0.1, "{exact} vs {grid}");
        }
    }
}
