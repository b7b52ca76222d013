//! What the benches share: where the reference corpus is.

use std::path::PathBuf;

/// `../shared/corpus` next to the repository, or `None` after printing the
/// skip notice the project promises.
pub fn corpus() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus");
    if dir.join("bunny-1m.ply").is_file() {
        Some(dir)
    } else {
        eprintln!("skipped: ../shared/corpus not found");
        None
    }
}
