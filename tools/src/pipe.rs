//! `-` as a file name: standard input for `encode` and `decode` inputs,
//! standard output for their outputs, with `--format` naming the mesh
//! format that no extension gives.
//!
//! Invariants:
//! - standard input is read within the same byte bound as a file
//!   ([`swm::Limits::max_input_bytes`]): one byte past it and the read
//!   stops and is refused, so `swm encode - < /dev/zero` ends;
//! - standard output gets the data in one write once it is complete (a
//!   failed encode or decode writes nothing there); no temporary file is
//!   involved, as there is nothing to rename over;
//! - while standard output carries data, the reports that normally go
//!   there (text and `--json`) go to standard error instead, so that the
//!   bytes on standard output are the file and nothing else.

use crate::error::CliError;
use std::io::{Read, Write};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether `say!` writes to standard error (see [`data_on_stdout`]).
static REPORTS_TO_STDERR: AtomicBool = AtomicBool::new(false);

/// Whether `path` is `-`, standard input or output.
pub fn is_stdio(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// Sends the reports (`say!`) to standard error from now on, when
/// `output` is standard output: set once by a command before it prints.
pub fn data_on_stdout(output: &Path) {
    if is_stdio(output) {
        REPORTS_TO_STDERR.store(true, Ordering::Relaxed);
    }
}

/// Where `say!` writes: false for standard output.
pub fn reports_to_stderr() -> bool {
    REPORTS_TO_STDERR.load(Ordering::Relaxed)
}

/// The `--format` values: a mesh format by its extension.
pub fn parse_format(s: &str) -> Result<swm::io::MeshFormat, String> {
    swm::io::MeshFormat::from_name(s.trim())
        .map_err(|_| "expected obj, ply, off, stl, glb or gltf".into())
}

/// The format of the mesh file `path` to read: `--format` if given, else
/// the extension (an unknown one is a bad input, exit 1, as before pipes
/// came); standard input without `--format` is a usage error.
pub fn input_format(
    path: &Path,
    format: Option<swm::io::MeshFormat>,
) -> Result<swm::io::MeshFormat, CliError> {
    match (format, is_stdio(path)) {
        (Some(f), _) => Ok(f),
        (None, true) => Err(needs_format(path)),
        (None, false) => swm::io::MeshFormat::from_path(path).map_err(|e| CliError::new(path, e)),
    }
}

/// The format of the mesh file `path` to write: `--format` if given,
/// else the extension; a format no writer has, or standard output
/// without `--format`, is a usage error (exit 2), before any work.
pub fn output_format(
    path: &Path,
    format: Option<swm::io::MeshFormat>,
) -> Result<swm::io::MeshFormat, CliError> {
    let format = match (format, is_stdio(path)) {
        (Some(f), _) => f,
        (None, true) => return Err(needs_format(path)),
        (None, false) => {
            swm::io::MeshFormat::from_path(path).map_err(|e| CliError::usage(path, e))?
        }
    };
    if !format.is_writable() {
        let e = swm::ParameterError::ReadOnly {
            format: format.name(),
        };
        return Err(CliError::usage(path, e));
    }
    Ok(format)
}

fn needs_format(path: &Path) -> CliError {
    let e = std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        "a mesh on standard input or output needs --format (obj, ply, off, stl, glb or gltf)",
    );
    CliError::usage(path, e)
}

/// All of standard input, refused once it holds more than `limit` bytes.
pub fn read_stdin(limit: u64) -> Result<Vec<u8>, swm::Error> {
    let mut bytes = Vec::new();
    std::io::stdin()
        .lock()
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)?;
    let read = bytes.len() as u64;
    if read > limit {
        return Err(swm::Error::LimitExceeded(swm::LimitError {
            what: swm::Limited::InputBytes,
            requested: read,
            limit,
        }));
    }
    Ok(bytes)
}

/// Writes the complete output `bytes` to standard output.
pub fn write_stdout(bytes: &[u8]) -> Result<(), swm::Error> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)?;
    out.flush()?;
    Ok(())
}

/// Writes `bytes` (a `.swm` file) to `path`, or to standard output for `-`.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), swm::Error> {
    if is_stdio(path) {
        write_stdout(bytes)
    } else {
        swm::io::write_bytes(path, bytes)
    }
}

/// Reads the mesh `path` names (standard input for `-`) in `format`,
/// within the default limits, with the report of what it dropped.
/// [`read_mesh`] with the input's attribute streams.
pub fn read_attributed_mesh(
    path: &Path,
    format: swm::io::MeshFormat,
) -> Result<(swm::AttributedMesh, swm::io::ReadReport), CliError> {
    let limits = swm::Limits::default();
    let err = |e| CliError::new(path, e);
    if is_stdio(path) {
        let bytes = read_stdin(limits.max_input_bytes).map_err(err)?;
        return swm::io::read_attributed_mesh_bytes(&bytes, format, &limits).map_err(err);
    }
    swm::io::read_attributed_mesh_with(path, Some(format), &limits).map_err(err)
}
