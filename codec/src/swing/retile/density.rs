//! Adaptive sampling (issue 19): the level of detail the retiler aims
//! for at each place of M, from M's curvature at the scale of the base
//! edge length L0. The file carries the result as one level step per C
//! tip (`swing::density`, format 1.1); this module only decides it.
//!
//! For isotropic triangles of side L on a surface of curvature κ the
//! chord error is about κ·L²/8, and a region of area A takes about
//! A/L² triangles; minimizing ∫ (κL²)² dA at a fixed ∫ L⁻² dA gives
//! L ∝ κ^(−1/3). So the target level at a vertex of M is
//!
//! ```text
//! ℓ = round(−(4/3)·log2(κ / κ_ref))        (ℓ in quarter octaves of L0)
//! ```
//!
//! clamped to [`FINEST`]..=[`COARSEST`], with κ the RMS curvature
//! sqrt((k1² + k2²)/2) of a least-squares quadric fitted to the edge
//! midpoints of M within [`SCALE`]·L0 (the samples of
//! `offset::sample_disk`), floored at [`FLAT`]/L0. κ_ref makes
//! the mean of (κ/κ_ref)^(2/3) over M's area 1, so that before clamping
//! the retiling has as many triangles as a uniform one at L0 and rate
//! control's search over L0 keeps its meaning. RMS rather than the mean
//! curvature `offset` uses: a saddle or a crease needs short edges as
//! much as a dome (the chord error grows with |κ|, whatever its sign),
//! and the samples across a thin part or a crease rightly count as high
//! curvature. A tip steps only when the target is more than
//! [`HYSTERESIS`] levels from its gate's.
//!
//! Measured: BENCHMARKS.md, "Adaptive sampling in the file" (opt-in: it
//! does not yet pay for its section on every mesh).
//!
//! Invariants: deterministic (fixed sample order, no threads); every
//! flood is bounded by `offset::MAX_FACES` faces and charged to the run's
//! work budget; targets are cached per vertex of M, so each costs one
//! flood.

use super::offset::{sample_disk, Scratch};
use super::surface::{face, Surface, NONE};
use crate::swing::LEVEL_MAX;

/// Finest target level: edges down to 2^(−6/4) ≈ 0.35 times L0.
pub(super) const FINEST: i8 = -6;
/// Coarsest target level: edges up to 2 L0 (longer ones leave too
/// little room for the front to turn on a small part).
pub(super) const COARSEST: i8 = 4;
/// Curvature floor, in 1/L0: a region flatter than that takes the
/// coarsest level anyway.
pub(super) const FLAT: f64 = 1e-3;
/// Radius of the disk whose curvature sets the target, in L0.
const SCALE: f64 = 2.0;
/// How far (in levels) the target must be from the gate's level before
/// a tip steps towards it.
const HYSTERESIS: f64 = 1.0;
/// Vertices of M sampled to calibrate κ_ref, at most.
const CALIBRATION_SAMPLES: usize = 4096;

/// The target level field over M.
pub(super) struct Field {
    l0: f64,
    /// log2 κ_ref.
    log_ref: f64,
    /// Per vertex of M: its target level (continuous), NaN before it is
    /// known, infinite where nothing can be measured.
    cache: Vec<f32>,
    sc: Scratch,
}

impl Field {
    /// Calibrates κ_ref on a spread of M's vertices (every k-th, by id).
    pub(super) fn new(s: &Surface, l0: f64) -> Field {
        let mut sc = Scratch::default();
        let n = s.vertex_count();
        let stride = n.div_ceil(CALIBRATION_SAMPLES).max(1);
        let (mut sum, mut area) = (0.0, 0.0);
        for x in (0..n as u32).step_by(stride) {
            let k = s.corner_of[x as usize];
            if k == NONE {
                continue;
            }
            let f = face(k);
            if s.patch(f) != NONE {
                continue;
            }
            let a = s.double_area(f);
            if let Some(kappa) = curvature(s, f, x, SCALE * l0, &mut sc) {
                sum += a * kappa.powf(2.0 / 3.0);
                area += a;
            }
        }
        let log_ref = if area > 0.0 && sum > 0.0 {
            1.5 * (sum / area).log2()
        } else {
            (1.0 / l0).log2()
        };
        Field {
            l0,
            log_ref,
            cache: Vec::new(),
            sc,
        }
    }

    /// The target level at vertex `x` of M.
    pub(super) fn at(&mut self, s: &Surface, x: u32) -> f32 {
        if self.cache.len() < s.vertex_count() {
            self.cache.resize(s.vertex_count(), f32::NAN);
        }
        if !self.cache[x as usize].is_nan() {
            return self.cache[x as usize];
        }
        let k = s.corner_of[x as usize];
        let level = if k == NONE || s.patch(face(k)) != NONE {
            // Nothing to measure (a hole patch is the encoder's own
            // filling): keep the gate's level.
            f32::INFINITY
        } else {
            match curvature(s, face(k), x, SCALE * self.l0, &mut self.sc) {
                Some(kappa) => {
                    let l = -(4.0 / 3.0) * (kappa.log2() - self.log_ref);
                    l.clamp(f64::from(FINEST), f64::from(COARSEST)) as f32
                }
                None => f32::INFINITY,
            }
        };
        self.cache[x as usize] = level;
        level
    }

    /// The level a tip on a gate of level `gate` whose anchors on M are
    /// `a` and `b` steps to: the mean of their targets, at most one step
    /// away, within the format's range.
    pub(super) fn step(&mut self, s: &Surface, gate: i8, a: u32, b: u32) -> i8 {
        // Called once per gate: no allocation for the two targets.
        let (mut sum, mut n) = (0.0, 0u32);
        for x in [a, b] {
            let t = if x == NONE {
                f32::INFINITY
            } else {
                self.at(s, x)
            };
            if t.is_finite() {
                sum += f64::from(t);
                n += 1;
            }
        }
        if n == 0 {
            return 0;
        }
        let mean = sum / f64::from(n);
        // A dead zone of one level either side: the target wanders by a
        // fraction of a level from vertex to vertex (scan noise, the two
        // anchors), and a step at every wobble would cost more bits than
        // the grading saves.
        let off = mean - f64::from(gate);
        let d = if off > HYSTERESIS {
            1
        } else if off < -HYSTERESIS {
            -1
        } else {
            0
        };
        if (gate + d).abs() > LEVEL_MAX {
            0
        } else {
            d
        }
    }
}

/// RMS curvature sqrt((k1² + k2²)/2) of M around vertex `x` (on face
/// `f`) at the scale `l0`, floored at [`FLAT`]/`l0`; `None` without
/// samples. From the weighted least-squares quadric
/// h = a·x² + b·xy + c·y² + d·x + e·y + g over the sampled disk, in the
/// frame of its mean normal: k1² + k2² is the trace of the squared
/// Hessian, 4a² + 2b² + 4c². A fit, unlike the sections' own curvatures
/// 2h/ρ², averages a scan's noise out instead of blowing it up near V.
fn curvature(s: &Surface, f: u32, x: u32, l0: f64, sc: &mut Scratch) -> Option<f64> {
    let v = s.pos[x as usize];
    let (n, _) = sample_disk(s, f, v, l0, sc)?;
    let t1 = n.any_orthonormal_vector();
    let t2 = n.cross(t1);
    // Normal equations, scaled by 1/l0 so that they stay well conditioned.
    let mut m = [[0.0f64; 7]; 6];
    for &(w, d) in sc.samples() {
        let (px, py, h) = (d.dot(t1) / l0, d.dot(t2) / l0, d.dot(n) / l0);
        let row = [px * px, px * py, py * py, px, py, 1.0];
        for i in 0..6 {
            for j in 0..6 {
                m[i][j] += w * row[i] * row[j];
            }
            m[i][6] += w * row[i] * h;
        }
    }
    let [a, b, c] = solve(m)?;
    // h/l0 = a (x/l0)² + …: curvatures in 1/l0.
    let k2 = 2.0 * a * a + b * b + 2.0 * c * c;
    Some((k2.sqrt() / l0).max(FLAT / l0))
}

/// The first three unknowns of the 6×6 system `m` (augmented), by
/// Gaussian elimination with partial pivoting; `None` when singular (too
/// few samples to fit a quadric).
fn solve(mut m: [[f64; 7]; 6]) -> Option<[f64; 3]> {
    let scale = (0..6).map(|i| m[i][i].abs()).fold(0.0, f64::max);
    if scale.is_nan() || scale <= 0.0 {
        return None;
    }
    for col in 0..6 {
        let p = (col..6).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        if m[p][col].abs() <= 1e-12 * scale {
            return None;
        }
        m.swap(col, p);
        let pivot = m[col];
        for row in m.iter_mut().skip(col + 1) {
            let k = row[col] / pivot[col];
            for (x, p) in row.iter_mut().zip(pivot).skip(col) {
                *x -= k * p;
            }
        }
    }
    let mut x = [0.0; 6];
    for i in (0..6).rev() {
        let mut acc = m[i][6];
        for j in i + 1..6 {
            acc -= m[i][j] * x[j];
        }
        x[i] = acc / m[i][i];
    }
    x[..3]
        .iter()
        .all(|v| v.is_finite())
        .then(|| [x[0], x[1], x[2]])
}
