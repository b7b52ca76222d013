//! Round trips of position coding, hostile predictions, tables and bytes,
//! and the bits-per-vertex figures on the shared corpus.

use super::lossless::*;
use super::*;
use crate::entropy::{Decoder, Encoder};
use crate::mesh::{CornerId, CornerTable, VertexId};
use crate::{Error, FormatError, Malformed};

/// SplitMix64, so tests need no crate.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u32 {
        (self.next() % n) as u32
    }
}

const CODINGS: [Coding; 2] = [Coding::Plain, Coding::Offsets];

fn encode(q: &[[u32; 3]], p: &Predictions, bits: u8) -> Vec<u8> {
    encode_as(q, p, bits, Coding::Plain)
}

fn encode_as(q: &[[u32; 3]], p: &Predictions, bits: u8, coding: Coding) -> Vec<u8> {
    let mut enc = Encoder::new();
    encode_positions_as(q, p, bits, coding, &mut enc);
    enc.finish()
}

fn decode(bytes: &[u8], p: &Predictions, bits: u8) -> Result<Vec<[u32; 3]>, Error> {
    decode_as(bytes, p, bits, Coding::Plain)
}

fn decode_as(
    bytes: &[u8],
    p: &Predictions,
    bits: u8,
    coding: Coding,
) -> Result<Vec<[u32; 3]>, Error> {
    let mut dec = Decoder::new(bytes)?;
    let mut out = vec![[7, 7, 7]; 3]; // stale content must not leak
    decode_positions_as(p, bits, coding, &mut dec, &mut out)?;
    dec.finish()?;
    Ok(out)
}

/// Random valid predictions for `n` vertices (every kind, any reference
/// below the vertex, Multi lists of 1 to 6 entries).
fn random_predictions(rng: &mut Rng, n: usize) -> Predictions {
    let mut p = Predictions::default();
    for k in 0..n {
        let any = |rng: &mut Rng| rng.below(k as u64);
        let pred = match (k, rng.below(4)) {
            (0, _) | (_, 0) => Prediction::None,
            (_, 1) => Prediction::Delta { from: any(rng) },
            (_, 2) => Prediction::Parallelogram {
                a: any(rng),
                b: any(rng),
                opposite: any(rng),
            },
            _ => {
                let first = p.parallelograms.len() as u32;
                let count = 1 + rng.below(6);
                for _ in 0..count {
                    p.parallelograms.push([any(rng), any(rng), any(rng)]);
                }
                Prediction::Multi { first, count }
            }
        };
        p.vertices.push(pred);
    }
    p
}

/// Points near a smooth curve (so predictions are meaningful) plus
/// outliers at the grid's corners.
fn random_points(rng: &mut Rng, n: usize, bits: u8) -> Vec<[u32; 3]> {
    let max = ((1u64 << bits) - 1) as u32;
    (0..n)
        .map(|i| match rng.below(10) {
            0 => [0, max, rng.below(max as u64 + 1)],
            1 => [max; 3],
            _ => core::array::from_fn(|k| {
                let t = (i as f64 * 0.01 + k as f64).sin() * 0.5 + 0.5;
                ((t * max as f64) as u32).min(max)
            }),
        })
        .collect()
}

#[test]
fn random_round_trips() {
    let mut rng = Rng(1);
    for bits in [1u8, 2, 6, 11, 16, 24] {
        for n in [0, 1, 2, 3, 50, 2_000] {
            let p = random_predictions(&mut rng, n);
            let q = random_points(&mut rng, n, bits);
            for coding in CODINGS {
                let bytes = encode_as(&q, &p, bits, coding);
                let back = decode_as(&bytes, &p, bits, coding).unwrap();
                assert_eq!(back, q, "bits {bits} n {n} {coding:?}");
                // Deterministic.
                assert_eq!(encode_as(&q, &p, bits, coding), bytes);
            }
        }
    }
}

#[test]
fn invalid_references_are_rejected() {
    let q = [[1, 2, 3], [4, 5, 6], [7, 8, 9]];
    let ok = Predictions {
        vertices: vec![
            Prediction::None,
            Prediction::Delta { from: 0 },
            Prediction::Multi { first: 0, count: 2 },
        ],
        parallelograms: vec![[0, 1, 0], [1, 1, 0]],
    };
    let bytes = encode(&q, &ok, 8);
    assert_eq!(decode(&bytes, &ok, 8).unwrap(), q);

    let mut bad = Vec::new();
    let mut p = ok.clone();
    p.vertices[1] = Prediction::Delta { from: 1 };
    bad.push(p);
    let mut p = ok.clone();
    p.vertices[2] = Prediction::Parallelogram {
        a: 0,
        b: 1,
        opposite: 2,
    };
    bad.push(p);
    let mut p = ok.clone();
    p.parallelograms[1] = [0, 2, 1];
    bad.push(p);
    let mut p = ok.clone();
    p.vertices[2] = Prediction::Multi { first: 1, count: 2 };
    bad.push(p);
    let mut p = ok.clone();
    p.vertices[2] = Prediction::Multi { first: 0, count: 0 };
    bad.push(p);
    let mut p = ok.clone();
    p.vertices[0] = Prediction::Delta { from: u32::MAX };
    bad.push(p);
    for p in bad {
        match decode(&bytes, &p, 8) {
            Err(Error::Format(FormatError {
                what: Malformed::IndexOutOfRange { .. },
                ..
            })) => {}
            other => panic!("{p:?}: {other:?}"),
        }
    }
    for bits in [0, 25, 255] {
        assert!(matches!(
            decode(&bytes, &ok, bits),
            Err(Error::Format(FormatError {
                what: Malformed::BadHeader(_),
                ..
            }))
        ));
    }
}

#[test]
fn garbage_never_panics() {
    let mut rng = Rng(2);
    for round in 0..500 {
        let n = rng.below(300) as usize;
        let mut p = random_predictions(&mut rng, n);
        if round % 3 == 0 && n > 0 {
            // Hostile predictions too: any index at all.
            let k = rng.below(n as u64) as usize;
            p.vertices[k] = Prediction::Delta {
                from: rng.next() as u32,
            };
        }
        let len = 4 * rng.below(100) as usize;
        let bytes: Vec<u8> = match round % 4 {
            0 => vec![0xFF; len],
            _ => (0..len).map(|_| rng.next() as u8).collect(),
        };
        let bits = 1 + rng.below(24) as u8;
        let mut out = Vec::new();
        let coding = CODINGS[(round / 2) % 2];
        if let Ok(mut dec) = Decoder::new(&bytes) {
            if decode_positions_as(&p, bits, coding, &mut dec, &mut out).is_ok() {
                let max = ((1u64 << bits) - 1) as u32;
                assert_eq!(out.len(), n);
                assert!(out.iter().flatten().all(|&c| c <= max));
            }
        }
    }
}

/// A closed torus of `n × m` quads split into triangles, with positions
/// on a slightly noisy torus.
fn torus(n: u32, m: u32, rng: &mut Rng) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut pos = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (
                i as f64 / n as f64 * std::f64::consts::TAU,
                j as f64 / m as f64 * std::f64::consts::TAU,
            );
            let r = 1.0 + 0.35 * v.cos() + (rng.below(1000) as f64 - 500.0) * 1e-6;
            pos.push([
                (r * u.cos()) as f32,
                (r * u.sin()) as f32,
                (0.35 * v.sin()) as f32,
            ]);
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..m {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (pos, tris)
}

fn check_traversal(t: &Traversal, vertices: usize, excluded: &[bool]) {
    let mut seen = vec![false; vertices];
    for v in &t.order {
        assert!(!seen[v.idx()], "vertex {v} twice");
        assert!(!excluded.get(v.idx()).copied().unwrap_or(false));
        seen[v.idx()] = true;
    }
    let expected = (0..vertices)
        .filter(|&v| !excluded.get(v).copied().unwrap_or(false))
        .count();
    assert_eq!(t.order.len(), expected);
    assert_eq!(t.predictions.len(), expected);
    for (k, p) in t.predictions.vertices.iter().enumerate() {
        p.check(k, &t.predictions.parallelograms).unwrap();
    }
}

#[test]
fn mesh_round_trip_and_traversal() {
    let mut rng = Rng(3);
    let (mut pos, mut tris) = torus(40, 24, &mut rng);
    // A second component and an unreferenced vertex.
    let base = pos.len() as u32;
    let (p2, t2) = torus(6, 5, &mut rng);
    pos.extend(p2.iter().map(|p| [p[0] + 5.0, p[1], p[2]]));
    tris.extend(t2.iter().map(|t| t.map(|v| v + base)));
    pos.push([9.0, 9.0, 9.0]);
    let table = CornerTable::new(&tris, pos.len()).unwrap();
    let quant = Quantizer::from_positions(&pos, 12).unwrap();
    let q: Vec<[u32; 3]> = pos.iter().map(|&p| quant.quantize(p)).collect();

    let t = traverse(&table).unwrap();
    check_traversal(&t, pos.len(), &[]);
    // Nearly every vertex of a regular mesh gets two parallelograms.
    let multi = t
        .predictions
        .vertices
        .iter()
        .filter(|p| matches!(p, Prediction::Multi { .. }))
        .count();
    assert!(multi * 10 > pos.len() * 8, "{multi} of {}", pos.len());

    let mut enc = Encoder::new();
    encode_mesh_positions(&table, &[], &q, 12, &mut enc).unwrap();
    let bytes = enc.finish();
    let mut dec = Decoder::new(&bytes).unwrap();
    let mut out = Vec::new();
    decode_mesh_positions(&table, &[], 12, &mut dec, &mut out).unwrap();
    dec.finish().unwrap();
    assert_eq!(out, q);

    // Excluding vertices (as hole-filling dummies would be).
    let excluded: Vec<bool> = (0..pos.len()).map(|v| v % 7 == 3).collect();
    let t = traverse_except(&table, &excluded).unwrap();
    check_traversal(&t, pos.len(), &excluded);
    let mut enc = Encoder::new();
    encode_mesh_positions(&table, &excluded, &q, 12, &mut enc).unwrap();
    let bytes = enc.finish();
    let mut dec = Decoder::new(&bytes).unwrap();
    decode_mesh_positions(&table, &excluded, 12, &mut dec, &mut out).unwrap();
    for (v, p) in out.iter().enumerate() {
        assert_eq!(*p, if excluded[v] { [0; 3] } else { q[v] });
    }
}

#[test]
fn traversal_survives_corrupt_tables() {
    let mut rng = Rng(4);
    for _ in 0..200 {
        let faces = 1 + rng.below(40) as usize;
        let vertices = 1 + rng.below(30) as usize;
        let v: Vec<VertexId> = (0..3 * faces)
            .map(|_| VertexId(rng.below(vertices as u64)))
            .collect();
        let o: Vec<CornerId> = (0..3 * faces)
            .map(|_| match rng.below(4) {
                0 => CornerId::NONE,
                _ => CornerId(rng.below(3 * faces as u64)),
            })
            .collect();
        let table = CornerTable::from_parts(v, o, vertices);
        let t = traverse(&table).unwrap();
        check_traversal(&t, vertices, &[]);
    }
}

/// Breadth-first predictions over triangles from face 0 (then the first
/// unvisited face of each further component): a vertex is emitted the
/// first time a triangle containing it is reached, predicted by the
/// parallelogram across the edge the traversal came through (or, with
/// `multi`, by every parallelogram around it over emitted vertices);
/// `None` / `Delta` in a component's first triangle. The brief's baseline.
fn traverse_bfs(table: &CornerTable, vertices: usize, multi: bool) -> Traversal {
    let faces = table.face_count();
    let mut id = vec![u32::MAX; vertices];
    let mut visited = vec![false; faces];
    let mut t = Traversal::default();
    let mut queue = std::collections::VecDeque::new();
    let vtx = |c: CornerId| table.vertex(c).idx();
    let emit = |v: usize, p: Prediction, id: &mut [u32], t: &mut Traversal| {
        id[v] = t.order.len() as u32;
        t.order.push(VertexId(v as u32));
        t.predictions.vertices.push(p);
    };
    for seed in 0..faces {
        if visited[seed] {
            continue;
        }
        visited[seed] = true;
        let mut last = None;
        for k in 0..3 {
            let v = vtx(CornerId(3 * seed as u32 + k));
            if id[v] == u32::MAX {
                let p = last.map_or(Prediction::None, |from| Prediction::Delta { from });
                emit(v, p, &mut id, &mut t);
            }
            last = Some(id[v]);
        }
        let mut push = |x: CornerId, queue: &mut std::collections::VecDeque<CornerId>| {
            let o = table.opposite(x);
            if o.is_some() && !visited[o.face().idx()] {
                visited[o.face().idx()] = true;
                queue.push_back(o);
            }
        };
        for k in 0..3 {
            push(CornerId(3 * seed as u32 + k), &mut queue);
        }
        while let Some(c) = queue.pop_front() {
            let v = vtx(c);
            if id[v] == u32::MAX {
                let p = if multi {
                    let paras = &mut t.predictions.parallelograms;
                    let first = paras.len() as u32;
                    for cv in table.ring(VertexId(v as u32)) {
                        let o = table.opposite(cv);
                        if o.is_none() {
                            continue;
                        }
                        let tri = [vtx(cv.next()), vtx(cv.prev()), vtx(o)];
                        if tri.iter().all(|&w| id[w] != u32::MAX) {
                            paras.push(tri.map(|w| id[w]));
                        }
                    }
                    let count = paras.len() as u32 - first;
                    Prediction::Multi { first, count }
                } else {
                    Prediction::Parallelogram {
                        a: id[vtx(c.next())],
                        b: id[vtx(c.prev())],
                        opposite: id[vtx(table.opposite(c))],
                    }
                };
                emit(v, p, &mut id, &mut t);
            }
            push(c.next(), &mut queue);
            push(c.prev(), &mut queue);
        }
    }
    t
}

use crate::io::shared_corpus_mesh as corpus;

/// Bits per vertex of each traversal on a corpus mesh, after checking
/// the round trip.
fn corpus_figures(name: &str, bits: u8) -> Option<[f64; 3]> {
    let mesh = corpus(name)?;
    let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
    let (m, table) = (&cleaned.mesh, &cleaned.table);
    let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
    let q: Vec<[u32; 3]> = m.positions.iter().map(|&p| quant.quantize(p)).collect();
    let traversals = [
        traverse_bfs(table, q.len(), false),
        traverse_bfs(table, q.len(), true),
        traverse(table).unwrap(),
    ];
    Some(traversals.map(|t| {
        let ordered: Vec<[u32; 3]> = t.order.iter().map(|v| q[v.idx()]).collect();
        let bytes = encode(&ordered, &t.predictions, bits);
        assert_eq!(decode(&bytes, &t.predictions, bits).unwrap(), ordered);
        bytes.len() as f64 * 8.0 / q.len() as f64
    }))
}

/// Ratchet: the corpus figures may only go down. Prints them.
#[test]
fn corpus_bits_per_vertex() {
    for (name, bits, ceiling) in [("stanford-bunny.obj", 11u8, 7.85), ("horse.ply", 12, 8.8)] {
        let Some([bfs, bfs_multi, degree]) = corpus_figures(name, bits) else {
            return;
        };
        eprintln!(
            "{name} at {bits} bits: breadth-first parallelogram {bfs:.3}, \
             breadth-first multi {bfs_multi:.3}, max-degree multi {degree:.3} bits/vertex"
        );
        assert!(degree <= ceiling, "{name}: {degree:.3} > {ceiling}");
        assert!(degree < bfs_multi && bfs_multi < bfs);
    }
}
