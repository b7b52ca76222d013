//! The guard every command that writes a file runs first: an output
//! that names the input file is refused, since the command would
//! otherwise replace the original with its own result.

use crate::error::CliError;
use crate::pipe;
use std::path::Path;

/// Refuses to write `output` when it names the same file as `input`: the
/// output is written in full before it replaces anything, but a command
/// that replaced its own input would still destroy the original.
pub fn refuse_same_file(input: &Path, output: &Path) -> Result<(), CliError> {
    // `-` is a pipe, whatever a file named `-` may be.
    if !pipe::is_stdio(input) && !pipe::is_stdio(output) && same_file(input, output) {
        let e = std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "the output is the input file; refusing to overwrite it",
        );
        return Err(CliError::new(output, e));
    }
    Ok(())
}

/// Whether two paths name the same existing file: on Unix the same device
/// and inode, which sees through `./a.obj`, symbolic links and hard
/// links; elsewhere the same canonical path. An output that does not
/// exist yet cannot be the input.
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        }
    }
}
