//! Round trips of attributed meshes through `ATTR`: values within half a
//! quantization step (normals within the octahedral grid's angle),
//! corners sharing a value exactly as in the input, hostile bytes.

use crate::mesh::test_shapes::{coloured_sphere, seamed_cube, textured_sphere};
use crate::{
    AttributeKind, AttributeStream, AttributedMesh, DecodeOptions, EncodeMode, EncodeOptions,
};

fn lossless(qp: u8) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Lossless { qp },
        ..Default::default()
    }
}

fn angle(a: &[f32], b: &[f32]) -> f64 {
    let dot: f64 = (0..3).map(|k| f64::from(a[k]) * f64::from(b[k])).sum();
    let n = |x: &[f32]| (0..3).map(|k| f64::from(x[k]).powi(2)).sum::<f64>().sqrt();
    (dot / n(a) / n(b)).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Encodes `input` (positions distinct, already clean), decodes it, and
/// checks every corner's value and which corners share one. Returns the
/// file.
pub(crate) fn check_round_trip(input: &AttributedMesh, options: &EncodeOptions) -> Vec<u8> {
    let EncodeMode::Lossless { qp } = options.mode else {
        panic!("lossless only")
    };
    let bytes = crate::encode_attributed(input, options).unwrap().bytes;
    let out = crate::decode_attributed(&bytes, &DecodeOptions::default()).unwrap();
    out.validate().unwrap();
    assert_eq!(
        out.mesh,
        crate::decode(&bytes, &DecodeOptions::default()).unwrap()
    );
    assert_eq!(out.streams.len(), input.streams.len());
    // Decoded corner -> input corner, by the grid points of the corners.
    let q = crate::geometry::Quantizer::from_positions(&input.mesh.positions, qp).unwrap();
    let key = |m: &crate::TriMesh, t: &[u32; 3]| t.map(|v| q.quantize(m.positions[v as usize]));
    let mut faces = std::collections::HashMap::new();
    for (f, t) in input.mesh.triangles.iter().enumerate() {
        let k = key(&input.mesh, t);
        for r in 0..3 {
            faces.insert([k[r], k[(r + 1) % 3], k[(r + 2) % 3]], (f, r));
        }
    }
    let map: Vec<(usize, usize)> = out
        .mesh
        .triangles
        .iter()
        .map(|t| faces[&key(&out.mesh, t)])
        .collect();
    for (s_in, s_out) in input.streams.iter().zip(&out.streams) {
        assert_eq!((s_in.kind, s_in.dims), (s_out.kind, s_out.dims));
        let bits = match s_in.kind {
            AttributeKind::Normal => options.attributes.normal_bits,
            AttributeKind::TexCoord(_) => options.attributes.texcoord_bits,
            AttributeKind::Color(_) => options.attributes.color_bits,
            _ => options.attributes.generic_bits,
        };
        // Half a step of the grid over the used values, plus f32 rounding.
        let d = usize::from(s_in.dims);
        let extent = (0..d)
            .map(|k| {
                let xs = s_in.values.iter().skip(k).step_by(d);
                let lo = xs.clone().fold(f32::INFINITY, |a, &b| a.min(b));
                xs.fold(f32::NEG_INFINITY, |a, &b| a.max(b)) - lo
            })
            .fold(0f32, f32::max);
        let tolerance = f64::from(extent) / ((1u64 << bits) - 1) as f64 / 2.0 + 1e-6;
        // Per decoded vertex: the (input value, decoded value) pairs seen.
        let mut seen: Vec<Vec<(u32, u32)>> = vec![Vec::new(); out.mesh.positions.len()];
        for (t, &(f, r)) in map.iter().enumerate() {
            for k in 0..3 {
                let vi = s_in.corners[f][(r + k) % 3];
                let vo = s_out.corners[t][k];
                let (a, b) = (s_in.value(vi), s_out.value(vo));
                if s_in.kind == AttributeKind::Normal {
                    let bound = if bits == 8 {
                        super::octahedral::NORMAL_ANGLE_8_BITS
                    } else {
                        90.0 / f64::from(1u32 << (bits - 2))
                    };
                    assert!(angle(a, b) <= bound, "normal {a:?} -> {b:?}");
                } else {
                    for c in 0..d {
                        let e = (f64::from(a[c]) - f64::from(b[c])).abs();
                        assert!(
                            e <= tolerance,
                            "{:?} {a:?} -> {b:?}: {e} > {tolerance}",
                            s_in.kind
                        );
                    }
                }
                seen[out.mesh.triangles[t][k] as usize].push((vi, vo));
            }
        }
        // Seams kept exactly: at each vertex, corners share a decoded value
        // exactly when they shared an input value.
        for pairs in &seen {
            for x in pairs {
                for y in pairs {
                    assert_eq!(x.0 == y.0, x.1 == y.1, "{:?}: {pairs:?}", s_in.kind);
                }
            }
        }
    }
    bytes
}

#[test]
fn textured_spheres_round_trip_with_their_seams() {
    for (nu, nv) in [(3, 2), (8, 5), (24, 12)] {
        check_round_trip(&textured_sphere(nu, nv), &lossless(12));
    }
}

#[test]
fn creased_cube_and_coloured_sphere_round_trip() {
    check_round_trip(&seamed_cube(), &lossless(10));
    check_round_trip(&coloured_sphere(), &lossless(10));
    let mut both = textured_sphere(10, 6);
    both.streams.extend(coloured_sphere_on(&both.mesh));
    check_round_trip(&both, &lossless(12));
    // A generic scalar and a three-component texture set (parallelograms
    // only: the projection is for two components).
    let m = &both.mesh;
    let scalar = m.positions.iter().map(|p| p[0] * p[1] - p[2]).collect();
    let uvw = m
        .positions
        .iter()
        .flat_map(|p| [p[0], p[1] * 0.5, p[2] * 2.0])
        .collect();
    both.streams.push(AttributeStream::new(
        AttributeKind::Generic(7),
        1,
        scalar,
        m.triangles.clone(),
    ));
    both.streams.push(AttributeStream::new(
        AttributeKind::TexCoord(1),
        3,
        uvw,
        m.triangles.clone(),
    ));
    let mut options = lossless(12);
    options.attributes.generic_bits = 12;
    check_round_trip(&both, &options);
}

/// A colour per vertex of `mesh`, smooth over the surface.
fn coloured_sphere_on(mesh: &crate::TriMesh) -> Vec<AttributeStream> {
    let c = mesh
        .positions
        .iter()
        .flat_map(|p| [0.5 + 0.5 * p[0], 0.5 + 0.25 * p[1], 0.5 - 0.5 * p[2]])
        .collect();
    vec![AttributeStream::new(
        AttributeKind::Color(0),
        3,
        c,
        mesh.triangles.clone(),
    )]
}

#[test]
fn other_quantizations_and_mirrored_charts_round_trip() {
    let mut options = lossless(11);
    options.attributes.texcoord_bits = 14;
    options.attributes.normal_bits = 12;
    let mut m = textured_sphere(16, 8);
    // Mirror the texture (u → 1 − u): every chart's orientation flips.
    for u in m.streams[0].values.iter_mut().step_by(2) {
        *u = 1.0 - *u;
    }
    // And turn the normals inward.
    for n in m.streams[1].values.iter_mut() {
        *n = -*n;
    }
    check_round_trip(&m, &options);
    options.attributes.texcoord_bits = 2;
    options.attributes.normal_bits = 4;
    check_round_trip(&m, &options);
}

#[test]
fn a_mesh_without_streams_is_the_plain_file() {
    let m = textured_sphere(8, 5);
    let plain = crate::encode(&m.mesh, &lossless(12)).unwrap().bytes;
    let none = crate::encode_attributed(&m.mesh.clone().into(), &lossless(12))
        .unwrap()
        .bytes;
    assert_eq!(plain, none);
    let with = crate::encode_attributed(&m, &lossless(12)).unwrap();
    let info = crate::inspect(&with.bytes, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 2));
    assert_eq!(info.attributes.len(), 2);
    assert_eq!(info.attributes[0].kind, AttributeKind::TexCoord(0));
    assert_eq!(
        (info.attributes[1].kind, info.attributes[1].bits),
        (AttributeKind::Normal, 8)
    );
    // Deterministic.
    assert_eq!(
        with.bytes,
        crate::encode_attributed(&m, &lossless(12)).unwrap().bytes
    );
    // A mode naming a method whose file cannot carry them drops the
    // streams and says so (issue 47, item 3; the automatic mode keeps
    // them: `encoder::tests_attributed`).
    let swing = EncodeOptions {
        mode: EncodeMode::Swing {
            target: crate::SwingTarget::Bytes(500),
            angle_bits: None,
            max_bytes: None,
        },
        ..Default::default()
    };
    let dropped = crate::encode_attributed(&m, &swing).unwrap();
    assert_eq!(dropped.stats.attributes.dropped.len(), m.streams.len());
    assert!(dropped.stats.attributes.kept.is_empty());
}

#[test]
fn hostile_attr_bytes_are_errors_never_panics() {
    let bytes = crate::encode_attributed(&textured_sphere(8, 5), &lossless(10))
        .unwrap()
        .bytes;
    hostile_attr_is_refused(&bytes, 0x9E37_79B9_7F4A_7C15, 3000);
}

/// Damages the `ATTR` payload of `bytes` (a valid file with one) and
/// decodes each copy with its streams, the CRC fixed so the damage
/// reaches the section: each byte inverted in turn, then single bits at
/// random (`seed`) up to `tries` in all, must give an error or a valid
/// mesh, never a panic; every truncation of the payload an error.
pub(crate) fn hostile_attr_is_refused(bytes: &[u8], seed: u64, tries: usize) {
    let file = crate::container::parse_container(bytes, &Default::default()).unwrap();
    let attr = file.find(crate::container::Tag::ATTR).unwrap();
    let start = attr.bytes.as_ptr() as usize - bytes.as_ptr() as usize;
    let len = attr.bytes.len();
    let options = DecodeOptions::default();
    let mut rng = crate::mesh::test_rng::Rng(seed);
    for i in 0..tries {
        let mut b = bytes.to_vec();
        let at = start
            + if i < len {
                i
            } else {
                rng.below(len as u64) as usize
            };
        b[at] ^= if i < len { 0xFF } else { 1 << rng.below(8) };
        refresh_crc(&mut b);
        // Either an error or a valid mesh; never a panic.
        if let Ok(m) = crate::decode_attributed(&b, &options) {
            m.validate().unwrap();
        }
    }
    // Every truncation of the section's payload.
    for cut in 0..len {
        let mut b = bytes.to_vec();
        b.drain(start + cut..start + len);
        assert!(crate::decode_attributed(&b, &options).is_err());
    }
}

/// Rewrites the trailing CRC-32 so a corrupted file reaches the sections.
fn refresh_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crate::container::crc32(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}
