//! Tip fitting: the angle code of a C chosen by the distance between its
//! triangle and the surface it covers, not by where its tip falls (issue
//! 19, "error-aware geometry"; beyond the thesis, which quantizes the
//! angle of the surface point V itself). Encoder only: the decoder reads
//! the code it is given.
//!
//! Once a C's triangloid is claimed (`Retiler::attempt`, in `triangle`), the region of
//! M the triangle stands for is known and does not depend on the code
//! (paths and region follow M's sample V, never X̂). From the aimed code
//! (V, moved by `offset`), the tip steps one code at a time towards the
//! neighbour that lowers
//!
//! ```text
//!   mean over the region's face corners p of  d(p, T)²        (M → T)
//! + mean over the FIT_POINTS x of T          of  d(x, region)²  (T → M)
//!
//!          tip                 FIT_POINTS, in barycentric weights
//!          /\                  (tip, GL, GR): the tip, the centroid,
//!         /  \                 the three edge midpoints, and the points
//!        / .  \                two thirds of the way to the tip and to
//!       /______\               GR from the centroid's side
//!     GL        GR
//! ```
//!
//! and stops where neither neighbour does, or [`FIT_CODES`] away.
//!
//! Why it pays: V is one point of the input, so on a scan it carries the
//! scan's roughness at the scale of L into the code; the region averages
//! it out. Both directions are needed: fitted to M → T alone, triangles
//! tilt onto their own region and leave the next ones, which share the
//! tip, farther off. Measured (BENCHMARKS.md, "Tip fitting"): 0.92-0.93x
//! the L2 at the same size over 85 files of five corpus scans and
//! organic models, 0.85-0.93x on a sphere roughened by 1% of its
//! radius; on perfectly smooth synthetic surfaces, where V is exact, the
//! codes spread and files of the same L grow by up to 9%, about 5% more
//! L2 at the same size.
//!
//! The cost itself, and the region it is measured against (`Region`,
//! scratch the run keeps), are in `fit_cost`; the descent over the codes
//! is here.
//!
//! Invariants: the code is one the tip's frame gives (the decoder
//! rebuilds X̂ from it bit for bit); a move needs a strict drop of the
//! cost ([`FIT_GAIN`]), so a flat region keeps the aimed code; the work
//! is O(region faces) per step, so O(input faces) per run overall; the
//! cost is bit for bit the exhaustive per-corner one (`fit_cost`,
//! issue 22).

use super::state::Retiler;
use crate::swing::Frame;
use glam::DVec3;

/// How far (in codes, either way) the descent may move the tip from the
/// aimed code: 34° at 6 angle bits. Measured on five corpus meshes at
/// 0.9-4.4 b/v: ±2 codes tried exhaustively bought 0.96x the L2, ±4
/// 0.94x, ±6 0.92x; the descent rarely goes that far.
pub(super) const FIT_CODES: i64 = 6;

/// The least relative drop of the cost for which the tip moves one code
/// further: any drop beyond rounding, so that a flat region never moves
/// it. A threshold as a rate-distortion guard was measured: 10% keeps a
/// third of the gain on the corpus (0.968x), 30% none (0.999x).
pub(super) const FIT_GAIN: f64 = 1e-9;

impl Retiler<'_> {
    /// The code, among those within [`FIT_CODES`] of `aimed`, whose tip
    /// makes the triangle (tip, `vl`, `vr`) nearest the region just
    /// claimed (`Flood::faces`), found by descent from `aimed`: a step to
    /// the better neighbour code while it lowers the cost. Returns
    /// `aimed` when the region is empty.
    pub(super) fn fit_code(&mut self, frame: &Frame, aimed: u32, vl: u32, vr: u32) -> u32 {
        let faces = self.flood.faces();
        if faces.is_empty() {
            return aimed;
        }
        let region = &mut self.fit_region;
        region.fill(&self.s, faces);
        let (gl, gr) = (self.xhat[vl as usize], self.xhat[vr as usize]);
        let table = &self.table;
        let mut cost = |code: u32| {
            let tip = DVec3::from_array(frame.point(table, code));
            region.two_sided([tip, gl, gr])
        };
        let n = 1i64 << table.bits();
        let code_at = |d: i64| (i64::from(aimed) + d).rem_euclid(n) as u32;
        let here = cost(aimed);
        let better = |c: f64, than: f64| c < than * (1.0 - FIT_GAIN);
        let (down, up) = (cost(code_at(-1)), cost(code_at(1)));
        let (step, mut best) = if better(down, here) && better(down, up) {
            (-1i64, (down, -1i64))
        } else if better(up, here) {
            (1, (up, 1))
        } else {
            return aimed;
        };
        while best.1.abs() < FIT_CODES.min(n / 2 - 1) {
            let next = best.1 + step;
            let c = cost(code_at(next));
            if !better(c, best.0) {
                break;
            }
            best = (c, next);
        }
        code_at(best.1)
    }
}

#[cfg(test)]
mod tests {
    use crate::metrics::{distance, DistanceOptions};
    use crate::{EncodeMode, EncodeOptions, SwingTarget, SwingTuning, TriMesh};

    /// Relative L2 between `mesh` and its retiling at `l` (6 angle bits),
    /// and the retiling's size.
    fn l2(mesh: &TriMesh, l: f64, fit_tips: bool) -> (f64, usize) {
        let options = EncodeOptions {
            mode: EncodeMode::Swing {
                target: SwingTarget::EdgeLength(l),
                angle_bits: Some(6),
                max_bytes: None,
            },
            swing: SwingTuning {
                fit_tips,
                ..SwingTuning::default()
            },
            ..EncodeOptions::default()
        };
        let encoded = crate::encode(mesh, &options).unwrap();
        let decoded = crate::decode(&encoded.bytes, &Default::default()).unwrap();
        let d = distance(mesh, &decoded, &DistanceOptions::area_uniform(20_000)).unwrap();
        (d.l2_relative(), encoded.bytes.len())
    }

    /// A sphere whose vertices are pushed along their radius by up to
    /// ±`amp` (a deterministic hash): a scan's roughness.
    fn rough(levels: u32, amp: f64) -> TriMesh {
        let mut m = crate::swing::retile::tests::sphere(levels);
        for (i, p) in m.positions.iter_mut().enumerate() {
            let h = (i as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 11;
            let u = h as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
            *p = p.map(|c| (f64::from(c) * (1.0 + amp * u)) as f32);
        }
        m
    }

    #[test]
    fn fitted_codes_bring_a_rough_surface_closer_at_about_the_same_size() {
        // A scan's roughness: radii off by up to 1%. Figures at L = 0.1,
        // 0.14, 0.2 when written: 0.89x, 0.85x, 0.90x the L2 times the
        // size.
        let mesh = rough(5, 0.01);
        let mut log_ratio = 0.0;
        for l in [0.1, 0.14, 0.2] {
            let (plain, plain_bytes) = l2(&mesh, l, false);
            let (fitted, fitted_bytes) = l2(&mesh, l, true);
            let ratio = fitted * fitted_bytes as f64 / (plain * plain_bytes as f64);
            eprintln!("L {l}: {plain:.3e} ({plain_bytes} B) -> {fitted:.3e} ({fitted_bytes} B): {ratio:.3}");
            log_ratio += ratio.ln() / 3.0;
        }
        assert!(log_ratio.exp() < 0.95, "geometric mean {}", log_ratio.exp());
    }
}
