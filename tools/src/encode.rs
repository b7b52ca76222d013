//! `swm encode IN -o OUT.swm [--mode lossless] [--qp N] [--json]`.

use crate::CliError;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeArg {
    /// Keep the input's exact triangles; positions quantized to --qp bits.
    Lossless,
}

#[derive(clap::Args)]
pub struct Args {
    /// The mesh to encode (.obj, .ply, .off, .stl).
    input: PathBuf,
    /// The .swm file to write.
    #[arg(short, long)]
    output: PathBuf,
    /// The codec. (SwingWrapper, the planned default, is not released yet.)
    #[arg(long, value_enum, default_value = "lossless")]
    mode: ModeArg,
    /// Bits per coordinate in the lossless mode.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u8).range(6..=24))]
    qp: u8,
    /// Print statistics as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let mesh = swm::io::read_mesh(&args.input).map_err(|e| CliError::new(&args.input, e))?;
    let options = swm::EncodeOptions {
        mode: match args.mode {
            ModeArg::Lossless => swm::EncodeMode::Lossless { qp: args.qp },
        },
        ..Default::default()
    };
    let start = Instant::now();
    let encoded = swm::encode(&mesh, &options).map_err(|e| CliError::new(&args.input, e))?;
    let seconds = start.elapsed().as_secs_f64();
    swm::io::write_bytes(&args.output, &encoded.bytes)
        .map_err(|e| CliError::new(&args.output, e))?;
    let stats = crate::report::lossless_json(&encoded.stats.lossless, args.qp);
    if args.json {
        let mut v = stats;
        v["encode_seconds"] = seconds.into();
        v["cleaning"] = crate::report::clean_json(&encoded.stats.clean);
        crate::report::print_json(&v);
    } else {
        say!(
            "{} -> {}: {} bytes, {} vertices, {} triangles, {:.3} bits/triangle, {:.3} s",
            args.input.display(),
            args.output.display(),
            encoded.bytes.len(),
            encoded.stats.lossless.vertices,
            encoded.stats.lossless.triangles,
            8.0 * encoded.bytes.len() as f64 / encoded.stats.lossless.triangles.max(1) as f64,
            seconds
        );
    }
    Ok(())
}
