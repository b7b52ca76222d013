//! Streams resampled at the vertices of a displaced-subdivision or
//! SwingWrapper file (`resample`, `ATTR` over a decoded mesh): a sphere with a colour that
//! is a linear function of the position and a generic scalar, so that
//! each decoded vertex's value can be checked against where it stands.

use super::stats::{AttributesDropped, CandidateFailure, Method};
use crate::mesh::test_shapes::{textured_sphere, uv_sphere};
use crate::options::{EncodeMode, EncodeOptions, SwingTarget};
use crate::{AttributeKind, AttributeStream, AttributedMesh, DecodeOptions};

/// The colour the sphere has at `p`.
fn colour_at(p: [f32; 3]) -> [f32; 3] {
    [0.5 + 0.5 * p[0], 0.5 + 0.25 * p[1], 0.5 - 0.5 * p[2]]
}

/// A unit sphere of `nu` x `nv` quads with [`colour_at`] and a scalar
/// `x·y − z` per vertex.
fn coloured_sphere(nu: u32, nv: u32) -> AttributedMesh {
    let mesh = uv_sphere(nu, nv);
    let colours = mesh.positions.iter().flat_map(|&p| colour_at(p)).collect();
    let scalar = mesh.positions.iter().map(|p| p[0] * p[1] - p[2]).collect();
    let streams = vec![
        AttributeStream::new(AttributeKind::Color(0), 3, colours, mesh.triangles.clone()),
        AttributeStream::new(AttributeKind::Generic(3), 1, scalar, mesh.triangles.clone()),
    ];
    AttributedMesh::new(mesh, streams)
}

fn swing(bytes: u64) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: SwingTarget::Bytes(bytes),
            angle_bits: None,
            max_bytes: None,
        },
        ..Default::default()
    }
}

fn displaced(bytes: u64) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Displaced {
            target: SwingTarget::Bytes(bytes),
            max_bytes: None,
        },
        ..Default::default()
    }
}

/// Each decoded vertex's colour and scalar are the input's where it
/// stands: within the interpolation over an input face (both are linear
/// in the position, so only the vertex's distance from the sphere and the
/// quantization move them) and 8-bit steps.
fn assert_where_they_stand(decoded: &AttributedMesh) {
    let [colour, scalar] = &decoded.streams[..] else {
        panic!("two streams: {:?}", decoded.streams.len());
    };
    assert_eq!(colour.kind, AttributeKind::Color(0));
    assert_eq!(scalar.kind, AttributeKind::Generic(3));
    let m = &decoded.mesh;
    for (t, tri) in m.triangles.iter().enumerate() {
        for k in 0..3 {
            let p = m.positions[tri[k] as usize];
            let c = &colour.values[3 * colour.corners[t][k] as usize..][..3];
            let want = colour_at(p);
            for (a, b) in c.iter().zip(want) {
                assert!((a - b).abs() < 0.03, "colour {c:?} at {p:?}, want {want:?}");
            }
            let s = scalar.values[scalar.corners[t][k] as usize];
            let want = p[0] * p[1] - p[2];
            assert!((s - want).abs() < 0.03, "scalar {s} at {p:?}, want {want}");
        }
    }
}

#[test]
fn displaced_subdivision_keeps_colours_and_generic_streams() {
    let input = coloured_sphere(96, 48);
    let request = 3_000;
    let e = crate::encode_attributed(&input, &displaced(request)).unwrap();
    assert!(matches!(
        e.stats.method,
        super::stats::MethodStats::Displaced(_)
    ));
    let a = &e.stats.attributes;
    assert_eq!(
        a.kept,
        vec![AttributeKind::Color(0), AttributeKind::Generic(3)]
    );
    assert!(a.dropped.is_empty(), "{a:?}");
    // The streams' bytes are inside the request, not on top of it.
    let size = e.bytes.len() as f64;
    assert!(
        (size - request as f64).abs() <= 0.03 * request as f64,
        "{size} bytes for {request}"
    );
    let decoded = crate::decode_attributed(&e.bytes, &DecodeOptions::default()).unwrap();
    decoded.validate().unwrap();
    assert_eq!(
        decoded.mesh,
        crate::decode(&e.bytes, &DecodeOptions::plain()).unwrap()
    );
    assert_where_they_stand(&decoded);
    // Deterministic.
    let again = crate::encode_attributed(&input, &displaced(request)).unwrap();
    assert_eq!(e.bytes, again.bytes);

    // A prefix is the coarser mesh, without streams (they are the finest
    // level's), both cut and decoded short.
    let info = crate::inspect(&e.bytes, &Default::default()).unwrap();
    assert!(info.levels.len() >= 1 && !info.stats.attributes.is_empty());
    let coarser = DecodeOptions {
        max_level: Some(info.levels.len() as u8 - 1),
        ..Default::default()
    };
    let short = crate::decode_attributed(&e.bytes, &coarser).unwrap();
    assert!(short.streams.is_empty());
    assert_eq!(short.mesh, crate::decode(&e.bytes, &coarser).unwrap());
    let cut = crate::cut_levels(&e.bytes, info.levels.len() - 1, &Default::default()).unwrap();
    let cut = crate::decode_attributed(&cut, &DecodeOptions::default()).unwrap();
    assert!(cut.streams.is_empty());
    assert_eq!(cut.mesh, short.mesh);
}

#[test]
fn the_chooser_runs_displaced_subdivision_on_a_coloured_mesh() {
    let input = coloured_sphere(96, 48);
    let options = EncodeOptions {
        mode: EncodeMode::Auto {
            target: SwingTarget::BitsPerVertex(2.0),
            max_bytes: None,
        },
        ..Default::default()
    };
    let e = crate::encode_attributed(&input, &options).unwrap();
    let tried = |m: Method| {
        e.stats
            .candidates
            .iter()
            .find(|c| c.method == m)
            .map(|c| c.outcome.clone())
    };
    let displaced = tried(Method::Displaced).expect("displaced is in default's list");
    assert!(
        displaced != Err(CandidateFailure::DropsAttributes),
        "{displaced:?}"
    );
    // SwingWrapper carries them too (here perhaps over the level's work
    // budget, but not left out for its file).
    let swing = tried(Method::Swing).expect("swing is in default's list");
    assert!(swing != Err(CandidateFailure::DropsAttributes), "{swing:?}");
    assert_eq!(
        e.stats.attributes.kept,
        vec![AttributeKind::Color(0), AttributeKind::Generic(3)]
    );
    let decoded = crate::decode_attributed(&e.bytes, &DecodeOptions::default()).unwrap();
    assert_where_they_stand(&decoded);
}

#[test]
fn texture_coordinates_still_keep_displaced_subdivision_out() {
    let e = crate::encode_attributed(&textured_sphere(40, 20), &displaced(2_000)).unwrap();
    let a = &e.stats.attributes;
    assert!(a.kept.is_empty());
    assert_eq!(
        a.dropped_because,
        Some(AttributesDropped::Method(Method::Displaced))
    );
}

#[test]
fn hostile_attr_bytes_in_a_displaced_file_are_errors_never_panics() {
    let bytes = crate::encode_attributed(&coloured_sphere(24, 12), &displaced(800))
        .unwrap()
        .bytes;
    crate::lossless::attributes::tests::hostile_attr_is_refused(
        &bytes,
        0x2545_F491_4F6C_DD1D,
        2000,
    );
}

#[test]
fn swingwrapper_keeps_colours_and_generic_streams() {
    let input = coloured_sphere(96, 48);
    let request = 3_000;
    let e = crate::encode_attributed(&input, &swing(request)).unwrap();
    let super::stats::MethodStats::Swing(report) = &e.stats.method else {
        panic!("{:?}", e.stats.method);
    };
    // Its report answers the request (geometry and streams together).
    assert_eq!(report.rate.requested_bytes, Some(request));
    let a = &e.stats.attributes;
    assert_eq!(
        a.kept,
        vec![AttributeKind::Color(0), AttributeKind::Generic(3)]
    );
    let size = e.bytes.len() as f64;
    assert!(
        (size - request as f64).abs() <= 0.03 * request as f64,
        "{size} bytes for {request}"
    );
    assert_eq!(report.rate.within_tolerance, true);
    let info = crate::inspect(&e.bytes, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 2));
    assert_eq!(info.stats.attributes.len(), 2);
    let decoded = crate::decode_attributed(&e.bytes, &DecodeOptions::default()).unwrap();
    decoded.validate().unwrap();
    // Over the plain decode, which is also the default one: no hint is
    // written for a file with streams.
    let plain = crate::decode(&e.bytes, &DecodeOptions::plain()).unwrap();
    assert_eq!(decoded.mesh, plain);
    assert_eq!(
        crate::decode(&e.bytes, &DecodeOptions::default()).unwrap(),
        plain
    );
    assert_where_they_stand(&decoded);
    let again = crate::encode_attributed(&input, &swing(request)).unwrap();
    assert_eq!(e.bytes, again.bytes);
}

#[test]
fn texture_coordinates_keep_swingwrapper_out() {
    let e = crate::encode_attributed(&textured_sphere(40, 20), &swing(2_000)).unwrap();
    let a = &e.stats.attributes;
    assert!(a.kept.is_empty());
    assert_eq!(
        a.dropped_because,
        Some(AttributesDropped::Method(Method::Swing))
    );
}

#[test]
fn hostile_attr_bytes_in_a_swingwrapper_file_are_errors_never_panics() {
    let bytes = crate::encode_attributed(&coloured_sphere(24, 12), &swing(800))
        .unwrap()
        .bytes;
    assert_eq!(
        crate::inspect(&bytes, &Default::default()).unwrap().mode,
        crate::container::Mode::Swing
    );
    crate::lossless::attributes::tests::hostile_attr_is_refused(
        &bytes,
        0x9E37_79B9_7F4A_7C15,
        2000,
    );
}
