//! Helpers shared by the end-to-end tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The shared reference corpus (`../shared/corpus` next to the repository),
/// or `None` after printing the skip notice the project promises.
pub fn shared_corpus() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus");
    if dir.join("README.md").is_file() {
        Some(dir)
    } else {
        println!("skipped: ../shared/corpus not found");
        None
    }
}

/// A fresh, empty scratch directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swm-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch directory");
    dir
}

/// Runs the `swm` binary built by this package.
pub fn swm(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .output()
        .expect("run swm")
}

/// Runs `swm` with its address space capped (in KiB), so that an attempt to
/// allocate what a lying header declares fails loudly instead of passing.
pub fn swm_capped(args: &[&str], max_kib: u64) -> Output {
    let mut script = format!("ulimit -v {max_kib}; exec \"$0\"");
    for i in 1..=args.len() {
        script.push_str(&format!(" \"${i}\""));
    }
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .output()
        .expect("run swm under ulimit")
}

/// Parses `swm ... --json` output, failing the test with stderr on error.
pub fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "swm failed: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON on stdout")
}

/// Meshes of the shared corpus that the README lists as manifold, with the
/// counts it gives: (file, vertices, faces, components, boundary loops, genus).
pub const MANIFOLD_CORPUS: &[(&str, u64, u64, u64, u64, i64)] = &[
    ("fandisk.obj", 6475, 12946, 1, 0, 0),
    ("stanford-bunny.obj", 35947, 69451, 1, 5, 0),
    ("horse.ply", 48485, 96966, 1, 0, 0),
    ("spot.obj", 2930, 5856, 1, 0, 0),
    ("homer.obj", 6002, 12000, 1, 0, 0),
    ("cheburashka.obj", 6669, 13334, 1, 0, 0),
    ("alligator.obj", 3208, 5981, 1, 1, 0),
    ("woody.obj", 694, 1267, 1, 1, 0),
    ("bunny-1m.ply", 557164, 1111216, 1, 5, 0),
];

/// The non-manifold meshes of the shared corpus: (file, vertices, faces).
pub const NON_MANIFOLD_CORPUS: &[(&str, u64, u64)] = &[
    ("cow.obj", 2903, 5804),
    ("teapot.obj", 3241, 6320),
    ("suzanne.obj", 505, 968),
    ("beetle.obj", 1148, 2053),
];
