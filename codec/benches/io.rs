//! Reading meshes and building the corner table (issue 2 speed targets):
//! `bunny-1m.ply` (1.1M faces) read + corner table at >= 5 M faces/s, and
//! OBJ at >= 1 M faces/s, on one core.
//!
//! Run: `cargo bench -p swm --bench io`. Needs `../shared/corpus`.

mod common;
use common::corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use swm::{CornerTable, Limits};

fn io(c: &mut Criterion) {
    let Some(dir) = corpus() else { return };
    let ply = dir.join("bunny-1m.ply");
    let mesh = swm::io::read_mesh(&ply).expect("read bunny-1m");
    let faces = mesh.face_count() as u64;

    let mut g = c.benchmark_group("io");
    g.sample_size(20);
    g.throughput(Throughput::Elements(faces));
    g.bench_function("ply_read+corner_table/bunny-1m", |b| {
        b.iter(|| {
            let m = swm::io::read_mesh(black_box(&ply)).unwrap();
            let t = CornerTable::new(&m.triangles, m.vertex_count()).unwrap();
            black_box(t.corner_count())
        })
    });
    g.bench_function("ply_read/bunny-1m", |b| {
        b.iter(|| black_box(swm::io::read_mesh(black_box(&ply)).unwrap().face_count()))
    });
    g.bench_function("corner_table/bunny-1m", |b| {
        b.iter(|| {
            black_box(
                CornerTable::new(black_box(&mesh.triangles), mesh.vertex_count())
                    .unwrap()
                    .corner_count(),
            )
        })
    });
    g.bench_function("clean/bunny-1m", |b| {
        b.iter(|| {
            black_box(
                swm::clean(black_box(&mesh), &swm::CleanOptions::default())
                    .unwrap()
                    .mesh
                    .face_count(),
            )
        })
    });

    // The same mesh as OBJ text, written once outside the timed loop.
    let obj = std::env::temp_dir().join(format!("swm-bench-{}.obj", std::process::id()));
    swm::io::write_mesh(&obj, &mesh).expect("write OBJ");
    let bytes = std::fs::read(&obj).unwrap();
    g.bench_function("obj_read/bunny-1m", |b| {
        b.iter(|| {
            let m = swm::io::read_mesh_bytes(
                black_box(&bytes),
                swm::io::MeshFormat::Obj,
                &Limits::default(),
            );
            black_box(m.unwrap().face_count())
        })
    });
    g.finish();
    let _ = std::fs::remove_file(obj);
}

criterion_group!(benches, io);
criterion_main!(benches);
