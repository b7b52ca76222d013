//! Connectivity cost (the CLRS and TOPO sections) per triangle: at most
//! 1.8 bits on every corpus mesh over 5,000 faces, at most 1.0 on a
//! regular (valence-6) mesh. A ratchet: lower these bounds as the coder
//! improves, never raise them.

mod common;
use common::*;

fn connectivity_bits_per_triangle(mesh: &swm::TriMesh) -> (f64, u64) {
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp: 12 },
        ..Default::default()
    };
    let encoded = swm::encode(mesh, &options).unwrap();
    let info = swm::inspect(&encoded.bytes, &swm::Limits::default()).unwrap();
    let bytes: usize = info
        .stats
        .sections
        .iter()
        .filter(|(t, _)| t == b"CLRS" || t == b"TOPO")
        .map(|s| s.1)
        .sum();
    (
        8.0 * bytes as f64 / info.stats.triangles as f64,
        info.stats.triangles,
    )
}

#[test]
fn corpus_meshes_cost_at_most_1_8_bits_per_triangle() {
    let Some(dir) = shared_corpus() else { return };
    let names = MANIFOLD_CORPUS
        .iter()
        .map(|m| m.0)
        .chain(NON_MANIFOLD_CORPUS.iter().map(|m| m.0));
    for name in names {
        let mesh = swm::io::read_mesh(&dir.join(name)).unwrap();
        let (bpt, triangles) = connectivity_bits_per_triangle(&mesh);
        println!("{name}: {bpt:.3} bits/triangle over {triangles} triangles");
        if triangles > 5000 {
            assert!(bpt <= 1.8, "{name}: {bpt} bits per triangle");
        }
    }
}

#[test]
fn regular_mesh_costs_at_most_1_bit_per_triangle() {
    let (bpt, _) = connectivity_bits_per_triangle(&swm_corpus::icosphere(1.0, 5));
    println!("icosphere(5): {bpt:.3} bits/triangle");
    assert!(bpt <= 1.0, "{bpt} bits per triangle");
}
