//! `swm decode IN.swm -o OUT.glb`: the GLB file must load in an
//! independent glTF reader (the `gltf` crate, which validates the
//! document) and hold the same mesh as the OBJ output of the same
//! command: same vertices bit for bit, same triangles, accessor bounds
//! equal to the positions' bounds, and unit normals.
//!
//! `gltf::import_slice` needs the crate's `import` feature, which pulls in
//! the `image` codecs; `Gltf::from_slice` parses the GLB container and
//! runs the same validation, and the test makes the one check `import`
//! adds for a GLB buffer (the BIN chunk holds the declared byteLength).

mod common;
use common::*;
use gltf::mesh::Mode;
use gltf::Semantic;
use std::path::Path;
use swm::TriMesh;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// What a GLB file holds, read with the `gltf` crate.
struct Loaded {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    min: [f32; 3],
    max: [f32; 3],
}

/// Loads a GLB file holding one triangle mesh, checking its structure.
fn load(path: &Path) -> Loaded {
    let bytes = std::fs::read(path).unwrap();
    let file = gltf::Gltf::from_slice(&bytes).expect("a valid glTF document");
    let asset = &file.document.as_json().asset;
    assert_eq!(asset.version, "2.0");
    assert_eq!(
        asset.generator.as_deref(),
        Some(concat!("swm ", env!("CARGO_PKG_VERSION")))
    );
    let blob = file.blob.as_deref().expect("a BIN chunk");
    let buffers: Vec<_> = file.buffers().collect();
    assert_eq!(buffers.len(), 1);
    assert!(matches!(buffers[0].source(), gltf::buffer::Source::Bin));
    assert!(blob.len() >= buffers[0].length());

    let scene = file.default_scene().expect("a default scene");
    let nodes: Vec<_> = scene.nodes().collect();
    assert_eq!(nodes.len(), 1);
    let mesh = nodes[0].mesh().expect("the node's mesh");
    let primitives: Vec<_> = mesh.primitives().collect();
    assert_eq!(primitives.len(), 1);
    let primitive = &primitives[0];
    assert_eq!(primitive.mode(), Mode::Triangles);

    let reader = primitive.reader(|b| (b.index() == 0).then_some(blob));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!(indices.len() % 3, 0);
    let triangles = indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();

    let accessor = primitive.get(&Semantic::Positions).unwrap();
    let bound = |v: Option<gltf::json::Value>| -> [f32; 3] {
        let v = v.expect("POSITION min/max");
        let a = v.as_array().unwrap();
        assert_eq!(a.len(), 3);
        [0, 1, 2].map(|k| a[k].as_f64().unwrap() as f32)
    };
    Loaded {
        positions,
        normals,
        triangles,
        min: bound(accessor.min()),
        max: bound(accessor.max()),
    }
}

fn bits(positions: &[[f32; 3]]) -> Vec<[u32; 3]> {
    positions.iter().map(|p| p.map(f32::to_bits)).collect()
}

/// Decodes `file` to `.glb` and `.obj` with `extra` options and compares.
fn decode_both(dir: &Path, file: &Path, name: &str, extra: &[&str]) -> TriMesh {
    let glb = dir.join(format!("{name}.glb"));
    let obj = dir.join(format!("{name}.obj"));
    for out in [&glb, &obj] {
        let mut args = vec!["decode", s(file), "-o", s(out)];
        args.extend_from_slice(extra);
        let o = swm(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    // The OBJ writer prints shortest round-trip decimals, so the OBJ gives
    // the decoded positions back exactly.
    let expected = swm::io::read_mesh(&obj).unwrap();
    let got = load(&glb);
    assert_eq!(got.positions.len(), expected.vertex_count(), "{name}");
    assert_eq!(got.triangles.len(), expected.face_count(), "{name}");
    assert_eq!(bits(&got.positions), bits(&expected.positions), "{name}");
    assert_eq!(got.triangles, expected.triangles, "{name}");
    for k in 0..3 {
        let axis = expected.positions.iter().map(|p| p[k]);
        let lo = axis.clone().fold(f32::INFINITY, f32::min);
        let hi = axis.fold(f32::NEG_INFINITY, f32::max);
        assert_eq!(got.min[k].to_bits(), lo.to_bits(), "{name}: min {k}");
        assert_eq!(got.max[k].to_bits(), hi.to_bits(), "{name}: max {k}");
    }
    assert_eq!(got.normals.len(), got.positions.len());
    for (v, n) in got.normals.iter().enumerate() {
        let len = n.iter().map(|c| f64::from(*c).powi(2)).sum::<f64>().sqrt();
        assert!((len - 1.0).abs() <= 1e-5, "{name}: vertex {v} normal {n:?}");
    }
    expected
}

fn encode(dir: &Path, mesh: &TriMesh, extra: &[&str]) -> std::path::PathBuf {
    let input = dir.join("in.obj");
    swm::io::write_mesh(&input, mesh).unwrap();
    let file = dir.join("in.swm");
    let mut args = vec!["encode", s(&input), "-o", s(&file)];
    args.extend_from_slice(extra);
    let o = swm(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    file
}

#[test]
fn glb_matches_obj_lossless() {
    let dir = scratch("gltf_lossless");
    let file = encode(
        &dir,
        &swm_corpus::icosphere(1.0, 2),
        &["--mode", "lossless"],
    );
    let mesh = decode_both(&dir, &file, "sphere", &[]);
    assert_eq!(mesh.face_count(), 320);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn glb_matches_obj_swing_sharpened_and_bent() {
    let dir = scratch("gltf_swing");
    let file = encode(&dir, &swm_corpus::cube(16), &["--edge-length", "0.08"]);
    let plain = decode_both(&dir, &file, "plain", &[]);
    let bent = decode_both(&dir, &file, "bent", &["--sharpen", "--bend", "1"]);
    assert!(bent.face_count() > 2 * plain.face_count());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A mesh without triangles is written as a valid file whose scene has
/// one node and no mesh (glTF accessors cannot be empty).
#[test]
fn empty_mesh_is_a_scene_without_a_mesh() {
    for mesh in [
        TriMesh::default(),
        TriMesh::new(vec![[1.0, 2.0, 3.0]], vec![]),
    ] {
        let mut bytes = Vec::new();
        swm::io::write_mesh_to(&mut bytes, swm::io::MeshFormat::Glb, &mesh).unwrap();
        let file = gltf::Gltf::from_slice(&bytes).expect("a valid glTF document");
        assert!(file.blob.is_none());
        let scene = file.default_scene().expect("a default scene");
        let nodes: Vec<_> = scene.nodes().collect();
        assert_eq!(nodes.len(), 1);
        assert!(nodes[0].mesh().is_none());
        assert_eq!(file.meshes().count(), 0);
        assert_eq!(file.buffers().count(), 0);
    }
}

/// `.glb` is read back (by `swm info` and `read_mesh`) to the mesh the
/// OBJ output holds.
#[test]
fn glb_reads_back() {
    let dir = scratch("gltf_back");
    let glb = dir.join("m.glb");
    let mesh = swm_corpus::icosphere(1.0, 1);
    swm::io::write_mesh(&glb, &mesh).unwrap();
    let back = swm::io::read_mesh(&glb).unwrap();
    assert_eq!(back.positions, mesh.positions);
    assert_eq!(back.triangles, mesh.triangles);
    let info = json(&swm(&["info", s(&glb), "--json"]));
    assert_eq!(info["faces"], mesh.face_count());
    let _ = std::fs::remove_dir_all(&dir);
}
