//! Speed of the displaced-subdivision decoder (mode 2, issue 46 item 5:
//! ≥ 30 M output triangles/s on one core into caller buffers).
//!
//! Groups, for `stanford-bunny.obj` encoded once with
//! `EncodeMode::Displaced` at 2 and 8 bits per vertex:
//! * `displaced-decode/bunny-<R>bpv/owned`: `swm::decode` into a new
//!   `TriMesh`;
//! * `displaced-decode/bunny-<R>bpv/into`: `swm::decode_into_with` into
//!   buffers sized once by `decoded_len`;
//! * `displaced-decode/bunny-<R>bpv/base-only`: the same file cut to no
//!   level (`swm::cut_levels(_, 0)`): the base's lossless decode and the
//!   container, the part the levels do not touch.
//!
//! Throughput is in output triangles of the whole file per second
//! (criterion "elements"; `base-only` too, so the gap to the others is
//! the levels' share). Run single-threaded:
//! `RAYON_NUM_THREADS=1 cargo bench -p swm --bench displaced`. Needs
//! `../shared/corpus`.

mod common;
use common::corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::{DecodeOptions, EncodeMode, EncodeOptions, Limits, SwingTarget};

fn displaced(c: &mut Criterion) {
    let Some(dir) = corpus() else { return };
    let mesh = swm::io::read_mesh(&dir.join("stanford-bunny.obj")).expect("read bunny");
    let options = DecodeOptions::plain();
    let mut g = c.benchmark_group("displaced-decode");
    g.sample_size(20);
    for bpv in [2.0, 8.0] {
        let encode = EncodeOptions {
            mode: EncodeMode::Displaced {
                target: SwingTarget::BitsPerVertex(bpv),
                max_bytes: None,
            },
            ..Default::default()
        };
        let bytes = swm::encode(&mesh, &encode).expect("encodes").bytes;
        let base = swm::cut_levels(&bytes, 0, &Limits::default()).expect("cuts");
        let len = swm::decoded_len(&bytes, &options).expect("bounds");
        let mut p = vec![0f32; len.position_floats() as usize];
        let mut i = vec![0u32; len.index_count() as usize];
        let name = format!("bunny-{bpv}bpv");
        g.throughput(Throughput::Elements(len.triangles));
        g.bench_function(format!("{name}/owned"), |b| {
            b.iter(|| {
                let m = swm::decode(black_box(&bytes), &options).expect("decodes");
                black_box(m.face_count())
            })
        });
        g.bench_function(format!("{name}/into"), |b| {
            b.iter(|| {
                swm::decode_into_with(black_box(&bytes), &options, &mut p, &mut i).expect("decodes")
            })
        });
        g.bench_function(format!("{name}/base-only"), |b| {
            b.iter(|| {
                let m = swm::decode(black_box(&base), &options).expect("decodes");
                black_box(m.face_count())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, displaced);
criterion_main!(benches);
