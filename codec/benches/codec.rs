//! Speed of the lossless codec (issue 3 targets, one core, release build):
//! on `bunny-1m.ply` (1.1M triangles), `swm::decode` at ≥ 20 M
//! triangles/s and `swm::encode` (cleaning included) at ≥ 5 M
//! triangles/s.
//!
//! Groups:
//! * `lossless/bunny-1m`: the whole `encode` (qp 12) and `decode`;
//! * `encode-parts/bunny-1m`: cleaning, closing the holes (the closed
//!   corner table), the Edgebreaker traversal;
//! * `decode-parts/bunny-1m`: container and connectivity read (CRC, TOPO,
//!   CLERS entropy decoding: what `swm::inspect` does), Spirale Reversi,
//!   the geometry traversal alone, and geometry decoding (traversal plus
//!   residuals);
//! * `crc32`: the checksum over the encoded file;
//! * `decode`: whole decodes of the smaller corpus meshes.
//!
//! Throughput is in triangles per second (criterion "elements"), bytes
//! per second for the CRC.
//!
//! Run: `cargo bench -p swm --bench codec`. Needs `../shared/corpus`.

mod common;
use common::corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::container::{parse_container, Tag};
use swm::edgebreaker::{self, Connectivity};
use swm::entropy::Decoder;
use swm::{CornerTable, DecodeOptions, EncodeMode, EncodeOptions, Limits, TriMesh};

const QP: u8 = 12;

fn options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Lossless { qp: QP },
        ..Default::default()
    }
}

/// What the decoder has in hand before geometry decoding: its corner
/// table, which vertices are dummies, and the GEOM section.
struct DecoderInputs {
    conn: Connectivity,
    table: CornerTable,
    excluded: Vec<bool>,
    bits: u8,
    geom: Vec<u8>,
}

/// Rebuilds the decoder's inputs with public calls, the way the encoder
/// does (the decoder's own parsing is private).
fn decoder_inputs(mesh: &TriMesh, bytes: &[u8]) -> DecoderInputs {
    let cleaned = swm::clean(mesh, &swm::CleanOptions::default()).unwrap();
    let closed = edgebreaker::close_holes(&cleaned.table).table;
    let eb = edgebreaker::encode(&closed).unwrap();
    let table = edgebreaker::decode(&eb.connectivity).unwrap();
    let real = cleaned.mesh.vertex_count() as u32;
    let excluded = eb.vertex_order.iter().map(|v| v.0 >= real).collect();
    let file = parse_container(bytes, &Limits::default()).unwrap();
    DecoderInputs {
        conn: eb.connectivity,
        table,
        excluded,
        bits: file.section(Tag::HEAD).unwrap()[0],
        geom: file.section(Tag::GEOM).unwrap().to_vec(),
    }
}

fn bunny_1m(c: &mut Criterion) {
    let Some(dir) = corpus() else { return };
    let mesh = swm::io::read_mesh(&dir.join("bunny-1m.ply")).expect("read bunny-1m");
    let triangles = mesh.face_count() as u64;
    let bytes = swm::encode(&mesh, &options()).unwrap().bytes;
    let decode_options = DecodeOptions::plain();

    let mut g = c.benchmark_group("lossless/bunny-1m");
    g.sample_size(10);
    g.throughput(Throughput::Elements(triangles));
    g.bench_function("encode", |b| {
        b.iter(|| {
            black_box(
                swm::encode(black_box(&mesh), &options())
                    .unwrap()
                    .bytes
                    .len(),
            )
        })
    });
    g.bench_function("decode", |b| {
        b.iter(|| {
            let m = swm::decode(black_box(&bytes), &decode_options).unwrap();
            black_box(m.face_count())
        })
    });
    g.finish();

    let cleaned = swm::clean(&mesh, &swm::CleanOptions::default()).unwrap();
    let closed = edgebreaker::close_holes(&cleaned.table).table;
    let mut g = c.benchmark_group("encode-parts/bunny-1m");
    g.sample_size(10);
    g.throughput(Throughput::Elements(triangles));
    g.bench_function("clean", |b| {
        b.iter(|| {
            let c = swm::clean(black_box(&mesh), &swm::CleanOptions::default()).unwrap();
            black_box(c.mesh.face_count())
        })
    });
    g.bench_function("close_holes", |b| {
        b.iter(|| {
            let closed = edgebreaker::close_holes(black_box(&cleaned.table));
            black_box(closed.table.corner_count())
        })
    });
    g.bench_function("edgebreaker_encode", |b| {
        b.iter(|| {
            black_box(
                edgebreaker::encode(black_box(&closed))
                    .unwrap()
                    .vertex_order
                    .len(),
            )
        })
    });
    g.finish();

    let inputs = decoder_inputs(&mesh, &bytes);
    let mut g = c.benchmark_group("decode-parts/bunny-1m");
    g.sample_size(10);
    g.throughput(Throughput::Elements(triangles));
    g.bench_function("read_connectivity", |b| {
        b.iter(|| {
            let info = swm::inspect(black_box(&bytes), &Limits::default()).unwrap();
            black_box(info.stats.clers[0])
        })
    });
    g.bench_function("edgebreaker_decode", |b| {
        b.iter(|| {
            let t = edgebreaker::decode(black_box(&inputs.conn)).unwrap();
            black_box(t.corner_count())
        })
    });
    g.bench_function("geometry_traverse", |b| {
        b.iter(|| {
            let t = swm::geometry::traverse_except(black_box(&inputs.table), &inputs.excluded);
            black_box(t.unwrap().order.len())
        })
    });
    g.bench_function("geometry_decode", |b| {
        b.iter(|| {
            let mut dec = Decoder::new(black_box(&inputs.geom)).unwrap();
            let mut out = Vec::new();
            swm::geometry::lossless::decode_mesh_positions(
                &inputs.table,
                &inputs.excluded,
                inputs.bits,
                &mut dec,
                &mut out,
            )
            .unwrap();
            black_box(out.len())
        })
    });
    g.finish();

    let mut g = c.benchmark_group("crc32");
    g.sample_size(10);
    g.throughput(Throughput::Bytes(bytes.len() as u64));
    g.bench_function("bunny-1m.swm", |b| {
        b.iter(|| black_box(swm::container::crc32(black_box(&bytes))))
    });
    g.finish();
}

fn smaller_meshes(c: &mut Criterion) {
    let Some(dir) = corpus() else { return };
    let mut g = c.benchmark_group("decode");
    g.sample_size(10);
    for name in ["stanford-bunny.obj", "horse.ply"] {
        let mesh = swm::io::read_mesh(&dir.join(name)).expect("read corpus mesh");
        let bytes = swm::encode(&mesh, &options()).unwrap().bytes;
        g.throughput(Throughput::Elements(mesh.face_count() as u64));
        g.bench_function(name, |b| {
            b.iter(|| {
                let m = swm::decode(black_box(&bytes), &DecodeOptions::plain()).unwrap();
                black_box(m.face_count())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bunny_1m, smaller_meshes);
criterion_main!(benches);
