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
/// Edgebreaker order (one component after another), each component's
/// first three vertices rounded to f32, and every C tip replaced by the
/// point of its quantized angle, built on the already replaced positions
/// (so errors do not accumulate). Every component's tips use the radius
/// of component 0's first edge, as the decoder does.
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
    let edge_length = first_edge_length(&[truth[0], truth[1], truth[2]]);
    let r = tip_radius(edge_length);
    let angles = AngleTable::new(bits);
    let (mut positions, mut first, mut codes) = (Vec::new(), Vec::new(), Vec::new());
    for (t, tri) in triangles.iter().enumerate() {
        let next = positions.len();
        if tri[1] as usize >= next {
            let f = tri.map(|v| truth[v as usize]);
            first.push(f);
            positions.extend_from_slice(&f);
            continue;
        }
        if tri[0] as usize != next {
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
        steps: Vec::new(),
        stretch: Vec::new(),
        hole_mask: Vec::new(),
        rest: None,
        loops: Default::default(),
        loop_codes: Vec::new(),
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

/// 05-swing.md's frame, written out in the spec's order of operations
/// in one go, as `Frame::new` computed it before the decoder split it
/// into a radius-free `Hinge` and `Frame::on`.
fn frame_at_once(gl: [f64; 3], gr: [f64; 3], t: [f64; 3], r: f64) -> Frame {
    let unit = |v: [f64; 3]| {
        let s = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / s, v[1] / s, v[2] / s]
    };
    let m = [0, 1, 2].map(|a| (gl[a] + gr[a]) * 0.5);
    let e = unit([0, 1, 2].map(|a| gr[a] - gl[a]));
    let d = [0, 1, 2].map(|a| t[a] - m[a]);
    let k = d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
    let w = [0, 1, 2].map(|a| d[a] - k * e[a]);
    let u = if w[0] * w[0] + w[1] * w[1] + w[2] * w[2] > (r * r) * (1.0 / (1u64 << 40) as f64) {
        unit(w)
    } else {
        let mut i = 0;
        for a in 1..3 {
            if e[a].abs() < e[i].abs() {
                i = a;
            }
        }
        unit([0, 1, 2].map(|a| if a == i { 1.0 } else { 0.0 } - e[i] * e[a]))
    };
    let n = [
        u[1] * e[2] - u[2] * e[1],
        u[2] * e[0] - u[0] * e[2],
        u[0] * e[1] - u[1] * e[0],
    ];
    Frame { m, u, n, r }
}

#[test]
fn a_hinge_finished_with_its_radius_is_the_frame_bit_for_bit() {
    let same = |a: &Frame, b: &Frame| {
        let bits = |f: &Frame| [f.m, f.u, f.n].map(|v| v.map(f64::to_bits));
        bits(a) == bits(b) && a.r.to_bits() == b.r.to_bits()
    };
    // Pseudo-random gates (a fixed linear congruential sequence), plus
    // previous tips on the gate's line and within 2^-20 r of it, where
    // the radius decides between u and the fallback axis.
    let mut x = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((x >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 2.0
    };
    for _ in 0..2000 {
        let gl = [next(), next(), next()];
        let gr = [next(), next(), next()];
        let t = [next(), next(), next()];
        let on_line = [0, 1, 2].map(|a| gl[a] + 0.3 * (gr[a] - gl[a]));
        let near_line = [0, 1, 2].map(|a| on_line[a] + if a == 2 { 1e-7 } else { 0.0 });
        for t in [t, on_line, near_line] {
            for r in [0.01, 0.5, 1.7, 1e3] {
                let hinge = super::angle::Hinge::new(gl, gr, t);
                assert!(same(&Frame::on(&hinge, r), &frame_at_once(gl, gr, t, r)));
                assert!(same(
                    &Frame::new(gl, gr, t, r),
                    &frame_at_once(gl, gr, t, r)
                ));
            }
        }
    }
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

/// `CLRF` follows Edgebreaker on every emulated mesh, handles (the
/// torus: S* and skipped gates) and several components included, and
/// decodes to the mesh `CLRS` decodes to.
#[test]
fn front_coded_symbols_decode_to_the_clrs_mesh() {
    use crate::edgebreaker::tests_support::{tetra, torus};
    let mut meshes = test_meshes();
    meshes.push(("torus-8x5", torus(8, 5)));
    meshes.push(("torus-3x3", torus(3, 3)));
    let mut two = torus(6, 4);
    let t = tetra();
    let base = two.positions.len() as u32;
    two.positions
        .extend(t.positions.iter().map(|p| [p[0] + 5.0, p[1], p[2]]));
    two.triangles
        .extend(t.triangles.iter().map(|f| f.map(|v| v + base)));
    meshes.push(("torus-and-tetrahedron", two));
    for (name, mesh) in meshes {
        let r = emulate(&mesh, 8);
        let front = write(&r, Clers::Front, Default::default()).unwrap().0;
        let plain = write(&r, Clers::Plain, Default::default()).unwrap().0;
        let best = write(&r, Clers::Smaller, Default::default()).unwrap().0;
        let plain_fixed = write(&r, Clers::Plain, crate::Framing::Fixed).unwrap().0;
        assert_eq!(best.len(), front.len().min(plain.len()), "{name}");
        let file = crate::container::parse_container(&front, &crate::Limits::default()).unwrap();
        assert!(
            file.find(Tag::CLRF).is_some(),
            "{name}: the pass did not follow"
        );
        assert!(file.find(Tag::CLRS).is_none(), "{name}: both sections");
        assert_eq!((file.header.major, file.header.minor), (1, 1), "{name}");
        let plain_file =
            crate::container::parse_container(&plain_fixed, &crate::Limits::default()).unwrap();
        assert_eq!(
            plain_file.header.minor, 0,
            "{name}: fixed CLRS files stay 1.0"
        );
        assert_eq!(
            decode_bytes(&plain_fixed).unwrap(),
            decode_bytes(&plain).unwrap()
        );
        let (a, b) = (decode_bytes(&front).unwrap(), decode_bytes(&plain).unwrap());
        assert_eq!(a, b, "{name}: the two files decode differently");
        assert_eq!(a.triangles, r.triangles, "{name}");
        println!(
            "{name}: {} bytes with CLRF, {} with CLRS",
            front.len(),
            plain.len()
        );
    }
}

/// The `CLRF` pass is the whole decoder of a `CLRF` file: on every
/// emulated mesh, handles and a masked disk included, the triangles it
/// builds are those of connectivity decoding (`CLRS`'s corner table) in
/// the same order, its positions those of the rebuilding pass, and the
/// `HOLE` bits it reads in place (contexts from the front) those the
/// table's contexts give.
#[test]
fn the_pass_builds_the_tables_mesh_and_reads_the_mask_in_place() {
    use crate::edgebreaker::tests_support::torus;
    let limits = crate::Limits::default();
    let mut meshes = test_meshes();
    meshes.push(("torus-8x5", torus(8, 5)));
    let mut masked_files = 0;
    for (name, mesh) in meshes {
        let mut r = emulate(&mesh, 8);
        r.hole_mask = disk_mask(&r, [0.3, -0.5, 0.8], 40.0);
        let bytes = write(&r, Clers::Front, Default::default()).unwrap().0;
        let file = crate::container::parse_container(&bytes, &limits).unwrap();
        assert!(
            file.find(Tag::CLRF).is_some(),
            "{name}: the pass did not follow"
        );
        let hole = file.find(Tag::HOLE);
        masked_files += usize::from(hole.is_some());
        let (head, _, table, _) = read::read_connectivity(&file, &limits).unwrap();
        let (_, pass, _) = read::read_forward(&file, &limits, &head, true, false).unwrap();
        assert_eq!(pass.triangles, table.triangles(), "{name}");
        assert_eq!(pass.triangles, r.triangles, "{name}");
        let bits = |x: &[[f64; 3]]| x.iter().flatten().map(|c| c.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&pass.positions), bits(&r.positions), "{name}");
        let from_table = hole.map(|s| super::hole::decode(&table, s.bytes).unwrap());
        assert_eq!(pass.mask, from_table, "{name}");
        let plain = write(&r, Clers::Plain, Default::default()).unwrap().0;
        assert_eq!(
            decode_bytes(&bytes).unwrap(),
            decode_bytes(&plain).unwrap(),
            "{name}: CLRF and CLRS decode differently"
        );
    }
    assert!(masked_files >= 3, "only {masked_files} files had a HOLE");
}

/// A file may carry its symbols in one section only.
#[test]
fn a_file_with_both_clrs_and_clrf_is_an_error() {
    let front = small_file_with(true);
    let plain = small_file_with(false);
    let limits = crate::Limits::default();
    let clrs = crate::container::parse_container(&plain, &limits)
        .unwrap()
        .section(Tag::CLRS)
        .unwrap()
        .to_vec();
    let file = crate::container::parse_container(&front, &limits).unwrap();
    let mut owned: Vec<(Tag, Vec<u8>)> =
        file.sections().map(|s| (s.tag, s.bytes.to_vec())).collect();
    owned.push((Tag::CLRS, clrs));
    let refs: Vec<(Tag, &[u8])> = owned.iter().map(|(t, b)| (*t, b.as_slice())).collect();
    let both = crate::container::write_container(&file.header, &refs).unwrap();
    assert!(decode_bytes(&both).is_err());
}

#[test]
fn emulated_retilings_roundtrip_bit_for_bit() {
    for (name, mesh) in test_meshes() {
        for bits in [4, 8, 12] {
            let r = emulate(&mesh, bits);
            let (bytes, stats) = write(&r, Clers::Smaller, Default::default())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(
                write(&r, Clers::Smaller, Default::default()).unwrap().0,
                bytes,
                "{name}: not deterministic"
            );
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
        let (bytes, stats) = write(&r, Clers::Smaller, Default::default()).unwrap();
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
    assert!(write(&good, Clers::Smaller, Default::default()).is_ok());
    let mut bad = good.clone();
    bad.codes[5] ^= 1;
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "positions no longer match the codes"
    );
    let mut bad = good.clone();
    bad.codes.push(0);
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "one code too many"
    );
    let mut bad = good.clone();
    bad.positions[7][1] += 1e-9;
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "moved vertex"
    );
    let mut bad = good.clone();
    bad.first[0][0][0] += 1e-12;
    bad.positions[0] = bad.first[0][0];
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "first vertex is not binary32"
    );
    let mut bad = good.clone();
    bad.edge_length *= 1.0 + f64::EPSILON;
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "edge length"
    );
    let mut bad = good.clone();
    let other = bad
        .symbols
        .iter()
        .position(|&x| x != bad.symbols[0])
        .unwrap();
    bad.symbols.swap(0, other);
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "symbols"
    );
    let mut bad = good.clone();
    bad.triangles.swap(3, 4);
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "triangle order"
    );
    let mut bad = good.clone();
    bad.triangles[2] = [
        bad.triangles[2][1],
        bad.triangles[2][2],
        bad.triangles[2][0],
    ];
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "tip corner"
    );
    let mut bad = good.clone();
    bad.angle_bits = 13;
    assert!(matches!(
        write(&bad, Clers::Smaller, Default::default()),
        Err(Error::Parameter(_))
    ));
}

fn small_file() -> Vec<u8> {
    small_file_with(true)
}

/// The small file with its symbols in `CLRF` (`front`) or in `CLRS`.
fn small_file_with(front: bool) -> Vec<u8> {
    write(
        &emulate(&flat_icosahedron(1), 8),
        if front { Clers::Front } else { Clers::Plain },
        Default::default(),
    )
    .unwrap()
    .0
}

#[test]
fn truncated_and_flipped_files_are_errors() {
    for front in [false, true] {
        crate::container::assert_damage_refused(&small_file_with(front), true, decode_bytes);
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
    for front in [false, true] {
        hostile_sections(front);
    }
}

fn hostile_sections(front: bool) {
    let bytes = small_file_with(front);
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
    let clers = if front { Tag::CLRF } else { Tag::CLRS };
    for tag in [Tag::HEAD, Tag::TOPO, clers, Tag::GEOM] {
        let owned: Vec<(Tag, Vec<u8>)> = file
            .sections()
            .filter(|s| s.tag != tag)
            .map(|s| (s.tag, s.bytes.to_vec()))
            .collect();
        let refs: Vec<(Tag, &[u8])> = owned.iter().map(|(t, b)| (*t, b.as_slice())).collect();
        let b = crate::container::write_container(&file.header, &refs).unwrap();
        assert!(decode_bytes(&b).is_err(), "{tag} missing");
    }
    // Mode 0's positions section (1.1) has no meaning here.
    let mut refs: Vec<(Tag, &[u8])> = file.sections().map(|s| (s.tag, s.bytes)).collect();
    refs.push((Tag::GEOF, &[]));
    let b = crate::container::write_container(&file.header, &refs).unwrap();
    assert!(decode_bytes(&b).is_err(), "GEOF in a SwingWrapper file");
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
        let (result, largest) = crate::test_alloc::largest_allocation(|| decode_bytes(&b));
        assert!(result.is_err(), "count {value} at {at} accepted");
        // The file's own decode allocates a few KiB at most.
        assert!(
            largest < 1 << 20,
            "count {value} at {at}: {largest} bytes allocated at once"
        );
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
    assert_eq!(Some(&info.stats), enc.stats.lossless());
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

// --- Several components, the hole mask, the lossless remainder ---

/// `a` and `b` side by side in one mesh, `b` moved by `shift` along x.
fn concat(a: &TriMesh, b: &TriMesh, shift: f32) -> TriMesh {
    let n = a.vertex_count() as u32;
    let mut positions = a.positions.clone();
    positions.extend(b.positions.iter().map(|p| [p[0] + shift, p[1], p[2]]));
    let mut triangles = a.triangles.clone();
    triangles.extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
    TriMesh::new(positions, triangles)
}

/// Masks the triangles of `r` whose centroid's direction from the origin
/// is within `degrees` of `axis`: a disk on a sphere.
fn disk_mask(r: &Retiled, axis: [f64; 3], degrees: f64) -> Vec<bool> {
    let a = axis.map(|c| c / norm(axis));
    let cos = degrees.to_radians().cos();
    r.triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| r.positions[v as usize]);
            let c: [f64; 3] = core::array::from_fn(|k| p[0][k] + p[1][k] + p[2][k]);
            dot3(c, a) / norm(c) >= cos
        })
        .collect()
}

/// Masks the `n` triangles of `r` whose centroids' directions are
/// nearest `axis`: a disk of `n` triangles.
fn disk_of(r: &Retiled, axis: [f64; 3], n: usize) -> Vec<bool> {
    let a = axis.map(|c| c / norm(axis));
    let cos: Vec<f64> = r
        .triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| r.positions[v as usize]);
            let c: [f64; 3] = core::array::from_fn(|k| p[0][k] + p[1][k] + p[2][k]);
            dot3(c, a) / norm(c)
        })
        .collect();
    let mut order: Vec<usize> = (0..cos.len()).collect();
    order.sort_by(|&x, &y| cos[y].total_cmp(&cos[x]));
    let mut mask = vec![false; cos.len()];
    for &t in &order[..n] {
        mask[t] = true;
    }
    mask
}

/// Boundary loops of a mesh: `None` unless every boundary vertex has
/// exactly one outgoing and one incoming boundary edge.
fn boundary_loops(mesh: &TriMesh) -> Option<usize> {
    use std::collections::{HashMap, HashSet};
    let edges: HashSet<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    let mut next = HashMap::new();
    let mut incoming = HashSet::new();
    for &(a, b) in &edges {
        if !edges.contains(&(b, a)) && (next.insert(a, b).is_some() || !incoming.insert(b)) {
            return None;
        }
    }
    let mut seen = HashSet::new();
    let mut loops = 0;
    for &start in next.keys() {
        if seen.insert(start) {
            loops += 1;
            let mut v = next[&start];
            while v != start {
                seen.insert(v);
                v = *next.get(&v)?;
            }
        }
    }
    Some(loops)
}

/// What the decoder must output for `r` with its mask: the unmasked
/// triangles in order, the vertices they use renumbered in order, as f32.
fn expected_kept(r: &Retiled) -> TriMesh {
    let kept: Vec<[u32; 3]> = r
        .triangles
        .iter()
        .enumerate()
        .filter(|(t, _)| !r.hole_mask.get(*t).copied().unwrap_or(false))
        .map(|(_, t)| *t)
        .collect();
    let used: std::collections::BTreeSet<u32> = kept.iter().flatten().copied().collect();
    let new: std::collections::HashMap<u32, u32> = used
        .iter()
        .enumerate()
        .map(|(k, &v)| (v, k as u32))
        .collect();
    TriMesh {
        positions: used
            .iter()
            .map(|&v| r.positions[v as usize].map(|c| c as f32))
            .collect(),
        triangles: kept.iter().map(|t| t.map(|v| new[&v])).collect(),
    }
}

fn assert_same_bits(got: &TriMesh, want: &TriMesh, what: &str) {
    assert_eq!(got.triangles, want.triangles, "{what}: triangles differ");
    assert_eq!(
        got.positions.len(),
        want.positions.len(),
        "{what}: vertices"
    );
    for (k, (p, q)) in got.positions.iter().zip(&want.positions).enumerate() {
        assert_eq!(
            p.map(f32::to_bits),
            q.map(f32::to_bits),
            "{what}: vertex {k}"
        );
    }
}

/// Encodes `r`, checks that decoding and `inspect` agree with the writer,
/// returns the bytes, the stats and the decoded mesh.
fn roundtrip(r: &Retiled) -> (Vec<u8>, SwingStats, TriMesh) {
    let (bytes, stats) = write(r, Clers::Smaller, Default::default()).unwrap();
    assert_eq!(
        write(r, Clers::Smaller, Default::default()).unwrap().0,
        bytes,
        "not deterministic"
    );
    let out = decode_bytes(&bytes).unwrap();
    out.validate().unwrap();
    let info = crate::inspect(&bytes, &crate::Limits::default()).unwrap();
    assert_eq!(info.swing.as_ref(), Some(&stats), "inspect differs");
    (bytes, stats, out)
}

#[test]
fn two_components_roundtrip_bit_for_bit() {
    let mesh = concat(&sphere(3, |_| 1.0), &bumpy(2), 3.0);
    for bits in [4, 8, 12] {
        let r = emulate(&mesh, bits);
        assert_eq!(r.first.len(), 2);
        let (bytes, stats, out) = roundtrip(&r);
        assert_same_bits(&out, &expected_kept(&r), "two spheres");
        assert_eq!(stats.components, 2);
        assert_eq!(stats.edge_length, first_edge_length(&r.first[0]));
        assert_eq!((stats.hole_bytes, stats.rest_bytes), (0, 0));
        let file = crate::container::parse_container(&bytes, &crate::Limits::default()).unwrap();
        assert_eq!(file.header.component_count, 2);
        assert_eq!(file.section(Tag::HEAD).unwrap().len(), 3 + 36 * 2);
        assert_eq!(file.sections().count(), 4, "no HOLE or REST");
    }
    // The writer checks the second component's first vertices too.
    let good = emulate(&mesh, 8);
    let mut bad = good.clone();
    bad.first[1][2][1] = f64::from(bad.first[1][2][1] as f32 + 0.5);
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "second first triangle moved"
    );
    let mut bad = good.clone();
    bad.first.pop();
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "one first triangle missing"
    );
    let mut bad = good.clone();
    bad.first.push(bad.first[1]);
    assert!(
        write(&bad, Clers::Smaller, Default::default()).is_err(),
        "one first triangle too many"
    );
}

#[test]
fn a_masked_disk_is_dropped_by_the_decoder() {
    let mut r = emulate(&sphere(4, |_| 1.0), 8);
    r.hole_mask = disk_mask(&r, [0.3, -0.5, 0.8], 25.0);
    let masked = r.hole_mask.iter().filter(|&&m| m).count();
    assert!(masked > 100 && masked < r.triangles.len() / 4, "{masked}");
    let (bytes, stats, out) = roundtrip(&r);
    let want = expected_kept(&r);
    assert_same_bits(&out, &want, "masked sphere");
    assert_eq!(out.face_count(), r.triangles.len() - masked);
    assert!(out.vertex_count() < r.positions.len());
    assert_eq!(boundary_loops(&out), Some(1), "one boundary loop");
    // A sphere minus a disk is a disk: V − E + F = 1.
    let edges = (3 * out.face_count() + stats_boundary_edges(&out)) / 2;
    assert_eq!(out.vertex_count() + out.face_count(), edges + 1);
    assert_eq!(stats.holes_masked_triangles, masked as u64);
    let file = crate::container::parse_container(&bytes, &crate::Limits::default()).unwrap();
    assert_eq!(
        stats.hole_bytes,
        file.section(Tag::HOLE).unwrap().len() as u64
    );
    assert!(file.find(Tag::HOLE).unwrap().tag.is_critical());
    // The header keeps the coded (closed) mesh's counts.
    assert_eq!(file.header.triangle_count as usize, r.triangles.len());
    // An all-false mask writes no HOLE: the same bytes as no mask at all.
    let mut none = r.clone();
    none.hole_mask = vec![false; r.triangles.len()];
    let plain = write(
        &emulate(&sphere(4, |_| 1.0), 8),
        Clers::Smaller,
        Default::default(),
    )
    .unwrap()
    .0;
    assert_eq!(
        write(&none, Clers::Smaller, Default::default()).unwrap().0,
        plain
    );
    // A mask of the wrong length is the retiler's bug.
    none.hole_mask.pop();
    assert!(write(&none, Clers::Smaller, Default::default()).is_err());
}

fn stats_boundary_edges(mesh: &TriMesh) -> usize {
    let edges: std::collections::HashSet<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    edges
        .iter()
        .filter(|&&(a, b)| !edges.contains(&(b, a)))
        .count()
}

/// Edges between a masked and an unmasked triangle.
fn rim_edges(r: &Retiled) -> usize {
    let table = CornerTable::new(&r.triangles, r.positions.len()).unwrap();
    (0..3 * r.triangles.len())
        .filter(|&c| {
            let o = table.opposite(crate::CornerId(c as u32));
            r.hole_mask[c / 3] != r.hole_mask[o.idx() / 3]
        })
        .count()
        / 2
}

#[test]
fn a_small_hole_costs_little_and_nothing_away_from_its_rim() {
    // The same small disk (about 60 triangles) on spheres of 5,120 and
    // 81,920 triangles: the rim costs a few bits per edge, the 77,000
    // triangles away from it almost nothing. (A stream is whole 32-bit
    // words, so small masks cost in steps of 32 bits.)
    let mut costs = Vec::new();
    for levels in [4u32, 6] {
        let mut r = emulate(&sphere(levels, |_| 1.0), 8);
        r.hole_mask = disk_of(&r, [0.3, -0.5, 0.8], 60);
        let masked = r.hole_mask.iter().filter(|&&m| m).count();
        let rim = rim_edges(&r);
        let (bytes, stats, _) = roundtrip(&r);
        let bits = 8 * stats.hole_bytes;
        println!(
            "{} triangles, {masked} masked, {rim} rim edges: HOLE {} bytes, \
             {:.2} bits per rim edge, {:.4} bits per triangle, {:.2}% of {} bytes",
            r.triangles.len(),
            stats.hole_bytes,
            bits as f64 / rim as f64,
            bits as f64 / r.triangles.len() as f64,
            100.0 * stats.hole_bytes as f64 / bytes.len() as f64,
            bytes.len()
        );
        // At most 64 bits of coder termination and 6 bits per rim edge
        // (which include each context's first 16 symbols, coded before
        // its model adapts).
        assert!(
            bits <= 64 + 6 * rim as u64,
            "{bits} bits for {rim} rim edges"
        );
        costs.push((r.triangles.len(), bits));
    }
    let extra = (costs[1].0 - costs[0].0) as f64;
    let per = (costs[1].1 as f64 - costs[0].1 as f64) / extra;
    println!("away from the rim: {per:.5} bits per triangle");
    assert!(per < 0.002, "{per} bits per triangle away from the rim");
}

/// The lossless remainder of the tests: a closed torus and an open grid.
fn rest_mesh() -> TriMesh {
    use crate::edgebreaker::tests_support::{grid, torus};
    concat(&torus(8, 5), &grid(3, 2), 9.0)
}

#[test]
fn the_lossless_rest_follows_the_retiled_mesh() {
    let rest = rest_mesh();
    let mut r = emulate(&sphere(3, |_| 1.0), 8);
    r.hole_mask = disk_mask(&r, [1.0, 0.0, 0.0], 30.0);
    r.rest = Some((rest.clone(), 12));
    let (bytes, stats, out) = roundtrip(&r);
    let kept = expected_kept(&r);
    let (nv, nt) = (kept.vertex_count(), kept.face_count());
    assert_eq!(out.vertex_count(), nv + rest.vertex_count());
    assert_eq!(out.face_count(), nt + rest.face_count());
    let head = TriMesh {
        positions: out.positions[..nv].to_vec(),
        triangles: out.triangles[..nt].to_vec(),
    };
    assert_same_bits(&head, &kept, "retiled part");
    // REST's mesh is the lossless decoding: decoded vertex k is input
    // vertex source[k], within the quantization error.
    let table = CornerTable::new(&rest.triangles, rest.vertex_count()).unwrap();
    let (_, _, source) = crate::lossless::encode(&table, &rest, 12, Default::default()).unwrap();
    let step = rest.bbox_diagonal() / 4096.0;
    for (k, &s) in source.iter().enumerate() {
        let (p, q) = (out.positions[nv + k], rest.positions[s as usize]);
        let d = norm(core::array::from_fn(|a| f64::from(p[a]) - f64::from(q[a])));
        assert!(d <= step, "rest vertex {k}: {d} > {step}");
    }
    let canon = |t: [u32; 3]| {
        let k = (0..3).min_by_key(|&k| t[k]).unwrap();
        [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
    };
    let mut got: Vec<[u32; 3]> = out.triangles[nt..]
        .iter()
        .map(|t| canon(t.map(|v| source[(v as usize) - nv])))
        .collect();
    let mut want: Vec<[u32; 3]> = rest.triangles.iter().map(|&t| canon(t)).collect();
    got.sort();
    want.sort();
    assert_eq!(got, want, "REST's triangles");
    assert_eq!(stats.rest_triangles, rest.face_count() as u64);
    let file = crate::container::parse_container(&bytes, &crate::Limits::default()).unwrap();
    assert_eq!(
        stats.rest_bytes,
        file.section(Tag::REST).unwrap().len() as u64
    );
    // An empty rest mesh writes no REST.
    let mut r0 = r.clone();
    r0.rest = Some((TriMesh::default(), 12));
    r.rest = None;
    assert_eq!(
        write(&r0, Clers::Smaller, Default::default()).unwrap().0,
        write(&r, Clers::Smaller, Default::default()).unwrap().0
    );
}

#[test]
fn a_file_may_be_all_rest() {
    let r = Retiled {
        angle_bits: 8,
        first: Vec::new(),
        triangles: Vec::new(),
        positions: Vec::new(),
        symbols: Vec::new(),
        codes: Vec::new(),
        edge_length: 0.0,
        steps: Vec::new(),
        stretch: Vec::new(),
        hole_mask: Vec::new(),
        rest: Some((rest_mesh(), 10)),
        loops: Default::default(),
        loop_codes: Vec::new(),
    };
    let (_, stats, out) = roundtrip(&r);
    assert_eq!(out.face_count(), rest_mesh().face_count());
    assert_eq!((stats.components, stats.triangles), (0, 0));
}

/// A small file with both new sections: a masked disk and a tetrahedron
/// kept losslessly.
fn file_with_hole_and_rest() -> Vec<u8> {
    let mut r = emulate(&flat_icosahedron(1), 8);
    r.hole_mask = disk_mask(&r, [0.0, 0.0, 1.0], 40.0);
    assert!(r.hole_mask.contains(&true));
    r.rest = Some((crate::edgebreaker::tests_support::tetra(), 8));
    write(&r, Clers::Smaller, Default::default()).unwrap().0
}

#[test]
fn hostile_hole_and_rest_sections_are_errors() {
    let bytes = file_with_hole_and_rest();
    let limits = crate::Limits::default();
    assert!(decode_bytes(&bytes).is_ok());
    let file = crate::container::parse_container(&bytes, &limits).unwrap();
    let hole = file.section(Tag::HOLE).unwrap().to_vec();
    let rest = file.section(Tag::REST).unwrap().to_vec();
    let with = |tag: Tag, payload: &[u8]| {
        let b = crate::container::with_section(&bytes, tag, payload);
        let _ = crate::inspect(&b, &limits);
        decode_bytes(&b)
    };
    let is = |r: Result<TriMesh, Error>, what: Malformed| matches!(r, Err(Error::Format(FormatError { what: ref w, .. })) if *w == what);
    // HOLE: a word short, a word or a byte too many, nothing.
    assert!(with(Tag::HOLE, &hole[..hole.len() - 4]).is_err());
    let mut longer = hole.clone();
    longer.extend_from_slice(&[0, 0, 0, 0]);
    assert!(is(with(Tag::HOLE, &longer), Malformed::TrailingData));
    longer.truncate(hole.len() + 1);
    assert!(with(Tag::HOLE, &longer).is_err(), "not whole words");
    assert!(matches!(
        with(Tag::HOLE, &[]),
        Err(Error::Format(FormatError {
            what: Malformed::CountTooLarge { .. },
            ..
        }))
    ));
    // REST: a SwingWrapper file, garbage, nothing, a cut file.
    let nested_swing = Malformed::BadSyntax("REST does not hold a lossless (mode 0) file");
    assert!(is(with(Tag::REST, &small_file()), nested_swing));
    assert!(with(Tag::REST, &bytes).is_err(), "nested mode 1 with REST");
    assert!(with(Tag::REST, b"SWM\0garbage, not a file").is_err());
    assert!(with(Tag::REST, &[0x55; 64]).is_err());
    assert!(with(Tag::REST, &[]).is_err());
    // A damaged nested file is located in the outer one.
    let rest_at = file.find(Tag::REST).unwrap().offset as u64;
    match with(Tag::REST, &rest[..rest.len() - 1]) {
        Err(Error::Format(FormatError {
            what: Malformed::ChecksumMismatch { .. },
            at: Some(crate::Location::Byte(b)),
            ..
        })) => assert!(b >= rest_at, "located at {b}, before REST at {rest_at}"),
        other => panic!("cut REST: {other:?}"),
    }
    // A lossless file with a HOLE or REST section of its own.
    let nested = crate::container::parse_container(&rest, &limits).unwrap();
    for extra in [Tag::HOLE, Tag::REST] {
        let mut owned: Vec<(Tag, Vec<u8>)> = nested
            .sections()
            .map(|s| (s.tag, s.bytes.to_vec()))
            .collect();
        owned.push((extra, Vec::new()));
        let refs: Vec<(Tag, &[u8])> = owned.iter().map(|(t, b)| (*t, b.as_slice())).collect();
        let inner = crate::container::write_container(&nested.header, &refs).unwrap();
        let why = Malformed::BadSyntax("the file in REST has a HOLE or REST section");
        assert!(is(with(Tag::REST, &inner), why), "REST with {extra}");
    }
    // The whole output must fit the limits, REST's mesh included.
    let h = file.header;
    let tight = crate::Limits {
        max_faces: u64::from(h.triangle_count) + 3,
        ..limits
    };
    let options = crate::DecodeOptions {
        limits: tight,
        ..Default::default()
    };
    assert!(matches!(
        crate::decode(&bytes, &options),
        Err(Error::LimitExceeded(_))
    ));
}

#[test]
fn a_file_with_hole_and_rest_survives_damage() {
    let bytes = file_with_hole_and_rest();
    for cut in 0..bytes.len() {
        assert!(decode_bytes(&bytes[..cut]).is_err(), "prefix {cut} decoded");
    }
    let mut rng = crate::mesh::test_rng::Rng(0x51ed_2701_9e37_79b9);
    let mut decoded = 0;
    for _ in 0..6000 {
        let b = crate::container::overwrite_randomly(&bytes, &mut rng);
        if let Ok(mesh) = decode_bytes(&b) {
            mesh.validate().unwrap();
            decoded += 1;
        }
        let _ = crate::inspect(&b, &crate::Limits::default());
    }
    assert!(decoded > 0);
}

/// Bits of the hole mask under other contexts than the format's, on
/// masked disks (run with --ignored --nocapture): the figures the docs
/// of `hole` cite.
#[test]
#[ignore]
fn measure_hole_contexts() {
    use crate::entropy::{ContextModel, Encoder};
    type Ctx = fn(&CornerTable, usize, &[bool]) -> (usize, usize);
    // (context, number of contexts) from the bits of earlier triangles.
    fn across(table: &CornerTable, t: usize, k: usize) -> Option<usize> {
        let f = table.opposite(crate::CornerId((3 * t + k) as u32)).idx() / 3;
        (f < t).then_some(f)
    }
    fn parent_only(table: &CornerTable, t: usize, m: &[bool]) -> (usize, usize) {
        (across(table, t, 0).map_or(2, |p| usize::from(m[p])), 3)
    }
    fn format(table: &CornerTable, t: usize, m: &[bool]) -> (usize, usize) {
        let side = |k| across(table, t, k).is_some_and(|f| m[f]);
        let c = across(table, t, 0).map_or(4, |p| {
            2 * usize::from(m[p]) + usize::from(side(1) || side(2))
        });
        (c, 5)
    }
    fn sideways_count(table: &CornerTable, t: usize, m: &[bool]) -> (usize, usize) {
        let side = |k| usize::from(across(table, t, k).is_some_and(|f| m[f]));
        let c = across(table, t, 0).map_or(6, |p| 3 * usize::from(m[p]) + side(1) + side(2));
        (c, 7)
    }
    fn sideways_known(table: &CornerTable, t: usize, m: &[bool]) -> (usize, usize) {
        // Sideways neighbours: masked / unmasked / not yet decoded, for
        // the parent's bit.
        let side = |k| across(table, t, k).map_or(0, |f| 1 + usize::from(m[f]));
        let s = side(1).max(side(2));
        let c = across(table, t, 0).map_or(6, |p| 3 * usize::from(m[p]) + s);
        (c, 7)
    }
    let schemes: [(&str, Ctx); 4] = [
        ("parent", parent_only),
        ("format", format),
        ("sideways count", sideways_count),
        ("sideways known", sideways_known),
    ];
    let mut cases = Vec::new();
    for (levels, degrees) in [(4u32, 10.0), (4, 25.0), (5, 15.0), (6, 2.5), (6, 30.0)] {
        let mut r = emulate(&sphere(levels, |_| 1.0), 8);
        r.hole_mask = disk_mask(&r, [0.3, -0.5, 0.8], degrees);
        cases.push((format!("sphere-{levels} disk {degrees}°"), r));
    }
    let mut r = emulate(&bumpy(5), 8);
    let a = disk_mask(&r, [1.0, 0.0, 0.0], 20.0);
    let b = disk_mask(&r, [-0.2, 1.0, 0.3], 12.0);
    r.hole_mask = a.iter().zip(&b).map(|(x, y)| x | y).collect();
    cases.push(("bumpy-5 two disks".to_string(), r));
    for (name, r) in &cases {
        let table = crate::edgebreaker::decode(
            &crate::edgebreaker::encode(
                &CornerTable::new(&r.triangles, r.positions.len()).unwrap(),
            )
            .unwrap()
            .connectivity,
        )
        .unwrap();
        let rim = rim_edges(r);
        let line: Vec<String> = schemes
            .iter()
            .map(|(scheme, ctx)| {
                let mut models = ContextModel::new(ctx(&table, 0, &[]).1, 2);
                let mut enc = Encoder::new();
                for (t, &bit) in r.hole_mask.iter().enumerate() {
                    let (c, _) = ctx(&table, t, &r.hole_mask[..t]);
                    enc.encode(models.get(c), u32::from(bit));
                }
                let bits = 8 * enc.finish().len();
                format!(
                    "{scheme} {bits} bits ({:.2}/rim edge)",
                    bits as f64 / rim as f64
                )
            })
            .collect();
        println!(
            "{name}: {} triangles, {rim} rim edges: {}",
            r.triangles.len(),
            line.join(" | ")
        );
    }
}

#[test]
fn first_triangles_are_exactly_those_without_an_earlier_parent() {
    // The HOLE contexts rely on it (format-spec/05-swing.md, "Contexts"):
    // f(O[3t]) < t for every triangle but the first of each component,
    // handles and several components included.
    use crate::edgebreaker::tests_support::torus;
    let two = concat(&torus(8, 5), &sphere(2, |_| 1.0), 9.0);
    for (name, mesh) in [("sphere", sphere(3, |_| 1.0)), ("torus + sphere", two)] {
        let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
        let conn = crate::edgebreaker::encode(&table).unwrap().connectivity;
        let decoded = crate::edgebreaker::decode(&conn).unwrap();
        let v = decoded.vertices();
        let mut next = 0;
        for t in 0..decoded.face_count() {
            let parent = decoded.opposite(crate::CornerId(3 * t as u32)).idx() / 3;
            let first = v[3 * t + 1].idx() >= next;
            assert_eq!(parent >= t, first, "{name}: triangle {t}");
            next += if first {
                3
            } else {
                usize::from(v[3 * t].idx() == next)
            };
        }
        assert_eq!(next, decoded.vertex_count());
    }
}
