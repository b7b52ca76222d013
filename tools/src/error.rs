//! `CliError`: how every subcommand reports a failure, a file and what is
//! wrong with it, plus the exit status (1, or 2 for bad usage, clap's
//! convention). `main` prints it as one line, `swm: error: FILE: what`.
//!
//! It sits below every subcommand and imports none of them, so that the
//! subcommands and `main`, which dispatches to them, form no cycle.

use std::path::PathBuf;

/// A failure tied to the file it concerns.
pub struct CliError {
    pub(crate) path: PathBuf,
    pub(crate) error: swm::Error,
    /// The exit status: 1, or 2 for bad usage.
    pub(crate) code: u8,
}

impl CliError {
    /// Wraps a library error with the file it came from.
    pub fn new(path: impl Into<PathBuf>, error: impl Into<swm::Error>) -> Self {
        CliError {
            path: path.into(),
            error: error.into(),
            code: 1,
        }
    }

    /// A usage error about `path` found after parsing (such as an output
    /// extension no writer has): exit status 2, as clap's own.
    pub fn usage(path: impl Into<PathBuf>, error: impl Into<swm::Error>) -> Self {
        CliError {
            code: 2,
            ..CliError::new(path, error)
        }
    }
}

/// A failure the tool finds itself (not the library), said in words.
pub fn fail(path: impl Into<PathBuf>, what: impl Into<String>) -> CliError {
    CliError::new(path, std::io::Error::other(what.into()))
}
