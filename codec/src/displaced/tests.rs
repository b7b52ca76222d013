//! Mode 2 end to end: decode equals the encoder's reconstruction bit for
//! bit, every level cut decodes and is no farther from the input than
//! the coarser one, hostile headers are refused before any large
//! allocation, and encoding is deterministic.

use super::fit::{Fallback, Target};
use super::predict::Rule;
use super::write::{write, Plan, Settings, Written};
use crate::container::{fix_crc, parse_container, Framing, Mode};
use crate::metrics::{distance_between, DistanceOptions, Surface};
use crate::simplify::Simplifier;
use crate::{Error, Limits, TriMesh};

/// A bumpy sphere with a hole at its north pole: smooth enough for
/// subdivision to predict, curved enough for the scalars to matter.
fn input() -> TriMesh {
    let mut m = crate::mesh::test_shapes::uv_sphere(64, 48);
    for p in &mut m.positions {
        let (x, y, z) = (p[0], p[1], p[2]);
        let r = 1.0 + 0.08 * (5.0 * x).sin() * (4.0 * y).cos() + 0.05 * (3.0 * z).sin();
        *p = [x * r, y * r, z * r];
    }
    let keep: Vec<[u32; 3]> = m
        .triangles
        .iter()
        .copied()
        .filter(|t| t.iter().any(|&v| m.positions[v as usize][2] < 0.8))
        .collect();
    TriMesh::new(m.positions, keep)
}

fn plan(levels: usize, rule: Rule) -> Plan {
    Plan {
        levels,
        settings: Settings {
            rule,
            step_scale: 1.0 / 16.0,
            step_decay: 1.0,
            snap_base: true,
            reach_scale: 2.0,
            fallback: Fallback::Nearest,
            facing: true,
            qp: Some(12),
            qp_slack: 1.0,
            bend: true,
            bare_base: true,
            step_error: None,
        },
        framing: Framing::Compact,
        step: None,
    }
}

/// The file of `input()` from a base of `faces` faces.
fn written(faces: u32, plan: &Plan) -> (Written, Surface) {
    let mesh = input();
    let cleaned = crate::clean(&mesh, &Default::default()).unwrap();
    let s = Simplifier::new(&cleaned.mesh, Framing::Compact);
    let mut base = s.simplify(faces);
    s.refit(&mut base);
    let r = s.reference();
    let surface = Surface::new(r).unwrap();
    let target = Target { surface: &surface };
    (write(&base, &target, plan).unwrap(), surface)
}

fn decode(bytes: &[u8]) -> Result<TriMesh, Error> {
    crate::decoder::decode(bytes, &Default::default())
}

fn same_bits(a: &TriMesh, b: &TriMesh) -> bool {
    let bits =
        |m: &TriMesh| -> Vec<u32> { m.positions.iter().flatten().map(|c| c.to_bits()).collect() };
    a.triangles == b.triangles && bits(a) == bits(b)
}

#[test]
fn decode_is_the_encoders_reconstruction_bit_for_bit() {
    for rule in [Rule::Loop, Rule::Butterfly] {
        let (w, _) = written(300, &plan(3, rule));
        let file = parse_container(&w.bytes, &Limits::default()).unwrap();
        assert_eq!(file.header.mode, Mode::Displaced);
        assert_eq!((file.header.major, file.header.minor), (1, 2));
        let mesh = decode(&w.bytes).unwrap();
        assert!(same_bits(&mesh, &w.mesh), "{rule:?}");
        assert_eq!(mesh.triangles.len(), w.base_faces * 64);
        mesh.validate().unwrap();
        // The hole's rim made boundary edges; none of them missed so
        // badly that no scalar moved anything.
        assert!(w.level_bytes.iter().all(|&b| b > 0));
    }
}

/// Decoding into buffers (the finest level placed and split straight
/// into them) gives the owned decode's bits at every `max_level`, for
/// both rules, and leaves the rest of the buffers as they were.
#[test]
fn decode_into_buffers_is_the_owned_decode_at_every_level() {
    for rule in [Rule::Loop, Rule::Butterfly] {
        let (w, _) = written(200, &plan(3, rule));
        for max_level in [None, Some(0), Some(1), Some(2), Some(3), Some(7)] {
            let o = crate::DecodeOptions {
                max_level,
                ..crate::DecodeOptions::plain()
            };
            let mesh = crate::decoder::decode(&w.bytes, &o).unwrap();
            let len = crate::decoded_len(&w.bytes, &o).unwrap();
            let mut p = vec![f32::NAN; len.position_floats() as usize];
            let mut i = vec![u32::MAX; len.index_count() as usize];
            let got = crate::decode_into_with(&w.bytes, &o, &mut p, &mut i).unwrap();
            let (v, t) = (mesh.positions.len(), mesh.triangles.len());
            let what = format!("{rule:?} {max_level:?}");
            assert_eq!(
                (got.vertices, got.triangles),
                (v as u64, t as u64),
                "{what}"
            );
            let bits = |x: &[f32]| x.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&p[..3 * v]),
                bits(mesh.positions.as_flattened()),
                "{what}"
            );
            assert_eq!(&i[..3 * t], mesh.triangles.as_flattened(), "{what}");
            assert!(p[3 * v..].iter().all(|x| x.is_nan()), "{what}");
            assert!(i[3 * t..].iter().all(|&x| x == u32::MAX), "{what}");
        }
    }
}

#[test]
fn every_level_cut_decodes_and_the_error_falls_level_by_level() {
    let (w, surface) = written(200, &plan(3, Rule::Loop));
    let mut last = f64::INFINITY;
    let mut triangles = w.base_faces;
    for levels in 0..=3 {
        let cut = crate::cut_levels(&w.bytes, levels, &Limits::default()).unwrap();
        let mesh = decode(&cut).unwrap();
        assert_eq!(mesh.triangles.len(), triangles, "level {levels}");
        triangles *= 4;
        let d = distance_between(
            &surface,
            &Surface::new(&mesh).unwrap(),
            &DistanceOptions::area_uniform(20_000),
        )
        .unwrap()
        .l2_relative();
        assert!(d <= last, "level {levels}: {d} after {last}");
        last = d;
        if levels == 3 {
            assert_eq!(cut, w.bytes, "all levels: the file itself");
        }
    }
}

#[test]
fn encoding_is_deterministic_at_any_thread_count() {
    let (w, _) = written(250, &plan(2, Rule::Butterfly));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (v, _) = pool.install(|| written(250, &plan(2, Rule::Butterfly)));
    assert_eq!(w.bytes, v.bytes);
}

#[test]
fn a_header_asking_for_4_to_the_k_is_refused_before_allocating() {
    let (w, _) = written(200, &plan(2, Rule::Loop));
    let file = parse_container(&w.bytes, &Limits::default()).unwrap();
    let base_t = u64::from(file.header.triangle_count) / 16;
    // Eight levels declared in HEAD and DISP (empty chunks), the header's
    // counts those of eight levels: far above small limits, refused by the
    // container before the mode runs.
    let mut head = vec![0u8, 8];
    for _ in 0..8 {
        head.extend_from_slice(&1.0f32.to_le_bytes());
    }
    let disp = [0u8; 8];
    let forged = crate::container::with_section(&w.bytes, crate::container::Tag::HEAD, &head);
    let forged = crate::container::with_section(&forged, crate::container::Tag::DISP, &disp);
    let mut header = parse_container(&forged, &Limits::default()).unwrap().header;
    let t = base_t << 16;
    header.triangle_count = t as u32;
    header.vertex_count = (t / 2) as u32;
    let f = parse_container(&forged, &Limits::default()).unwrap();
    let sections: Vec<(crate::container::Tag, &[u8])> =
        f.sections().map(|s| (s.tag, s.bytes)).collect();
    let b = crate::container::write_container(&header, &sections).unwrap();
    let small = Limits {
        max_faces: 1 << 20,
        ..Limits::default()
    };
    let options = crate::DecodeOptions {
        limits: small,
        ..Default::default()
    };
    let (r, largest) =
        crate::test_alloc::largest_allocation(|| crate::decoder::decode(&b, &options));
    assert!(matches!(r, Err(Error::LimitExceeded(_))), "{r:?}");
    assert!(largest < 1 << 16, "allocated {largest} bytes");
    // Within the default limits, the empty chunks cannot hold 4^8 × the
    // base's scalars: refused by the count rule, after the base decodes
    // but before the level's scalars are allocated.
    let (r, largest) = crate::test_alloc::largest_allocation(|| decode(&b));
    assert!(r.is_err());
    assert!(largest < 1 << 20, "allocated {largest} bytes");
    // Header counts that disagree with the base's: refused.
    let mut h2 = header;
    h2.triangle_count = (base_t * 16 + 1) as u32;
    let b2 = crate::container::write_container(&h2, &sections).unwrap();
    assert!(decode(&b2).is_err());
}

#[test]
fn damaged_files_are_refused_or_decode_never_panics() {
    let (w, _) = written(120, &plan(2, Rule::Butterfly));
    let mut rng = crate::mesh::test_rng::Rng(46);
    for _ in 0..400 {
        let b = crate::container::overwrite_randomly(&w.bytes, &mut rng);
        if let Ok(m) = decode(&b) {
            m.validate().unwrap();
        }
    }
    crate::container::assert_damage_refused(&w.bytes, true, decode);
    // A scalar chunk's last byte changed (CRC fixed): an error or a
    // valid mesh, never a panic.
    let mut b = w.bytes.clone();
    let n = b.len();
    b[n - 5] ^= 0x40;
    fix_crc(&mut b);
    if let Ok(m) = decode(&b) {
        m.validate().unwrap();
    }
}

/// Loop's scalars lean against their lifts on a curved surface: the
/// first of two levels gets a positive bend (a share of the way to the
/// midpoint; the finest of several is left unbent, for the decoder's
/// sake), the file says so in `HEAD`, decodes to the encoder's
/// reconstruction, and its first level costs fewer bytes than without.
/// With one level on this bumpy sphere no bend pays, and none is
/// written: a bend never makes a level's chunk larger.
#[test]
fn a_bend_takes_the_lean_out_of_loops_scalars() {
    let head = |bytes: &[u8]| {
        let file = parse_container(bytes, &Limits::default()).unwrap();
        super::Head::read(file.section(crate::container::Tag::HEAD).unwrap()).unwrap()
    };
    for levels in [1, 2] {
        let bent_plan = plan(levels, Rule::Loop);
        let mut flat_plan = plan(levels, Rule::Loop);
        flat_plan.settings.bend = false;
        let (bent, _) = written(300, &bent_plan);
        let (flat, _) = written(300, &flat_plan);
        let (hb, hf) = (head(&bent.bytes), head(&flat.bytes));
        println!(
            "bends {:?}, bytes {:?} against {:?}",
            hb.bends, bent.level_bytes, flat.level_bytes
        );
        assert_eq!(hf.bends, vec![0; levels]);
        assert!(same_bits(&decode(&bent.bytes).unwrap(), &bent.mesh));
        assert!(bent.level_bytes[0] <= flat.level_bytes[0]);
        if levels == 2 {
            assert!(hb.bends[0] > 0 && hb.bends[1] == 0, "{:?}", hb.bends);
            assert!(bent.level_bytes[0] < flat.level_bytes[0]);
        }
        // The file without bends is byte for byte what it was before
        // them: no flag, no codes (the rule byte, `K`, the steps).
        let file = parse_container(&flat.bytes, &Limits::default()).unwrap();
        let len = file.section(crate::container::Tag::HEAD).unwrap().len();
        assert_eq!(len, 2 + 4 * levels);
    }
}
