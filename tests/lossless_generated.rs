//! The lossless mode on every generated mesh: the decoded triangles are the
//! input's, with their orientation, each corner within half a quantization
//! step (compared through the public quantizer: the decoded corners equal
//! the quantized input corners exactly).

use swm::geometry::Quantizer;
use swm::{DecodeOptions, EncodeMode, EncodeOptions, TriMesh};

/// Triangles as corner positions (bit patterns), each rotated to start at
/// its smallest corner, sorted.
fn canonical(mesh: &TriMesh, map: impl Fn([f32; 3]) -> [f32; 3]) -> Vec<[[u32; 3]; 3]> {
    let mut v: Vec<[[u32; 3]; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            let c = t.map(|i| map(mesh.positions[i as usize]).map(f32::to_bits));
            let k = (0..3).min_by_key(|&k| c[k]).unwrap();
            [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]
        })
        .collect();
    v.sort_unstable();
    v
}

#[test]
fn generated_meshes_roundtrip_exactly() {
    for (name, mesh) in swm_corpus::all() {
        for qp in [10u8, 16, 24] {
            let options = EncodeOptions {
                mode: EncodeMode::Lossless { qp },
                ..Default::default()
            };
            let encoded = swm::encode(&mesh, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
            let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
            assert_eq!(decoded.face_count(), mesh.face_count(), "{name}");
            assert_eq!(decoded.vertex_count(), mesh.vertex_count(), "{name}");
            let q = Quantizer::from_positions(&mesh.positions, qp).unwrap();
            let expected = canonical(&mesh, |p| q.dequantize(q.quantize(p)));
            assert_eq!(canonical(&decoded, |p| p), expected, "{name} at qp {qp}");
            let half = q.step() / 2.0;
            let qmesh = TriMesh::new(
                mesh.positions
                    .iter()
                    .map(|&p| q.dequantize(q.quantize(p)))
                    .collect(),
                vec![],
            );
            for (p, r) in mesh.positions.iter().zip(&qmesh.positions) {
                for a in 0..3 {
                    let d = (p[a] as f64 - r[a] as f64).abs();
                    assert!(d <= half * (1.0 + 1e-6) + 1e-7, "{name}: {d} > {half}");
                }
            }
        }
    }
}
