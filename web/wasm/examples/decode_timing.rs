//! The native side of the browser benchmark (BENCHMARKS.md, "Web"):
//! decodes one `.swm` file as `web/test/browser.mjs --bench` does in the
//! page (default options, 10 warm-up decodes, then N timed ones) with the
//! same library build the module has (no default features), and prints
//! the figures as the same JSON keys.
//!
//! `cargo run --release -p swm-wasm --example decode_timing -- FILE.swm [N]`

use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let (Some(path), runs) = (args.next(), args.next()) else {
        eprintln!("usage: decode_timing FILE.swm [RUNS]");
        std::process::exit(2);
    };
    let runs: usize = match runs.as_deref().map(str::parse).unwrap_or(Ok(50)) {
        Ok(n) if n > 0 => n,
        _ => {
            eprintln!("decode_timing: RUNS must be a positive integer");
            std::process::exit(2);
        }
    };
    let bytes = std::fs::read(&path).unwrap_or_else(|e| {
        eprintln!("decode_timing: {path}: {e}");
        std::process::exit(1);
    });
    let options = swm::DecodeOptions::default();
    let decode = || {
        swm::decode(&bytes, &options).unwrap_or_else(|e| {
            eprintln!("decode_timing: {path}: {e}");
            std::process::exit(1);
        })
    };
    for _ in 0..10 {
        std::hint::black_box(decode());
    }
    let mut times = Vec::with_capacity(runs);
    let mut mesh = None;
    for _ in 0..runs {
        let start = Instant::now();
        mesh = Some(std::hint::black_box(decode()));
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    let mesh = mesh.expect("runs > 0");
    println!(
        "{{\"file\":\"{path}\",\"runs\":{runs},\"vertices\":{},\"triangles\":{},\"bytes\":{},\"min_ms\":{},\"median_ms\":{}}}",
        mesh.positions.len(),
        mesh.triangles.len(),
        bytes.len(),
        times[0],
        times[runs / 2]
    );
}
