//! Arbitrary bytes as a `.swm` file: `swm::decode` must return an error or
//! a valid mesh, never panic, hang or allocate beyond its limits.
//!
//! The first byte picks the options, so one corpus exercises both paths:
//! even, the defaults (what a viewer does); odd, EdgeSharpener and one
//! Bender step under tight limits, which reach the post-processing code and
//! the limit checks on Bender's fourfold output. Bit 1 set also decodes
//! the attribute streams (`swm::decode_attributed`, a lossless or
//! displaced file's `ATTR`): an error, or a mesh whose streams pass
//! `AttributedMesh::validate` and whose mesh is `decode`'s.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swm::{DecodeOptions, Limits};

/// Small enough that a lying header is caught early, large enough for the
/// seed files (a few thousand triangles, four times that after Bender).
const TIGHT: Limits = Limits {
    max_vertices: 1 << 16,
    max_faces: 1 << 17,
    max_alloc_bytes: 64 << 20,
    ..Limits::UNLIMITED
};

fuzz_target!(|data: &[u8]| {
    let Some((&selector, file)) = data.split_first() else {
        return;
    };
    let options = if selector & 1 == 0 {
        DecodeOptions::default()
    } else {
        DecodeOptions {
            limits: TIGHT,
            sharpen: Some(true),
            bend_steps: Some(1),
            max_level: None,
        }
    };
    let plain = swm::decode(file, &options);
    if let Ok(mesh) = &plain {
        // A decoded mesh is a mesh: indices in range, positions finite.
        mesh.validate().expect("decode returned an invalid mesh");
    }
    if selector & 2 != 0 {
        if let Ok(m) = swm::decode_attributed(file, &options) {
            m.validate().expect("decode_attributed returned an invalid mesh");
            // With streams, the file's hint is not followed (the mesh is
            // the one they were coded over); asked-for post-processing
            // drops them.
            if m.streams.is_empty() {
                assert_eq!(Some(&m.mesh), plain.as_ref().ok(), "decode_attributed's mesh is not decode's");
            }
        }
    }
});
