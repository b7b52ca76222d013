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
mod error;
mod fidelity;
mod info;
mod pipe;
mod progress;
mod rd;
mod render;
mod report;
mod same_file;
mod scene;
mod sharpen;
mod signals;

use clap::{CommandFactory, Parser, Subcommand};
// `encode` still names it `crate::refuse_same_file`; the other commands
// name its module.
use same_file::refuse_same_file;
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
    /// histogram; a displaced file's levels, steps and bends).
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
        // A glTF input to a .glb or .gltf output is a whole scene.
        Command::Encode(args) => match scene::scene_output(&args) {
            Some(format) => scene::encode(&args, format),
            None => encode::run(&args),
        },
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

#[cfg(test)]
mod tests {
    use super::Cli;
    use crate::fidelity::{MAX_HAUSDORFF, MIN_AREA_RATIO};

    /// `encode --help` and the README state the thresholds and the
    /// sample count in words: they follow the constants. (Here rather
    /// than in `fidelity`, which would otherwise import `main`'s `Cli`
    /// while `main` imports it: a cycle.)
    #[test]
    fn the_help_and_the_readme_state_the_thresholds() {
        use clap::CommandFactory as _;
        let mut cli = Cli::command();
        let encode = cli.find_subcommand_mut("encode").expect("encode");
        let help = encode.render_long_help().to_string();
        let readme = include_str!("../../README.md");
        let readme = readme.split_whitespace().collect::<Vec<_>>().join(" ");
        let area = format!("under {:.0}% of the input's", 100.0 * MIN_AREA_RATIO);
        let far = format!("over {:.0}% of the", 100.0 * MAX_HAUSDORFF);
        assert_eq!(swm::CHECK_SAMPLES, 60_000, "the texts say 60,000");
        for text in [&help, &readme] {
            assert!(text.contains(&area), "{area}");
            assert!(text.contains(&far), "{far}");
            assert!(text.contains("60,000 of Metro's samples"));
        }
    }
}
