//! Arbitrary bytes as a OFF file: `swm::io::read_mesh_bytes` must return an
//! error or a mesh that passes `TriMesh::validate`, never panic, hang or
//! allocate because a header said so.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swm::io::MeshFormat;

fuzz_target!(|data: &[u8]| {
    let limits = swm::Limits {
        max_vertices: 1 << 20,
        max_faces: 1 << 20,
        max_alloc_bytes: 256 << 20,
    };
    if let Ok(mesh) = swm::io::read_mesh_bytes(data, MeshFormat::Off, &limits) {
        // The readers promise indices in range and finite positions.
        mesh.validate().expect("reader returned an invalid mesh");
    }
});
