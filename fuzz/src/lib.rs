//! What the mesh-reader fuzz targets share: one check, four formats.

use swm::io::MeshFormat;

/// Reads `data` as a `format` file under limits a fuzzer can afford:
/// `swm::io::read_mesh_bytes` must return an error or a mesh that passes
/// `TriMesh::validate`, never panic, hang or allocate because a header
/// said so.
pub fn check_reader(data: &[u8], format: MeshFormat) {
    let limits = swm::Limits {
        max_vertices: 1 << 20,
        max_faces: 1 << 20,
        max_alloc_bytes: 256 << 20,
        ..swm::Limits::UNLIMITED
    };
    if let Ok(mesh) = swm::io::read_mesh_bytes(data, format, &limits) {
        // The readers promise indices in range and finite positions.
        mesh.validate().expect("reader returned an invalid mesh");
    }
}
