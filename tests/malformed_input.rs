//! Malformed mesh files: each gives one line on stderr starting
//! `swm: error:` that names the file, exit status 1, no panic, and no
//! allocation sized by a lying header (the run is address-space capped).

mod common;
use common::*;
use std::path::Path;

/// 1 GiB of address space: plenty for these tiny inputs, far too little for
/// the billions of elements their headers claim.
const CAP_KIB: u64 = 1 << 20;

fn assert_clean_error(path: &Path, what: &str) {
    let p = path.to_str().unwrap();
    let out = swm_capped(&["info", p], CAP_KIB);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{what}: exit status {:?}, stderr: {stderr}",
        out.status
    );
    assert!(stderr.starts_with("swm: error:"), "{what}: {stderr}");
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "{what}: not one line: {stderr}"
    );
    assert!(
        stderr.contains(p),
        "{what}: the message does not name the file: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{what}: {stderr}");
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A valid binary PLY of a small generated mesh.
fn good_ply(dir: &Path) -> Vec<u8> {
    let path = dir.join("good.ply");
    swm::io::write_mesh(&path, &swm_corpus::icosphere(1.0, 1)).unwrap();
    std::fs::read(path).unwrap()
}

#[test]
fn empty_files() {
    let dir = scratch("empty");
    for ext in ["obj", "ply", "off", "stl"] {
        assert_clean_error(&write(&dir, &format!("empty.{ext}"), b""), ext);
        assert_clean_error(&write(&dir, &format!("blank.{ext}"), b"\n\n  \n"), ext);
    }
}

#[test]
fn truncated_files() {
    let dir = scratch("truncated");
    let ply = good_ply(&dir);
    let header_end = ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    for cut in [
        5,
        header_end - 3,
        header_end + 7,
        (header_end + ply.len()) / 2,
        ply.len() - 1,
    ] {
        assert_clean_error(
            &write(&dir, &format!("cut{cut}.ply"), &ply[..cut]),
            &format!("PLY cut at {cut}"),
        );
    }
    // Binary STL: header says 10 triangles, only 3 follow.
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&10u32.to_le_bytes());
    stl.extend(std::iter::repeat_n(0u8, 3 * 50));
    assert_clean_error(&write(&dir, "cut.stl", &stl), "STL");
    assert_clean_error(
        &write(&dir, "cut.off", b"OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n"),
        "OFF",
    );
}

#[test]
fn garbage_bytes() {
    let dir = scratch("garbage");
    // A fixed pseudo-random byte string (xorshift), so the test is repeatable.
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let bytes: Vec<u8> = (0..4096)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as u8
        })
        .collect();
    for ext in ["obj", "ply", "off", "stl"] {
        assert_clean_error(&write(&dir, &format!("garbage.{ext}"), &bytes), ext);
    }
    let mut ply = b"ply\nformat binary_little_endian 1.0\n".to_vec();
    ply.extend_from_slice(&bytes);
    assert_clean_error(
        &write(&dir, "garbage-header.ply", &ply),
        "PLY with a garbage header",
    );
}

#[test]
fn header_counts_larger_than_the_file() {
    let dir = scratch("counts");
    let ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n\
property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
\0\0\0\0\0\0\0\0\0\0\0\0";
    assert_clean_error(&write(&dir, "huge.ply", ply), "PLY with 2 billion vertices");
    let ascii = b"ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n\
property float z\nelement face 2000000000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n";
    assert_clean_error(
        &write(&dir, "huge-ascii.ply", ascii),
        "ASCII PLY with 2 billion vertices",
    );
    assert_clean_error(
        &write(&dir, "huge.off", b"OFF\n2000000000 2000000000 0\n0 0 0\n"),
        "OFF",
    );
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&u32::MAX.to_le_bytes());
    stl.extend(std::iter::repeat_n(0u8, 50));
    assert_clean_error(
        &write(&dir, "huge.stl", &stl),
        "STL with 4 billion triangles",
    );
}

#[test]
fn face_indices_out_of_range() {
    let dir = scratch("indices");
    assert_clean_error(
        &write(&dir, "a.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n"),
        "OBJ",
    );
    assert_clean_error(
        &write(&dir, "b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n"),
        "OBJ negative",
    );
    assert_clean_error(
        &write(&dir, "a.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
        "OFF",
    );
    let ply = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n";
    assert_clean_error(&write(&dir, "a.ply", ply), "PLY");
    let mut bin = good_ply(&dir);
    let n = bin.len();
    bin[n - 4..].copy_from_slice(&1_000_000i32.to_le_bytes()); // last index of the last face
    assert_clean_error(&write(&dir, "b.ply", &bin), "binary PLY");
}

#[test]
fn non_finite_coordinates() {
    let dir = scratch("nan");
    assert_clean_error(
        &write(&dir, "nan.obj", b"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        "OBJ NaN",
    );
    assert_clean_error(
        &write(&dir, "inf.obj", b"v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n"),
        "OBJ inf",
    );
    assert_clean_error(
        &write(&dir, "big.obj", b"v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n"),
        "OBJ f32 overflow",
    );
    assert_clean_error(
        &write(
            &dir,
            "nan.off",
            b"OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n",
        ),
        "OFF NaN",
    );
    let mut bin = good_ply(&dir);
    let header_end = bin.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    bin[header_end..header_end + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    assert_clean_error(&write(&dir, "nan.ply", &bin), "binary PLY NaN");
}

#[test]
fn missing_files_and_unknown_formats() {
    let dir = scratch("missing");
    assert_clean_error(&dir.join("does-not-exist.obj"), "missing file");
    assert_clean_error(&write(&dir, "mesh.xyz", b"v 0 0 0\n"), "unknown extension");
    let sub = dir.join("a-directory.obj");
    std::fs::create_dir_all(&sub).unwrap();
    assert_clean_error(&sub, "a directory");
}

/// Issue 18: bytes that are not text get the right reason, not "empty":
/// UTF-16 (with or without a byte-order mark) and binary data (a `.swm`
/// file named `.obj`).
#[test]
fn undecodable_text_says_why() {
    let dir = scratch("not-text");
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let utf16 = |text: &str, bom: &[u8], le: bool| -> Vec<u8> {
        let mut b = bom.to_vec();
        for c in text.bytes() {
            b.extend(if le { [c, 0] } else { [0, c] });
        }
        b
    };
    let swm_bytes = samples()[0].bytes.clone();
    for (name, bytes, reason) in [
        (
            "le.obj",
            utf16(obj, &[0xFF, 0xFE], true),
            "UTF-16 text is not supported; save the file as UTF-8",
        ),
        ("be.obj", utf16(obj, &[0xFE, 0xFF], false), "UTF-16"),
        ("nobom.obj", utf16(obj, &[], true), "UTF-16"),
        ("le.off", utf16(off, &[0xFF, 0xFE], true), "UTF-16"),
        ("swm.obj", swm_bytes.clone(), "binary data, not a text file"),
        ("swm.off", swm_bytes, "binary data"),
    ] {
        let path = write(&dir, name, &bytes);
        assert_clean_error(&path, name);
        let err =
            String::from_utf8_lossy(&swm(&["info", path.to_str().unwrap()]).stderr).into_owned();
        assert!(err.contains(reason), "{name}: {err}");
        assert!(!err.contains("empty"), "{name}: {err}");
    }
}

/// Issue 18: OBJ index errors quote the index as written in the file.
#[test]
fn obj_index_errors_quote_the_file() {
    let dir = scratch("obj-index");
    let v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (face, expected) in [
        (
            "f 0 1 2",
            "vertex index 0 is invalid: OBJ indices start at 1",
        ),
        (
            "f -1 -2 -4",
            "vertex index -4 is out of range (the mesh has 3 vertices)",
        ),
        ("f 1 2 4", "vertex index 4 is out of range"),
        ("f 1/1 2/2 7/7", "vertex index 7 is out of range"),
    ] {
        let path = write(&dir, "f.obj", format!("{v}{face}\n").as_bytes());
        assert_clean_error(&path, face);
        let err =
            String::from_utf8_lossy(&swm(&["info", path.to_str().unwrap()]).stderr).into_owned();
        assert!(
            err.contains("at line 4") && err.contains(expected),
            "{face}: {err}"
        );
    }
}

#[test]
fn usage_errors_exit_2() {
    let out = swm(&["info"]);
    assert_eq!(out.status.code(), Some(2));
    let out = swm(&["frobnicate"]);
    assert_eq!(out.status.code(), Some(2));
    // An output format swm does not write is refused before any work.
    let dir = scratch("usage");
    let input = dir.join("in.swm");
    std::fs::write(&input, &samples()[0].bytes).unwrap();
    let mesh = write(&dir, "in.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    for args in [
        ["decode", input.to_str().unwrap(), "-o", "out.xyz"],
        ["decode", input.to_str().unwrap(), "-o", "no-extension"],
        ["sharpen", mesh.to_str().unwrap(), "-o", "out.swm"],
    ] {
        let out = swm(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("unknown mesh format (expected .obj"),
            "{args:?}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
}

/// Every fuzz target (`fuzz/fuzz_targets/*.rs`) starts from committed
/// seeds (`fuzz/seeds/<target>/`, issue 48: a run of the glTF reader's
/// target from nothing stayed shallow), and the mesh readers' seeds are
/// files their reader accepts, so that mutations start from inside it.
#[test]
fn every_fuzz_target_has_seeds_its_reader_accepts() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz");
    let mut targets = 0;
    for entry in std::fs::read_dir(fuzz.join("fuzz_targets")).unwrap() {
        let path = entry.unwrap().path();
        let Some(name) = path.file_stem().and_then(|s| s.to_str()) else {
            continue;
        };
        targets += 1;
        let seeds = fuzz.join("seeds").join(name);
        let files: Vec<_> = std::fs::read_dir(&seeds)
            .unwrap_or_else(|e| panic!("{}: {e}", seeds.display()))
            .map(|e| e.unwrap().path())
            .collect();
        assert!(!files.is_empty(), "{name}: no seeds in {}", seeds.display());
        let format = match name {
            "read_obj" => swm::io::MeshFormat::Obj,
            "read_ply" => swm::io::MeshFormat::Ply,
            "read_off" => swm::io::MeshFormat::Off,
            "read_stl" => swm::io::MeshFormat::Stl,
            // GLB or glTF JSON: the reader tells them apart by the magic.
            "read_gltf" => swm::io::MeshFormat::Glb,
            _ => continue,
        };
        for file in &files {
            let bytes = std::fs::read(file).unwrap();
            let mesh = swm::io::read_mesh_bytes(&bytes, format, &swm::Limits::default())
                .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            assert!(!mesh.triangles.is_empty(), "{}", file.display());
        }
    }
    assert!(targets >= 10, "{targets} fuzz targets");
}
