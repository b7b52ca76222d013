//! Where a surface is sampled, Metro's way (Cignoni, Rocchini & Scopigno,
//! "Metro: measuring error on simplified surfaces", CGF 1998): every
//! vertex, points along every edge, and points on the faces in proportion
//! to their area.
//!
//! * **Faces.** With `N` face samples over total area `A` (density
//!   `ρ = N/A`), face `f` gets `⌊carry + ρ·area(f)⌋` samples, the fraction
//!   carried to the next face, so the total is `N` up to rounding. Inside
//!   a face the samples are *stratified*: the face is cut into `k²`
//!   similar sub-triangles (`k = ⌈√n⌉`), `n` of them are picked at an even
//!   stride from a random offset, and each holds one uniformly random
//!   point. Stratification keeps the estimate of the area integral close
//!   to its mean even at a few samples per face, which plain Monte Carlo
//!   does not.
//! * **Edges.** Each edge (once, however many faces share it) gets
//!   `⌊carry + √ρ·length⌋` evenly spaced interior points, as in Metro.
//! * **Vertices.** Every vertex that a face uses.
//!
//! Determinism: a face's random numbers come from a generator seeded by
//! `(seed, face index)`, and counts are carried in one fixed order, so the
//! samples do not depend on how the work is split between threads.
//! Samples are produced in the order of the surface's own (spatially
//! coherent) face order, which keeps consecutive nearest-point queries
//! close together.

use super::triangle::Tri;

/// SplitMix64 (Steele, Lea & Flood, 2014): tiny, and each face can start
/// its own stream from a hashed seed.
#[derive(Clone, Debug)]
pub struct SplitMix(u64);

impl SplitMix {
    /// The stream for item `index` of a sampling with seed `seed`.
    pub fn new(seed: u64, index: u64) -> Self {
        let mut s = SplitMix(seed ^ index.wrapping_mul(0xD1B5_4A32_D192_ED03));
        s.next_u64();
        s
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Per-item counts `⌊carry + density·measure⌋`, the fraction carried
/// forward in item order.
pub fn carried_counts(measures: impl Iterator<Item = f64>, density: f64) -> Vec<u64> {
    let mut carry = 0.0f64;
    measures
        .map(|m| {
            let x = carry + density * m;
            let n = x.floor().max(0.0);
            carry = x - n;
            n as u64
        })
        .collect()
}

#[inline]
fn wide(p: [f32; 3]) -> [f64; 3] {
    [p[0] as f64, p[1] as f64, p[2] as f64]
}

/// Area of a triangle, in `f64`.
pub fn area(t: &Tri) -> f64 {
    let (a, b, c) = (wide(t[0]), wide(t[1]), wide(t[2]));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

/// Calls `emit` with `n` stratified random points of triangle `t` (see the
/// module docs); `rng` is the face's own stream.
pub fn face_points(t: &Tri, n: u64, rng: &mut SplitMix, mut emit: impl FnMut([f64; 3])) {
    if n == 0 {
        return;
    }
    let (a, b, c) = (wide(t[0]), wide(t[1]), wide(t[2]));
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ac = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let k = (n as f64).sqrt().ceil().max(1.0) as u64;
    let k = if k * k < n { k + 1 } else { k };
    let cells = (k * k) as f64;
    let kf = k as f64;
    let offset = rng.unit();
    // Row r (along ac) holds 2(k − r) − 1 cells and starts at cell
    // r(2k − r); cells are visited in increasing order, so the row only
    // moves forward.
    let mut row = 0u64;
    let row_start = |r: u64| r * (2 * k - r);
    for j in 0..n {
        let m = (((j as f64 + offset) * cells / n as f64) as u64).min(k * k - 1);
        while row + 1 < k && m >= row_start(row + 1) {
            row += 1;
        }
        let s = m - row_start(row);
        let (q, upright) = (s / 2, s.is_multiple_of(2));
        let (mut r1, mut r2) = (rng.unit(), rng.unit());
        if r1 + r2 > 1.0 {
            (r1, r2) = (1.0 - r1, 1.0 - r2);
        }
        let (u, v) = if upright {
            ((q as f64 + r1) / kf, (row as f64 + r2) / kf)
        } else {
            ((q as f64 + 1.0 - r1) / kf, (row as f64 + 1.0 - r2) / kf)
        };
        emit([
            a[0] + u * ab[0] + v * ac[0],
            a[1] + u * ab[1] + v * ac[1],
            a[2] + u * ab[2] + v * ac[2],
        ]);
    }
}

/// Calls `emit` with `n` evenly spaced interior points of segment `pq`,
/// at `i/(n+1)` for `i = 1 … n`.
pub fn edge_points(p: [f32; 3], q: [f32; 3], n: u64, mut emit: impl FnMut([f64; 3])) {
    let (p, q) = (wide(p), wide(q));
    for i in 1..=n {
        let t = i as f64 / (n + 1) as f64;
        emit(core::array::from_fn(|k| p[k] + t * (q[k] - p[k])));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn carried_counts_sum_to_the_total() {
        let counts = carried_counts([0.3, 0.3, 0.3, 0.1].into_iter(), 10.0);
        assert_eq!(counts, vec![3, 3, 3, 1]);
        let counts = carried_counts(core::iter::repeat_n(1.0, 7), 0.5);
        assert_eq!(counts.iter().sum::<u64>(), 3);
    }

    #[test]
    fn face_points_are_inside_and_stratified() {
        for n in [1u64, 2, 3, 7, 16, 50, 1000] {
            let mut rng = SplitMix::new(7, n);
            let mut pts = Vec::new();
            face_points(&T, n, &mut rng, |p| pts.push(p));
            assert_eq!(pts.len() as u64, n);
            for p in &pts {
                assert!(
                    p[0] >= 0.0 && p[1] >= 0.0 && p[0] + p[1] <= 1.0 + 1e-12,
                    "{p:?}"
                );
                assert_eq!(p[2], 0.0);
            }
            if n == 1000 {
                // Stratified: the mean is much closer to the centroid than
                // the ~0.008 standard error of 1000 independent points.
                let mx = pts.iter().map(|p| p[0]).sum::<f64>() / n as f64;
                let my = pts.iter().map(|p| p[1]).sum::<f64>() / n as f64;
                assert!((mx - 1.0 / 3.0).abs() < 0.003, "{mx}");
                assert!((my - 1.0 / 3.0).abs() < 0.003, "{my}");
                // Every quarter triangle (the four similar halves-of-sides
                // cells) holds its share.
                let corner = pts.iter().filter(|p| p[0] + p[1] < 0.5).count();
                assert!((corner as i64 - 250).abs() <= 8, "{corner}");
            }
        }
    }

    #[test]
    fn same_seed_same_points() {
        let run = |seed| {
            let mut v = Vec::new();
            face_points(&T, 20, &mut SplitMix::new(seed, 3), |p| v.push(p));
            v
        };
        assert_eq!(run(1), run(1));
        assert_ne!(run(1), run(2));
    }

    #[test]
    fn edge_points_are_interior_and_even() {
        let mut v = Vec::new();
        edge_points([0.0; 3], [4.0, 0.0, 0.0], 3, |p| v.push(p[0]));
        assert_eq!(v, vec![1.0, 2.0, 3.0]);
    }
}
