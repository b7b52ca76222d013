//! Property target: encode a small mesh built from the input, then
//! - every file `swm::encode` produced decodes (`swm::decode` succeeds and
//!   gives a valid mesh);
//! - encoding the same mesh with the same options twice gives the same
//!   bytes (the encoder promises determinism);
//! - `swm::encode` may refuse a mesh or a target with an error, but never
//!   panics.
//!
//! The mesh is either one of the corpus generators at a small size or a
//! handful of raw vertices and triangles taken from the bytes (degenerate,
//! non-manifold and duplicated faces included: cleaning must cope). It is
//! then scaled and shifted so quantization sees tiny and huge boxes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swm::{DecodeOptions, EncodeMode, EncodeOptions, SwingTarget, TriMesh};
use swm_fuzz::Bytes;

fn mesh(b: &mut Bytes) -> TriMesh {
    let mut m = match b.u8() % 6 {
        0 => swm_corpus::icosphere(1.0, b.range(0, 2)),
        1 => swm_corpus::torus(
            1.0,
            0.1 + b.range(1, 8) as f64 * 0.1,
            b.range(3, 12),
            b.range(3, 8),
        ),
        2 => swm_corpus::uv_sphere(1.0, b.range(2, 8), b.range(3, 10)),
        3 => swm_corpus::plane_patch(b.range(1, 6), b.range(1, 6)),
        4 => swm_corpus::cube(b.range(1, 3)),
        _ => {
            // Raw soup: coordinates on a coarse grid so that coincident
            // vertices and degenerate triangles are common.
            let n = b.range(3, 12) as usize;
            let positions = (0..n)
                .map(|_| [0; 3].map(|_: i32| (b.u8() as i8) as f32 / 16.0))
                .collect();
            let t = b.range(1, 16);
            let triangles = (0..t)
                .map(|_| [0; 3].map(|_: i32| b.u8() as u32 % n as u32))
                .collect();
            TriMesh::new(positions, triangles)
        }
    };
    // Scale by 2^-12..2^12 and shift by up to a few thousand boxes.
    let scale = 2f32.powi(b.range(0, 24) as i32 - 12);
    let shift = (b.u8() as i8) as f32 * scale * 16.0;
    for p in &mut m.positions {
        *p = p.map(|x| x * scale + shift);
    }
    m
}

fn options(b: &mut Bytes, m: &TriMesh) -> EncodeOptions {
    let (lo, hi) = m
        .positions
        .iter()
        .fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), p| {
            let p = p.map(f64::from);
            (
                [0, 1, 2].map(|i| lo[i].min(p[i])),
                [0, 1, 2].map(|i| hi[i].max(p[i])),
            )
        });
    let diagonal = (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt();
    let mode = match b.u8() % 3 {
        0 => EncodeMode::Lossless {
            qp: b.range(6, 24) as u8,
        },
        k => EncodeMode::Swing {
            // Edge lengths of 1/12 to 2/3 of the diagonal keep the
            // retiled mesh to a few hundred triangles, so runs stay fast.
            target: if k == 1 {
                SwingTarget::EdgeLength(diagonal * b.range(8, 64) as f64 / 96.0)
            } else {
                SwingTarget::BitsPerVertex(b.range(1, 16) as f64)
            },
            // One input in eight leaves the bits to rate control.
            angle_bits: if b.u8() < 32 {
                None
            } else {
                Some(b.range(4, 12) as u8)
            },
            max_bytes: match b.u8() {
                0..=223 => None,
                x => Some(x as u64 * 4),
            },
        },
    };
    EncodeOptions {
        mode,
        ..Default::default()
    }
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let m = mesh(&mut b);
    let options = options(&mut b, &m);
    let Ok(first) = swm::encode(&m, &options) else {
        return;
    };
    let second = swm::encode(&m, &options).expect("the same encode failed the second time");
    assert!(first.bytes == second.bytes, "encode is not deterministic");
    let decoded = swm::decode(&first.bytes, &DecodeOptions::default())
        .unwrap_or_else(|e| panic!("decode of an encoded file failed: {e}"));
    decoded.validate().expect("decoded mesh is invalid");
});
