//! Read -> write -> read keeps the mesh, for every format swm writes.

mod common;
use common::*;
use swm::TriMesh;

fn roundtrip(name: &str, mesh: &TriMesh, dir: &std::path::Path) {
    for ext in ["obj", "ply", "off"] {
        let path = dir.join(format!("{name}.{ext}"));
        swm::io::write_mesh(&path, mesh).unwrap_or_else(|e| panic!("{name}.{ext}: {e}"));
        let back = swm::io::read_mesh(&path).unwrap_or_else(|e| panic!("{name}.{ext}: {e}"));
        assert_eq!(back.positions.len(), mesh.positions.len(), "{name}.{ext}");
        assert!(
            back.positions
                .iter()
                .zip(&mesh.positions)
                .all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits)),
            "{name}.{ext}: positions changed"
        );
        assert_eq!(
            back.triangles, mesh.triangles,
            "{name}.{ext}: triangles changed"
        );
    }
}

#[test]
fn generated_meshes_roundtrip() {
    let dir = scratch("roundtrip-generated");
    for (name, mesh) in swm_corpus::all() {
        roundtrip(name, &mesh, &dir);
    }
}

#[test]
fn corpus_meshes_roundtrip() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    let dir = scratch("roundtrip-corpus");
    for name in [
        "fandisk.obj",
        "horse.ply",
        "suzanne.obj",
        "beetle.obj",
        "woody.obj",
    ] {
        let mesh = swm::io::read_mesh(&corpus.join(name)).unwrap();
        roundtrip(name, &mesh, &dir);
    }
}

#[test]
fn writing_never_leaves_a_partial_file() {
    let dir = scratch("atomic");
    let path = dir.join("out.ply");
    std::fs::write(&path, b"previous content").unwrap();
    // An invalid mesh (index out of range) must not replace the old file.
    let bad = TriMesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 7]]);
    assert!(swm::io::write_mesh(&path, &bad).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"previous content");
    let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(leftovers.len(), 1, "temporary files left behind");
}
