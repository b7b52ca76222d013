//! No lost output: `swm encode`, `decode` and `sharpen` write through a
//! temporary file and a rename, so a failing run leaves neither a partial
//! output nor a temporary file behind, keeps an existing output as it
//! was, and a command never overwrites its own input.

mod common;
use common::*;
use std::path::{Path, PathBuf};

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Runs `swm args` and checks it fails with one error line naming `file`.
fn fails(args: &[&str], file: &Path) -> String {
    let out = swm(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(stderr.starts_with("swm: error:"), "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
    assert!(
        stderr.contains(s(file)),
        "{args:?}: does not name {file:?}: {stderr}"
    );
    stderr
}

/// A valid small mesh file and its `.swm` encoding in `dir`.
fn good_files(dir: &Path) -> (PathBuf, PathBuf) {
    let mesh = dir.join("good.obj");
    swm::io::write_mesh(&mesh, &swm_corpus::icosphere(1.0, 1)).unwrap();
    let swm_file = dir.join("good.swm");
    ok(&swm(&[
        "encode",
        s(&mesh),
        "-o",
        s(&swm_file),
        "--mode",
        "lossless",
    ]));
    (mesh, swm_file)
}

#[test]
fn failing_runs_leave_no_file_behind() {
    let dir = scratch("lost-none");
    let bad_mesh = write(&dir, "bad.obj", b"v 0 0 0\nf 1 2 3\n");
    let bad_swm = write(&dir, "bad.swm", b"SWM\0\x01\0 certainly not a valid file");
    let before = listing(&dir);
    fails(
        &["encode", s(&bad_mesh), "-o", s(&dir.join("out.swm"))],
        &bad_mesh,
    );
    fails(
        &[
            "encode",
            s(&bad_mesh),
            "-o",
            s(&dir.join("out.swm")),
            "--mode",
            "lossless",
        ],
        &bad_mesh,
    );
    fails(
        &["decode", s(&bad_swm), "-o", s(&dir.join("out.obj"))],
        &bad_swm,
    );
    fails(
        &["sharpen", s(&bad_mesh), "-o", s(&dir.join("out.ply"))],
        &bad_mesh,
    );
    assert_eq!(listing(&dir), before, "a failing run left a file behind");
}

#[test]
fn an_existing_output_survives_a_failure() {
    let dir = scratch("lost-existing");
    let (good_mesh, good_swm) = good_files(&dir);
    let bad_mesh = write(&dir, "bad.obj", b"v 0 0 0\nf 1 2 3\n");
    let mut damaged = std::fs::read(&good_swm).unwrap();
    let mid = damaged.len() / 2;
    damaged[mid] ^= 0x40;
    let bad_swm = write(&dir, "damaged.swm", &damaged);
    let old_swm = write(&dir, "old.swm", b"previous contents");
    let old_obj = write(&dir, "old.obj", b"# previous contents\n");
    let before = listing(&dir);
    fails(&["encode", s(&bad_mesh), "-o", s(&old_swm)], &bad_mesh);
    fails(&["decode", s(&bad_swm), "-o", s(&old_obj)], &bad_swm);
    fails(&["sharpen", s(&bad_mesh), "-o", s(&old_obj)], &bad_mesh);
    // A valid file refused by a limit: the failure comes after reading.
    fails(
        &[
            "decode",
            s(&good_swm),
            "-o",
            s(&old_obj),
            "--max-faces",
            "10",
        ],
        &good_swm,
    );
    assert_eq!(std::fs::read(&old_swm).unwrap(), b"previous contents");
    assert_eq!(std::fs::read(&old_obj).unwrap(), b"# previous contents\n");
    assert_eq!(listing(&dir), before);
    // And the same commands succeed on good input, replacing the file.
    ok(&swm(&[
        "decode",
        s(&good_swm),
        "-o",
        s(&old_obj),
        "--max-faces",
        "80",
    ]));
    assert!(swm::io::read_mesh(&old_obj).is_ok());
    let _ = good_mesh;
}

#[test]
fn the_output_may_not_be_the_input() {
    let dir = scratch("lost-same");
    let (mesh, swm_file) = good_files(&dir);
    let mesh_bytes = std::fs::read(&mesh).unwrap();
    let swm_bytes = std::fs::read(&swm_file).unwrap();
    // Spelled differently, so that only a comparison of the files (not of
    // the strings) catches it.
    let other_spelling = dir.join(".").join("good.obj");
    for (args, named) in [
        (vec!["sharpen", s(&mesh), "-o", s(&mesh)], &mesh),
        (
            vec!["sharpen", s(&mesh), "-o", s(&other_spelling)],
            &other_spelling,
        ),
        (vec!["encode", s(&mesh), "-o", s(&mesh)], &mesh),
        (vec!["decode", s(&swm_file), "-o", s(&swm_file)], &swm_file),
    ] {
        let stderr = fails(&args, named);
        assert!(stderr.contains("input"), "{args:?}: {stderr}");
    }
    assert_eq!(std::fs::read(&mesh).unwrap(), mesh_bytes);
    assert_eq!(std::fs::read(&swm_file).unwrap(), swm_bytes);
    assert_eq!(listing(&dir), ["good.obj", "good.swm"]);
}
