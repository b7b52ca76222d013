//! Where a mesh of an rd table comes from, and how a table names it.
//!
//! A table outlives the machine that wrote it: `--check` runs on a fresh
//! clone, in CI, from any working directory. So the `mesh` column never
//! holds a path that only made sense where the table was written:
//!
//! * `generated:NAME` — a mesh of the project's own corpus, rebuilt in
//!   memory by `swm_corpus::by_name` (no file needed);
//! * `shared:FILE` — a file of the shared reference corpus, found in
//!   `$SWM_SHARED_CORPUS` if set, else in the `shared/corpus` folder of the
//!   nearest ancestor of the table's folder (or of the current folder) that
//!   has one: `../shared/corpus` beside the repository, as the project lays
//!   it out;
//! * anything else — a file path, stored relative to the table's folder so
//!   that table and meshes can move together.
//!
//! The same three spellings are accepted on the command line.

use crate::error::fail;
use crate::error::CliError;
use std::path::{Component, Path, PathBuf};

const GENERATED: &str = "generated:";
const SHARED: &str = "shared:";

/// Environment variable that overrides the search for the shared corpus.
pub const SHARED_ENV: &str = "SWM_SHARED_CORPUS";

/// A mesh as the user or a table names it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Source {
    /// A mesh of `swm_corpus`, by name.
    Generated(String),
    /// A file of the shared corpus, by file name.
    Shared(String),
    /// Any mesh file.
    File(PathBuf),
}

impl Source {
    /// Parses a command-line argument; paths are taken as given.
    pub fn from_arg(arg: &str) -> Source {
        if let Some(name) = arg.strip_prefix(GENERATED) {
            Source::Generated(name.to_string())
        } else if let Some(file) = arg.strip_prefix(SHARED) {
            Source::Shared(file.to_string())
        } else {
            Source::File(PathBuf::from(arg))
        }
    }

    /// Parses a table's `mesh` column; relative paths are relative to the
    /// table's folder.
    pub fn from_table(cell: &str, table_dir: &Path) -> Source {
        match Source::from_arg(cell) {
            Source::File(p) if p.is_relative() => Source::File(table_dir.join(p)),
            other => other,
        }
    }

    /// How a table written into `table_dir` names this mesh.
    pub fn table_name(&self, table_dir: &Path) -> String {
        match self {
            Source::Generated(name) => format!("{GENERATED}{name}"),
            Source::Shared(file) => format!("{SHARED}{file}"),
            Source::File(path) => relative_to(path, table_dir)
                .unwrap_or_else(|| path.clone())
                .to_string_lossy()
                .replace('\\', "/"),
        }
    }

    /// A short name for plots, file names and `--only`: the generator's
    /// name or the file's stem.
    pub fn short_name(&self) -> String {
        match self {
            Source::Generated(name) => name.clone(),
            Source::Shared(file) => stem(Path::new(file)),
            Source::File(path) => stem(path),
        }
    }

    /// What error messages call this mesh.
    pub fn label(&self) -> PathBuf {
        match self {
            Source::Generated(name) => PathBuf::from(format!("{GENERATED}{name}")),
            Source::Shared(file) => PathBuf::from(format!("{SHARED}{file}")),
            Source::File(path) => path.clone(),
        }
    }

    /// Builds or reads the mesh. `base` is where the search for the shared
    /// corpus starts (the table's folder when checking a table).
    pub fn load(&self, base: Option<&Path>) -> Result<swm::TriMesh, CliError> {
        match self {
            Source::Generated(name) => swm_corpus::by_name(name).ok_or_else(|| {
                fail(
                    self.label(),
                    format!(
                        "no such generated mesh (known: {})",
                        swm_corpus::NAMES.join(", ")
                    ),
                )
            }),
            Source::Shared(file) => {
                let dir = shared_corpus(base).ok_or_else(|| {
                    fail(
                        self.label(),
                        format!(
                            "the shared corpus was not found (set {SHARED_ENV}, or place it at ../shared/corpus beside the repository)"
                        ),
                    )
                })?;
                let path = dir.join(file);
                swm::io::read_mesh(&path).map_err(|e| CliError::new(path, e))
            }
            Source::File(path) => swm::io::read_mesh(path).map_err(|e| CliError::new(path, e)),
        }
    }
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.to_string_lossy().into_owned())
}

/// The shared corpus folder: `$SWM_SHARED_CORPUS`, else `A/shared/corpus`
/// for the nearest ancestor `A` of `base` (then of the current folder).
pub fn shared_corpus(base: Option<&Path>) -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os(SHARED_ENV) {
        return Some(PathBuf::from(dir));
    }
    let cwd = std::env::current_dir().ok();
    let starts = base.into_iter().chain(cwd.as_deref());
    for start in starts {
        let Ok(start) = start.canonicalize() else {
            continue;
        };
        if let Some(found) = start
            .ancestors()
            .map(|a| a.join("shared").join("corpus"))
            .find(|d| d.is_dir())
        {
            return Some(found);
        }
    }
    None
}

/// `path` relative to the folder `base`, when both exist on disk.
fn relative_to(path: &Path, base: &Path) -> Option<PathBuf> {
    let path = path.canonicalize().ok()?;
    let base = base.canonicalize().ok()?;
    let p: Vec<Component> = path.components().collect();
    let b: Vec<Component> = base.components().collect();
    // Different roots (Windows drives) have no relative path.
    if p.first() != b.first() {
        return None;
    }
    let common = p.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut rel = PathBuf::new();
    for _ in common..b.len() {
        rel.push("..");
    }
    for c in &p[common..] {
        rel.push(c);
    }
    Some(rel)
}
