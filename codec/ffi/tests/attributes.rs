//! `swm_decode_attributed` and `swm_attributed_mesh_free`: the streams of
//! a file with attributes (lossless, SwingWrapper, displaced), per vertex, bit for bit what the Rust
//! API's `decode_attributed(..).split_vertices()` gives; hostile bytes
//! give error codes and a zeroed output.

use std::ffi::CStr;
use std::ptr;

use swm::{AttributeKind, AttributeStream, AttributedMesh};
use swm_ffi::*;

/// An icosphere with per-vertex texture coordinates and normals, and a
/// colour per face (so every vertex splits into one copy per face around
/// it), coded losslessly.
fn sample() -> Vec<u8> {
    let mesh = swm_corpus::icosphere(1.0, 2);
    let tris = mesh.triangles.clone();
    let uv: Vec<f32> = mesh.positions.iter().flat_map(|p| [p[0], p[1]]).collect();
    let normals: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
    let colors: Vec<f32> = (0..tris.len())
        .flat_map(|f| [(f % 7) as f32 / 7.0, (f % 3) as f32 / 3.0, 0.5])
        .collect();
    let per_face: Vec<[u32; 3]> = (0..tris.len() as u32).map(|f| [f; 3]).collect();
    let streams = vec![
        AttributeStream::new(AttributeKind::TexCoord(0), 2, uv, tris.clone()),
        AttributeStream::new(AttributeKind::Normal, 3, normals, tris.clone()),
        AttributeStream::new(AttributeKind::Color(1), 3, colors, per_face),
    ];
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp: 12 },
        ..Default::default()
    };
    swm::encode_attributed(&AttributedMesh::new(mesh, streams), &options)
        .unwrap()
        .bytes
}

fn last_error() -> String {
    // SAFETY: the library returns a valid NUL-terminated string.
    unsafe { CStr::from_ptr(swm_last_error()) }
        .to_string_lossy()
        .into_owned()
}

fn zeroed() -> swm_attributed_mesh {
    swm_attributed_mesh {
        mesh: swm_mesh {
            positions: ptr::null_mut(),
            vertex_count: 0,
            indices: ptr::null_mut(),
            triangle_count: 0,
            normals: ptr::null_mut(),
        },
        attributes: ptr::null_mut(),
        attribute_count: 0,
    }
}

fn is_zeroed(m: &swm_attributed_mesh) -> bool {
    m.mesh.positions.is_null()
        && m.mesh.indices.is_null()
        && m.mesh.normals.is_null()
        && m.mesh.vertex_count == 0
        && m.attributes.is_null()
        && m.attribute_count == 0
}

#[test]
fn streams_come_per_vertex_as_the_rust_api_splits_them() {
    let bytes = sample();
    let want = swm::decode_attributed(&bytes, &Default::default())
        .unwrap()
        .split_vertices();
    let mut m = zeroed();
    let mut o = swm_decode_options_default();
    o.normals = true;
    // SAFETY: valid bytes, options and output.
    let rc = unsafe { swm_decode_attributed(bytes.as_ptr(), bytes.len(), &o, &mut m) };
    assert_eq!(rc, SWM_OK, "{}", last_error());
    let n = m.mesh.vertex_count;
    assert_eq!(n, want.mesh.positions.len());
    // The per-face colours split every vertex: more vertices than positions.
    assert!(
        n > swm::decode(&bytes, &Default::default())
            .unwrap()
            .positions
            .len()
    );
    // SAFETY: the library filled these with exactly these lengths.
    let (p, t, normals, streams) = unsafe {
        (
            std::slice::from_raw_parts(m.mesh.positions, 3 * n),
            std::slice::from_raw_parts(m.mesh.indices, 3 * m.mesh.triangle_count),
            std::slice::from_raw_parts(m.mesh.normals, 3 * n),
            std::slice::from_raw_parts(m.attributes, m.attribute_count),
        )
    };
    assert_eq!(p, want.mesh.positions.as_flattened());
    assert_eq!(t, want.mesh.triangles.as_flattened());
    assert_eq!(normals, swm::vertex_normals(&want.mesh).as_flattened());
    let kinds: Vec<(u32, u32, u32)> = streams.iter().map(|s| (s.kind, s.set, s.dims)).collect();
    let expected: Vec<(u32, u32, u32)> = want
        .streams
        .iter()
        .map(|s| match s.kind {
            AttributeKind::TexCoord(k) => (SWM_ATTRIBUTE_TEXCOORD, k.into(), 2),
            AttributeKind::Normal => (SWM_ATTRIBUTE_NORMAL, 0, 3),
            AttributeKind::Color(k) => (SWM_ATTRIBUTE_COLOR, k.into(), 3),
            other => panic!("unexpected stream {other:?}"),
        })
        .collect();
    assert_eq!(kinds, expected);
    for (s, w) in streams.iter().zip(&want.streams) {
        // SAFETY: `dims * vertex_count` floats, as documented.
        let values = unsafe { std::slice::from_raw_parts(s.values, s.dims as usize * n) };
        assert_eq!(values, &w.values[..], "stream {:?}", w.kind);
    }
    // SAFETY: filled by the library; the second call sees a zeroed mesh.
    unsafe {
        swm_attributed_mesh_free(&mut m);
        assert!(is_zeroed(&m));
        swm_attributed_mesh_free(&mut m);
        swm_attributed_mesh_free(ptr::null_mut());
    }
}

/// The golden files with `ATTR` over a decoded mesh (SwingWrapper and
/// displaced subdivision): their colours come out one per vertex, as the
/// Rust API gives them.
#[test]
fn retiled_and_displaced_files_give_their_streams() {
    for bytes in [
        &include_bytes!("../../../format-spec/golden/swing-attr-v1.2.swm")[..],
        &include_bytes!("../../../format-spec/golden/displaced-attr-v1.2.swm")[..],
    ] {
        let want = swm::decode_attributed(bytes, &Default::default())
            .unwrap()
            .split_vertices();
        let mut m = zeroed();
        // SAFETY: valid bytes and output; NULL options are the defaults.
        unsafe {
            let rc = swm_decode_attributed(bytes.as_ptr(), bytes.len(), ptr::null(), &mut m);
            assert_eq!(rc, SWM_OK, "{}", last_error());
            assert_eq!(m.attribute_count, 1);
            let n = m.mesh.vertex_count;
            assert_eq!(n, want.mesh.positions.len());
            let s = &*m.attributes;
            assert_eq!((s.kind, s.set, s.dims), (SWM_ATTRIBUTE_COLOR, 0, 3));
            let values = std::slice::from_raw_parts(s.values, 3 * n);
            assert_eq!(values, &want.streams[0].values[..]);
            swm_attributed_mesh_free(&mut m);
        }
    }
}

#[test]
fn a_file_without_streams_decodes_as_swm_decode_with() {
    let mesh = swm_corpus::icosphere(1.0, 1);
    let bytes = swm::encode(&mesh, &Default::default()).unwrap().bytes;
    let mut m = zeroed();
    let mut plain = zeroed().mesh;
    // SAFETY: valid bytes and outputs; NULL options are the defaults.
    unsafe {
        assert_eq!(
            swm_decode_attributed(bytes.as_ptr(), bytes.len(), ptr::null(), &mut m),
            SWM_OK
        );
        assert_eq!(swm_decode(bytes.as_ptr(), bytes.len(), &mut plain), SWM_OK);
        assert!(m.attributes.is_null() && m.attribute_count == 0);
        assert_eq!(m.mesh.vertex_count, plain.vertex_count);
        assert_eq!(
            std::slice::from_raw_parts(m.mesh.positions, 3 * plain.vertex_count),
            std::slice::from_raw_parts(plain.positions, 3 * plain.vertex_count)
        );
        swm_attributed_mesh_free(&mut m);
        swm_mesh_free(&mut plain);
    }
}

#[test]
fn hostile_bytes_give_codes_and_a_zeroed_mesh() {
    let bytes = sample();
    let mut m = zeroed();
    // SAFETY: valid pointers throughout, NULL where the library checks.
    unsafe {
        assert_eq!(
            swm_decode_attributed(bytes.as_ptr(), bytes.len(), ptr::null(), ptr::null_mut()),
            SWM_ERROR_ARGUMENT
        );
        assert_eq!(
            swm_decode_attributed(ptr::null(), 5, ptr::null(), &mut m),
            SWM_ERROR_ARGUMENT
        );
        // Every truncation, and every byte flipped in turn (the file's
        // checksum or the decoder's checks catch each).
        for cut in 0..bytes.len() {
            let rc = swm_decode_attributed(bytes.as_ptr(), cut, ptr::null(), &mut m);
            assert!(rc != SWM_OK && rc != SWM_ERROR_INTERNAL, "cut {cut}: {rc}");
            assert!(is_zeroed(&m) && !last_error().is_empty());
        }
        for at in 0..bytes.len() {
            let mut damaged = bytes.clone();
            damaged[at] ^= 0x5a;
            let rc = swm_decode_attributed(damaged.as_ptr(), damaged.len(), ptr::null(), &mut m);
            assert_ne!(rc, SWM_ERROR_INTERNAL, "byte {at}: {}", last_error());
            swm_attributed_mesh_free(&mut m);
        }
        let mut o = swm_decode_options_default();
        o.max_vertices = 10;
        assert_eq!(
            swm_decode_attributed(bytes.as_ptr(), bytes.len(), &o, &mut m),
            SWM_ERROR_LIMIT
        );
        assert!(is_zeroed(&m));
    }
}
