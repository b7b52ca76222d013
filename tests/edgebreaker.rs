//! Edgebreaker on every corpus mesh (after cleaning, holes closed by dummy
//! vertices) and every generated mesh: decode(encode(M)) has exactly M's
//! triangles, and recompressing the decoded mesh gives the same symbols.

mod common;
use common::*;
use swm::edgebreaker::{decode, encode, fill_holes, Symbol};
use swm::{CleanOptions, CornerTable, TriMesh};

/// Round trip; returns (triangles, order-1 conditional entropy of the
/// CLERS string in bits per triangle) for the record.
fn check(name: &str, mesh: &TriMesh) -> (usize, f64) {
    let cleaned =
        swm::clean(mesh, &CleanOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    let filled = fill_holes(&cleaned.table);
    let table = CornerTable::new(&filled.triangles, filled.vertex_count).unwrap();
    let enc = encode(&table).unwrap_or_else(|e| panic!("{name}: {e}"));
    let dec = decode(&enc.connectivity).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut new_id = vec![u32::MAX; table.vertex_count()];
    for (k, v) in enc.vertex_order.iter().enumerate() {
        new_id[v.idx()] = k as u32;
    }
    let want: Vec<[u32; 3]> = enc
        .tip_corners
        .iter()
        .map(|&c| [c, c.next(), c.prev()].map(|x| new_id[table.vertex(x).idx()]))
        .collect();
    assert_eq!(dec.triangles(), want, "{name}: decoded triangles differ");
    let again = encode(&dec).unwrap();
    assert_eq!(
        again.connectivity, enc.connectivity,
        "{name}: recompression differs"
    );
    // Empirical H(symbol | previous symbol), the target of the adaptive coder.
    let mut counts = [[0f64; 5]; 5];
    let mut prev = Symbol::C;
    for &s in &enc.connectivity.symbols {
        counts[prev as usize][s as usize] += 1.0;
        prev = s;
    }
    let n: f64 = counts.iter().flatten().sum();
    let h: f64 = counts
        .iter()
        .map(|row| {
            let r: f64 = row.iter().sum();
            row.iter()
                .filter(|&&c| c > 0.0)
                .map(|&c| -c * (c / r).log2())
                .sum::<f64>()
        })
        .sum::<f64>()
        / n.max(1.0);
    (cleaned.mesh.face_count(), h)
}

#[test]
fn generated_corpus_roundtrips() {
    for (name, mesh) in swm_corpus::all() {
        let (_, h) = check(name, &mesh);
        if name == "icosphere" {
            assert!(h < 1.0, "regular mesh: H1 = {h} bits per triangle");
        }
    }
}

#[test]
fn shared_corpus_roundtrips() {
    let Some(dir) = shared_corpus() else { return };
    let mut names: Vec<&str> = MANIFOLD_CORPUS.iter().map(|m| m.0).collect();
    names.extend(NON_MANIFOLD_CORPUS.iter().map(|m| m.0));
    for name in names {
        let mesh = swm::io::read_mesh(&dir.join(name)).unwrap();
        let (faces, h) = check(name, &mesh);
        println!("{name}: {faces} faces, H1 = {h:.3} bits/triangle");
    }
}
