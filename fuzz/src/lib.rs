//! What the fuzz targets share: the mesh readers' one check (four
//! formats), and the byte reader the encoder targets build meshes with.

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

/// Reads a fuzz input front to back; zeros once it runs out, so every
/// input builds some mesh.
pub struct Bytes<'a>(pub &'a [u8]);

impl Bytes<'_> {
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    /// A value in `lo..=hi`.
    pub fn range(&mut self, lo: u32, hi: u32) -> u32 {
        lo + self.u8() as u32 % (hi - lo + 1)
    }
}
