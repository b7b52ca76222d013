use super::*;
use crate::edgebreaker::tests_support::{icosahedron, subdivided};
use crate::{CornerTable, Error, FormatError, Malformed, TriMesh};

/// A sphere-like test surface: an icosahedron subdivided `levels` times,
/// every vertex moved to radius `radius(direction)`.
fn sphere(levels: u32, radius: impl Fn([f64; 3]) -> f64) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let (p, f) = subdivided(icosahedron(t), levels, |a, b| {
        core::array::from_fn(|k| (a[k] + b[k]) / 2.0)
    });
    let positions = p
        .iter()
        .map(|q| {
            let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            let d = q.map(|c| c / l);
            let r = radius(d);
            d.map(|c| (c * r) as f32)
        })
        .collect();
    TriMesh::new(positions, f)
}

/// What the retiler would hand over for `mesh`: M′ = `mesh` in
/// Edgebreaker order, the first three vertices rounded to f32, and every
/// C tip replaced by the point of its quantized angle, built on the
/// already replaced positions (so errors do not accumulate).
pub(super) fn emulate(mesh: &TriMesh, bits: u8) -> Retiled {
    let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
    let eb = crate::edgebreaker::encode(&table).unwrap();
    let mut rank = vec![u32::MAX; mesh.vertex_count()];
    for (k, v) in eb.vertex_order.iter().enumerate() {
        rank[v.idx()] = k as u32;
    }
    let triangles: Vec<[u32; 3]> = eb
        .tip_corners
        .iter()
        .map(|&c| [c, c.next(), c.prev()].map(|c| rank[table.vertex(c).idx()]))
        .collect();
    let truth: Vec<[f64; 3]> = eb
        .vertex_order
        .iter()
        .map(|v| mesh.positions[v.idx()].map(f64::from))
        .collect();
    let ordered = CornerTable::new(&triangles, truth.len()).unwrap();
    let first = [truth[0], truth[1], truth[2]];
    let edge_length = first_edge_length(&first);
    let r = tip_radius(edge_length);
    let angles = AngleTable::new(bits);
    let mut positions = first.to_vec();
    let mut codes = Vec::new();
    for (t, tri) in triangles.iter().enumerate().skip(1) {
        if tri[0] as usize != positions.len() {
            continue;
        }
        let prev = ordered.vertex(ordered.opposite(crate::CornerId(3 * t as u32)));
        let [gl, gr, tip] = [tri[1], tri[2], prev.0].map(|v| positions[v as usize]);
        let frame = Frame::new(gl, gr, tip, r);
        let q = quantize(bits, frame.angle(truth[tri[0] as usize]));
        codes.push(q);
        positions.push(frame.point(&angles, q));
    }
    Retiled {
        angle_bits: bits,
        first,
        triangles,
        positions,
        symbols: eb.connectivity.symbols,
        codes,
        edge_length,
    }
}

fn bumpy(levels: u32) -> TriMesh {
    sphere(levels, |d| {
        1.0 + 0.15 * (3.0 * d[0]).sin() * (4.0 * d[1]).sin()
    })
}

fn flat_icosahedron(levels: u32) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let (p, f) = subdivided(icosahedron(t), levels, |a, b| {
        core::array::from_fn(|k| (a[k] + b[k]) / 2.0)
    });
    TriMesh::new(p.iter().map(|q| q.map(|c| c as f32)).collect(), f)
}

fn decode_bytes(bytes: &[u8]) -> Result<TriMesh, Error> {
    crate::decode(bytes, &crate::DecodeOptions::default())
}

// --- The angle table ---

#[test]
fn angle_table_matches_libm_and_is_symmetric() {
    for bits in MIN_ANGLE_BITS..=MAX_ANGLE_BITS {
        let a = AngleTable::new(bits);
        let n = a.codes();
        assert_eq!((a.bits(), n), (bits, 1 << bits));
        let step = core::f64::consts::TAU / n as f64;
        for q in 0..n {
            let x = q as f64 * step;
            let (c, s) = (a.cos(q), a.sin(q));
            assert!(
                (c - x.cos()).abs() <= 1e-15,
                "K={bits} q={q}: cos {c} vs {}",
                x.cos()
            );
            assert!(
                (s - x.sin()).abs() <= 1e-15,
                "K={bits} q={q}: sin {s} vs {}",
                x.sin()
            );
            let m = (n - q) % n;
            assert!(
                a.cos(m) == c && a.sin(m) == -s,
                "K={bits} q={q}: not symmetric"
            );
            // A quarter turn swaps cosine and sine exactly.
            let r = (q + n / 4) % n;
            assert!(
                a.cos(r) == -s && a.sin(r) == c,
                "K={bits} q={q}: quarter turn"
            );
        }
        assert_eq!((a.cos(0), a.sin(0)), (1.0, 0.0));
        assert_eq!((a.cos(n / 2), a.sin(n / 2).abs()), (-1.0, 0.0));
        assert_eq!(a.cos(n / 8), a.sin(n / 8));
    }
}

#[test]
fn angle_table_is_the_recipe_of_the_spec() {
    // Bit patterns from an independent implementation of the recipe in
    // format-spec/05-swing.md (Python, binary64): a platform `sin`/`cos`
    // or another operation order would not give exactly these.
    let pins: [(u8, u32, u64, u64); 10] = [
        (8, 1, 0x3FEFFD886084CD0D, 0x3F992155F7A3667E),
        (8, 13, 0x3FEE6288EC48E112, 0x3FD4135C94176602),
        (8, 31, 0x3FE72D0837EFFF97, 0x3FE610B7551D2CDE),
        (8, 100, 0xBFE8BC806B151741, 0x3FE44CF325091DD6),
        (8, 255, 0x3FEFFD886084CD0D, 0xBF992155F7A3667E),
        (12, 1, 0x3FEFFFFD88586EE6, 0x3F5921FAAEE6472D),
        (12, 333, 0x3FEBEA424837DE6D, 0x3FDF49F4A7E97729),
        (12, 1000, 0x3FA2D865759455CD, 0x3FEFFA72EFFEF75D),
        (12, 2049, 0xBFEFFFFD88586EE6, 0xBF5921FAAEE6472D),
        (12, 4000, 0x3FEFA7557F08A517, 0xBFC2C8106E8E613A),
    ];
    assert_eq!(tip_radius(1.0).to_bits(), 0x3FEBB67AE8584CAA); // √3/2
    assert_eq!(AngleTable::new(8).cos(32).to_bits(), 0x3FE6A09E667F3BCD); // √½
    for (bits, q, c, s) in pins {
        let a = AngleTable::new(bits);
        let got = (a.cos(q).to_bits(), a.sin(q).to_bits());
        assert_eq!(
            got,
            (c, s),
            "K={bits} q={q}: {:#018X} {:#018X}",
            got.0,
            got.1
        );
    }
}

// --- The frame ---

#[test]
fn tips_are_the_arithmetic_of_the_spec() {
    // Bit patterns from an independent implementation of the spec's
    // frame and tip (Python, binary64): a chain of three tips and one
    // degenerate frame (previous tip on the gate's line).
    let first = [[0.1f32, 0.2, 0.3], [0.9, 0.25, 0.35], [0.5, 0.9, 0.1]].map(|p| p.map(f64::from));
    let l = first_edge_length(&first);
    let r = tip_radius(l);
    assert_eq!(
        (l.to_bits(), r.to_bits()),
        (0x3FEA94C93DB88482, 0x3FE7051E1CE20066)
    );
    let table = AngleTable::new(8);
    let mut x = first.to_vec();
    for (gl, gr, t, q) in [(0, 2, 1, 120), (3, 2, 0, 131), (3, 4, 2, 7)] {
        x.push(Frame::new(x[gl], x[gr], x[t], r).point(&table, q));
    }
    x.push(Frame::new([0.0; 3], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0], r).point(&table, 77));
    let want: [[u64; 3]; 4] = [
        [0xBFD381C642EBA534, 0x3FEA09B6EF9F8F51, 0xBFB63162A6390D40],
        [0x3FB5050D79A84598, 0x3FF8863E56843C58, 0xBFCE99974F393487],
        [0x3FE0AEC9A2453AE6, 0x3FEBA536FE4B72C0, 0xBF907DF2A61A6628],
        [0x3FEF74BE8187D619, 0x3F91682FCF053CE0, 0xBFCCE240EA5AF39D],
    ];
    for (k, w) in want.iter().enumerate() {
        assert_eq!(x[3 + k].map(f64::to_bits), *w, "tip {k}");
    }
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn minus(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Some gates with their previous tips, in general position.
fn gates() -> Vec<([f64; 3], [f64; 3], [f64; 3])> {
    let mut out = Vec::new();
    let mut rng = crate::mesh::test_rng::Rng(0x2545_f491_4f6c_dd1d);
    let mut rand = move || rng.unit() * 2.0 - 1.0;
    for _ in 0..200 {
        let p: [[f64; 3]; 3] = core::array::from_fn(|_| [rand(), rand(), rand()].map(|c| 10.0 * c));
        out.push((p[0], p[1], p[2]));
    }
    out.push(([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
    out
}

#[test]
fn flat_angle_lies_in_the_previous_plane_on_the_far_side() {
    let table = AngleTable::new(8);
    for (gl, gr, t) in gates() {
        let r = tip_radius(norm(minus(gr, gl)));
        let f = Frame::new(gl, gr, t, r);
        let x = f.point(&table, 128);
        let normal = cross(minus(gr, t), minus(gl, t));
        let unit = normal.map(|c| c / norm(normal));
        let scale = norm(minus(gr, gl)) + norm(minus(t, gl));
        assert!(
            dot3(minus(x, t), unit).abs() < 1e-12 * scale,
            "not in the plane"
        );
        assert!(
            dot3(minus(x, f.m), minus(t, f.m)) < 0.0,
            "not on the far side"
        );
        assert!(
            (norm(minus(x, f.m)) - r).abs() < 1e-12 * scale,
            "not at distance r"
        );
        assert!((norm(minus(x, gl)) - norm(minus(x, gr))).abs() < 1e-12 * scale);
        // n is the previous triangle's outward normal; δ < π bends inwards.
        assert!((dot3(f.n, unit) - 1.0).abs() < 1e-12);
        assert!(
            dot3(minus(f.point(&table, 100), f.m), unit) < 0.0,
            "convex side"
        );
        assert!(
            dot3(minus(f.point(&table, 156), f.m), unit) > 0.0,
            "concave side"
        );
    }
}

#[test]
fn angle_of_a_point_quantizes_back_to_its_code() {
    for bits in [4, 8, 12] {
        let table = AngleTable::new(bits);
        for (gl, gr, t) in gates() {
            let f = Frame::new(gl, gr, t, 1.7);
            for q in 0..table.codes() {
                assert_eq!(quantize(bits, f.angle(f.point(&table, q))), q, "K={bits}");
            }
        }
    }
    // Any range of δ: whole turns are dropped, the grid is anchored at 0.
    assert_eq!(quantize(8, -core::f64::consts::PI / 128.0), 255);
    assert_eq!(quantize(8, 5.0 * core::f64::consts::TAU), 0);
    assert_eq!(quantize(8, f64::NAN), 0);
}

#[test]
fn degenerate_frames_fall_back_and_hostile_ones_give_no_panic() {
    let table = AngleTable::new(8);
    // The previous tip on the gate's line: u is the fallback axis.
    let f = Frame::new([0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0], 1.0);
    let e = [0.5f64.sqrt(), 0.5f64.sqrt(), 0.0];
    assert_eq!(f.u, [0.0, 0.0, 1.0]); // z is least parallel to e
    assert!(dot3(f.n, e).abs() < 1e-15 && (norm(f.n) - 1.0).abs() < 1e-15);
    assert!(f.point(&table, 7).iter().all(|c| c.is_finite()));
    // A zero gate gives non-finite points, never a panic.
    let z = Frame::new([1.0; 3], [1.0; 3], [0.0; 3], 1.0);
    assert!(z.point(&table, 3).iter().any(|c| !c.is_finite()));
    let nan = Frame::new([f64::NAN; 3], [1.0; 3], [0.0; 3], 1.0);
    assert!(nan.point(&table, 3).iter().any(|c| !c.is_finite()));
}

// --- Files ---

fn test_meshes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("icosphere", crate::edgebreaker::tests_support::icosphere()),
        ("icosahedron-3", flat_icosahedron(3)),
        ("sphere-4", sphere(4, |_| 1.0)),
        ("bumpy-5", bumpy(5)),
    ]
}

#[test]
fn emulated_retilings_roundtrip_bit_for_bit() {
    for (name, mesh) in test_meshes() {
        for bits in [4, 8, 12] {
            let r = emulate(&mesh, bits);
            let (bytes, stats) = write(&r).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(write(&r).unwrap().0, bytes, "{name}: not deterministic");
            let out = decode_bytes(&bytes).unwrap_or_else(|e| panic!("{name} K={bits}: {e}"));
            assert_eq!(out.triangles, r.triangles, "{name}: triangles differ");
            assert_eq!(out.positions.len(), r.positions.len());
            for (k, (p, x)) in out.positions.iter().zip(&r.positions).enumerate() {
                let want = x.map(|c| (c as f32).to_bits());
                assert_eq!(p.map(f32::to_bits), want, "{name} K={bits}: vertex {k}");
            }
            // inspect reads the same figures without decoding geometry.
            let info = crate::inspect(&bytes, &crate::Limits::default()).unwrap();
            assert_eq!(info.mode, crate::Mode::Swing);
            assert_eq!(info.swing.as_ref(), Some(&stats), "{name}: inspect differs");
            assert_eq!(stats.file_bytes, bytes.len());
            assert_eq!(stats.angle_bits, bits);
            assert_eq!(stats.edge_length, r.edge_length);
            assert_eq!(stats.vertices, r.positions.len() as u64);
            assert_eq!(stats.triangles, r.triangles.len() as u64);
            assert_eq!(stats.clers[0], r.codes.len() as u64);
            assert_eq!(info.stats.clers, stats.clers);
            if bits == 8 {
                println!(
                    "{name}: {} triangles, {} angles, {:.3} bits/angle, connectivity {:.3} \
                     and geometry {:.3} bits/triangle, {} bytes, C+R {:.3}, valence 6 {:.3}",
                    stats.triangles,
                    r.codes.len(),
                    stats.bits_per_angle,
                    stats.connectivity_bits_per_triangle,
                    stats.geometry_bits_per_triangle,
                    stats.file_bytes,
                    stats.cr_share,
                    stats.valence6_share
                );
            }
        }
    }
}

#[test]
fn file_size_obeys_the_thesis_bound() {
    // bits <= 288 + 5.83·T + allowance (format-spec/05-swing.md).
    for (name, mesh) in test_meshes() {
        let r = emulate(&mesh, 8);
        let (bytes, stats) = write(&r).unwrap();
        let bound = 288.0 + 5.83 * stats.triangles as f64 + 8.0 * 85.0;
        assert!(
            (8 * bytes.len()) as f64 <= bound,
            "{name}: {} bits > {bound}",
            8 * bytes.len()
        );
    }
}

#[test]
fn the_writer_refuses_an_inconsistent_retiling() {
    let good = emulate(&flat_icosahedron(2), 8);
    assert!(write(&good).is_ok());
    let mut bad = good.clone();
    bad.codes[5] ^= 1;
    assert!(write(&bad).is_err(), "positions no longer match the codes");
    let mut bad = good.clone();
    bad.codes.push(0);
    assert!(write(&bad).is_err(), "one code too many");
    let mut bad = good.clone();
    bad.positions[7][1] += 1e-9;
    assert!(write(&bad).is_err(), "moved vertex");
    let mut bad = good.clone();
    bad.first[0][0] += 1e-12;
    bad.positions[0] = bad.first[0];
    assert!(write(&bad).is_err(), "first vertex is not binary32");
    let mut bad = good.clone();
    bad.edge_length *= 1.0 + f64::EPSILON;
    assert!(write(&bad).is_err(), "edge length");
    let mut bad = good.clone();
    let other = bad
        .symbols
        .iter()
        .position(|&x| x != bad.symbols[0])
        .unwrap();
    bad.symbols.swap(0, other);
    assert!(write(&bad).is_err(), "symbols");
    let mut bad = good.clone();
    bad.triangles.swap(3, 4);
    assert!(write(&bad).is_err(), "triangle order");
    let mut bad = good.clone();
    bad.triangles[2] = [
        bad.triangles[2][1],
        bad.triangles[2][2],
        bad.triangles[2][0],
    ];
    assert!(write(&bad).is_err(), "tip corner");
    let mut bad = good.clone();
    bad.angle_bits = 13;
    assert!(matches!(write(&bad), Err(Error::Parameter(_))));
}

fn small_file() -> Vec<u8> {
    write(&emulate(&flat_icosahedron(1), 8)).unwrap().0
}

#[test]
fn truncated_and_flipped_files_are_errors() {
    let bytes = small_file();
    for cut in 0..bytes.len() {
        assert!(decode_bytes(&bytes[..cut]).is_err(), "prefix {cut} decoded");
    }
    for bit in 0..bytes.len() * 8 {
        let mut b = bytes.clone();
        b[bit / 8] ^= 1 << (bit % 8);
        assert!(
            decode_bytes(&b).is_err(),
            "bit {bit} flipped and still decoded"
        );
    }
}

#[test]
fn random_overwrites_with_valid_crc_never_panic() {
    let bytes = small_file();
    let mut rng = crate::mesh::test_rng::Rng(0x9e37_79b9_7f4a_7c15);
    let mut decoded = 0;
    for _ in 0..6000 {
        let b = crate::container::overwrite_randomly(&bytes, &mut rng);
        if let Ok(mesh) = decode_bytes(&b) {
            mesh.validate().unwrap();
            decoded += 1;
        }
        let _ = crate::inspect(&b, &crate::Limits::default());
    }
    // Damage to the angles alone still decodes (to other positions).
    assert!(decoded > 0);
}

use crate::container::Tag;

#[test]
fn hostile_sections_with_valid_frames_are_errors() {
    let bytes = small_file();
    let limits = crate::Limits::default();
    let file = crate::container::parse_container(&bytes, &limits).unwrap();
    let head = file.section(Tag::HEAD).unwrap().to_vec();
    let geom = file.section(Tag::GEOM).unwrap().to_vec();
    let topo = file.section(Tag::TOPO).unwrap().to_vec();
    let with_head = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut h = head.clone();
        f(&mut h);
        decode_bytes(&crate::container::with_section(&bytes, Tag::HEAD, &h))
    };
    assert!(with_head(&|_| {}).is_ok(), "the helper itself is sound");
    assert!(with_head(&|h| h[0] = 3).is_err(), "K below 4");
    assert!(with_head(&|h| h[0] = 13).is_err(), "K above 12");
    assert!(
        with_head(&|h| h[2] = 1).is_err(),
        "q_pred = 256 + … at K = 8"
    );
    assert!(with_head(&|h| h.push(0)).is_err(), "trailing byte");
    assert!(with_head(&|h| {
        h.pop();
    })
    .is_err());
    assert!(with_head(&|h| h[3..7].copy_from_slice(&f32::NAN.to_le_bytes())).is_err());
    assert!(with_head(&|h| h[3..7].copy_from_slice(&f32::INFINITY.to_le_bytes())).is_err());
    // Vertex 2 on vertex 0: a first gate of length zero.
    assert!(with_head(&|h| {
        let v0 = h[3..15].to_vec();
        h[27..39].copy_from_slice(&v0);
    })
    .is_err());
    // Huge coordinates: tips that overflow binary32 are refused.
    let huge = with_head(&|h| {
        for (k, x) in [3e38f32, 0.0, 0.0, 0.0, 1e38, 0.0, -3e38, 0.0, 0.0]
            .iter()
            .enumerate()
        {
            h[3 + 4 * k..7 + 4 * k].copy_from_slice(&x.to_le_bytes());
        }
    });
    assert!(matches!(
        huge,
        Err(Error::Format(FormatError {
            what: Malformed::NonFinite { .. },
            ..
        }))
    ));
    // GEOM: a word the encoder never wrote, a missing word, nothing.
    let mut longer = geom.clone();
    longer.extend_from_slice(&[0, 0, 0, 0]);
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::GEOM, &longer)).is_err());
    assert!(decode_bytes(&crate::container::with_section(
        &bytes,
        Tag::GEOM,
        &geom[..geom.len() - 4]
    ))
    .is_err());
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::GEOM, &[])).is_err());
    // TOPO with a dummy vertex: not a SwingWrapper file.
    let mut t = vec![topo[0], 1, 0, 0];
    t.truncate(4);
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::TOPO, &t)).is_err());
    // Sections missing.
    for tag in [Tag::HEAD, Tag::TOPO, Tag::CLRS, Tag::GEOM] {
        let owned: Vec<(Tag, Vec<u8>)> = file
            .sections()
            .filter(|s| s.tag != tag)
            .map(|s| (s.tag, s.bytes.to_vec()))
            .collect();
        let refs: Vec<(Tag, &[u8])> = owned.iter().map(|(t, b)| (*t, b.as_slice())).collect();
        let b = crate::container::write_container(&file.header, &refs).unwrap();
        assert!(decode_bytes(&b).is_err(), "{tag} missing");
    }
}

#[test]
fn absurd_counts_are_refused_before_allocating() {
    let bytes = small_file();
    // Header counts at offsets 9 (vertices), 13 (triangles), 17 (components).
    for (at, value) in [
        (9, u32::MAX),
        (13, u32::MAX),
        (13, 1 << 28),
        (17, 1 << 27),
        (17, 2),
        (9, 3),
    ] {
        let mut b = bytes.clone();
        b[at..at + 4].copy_from_slice(&value.to_le_bytes());
        crate::container::fix_crc(&mut b);
        assert!(decode_bytes(&b).is_err(), "count {value} at {at} accepted");
    }
}

#[test]
fn lossless_files_and_their_inspection_are_unchanged() {
    use crate::edgebreaker::tests_support::torus;
    let options = crate::EncodeOptions::default();
    let enc = crate::encode(&torus(8, 5), &options).unwrap();
    let info = crate::inspect(&enc.bytes, &crate::Limits::default()).unwrap();
    assert_eq!(
        (info.mode, info.qp, info.swing),
        (crate::Mode::Lossless, 12, None)
    );
    assert_eq!(Some(info.stats), enc.stats.lossless);
    let golden = include_bytes!("../../../format-spec/golden/lossless-v1.0.swm");
    let mesh = decode_bytes(golden).unwrap();
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (48, 94));
}

// --- Measurement (run with --ignored --nocapture) ---

/// Bits per angle of the format's coding against the alternatives the
/// module docs of `residual` cite, on emulated retilings.
#[test]
#[ignore]
fn measure_residual_schemes() {
    use crate::entropy::{AdaptiveModel, ContextModel, Encoder};
    let noise = |d: [f64; 3]| {
        let h = (d[0] * 12.9898 + d[1] * 78.233 + d[2] * 37.719).sin() * 43758.5453;
        1.0 + 0.02 * (h - h.floor() - 0.5)
    };
    let meshes: Vec<(&str, TriMesh)> = vec![
        ("sphere-5", sphere(5, |_| 1.0)),
        ("bumpy-4", bumpy(4)),
        ("bumpy-6", bumpy(6)),
        (
            "ellipsoid-5",
            sphere(5, |d| {
                1.0 / (d[0] * d[0] + 4.0 * d[1] * d[1] + 9.0 * d[2] * d[2]).sqrt()
            }),
        ),
        ("noisy-6", sphere(6, noise)),
        ("icosahedron-3", flat_icosahedron(3)),
    ];
    for bits in [6u8, 8, 10] {
        for (name, mesh) in &meshes {
            let r = emulate(mesh, bits);
            let (codes, n) = (&r.codes, 1i64 << bits);
            let angles = AngleTable::new(bits);
            let pred = residual::predict(codes, &angles);
            let table = crate::edgebreaker::decode(
                &crate::edgebreaker::encode(
                    &CornerTable::new(&r.triangles, r.positions.len()).unwrap(),
                )
                .unwrap()
                .connectivity,
            )
            .unwrap();
            let format = residual::encode(&table, codes, bits, pred).unwrap().len();
            // One adaptive model over all 2^K residuals.
            let mut enc = Encoder::new();
            let mut m = AdaptiveModel::new(1 << bits);
            for &q in codes {
                enc.encode(
                    &mut m,
                    (i64::from(q) - i64::from(pred)).rem_euclid(n) as u32,
                );
            }
            let direct = enc.finish().len();
            // The same binarization with the previous angle's length as context.
            let mut enc = Encoder::new();
            let mut len = ContextModel::new(bits as usize + 1, bits as u32 + 1);
            let mut man: Vec<AdaptiveModel> = (0..=bits)
                .map(|l| AdaptiveModel::new(if l <= 2 { 2 } else { 4 }))
                .collect();
            let mut prev = 0;
            for &q in codes {
                let mut s = (i64::from(q) - i64::from(pred)).rem_euclid(n);
                if s >= n / 2 {
                    s -= n;
                }
                let z = if s >= 0 { 2 * s } else { -2 * s - 1 } as u32;
                let l = 32 - z.leading_zeros();
                enc.encode(len.get(prev), l);
                if l >= 2 {
                    let top = (l - 1).min(2);
                    let below = l - 1 - top;
                    enc.encode(&mut man[l as usize], (z >> below) & ((1 << top) - 1));
                    if below > 0 {
                        enc.encode_bits(z & ((1 << below) - 1), below);
                    }
                }
                prev = l as usize;
            }
            let previous = enc.finish().len();
            let per = |b: usize| 8.0 * b as f64 / codes.len() as f64;
            println!(
                "K={bits} {name} ({} angles): format {:.3} | one model {:.3} | previous-length context {:.3} bits/angle",
                codes.len(),
                per(format),
                per(direct),
                per(previous)
            );
        }
    }
}

#[test]
fn the_empty_mesh_is_a_valid_file() {
    use crate::container::{write_container, Header, Mode};
    let head = [8u8, 0, 0];
    let sections: [(Tag, &[u8]); 4] = [
        (Tag::HEAD, &head),
        (Tag::TOPO, &[0, 0, 0]),
        (Tag::CLRS, &[]),
        (Tag::GEOM, &[]),
    ];
    let bytes = write_container(&Header::new(Mode::Swing, 0, 0, 0), &sections).unwrap();
    let mesh = decode_bytes(&bytes).unwrap();
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (0, 0));
}
