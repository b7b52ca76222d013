//! What a viewer pays to decode (issue 9): the owned `decode` against
//! `decode_into` caller buffers sized by `decoded_len`, and the
//! angle-weighted normals a viewer computes after (the format stores
//! none). One core, release build; triangles of the decoded mesh per
//! second.
//!
//! Inputs: bunny-1m in the lossless mode (qp 12, the large-mesh case) and
//! SwingWrapper files of horse and bunny-1m at 4 b/v (the mode the codec
//! is for).
//! * `viewer-decode/<input>/{owned,into}`: `decode` vs `decode_into_with`
//!   (which checks the bound and copies the result out once);
//! * `viewer-normals/<input>/{owned,into}`: `vertex_normals` over the
//!   `TriMesh` vs `vertex_normals_into` over flat buffers.
//!
//! Run: `cargo bench -p swm --bench viewer`. Needs `../shared/corpus`.

mod common;
use common::corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::{DecodeOptions, EncodeMode, EncodeOptions, SwingTarget};

fn encoded(dir: &std::path::Path, name: &str, mode: EncodeMode) -> Vec<u8> {
    let mesh = swm::io::read_mesh(&dir.join(name)).expect("corpus mesh");
    let options = EncodeOptions {
        mode,
        ..Default::default()
    };
    swm::encode(&mesh, &options).expect("encodes").bytes
}

fn swing(bpv: f64) -> EncodeMode {
    EncodeMode::Swing {
        target: SwingTarget::BitsPerVertex(bpv),
        angle_bits: Some(8),
        max_bytes: None,
    }
}

fn viewer(c: &mut Criterion) {
    let Some(dir) = corpus() else {
        return;
    };
    let inputs = [
        (
            "bunny-1m-lossless",
            encoded(&dir, "bunny-1m.ply", EncodeMode::Lossless { qp: 12 }),
        ),
        ("horse-swing-4bpv", encoded(&dir, "horse.ply", swing(4.0))),
        (
            "bunny-1m-swing-4bpv",
            encoded(&dir, "bunny-1m.ply", swing(4.0)),
        ),
    ];
    let options = DecodeOptions::plain();
    let mut g = c.benchmark_group("viewer-decode");
    g.sample_size(10);
    for (name, bytes) in &inputs {
        let len = swm::decoded_len(bytes, &options).expect("bounds");
        let mut p = vec![0f32; len.position_floats() as usize];
        let mut i = vec![0u32; len.index_count() as usize];
        g.throughput(Throughput::Elements(len.triangles));
        g.bench_function(format!("{name}/owned"), |b| {
            b.iter(|| swm::decode(black_box(bytes), &options).expect("decodes"))
        });
        g.bench_function(format!("{name}/into"), |b| {
            b.iter(|| {
                swm::decode_into_with(black_box(bytes), &options, &mut p, &mut i).expect("decodes")
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("viewer-normals");
    g.sample_size(10);
    for (name, bytes) in &inputs {
        let mesh = swm::decode(bytes, &options).expect("decodes");
        let mut n = vec![0f32; 3 * mesh.vertex_count()];
        g.throughput(Throughput::Elements(mesh.face_count() as u64));
        g.bench_function(format!("{name}/owned"), |b| {
            b.iter(|| swm::vertex_normals(black_box(&mesh)))
        });
        g.bench_function(format!("{name}/into"), |b| {
            b.iter(|| {
                swm::vertex_normals_into(
                    black_box(mesh.positions.as_flattened()),
                    mesh.triangles.as_flattened(),
                    &mut n,
                )
            })
        });
    }
    g.finish();
}

criterion_group!(benches, viewer);
criterion_main!(benches);
