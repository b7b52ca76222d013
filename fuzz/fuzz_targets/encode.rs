//! Property target for the encoder on hostile input (issue 18): an OBJ
//! text built from the bytes (polygon faces of up to a few hundred
//! vertices, fans around one vertex, duplicate, reversed and degenerate
//! faces, coordinates from 1e-30 to 1e30) is read by the OBJ reader and
//! encoded in the SwingWrapper mode under an `EncodeLimits` work budget:
//! - `swm::encode` returns a file or an error, never panics; with the
//!   budget it ends in bounded time whatever the shape (libFuzzer's
//!   `-timeout` catches a run that does not);
//! - every file it writes decodes to a valid mesh;
//! - the simplified method (`EncodeMode::Simplified`: quadric collapse,
//!   refit, lossless mode) at a size, for one input in eight, writes a
//!   file within it that decodes to a valid mesh, or fails cleanly.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::fmt::Write as _;
use swm::{DecodeOptions, EncodeLimits, EncodeMode, EncodeOptions, SwingTarget};
use swm_fuzz::Bytes;

/// Vertices on a coarse grid (coincident points are common), some on a
/// circle (a polygon face), scaled by a power of ten from -30 to 30.
fn obj(b: &mut Bytes) -> String {
    let mut s = String::new();
    let exponent = b.range(0, 60) as i32 - 30;
    let scale = 10f64.powi(exponent);
    let n = b.range(3, 24);
    // Mostly short rings, which keep an input to a millisecond or two;
    // one in 8 long enough for a polygon face or a fan of valence above
    // the retiler's cap of 256 (`retile::valence`).
    let ring = if b.u8() % 8 == 7 {
        b.range(200, 300)
    } else {
        b.range(3, 48)
    };
    for _ in 0..n {
        let [x, y, z] = [0; 3].map(|_: i32| (b.u8() as i8) as f64 / 16.0 * scale);
        writeln!(s, "v {x:e} {y:e} {z:e}").unwrap();
    }
    let bump = (b.u8() as i8) as f64 / 64.0;
    for i in 0..ring {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(ring);
        let z = bump * (3.0 * a).sin();
        writeln!(
            s,
            "v {:e} {:e} {:e}",
            a.cos() * scale,
            a.sin() * scale,
            z * scale
        )
        .unwrap();
    }
    let total = n + ring;
    let faces = b.range(1, 24);
    for _ in 0..faces {
        match b.u8() % 4 {
            // The ring as one polygon, either way round.
            0 => {
                let forward = b.u8() % 2 == 0;
                s.push('f');
                for i in 0..ring {
                    let k = if forward { i } else { ring - 1 - i };
                    write!(s, " {}", n + 1 + k).unwrap();
                }
                s.push('\n');
            }
            // A fan from one grid vertex over the ring (a cone's apex).
            1 => {
                let apex = b.range(1, n);
                for i in 0..ring {
                    let (p, q) = (n + 1 + i, n + 1 + (i + 1) % ring);
                    writeln!(s, "f {apex} {p} {q}").unwrap();
                }
            }
            // Small polygons of arbitrary vertices (repeats allowed).
            _ => {
                let k = b.range(3, 8);
                s.push('f');
                for _ in 0..k {
                    write!(s, " {}", b.range(1, total)).unwrap();
                }
                s.push('\n');
            }
        }
    }
    s
}

/// The rate and the work limit. Most inputs get one retiling run at an
/// edge length of 1/2 to 1/16 of the bounding-box diagonal (a few to a
/// few hundred triangles: the hostile shapes are in the input, not in the
/// output's resolution) under a small budget, so that libFuzzer gets
/// through a million inputs in one to two hours; one in 64 (never a zero
/// byte, which an input that ran out gives) asks for a size or a rate, so
/// rate control with its retries, steps and brackets is reached too,
/// under a budget that allows a few runs.
fn target(b: &mut Bytes, diagonal: f64) -> (SwingTarget, u64) {
    match b.u8() {
        s if s % 64 == 63 => match s / 64 % 2 {
            0 => (
                SwingTarget::BitsPerVertex(f64::from(b.range(1, 16))),
                300_000,
            ),
            _ => (SwingTarget::Bytes(u64::from(b.range(40, 2000))), 300_000),
        },
        // A zero or non-finite diagonal (coincident or overflowing
        // points) gives an edge length `encode` must refuse cleanly.
        _ => (
            SwingTarget::EdgeLength(diagonal / f64::from(b.range(2, 16))),
            50_000,
        ),
    }
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let text = obj(&mut b);
    let limits = swm::Limits {
        max_vertices: 1 << 16,
        max_faces: 1 << 16,
        max_alloc_bytes: 64 << 20,
        ..swm::Limits::default()
    };
    let Ok(mesh) = swm::io::read_mesh_bytes(text.as_bytes(), swm::io::MeshFormat::Obj, &limits)
    else {
        return;
    };
    let (target, max_work) = target(&mut b, mesh.bbox_diagonal());
    // The simplified method (quadric collapse, refit, lossless mode) at a
    // size: a file within it that decodes, or a clean error. One input in
    // eight: its search measures each candidate with 30,000 samples a
    // side, a hundred times a retiling of these small inputs.
    let budget = match target {
        SwingTarget::Bytes(n) => n,
        _ => 200,
    };
    let try_simplified = data.first().is_some_and(|&x| x % 8 == 0);
    let simplified = EncodeOptions {
        mode: EncodeMode::Simplified {
            target: SwingTarget::Bytes(budget),
            max_bytes: None,
        },
        ..Default::default()
    };
    if let Some(Ok(e)) = try_simplified.then(|| swm::encode(&mesh, &simplified)) {
        assert!(e.bytes.len() as u64 <= budget, "{} bytes for {budget}", e.bytes.len());
        swm::decode(&e.bytes, &DecodeOptions::default())
            .unwrap_or_else(|e| panic!("decode of a simplified file failed: {e}"))
            .validate()
            .expect("decoded simplified mesh is invalid");
    }
    let options = EncodeOptions {
        mode: EncodeMode::Swing {
            target,
            angle_bits: Some(8),
            max_bytes: None,
        },
        limits: EncodeLimits {
            max_work,
            max_memory_bytes: 256 << 20,
            max_milliseconds: None,
        },
        ..Default::default()
    };
    let Ok(encoded) = swm::encode(&mesh, &options) else {
        return;
    };
    let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default())
        .unwrap_or_else(|e| panic!("decode of an encoded file failed: {e}"));
    decoded.validate().expect("decoded mesh is invalid");
});
