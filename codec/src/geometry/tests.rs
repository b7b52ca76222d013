//! Round trips of position coding, hostile predictions and bytes, and the
//! bits-per-vertex figures on the shared corpus.

use super::lossless::*;
use super::*;
use crate::entropy::{Decoder, Encoder};
use crate::mesh::{CornerId, CornerTable, VertexId};

/// Predictions for a mesh, in a breadth-first order over its triangles:
/// what a connectivity decoder would hand the geometry coder.
pub(crate) struct Traversal {
    /// Original vertex of each decoded vertex.
    pub order: Vec<u32>,
    /// Prediction of each decoded vertex.
    pub predictions: Vec<Prediction>,
    /// Parallelogram list of the `Multi` predictions.
    pub parallelograms: Vec<[u32; 3]>,
}

/// Breadth-first traversal over triangles from face 0 (then from the
/// first unvisited face of each further component). A vertex is emitted
/// the first time a triangle containing it is reached: as `None` /
/// `Delta` in a component's first triangle, otherwise as the parallelogram
/// over the edge the traversal came through or, with `multi`, as every
/// parallelogram around it whose three vertices are already emitted.
pub(crate) fn traverse(table: &CornerTable, vertices: usize, multi: bool) -> Traversal {
    let faces = table.face_count();
    let mut id = vec![u32::MAX; vertices];
    let mut visited = vec![false; faces];
    let mut t = Traversal {
        order: Vec::with_capacity(vertices),
        predictions: Vec::with_capacity(vertices),
        parallelograms: Vec::new(),
    };
    let mut queue = std::collections::VecDeque::new();
    let vtx = |c: CornerId| table.vertex(c).0 as usize;
    for seed in 0..faces {
        if visited[seed] {
            continue;
        }
        visited[seed] = true;
        let mut last = None;
        for k in 0..3 {
            let v = vtx(CornerId(3 * seed as u32 + k));
            if id[v] == u32::MAX {
                let p = match last {
                    None => Prediction::None,
                    Some(from) => Prediction::Delta { from },
                };
                id[v] = t.order.len() as u32;
                t.order.push(v as u32);
                t.predictions.push(p);
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
                    let first = t.parallelograms.len() as u32;
                    for cv in table.ring(VertexId(v as u32)) {
                        let o = table.opposite(cv);
                        if o.is_none() {
                            continue;
                        }
                        let tri = [vtx(cv.next()), vtx(cv.prev()), vtx(o)];
                        if tri.iter().all(|&w| id[w] != u32::MAX) {
                            t.parallelograms.push(tri.map(|w| id[w]));
                        }
                    }
                    let count = t.parallelograms.len() as u32 - first;
                    Prediction::Multi { first, count }
                } else {
                    Prediction::Parallelogram {
                        a: id[vtx(c.next())],
                        b: id[vtx(c.prev())],
                        opposite: id[vtx(table.opposite(c))],
                    }
                };
                id[v] = t.order.len() as u32;
                t.order.push(v as u32);
                t.predictions.push(p);
            }
            push(c.next(), &mut queue);
            push(c.prev(), &mut queue);
        }
    }
    t
}

fn round_trip(
    q: &[[u32; 3]],
    predictions: &[Prediction],
    parallelograms: &[[u32; 3]],
    bits: u8,
    cfg: Config,
) -> usize {
    let mut enc = Encoder::new();
    encode_positions_cfg(q, predictions, parallelograms, bits, &mut enc, cfg);
    let bytes = enc.finish();
    let mut dec = Decoder::new(&bytes).unwrap();
    let mut out = Vec::new();
    decode_positions_cfg(predictions, parallelograms, bits, &mut dec, &mut out, cfg).unwrap();
    dec.finish().unwrap();
    assert_eq!(out, q);
    bytes.len()
}

fn corpus(name: &str) -> Option<crate::TriMesh> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/corpus")
        .join(name);
    if !path.exists() {
        eprintln!("skipped: ../shared/corpus not found");
        return None;
    }
    Some(crate::io::read_mesh(&path).unwrap())
}

#[test]
#[ignore]
fn measure() {
    for (name, bits) in [("stanford-bunny.obj", 11u8), ("horse.ply", 12)] {
        let Some(mesh) = corpus(name) else { return };
        let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
        let m = &cleaned.mesh;
        let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
        for multi in [false, true] {
            let t = traverse(&cleaned.table, m.positions.len(), multi);
            let q: Vec<[u32; 3]> = t
                .order
                .iter()
                .map(|&v| quant.quantize(m.positions[v as usize]))
                .collect();
            for ctx_mode in [2, 4, 5, 6, 7] {
                for adaptive_top in [1, 2] {
                    let cfg = Config {
                        ctx_mode,
                        adaptive_top,
                        select: 0,
                    };
                    let bytes = round_trip(&q, &t.predictions, &t.parallelograms, bits, cfg);
                    eprintln!(
                        "{name} {bits} bits multi={multi} ctx={ctx_mode} top={adaptive_top}: {} B, {:.3} bits/vertex",
                        bytes,
                        bytes as f64 * 8.0 / q.len() as f64
                    );
                }
            }
        }
    }
}

#[test]
#[ignore]
fn stats() {
    for (name, bits) in [("stanford-bunny.obj", 11u8), ("horse.ply", 12)] {
        let Some(mesh) = corpus(name) else { return };
        let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
        let m = &cleaned.mesh;
        eprintln!(
            "{name}: {} vertices {} faces, components {:?}",
            m.positions.len(),
            m.triangles.len(),
            cleaned.table.stats(m).components
        );
        let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
        for multi in [false, true] {
            let t = traverse(&cleaned.table, m.positions.len(), multi);
            let q: Vec<[u32; 3]> = t
                .order
                .iter()
                .map(|&v| quant.quantize(m.positions[v as usize]))
                .collect();
            let mut hist = std::collections::HashMap::<i64, u64>::new();
            let mut counts = [0u64; 8];
            let mut abs_sum = 0f64;
            for (k, p) in t.predictions.iter().enumerate() {
                if let Prediction::Multi { count, .. } = p {
                    counts[(*count as usize).min(7)] += 1;
                }
                let pred = p.predict(&q[..k], &t.parallelograms, bits);
                for a in 0..3 {
                    let r = q[k][a] as i64 - pred[a] as i64;
                    abs_sum += r.abs() as f64;
                    *hist.entry(r).or_default() += 1;
                }
            }
            let n: u64 = hist.values().sum();
            let h: f64 = hist
                .values()
                .map(|&c| -(c as f64) * (c as f64 / n as f64).log2())
                .sum::<f64>()
                / q.len() as f64;
            eprintln!("  multi={multi}: order-0 entropy of residuals {h:.3} bits/vertex, mean |r| {:.3}, counts {:?}", abs_sum / n as f64, counts);
        }
    }
}

fn entropy_of(res: &[[i64; 3]]) -> f64 {
    let mut hist = std::collections::HashMap::<i64, u64>::new();
    for r in res {
        for a in 0..3 {
            *hist.entry(r[a]).or_default() += 1;
        }
    }
    let n: u64 = hist.values().sum();
    hist.values()
        .map(|&c| -(c as f64) * (c as f64 / n as f64).log2())
        .sum::<f64>()
        / res.len() as f64
}

#[test]
#[ignore]
fn correction() {
    for (name, bits) in [("stanford-bunny.obj", 11u8), ("horse.ply", 12)] {
        let Some(mesh) = corpus(name) else { return };
        let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
        let m = &cleaned.mesh;
        let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
        let t = traverse(&cleaned.table, m.positions.len(), true);
        let q: Vec<[u32; 3]> = t
            .order
            .iter()
            .map(|&v| quant.quantize(m.positions[v as usize]))
            .collect();
        for lambda in [0.0, 0.25, 0.5, 0.75, 1.0] {
            for use_o in [false, true] {
                let mut res: Vec<[i64; 3]> = Vec::new();
                let mut out = Vec::new();
                for (k, p) in t.predictions.iter().enumerate() {
                    let pred = p.predict(&q[..k], &t.parallelograms, bits);
                    let mut corr = [0f64; 3];
                    if let Prediction::Multi { first, count } = *p {
                        let mut n = 0.0;
                        for tri in &t.parallelograms[first as usize..(first + count) as usize] {
                            for (i, &w) in tri.iter().enumerate() {
                                if i == 2 && !use_o {
                                    continue;
                                }
                                let sign = if i == 2 { -1.0 } else { 1.0 };
                                let _ = sign;
                                for a in 0..3 {
                                    corr[a] += res[w as usize][a] as f64;
                                }
                                n += 1.0;
                            }
                        }
                        for a in 0..3 {
                            corr[a] = (corr[a] / n * lambda).round();
                        }
                    }
                    let r: [i64; 3] = core::array::from_fn(|a| q[k][a] as i64 - pred[a] as i64);
                    res.push(r);
                    out.push(core::array::from_fn(|a| r[a] - corr[a] as i64));
                }
                eprintln!(
                    "{name} lambda={lambda} use_o={use_o}: entropy {:.3}",
                    entropy_of(&out)
                );
            }
        }
    }
}

/// Max-prediction-degree order (experiment).
pub(crate) fn traverse_degree(table: &CornerTable, vertices: usize, lifo: bool) -> Traversal {
    const MAXD: usize = 8;
    let faces = table.face_count();
    let mut id = vec![u32::MAX; vertices];
    let mut degree = vec![u8::MAX; vertices]; // MAX: not queued
    let mut buckets: Vec<std::collections::VecDeque<u32>> = vec![Default::default(); MAXD + 1];
    let mut t = Traversal {
        order: Vec::new(),
        predictions: Vec::new(),
        parallelograms: Vec::new(),
    };
    let vtx = |c: CornerId| table.vertex(c).0 as usize;
    let paras = |v: usize, id: &[u32]| -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        for cv in table.ring(VertexId(v as u32)) {
            let o = table.opposite(cv);
            if o.is_none() {
                continue;
            }
            let tri = [vtx(cv.next()), vtx(cv.prev()), vtx(o)];
            if tri.iter().all(|&w| id[w] != u32::MAX) {
                out.push(tri.map(|w| id[w]));
            }
        }
        out
    };
    let mut face_done = vec![false; faces];
    let _ = &mut face_done;
    let mut emit = |v: usize, p: Prediction, id: &mut [u32], t: &mut Traversal| {
        id[v] = t.order.len() as u32;
        t.order.push(v as u32);
        t.predictions.push(p);
    };
    for seed in 0..faces {
        let c0 = CornerId(3 * seed as u32);
        if id[vtx(c0)] != u32::MAX {
            continue;
        }
        // seed triangle
        let mut last = None;
        for k in 0..3 {
            let v = vtx(CornerId(c0.0 + k));
            if id[v] == u32::MAX {
                let p = match last {
                    None => Prediction::None,
                    Some(from) => Prediction::Delta { from },
                };
                emit(v, p, &mut id, &mut t);
            }
            last = Some(id[v]);
        }
        let mut touched: Vec<usize> = Vec::new();
        let mut refresh = |w: usize,
                           id: &[u32],
                           degree: &mut [u8],
                           buckets: &mut Vec<std::collections::VecDeque<u32>>,
                           touched: &mut Vec<usize>| {
            // neighbours and flap vertices of w
            touched.clear();
            for cw in table.ring(VertexId(w as u32)) {
                touched.push(vtx(cw.next()));
                touched.push(vtx(cw.prev()));
                let o = table.opposite(cw);
                if o.is_some() {
                    touched.push(vtx(o));
                }
            }
            for &v in touched.iter() {
                if id[v] != u32::MAX {
                    continue;
                }
                // only vertices adjacent to a decoded vertex are candidates
                let d = paras(v, id).len().min(MAXD) as u8;
                let adjacent = table
                    .ring(VertexId(v as u32))
                    .any(|c| id[vtx(c.next())] != u32::MAX || id[vtx(c.prev())] != u32::MAX);
                if !adjacent {
                    continue;
                }
                if degree[v] != d {
                    degree[v] = d;
                    if lifo {
                        buckets[d as usize].push_front(v as u32)
                    } else {
                        buckets[d as usize].push_back(v as u32)
                    }
                }
            }
        };
        for k in 0..3 {
            let v = vtx(CornerId(c0.0 + k));
            refresh(v, &id, &mut degree, &mut buckets, &mut touched);
        }
        loop {
            let mut found = None;
            for d in (0..=MAXD).rev() {
                while let Some(v) = buckets[d].pop_front() {
                    let v = v as usize;
                    if id[v] == u32::MAX && degree[v] as usize == d {
                        found = Some(v);
                        break;
                    }
                }
                if found.is_some() {
                    break;
                }
            }
            let Some(v) = found else { break };
            let list = paras(v, &id);
            let p = if list.is_empty() {
                let from = table
                    .ring(VertexId(v as u32))
                    .map(|c| vtx(c.next()))
                    .chain(table.ring(VertexId(v as u32)).map(|c| vtx(c.prev())))
                    .find(|&w| id[w] != u32::MAX)
                    .unwrap();
                Prediction::Delta { from: id[from] }
            } else {
                let first = t.parallelograms.len() as u32;
                t.parallelograms.extend_from_slice(&list);
                Prediction::Multi {
                    first,
                    count: list.len() as u32,
                }
            };
            emit(v, p, &mut id, &mut t);
            refresh(v, &id, &mut degree, &mut buckets, &mut touched);
        }
    }
    assert_eq!(t.order.len(), vertices);
    t
}

#[test]
#[ignore]
fn degree_order() {
    for (name, bits) in [("stanford-bunny.obj", 11u8), ("horse.ply", 12)] {
        let Some(mesh) = corpus(name) else { return };
        let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
        let m = &cleaned.mesh;
        let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
        for lifo in [false, true] {
            let t = traverse_degree(&cleaned.table, m.positions.len(), lifo);
            let q: Vec<[u32; 3]> = t
                .order
                .iter()
                .map(|&v| quant.quantize(m.positions[v as usize]))
                .collect();
            let mut counts = [0u64; 9];
            let mut res = Vec::new();
            for (k, p) in t.predictions.iter().enumerate() {
                if let Prediction::Multi { count, .. } = p {
                    counts[(*count as usize).min(8)] += 1;
                }
                let pred = p.predict(&q[..k], &t.parallelograms, bits);
                res.push(core::array::from_fn::<i64, 3, _>(|a| {
                    q[k][a] as i64 - pred[a] as i64
                }));
            }
            for select in 0..3 {
                for ctx_mode in [2, 6] {
                    let cfg = Config {
                        ctx_mode,
                        adaptive_top: 2,
                        select,
                    };
                    let bytes = round_trip(&q, &t.predictions, &t.parallelograms, bits, cfg);
                    eprintln!("{name} lifo={lifo} select={select} ctx={ctx_mode}: entropy {:.3}, coded {:.3} bits/vertex, counts {counts:?}", entropy_of(&res), bytes as f64 * 8.0 / q.len() as f64);
                }
            }
        }
    }
}

#[test]
#[ignore]
fn normal_bias() {
    for (name, bits) in [("stanford-bunny.obj", 11u8), ("horse.ply", 12)] {
        let Some(mesh) = corpus(name) else { return };
        let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
        let m = &cleaned.mesh;
        let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
        let t = traverse_degree(&cleaned.table, m.positions.len(), false);
        let q: Vec<[u32; 3]> = t
            .order
            .iter()
            .map(|&v| quant.quantize(m.positions[v as usize]))
            .collect();
        let f = |v: u32| {
            glam::DVec3::new(
                q[v as usize][0] as f64,
                q[v as usize][1] as f64,
                q[v as usize][2] as f64,
            )
        };
        let (mut sn, mut sn2, mut st2, mut n, mut se2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let mut ratio = 0.0;
        for (k, p) in t.predictions.iter().enumerate() {
            let Prediction::Multi { first, count } = *p else {
                continue;
            };
            let mut pred = glam::DVec3::ZERO;
            let mut nrm = glam::DVec3::ZERO;
            let mut len2 = 0.0;
            for tri in &t.parallelograms[first as usize..(first + count) as usize] {
                pred += f(tri[0]) + f(tri[1]) - f(tri[2]);
                nrm += (f(tri[1]) - f(tri[2])).cross(f(tri[0]) - f(tri[2]));
                len2 += (f(tri[0]) - f(tri[1])).length_squared();
            }
            pred /= count as f64;
            len2 /= count as f64;
            let r = f(k as u32) - pred;
            let nh = nrm.normalize_or_zero();
            let rn = r.dot(nh);
            sn += rn;
            sn2 += rn * rn;
            st2 += (r - rn * nh).length_squared();
            se2 += len2;
            n += 1.0;
            ratio += rn / len2.max(1.0);
        }
        eprintln!("{name}: mean r·n {:.3}, rms r·n {:.3}, rms tangential {:.3}, rms edge {:.2}, mean r·n/edge² {:.5}", sn / n, (sn2 / n).sqrt(), (st2 / n).sqrt(), (se2/n).sqrt(), ratio / n);
    }
}

#[test]
#[ignore]
fn subset_oracle() {
    for (name, bits) in [("stanford-bunny.obj", 11u8), ("horse.ply", 12)] {
        let Some(mesh) = corpus(name) else { return };
        let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
        let m = &cleaned.mesh;
        let quant = Quantizer::from_positions(&m.positions, bits).unwrap();
        let t = traverse_degree(&cleaned.table, m.positions.len(), false);
        let q: Vec<[u32; 3]> = t
            .order
            .iter()
            .map(|&v| quant.quantize(m.positions[v as usize]))
            .collect();
        let mut all = Vec::new();
        let mut best = Vec::new();
        let mut choices = std::collections::HashMap::<(u32, u32), u64>::new();
        for (k, p) in t.predictions.iter().enumerate() {
            let pred = p.predict(&q[..k], &t.parallelograms, bits);
            let r: [i64; 3] = core::array::from_fn(|a| q[k][a] as i64 - pred[a] as i64);
            all.push(r);
            let Prediction::Multi { first, count } = *p else {
                best.push(r);
                continue;
            };
            let list = &t.parallelograms[first as usize..(first + count) as usize];
            let mut b = (i64::MAX, r, 0u32);
            for mask in 1u32..(1 << count.min(6)) {
                let sub: Vec<[u32; 3]> = (0..count)
                    .filter(|i| mask >> i & 1 == 1)
                    .map(|i| list[i as usize])
                    .collect();
                let pr = predict_multi(&q[..k], &sub, bits);
                let rr: [i64; 3] = core::array::from_fn(|a| q[k][a] as i64 - pr[a] as i64);
                let l1 = rr.iter().map(|x| x.abs()).sum::<i64>();
                if l1 < b.0 {
                    b = (l1, rr, mask);
                }
            }
            *choices.entry((count, b.2)).or_default() += 1;
            best.push(b.1);
        }
        eprintln!(
            "{name}: all {:.3} oracle-subset {:.3}; choices {:?}",
            entropy_of(&all),
            entropy_of(&best),
            {
                let mut c: Vec<_> = choices.into_iter().collect();
                c.sort();
                c
            }
        );
    }
}
