//! Tests of the lossless mode: round trips, the sections' layouts, the
//! corpus meshes, hostile input.

use super::*;
use crate::varint;
use crate::CleanOptions;

use crate::io::shared_corpus_mesh as corpus;

/// Triangles as rotations starting at their smallest vertex, sorted:
/// equal lists mean the same triangles with the same orientations.
fn canonical(tris: impl Iterator<Item = [u32; 3]>) -> Vec<[u32; 3]> {
    let mut v: Vec<[u32; 3]> = tris
        .map(|t| {
            let k = (0..3).min_by_key(|&k| t[k]).unwrap();
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect();
    v.sort_unstable();
    v
}

/// decode(encode(M)) has exactly M's triangles (through the decoder's
/// vertex order), positions within half a step, and the connectivity
/// of the decoded mesh recompresses to the same symbols.
pub(crate) fn check_roundtrip(name: &str, mesh: &TriMesh, qp: u8) -> usize {
    let c = crate::clean(mesh, &CleanOptions::default()).unwrap();
    let (bytes, stats, source) = encode(&c.table, &c.mesh, qp, Framing::default()).unwrap();
    let again = encode(&c.table, &c.mesh, qp, Framing::default()).unwrap().0;
    assert_eq!(bytes, again, "{name}: encoding is not deterministic");
    let out = decode_bytes(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mapped = out.triangles.iter().map(|t| t.map(|v| source[v as usize]));
    assert_eq!(
        canonical(mapped),
        canonical(c.mesh.triangles.iter().copied()),
        "{name}: triangles differ"
    );
    let q = Quantizer::from_positions(&c.mesh.positions, qp).unwrap();
    let tol = q.step() / 2.0 * (1.0 + 1e-6) + f32::EPSILON as f64 * q.range as f64;
    for (k, p) in out.positions.iter().enumerate() {
        let o = c.mesh.positions[source[k] as usize];
        for a in 0..3 {
            let d = (p[a] as f64 - o[a] as f64).abs();
            assert!(d <= tol, "{name}: vertex {k} axis {a} off by {d} > {tol}");
        }
    }
    let table = CornerTable::new(&out.triangles, out.vertex_count()).unwrap();
    let filled = edgebreaker::fill_holes(&table);
    let closed = CornerTable::new(&filled.triangles, filled.vertex_count).unwrap();
    let recoded = edgebreaker::encode(&closed).unwrap().connectivity;
    let file = parse_container(&bytes, &Limits::default()).unwrap();
    let (_, coded, _, _) = read_connectivity(&file, &Limits::default()).unwrap();
    assert_eq!(
        recoded.symbols, coded.symbols,
        "{name}: recompression gives other symbols"
    );
    assert_eq!(stats.file_bytes, bytes.len());
    bytes.len()
}

#[test]
fn small_meshes_roundtrip() {
    use crate::edgebreaker::tests_support::*;
    check_roundtrip("tetra", &tetra(), 12);
    check_roundtrip("icosphere", &icosphere(), 8);
    check_roundtrip("torus", &torus(12, 7), 16);
    check_roundtrip("grid", &grid(9, 6), 24);
    check_roundtrip("grid-qp6", &grid(9, 6), 6);
}

#[test]
fn corpus_roundtrips() {
    for name in [
        "fandisk.obj",
        "stanford-bunny.obj",
        "horse.ply",
        "spot.obj",
        "homer.obj",
        "cheburashka.obj",
        "alligator.obj",
        "woody.obj",
        "bunny-1m.ply",
        "cow.obj",
        "teapot.obj",
        "beetle.obj",
        "suzanne.obj",
    ] {
        let Some(mesh) = corpus(name) else { return };
        let bytes = check_roundtrip(name, &mesh, 12);
        println!("{name}: {bytes} bytes at qp 12");
    }
}

#[test]
fn corrupt_files_are_errors() {
    use crate::edgebreaker::tests_support::*;
    let c = crate::clean(&torus(8, 5), &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
    crate::container::assert_damage_refused(&bytes, true, decode_bytes);
}

#[test]
fn random_overwrites_with_valid_crc_never_panic() {
    use crate::edgebreaker::tests_support::*;
    let c = crate::clean(&torus(10, 6), &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
    let mut rng = crate::mesh::test_rng::Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..4000 {
        let b = crate::container::overwrite_randomly(&bytes, &mut rng);
        if let Ok(mesh) = decode_bytes(&b) {
            mesh.validate().unwrap();
        }
    }
}

#[test]
fn absurd_counts_are_refused_before_allocating() {
    use crate::edgebreaker::tests_support::*;
    let c = crate::clean(&torus(10, 6), &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
    // Header counts at offsets 9 (vertices), 13 (triangles), 17 (components).
    for (at, value) in [
        (9, u32::MAX),
        (13, u32::MAX),
        (13, 1 << 28),
        (17, 1 << 27),
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
    // A TOPO section claiming 2^40 symbols: its first varu.
    let file = parse_container(&bytes, &Limits::default()).unwrap();
    let topo = file.find(Tag::TOPO).unwrap().offset;
    let mut b = bytes.clone();
    b[topo..topo + 6].copy_from_slice(&[0x80, 0x80, 0x80, 0x80, 0x80, 0x20]);
    crate::container::fix_crc(&mut b);
    let (result, largest) = crate::test_alloc::largest_allocation(|| decode_bytes(&b));
    assert!(result.is_err());
    assert!(
        largest < 1 << 20,
        "2^40 symbols: {largest} bytes allocated at once"
    );
}

#[test]
fn hostile_sections_with_valid_frames_are_errors() {
    use crate::edgebreaker::tests_support::*;
    let c = crate::clean(&grid(6, 4), &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
    let file = parse_container(&bytes, &Limits::default()).unwrap();
    let (clrs, topo) = (
        file.section(Tag::CLRS).unwrap().to_vec(),
        file.section(Tag::TOPO).unwrap().to_vec(),
    );
    // CLRS with a word the encoder never wrote.
    let mut longer = clrs.clone();
    longer.extend_from_slice(&[0, 0, 0, 0]);
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::CLRS, &longer)).is_err());
    // TOPO whose dummy gaps overflow 64 bits.
    let mut t = Vec::new();
    varint::put(&mut t, topo[0] as u64); // symbol count (one byte for this mesh)
    varint::put(&mut t, 2);
    varint::put(&mut t, u64::MAX);
    varint::put(&mut t, u64::MAX);
    varint::put(&mut t, 0);
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::TOPO, &t)).is_err());
    // A grid that does not fit in f32: origin 3e38, range 1e38.
    let mut head = vec![12u8];
    for x in [3e38f32, 0.0, 0.0, 1e38] {
        head.extend_from_slice(&x.to_le_bytes());
    }
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::HEAD, &head)).is_err());
    // The unmodified frame still decodes (the helper itself is sound).
    assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::CLRS, &clrs)).is_ok());
}

/// The section that holds the positions, and its size.
fn positions_tag(bytes: &[u8]) -> (Tag, usize) {
    let file = parse_container(bytes, &Limits::default()).unwrap();
    let s = file
        .sections()
        .find(|s| s.tag == Tag::GEOM || s.tag == Tag::GEOF)
        .unwrap();
    (s.tag, s.bytes.len())
}

#[test]
fn dense_meshes_take_geof_and_coarse_ones_keep_geom() {
    use crate::edgebreaker::tests_support::*;
    // About two grid steps between vertices: residuals are a step or
    // less, where the offsets' contexts pay.
    let dense = bumpy_sphere(5);
    let c = crate::clean(&dense, &CleanOptions::default()).unwrap();
    let (bytes, _, _) = encode(&c.table, &c.mesh, 8, Framing::Compact).unwrap();
    let (tag, geof) = positions_tag(&bytes);
    assert_eq!(tag, Tag::GEOF);
    let fixed = encode(&c.table, &c.mesh, 8, Framing::Fixed).unwrap().0;
    let (tag, geom) = positions_tag(&fixed);
    assert_eq!(tag, Tag::GEOM, "the fixed framing writes a 1.0 file");
    assert!(
        geof * 10 < geom * 9,
        "GEOF {geof} against GEOM {geom} bytes"
    );
    let (a, b) = (decode_bytes(&bytes).unwrap(), decode_bytes(&fixed).unwrap());
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.triangles, b.triangles);
    check_roundtrip("dense sphere", &dense, 8);
    // Coarse: hundreds of steps between vertices.
    let coarse = crate::clean(&torus(12, 7), &CleanOptions::default()).unwrap();
    let bytes = encode(&coarse.table, &coarse.mesh, 16, Framing::Compact)
        .unwrap()
        .0;
    assert_eq!(positions_tag(&bytes).0, Tag::GEOM);
}

#[test]
fn geof_is_checked_like_geom() {
    let c = crate::clean(&bumpy_sphere(3), &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 7, Framing::Compact).unwrap().0;
    assert_eq!(positions_tag(&bytes).0, Tag::GEOF);
    crate::container::assert_damage_refused(&bytes, true, decode_bytes);
    // Both position sections, or GEOF's payload read as GEOM's.
    let file = parse_container(&bytes, &Limits::default()).unwrap();
    let mut sections: Vec<(Tag, &[u8])> = file.sections().map(|s| (s.tag, s.bytes)).collect();
    let geof = sections.iter().find(|s| s.0 == Tag::GEOF).unwrap().1;
    sections.push((Tag::GEOM, geof));
    let both = write_container(&file.header, &sections).unwrap();
    assert!(matches!(
        decode_bytes(&both),
        Err(Error::Format(FormatError {
            what: Malformed::BadSyntax(_),
            ..
        }))
    ));
    sections.retain(|s| s.0 != Tag::GEOF);
    let renamed = write_container(&file.header, &sections).unwrap();
    assert!(decode_bytes(&renamed).is_err());
    sections.retain(|s| s.0 != Tag::GEOM);
    let none = write_container(&file.header, &sections).unwrap();
    assert!(decode_bytes(&none).is_err());
}

/// A dense smooth closed surface in general position: an icosphere
/// of `levels` subdivisions with smooth bumps, turned off the axes.
fn bumpy_sphere(levels: u32) -> TriMesh {
    use crate::edgebreaker::tests_support::*;
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let (p, f) = subdivided(icosahedron(t), levels, |a, b| {
        let m: [f64; 3] = core::array::from_fn(|k| a[k] + b[k]);
        let n = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        m.map(|c| c / n)
    });
    let (c1, s1, c2, s2) = (0.8f64.cos(), 0.8f64.sin(), 0.5f64.cos(), 0.5f64.sin());
    let p = p
        .iter()
        .map(|&[x, y, z]| {
            let r = 1.0 + 0.15 * (3.0 * x + 1.0).sin() * (2.0 * y).sin() * (2.5 * z).cos();
            let (x, y, z) = (x * r, y * r, z * r);
            let (x, y) = (c1 * x - s1 * y, s1 * x + c1 * y);
            let (y, z) = (c2 * y - s2 * z, s2 * y + c2 * z);
            [x as f32, y as f32, z as f32]
        })
        .collect();
    TriMesh::new(p, f)
}

/// The section that holds the symbols.
fn symbols_tag(bytes: &[u8]) -> Tag {
    let file = parse_container(bytes, &Limits::default()).unwrap();
    let s = file
        .sections()
        .find(|s| s.tag == Tag::CLRS || s.tag == Tag::CLRD)
        .unwrap();
    s.tag
}

/// Three dense spheres side by side: three components.
fn three_spheres() -> TriMesh {
    let one = bumpy_sphere(3);
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for k in 0..3u32 {
        let base = positions.len() as u32;
        positions.extend(
            one.positions
                .iter()
                .map(|p| [p[0] + 3.0 * k as f32, p[1], p[2]]),
        );
        triangles.extend(one.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    TriMesh::new(positions, triangles)
}

#[test]
fn regular_meshes_take_clrd_with_their_component_lengths() {
    let mesh = three_spheres();
    let c = crate::clean(&mesh, &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 8, Framing::Compact).unwrap().0;
    assert_eq!(symbols_tag(&bytes), Tag::CLRD);
    let fixed = encode(&c.table, &c.mesh, 8, Framing::Fixed).unwrap().0;
    assert_eq!(
        symbols_tag(&fixed),
        Tag::CLRS,
        "the fixed framing writes a 1.0 file"
    );
    let file = parse_container(&bytes, &Limits::default()).unwrap();
    let clrd = file.section(Tag::CLRD).unwrap().to_vec();
    let clrs = parse_container(&fixed, &Limits::default()).unwrap();
    let clrs = clrs.section(Tag::CLRS).unwrap().len();
    assert!(
        clrd.len() * 2 < clrs,
        "CLRD {} against CLRS {clrs} bytes",
        clrd.len()
    );
    check_roundtrip("three spheres", &mesh, 8);
    let (a, b) = (decode_bytes(&bytes).unwrap(), decode_bytes(&fixed).unwrap());
    assert_eq!(a.triangles, b.triangles);
    // Two component lengths (1,279 symbols each: 1,280 triangles less
    // the first), then the stream.
    assert_eq!(&clrd[..4], &[0xFF, 0x09, 0xFF, 0x09]);
    for (at, value) in [(0, 0xFD), (0, 0x80), (2, 0xFE), (1, 0x7F), (3, 0x0A)] {
        let mut d = clrd.clone();
        d[at] = value;
        let b = crate::container::with_section(&bytes, Tag::CLRD, &d);
        assert!(
            decode_bytes(&b).is_err(),
            "length byte {at} = {value:#x} accepted"
        );
    }
    // No lengths at all, or the stream alone.
    let b = crate::container::with_section(&bytes, Tag::CLRD, &clrd[4..]);
    assert!(decode_bytes(&b).is_err());
    let b = crate::container::with_section(&bytes, Tag::CLRD, &[]);
    assert!(decode_bytes(&b).is_err());
    // Both symbol sections, or neither.
    let mut sections: Vec<(Tag, &[u8])> = file.sections().map(|s| (s.tag, s.bytes)).collect();
    let clrs_bytes = write_clers(
        &read_connectivity(&file, &Limits::default())
            .unwrap()
            .1
            .symbols,
    );
    sections.push((Tag::CLRS, &clrs_bytes));
    let both = write_container(&file.header, &sections).unwrap();
    assert!(decode_bytes(&both).is_err());
    sections.retain(|s| s.0 != Tag::CLRS && s.0 != Tag::CLRD);
    let none = write_container(&file.header, &sections).unwrap();
    assert!(decode_bytes(&none).is_err());
    // CLRS's stream in CLRD's place (lengths and all).
    sections.push((Tag::CLRD, &clrs_bytes));
    let swapped = write_container(&file.header, &sections).unwrap();
    assert!(decode_bytes(&swapped).is_err());
}

#[test]
fn clrd_survives_hostile_bytes() {
    let c = crate::clean(&bumpy_sphere(2), &CleanOptions::default()).unwrap();
    let bytes = encode(&c.table, &c.mesh, 6, Framing::Compact).unwrap().0;
    assert_eq!(symbols_tag(&bytes), Tag::CLRD);
    crate::container::assert_damage_refused(&bytes, false, decode_bytes);
    let mut rng = crate::mesh::test_rng::Rng(0x5eed);
    for _ in 0..3000 {
        let b = crate::container::overwrite_randomly(&bytes, &mut rng);
        if let Ok(mesh) = decode_bytes(&b) {
            mesh.validate().unwrap();
        }
    }
}
