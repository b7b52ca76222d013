//! A minimal Wavefront OBJ writer (positions and triangles only).
//!
//! Coordinates are written with Rust's `{}` formatting of `f32`, which
//! prints the shortest decimal that parses back to the same value, so a
//! written file reads back bit-identical. Files are written to a temporary
//! name beside the target and renamed into place, so a reader never sees a
//! half-written mesh.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use swm::TriMesh;

/// Writes `mesh` as OBJ text: a comment line, `v x y z` per vertex, then
/// `f a b c` per triangle with 1-based indices.
pub fn write_obj<W: Write>(mesh: &TriMesh, mut out: W) -> io::Result<()> {
    writeln!(
        out,
        "# swm-corpus: {} vertices, {} triangles",
        mesh.vertex_count(),
        mesh.face_count()
    )?;
    for p in &mesh.positions {
        writeln!(out, "v {} {} {}", p[0], p[1], p[2])?;
    }
    for t in &mesh.triangles {
        writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
    }
    out.flush()
}

/// Writes `mesh` to `path` through a temporary file `path.tmp` and a
/// rename (atomic on the same file system).
pub fn save_obj(mesh: &TriMesh, path: &Path) -> io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = Path::new(&tmp);
    let result = (|| {
        let mut w = BufWriter::new(File::create(tmp)?);
        write_obj(mesh, &mut w)?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all()
    })();
    match result {
        Ok(()) => std::fs::rename(tmp, path),
        Err(e) => {
            let _ = std::fs::remove_file(tmp);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_shortest_round_tripping_floats_and_one_based_faces() {
        let mesh = TriMesh::new(
            vec![[0.1, -0.0, 1.0], [1.0 / 3.0, 2.5e-8, -7.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        );
        let mut buf = Vec::new();
        write_obj(&mesh, &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[1], "v 0.1 -0 1");
        assert_eq!(lines[4], "f 1 2 3");
        let parsed: Vec<f32> = lines[2][2..]
            .split(' ')
            .map(|s| s.parse().unwrap())
            .collect();
        assert_eq!(parsed, mesh.positions[1]);
    }
}
