//! Tests across formats: round trips, malformed input every reader must
//! refuse the same way, and the shared corpus.

use super::*;
use crate::{LimitError, Limited, Location};
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub(super) fn read(bytes: &[u8], format: MeshFormat) -> Result<TriMesh, Error> {
    read_mesh_bytes(bytes, format, &Limits::default())
}

/// The `Malformed` and location of a format error; panics on other errors.
pub(super) fn malformed(result: Result<TriMesh, Error>) -> (Malformed, Option<Location>) {
    match result {
        Err(Error::Format(e)) => (e.what, e.at),
        other => panic!("expected a format error, got {other:?}"),
    }
}

fn bits(mesh: &TriMesh) -> Vec<[u32; 3]> {
    mesh.positions.iter().map(|p| p.map(f32::to_bits)).collect()
}

/// A small mesh with awkward numbers: negative zero, subnormals, huge and
/// tiny magnitudes, values with long shortest representations, an
/// unreferenced vertex, a degenerate and a repeated triangle.
fn awkward_mesh() -> TriMesh {
    let positions = vec![
        [0.0, -0.0, 1.0],
        [0.1, 0.2, 0.3],
        [1e-45, -1.1754942e-38, 3.4028235e38],
        [-1.0e-7, 123456.79, 1.0 / 3.0],
        [f32::MIN_POSITIVE, 16777217.0, -2.5],
        [7.0, 8.0, 9.0], // unreferenced
        [0.5, 0.25, 0.125],
    ];
    let triangles = vec![
        [0, 1, 2],
        [2, 1, 3],
        [3, 4, 0],
        [4, 4, 1],
        [0, 1, 2],
        [6, 0, 3],
    ];
    TriMesh::new(positions, triangles)
}

fn round_trip(mesh: &TriMesh, format: MeshFormat) -> TriMesh {
    let mut bytes = Vec::new();
    write_mesh_to(&mut bytes, format, mesh).unwrap();
    read(&bytes, format).unwrap_or_else(|e| panic!("{}: {e}", format.name()))
}

#[test]
fn indexed_formats_round_trip_bit_exactly() {
    let mesh = awkward_mesh();
    for format in [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Off] {
        let back = round_trip(&mesh, format);
        assert_eq!(bits(&back), bits(&mesh), "{}", format.name());
        assert_eq!(back.triangles, mesh.triangles, "{}", format.name());
    }
}

#[test]
fn stl_round_trip_keeps_corners() {
    let mesh = awkward_mesh();
    let back = round_trip(&mesh, MeshFormat::Stl);
    assert_eq!(back.triangles.len(), mesh.triangles.len());
    assert_eq!(back.positions.len(), 3 * mesh.triangles.len());
    for (t, u) in mesh.triangles.iter().zip(&back.triangles) {
        for k in 0..3 {
            let a = mesh.positions[t[k] as usize].map(f32::to_bits);
            let b = back.positions[u[k] as usize].map(f32::to_bits);
            assert_eq!(a, b);
        }
    }
}

#[test]
fn formats_by_extension() {
    let f = |p: &str| MeshFormat::from_path(Path::new(p));
    assert_eq!(f("a/b.obj").unwrap(), MeshFormat::Obj);
    assert_eq!(f("B.PLY").unwrap(), MeshFormat::Ply);
    assert_eq!(f("x.Off").unwrap(), MeshFormat::Off);
    assert_eq!(f("x.stl").unwrap(), MeshFormat::Stl);
    assert_eq!(f("x.GLB").unwrap(), MeshFormat::Glb);
    assert_eq!(f("x.gltf").unwrap(), MeshFormat::Gltf);
    assert_eq!(MeshFormat::from_name("Ply").unwrap(), MeshFormat::Ply);
    assert!(MeshFormat::from_name("swm").is_err());
    for bad in ["x.xyz", "noext", "obj", ""] {
        assert!(matches!(
            f(bad),
            Err(Error::Parameter(ParameterError::UnknownExtension))
        ));
    }
    assert_eq!(MeshFormat::Stl.name(), "STL");
    assert_eq!(MeshFormat::Glb.name(), "GLB");
}

#[test]
fn glb_round_trips_and_gltf_is_read_only() {
    assert!(MeshFormat::Glb.is_readable() && MeshFormat::Glb.is_writable());
    assert!(MeshFormat::Gltf.is_readable() && !MeshFormat::Gltf.is_writable());
    let mesh = awkward_mesh();
    let back = round_trip(&mesh, MeshFormat::Glb);
    assert_eq!(bits(&back), bits(&mesh));
    assert_eq!(back.triangles, mesh.triangles);

    let read_only = |r: Result<(), Error>| {
        matches!(
            r,
            Err(Error::Parameter(ParameterError::ReadOnly {
                format: "GLTF"
            }))
        )
    };
    let dir = scratch("gltf");
    let path = dir.join("m.gltf");
    assert!(read_only(write_mesh(&path, &mesh)));
    assert!(!path.exists(), "refused before anything is created");
    assert!(read_only(write_mesh_to(
        Vec::new(),
        MeshFormat::Gltf,
        &mesh
    )));
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn read_file_maps_or_reads() {
    let dir = scratch("read-file");
    for len in [0, 5, 1 << 20, (1 << 20) + 3] {
        let path = dir.join(format!("f{len}"));
        let bytes = garbage(len, len as u64 + 1);
        fs::write(&path, &bytes).unwrap();
        assert_eq!(&*read_file(&path).unwrap(), &bytes[..], "{len}");
    }
    assert!(matches!(read_file(&dir.join("missing")), Err(Error::Io(_))));
    let _ = fs::remove_dir_all(&dir);
}

/// The `InputBytes` limit error of a read, or a panic.
fn input_limit<T>(result: Result<T, Error>) -> LimitError {
    match result {
        Err(Error::LimitExceeded(e)) if e.what == Limited::InputBytes => e,
        Err(e) => panic!("expected an input limit error, got {e:?}"),
        Ok(_) => panic!("expected an input limit error, got a file"),
    }
}

#[test]
fn reads_stop_at_the_input_limit() {
    let dir = scratch("input-limit");
    let limits = |max_input_bytes| Limits {
        max_input_bytes,
        ..Limits::default()
    };
    // Read into memory, then mapped: exactly the limit passes, one byte
    // more is refused, naming the file's length.
    for len in [100u64, (1 << 20) + 7] {
        let path = dir.join(format!("f{len}.obj"));
        fs::write(&path, garbage(len as usize, len)).unwrap();
        assert_eq!(
            read_file_with(&path, &limits(len)).unwrap().len() as u64,
            len
        );
        let e = input_limit(read_file_with(&path, &limits(len - 1)));
        assert_eq!((e.requested, e.limit), (len, len - 1));
        input_limit(read_mesh_with(&path, &limits(len - 1)));
    }
    // A sparse file longer than the default limit is refused by its
    // length, before a byte of it is read (scanning 20 GiB of zeros would
    // take minutes).
    let huge = dir.join("huge.obj");
    let file = fs::File::create(&huge).unwrap();
    if file.set_len(20 << 30).is_ok() {
        let e = input_limit(read_mesh(&huge));
        assert_eq!((e.requested, e.limit), (20 << 30, 16 << 30));
        assert!(e.to_string().contains("input limit"), "{e}");
    } else {
        crate::test_skip::skip("this file system has no 20 GiB sparse files");
    }
    drop(file);
    let _ = fs::remove_dir_all(&dir);
}

/// A regular file that holds more than its length says (files under
/// `/proc` say 0) is cut off one byte past the limit.
#[cfg(target_os = "linux")]
#[test]
fn a_file_longer_than_its_length_is_cut_off_at_the_limit() {
    let path = Path::new("/proc/self/status");
    assert_eq!(fs::metadata(path).unwrap().len(), 0);
    let limits = Limits {
        max_input_bytes: 10,
        ..Limits::default()
    };
    let e = input_limit(read_file_with(path, &limits));
    assert_eq!((e.requested, e.limit), (11, 10));
    assert!(read_file(path).unwrap().len() > 11);
}

/// The kind of a refused input, or a panic.
fn refused_kind<T>(result: Result<T, Error>) -> crate::FileKind {
    match result {
        Err(Error::Input(crate::InputError::NotARegularFile { kind })) => kind,
        Err(e) => panic!("expected a refused input, got {e:?}"),
        Ok(_) => panic!("expected a refused input, got a file"),
    }
}

#[test]
fn only_regular_files_are_read() {
    use crate::FileKind;
    let dir = scratch("not-regular");
    let sub = dir.join("sub.obj");
    fs::create_dir(&sub).unwrap();
    assert_eq!(refused_kind(read_mesh(&sub)), FileKind::Directory);
    assert_eq!(refused_kind(read_file(&sub)), FileKind::Directory);
    #[cfg(unix)]
    {
        // Symbolic links are followed and their target judged.
        for ext in ["obj", "ply", "off", "stl", "swm"] {
            let zero = dir.join(format!("zero.{ext}"));
            std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
            assert_eq!(refused_kind(read_file(&zero)), FileKind::CharDevice);
            if ext != "swm" {
                assert_eq!(refused_kind(read_mesh(&zero)), FileKind::CharDevice);
            }
        }
        let message = read_file(Path::new("/dev/zero")).err().unwrap().to_string();
        assert_eq!(
            message,
            "a character device, not a regular file; only regular files are read"
        );
        // A FIFO without a writer: opening it must not wait for one.
        let fifo = dir.join("fifo.ply");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert_eq!(refused_kind(read_mesh(&fifo)), FileKind::Fifo);
            assert_eq!(refused_kind(read_file(&fifo)), FileKind::Fifo);
        } else {
            crate::test_skip::skip("mkfifo not found");
        }
    }
    let _ = fs::remove_dir_all(&dir);
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swm-io-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn write_mesh_replaces_atomically() {
    let dir = scratch("atomic");
    let mesh = awkward_mesh();
    for ext in ["obj", "ply", "off", "stl"] {
        let path = dir.join(format!("m.{ext}"));
        fs::write(&path, b"old").unwrap();
        write_mesh(&path, &mesh).unwrap();
        let back = read_mesh(&path).unwrap();
        assert_eq!(back.triangles.len(), mesh.triangles.len(), "{ext}");
        // An invalid mesh leaves the file alone.
        let bad = TriMesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 7]]);
        assert!(write_mesh(&path, &bad).is_err());
        let nan = TriMesh::new(vec![[f32::NAN; 3]; 3], vec![[0, 1, 2]]);
        assert!(write_mesh(&path, &nan).is_err());
        assert_eq!(read_mesh(&path).unwrap(), back, "{ext}");
    }
    // A directory that does not exist: an error, and nothing left behind.
    assert!(matches!(
        write_mesh(&dir.join("missing/m.obj"), &mesh),
        Err(Error::Io(_))
    ));
    let names: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 4, "leftovers: {names:?}");
    assert!(matches!(
        write_mesh(&dir.join("m.txt"), &mesh),
        Err(Error::Parameter(_))
    ));
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn empty_and_blank_input_is_empty_everywhere() {
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Off,
        MeshFormat::Stl,
    ] {
        for bytes in [&b""[..], b"\n \r\n\t\n"] {
            assert_eq!(
                malformed(read(bytes, format)).0,
                Malformed::Empty,
                "{format:?}"
            );
        }
    }
    let only_comments = b"# nothing\n# here\n";
    assert_eq!(
        malformed(read(only_comments, MeshFormat::Obj)).0,
        Malformed::Empty
    );
    assert_eq!(
        malformed(read(only_comments, MeshFormat::Off)).0,
        Malformed::Empty
    );
    let no_elements = b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n\
property float y\nproperty float z\nend_header\n";
    assert_eq!(
        malformed(read(no_elements, MeshFormat::Ply)).0,
        Malformed::Empty
    );
    assert_eq!(
        malformed(read(b"OFF\n0 0 0\n", MeshFormat::Off)).0,
        Malformed::Empty
    );
    assert_eq!(
        malformed(read(b"solid x\nendsolid x\n", MeshFormat::Stl)).0,
        Malformed::Empty
    );
    let mut stl = vec![0u8; 84];
    assert_eq!(malformed(read(&stl, MeshFormat::Stl)).0, Malformed::Empty);
    stl.truncate(83);
    assert_eq!(
        malformed(read(&stl, MeshFormat::Stl)).0,
        Malformed::Truncated
    );
}

/// Pseudo-random bytes (xorshift), the same on every run.
pub(super) fn garbage(n: usize, seed: u64) -> Vec<u8> {
    let mut x = seed | 1;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

#[test]
fn garbage_is_an_error_not_a_panic() {
    for seed in 1..40u64 {
        for len in [1, 7, 83, 84, 100, 134, 4096] {
            let bytes = garbage(len, seed);
            for format in [
                MeshFormat::Obj,
                MeshFormat::Ply,
                MeshFormat::Off,
                MeshFormat::Stl,
            ] {
                // Any outcome but a panic; short garbage is never a mesh.
                let result = read(&bytes, format);
                if format != MeshFormat::Stl || len < 134 {
                    assert!(result.is_err(), "{format:?} {seed} {len}");
                }
            }
        }
    }
}

#[test]
fn every_prefix_of_every_format_is_handled() {
    let mesh = awkward_mesh();
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Off,
        MeshFormat::Stl,
    ] {
        let mut bytes = Vec::new();
        write_mesh_to(&mut bytes, format, &mesh).unwrap();
        for cut in 0..bytes.len() {
            // Text formats may legitimately read a shorter mesh when the
            // cut falls between statements; binary ones must refuse.
            let result = read(&bytes[..cut], format);
            if matches!(format, MeshFormat::Ply | MeshFormat::Stl) {
                assert!(result.is_err(), "{format:?} cut at {cut}");
            }
        }
    }
}

#[test]
fn limits_are_enforced() {
    let mesh = awkward_mesh();
    let tight = Limits {
        max_vertices: 3,
        ..Limits::default()
    };
    let few_faces = Limits {
        max_faces: 2,
        ..Limits::default()
    };
    let little_memory = Limits {
        max_alloc_bytes: 100,
        ..Limits::default()
    };
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Off,
        MeshFormat::Stl,
    ] {
        let mut bytes = Vec::new();
        write_mesh_to(&mut bytes, format, &mesh).unwrap();
        for limits in [&tight, &few_faces, &little_memory] {
            let result = read_mesh_bytes(&bytes, format, limits);
            assert!(
                matches!(result, Err(Error::LimitExceeded(_))),
                "{format:?} {limits:?}: {result:?}"
            );
        }
        assert!(read_mesh_bytes(&bytes, format, &Limits::UNLIMITED).is_ok());
    }
}

/// `../shared/corpus`, or `None` after saying the test was skipped.
fn corpus() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus");
    if dir.is_dir() {
        Some(dir)
    } else {
        crate::test_skip::skip("../shared/corpus not found");
        None
    }
}

#[test]
fn reads_the_shared_corpus() {
    let Some(dir) = corpus() else { return };
    // Faces after merging coincident vertices, from the corpus README; the
    // raw files may hold a few more (degenerate or duplicate) faces.
    let known = [
        ("fandisk.obj", 12946),
        ("stanford-bunny.obj", 69451),
        ("horse.ply", 96966),
        ("spot.obj", 5856),
        ("homer.obj", 12000),
        ("cheburashka.obj", 13334),
        ("alligator.obj", 5981),
        ("woody.obj", 1267),
        ("cow.obj", 5804),
        ("teapot.obj", 6320),
        ("suzanne.obj", 968),
        ("beetle.obj", 2053),
        ("bunny-1m.ply", 1111216),
    ];
    let mut files: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| MeshFormat::from_path(p).is_ok())
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for path in files {
        let name = path.file_name().unwrap().to_str().unwrap().to_owned();
        let mesh = read_mesh(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        mesh.validate().unwrap();
        println!(
            "{name}: {} vertices, {} faces",
            mesh.vertex_count(),
            mesh.face_count()
        );
        assert!(mesh.vertex_count() >= 3 && mesh.face_count() >= 1, "{name}");
        if let Some(&(_, faces)) = known.iter().find(|(n, _)| *n == name) {
            let n = mesh.face_count();
            assert!(
                n >= faces && n <= faces + faces / 50 + 10,
                "{name}: {n} faces, expected about {faces}"
            );
        }
    }
}

/// Read speeds, for the record: `cargo test --release -p swm --lib
/// io::tests::read_speed -- --ignored --nocapture`.
#[test]
#[ignore = "timing; run in release"]
fn read_speed() {
    let Some(dir) = corpus() else { return };
    let ply = dir.join("bunny-1m.ply");
    let bytes = fs::read(&ply).unwrap();
    let mut mesh = TriMesh::default();
    let mut best = f64::MAX;
    for _ in 0..10 {
        let t = Instant::now();
        mesh = read_mesh(&ply).unwrap();
        best = best.min(t.elapsed().as_secs_f64());
    }
    let faces = mesh.face_count() as f64;
    println!(
        "bunny-1m.ply: read_mesh {:.1} ms ({:.1} M faces/s)",
        best * 1e3,
        faces / best / 1e6
    );
    let mut best = f64::MAX;
    for _ in 0..10 {
        let t = Instant::now();
        read(&bytes, MeshFormat::Ply).unwrap();
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!("bunny-1m.ply: from memory {:.1} ms", best * 1e3);

    for format in [MeshFormat::Obj, MeshFormat::Off] {
        let path = std::env::temp_dir().join(format!(
            "swm-bunny-1m-{}.{}",
            std::process::id(),
            format.name().to_lowercase()
        ));
        write_mesh(&path, &mesh).unwrap();
        let bytes = fs::read(&path).unwrap();
        let mut best = f64::MAX;
        for _ in 0..3 {
            let t = Instant::now();
            let back = read(&bytes, format).unwrap();
            best = best.min(t.elapsed().as_secs_f64());
            assert_eq!(back.triangles, mesh.triangles);
        }
        println!(
            "bunny-1m as {} ({} MB): {:.0} ms ({:.2} M faces/s)",
            format.name(),
            bytes.len() >> 20,
            best * 1e3,
            faces / best / 1e6
        );
        let _ = fs::remove_file(path);
    }
}

/// Random edits of valid files (byte changes, digit and sign swaps, cuts,
/// duplicated lines): every reader must return, never panic or hang.
#[test]
fn mutated_files_never_panic() {
    let mesh = awkward_mesh();
    let ascii_ply =
        b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty uchar y\n\
property double z\nelement face 2\nproperty list uchar int vertex_indices\nelement tristrips 1\n\
property list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3\n\
7 0 1 2 3 -1 1 2\n"
            .to_vec();
    let ascii_stl = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"
        .to_vec();
    let mut inputs = vec![(ascii_ply, MeshFormat::Ply), (ascii_stl, MeshFormat::Stl)];
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Off,
        MeshFormat::Stl,
    ] {
        let mut bytes = Vec::new();
        write_mesh_to(&mut bytes, format, &mesh).unwrap();
        inputs.push((bytes, format));
    }
    let noise = garbage(1 << 16, 99);
    let mut k = 0;
    let mut next = || {
        k = (k + 1) % noise.len();
        noise[k] as usize
    };
    let started = Instant::now();
    let (mut accepted, mut refused) = (0u32, 0u32);
    for (original, format) in &inputs {
        for _ in 0..1500 {
            let mut bytes = original.clone();
            for _ in 0..1 + next() % 4 {
                let at = (next() << 8 | next()) % bytes.len().max(1);
                match next() % 6 {
                    0 => bytes.truncate(at),
                    1 => {
                        if let Some(b) = bytes.get_mut(at) {
                            *b = next() as u8;
                        }
                    }
                    2 => bytes.insert(at.min(bytes.len()), b"-0123456789 \n/#e."[next() % 17]),
                    3 => {
                        let piece = bytes[at..]
                            .iter()
                            .take(1 + next() % 40)
                            .copied()
                            .collect::<Vec<_>>();
                        bytes.splice(at..at, piece);
                    }
                    4 => {
                        if let Some(b) = bytes.get_mut(at) {
                            *b ^= 1 << (next() % 8);
                        }
                    }
                    _ => {
                        if at < bytes.len() {
                            bytes.remove(at);
                        }
                    }
                }
            }
            // What a reader accepts is a mesh the library can work on:
            // finite positions, every index in range.
            match read(&bytes, *format) {
                Ok(mesh) => {
                    mesh.validate()
                        .unwrap_or_else(|e| panic!("{format:?}: read into an invalid mesh: {e}"));
                    accepted += 1;
                }
                Err(_) => refused += 1,
            }
        }
    }
    // Both sides of the readers' checks were reached.
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
    // A hang guard, generous so that a loaded machine passes.
    assert!(started.elapsed().as_secs() < 300);
}

/// What each reader reports as dropped, by what the file declares or
/// holds; STL's facet normals are not vertex attributes.
#[test]
fn readers_report_the_attributes_they_drop() {
    let dropped = |bytes: &[u8], format| {
        read_mesh_bytes_with_report(bytes, format, &Limits::default())
            .unwrap()
            .1
            .dropped
    };
    let none = Attributes::default();
    let with = |uv, normals, colors| Attributes {
        uv,
        normals,
        colors,
        generic: false,
    };
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let obj = |extra: &str| format!("{tri}{extra}f 1 2 3\n");
    for (text, expected) in [
        (obj(""), none),
        (obj("v 0 0 1 1\n"), none),
        (obj("vt 0 0\n"), with(true, false, false)),
        (obj("vn 0 0 1\nvt 0 1\n"), with(true, true, false)),
        (obj("v 0 0 1 0.5 0.5 0.5\n"), with(false, false, true)),
    ] {
        assert_eq!(
            dropped(text.as_bytes(), MeshFormat::Obj),
            expected,
            "{text}"
        );
    }

    let ply = |vertex: &str, face: &str, values: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\n{vertex}element face 1\nproperty list uchar int vertex_indices\n\
             {face}end_header\n0 0 0{values}\n1 0 0{values}\n0 1 0{values}\n3 0 1 2{}\n",
            if face.is_empty() { "" } else { " 0" }
        )
    };
    let normals = "property float nx\nproperty float ny\nproperty float nz\n";
    let colours = "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    let texcoord = "property list uchar float texcoord\n";
    for (text, expected) in [
        (ply("", "", ""), none),
        (ply(normals, "", " 0 0 1"), with(false, true, false)),
        (
            ply(&format!("{normals}{colours}"), "", " 0 0 1 9 9 9"),
            with(false, true, true),
        ),
        (
            ply("property float s\nproperty float t\n", "", " 0 0"),
            with(true, false, false),
        ),
        (ply("", texcoord, ""), with(true, false, false)),
    ] {
        assert_eq!(
            dropped(text.as_bytes(), MeshFormat::Ply),
            expected,
            "{text}"
        );
    }

    let body = "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    for (keyword, expected) in [
        ("OFF", none),
        ("NOFF", with(false, true, false)),
        ("COFF", with(false, false, true)),
        ("STCNOFF", with(true, true, true)),
    ] {
        let text = format!("{keyword}\n{body}");
        assert_eq!(
            dropped(text.as_bytes(), MeshFormat::Off),
            expected,
            "{keyword}"
        );
    }
    // Counts first, keyword left out: nothing is announced.
    assert_eq!(dropped(body.as_bytes(), MeshFormat::Off), none);

    let stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
               vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    assert_eq!(dropped(stl.as_bytes(), MeshFormat::Stl), none);
}
