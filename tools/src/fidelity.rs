//! What `encode` checks of its own file before writing it (issue 23,
//! item 6, "honest summaries"): it decodes the bytes it made and measures
//! the decoded mesh against the input as read, so that a file that lost
//! most of the mesh (ten triangles for a beetle, a part cut away, three
//! triangles for a torus) does not pass as a success in silence.
//!
//! The measure is the codec's own (`swm::Check`, `EncodeStats::check`):
//! the encoder decodes its file and measures it against the reference
//! surface its chooser built anyway, with Metro's samples thinned to
//! `swm::CHECK_SAMPLES` a side. Before, this module built a second tree
//! over the input for the same answer (on a million-triangle scan about
//! a second of `fast`'s time).
//!
//! Two signs, each with its threshold:
//! * area: the decoded surface's area under [`MIN_AREA_RATIO`] of the
//!   input's (most of the surface gone);
//! * distance: the largest distance found between the two surfaces
//!   (a sampled Hausdorff distance) above [`MAX_HAUSDORFF`] of the
//!   input's bounding-box diagonal (a part missing, or a shape too
//!   coarse to resemble the input).
//!
//! By the Hausdorff column of the committed rd tables (corpus/rd/,
//! 300,000 samples per surface), the distance threshold flags 12 of the
//! 272 files of their auto, swing, baseline and lossless rows, all at
//! 0.5-2 b/v: woody's retiled file of 37 triangles at 2 b/v (20% of the
//! diagonal), alligator's of 39, cow's at 0.5 and 1 b/v (15%), suzanne
//! simplified to 25 triangles, the generated torus to 3 and cube to 10;
//! the next worst, beetle simplified to 137 triangles, is at 9%.

/// The decoded surface's area below this share of the input's is a
/// warning.
pub const MIN_AREA_RATIO: f64 = 0.10;

/// The Hausdorff distance above this share of the input's bounding-box
/// diagonal is a warning.
pub const MAX_HAUSDORFF: f64 = 0.10;

/// The decoded mesh as measured against the input.
pub struct Fidelity {
    pub vertices: usize,
    pub triangles: usize,
    /// Decoded area over the input's.
    pub area_ratio: f64,
    /// L2 distance (Metro's, estimated) over the input's bounding-box
    /// diagonal; `None` when the decoded mesh has no triangle.
    pub l2_relative: Option<f64>,
    /// Hausdorff distance over the input's bounding-box diagonal; `None`
    /// when the decoded mesh has no triangle to measure.
    pub hausdorff_relative: Option<f64>,
    /// Points measured on each surface.
    pub samples: u64,
}

impl Fidelity {
    /// The encoder's measure of its file.
    pub fn of(check: &swm::Check) -> Fidelity {
        Fidelity {
            vertices: check.decoded_vertices,
            triangles: check.decoded_triangles,
            area_ratio: check.area_ratio,
            l2_relative: check.l2_relative,
            hausdorff_relative: check.hausdorff_relative,
            samples: check.samples,
        }
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
    /// `area_ratio`, `l2_relative` and `hausdorff_relative` (`null`
    /// without triangles), `samples` (points measured a side) and
    /// `problems` (what the warning says, one sentence each).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "decoded_vertices": self.vertices,
            "decoded_triangles": self.triangles,
            "area_ratio": self.area_ratio,
            "l2_relative": self.l2_relative,
            "hausdorff_relative": self.hausdorff_relative,
            "samples": self.samples,
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
            l2_relative: hausdorff.map(|h| h / 4.0),
            hausdorff_relative: hausdorff,
            samples: 1000,
        }
    }

    /// The encoder's check of a sphere's file: the decoded counts are
    /// what `swm::decode` gives, the area and distance pass; the lossless
    /// mode at a fixed qp has none.
    #[test]
    fn the_encoders_check_is_the_decoded_file() {
        let sphere = swm_corpus::icosphere(1.0, 3);
        let options = swm::EncodeOptions {
            mode: swm::EncodeMode::Auto {
                target: swm::SwingTarget::BitsPerVertex(8.0),
                max_bytes: None,
            },
            ..Default::default()
        };
        let encoded = swm::encode(&sphere, &options).unwrap();
        let f = Fidelity::of(encoded.stats.check.as_ref().unwrap());
        let decoded = swm::decode(&encoded.bytes, &Default::default()).unwrap();
        assert_eq!(
            (f.vertices, f.triangles),
            (decoded.vertex_count(), decoded.face_count())
        );
        assert!((f.area_ratio - 1.0).abs() < 0.05, "{}", f.area_ratio);
        assert!(f.l2_relative.unwrap() < 0.01);
        assert!(f.hausdorff_relative.unwrap() >= f.l2_relative.unwrap());
        assert!(f.problems().is_empty());
        assert!(f.samples > 1000);
        let lossless = swm::encode(&sphere, &Default::default()).unwrap();
        assert!(lossless.stats.check.is_none());
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
