//! SwingWrapper on the closed genus-0 meshes of the shared corpus (issue
//! 5, "Must show"): the retiled mesh is a closed, regular manifold, the
//! file lands within 3% of the requested size and under the thesis's
//! bound, and decoding gives the encoder's mesh. Regularity is asserted
//! where it holds today (horse at every rate, fandisk's C+R share);
//! fandisk's valence-6 share (70-82%) is reported, not asserted.

mod common;

use swm::{DecodeOptions, EncodeMode, EncodeOptions, SwingTarget};

/// SwingWrapper at `bpv` bits per input vertex, as `swm encode --bpv`
/// runs it (angle bits chosen by rate control).
fn at_rate(bpv: f64) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: SwingTarget::BitsPerVertex(bpv),
            angle_bits: None,
            max_bytes: None,
        },
        ..EncodeOptions::default()
    }
}

fn encode(path: &std::path::Path, bpv: f64) -> (swm::Encoded, swm::TriMesh) {
    let mesh = swm::io::read_mesh(path).unwrap();
    (swm::encode(&mesh, &at_rate(bpv)).unwrap(), mesh)
}

/// Header allowance of the size bound, bytes (format-spec/05-swing.md).
const HEADER_ALLOWANCE: f64 = 85.0;

fn check(name: &str, bpv: f64, valence6_at_least: Option<f64>) {
    let Some(dir) = common::shared_corpus() else {
        return;
    };
    let (encoded, input) = encode(&dir.join(name), bpv);
    let stats = encoded.stats.swing().unwrap();
    let rate = encoded.stats.rate().unwrap();
    let requested = (bpv * input.vertex_count() as f64 / 8.0).round();
    let size = encoded.bytes.len() as f64;
    println!(
        "{name} {bpv} b/v: {size} bytes for {requested}, {} triangles, C+R {:.3}, valence-6 {:.3}, {} runs",
        stats.triangles,
        stats.cr_share,
        stats.valence6_share,
        rate.attempts.len()
    );
    assert!(
        stats.cr_share >= 0.90,
        "{name}: C+R share {}",
        stats.cr_share
    );
    if let Some(v6) = valence6_at_least {
        assert!(
            stats.valence6_share >= v6,
            "{name}: valence-6 {}",
            stats.valence6_share
        );
    }
    assert!(
        (size - requested).abs() <= 0.03 * requested,
        "{name}: {size} bytes for {requested}"
    );
    let bound = 288.0 + 5.83 * stats.triangles as f64 + 8.0 * HEADER_ALLOWANCE;
    assert!(8.0 * size <= bound, "{name}: {} bits > {bound}", 8.0 * size);
    // The retiled mesh itself, whatever post-processing the hint asks.
    let decoded = swm::decode(&encoded.bytes, &DecodeOptions::plain()).unwrap();
    assert_eq!(decoded.triangles.len() as u64, stats.triangles);
    let table = swm::CornerTable::new(&decoded.triangles, decoded.vertex_count())
        .expect("decoded mesh is a manifold");
    assert!(
        table.opposites().iter().all(|o| o.is_some()),
        "{name}: closed"
    );
    let (v, f) = (
        decoded.vertex_count() as i64,
        decoded.triangles.len() as i64,
    );
    assert_eq!(v - f / 2, 2, "{name}: a sphere (V - E + F = 2)");
}

#[test]
fn horse_is_regular_and_on_size_at_1_and_4_bpv() {
    check("horse.ply", 1.0, Some(0.75));
    check("horse.ply", 4.0, Some(0.75));
}

#[test]
fn fandisk_is_regular_and_on_size_at_1_and_4_bpv() {
    check("fandisk.obj", 1.0, None);
    check("fandisk.obj", 4.0, None);
}

/// Issue 6: the decoded mesh keeps the input's boundary loops (bunny's
/// five holes in its base; alligator and woody are flat disks, one loop
/// each), is manifold, and lands within 3% of the request. 4 b/v is the
/// rate all three reach today (woody's 1 and 2 b/v budgets, 87 and 173
/// bytes, are at or under the container's fixed cost plus its smallest
/// retiling).
#[test]
fn boundary_loops_survive_on_bunny_alligator_and_woody() {
    let Some(dir) = common::shared_corpus() else {
        return;
    };
    for (name, loops) in [
        ("stanford-bunny.obj", 5),
        ("alligator.obj", 1),
        ("woody.obj", 1),
    ] {
        let (encoded, input) = encode(&dir.join(name), 4.0);
        let input_loops = swm::clean(&input, &Default::default())
            .unwrap()
            .table
            .stats(&input)
            .boundary_loops;
        assert_eq!(input_loops, loops, "{name}: input loops");
        let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
        let table = swm::CornerTable::new(&decoded.triangles, decoded.vertex_count())
            .unwrap_or_else(|e| panic!("{name}: decoded mesh not manifold: {e}"));
        let stats = table.stats(&decoded);
        println!(
            "{name}: {} bytes, {} triangles decoded, {} loops",
            encoded.bytes.len(),
            decoded.face_count(),
            stats.boundary_loops
        );
        assert_eq!(stats.boundary_loops, loops, "{name}: decoded loops");
        let requested = (4.0 * input.vertex_count() as f64 / 8.0).round();
        let size = encoded.bytes.len() as f64;
        assert!(
            (size - requested).abs() <= 0.03 * requested,
            "{name}: {size} bytes for {requested}"
        );
    }
}

/// Issue 20, item 4: at 2 b/v an open surface's file no longer goes on
/// triangles the decoder drops. Alligator and woody start on their one
/// boundary loop (its fan, connectivity only, is counted apart), bunny
/// on its longest of five; under 10% of the retiled triangles are
/// masked over patches (they were 75%, 66% and 2.5% when every retiling
/// started inside).
#[test]
fn open_surfaces_mask_under_a_tenth_of_their_triangles_at_2_bpv() {
    let Some(dir) = common::shared_corpus() else {
        return;
    };
    for name in ["woody.obj", "alligator.obj", "stanford-bunny.obj"] {
        let (encoded, _) = encode(&dir.join(name), 2.0);
        let stats = encoded.stats.swing().unwrap();
        println!(
            "{name}: {} of {} retiled triangles masked, {} loop(s) of {} points, {} bytes of LOOP",
            stats.holes_masked_triangles,
            stats.triangles - stats.loop_points,
            stats.loops,
            stats.loop_points,
            stats.loop_bytes
        );
        assert_eq!(stats.loops, 1, "{name}: not started on a loop");
        assert!(
            stats.masked_share() < 0.1,
            "{name}: {}",
            stats.masked_share()
        );
        let info = swm::inspect(&encoded.bytes, &Default::default()).unwrap();
        let read = info.swing.unwrap();
        assert_eq!(
            (read.loops, read.loop_points, read.holes_masked_triangles),
            (stats.loops, stats.loop_points, stats.holes_masked_triangles)
        );
    }
}

/// Issue 6: every mesh of the shared corpus (bunny-1m aside: the encode
/// benchmark covers it) at 1, 2 and 4 b/v either encodes to a file that
/// decodes to a manifold mesh, or fails with a retiling error that names
/// why; none panics. The runs that land within 3% of the request today
/// are a ratchet: each must keep doing so.
#[test]
fn every_corpus_mesh_encodes_or_fails_cleanly() {
    let Some(dir) = common::shared_corpus() else {
        return;
    };
    // (mesh, rates in b/v that must land within 3%)
    let meshes: [(&str, &[f64]); 12] = [
        ("stanford-bunny.obj", &[1.0, 2.0, 4.0]),
        ("horse.ply", &[1.0, 2.0, 4.0]),
        ("fandisk.obj", &[1.0, 2.0, 4.0]),
        ("spot.obj", &[1.0, 2.0, 4.0]),
        ("homer.obj", &[1.0, 2.0, 4.0]),
        ("cheburashka.obj", &[1.0, 2.0, 4.0]),
        ("alligator.obj", &[2.0, 4.0]),
        ("woody.obj", &[4.0]),
        ("cow.obj", &[]),
        ("teapot.obj", &[]),
        ("suzanne.obj", &[]),
        ("beetle.obj", &[4.0]),
    ];
    let mut misses = Vec::new();
    for (name, on_size) in meshes {
        let input = swm::io::read_mesh(&dir.join(name)).unwrap();
        for bpv in [1.0, 2.0, 4.0] {
            let requested = (bpv * input.vertex_count() as f64 / 8.0).round();
            match swm::encode(&input, &at_rate(bpv)) {
                Ok(encoded) => {
                    let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
                    swm::CornerTable::new(&decoded.triangles, decoded.vertex_count())
                        .unwrap_or_else(|e| panic!("{name} {bpv}: decoded not manifold: {e}"));
                    let size = encoded.bytes.len() as f64;
                    let within = (size - requested).abs() <= 0.03 * requested;
                    println!(
                        "{name} {bpv} b/v: {size} bytes for {requested} (within 3%: {within})"
                    );
                    if on_size.contains(&bpv) && !within {
                        misses.push(format!("{name} {bpv} b/v: {size} bytes for {requested}"));
                    }
                }
                Err(e) => {
                    println!("{name} {bpv} b/v: {e}");
                    assert!(matches!(e, swm::Error::Retile(_)), "{name} {bpv}: {e:?}");
                    assert!(!on_size.contains(&bpv), "{name} {bpv} b/v failed: {e}");
                }
            }
        }
    }
    assert!(misses.is_empty(), "{misses:#?}");
}
