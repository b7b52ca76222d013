//! Lossy encodes that keep attribute streams (issue 47, item 3): a
//! textured sphere with a seam along a meridian, through the automatic
//! mode at every effort, the simplified mode and the modes that drop
//! them.

use super::stats::{AttributesDropped, CandidateFailure, Method};
use crate::mesh::test_shapes::{seamed_cube, textured_sphere, uv_sphere};
use crate::options::{Effort, EncodeMode, EncodeOptions, SwingTarget};
use crate::{AttributeKind, AttributedMesh};

fn auto(bpv: f64, effort: Effort) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Auto {
            target: SwingTarget::BitsPerVertex(bpv),
            max_bytes: None,
        },
        effort,
        ..Default::default()
    }
}

/// The equirectangular (u, v) of a point of the unit sphere, u in [0, 1).
fn expected_uv(p: [f32; 3]) -> [f64; 2] {
    let [x, y, z] = p.map(f64::from);
    let r = (x * x + y * y + z * z).sqrt();
    let u = y.atan2(x).rem_euclid(core::f64::consts::TAU) / core::f64::consts::TAU;
    [u, (z / r).clamp(-1.0, 1.0).acos() / core::f64::consts::PI]
}

/// Every decoded corner's texture coordinate lies in the sphere's one
/// chart where its position is (u within `tol` of the position's
/// longitude, or of it plus one on the seam's far side; v of its
/// latitude), and no face spans the seam: nothing was interpolated
/// across the chart's boundary.
fn assert_in_chart(decoded: &AttributedMesh, tol: f64) {
    let uv = decoded
        .stream(AttributeKind::TexCoord(0))
        .expect("the file keeps the texture coordinates");
    for (f, t) in decoded.mesh.triangles.iter().enumerate() {
        let us: Vec<f64> = (0..3)
            .map(|k| uv.corner_value(crate::FaceId(f as u32), k)[0] as f64)
            .collect();
        let span = us.iter().cloned().fold(f64::MIN, f64::max)
            - us.iter().cloned().fold(f64::MAX, f64::min);
        assert!(span < 0.5, "face {f} spans the seam: u = {us:?}");
        for k in 0..3 {
            let p = decoded.mesh.positions[t[k] as usize];
            let got = uv.corner_value(crate::FaceId(f as u32), k);
            let want = expected_uv(p);
            assert!(
                (got[1] as f64 - want[1]).abs() < tol,
                "corner {k} of face {f}: v {} against {}",
                got[1],
                want[1]
            );
            // Longitude is undefined at the poles.
            let polar = (p[2] as f64).abs() > 0.95;
            let du = (got[0] as f64 - want[0]).abs();
            assert!(
                polar || du < tol || (du - 1.0).abs() < tol,
                "corner {k} of face {f}: u {} against {}",
                got[0],
                want[0]
            );
        }
    }
}

#[test]
fn a_textured_sphere_keeps_its_uvs_and_its_seam_at_every_effort() {
    let mesh = textured_sphere(48, 24);
    // Its normals are the sphere's own: by default a lossy file leaves
    // them to the decoder (`smooth`) and keeps the UVs alone.
    let e = crate::encode_attributed(&mesh, &auto(8.0, Effort::Fast)).unwrap();
    let a = &e.stats.attributes;
    assert_eq!(a.kept, vec![AttributeKind::TexCoord(0)]);
    assert_eq!(a.dropped, vec![AttributeKind::Normal]);
    assert!(matches!(
        a.dropped_because,
        Some(AttributesDropped::SmoothNormals { .. })
    ));
    for effort in [Effort::Fast, Effort::Default, Effort::Max] {
        // Asked to, it carries both streams through the simplification.
        let options = EncodeOptions {
            keep_smooth_normals: true,
            ..auto(8.0, effort)
        };
        let e = crate::encode_attributed(&mesh, &options).unwrap();
        assert_eq!(e.stats.chosen(), Method::Simplified, "{effort:?}");
        let a = &e.stats.attributes;
        assert_eq!(
            a.kept,
            vec![AttributeKind::TexCoord(0), AttributeKind::Normal]
        );
        assert!(a.dropped.is_empty() && a.dropped_because.is_none());
        // The retiler was not run: its file cannot carry them.
        if let Some(c) = e.stats.candidate(Method::Swing) {
            assert_eq!(c.outcome, Err(CandidateFailure::DropsAttributes));
        }
        let decoded = crate::decode_attributed(&e.bytes, &Default::default()).unwrap();
        assert!(decoded.mesh.face_count() < mesh.mesh.face_count());
        assert_in_chart(&decoded, 0.06);
        // Bounded: on a sphere simplified to about 300 faces, whose flat
        // faces map their texture linearly where the equirectangular map
        // bends (most near the poles), about half a percent of the
        // texture (5.4-6.8 texels at 1024 over the three levels).
        let uv = a.texcoord_error.expect("measured");
        assert!(uv.rms_texels < 10.0, "{effort:?}: {uv:?}");
        // The budget (8 b/v: one byte a vertex) counts the ATTR bytes.
        let budget = mesh.mesh.distinct_positions();
        assert!(
            e.bytes.len() <= budget + budget * 3 / 100,
            "{}",
            e.bytes.len()
        );
    }
}

#[test]
fn the_whole_mesh_keeps_its_uvs_to_the_quantization() {
    // A budget the whole mesh fits: nothing simplified, the error is the
    // 10-bit grid's rounding (half a step is half a texel at 1024).
    let mesh = textured_sphere(24, 12);
    let e = crate::encode_attributed(&mesh, &auto(200.0, Effort::Default)).unwrap();
    let s = e.stats.simplified().unwrap();
    assert_eq!((s.faces, s.input_faces), (528, 528));
    let uv = e.stats.attributes.texcoord_error.unwrap();
    assert!(uv.rms_texels < 0.6 && uv.max_texels < 1.0, "{uv:?}");
}

#[test]
fn lossy_attributed_bytes_are_deterministic_at_any_thread_count() {
    let mesh = textured_sphere(40, 20);
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            crate::encode_attributed(&mesh, &auto(3.0, Effort::Default))
                .unwrap()
                .bytes
        })
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(1));
}

#[test]
fn without_streams_the_bytes_are_encodes() {
    let mesh = uv_sphere(40, 20);
    for effort in [Effort::Fast, Effort::Default] {
        let options = auto(2.0, effort);
        let plain = crate::encode(&mesh, &options).unwrap();
        let through =
            crate::encode_attributed(&AttributedMesh::from(mesh.clone()), &options).unwrap();
        assert_eq!(plain.bytes, through.bytes);
        assert_eq!(through.stats.attributes, Default::default());
    }
}

#[test]
fn a_mode_naming_swing_drops_them_and_says_why() {
    let mesh = textured_sphere(40, 20);
    let options = EncodeOptions {
        mode: EncodeMode::Swing {
            target: SwingTarget::BitsPerVertex(2.0),
            angle_bits: None,
            max_bytes: None,
        },
        ..Default::default()
    };
    let e = crate::encode_attributed(&mesh, &options).unwrap();
    let a = &e.stats.attributes;
    assert!(a.kept.is_empty());
    assert_eq!(
        a.dropped,
        vec![AttributeKind::TexCoord(0), AttributeKind::Normal]
    );
    assert_eq!(
        a.dropped_because,
        Some(AttributesDropped::Method(Method::Swing))
    );
    assert_eq!(e.bytes, crate::encode(&mesh.mesh, &options).unwrap().bytes);
}

#[test]
fn a_cube_with_normal_creases_and_uv_seams_keeps_both() {
    // Every edge a seam of both streams: nothing can collapse, the whole
    // mesh is the file, with its streams.
    let mesh = seamed_cube();
    let e = crate::encode_attributed(&mesh, &auto(600.0, Effort::Default)).unwrap();
    let decoded = crate::decode_attributed(&e.bytes, &Default::default()).unwrap();
    assert_eq!(decoded.mesh.face_count(), 12);
    assert_eq!(decoded.streams.len(), 2);
    assert_eq!(
        e.stats.attributes.kept,
        vec![AttributeKind::Normal, AttributeKind::TexCoord(0)]
    );
}

/// A bumpy sphere whose normals carry something the surface does not:
/// each vertex's tilted about 20° off its geometry's in a direction of
/// its own (a hash of its number), so they are beyond
/// `smooth::SMOOTH_NORMAL_DEGREES` and cost about as much as the
/// positions do.
fn tilted_normals() -> AttributedMesh {
    let mut mesh = uv_sphere(64, 48);
    for p in &mut mesh.positions {
        let [x, y, z] = p.map(f64::from);
        let r = 1.0 + 0.03 * (7.0 * x).sin() * (7.0 * y).sin() * (7.0 * z).cos();
        *p = [x * r, y * r, z * r].map(|c| c as f32);
    }
    let geometric = crate::vertex_normals(&mesh);
    let mut values = Vec::new();
    for (v, n) in geometric.iter().enumerate() {
        let n = glam::DVec3::from(n.map(f64::from));
        let h = (v as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let a = (h >> 11) as f64 / (1u64 << 53) as f64 * core::f64::consts::TAU;
        let (u, w) = n.any_orthonormal_pair();
        let tilted = (n + 0.22 * (u * a.cos() + w * a.sin())).normalize();
        values.extend([tilted.x as f32, tilted.y as f32, tilted.z as f32]);
    }
    let corners = mesh.triangles.clone();
    let normals = crate::AttributeStream::new(AttributeKind::Normal, 3, values, corners);
    AttributedMesh {
        mesh,
        streams: vec![normals],
    }
}

#[test]
fn normals_that_crowd_the_surface_out_are_dropped_and_said_so() {
    let mesh = tilted_normals();
    let off = super::smooth::normals_off(&mesh).unwrap();
    assert!(off > super::smooth::SMOOTH_NORMAL_DEGREES, "{off}");
    let sized = |bytes: u64, keep: bool| EncodeOptions {
        mode: EncodeMode::Auto {
            target: SwingTarget::Bytes(bytes),
            max_bytes: None,
        },
        keep_smooth_normals: keep,
        ..Default::default()
    };
    let l2 = |e: &crate::Encoded| e.stats.check.unwrap().l2_relative.unwrap();
    // At 1,000 bytes the normals would take most of the file: without
    // them the surface is about three times closer (measured 7.3e-4,
    // searched at `fast`, against 22.3e-4 of the diagonal), more than
    // their own 12° at 1e-4 a degree. (At 1,200 bytes, since displaced
    // subdivision runs there, the kept file is close enough that the
    // weighed choice keeps them: 17.7e-4 against 6.0e-4 + 12.4e-4.)
    let e = crate::encode_attributed(&mesh, &sized(1000, false)).unwrap();
    let kept = crate::encode_attributed(&mesh, &sized(1000, true)).unwrap();
    let a = &e.stats.attributes;
    assert!(a.kept.is_empty());
    assert_eq!(a.dropped, vec![AttributeKind::Normal]);
    let Some(AttributesDropped::CostlyNormals {
        rms_degrees,
        l2_kept,
    }) = a.dropped_because
    else {
        panic!("{:?}", a.dropped_because);
    };
    assert_eq!(f64::from(rms_degrees), off as f32 as f64);
    assert_eq!(l2_kept, l2(&kept) as f32);
    assert!(l2(&e) + super::smooth::NORMAL_DEGREE_WEIGHT * off < l2(&kept));
    assert_eq!(kept.stats.attributes.kept, vec![AttributeKind::Normal]);
    assert!(
        e.bytes.len() <= 1200
            && crate::decode_attributed(&e.bytes, &Default::default())
                .unwrap()
                .streams
                .is_empty()
    );
    // At 8,000 bytes the surface with them is within their weighed error
    // of the input: they stay, the same file as asked to keep them.
    let e = crate::encode_attributed(&mesh, &sized(8000, false)).unwrap();
    assert_eq!(e.stats.attributes.kept, vec![AttributeKind::Normal]);
    assert!(e.stats.attributes.dropped_because.is_none());
    assert_eq!(
        e.bytes,
        crate::encode_attributed(&mesh, &sized(8000, true))
            .unwrap()
            .bytes
    );
}
