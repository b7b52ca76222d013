//! Issue 45: effort levels and the error target. Every level answers the
//! request (on size, deterministic at any thread count) and reports what
//! it weighed; `--max-error E` writes a file whose L2 to the input, as
//! `swm distance` measures it, is at most E, and no file 5% smaller
//! from the same chooser meets E.

mod common;
use common::*;
use swm::{Effort, EncodeMode, EncodeOptions, ErrorBound, Method, SwingTarget};

fn encode(mesh: &swm::TriMesh, target: SwingTarget, effort: Effort) -> swm::Encoded {
    let options = EncodeOptions {
        mode: EncodeMode::Auto {
            target,
            max_bytes: None,
        },
        effort,
        ..Default::default()
    };
    swm::encode(mesh, &options).unwrap()
}

/// L2 between `mesh` and the file, relative to the mesh's diagonal, with
/// `swm distance`'s default (Metro) samples.
fn metro_l2(mesh: &swm::TriMesh, bytes: &[u8]) -> f64 {
    let decoded = swm::decode(bytes, &Default::default()).unwrap();
    swm::metrics::distance(mesh, &decoded, &Default::default())
        .unwrap()
        .l2_relative()
}

#[test]
fn every_level_answers_the_request_and_says_what_it_weighed() {
    let mesh = swm_corpus::fandisk_like(16);
    let bpv = 2.0;
    let budget = (bpv * mesh.vertex_count() as f64 / 8.0).round();
    for (effort, methods) in [
        (Effort::Fast, &[Method::Simplified][..]),
        (
            Effort::Default,
            &[Method::Swing, Method::Simplified, Method::Displaced][..],
        ),
        (
            Effort::Max,
            &[
                Method::Mixed,
                Method::Swing,
                Method::Simplified,
                Method::Displaced,
            ][..],
        ),
    ] {
        let e = encode(&mesh, SwingTarget::BitsPerVertex(bpv), effort);
        let n = e.bytes.len() as f64;
        assert!(
            n <= budget * 1.03 && n >= budget * 0.97,
            "{effort:?}: {n} for {budget}"
        );
        let weighed: Vec<Method> = e.stats.candidates.iter().map(|c| c.method).collect();
        assert_eq!(weighed, methods, "{effort:?}");
        let chosen = e.stats.candidate(e.stats.chosen()).expect("the chosen one");
        assert_eq!(chosen.outcome.as_ref().unwrap().bytes, e.bytes.len() as u64);
        swm::decode(&e.bytes, &Default::default()).unwrap();
        // The reported error is `swm distance`'s within 2%, from fewer
        // of Metro's samples at `fast`.
        let check = e.stats.check.expect("a lossy file is checked");
        let (reported, measured) = (check.l2_relative.unwrap(), metro_l2(&mesh, &e.bytes));
        assert!(
            (reported / measured - 1.0).abs() <= 0.02,
            "{effort:?}: {reported} against {measured}"
        );
        let cap = match effort {
            Effort::Fast => swm::FAST_CHECK_SAMPLES,
            _ => swm::CHECK_SAMPLES,
        };
        let n = check.samples as f64;
        assert!(n <= 1.1 * cap as f64, "{effort:?}: {n} samples");
        // The same bytes on one thread and on three.
        let at = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| encode(&mesh, SwingTarget::BitsPerVertex(bpv), effort).bytes)
        };
        assert_eq!(at(1), e.bytes, "{effort:?}");
        assert_eq!(at(3), e.bytes, "{effort:?}");
    }
}

/// Effort `fast` checks its file with a third of the samples, and its
/// reported error is still `swm distance`'s within 2%.
#[test]
fn fast_checks_with_fewer_samples_within_two_percent() {
    let mesh = swm_corpus::uv_sphere(1.0, 120, 240);
    let e = encode(&mesh, SwingTarget::BitsPerVertex(2.0), Effort::Fast);
    let check = e.stats.check.expect("a lossy file is checked");
    let n = check.samples as f64;
    let cap = swm::FAST_CHECK_SAMPLES as f64;
    assert!((0.9 * cap..=1.1 * cap).contains(&n), "{n} samples");
    let (reported, measured) = (check.l2_relative.unwrap(), metro_l2(&mesh, &e.bytes));
    assert!(
        (reported / measured - 1.0).abs() <= 0.02,
        "{reported} against {measured}"
    );
}

#[test]
fn default_leaves_a_large_retiling_to_max_and_says_so() {
    // A fine sphere at 8 b/v: the retiling it would take is far above the
    // default level's work budget, so the level does not start it.
    let mesh = swm_corpus::icosphere(1.0, 5);
    let e = encode(&mesh, SwingTarget::BitsPerVertex(8.0), Effort::Default);
    let swing = e.stats.candidate(Method::Swing).unwrap();
    assert!(
        matches!(
            swing.outcome,
            Err(swm::CandidateFailure::OverBudget { predicted, budget, .. }) if predicted > budget
        ),
        "{swing:?}"
    );
    assert_eq!(e.stats.chosen(), Method::Simplified);
}

#[test]
fn default_runs_displaced_subdivision_at_low_rates_only_and_says_so() {
    // A smooth sphere of 20,480 faces: its budget for the displaced
    // method is 2,925 bytes (one per seven faces).
    let mesh = swm_corpus::icosphere(1.0, 5);
    let low = encode(&mesh, SwingTarget::BitsPerVertex(1.0), Effort::Default);
    let displaced = low.stats.candidate(Method::Displaced).unwrap();
    assert!(displaced.outcome.is_ok(), "{displaced:?}");
    let high = encode(&mesh, SwingTarget::BitsPerVertex(4.0), Effort::Default);
    let displaced = high.stats.candidate(Method::Displaced).unwrap();
    match &displaced.outcome {
        Err(
            failure @ swm::CandidateFailure::OverBudget {
                predicted, budget, ..
            },
        ) => {
            assert!(predicted > budget);
            let said = failure.to_string();
            assert!(said.contains("bytes of file"), "{said}");
            assert!(said.contains("--mode displaced"), "{said}");
        }
        other => panic!("{other:?}"),
    }
}

/// `max` weighs every method `default` weighs, with at least its search,
/// so it never writes a file `default` measured closer than its own. It
/// once left the displaced method out: homer at 2 b/v got L2 7.95 at
/// `max` (simplified) against 7.65 at `default` (displaced).
#[test]
fn max_is_never_further_than_default() {
    let Some(dir) = shared_corpus() else {
        return;
    };
    let mesh = swm::io::read_mesh(&dir.join("homer.obj")).unwrap();
    let target = SwingTarget::BitsPerVertex(2.0);
    let default = encode(&mesh, target, Effort::Default);
    let max = encode(&mesh, target, Effort::Max);
    let l2 = |e: &swm::Encoded, m: Method| {
        e.stats
            .candidate(m)
            .and_then(|c| c.outcome.as_ref().ok())
            .and_then(|o| o.l2_relative)
    };
    // The displaced method runs the same search at both levels.
    let displaced = l2(&default, Method::Displaced).expect("default runs displaced");
    assert_eq!(l2(&max, Method::Displaced), Some(displaced));
    // The others search further at `max`, which can land a file a hair
    // further (the simplified method's whole search against its lean
    // one: 0.1% on a sphere), hence the tolerance.
    let chosen = |e: &swm::Encoded| l2(e, e.stats.chosen()).unwrap();
    assert!(
        chosen(&max) <= chosen(&default) * 1.01,
        "max {:?} {} against default {:?} {}",
        max.stats.chosen(),
        chosen(&max),
        default.stats.chosen(),
        chosen(&default)
    );
}

#[test]
fn the_cli_takes_effort_levels_and_reports_them() {
    let dir = scratch("effort-cli");
    let input = dir.join("part.obj");
    swm::io::write_mesh(&input, &swm_corpus::fandisk_like(16)).unwrap();
    let output = dir.join("part.swm");
    let (i, o) = (input.to_str().unwrap(), output.to_str().unwrap());
    for effort in ["fast", "default", "max"] {
        let j = json(&swm(&[
            "encode", i, "-o", o, "--bpv", "2", "--effort", effort, "--json",
        ]));
        assert_eq!(j["method"]["effort"], effort, "{j}");
        assert!(j["method"]["candidates"].as_array().is_some(), "{j}");
    }
    let text = ok(&swm(&[
        "encode", i, "-o", o, "--bpv", "2", "--effort", "fast",
    ]));
    assert!(
        text.contains("method: simplified (effort fast; L2 x 1e-4 of the diagonal: simplified "),
        "{text}"
    );
    let out = swm(&["encode", i, "-o", o, "--effort", "fastest"]);
    assert_eq!(out.status.code(), Some(2));
    // A mode with no choice of methods has no use for a level.
    for refused in [
        &["--mode", "swing", "--effort", "fast"][..],
        &["--mode", "lossless", "--effort", "max"][..],
    ] {
        let out = swm(&[&["encode", i, "-o", o][..], refused].concat());
        assert_eq!(out.status.code(), Some(2), "{refused:?}");
    }
}

#[test]
fn an_error_bound_gets_the_smallest_file_that_meets_it() {
    let Some(corpus) = shared_corpus() else {
        assert!(
            std::env::var_os("SWM_CI").is_none(),
            "SWM_CI is set and ../shared/corpus is missing"
        );
        return;
    };
    let mesh = swm::io::read_mesh(&corpus.join("stanford-bunny.obj")).unwrap();
    for e in [5e-4, 2e-4] {
        let bound = SwingTarget::MaxError(ErrorBound::Relative(e));
        let file = encode(&mesh, bound, Effort::Default);
        let l2 = metro_l2(&mesh, &file.bytes);
        assert!(l2 <= e, "E {e}: L2 {l2} at {} bytes", file.bytes.len());
        // The same chooser 5% smaller misses the bound: the file is within
        // 5% of the smallest that meets it.
        let smaller = (file.bytes.len() as f64 * 0.95) as u64;
        let less = encode(&mesh, SwingTarget::Bytes(smaller), Effort::Default);
        let l2_less = metro_l2(&mesh, &less.bytes);
        assert!(
            l2_less > e,
            "E {e}: {} bytes measure {l2}, and {} bytes {l2_less}",
            file.bytes.len(),
            less.bytes.len()
        );
        // In model units, the same bound.
        let d = e * mesh.bbox_diagonal();
        let units = encode(
            &mesh,
            SwingTarget::MaxError(ErrorBound::Absolute(d)),
            Effort::Default,
        );
        assert_eq!(units.bytes, file.bytes);
    }
    // A bound no file meets is an error naming the closest.
    let tiny = SwingTarget::MaxError(ErrorBound::Relative(1e-9));
    let options = EncodeOptions {
        mode: EncodeMode::Auto {
            target: tiny,
            max_bytes: Some(20_000),
        },
        effort: Effort::Fast,
        ..Default::default()
    };
    match swm::encode(&mesh, &options) {
        Err(swm::Error::ErrorBound(b)) => assert!(b.lowest > 1e-9 && b.bytes <= 20_000),
        other => panic!("{:?}", other.map(|e| e.bytes.len())),
    }
}

#[test]
fn a_rate_counts_positions_not_split_vertices() {
    // Every triangle with its own three vertices, as a glTF file with
    // flat normals has them: the same shape and positions.
    let welded = swm_corpus::icosphere(1.0, 2);
    let mut split = swm::TriMesh::new(Vec::new(), Vec::new());
    for t in &welded.triangles {
        let base = split.positions.len() as u32;
        split
            .positions
            .extend(t.iter().map(|&v| welded.positions[v as usize]));
        split.triangles.push([base, base + 1, base + 2]);
    }
    assert_eq!(split.distinct_positions(), welded.vertex_count());
    // The same budget for both (cleaning numbers the welded copy of the
    // split mesh in another order, so the files themselves may differ).
    let budget = (4.0 * welded.vertex_count() as f64 / 8.0).round();
    for mesh in [&split, &welded] {
        let n = encode(mesh, SwingTarget::BitsPerVertex(4.0), Effort::Fast)
            .bytes
            .len() as f64;
        assert!(
            n <= budget * 1.03 && n >= budget * 0.97,
            "{n} bytes for {budget}"
        );
    }
}
