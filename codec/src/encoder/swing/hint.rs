//! The encoder's measure of the post-processing hint (issue 21): the
//! file decoded plain, sharpened, and sharpened and bent once, each
//! measured against the input, and the simplest choice that no other
//! beats by more than [`HINT_GAIN`] written into the file's `post`
//! section. The hint's format (what a decoder reads and follows) is
//! `post::hint`; this is the encoder's half, beside the SwingWrapper
//! encoder that uses it.
use crate::container::Tag;
use crate::metrics::{DistanceOptions, Surface};
use crate::post::hint::{payload, PostProcessing};
use crate::prelude::*;
use crate::{DecodeOptions, Error};

/// Least relative drop of L2 a step must bring to be recommended
/// over the simpler choice (plain, or sharpening without Bender):
/// below it the difference is within the sampling's noise at
/// [`AUTO_SAMPLES`](crate::AUTO_SAMPLES), and a step that does not
/// measurably help is not worth its time and triangles in a viewer.
pub const HINT_GAIN: f64 = 0.02;

/// What the encoder measured for the hint: the relative L2 (to the
/// input's bounding-box diagonal) of each choice it tried.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct HintReport {
    /// The choice written (plain: no `post` section).
    pub chosen: PostProcessing,
    /// L2 of the plain decode.
    pub plain_l2: f64,
    /// L2 after EdgeSharpener (infinite when it failed on the mesh).
    pub sharpen_l2: f64,
    /// L2 after EdgeSharpener and one Bender step (likewise).
    pub bend_l2: f64,
    /// The file's tips were aimed on the surface, not by the options'
    /// offset and fit: EdgeSharpener restored more from them
    /// (`encoder::swing::hinted`).
    pub tips_on_surface: bool,
    /// The file's tips sit on the input's creases where a gate's
    /// plane crosses one (`retile::crease`): that file decoded closer
    /// after its hint (`encoder::swing::hinted`).
    pub crease_tips: bool,
}

impl HintReport {
    /// The L2 a default decode gives: after the chosen steps.
    pub fn l2_after(&self) -> f64 {
        match (self.chosen.sharpen, self.chosen.bend_steps) {
            (false, _) => self.plain_l2,
            (true, 0) => self.sharpen_l2,
            _ => self.bend_l2,
        }
    }
}

/// Decodes `bytes` plain, sharpened, and sharpened and bent once;
/// measures each against `reference` with `samples` area-uniform
/// samples each way (deterministic); recommends the simplest choice
/// that no other beats by more than [`HINT_GAIN`].
pub fn recommend(bytes: &[u8], reference: &Surface, samples: u64) -> Result<HintReport, Error> {
    let l2 = |sharpen: bool, bend_steps: u32| -> Result<f64, Error> {
        let options = DecodeOptions {
            sharpen: Some(sharpen),
            bend_steps: Some(bend_steps),
            ..Default::default()
        };
        let mesh = crate::decoder::decode(bytes, &options)?;
        let d = crate::metrics::distance_between(
            reference,
            &Surface::new(&mesh)?,
            &DistanceOptions::area_uniform(samples),
        )?;
        Ok(d.l2_relative())
    };
    let plain_l2 = l2(false, 0)?;
    // A step that fails on this mesh (EdgeSharpener can collapse
    // tiny flat components away, leaving nothing to measure; Bender
    // can exceed the limits) is simply not recommended.
    let sharpen_l2 = l2(true, 0).unwrap_or(f64::INFINITY);
    let bend_l2 = l2(true, 1).unwrap_or(f64::INFINITY);
    let beats = |a: f64, b: f64| a < (1.0 - HINT_GAIN) * b;
    let chosen = if beats(bend_l2, sharpen_l2.min(plain_l2)) {
        PostProcessing {
            sharpen: true,
            bend_steps: 1,
        }
    } else if beats(sharpen_l2, plain_l2) {
        PostProcessing {
            sharpen: true,
            bend_steps: 0,
        }
    } else {
        PostProcessing::PLAIN
    };
    Ok(HintReport {
        chosen,
        plain_l2,
        sharpen_l2,
        bend_l2,
        tips_on_surface: false,
        crease_tips: false,
    })
}

/// `bytes` with the hint's `post` section appended (none for a plain
/// hint: a file without one decodes plain). The header and every
/// other section are kept as they are.
pub fn with_hint(bytes: &[u8], hint: PostProcessing) -> Result<Vec<u8>, Error> {
    if hint.is_plain() {
        return Ok(bytes.to_vec());
    }
    with_post(bytes, &payload(hint))
}

/// `bytes` with `payload` as its last section, `post`, in place of
/// any `post` it had (the tests give it payloads no writer makes).
pub(crate) fn with_post(bytes: &[u8], payload: &[u8]) -> Result<Vec<u8>, Error> {
    let file = crate::container::parse_container(bytes, &crate::Limits::default())?;
    let mut sections: Vec<(Tag, &[u8])> = file
        .sections()
        .filter(|s| s.tag != Tag::POST)
        .map(|s| (s.tag, s.bytes))
        .collect();
    sections.push((Tag::POST, payload));
    crate::container::write_container(&file.header, &sections)
}

// The format's reading (`post::hint`) tested on files this half writes:
// the tests sit with the upper of the two halves.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::container::parse_container;
    use crate::post::hint::{read, resolve, MAX_HINT_BEND};

    fn file_with(payload: Option<&[u8]>) -> Vec<u8> {
        let mesh = crate::mesh::test_shapes::unit_cube();
        let options = crate::EncodeOptions {
            mode: crate::EncodeMode::Lossless { qp: 10 },
            ..Default::default()
        };
        let bytes = crate::encode(&mesh, &options).unwrap().bytes;
        match payload {
            None => bytes,
            Some(p) => with_post(&bytes, p).unwrap(),
        }
    }

    fn hint_of(bytes: &[u8]) -> Option<PostProcessing> {
        read(&parse_container(bytes, &Default::default()).unwrap())
    }

    #[test]
    fn payload_round_trips_and_odd_values_are_ignored() {
        for sharpen in [false, true] {
            for bend_steps in 0..=MAX_HINT_BEND {
                let h = PostProcessing {
                    sharpen,
                    bend_steps,
                };
                assert_eq!(hint_of(&file_with(Some(&payload(h)))), Some(h));
            }
        }
        assert_eq!(hint_of(&file_with(None)), None);
        // Longer payloads: later versions' bytes, ignored.
        assert_eq!(
            hint_of(&file_with(Some(&[1, 1, 7, 7]))),
            Some(PostProcessing {
                sharpen: true,
                bend_steps: 1
            })
        );
        for odd in [&[][..], &[1], &[2, 0], &[1, 3], &[255, 255]] {
            assert_eq!(hint_of(&file_with(Some(odd))), None, "{odd:?}");
        }
    }

    #[test]
    fn callers_choices_override_the_hint_field_by_field() {
        let bytes = file_with(Some(&[1, 2]));
        let file = parse_container(&bytes, &Default::default()).unwrap();
        let r = |s, b| resolve(&file, s, b);
        assert_eq!(
            r(None, None),
            PostProcessing {
                sharpen: true,
                bend_steps: 2
            }
        );
        assert_eq!(
            r(Some(false), None),
            PostProcessing {
                sharpen: false,
                bend_steps: 2
            }
        );
        assert_eq!(
            r(None, Some(0)),
            PostProcessing {
                sharpen: true,
                bend_steps: 0
            }
        );
        assert_eq!(r(Some(false), Some(0)), PostProcessing::PLAIN);
        let plain = file_with(None);
        let file = parse_container(&plain, &Default::default()).unwrap();
        assert_eq!(resolve(&file, None, None), PostProcessing::PLAIN);
        assert_eq!(
            resolve(&file, None, Some(1)),
            PostProcessing {
                sharpen: false,
                bend_steps: 1
            }
        );
    }

    #[test]
    fn with_hint_keeps_every_section_and_decodes_as_told() {
        let plain = file_with(None);
        assert_eq!(with_hint(&plain, PostProcessing::PLAIN).unwrap(), plain);
        let h = PostProcessing {
            sharpen: true,
            bend_steps: 1,
        };
        let hinted = with_hint(&plain, h).unwrap();
        assert_eq!(hint_of(&hinted), Some(h));
        // Re-hinting replaces, never duplicates.
        let again = with_hint(&hinted, h).unwrap();
        assert_eq!(again, hinted);
        // The default decode follows the hint; explicit options win.
        let default = crate::decode(&hinted, &Default::default()).unwrap();
        let told = crate::decode(
            &plain,
            &crate::DecodeOptions {
                sharpen: Some(true),
                bend_steps: Some(1),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(default, told);
        let off = crate::decode(&hinted, &crate::DecodeOptions::plain()).unwrap();
        assert_eq!(off, crate::decode(&plain, &Default::default()).unwrap());
    }
}
