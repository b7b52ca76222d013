//! The smallest useful decoder program: `.swm` in, Wavefront OBJ out,
//! built from the decoder alone (no encoder, no mesh readers, no CLI
//! crates). It is what BENCHMARKS.md's size figures measure:
//!
//! ```sh
//! cargo build -p swm --example decode_only --no-default-features --features std --release
//! ```
//!
//! Usage: `decode_only IN.swm OUT.obj`. Like the `swm` tool, it writes to
//! a temporary file beside the output and renames it, so a failure leaves
//! no partial file.

use std::io::{BufWriter, Write};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let [_, input, output] = &args[..] else {
        eprintln!("usage: decode_only IN.swm OUT.obj");
        return ExitCode::from(2);
    };
    match run(input, output) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("decode_only: error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(input: &str, output: &str) -> Result<(), String> {
    let bytes = std::fs::read(input).map_err(|e| format!("{input}: {e}"))?;
    let mesh =
        swm::decode(&bytes, &swm::DecodeOptions::default()).map_err(|e| format!("{input}: {e}"))?;
    let temp = format!("{output}.part");
    let written = (|| {
        let mut w = BufWriter::new(std::fs::File::create(&temp)?);
        for p in &mesh.positions {
            writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
        }
        for t in &mesh.triangles {
            writeln!(w, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
        }
        w.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        std::fs::rename(&temp, output)
    })();
    written.map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        format!("{output}: {e}")
    })
}
