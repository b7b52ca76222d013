//! The seam, shown with a method that exists only here: adding it is
//! this one module (a [`CodingMethod`] impl) and one line in the
//! chooser's list, and the chooser weighs it like the others.

use super::choose::choose;
use super::effort::Entry;
use super::method::{Ask, CodingMethod, Job, Made, Services};
use super::simplified::Simplified;
use super::stats::{CandidateFailure, Method, MethodStats};
use crate::options::{EncodeOptions, SwingTarget};
use crate::{Error, SizeError};

/// Test-only: the whole cleaned mesh in the lossless mode, at the finest
/// quantization whose file fits (no simplification at all).
struct Quantized;

impl CodingMethod for Quantized {
    fn method(&self) -> Method {
        Method::Lossless
    }

    fn runs_when_whole_fits(&self) -> bool {
        true
    }

    fn encode(&self, job: &Job<'_, '_>, ask: Ask) -> Result<Option<Made>, Error> {
        let budget =
            super::request::budget(ask.target, job.input_vertices, ask.max_bytes, "quantized")?;
        let c = job.cleaned;
        let mut smallest = u64::MAX;
        for qp in (crate::geometry::MIN_BITS..=16).rev() {
            let (bytes, stats, _) =
                crate::lossless::encode(&c.table, &c.mesh, qp, job.options.framing)?;
            smallest = smallest.min(bytes.len() as u64);
            if bytes.len() as u64 <= budget {
                return Ok(Some(Made {
                    bytes,
                    stats: MethodStats::Lossless(stats),
                    l2_relative: None,
                    whole: true,
                    seeds: None,
                }));
            }
        }
        Err(SizeError {
            requested: budget,
            smallest,
        }
        .into())
    }
}

/// The chooser's file for `bytes` over `list`, on a sphere of 1,152
/// triangles.
fn chosen_at(bytes: u64, list: &[Entry]) -> super::choose::Chosen {
    let mesh = crate::mesh::test_shapes::uv_sphere(24, 24);
    let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
    let options = EncodeOptions::default();
    let services = Services::new(&mesh, &cleaned, options.framing, false);
    let job = Job {
        cleaned: &cleaned,
        input_vertices: mesh.vertex_count(),
        options: &options,
        services: &services,
    };
    let ask = Ask {
        target: SwingTarget::Bytes(bytes),
        max_bytes: None,
    };
    choose(&job, ask, list).unwrap()
}

#[test]
fn a_method_is_one_module_and_one_line_in_the_list() {
    let list = [
        // The one line.
        Entry {
            method: &Quantized,
            work: None,
        },
        Entry {
            method: &Simplified::FULL,
            work: None,
        },
    ];
    // Room for the whole sphere at a fair quantization: both are made
    // and measured, and the file written is the one the rule prefers.
    let roomy = chosen_at(4000, &list);
    assert_eq!(roomy.candidates.len(), 2);
    let figures: Vec<_> = roomy
        .candidates
        .iter()
        .map(|c| *c.outcome.as_ref().expect("both made a file"))
        .collect();
    assert!(figures.iter().all(|m| m.l2_relative.is_some()));
    let written = roomy.stats.method();
    let mine = figures[0];
    match written {
        Method::Lossless => assert_eq!(mine.bytes, roomy.bytes.len() as u64),
        _ => assert!(figures[1].l2_relative <= mine.l2_relative),
    }
    // Too small for the whole mesh at any quantization: the new method
    // drops out with its reason and the simplified file is written.
    let tight = chosen_at(300, &list);
    assert!(matches!(
        tight.candidates[0].outcome,
        Err(CandidateFailure::TooSmall(_))
    ));
    assert_eq!(tight.stats.method(), Method::Simplified);
    // Without the line, the method is not weighed.
    let without = chosen_at(4000, &list[1..]);
    assert_eq!(without.candidates.len(), 1);
    assert_eq!(without.candidates[0].method, Method::Simplified);
}

#[test]
fn or_smallest_writes_the_file_of_the_smallest_size_in_the_same_encode() {
    let mesh = crate::mesh::test_shapes::uv_sphere(12, 12);
    for mode in [
        crate::EncodeMode::Auto {
            target: SwingTarget::Bytes(10),
            max_bytes: None,
        },
        crate::EncodeMode::Simplified {
            target: SwingTarget::Bytes(10),
            max_bytes: None,
        },
    ] {
        let strict = EncodeOptions {
            mode,
            effort: crate::Effort::Fast,
            ..Default::default()
        };
        let Err(Error::Size(e)) = crate::encode(&mesh, &strict) else {
            panic!("10 bytes cannot hold a sphere");
        };
        let or_smallest = EncodeOptions {
            or_smallest: true,
            ..strict.clone()
        };
        let written = crate::encode(&mesh, &or_smallest).unwrap();
        assert_eq!(written.stats.smallest_instead, Some(e));
        // The same file as asking for that size outright.
        let at = EncodeOptions {
            mode: super::at_size(mode, e.smallest).unwrap(),
            ..strict.clone()
        };
        assert_eq!(written.bytes, crate::encode(&mesh, &at).unwrap().bytes);
        // A request that fits is untouched, and a cap below still fails.
        let fits = EncodeOptions {
            mode: super::at_size(mode, 4 * e.smallest).unwrap(),
            ..or_smallest.clone()
        };
        assert_eq!(
            crate::encode(&mesh, &fits).unwrap().stats.smallest_instead,
            None
        );
        let capped = EncodeOptions {
            mode: match mode {
                crate::EncodeMode::Auto { target, .. } => crate::EncodeMode::Auto {
                    target,
                    max_bytes: Some(10),
                },
                crate::EncodeMode::Simplified { target, .. } => crate::EncodeMode::Simplified {
                    target,
                    max_bytes: Some(10),
                },
                other => other,
            },
            ..or_smallest.clone()
        };
        assert!(matches!(crate::encode(&mesh, &capped), Err(Error::Size(_))));
    }
}
