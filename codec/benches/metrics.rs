//! Speed of the surface distance (issue 4 target: ≥ 2 million samples/s
//! against a 1-million-face reference, on one core).
//!
//! Groups:
//! * `distance/one-core`: one direction, 1,000,000 area-uniform samples on
//!   `stanford-bunny.obj` measured against `bunny-1m.ply` (1.1 M faces),
//!   in a one-thread pool; throughput in samples per second;
//! * `distance/prepare`: building the nearest-point hierarchy of bunny-1m;
//! * `distance/all-cores`: the whole symmetric Metro-default distance
//!   between the two meshes on every core.
//!
//! Run: `cargo bench -p swm --bench metrics`. Needs `../shared/corpus`.

mod common;
use common::corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::metrics::{distance_between, one_sided, DistanceOptions, Surface};

fn bench(c: &mut Criterion) {
    let Some(dir) = corpus() else { return };
    let big = swm::io::read_mesh(&dir.join("bunny-1m.ply")).expect("read bunny-1m");
    let small = swm::io::read_mesh(&dir.join("stanford-bunny.obj")).expect("read bunny");
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let reference = one.install(|| Surface::new(&big).unwrap());
    let samples = Surface::new(&small).unwrap();
    const N: u64 = 1_000_000;
    let options = DistanceOptions::area_uniform(N);

    let mut g = c.benchmark_group("distance");
    g.sample_size(10);
    g.throughput(Throughput::Elements(N));
    g.bench_function("one-core", |b| {
        b.iter(|| one.install(|| black_box(one_sided(&samples, &reference, N, &options))))
    });
    g.throughput(Throughput::Elements(big.face_count() as u64));
    g.bench_function("prepare", |b| {
        b.iter(|| one.install(|| black_box(Surface::new(&big).unwrap())))
    });
    g.throughput(Throughput::Elements(big.face_count() as u64));
    g.bench_function("all-cores", |b| {
        b.iter(|| {
            black_box(distance_between(&reference, &samples, &DistanceOptions::default()).unwrap())
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
