//! Speed of the decoder's Sharpen&Bend (issue 7 targets, one core,
//! release build): EdgeSharpener at ≥ 5 M input triangles/s, Bender at
//! ≥ 5 M output triangles/s per step (the thesis's took 22,000/s).
//!
//! Inputs are what the decoder hands them: SwingWrapper decodes, whose
//! chamfers EdgeSharpener has to find and cut.
//! * `post-sharpen`: `sharpen` on fandisk (a CAD part: many chamfers) and
//!   horse (a smooth scan: few), each encoded at 8 b/v, and on bunny-1m
//!   at 2 b/v (about 1 M retiled triangles); input triangles/s.
//! * `post-bend`: one Bender step on the sharpened meshes with their
//!   tags; output triangles/s.
//!
//! Run: `cargo bench -p swm --bench post`. Needs `../shared/corpus`.

mod common;
use common::corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::{DecodeOptions, EncodeMode, EncodeOptions, Limits, SwingTarget, TriMesh};

/// The SwingWrapper decode of `name` at `bpv` bits per input vertex,
/// plain (whatever post-processing its hint asks: that is what is timed).
fn decoded(dir: &std::path::Path, name: &str, bpv: f64) -> TriMesh {
    let mesh = swm::io::read_mesh(&dir.join(name)).expect("corpus mesh");
    let options = EncodeOptions {
        mode: EncodeMode::Swing {
            target: SwingTarget::BitsPerVertex(bpv),
            angle_bits: Some(8),
            max_bytes: None,
        },
        ..Default::default()
    };
    let encoded = swm::encode(&mesh, &options).expect("encodes");
    swm::decode(&encoded.bytes, &DecodeOptions::plain()).expect("decodes")
}

fn post(c: &mut Criterion) {
    let Some(dir) = corpus() else {
        return;
    };
    let inputs = [
        ("fandisk-8bpv", decoded(&dir, "fandisk.obj", 8.0)),
        ("horse-8bpv", decoded(&dir, "horse.ply", 8.0)),
        ("bunny-1m-2bpv", decoded(&dir, "bunny-1m.ply", 2.0)),
    ];
    let options = swm::SharpenOptions::default();
    let mut g = c.benchmark_group("post-sharpen");
    g.sample_size(10);
    for (name, mesh) in &inputs {
        g.throughput(Throughput::Elements(mesh.face_count() as u64));
        g.bench_function(*name, |b| {
            b.iter(|| swm::sharpen(black_box(mesh), &options).expect("sharpens"))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("post-bend");
    g.sample_size(10);
    let limits = Limits::UNLIMITED;
    for (name, mesh) in &inputs {
        let s = swm::sharpen(mesh, &options).expect("sharpens");
        g.throughput(Throughput::Elements(4 * s.mesh.face_count() as u64));
        g.bench_function(*name, |b| {
            b.iter(|| swm::bend(black_box(&s.mesh), &s.sharp, 1, &limits).expect("bends"))
        });
    }
    g.finish();
}

criterion_group!(benches, post);
criterion_main!(benches);
