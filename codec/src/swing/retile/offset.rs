//! Approximating tips (issue 19, "error-aware geometry"): where a C tip
//! is aimed, off the surface by the offset that cancels the mean chord
//! error of the triangles around it.
//!
//! The thesis puts every tip on M, so M′ interpolates M: over convex
//! parts every triangle lies inside. For a smooth surface with mean
//! curvature H and a triangle of side L whose vertices lie on it, the
//! deviation of the triangle from M averages H·L²/8 over its area (for
//! z = ½(k1·x² + k2·y²) and an equilateral triangle centred at 0, the
//! mean of the linear interpolant of x² is r²/2 = L²/6 and the mean of x²
//! is L²/24). Moving every vertex by that much along the normal makes the
//! mean deviation zero and cuts the RMS error of smooth regions by about
//! half; saddles (H = 0) stay where they are.
//!
//! H is estimated at the scale of L, not of the input's edges (a scanned
//! surface is rough at its own scale): the faces of M within Euclidean
//! distance [`REACH`]·L of V, found by adjacency from V's face, give
//! area-weighted samples at their edge midpoints (exact for quadratics).
//! With heights h over the plane through V with their mean normal and
//! squared tangential distances ρ², each sample gives the curvature 2h/ρ²
//! of the normal section through it; their mean weighted by w·ρ² is the
//! least-squares fit 2·Σw·h / Σw·ρ² (for a quadratic patch sampled
//! isotropically, Σw·h = H/2 · Σw·ρ², whatever the shape of the sampled
//! disk), and their weighted median, which swm uses, estimates H as well
//! on a smooth patch while ignoring a minority of samples across a
//! crease beside V.
//!
//! Where the disk wraps a thin part or spans a crease the quadratic model
//! fails: the coherence of the sampled normals (|Σw·n| / Σw, about
//! 1 − (L/R)²/8 on a smooth patch) fades the offset out between
//! [`COHERENT_HIGH`] and [`COHERENT_LOW`]. Measured over bunny, horse,
//! fandisk, spot, homer and cheburashka at 0.5-4 b/v (24 rd cells against
//! on-surface tips, 100k samples): without the fade the geometric mean of
//! the L2 ratios is 0.955 but single cells lose up to 42% (bunny and
//! fandisk at 0.5 b/v); with it 0.951 and at most 15%.
//!
//! Invariants: the offset only changes where the encoder aims the angle;
//! V itself (the on-surface sample that anchors the paths) is untouched,
//! and the decoder is unchanged. The offset is bounded by
//! [`MAX_OFFSET`]·L, so no tip is thrown far off. The flood visits at most
//! [`MAX_FACES`] faces and charges them to the run's work budget. Faces
//! of hole patches (the encoder's own filling, masked away in the file)
//! are neither sampled nor crossed, and a tip on one is not offset.

use super::marks::Marks;
use super::surface::{face, Surface, NONE};
use glam::DVec3;

/// Radius of the sampled disk, in L: the tip's future neighbours lie
/// within about L of it.
pub(super) const REACH: f64 = 1.0;
/// Largest offset, in L (a sphere of radius L would ask for L/8).
pub(super) const MAX_OFFSET: f64 = 0.15;
/// Faces sampled at most per tip (the disk is cut short, still about
/// isotropic, when L is many input edges long).
pub(super) const MAX_FACES: usize = 1024;
/// Normal coherence (|Σw·n| / Σw over the disk) at and below which no
/// offset is applied, and at and above which all of it is.
pub(super) const COHERENT_LOW: f64 = 0.75;
pub(super) const COHERENT_HIGH: f64 = 0.9;

/// Reusable buffers for the flood.
#[derive(Default)]
pub(super) struct Scratch {
    queue: Vec<u32>,
    /// Faces queued.
    queued: Marks,
    /// (weight, sample − V) of the samples within reach.
    samples: Vec<(f64, DVec3)>,
    /// (section curvature 2h/ρ², weight w·ρ²) per sample.
    sections: Vec<(f64, f64)>,
}

/// The displacement to add to V (on face `f` of M) before its angle is
/// quantized, for edge length `l`.
pub(super) fn offset(s: &Surface, f: u32, v: DVec3, l: f64, sc: &mut Scratch) -> DVec3 {
    // A hole patch is the encoder's own filling, masked away in the file:
    // its shape says nothing about the input's curvature, and a tip on it
    // is not worth the bits of an offset.
    if s.patch(f) != NONE {
        return DVec3::ZERO;
    }
    let Some((n, coherence)) = sample_disk(s, f, v, l, sc) else {
        return DVec3::ZERO;
    };
    // Coherence of the normals: |Σw·n| / Σw is about 1 − (L/R)²/8 on a
    // smooth patch, far less where the disk wraps a thin part or spans a
    // crease; the quadratic model fails there, so the offset fades out.
    let trust = ((coherence - COHERENT_LOW) / (COHERENT_HIGH - COHERENT_LOW)).clamp(0.0, 1.0);
    if trust == 0.0 {
        return DVec3::ZERO;
    }
    // Per sample, k = 2h/ρ² is the curvature of the normal section
    // through it; weighted by w·ρ², their mean is the least-squares fit
    // of h = κ·ρ²/2 and estimates −H. Their weighted median does too on a
    // smooth patch (the sections' curvatures are symmetric about H) and
    // ignores a minority of samples across a crease, which would make
    // the mean large and push a tip beside a sharp edge off its plane.
    let Some(total) = sections(sc, n) else {
        return DVec3::ZERO;
    };
    sc.sections.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let mut acc = 0.0;
    let kappa = sc
        .sections
        .iter()
        .find(|&&(_, w)| {
            acc += w;
            acc >= 0.5 * total
        })
        .map_or(0.0, |&(k, _)| k);
    // The mesh lies κ·L²/8 along n from M on average (κ < 0 on a convex
    // part, whose heights are negative under the outward normal), so the
    // tip moves the other way.
    let delta = (-kappa * l * l / 8.0).clamp(-MAX_OFFSET * l, MAX_OFFSET * l);
    n * (trust * delta)
}

impl Scratch {
    /// (weight, sample − V) of the last [`sample_disk`].
    pub(super) fn samples(&self) -> &[(f64, DVec3)] {
        &self.samples
    }
}

/// Fills `sc.sections` with (section curvature 2h/ρ², weight w·ρ²) of
/// the samples of the last [`sample_disk`], heights along `n`; returns
/// Σ w·ρ², or `None` when it is not positive.
fn sections(sc: &mut Scratch, n: DVec3) -> Option<f64> {
    sc.sections.clear();
    let mut total = 0.0;
    for &(w, d) in &sc.samples {
        let h = d.dot(n);
        let r2 = d.length_squared() - h * h;
        if r2 > 0.0 {
            sc.sections.push((2.0 * h / r2, w * r2));
            total += w * r2;
        }
    }
    (total > 0.0).then_some(total)
}

/// Samples the faces of M within [`REACH`]·`l` of point `v` of face `f`
/// (hole patches left out) into `sc.samples`; returns their mean normal
/// and its coherence |Σw·n| / Σw, or `None` without a sample.
pub(super) fn sample_disk(
    s: &Surface,
    f: u32,
    v: DVec3,
    l: f64,
    sc: &mut Scratch,
) -> Option<(DVec3, f64)> {
    let reach2 = (REACH * l) * (REACH * l);
    sc.queued.clear(s.face_count());
    sc.queued.insert(f);
    sc.queue.clear();
    sc.queue.push(f);
    sc.samples.clear();
    // Σw·n and Σw over the samples.
    let (mut normal, mut weight) = (DVec3::ZERO, 0.0);
    let mut head = 0;
    while head < sc.queue.len() && head < MAX_FACES {
        let g = sc.queue[head];
        head += 1;
        s.tick(1);
        if s.patch(g) != NONE {
            continue;
        }
        let [a, b, c] = Surface::corners(g).map(|k| s.p(k));
        let cross = (b - a).cross(c - a);
        let w = cross.length() / 6.0;
        let mut near = false;
        for m in [(a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5] {
            let d = m - v;
            if d.length_squared() <= reach2 {
                sc.samples.push((w, d));
                normal += w * s.normal(g);
                weight += w;
                near = true;
            }
        }
        near |= [a, b, c].iter().any(|p| p.distance_squared(v) <= reach2);
        if !near && g != f {
            continue;
        }
        for k in Surface::corners(g) {
            let h = face(s.opp[k as usize]);
            if sc.queued.insert(h) {
                sc.queue.push(h);
            }
        }
    }
    let n = normal.normalize_or_zero();
    (n != DVec3::ZERO).then(|| (n, normal.length() / weight))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::swing::retile::tests::{sphere, surface_of};

    /// The unit sphere as a dynamic surface, with its faces reversed when
    /// `inside_out`.
    fn surface(levels: u32, inside_out: bool) -> Surface {
        let mut m = sphere(levels);
        if inside_out {
            for t in &mut m.triangles {
                t.swap(1, 2);
            }
        }
        surface_of(&m)
    }

    fn centroid(s: &Surface, f: u32) -> DVec3 {
        Surface::corners(f).map(|k| s.p(k)).iter().sum::<DVec3>() / 3.0
    }

    #[test]
    fn a_sphere_asks_for_l_squared_over_8r_outwards_either_way_round() {
        for inside_out in [false, true] {
            let s = surface(4, inside_out);
            let mut sc = Scratch::default();
            for (f, l) in [(0u32, 0.2), (777, 0.3), (3000, 0.4)] {
                let v = centroid(&s, f);
                let d = offset(&s, f, v, l, &mut sc);
                let radial = d.dot(v.normalize());
                let expected = l * l / 8.0;
                assert!(
                    (radial / expected - 1.0).abs() < 0.15,
                    "face {f}, L {l}: {radial} outwards, expected about {expected}"
                );
                // Along the normal: no tangential drift.
                assert!((d - radial * v.normalize()).length() < 0.05 * expected);
            }
        }
    }

    #[test]
    fn offsets_are_bounded_fade_where_normals_disagree_and_skip_hole_patches() {
        let mut s = surface(3, false);
        let mut sc = Scratch::default();
        let v = centroid(&s, 5);
        // L far beyond the sphere's radius: the quadratic model fails, the
        // bound holds.
        for l in [0.9, 1.5] {
            assert!(offset(&s, 5, v, l, &mut sc).length() <= MAX_OFFSET * l + 1e-12);
        }
        // A disk that wraps most of the sphere: incoherent normals, no
        // offset at all.
        assert_eq!(offset(&s, 5, v, 1.5, &mut sc), DVec3::ZERO);
        let mut patches = vec![NONE; s.face_count()];
        patches[5] = 0;
        s.set_patches(&patches);
        assert_eq!(offset(&s, 5, v, 0.3, &mut sc), DVec3::ZERO);
    }
}
