//! `swm`: the command-line face of the swm codec.
//!
//! Exit status: 0 on success, 1 when an input is bad or an operation
//! fails, 2 on bad usage (clap's convention). Every failure prints one line
//! on stderr, `swm: error: FILE: what is wrong`.

mod info;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "swm",
    version,
    about = "Lossy triangle-mesh compression by SwingWrapper remeshing"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the topology and size of a mesh: vertices, faces, components,
    /// boundary loops, genus, defects found by cleaning, bounding box, area.
    Info(info::Args),
}

/// A failure tied to the file it concerns.
pub struct CliError {
    path: PathBuf,
    error: swm::Error,
}

impl CliError {
    /// Wraps a library error with the file it came from.
    pub fn new(path: impl Into<PathBuf>, error: impl Into<swm::Error>) -> Self {
        CliError {
            path: path.into(),
            error: error.into(),
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(args) => info::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One line, whatever the error says.
            let msg = e.error.to_string().replace('\n', " ");
            eprintln!("swm: error: {}: {msg}", e.path.display());
            ExitCode::from(1)
        }
    }
}
