//! Decoding speed of the entropy layer.
//!
//! * `clers-5x5`: 10M symbols of a 5-symbol model with the previous symbol
//!   as context, CLERS-like statistics (50% C, 40% R, 10% split over
//!   L/S/E) with the runs of a regular mesh (C and R alternate).
//! * `bytes-256`: 10M symbols of one 256-symbol model, a discretized
//!   Laplacian (like quantized residuals).
//! * `raw-bits`: 10M chunks of 12 raw bits.
//!
//! Throughput is reported in symbols per second (criterion "elements").
//!
//! ```sh
//! cargo bench -p swm --bench entropy
//! ```

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::entropy::{AdaptiveModel, ContextModel, Decoder, Encoder};

const N: usize = 10_000_000;

/// SplitMix64, so the bench needs no random-number crate.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// C = 0, L = 1, E = 2, R = 3, S = 4. Overall 50% C, 40% R, 10% L/S/E;
/// after a C an R is more likely and vice versa, as in a regular mesh.
fn clers_stream(rng: &mut Rng) -> Vec<u32> {
    let mut out = Vec::with_capacity(N);
    let mut prev = 0u32;
    for _ in 0..N {
        let u = rng.unit();
        let s = match prev {
            0 if u < 0.30 => 0,
            0 if u < 0.90 => 3,
            3 if u < 0.80 => 0,
            3 if u < 0.90 => 3,
            _ if u < 0.55 => 0,
            _ if u < 0.90 => 3,
            _ if u < 0.94 => 1,
            _ if u < 0.98 => 4,
            _ => 2,
        };
        out.push(s);
        prev = s;
    }
    out
}

fn laplace_stream(rng: &mut Rng) -> Vec<u32> {
    (0..N)
        .map(|_| {
            // Two-sided geometric around 128, scale ~12.
            let mag = (-(rng.unit().max(1e-12)).ln() * 12.0) as i32;
            let sign = if rng.next() & 1 == 0 { 1 } else { -1 };
            (128 + sign * mag).clamp(0, 255) as u32
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut rng = Rng(42);
    let mut group = c.benchmark_group("entropy-decode");
    group.sample_size(10);
    group.throughput(Throughput::Elements(N as u64));

    let clers = clers_stream(&mut rng);
    let mut enc = Encoder::new();
    let mut model = ContextModel::new(5, 5);
    let mut prev = 0usize;
    for &s in &clers {
        enc.encode(model.get(prev), s);
        prev = s as usize;
    }
    let bytes = enc.finish();
    eprintln!(
        "clers-5x5: {:.3} bits/symbol",
        bytes.len() as f64 * 8.0 / N as f64
    );
    group.bench_function("clers-5x5", |b| {
        b.iter(|| {
            let mut dec = Decoder::new(black_box(&bytes)).unwrap();
            let mut model = ContextModel::new(5, 5);
            let mut prev = 0usize;
            let mut sum = 0u32;
            for _ in 0..N {
                let s = dec.decode(model.get(prev)).unwrap();
                sum = sum.wrapping_add(s);
                prev = s as usize;
            }
            black_box(sum)
        })
    });

    let bytes256 = {
        let stream = laplace_stream(&mut rng);
        let mut enc = Encoder::new();
        let mut model = AdaptiveModel::new(256);
        for &s in &stream {
            enc.encode(&mut model, s);
        }
        enc.finish()
    };
    eprintln!(
        "bytes-256: {:.3} bits/symbol",
        bytes256.len() as f64 * 8.0 / N as f64
    );
    group.bench_function("bytes-256", |b| {
        b.iter(|| {
            let mut dec = Decoder::new(black_box(&bytes256)).unwrap();
            let mut model = AdaptiveModel::new(256);
            let mut sum = 0u32;
            for _ in 0..N {
                sum = sum.wrapping_add(dec.decode(&mut model).unwrap());
            }
            black_box(sum)
        })
    });

    let raw = {
        let mut enc = Encoder::new();
        for _ in 0..N {
            enc.encode_bits(rng.next() as u32 & 0xFFF, 12);
        }
        enc.finish()
    };
    group.bench_function("raw-bits-12", |b| {
        b.iter(|| {
            let mut dec = Decoder::new(black_box(&raw)).unwrap();
            let mut sum = 0u32;
            for _ in 0..N {
                sum = sum.wrapping_add(dec.decode_bits(12).unwrap());
            }
            black_box(sum)
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
