//! The displaced-subdivision method on the shared corpus: its files fit
//! the budget, and (ignored, run by hand) the ablation of its settings
//! that BENCHMARKS.md records.

use super::displaced::Displaced;
use super::method::{Ask, CodingMethod, Job, Services};
use super::stats::MethodStats;
use crate::displaced::fit::Fallback;
use crate::displaced::predict::Rule;
use crate::displaced::write::Settings;
use crate::options::{EncodeOptions, SwingTarget};
use crate::TriMesh;

use crate::io::shared_corpus_mesh as corpus;

/// Size and encoder-measured L2 (1e-4 of the diagonal) of `method` on
/// `mesh` at `bpv`, with the base faces and levels it chose.
fn run(mesh: &TriMesh, method: &Displaced, bpv: f64) -> (usize, f64, u64, u8) {
    let cleaned = crate::clean(mesh, &Default::default()).unwrap();
    let options = EncodeOptions::default();
    let services = Services::new(mesh, &cleaned, options.framing, false);
    let job = Job {
        cleaned: &cleaned,
        input_vertices: mesh.distinct_positions(),
        options: &options,
        services: &services,
    };
    let ask = Ask {
        target: SwingTarget::BitsPerVertex(bpv),
        max_bytes: None,
    };
    let made = method.encode(&job, ask).unwrap().unwrap();
    let MethodStats::Displaced(s) = &made.stats else {
        panic!("not a displaced file")
    };
    (
        made.bytes.len(),
        made.l2_relative.unwrap() * 1e4,
        s.base_faces,
        s.levels,
    )
}

#[test]
fn files_fit_their_budget_and_come_near_the_simplified_method() {
    // A bumpy sphere: subdivision has curvature to predict and detail
    // to add.
    let mut mesh = crate::mesh::test_shapes::uv_sphere(64, 64);
    for p in &mut mesh.positions {
        let r = 1.0 + 0.05 * (6.0 * p[0]).sin() * (5.0 * p[2]).cos();
        *p = p.map(|c| c * r);
    }
    let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
    let options = EncodeOptions::default();
    let services = Services::new(&mesh, &cleaned, options.framing, false);
    let job = Job {
        cleaned: &cleaned,
        input_vertices: mesh.distinct_positions(),
        options: &options,
        services: &services,
    };
    for bpv in [1.0, 4.0] {
        let budget = super::request::bytes_for(bpv, job.input_vertices) as usize;
        let (bytes, l2, faces, levels) = run(&mesh, &Displaced::DEFAULT, bpv);
        assert!(bytes <= budget, "{bytes} > {budget}");
        assert!(
            bytes as f64 >= 0.9 * budget as f64,
            "{bytes} far below {budget}"
        );
        assert!(faces >= 8 && levels >= 1);
        let simplified =
            super::simplified::encode_at(&job, budget as u64, super::simplified::Search::Full)
                .unwrap()
                .l2_relative
                .unwrap()
                * 1e4;
        println!("{bpv} b/v: displaced {l2:.2}, simplified {simplified:.2}");
        assert!(
            l2 < 1.25 * simplified,
            "{bpv} b/v: {l2} against {simplified}"
        );
    }
}

/// A small mesh at a low rate: the edge rule's step is a quarter of what
/// the file's error asks for, and the floor (`STEP_ERROR`) makes a
/// closer file of the same budget (homer at 0.5 b/v: 49.0 → 37.8).
#[test]
fn steps_are_never_finer_than_the_error_asks() {
    let Some(mesh) = corpus("homer.obj") else {
        return;
    };
    let edge_rule = Displaced {
        settings: Settings {
            step_error: None,
            ..Displaced::DEFAULT.settings
        },
    };
    let (bytes, l2, ..) = run(&mesh, &Displaced::DEFAULT, 0.5);
    let (edge_bytes, edge_l2, ..) = run(&mesh, &edge_rule, 0.5);
    println!("floor: {bytes} B, L2 {l2:.2}; edge rule: {edge_bytes} B, L2 {edge_l2:.2}");
    assert!(l2 < 0.9 * edge_l2, "{l2} against {edge_l2}");
}

/// A floored step whose search ends with the whole input as its base and
/// bytes to spare has no faces left to spend them on: the edge rule's
/// file is searched and weighed too (teapot at 8 b/v: the floored file
/// alone had L2 8.8 with 12% of the budget unused, the edge rule's 2.5).
#[test]
fn a_floored_search_short_of_the_budget_weighs_the_edge_rule() {
    let Some(mesh) = corpus("teapot.obj") else {
        return;
    };
    let budget = super::request::bytes_for(8.0, mesh.distinct_positions());
    let (bytes, l2, faces, levels) = run(&mesh, &Displaced::DEFAULT, 8.0);
    println!("{bytes} B of {budget}, L2 {l2:.2}, {faces}x4^{levels}");
    assert!(bytes as f64 >= 0.97 * budget as f64, "{bytes} of {budget}");
    assert!(l2 < 4.0, "{l2}");
}

/// The first file of a small mesh is far from its budget (beetle at
/// 2 b/v: 671 bytes of 284), so carrying its error to the budget
/// misjudges the edge rule against the floored step by a few percent:
/// the two were 5% apart, the edge rule's search landed on a base of 25
/// faces at L2 275 and the floored one on 50 at 124. Both are searched
/// when their carried errors are that close.
#[test]
fn a_close_other_step_is_searched_too() {
    let Some(mesh) = corpus("beetle.obj") else {
        return;
    };
    let (bytes, l2, faces, levels) = run(&mesh, &Displaced::DEFAULT, 2.0);
    println!("{bytes} B, L2 {l2:.1}, {faces}x4^{levels}");
    assert!(l2 < 180.0, "{l2}");
}

#[test]
#[ignore]
fn ablation() {
    let d = Displaced::DEFAULT;
    let c32 = Displaced {
        settings: Settings {
            step_scale: 1.0 / 32.0,
            ..d.settings
        },
    };
    let variants: Vec<(&str, Displaced)> = vec![
        ("default", d),
        (
            "butterfly",
            Displaced {
                settings: Settings {
                    rule: Rule::Butterfly,
                    ..d.settings
                },
            },
        ),
        (
            "fallback zero",
            Displaced {
                settings: Settings {
                    fallback: Fallback::Zero,
                    ..d.settings
                },
            },
        ),
        (
            "facing off",
            Displaced {
                settings: Settings {
                    facing: false,
                    ..d.settings
                },
            },
        ),
        (
            "c 1/8",
            Displaced {
                settings: Settings {
                    step_scale: 1.0 / 8.0,
                    ..d.settings
                },
            },
        ),
        ("c 1/32", c32),
        (
            "c 1/48",
            Displaced {
                settings: Settings {
                    step_scale: 1.0 / 48.0,
                    ..d.settings
                },
            },
        ),
        (
            "decay 1",
            Displaced {
                settings: Settings {
                    step_decay: 1.0,
                    ..d.settings
                },
            },
        ),
        (
            "decay 0.5",
            Displaced {
                settings: Settings {
                    step_decay: 0.5,
                    ..d.settings
                },
            },
        ),
        (
            "c 1/32 decay 0.5",
            Displaced {
                settings: Settings {
                    step_decay: 0.5,
                    ..c32.settings
                },
            },
        ),
        (
            "c 1/32 decay 1",
            Displaced {
                settings: Settings {
                    step_decay: 1.0,
                    ..c32.settings
                },
            },
        ),
        (
            "snap base",
            Displaced {
                settings: Settings {
                    snap_base: true,
                    ..d.settings
                },
            },
        ),
        (
            "qp 10",
            Displaced {
                settings: Settings {
                    qp: Some(10),
                    ..d.settings
                },
            },
        ),
        (
            "qp 14",
            Displaced {
                settings: Settings {
                    qp: Some(14),
                    ..d.settings
                },
            },
        ),
        (
            "qp rule 0",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 0.0,
                    ..d.settings
                },
            },
        ),
        (
            "qp rule 1",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 1.0,
                    ..d.settings
                },
            },
        ),
        (
            "qp rule 2",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 2.0,
                    ..d.settings
                },
            },
        ),
        (
            "c 1/32 qp rule 1",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 1.0,
                    ..c32.settings
                },
            },
        ),
        (
            "c 1/32 qp rule 2",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 2.0,
                    ..c32.settings
                },
            },
        ),
        (
            "c 1/32 qp rule 1 decay 1",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 1.0,
                    step_decay: 1.0,
                    ..c32.settings
                },
            },
        ),
        (
            "c 1/32 qp rule 1 decay 0.5",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 1.0,
                    step_decay: 0.5,
                    ..c32.settings
                },
            },
        ),
        (
            "c 1/24 qp rule 1 decay 0.5",
            Displaced {
                settings: Settings {
                    qp: None,
                    qp_slack: 1.0,
                    step_decay: 0.5,
                    step_scale: 1.0 / 24.0,
                    ..d.settings
                },
            },
        ),
    ];
    let only = std::env::var("SWM_ABLATION").ok();
    for name in ["stanford-bunny.obj", "horse.ply"] {
        let Some(mesh) = corpus(name) else { return };
        for (label, m) in &variants {
            if only
                .as_deref()
                .is_some_and(|o| !o.split(',').any(|x| x == *label))
            {
                continue;
            }
            let mut row = format!("| {name} | {label} |");
            for bpv in [0.5, 1.0, 2.0, 4.0, 8.0] {
                let (bytes, l2, faces, levels) = run(&mesh, m, bpv);
                row += &format!(" {l2:.2} ({bytes} B, {faces}x4^{levels}) |");
            }
            println!("{row}");
        }
    }
}
