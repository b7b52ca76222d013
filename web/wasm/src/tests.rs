//! The exports called as the glue calls them, on the host: a file of each
//! kind decodes to what `swm::decode` gives, errors come back as a status
//! and the library's message, and every block is released.

use super::*;

fn golden(name: &str) -> Vec<u8> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../format-spec/golden/");
    std::fs::read(format!("{path}{name}")).expect("read a golden file")
}

/// Copies `bytes` into a block from `swm_alloc`, as the glue does, and
/// decodes them.
/// `sharpen`, `bend`: negative follows the file's hint, as in the glue;
/// every level of a displaced file.
fn call(bytes: &[u8], sharpen: i32, bend: i32, normals: bool, limits: [f64; 3]) -> *mut Output {
    call_levels(bytes, sharpen, bend, normals, limits, -1)
}

/// [`call`] with `max_level` (negative: every level).
fn call_levels(
    bytes: &[u8],
    sharpen: i32,
    bend: i32,
    normals: bool,
    limits: [f64; 3],
    max_level: i32,
) -> *mut Output {
    let p = swm_alloc(bytes.len());
    assert!(!p.is_null());
    // SAFETY: the block holds `bytes.len()` bytes.
    unsafe {
        ptr::copy_nonoverlapping(bytes.as_ptr(), p, bytes.len());
        let out = swm_decode(
            p,
            bytes.len(),
            sharpen,
            bend,
            normals.into(),
            limits[0],
            limits[1],
            limits[2],
            max_level,
        );
        swm_free(p, bytes.len());
        out
    }
}

const DEFAULT: [f64; 3] = [
    (1u64 << 28) as f64,
    (1u64 << 29) as f64,
    (16u64 << 30) as f64,
];

/// The decoded arrays of an `Output`.
fn arrays(out: &Output) -> (&[f32], &[u32], Option<&[f32]>) {
    // SAFETY: a successful Output's pointers hold these many elements.
    unsafe {
        (
            core::slice::from_raw_parts(out.positions, 3 * out.vertex_count),
            core::slice::from_raw_parts(out.indices, 3 * out.triangle_count),
            (!out.normals.is_null())
                .then(|| core::slice::from_raw_parts(out.normals, 3 * out.vertex_count)),
        )
    }
}

fn message(out: &Output) -> &str {
    // SAFETY: the message is `message_len` bytes of UTF-8.
    unsafe {
        core::str::from_utf8(core::slice::from_raw_parts(out.message, out.message_len)).unwrap()
    }
}

#[test]
fn golden_files_decode_as_the_library_does() {
    for (name, mode, minor) in [
        ("lossless-v1.0.swm", 0, 0),
        ("swing-v1.0.swm", 1, 0),
        ("lossless-compact-v1.1.swm", 0, 1),
    ] {
        let bytes = golden(name);
        for (sharpen, bend, normals) in [(-1, -1, false), (0, 0, false), (1, 1, true)] {
            let expected = swm::decode(
                &bytes,
                &DecodeOptions {
                    sharpen: (sharpen >= 0).then_some(sharpen > 0),
                    bend_steps: u32::try_from(bend).ok(),
                    ..Default::default()
                },
            )
            .unwrap();
            let out = call(&bytes, sharpen, bend, normals, DEFAULT);
            // SAFETY: `swm_decode` returns a valid Output.
            let o = unsafe { &*out };
            assert_eq!(o.status, STATUS_OK, "{name}: {}", message(o));
            assert_eq!((o.mode, o.major, o.minor), (mode, 1, minor), "{name}");
            let (p, i, n) = arrays(o);
            assert_eq!(p, expected.positions.as_flattened(), "{name}");
            assert_eq!(i, expected.triangles.as_flattened(), "{name}");
            match n {
                Some(n) => assert_eq!(n, swm::vertex_normals(&expected).as_flattened()),
                None => assert!(!normals, "{name}: normals asked for, none given"),
            }
            // SAFETY: `out` came from `swm_decode`.
            unsafe { swm_output_free(out) };
        }
    }
}

/// The displaced-subdivision golden file (format 1.2, mode 2, two
/// levels), whole and cut by `max_level`: the library's mesh each time.
#[test]
fn displaced_files_decode_level_by_level() {
    let bytes = golden("displaced-v1.2.swm");
    for max_level in [-1, 0, 1, 2, 7] {
        let expected = swm::decode(
            &bytes,
            &DecodeOptions {
                max_level: u8::try_from(max_level).ok(),
                ..Default::default()
            },
        )
        .unwrap();
        let out = call_levels(&bytes, -1, -1, false, DEFAULT, max_level);
        // SAFETY: `swm_decode` returns a valid Output.
        let o = unsafe { &*out };
        assert_eq!(o.status, STATUS_OK, "{}", message(o));
        assert_eq!((o.mode, o.major, o.minor), (2, 1, 2));
        let levels = if max_level < 0 { 2 } else { max_level.min(2) };
        assert_eq!(o.triangle_count, 564 << (2 * levels));
        let (p, i, _) = arrays(o);
        assert_eq!(p, expected.positions.as_flattened());
        assert_eq!(i, expected.triangles.as_flattened());
        // SAFETY: `out` came from `swm_decode`.
        unsafe { swm_output_free(out) };
    }
}

/// A file pushed through a stream in pieces of 1, 7 and 1,000 bytes and
/// whole: each level of the displaced golden file comes out once, in
/// order, as soon as its chunk is in (the finest, where one piece
/// completes several), bit for bit the library's decode cut at that
/// level; `finish` gives the whole file's mesh. Other modes give no level
/// and the same whole mesh; a file cut short fails at `finish`.
#[test]
fn streams_hand_out_each_level_as_it_arrives() {
    for (name, levels) in [
        ("displaced-v1.2.swm", 3),
        ("lossless-compact-v1.1.swm", 0),
        ("swing-v1.1.swm", 0),
    ] {
        let bytes = golden(name);
        for piece in [1, 7, 1000, bytes.len()] {
            let s = swm_stream_new(-1, -1, 0, DEFAULT[0], DEFAULT[1], DEFAULT[2], -1);
            assert!(!s.is_null());
            let mut seen = Vec::new();
            for chunk in bytes.chunks(piece) {
                // SAFETY: a live stream and a readable chunk.
                let out = unsafe { swm_stream_push(s, chunk.as_ptr(), chunk.len()) };
                // SAFETY: never NULL.
                let o = unsafe { &*out };
                assert_eq!(o.status, STATUS_OK, "{name}: {}", message(o));
                if o.level >= 0 {
                    let expected = swm::decode(
                        &bytes,
                        &DecodeOptions {
                            max_level: u8::try_from(o.level).ok(),
                            ..Default::default()
                        },
                    )
                    .unwrap();
                    let (p, i, _) = arrays(o);
                    assert_eq!(
                        p,
                        expected.positions.as_flattened(),
                        "{name} level {}",
                        o.level
                    );
                    assert_eq!(
                        i,
                        expected.triangles.as_flattened(),
                        "{name} level {}",
                        o.level
                    );
                    assert_eq!((o.mode, o.major, o.minor), (2, 1, 2));
                    seen.push(o.level);
                } else {
                    assert_eq!((o.vertex_count, o.triangle_count), (0, 0));
                }
                // SAFETY: from `swm_stream_push`.
                unsafe { swm_output_free(out) };
            }
            // Small pieces complete one level at a time; a large one may
            // complete several, and the finest is handed out.
            let every: Vec<i32> = (0..levels).collect();
            if piece <= 7 {
                assert_eq!(seen, every, "{name} in pieces of {piece}");
            } else {
                assert!(seen.windows(2).all(|w| w[0] < w[1]), "{name}: {seen:?}");
                assert_eq!(seen.last(), every.last(), "{name} in pieces of {piece}");
            }
            // SAFETY: a live stream.
            let out = unsafe { swm_stream_finish(s) };
            // SAFETY: never NULL.
            let o = unsafe { &*out };
            assert_eq!(o.status, STATUS_OK, "{name}: {}", message(o));
            assert_eq!(o.level, -1);
            let whole = swm::decode(&bytes, &DecodeOptions::default()).unwrap();
            assert_eq!(arrays(o).0, whole.positions.as_flattened());
            // SAFETY: from `swm_stream_finish`, then a live stream.
            unsafe {
                swm_output_free(out);
                swm_stream_free(s);
            }
        }
        // Cut short: the levels so far, then an error at `finish`.
        let s = swm_stream_new(-1, -1, 0, DEFAULT[0], DEFAULT[1], DEFAULT[2], -1);
        let cut = &bytes[..bytes.len() - 3];
        // SAFETY: as above.
        unsafe {
            swm_output_free(swm_stream_push(s, cut.as_ptr(), cut.len()));
            let out = swm_stream_finish(s);
            assert_eq!((*out).status, STATUS_FORMAT, "{name}");
            swm_output_free(out);
            swm_stream_free(s);
        }
    }
    // A negative limit is refused.
    assert!(swm_stream_new(-1, -1, 0, -1.0, 1.0, 1.0, -1).is_null());
}

#[test]
fn errors_carry_the_status_and_the_library_message() {
    let bytes = golden("swing-v1.0.swm");
    let mut damaged = bytes.clone();
    let last = damaged.len() - 1;
    damaged[last] ^= 0x40;
    let expected = swm::decode(&damaged, &DecodeOptions::default()).unwrap_err();
    let cases: [(&[u8], [f64; 3], u32, String); 4] = [
        (&damaged, DEFAULT, STATUS_FORMAT, expected.to_string()),
        (
            b"",
            DEFAULT,
            STATUS_FORMAT,
            swm::decode(b"", &DecodeOptions::default())
                .unwrap_err()
                .to_string(),
        ),
        (
            &bytes,
            [2.0, DEFAULT[1], DEFAULT[2]],
            STATUS_LIMIT,
            swm::decode(
                &bytes,
                &DecodeOptions {
                    limits: super::limits(2.0, DEFAULT[1], DEFAULT[2]).unwrap(),
                    ..Default::default()
                },
            )
            .unwrap_err()
            .to_string(),
        ),
        (
            &bytes,
            [f64::NAN, DEFAULT[1], DEFAULT[2]],
            STATUS_ARGUMENT,
            String::new(),
        ),
    ];
    for (input, limits, status, text) in cases {
        let out = call(input, 0, 0, false, limits);
        // SAFETY: `swm_decode` returns a valid Output.
        let o = unsafe { &*out };
        assert_eq!(o.status, status, "{}", message(o));
        assert!(!message(o).is_empty());
        if !text.is_empty() {
            assert_eq!(message(o), text);
        }
        assert!(o.positions.is_null() && o.indices.is_null() && o.normals.is_null());
        // SAFETY: `out` came from `swm_decode`.
        unsafe { swm_output_free(out) };
    }
}

#[test]
fn null_and_empty_blocks_are_accepted() {
    let p = swm_alloc(0);
    assert!(!p.is_null());
    // SAFETY: as returned by `swm_alloc(0)`; NULL is documented as ignored.
    unsafe {
        swm_free(p, 0);
        swm_free(ptr::null_mut(), 5);
        swm_output_free(ptr::null_mut());
    }
}

/// The golden attribute file (format 1.2's `ATTR`): the mesh split at
/// seams and each stream per vertex, as the library's
/// `decode_attributed(..).split_vertices()` gives them; a file without
/// streams hands out none; every truncation is an error, not a trap.
#[test]
fn attribute_streams_come_split_per_vertex() {
    let bytes = golden("lossless-attr-v1.2.swm");
    let want = swm::decode_attributed(&bytes, &DecodeOptions::default())
        .unwrap()
        .split_vertices();
    assert!(!want.streams.is_empty());
    let out = call(&bytes, -1, -1, false, DEFAULT);
    // SAFETY: a live Output from `swm_decode`; its descriptors hold
    // `attribute_count` entries, each `dims * vertex_count` floats.
    unsafe {
        let o = &*out;
        assert_eq!(o.status, STATUS_OK, "{}", message(o));
        let (p, t, _) = arrays(o);
        assert_eq!(p, want.mesh.positions.as_flattened());
        assert_eq!(t, want.mesh.triangles.as_flattened());
        let descs = core::slice::from_raw_parts(o.attributes, o.attribute_count);
        assert_eq!(descs.len(), want.streams.len());
        for (d, s) in descs.iter().zip(&want.streams) {
            assert!((1..=4).contains(&d.kind), "{:?}", s.kind);
            assert_eq!(d.dims, u32::from(s.dims));
            let values = core::slice::from_raw_parts(d.values, s.values.len());
            assert_eq!(values, &s.values[..], "{:?}", s.kind);
        }
        swm_output_free(out);
        let plain = call(&golden("lossless-v1.0.swm"), -1, -1, false, DEFAULT);
        assert!((*plain).attributes.is_null() && (*plain).attribute_count == 0);
        swm_output_free(plain);
        for cut in 0..bytes.len() {
            let out = call(&bytes[..cut], -1, -1, false, DEFAULT);
            assert_ne!((*out).status, STATUS_OK, "cut {cut}");
            assert!((*out).attributes.is_null());
            swm_output_free(out);
        }
    }
}
