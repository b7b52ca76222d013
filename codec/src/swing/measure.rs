//! Measurements behind the coding choices of this mode, on real files:
//! `SWM_MEASURE=a.swm,b.swm cargo test -p swm --release --lib
//! swing::measure -- --ignored --nocapture`. Not part of the format.

use super::*;
use crate::container::{parse_container, Container, Tag};
use crate::edgebreaker::{Connectivity, Symbol};
use crate::entropy::{AdaptiveModel, ContextModel, Encoder};
use crate::mesh::CornerId;
use crate::{CornerTable, Limits};

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    a.map(|c| c / n)
}

/// Bending angle (positive convex) across the edge facing corner `c`,
/// between c's triangle and the one across; None unless all four
/// vertices are below `placed`.
fn bending(t: &CornerTable, x: &[[f64; 3]], c: usize, placed: usize) -> Option<(f64, [f64; 3])> {
    let o = t.opposite(CornerId(c as u32)).idx();
    let v = |k: usize| t.vertex(CornerId(k as u32)).idx();
    let tri = |k: usize| {
        let b = k - k % 3;
        [v(b), v(b + 1), v(b + 2)]
    };
    let (a, b) = (tri(c), tri(o));
    if a.iter().chain(b.iter()).any(|&w| w >= placed) {
        return None;
    }
    let na = unit(cross(sub(x[a[1]], x[a[0]]), sub(x[a[2]], x[a[0]])));
    let nb = unit(cross(sub(x[b[1]], x[b[0]]), sub(x[b[2]], x[b[0]])));
    let far = x[v(o)];
    let e0 = x[v(if c % 3 == 2 { c - 2 } else { c + 1 })];
    let e1 = x[v(if c % 3 == 0 { c + 2 } else { c - 1 })];
    let s = if dot(na, sub(far, e0)) < 0.0 {
        1.0
    } else {
        -1.0
    };
    let beta = (s * dot(cross(na, nb), cross(na, nb)).sqrt()).atan2(dot(na, nb));
    Some((beta, unit(sub(e1, e0))))
}

/// Bytes of the format's binarization with the gate-length context, for
/// residuals `z` (zig-zag) given per C triangle in order.
fn code_residuals(table: &CornerTable, zs: &[u32], bits: u8) -> usize {
    let mut len = ContextModel::new(bits as usize + 1, u32::from(bits) + 1);
    let mut man: Vec<AdaptiveModel> = (0..=bits)
        .map(|l| AdaptiveModel::new(if l <= 2 { 2 } else { 4 }))
        .collect();
    let mut lengths = vec![0u8; table.vertex_count()];
    let mut enc = Encoder::new();
    residual::for_each_c(table, |k, tip, gl, gr| {
        let z = zs[k];
        let l = 32 - z.leading_zeros();
        let ctx = lengths[gl].max(lengths[gr]) as usize;
        enc.encode(len.get(ctx), l);
        if l >= 2 {
            let top = (l - 1).min(2);
            let below = l - 1 - top;
            enc.encode(&mut man[l as usize], (z >> below) & ((1 << top) - 1));
            if below > 0 {
                enc.encode_bits(z & ((1 << below) - 1), below);
            }
        }
        lengths[tip] = l as u8;
        Ok(())
    })
    .unwrap();
    enc.finish().len()
}

fn zig(q: u32, pred: i64, bits: u8) -> u32 {
    let n = 1i64 << bits;
    let mut s = (i64::from(q) - pred).rem_euclid(n);
    if s >= n / 2 {
        s -= n;
    }
    (if s >= 0 { 2 * s } else { -2 * s - 1 }) as u32
}

fn clers_bytes(symbols: &[Symbol], order: usize) -> usize {
    let mut models: Vec<AdaptiveModel> = (0..5usize.pow(order as u32))
        .map(|_| AdaptiveModel::new(5))
        .collect();
    let mut enc = Encoder::new();
    let mut hist = vec![0usize; order];
    for &s in symbols {
        let ctx = hist.iter().fold(0, |a, &h| a * 5 + h);
        enc.encode(&mut models[ctx], s as u32);
        if order > 0 {
            hist.rotate_left(1);
            hist[order - 1] = s as usize;
        }
    }
    enc.finish().len()
}

/// The files named by `SWM_MEASURE` (comma-separated), read; none (and
/// a hint printed) when it is unset.
fn measured_files() -> Vec<(String, Vec<u8>)> {
    let Ok(list) = std::env::var("SWM_MEASURE") else {
        println!("set SWM_MEASURE=a.swm,b.swm");
        return Vec::new();
    };
    list.split(',')
        .map(|p| (p.to_string(), std::fs::read(p).unwrap()))
        .collect()
}

/// A SwingWrapper file's container, head, connectivity, decoded corner
/// table and number of C tips.
fn open(bytes: &[u8]) -> (Container<'_>, read::Head, Connectivity, CornerTable, usize) {
    let file = parse_container(bytes, &Limits::default()).unwrap();
    let (head, conn, table, _) = read::read_connectivity(&file, &Limits::default()).unwrap();
    let count = conn.symbols.iter().filter(|&&s| s == Symbol::C).count();
    (file, head, conn, table, count)
}

#[test]
#[ignore]
fn measure_contexts() {
    for (path, bytes) in measured_files() {
        let (file, head, conn, table, count) = open(&bytes);
        let geom = file.require(Tag::GEOM).unwrap().bytes;
        let codes = residual::decode(&table, geom, count, head.bits, head.predicted).unwrap();
        let x = rebuild::rebuild_positions(
            &table,
            &head.first,
            head.bits,
            &codes,
            read::read_levels(&file, &table, count).unwrap().as_deref(),
            None,
            None,
        )
        .unwrap();
        let bits = head.bits;
        let n = (1u32 << bits) as f64;
        let to_code = |beta: f64| {
            let d = core::f64::consts::PI - beta;
            ((d * n / core::f64::consts::TAU).round() as i64).rem_euclid(1 << bits)
        };
        let format = code_residuals(
            &table,
            &codes
                .iter()
                .map(|&q| zig(q, head.predicted.into(), bits))
                .collect::<Vec<_>>(),
            bits,
        );
        // Predictors from decoded neighbours.
        let mut z_parent = Vec::new();
        let mut z_ring = Vec::new();
        let mut z_dir = Vec::new();
        let mut have = 0;
        let v = |k: usize| table.vertex(CornerId(k as u32)).idx();
        let mut next = 0;
        let mut k = 0;
        for t in 0..table.face_count() {
            let (a, b) = (v(3 * t), v(3 * t + 1));
            if b >= next {
                next += 3;
                continue;
            }
            if a != next {
                continue;
            }
            let q = codes[k];
            k += 1;
            let placed = next;
            next += 1;
            let o = table.opposite(CornerId(3 * t as u32)).idx();
            let pc = o - o % 3;
            let gate = unit(sub(x[v(3 * t + 2)], x[v(3 * t + 1)]));
            // Parent's two other edges.
            let mut ps = Vec::new();
            for c in [pc, pc + 1, pc + 2] {
                if c == o {
                    continue;
                }
                if let Some((beta, _)) = bending(&table, &x, c, placed) {
                    ps.push(beta);
                }
            }
            let gp: i64 = head.predicted.into();
            let pred_p = if ps.is_empty() {
                gp
            } else {
                have += 1;
                to_code(ps.iter().sum::<f64>() / ps.len() as f64)
            };
            z_parent.push(zig(q, pred_p, bits));
            // All placed edges around the gate's vertices.
            let (mut sum, mut cnt, mut wsum, mut ws) = (0.0, 0.0, 0.0, 0.0);
            for g in [v(3 * t + 1), v(3 * t + 2)] {
                let start = table.vertex_corner(crate::mesh::VertexId(g as u32));
                for c in table.ring(crate::mesh::VertexId(g as u32)) {
                    let _ = start;
                    // edges facing the two other corners of c's triangle
                    let cc = c.idx();
                    for e in [cc - cc % 3 + (cc + 1) % 3, cc - cc % 3 + (cc + 2) % 3] {
                        if let Some((beta, dir)) = bending(&table, &x, e, placed) {
                            sum += beta;
                            cnt += 1.0;
                            let w = 0.05 + dot(dir, gate).powi(2);
                            wsum += w * beta;
                            ws += w;
                        }
                    }
                }
            }
            z_ring.push(zig(
                q,
                if cnt > 0.0 { to_code(sum / cnt) } else { gp },
                bits,
            ));
            z_dir.push(zig(q, if ws > 0.0 { to_code(wsum / ws) } else { gp }, bits));
        }
        let parent = code_residuals(&table, &z_parent, bits);
        let ring = code_residuals(&table, &z_ring, bits);
        let dir = code_residuals(&table, &z_dir, bits);
        let per = |b: usize| 8.0 * b as f64 / codes.len() as f64;
        println!(
            "{path}: K={bits}, {} angles ({have} with parent edges): format {:.3} | parent edges {:.3} | ring mean {:.3} | ring gate-aligned {:.3} bits/angle",
            codes.len(),
            per(format),
            per(parent),
            per(ring),
            per(dir)
        );
        let t = conn.symbols.len() as f64;
        let o: Vec<String> = (0..4)
            .map(|o| format!("{:.3}", 8.0 * clers_bytes(&conn.symbols, o) as f64 / t))
            .collect();
        println!("   CLERS bits/symbol by order 0..3: {}", o.join(" | "));
    }
}

/// Bits per level step under candidate contexts (`DENS`).
#[test]
#[ignore]
fn measure_density_contexts() {
    for (path, bytes) in measured_files() {
        let (file, _, _, table, count) = open(&bytes);
        let Some(dens) = file.find(Tag::DENS) else {
            continue;
        };
        let levels = density::decode(&table, dens.bytes, count).unwrap();
        let mut lv = vec![0i8; table.vertex_count()];
        let mut dv = vec![0i8; table.vertex_count()];
        let mut rows = Vec::new();
        residual::for_each_c(&table, |k, tip, gl, gr| {
            let d = levels[k] - density::gate_level(lv[gl], lv[gr]);
            lv[tip] = levels[k];
            dv[tip] = d;
            rows.push((d, dv[gl], dv[gr], lv[gl] - lv[gr]));
            Ok(())
        })
        .unwrap();
        let sym = |d: i8| (d + 1) as u32;
        let cost = |ctx: &dyn Fn(usize) -> usize, n: usize| {
            let mut m: Vec<AdaptiveModel> = (0..n).map(|_| AdaptiveModel::new(3)).collect();
            let mut enc = Encoder::new();
            for i in 0..rows.len() {
                enc.encode(&mut m[ctx(i)], sym(rows[i].0));
            }
            8.0 * enc.finish().len() as f64 / rows.len() as f64
        };
        let a = cost(
            &|i| usize::from(rows[i].1 != 0) + usize::from(rows[i].2 != 0),
            3,
        );
        let b = cost(
            &|i| (rows[i].1 + 1) as usize * 3 + (rows[i].2 + 1) as usize,
            9,
        );
        let c = cost(
            &|i| {
                ((rows[i].1 + 1) as usize * 3 + (rows[i].2 + 1) as usize) * 3
                    + if i > 0 {
                        (rows[i - 1].0 + 1) as usize
                    } else {
                        1
                    }
            },
            27,
        );
        let d = cost(
            &|i| {
                ((rows[i].1 + 1) as usize * 3 + (rows[i].2 + 1) as usize) * 3
                    + (rows[i].3.signum() + 1) as usize
            },
            27,
        );
        let steps = rows.iter().filter(|r| r.0 != 0).count() as f64 / rows.len() as f64;
        println!("{path}: {} steps ({:.3} nonzero): stepped count {a:.3} | (dGL,dGR) {b:.3} | + previous {c:.3} | + level order {d:.3} bits/step", rows.len(), steps);
    }
}
