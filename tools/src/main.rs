//! `swm`: the command-line face of the swm codec.
//!
//! Exit status: 0 on success, 1 when an input is bad or an operation
//! fails, 2 on bad usage (clap's convention): clap's own messages, the
//! value parsers of `args`, options of the other encoding mode, an
//! output extension no writer has, an `encode` output named like a mesh
//! file without `--force`, `-` (a pipe, see `pipe`) without
//! `--format`, and `render`'s output not named `.svg` or a bad `--view`.
//! Every other failure prints one line on stderr,
//! `swm: error: FILE: what is wrong`. SIGINT and SIGTERM exit
//! 130 and 143 after removing unfinished outputs (see `signals`).

/// `println!` that ignores a closed stdout (`swm info x | head`): the
/// reader has what it wanted, which is no reason to panic. On stderr
/// instead while stdout carries an output file (`-o -`, see `pipe`).
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        if $crate::pipe::reports_to_stderr() {
            let _ = writeln!(std::io::stderr(), $($t)*);
        } else {
            let _ = writeln!(std::io::stdout(), $($t)*);
        }
    }};
}

mod args;
mod decode;
mod distance;
mod encode;
mod fidelity;
mod info;
mod pipe;
mod progress;
mod rd;
mod render;
mod report;
mod sharpen;
mod signals;

use clap::{CommandFactory, Parser, Subcommand};
use std::path::{Path, PathBuf};
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
    /// Compress a mesh into a .swm file.
    Encode(encode::Args),
    /// Decompress a .swm file into a mesh file.
    Decode(decode::Args),
    /// Describe a mesh (topology, defects, size) or a .swm file (version,
    /// mode, counts, bytes and bits per triangle of each section, CLERS
    /// histogram).
    Info(info::Args),
    /// Measure the distance between two meshes (Metro-style L2, mean and
    /// Hausdorff, both one-sided values).
    Distance(distance::Args),
    /// Rate-distortion table: code meshes at several rates with every
    /// configuration, measure size and error; write CSV, Markdown and
    /// plots; or --check a committed table for regressions.
    Rd(rd::Args),
    /// Restore sharp edges and corners of any mesh (EdgeSharpener), then optionally subdivide (Bender).
    Sharpen(sharpen::Args),
    /// Draw a mesh or a .swm file as an SVG picture (flat-shaded
    /// triangles, orthographic view).
    Render(render::Args),
}

/// A failure tied to the file it concerns.
pub struct CliError {
    path: PathBuf,
    error: swm::Error,
    /// The exit status: 1, or 2 for bad usage.
    code: u8,
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    signals::install();
    // Checks clap's attributes cannot express, reported as clap reports
    // its own: usage on stderr, exit 2.
    if let Command::Encode(args) = &cli.command {
        if let Err(msg) = args.check_mode() {
            let mut cmd = Cli::command();
            // Built, so that the usage line says `swm encode`.
            cmd.build();
            let encode = cmd
                .find_subcommand_mut("encode")
                .expect("encode subcommand");
            encode
                .error(clap::error::ErrorKind::ArgumentConflict, msg)
                .exit();
        }
    }
    let result = match cli.command {
        Command::Encode(args) => encode::run(&args),
        Command::Decode(args) => decode::run(&args),
        Command::Info(args) => info::run(&args),
        Command::Distance(args) => distance::run(&args),
        Command::Rd(args) => rd::run(&args),
        Command::Sharpen(args) => sharpen::run(&args),
        Command::Render(args) => render::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One line, whatever the error says.
            let msg = e.error.to_string().replace('\n', " ");
            eprintln!("swm: error: {}: {msg}", e.path.display());
            ExitCode::from(e.code)
        }
    }
}
