//! The C functions called from Rust, for the cases the C example does not
//! reach: NULL pointers, short buffers, limits, freeing twice, the error
//! message's lifetime.

use std::ffi::CStr;
use std::ptr;

use swm_ffi::*;

fn sample() -> Vec<u8> {
    let mesh = swm_corpus::icosphere(1.0, 2);
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp: 10 },
        ..Default::default()
    };
    swm::encode(&mesh, &options).unwrap().bytes
}

fn last_error() -> String {
    // SAFETY: the library returns a valid NUL-terminated string.
    unsafe { CStr::from_ptr(swm_last_error()) }
        .to_string_lossy()
        .into_owned()
}

fn zeroed() -> swm_mesh {
    swm_mesh {
        positions: ptr::null_mut(),
        vertex_count: 0,
        indices: ptr::null_mut(),
        triangle_count: 0,
        normals: ptr::null_mut(),
    }
}

#[test]
fn decode_hands_over_arrays_that_free_once() {
    let bytes = sample();
    let want = swm::decode(&bytes, &Default::default()).unwrap();
    let mut m = zeroed();
    let mut o = swm_decode_options_default();
    o.normals = true;
    // SAFETY: valid bytes, options and output.
    let rc = unsafe { swm_decode_with(bytes.as_ptr(), bytes.len(), &o, &mut m) };
    assert_eq!(rc, SWM_OK, "{}", last_error());
    assert_eq!(last_error(), "");
    assert_eq!(
        (m.vertex_count, m.triangle_count),
        (want.vertex_count(), want.face_count())
    );
    // SAFETY: the library filled these with exactly these lengths.
    let p = unsafe { std::slice::from_raw_parts(m.positions, 3 * m.vertex_count) };
    let n = unsafe { std::slice::from_raw_parts(m.normals, 3 * m.vertex_count) };
    assert_eq!(p, want.positions.as_flattened());
    assert_eq!(n, swm::vertex_normals(&want).as_flattened());
    // SAFETY: filled by the library; the second call sees a zeroed mesh.
    unsafe {
        swm_mesh_free(&mut m);
        assert!(m.positions.is_null() && m.vertex_count == 0 && m.normals.is_null());
        swm_mesh_free(&mut m);
        swm_mesh_free(ptr::null_mut());
    }
}

/// The displaced-subdivision golden file (format 1.2, mode 2, two
/// levels): decoded whole and with `max_level`, each the Rust decoder's
/// mesh bit for bit.
#[test]
fn displaced_files_decode_whole_and_level_by_level() {
    let bytes = include_bytes!("../../../format-spec/golden/displaced-v1.2.swm");
    for max_level in [-1, 0, 1, 2, 3] {
        let want = swm::decode(
            bytes,
            &swm::DecodeOptions {
                max_level: u8::try_from(max_level).ok(),
                ..Default::default()
            },
        )
        .unwrap();
        let mut m = zeroed();
        let mut o = swm_decode_options_default();
        o.max_level = max_level;
        // SAFETY: valid bytes, options and output.
        let rc = unsafe { swm_decode_with(bytes.as_ptr(), bytes.len(), &o, &mut m) };
        assert_eq!(rc, SWM_OK, "{}", last_error());
        // 564 base triangles, times 4 per level, two levels in the file.
        let levels = if max_level < 0 { 2 } else { max_level.min(2) };
        assert_eq!(m.triangle_count, 564 << (2 * levels));
        // SAFETY: the library filled these with exactly these lengths.
        let p = unsafe { std::slice::from_raw_parts(m.positions, 3 * m.vertex_count) };
        let t = unsafe { std::slice::from_raw_parts(m.indices, 3 * m.triangle_count) };
        assert_eq!(p, want.positions.as_flattened());
        assert_eq!(t, want.triangles.as_flattened());
        // SAFETY: filled by the library.
        unsafe { swm_mesh_free(&mut m) };
    }
}

#[test]
fn null_pointers_are_argument_errors() {
    let bytes = sample();
    let mut m = zeroed();
    // SAFETY: NULL where the library checks for it.
    unsafe {
        assert_eq!(swm_decode(ptr::null(), 10, &mut m), SWM_ERROR_ARGUMENT);
        assert!(last_error().contains("NULL"));
        assert_eq!(
            swm_decode(bytes.as_ptr(), bytes.len(), ptr::null_mut()),
            SWM_ERROR_ARGUMENT
        );
        let mut s = swm_decoded_size::default();
        let rc = swm_decode_into(
            bytes.as_ptr(),
            bytes.len(),
            ptr::null(),
            ptr::null_mut(),
            3,
            ptr::null_mut(),
            0,
            &mut s,
        );
        assert_eq!(rc, SWM_ERROR_ARGUMENT);
        // An empty input is not an argument error but a damaged file.
        assert_eq!(swm_decode(ptr::null(), 0, &mut m), SWM_ERROR_FORMAT);
        assert!(m.positions.is_null());
    }
}

#[test]
fn buffers_limits_and_damage_have_their_codes() {
    let bytes = sample();
    let mut size = swm_decoded_size::default();
    // SAFETY: valid pointers and lengths throughout.
    unsafe {
        assert_eq!(
            swm_decoded_len(bytes.as_ptr(), bytes.len(), ptr::null(), &mut size),
            SWM_OK
        );
        assert!(size.exact);
        let mut p = vec![0f32; 3 * size.vertex_count];
        let mut i = vec![0u32; 3 * size.triangle_count - 1];
        let mut into = |i: &mut Vec<u32>, out: *mut swm_decoded_size| {
            swm_decode_into(
                bytes.as_ptr(),
                bytes.len(),
                ptr::null(),
                p.as_mut_ptr(),
                p.len(),
                i.as_mut_ptr(),
                i.len(),
                out,
            )
        };
        assert_eq!(into(&mut i, &mut size), SWM_ERROR_BUFFER);
        assert!(last_error().contains("indices"), "{}", last_error());
        i.push(0);
        assert_eq!(into(&mut i, ptr::null_mut()), SWM_OK);

        let mut o = swm_decode_options_default();
        o.max_vertices = 10;
        let mut m = zeroed();
        assert_eq!(
            swm_decode_with(bytes.as_ptr(), bytes.len(), &o, &mut m),
            SWM_ERROR_LIMIT
        );
        assert!(m.positions.is_null());

        let mut damaged = bytes.clone();
        damaged[0] = b'X';
        assert_eq!(
            swm_decode(damaged.as_ptr(), damaged.len(), &mut m),
            SWM_ERROR_FORMAT
        );
        assert!(!last_error().is_empty() && !last_error().contains('\n'));
    }
}

#[test]
fn version_is_the_crate_version() {
    // SAFETY: a static NUL-terminated string.
    let v = unsafe { CStr::from_ptr(swm_version()) };
    assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}
