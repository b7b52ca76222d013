//! What `encode` checks of its own file before writing it (issue 23,
//! item 6, "honest summaries"): it decodes the bytes it made and measures
//! the decoded mesh against the input as read, so that a file that lost
//! most of the mesh (ten triangles for a beetle, a part cut away, three
//! triangles for a torus) does not pass as a success in silence.
//!
//! Two signs, each with its threshold:
//! * area: the decoded surface's area under [`MIN_AREA_RATIO`] of the
//!   input's (most of the surface gone);
//! * distance: the Hausdorff distance between the two, from
//!   [`SAMPLES`] area-uniform samples on each surface (the count the
//!   auto mode measures its candidates with; see `swm::metrics`), above
//!   [`MAX_HAUSDORFF`] of the input's bounding-box diagonal (a part
//!   missing, or a shape too coarse to resemble the input).
//!
//! By the Hausdorff column of the committed rd tables (corpus/rd/,
//! 300,000 samples per surface), the distance threshold flags 12 of the
//! 272 files of their auto, swing, baseline and lossless rows, all at
//! 0.5-2 b/v: woody's retiled file of 37 triangles at 2 b/v (20% of the
//! diagonal), alligator's of 39, cow's at 0.5 and 1 b/v (15%), suzanne
//! simplified to 25 triangles, the generated torus to 3 and cube to 10;
//! the next worst, beetle simplified to 137 triangles, is at 9%.

use swm::metrics::{DistanceOptions, Surface};
use swm::TriMesh;

/// Triangles around one vertex above which the input is measured with
/// its fans rebuilt (a polygon face of thousands of sides, fanned by the
/// reader, is thousands of overlapping slivers from one vertex: each
/// nearest-point query would visit them all, 5 s for a 10,000-gon).
const FAN: usize = 64;

/// What the decoded mesh is measured against: the input as read, or,
/// when it has a fan wider than [`FAN`], the same surface cleaned and
/// with its fans rebuilt as the encoder measures it
/// (`swm::simplify::Simplifier::reference`; within about 1e-4 of a spoke,
/// far below the thresholds here).
fn reference(input: &TriMesh) -> Result<Surface, swm::Error> {
    let mut around = vec![0usize; input.vertex_count()];
    for t in &input.triangles {
        for &v in t {
            if let Some(n) = around.get_mut(v as usize) {
                *n += 1;
            }
        }
    }
    if around.iter().all(|&n| n <= FAN) {
        return Surface::new(input);
    }
    let cleaned = swm::clean(input, &Default::default())?;
    let s = swm::simplify::Simplifier::new(&cleaned.mesh, swm::Framing::Compact);
    Surface::new(s.reference())
}

/// The decoded surface's area below this share of the input's is a
/// warning.
pub const MIN_AREA_RATIO: f64 = 0.10;

/// The Hausdorff distance above this share of the input's bounding-box
/// diagonal is a warning.
pub const MAX_HAUSDORFF: f64 = 0.10;

/// Area-uniform face samples on each surface.
pub const SAMPLES: u64 = 30_000;

/// The decoded mesh as measured against the input.
pub struct Fidelity {
    pub vertices: usize,
    pub triangles: usize,
    /// Decoded area over the input's.
    pub area_ratio: f64,
    /// Hausdorff distance over the input's bounding-box diagonal; `None`
    /// when the decoded mesh has no triangle to measure.
    pub hausdorff_relative: Option<f64>,
}

impl Fidelity {
    /// Decodes `bytes` and measures the result against `input`.
    pub fn measure(input: &TriMesh, bytes: &[u8]) -> Result<Fidelity, swm::Error> {
        let decoded = swm::decode(bytes, &swm::DecodeOptions::default())?;
        let reference = reference(input)?;
        let (vertices, triangles) = (decoded.vertex_count(), decoded.face_count());
        if triangles == 0 {
            return Ok(Fidelity {
                vertices,
                triangles,
                area_ratio: 0.0,
                hausdorff_relative: None,
            });
        }
        let other = Surface::new(&decoded)?;
        let d = swm::metrics::distance_between(
            &reference,
            &other,
            &DistanceOptions::area_uniform(SAMPLES),
        )?;
        Ok(Fidelity {
            vertices,
            triangles,
            area_ratio: other.area() / reference.area().max(f64::MIN_POSITIVE),
            hausdorff_relative: Some(d.hausdorff_relative()),
        })
    }

    /// What is wrong, in words; empty when the file passes.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        let Some(hausdorff) = self.hausdorff_relative else {
            problems.push("the file decodes to no triangles".to_string());
            return problems;
        };
        if self.area_ratio < MIN_AREA_RATIO {
            problems.push(format!(
                "the decoded mesh keeps {} of the input's surface area (under {:.0}%)",
                percent(self.area_ratio),
                100.0 * MIN_AREA_RATIO
            ));
        }
        // A NaN distance is no pass.
        if hausdorff.is_nan() || hausdorff > MAX_HAUSDORFF {
            problems.push(format!(
                "the decoded mesh lies up to {} of the bounding-box diagonal from the input (Hausdorff distance, over {:.0}%)",
                percent(hausdorff),
                100.0 * MAX_HAUSDORFF
            ));
        }
        problems
    }

    /// The figures for `--json`: `decoded_vertices`, `decoded_triangles`,
    /// `area_ratio`, `hausdorff_relative` (`null` without triangles),
    /// `samples` and `problems` (what the warning says, one sentence each).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "decoded_vertices": self.vertices,
            "decoded_triangles": self.triangles,
            "area_ratio": self.area_ratio,
            "hausdorff_relative": self.hausdorff_relative,
            "samples": SAMPLES,
            "problems": self.problems(),
        })
    }
}

/// A share as a percentage with enough digits to tell it from zero.
fn percent(share: f64) -> String {
    if share < 0.001 {
        format!("{:.2e}%", 100.0 * share)
    } else {
        format!("{:.1}%", 100.0 * share)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fidelity(area_ratio: f64, hausdorff: Option<f64>) -> Fidelity {
        Fidelity {
            vertices: 3,
            triangles: 1,
            area_ratio,
            hausdorff_relative: hausdorff,
        }
    }

    /// A file of a small sphere measured against itself passes; against
    /// a sphere ten times as large around it, it keeps 1% of the area and
    /// lies 0.9 radii (26% of the diagonal) from it: both problems.
    #[test]
    fn measure_decodes_and_compares_with_the_input() {
        let small = swm_corpus::icosphere(0.1, 3);
        let large = swm_corpus::icosphere(1.0, 3);
        let bytes = swm::encode(&small, &swm::EncodeOptions::default())
            .unwrap()
            .bytes;
        let same = Fidelity::measure(&small, &bytes).unwrap();
        assert_eq!(
            (same.vertices, same.triangles),
            (small.vertex_count(), small.face_count())
        );
        assert!((same.area_ratio - 1.0).abs() < 1e-3, "{}", same.area_ratio);
        assert!(same.hausdorff_relative.unwrap() < 1e-3);
        assert!(same.problems().is_empty());
        let lost = Fidelity::measure(&large, &bytes).unwrap();
        assert!((lost.area_ratio - 0.01).abs() < 1e-3, "{}", lost.area_ratio);
        let h = lost.hausdorff_relative.unwrap();
        assert!((h - 0.9 / 12f64.sqrt()).abs() < 0.01, "{h}");
        let p = lost.problems();
        assert_eq!(p.len(), 2, "{p:?}");
        assert!(p[0].contains("1.0% of the input's surface area"), "{p:?}");
        // A file that is no .swm file is an error, not a pass.
        assert!(Fidelity::measure(&small, &bytes[..bytes.len() / 2]).is_err());
    }

    #[test]
    fn thresholds() {
        assert!(fidelity(1.0, Some(0.01)).problems().is_empty());
        assert!(fidelity(0.1, Some(0.1)).problems().is_empty());
        let p = fidelity(0.05, Some(0.01)).problems();
        assert_eq!(p.len(), 1);
        assert!(p[0].contains("5.0% of the input's surface area"), "{p:?}");
        let p = fidelity(0.9, Some(0.15)).problems();
        assert_eq!(p.len(), 1);
        assert!(p[0].contains("15.0% of the bounding-box diagonal"), "{p:?}");
        assert_eq!(fidelity(0.01, Some(0.5)).problems().len(), 2);
        assert_eq!(fidelity(1.0, Some(f64::NAN)).problems().len(), 1);
        let p = fidelity(0.0, None).problems();
        assert_eq!(p, ["the file decodes to no triangles"]);
    }
}
