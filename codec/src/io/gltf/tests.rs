//! The glTF reader on small hand-made documents: primitive modes,
//! transforms, scene choice, and every way a file can be wrong.

use super::super::{read_mesh, read_mesh_bytes, MeshFormat};
use crate::{Error, Limited, Limits, Malformed, TriMesh};
use serde_json::{json, Value};

/// Five vertices on the unit square's corners and centre.
const POSITIONS: [[f32; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.5, 0.0],
];

/// A GLB file: `doc` with a BIN chunk of `bin`.
pub(in crate::io) fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(doc).unwrap();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().div_ceil(4) * 4, 0);
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((28 + json.len() as u32 + bin.len() as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

/// The BIN chunk: POSITIONS (60 bytes) then `indices` as u32.
fn bin(indices: &[u32]) -> Vec<u8> {
    let mut b: Vec<u8> = POSITIONS
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    b.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    b
}

/// A document drawing `indices` with `mode` from one node, given by
/// `node` (its mesh is set here).
fn doc(indices: &[u32], mode: u32, node: Value) -> Value {
    let mut node = node;
    node["mesh"] = json!(0);
    let n = indices.len();
    json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [node],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": mode}]}],
        "buffers": [{"byteLength": 60 + 4 * n}],
        "bufferViews": [
            {"buffer": 0, "byteLength": 60},
            {"buffer": 0, "byteOffset": 60, "byteLength": 4 * n}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 5, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5125, "count": n, "type": "SCALAR"}
        ]
    })
}

fn read(bytes: &[u8]) -> Result<TriMesh, Error> {
    read_mesh_bytes(bytes, MeshFormat::Glb, &Limits::default())
}

fn read_doc(doc: &Value, indices: &[u32]) -> Result<TriMesh, Error> {
    read(&glb(doc, &bin(indices)))
}

fn malformed(r: Result<TriMesh, Error>) -> Malformed {
    match r {
        Err(Error::Format(e)) => e.what,
        other => panic!("expected a format error, got {other:?}"),
    }
}

#[test]
fn lists_strips_and_fans() {
    let list = read_doc(&doc(&[0, 1, 4, 1, 2, 4], 4, json!({})), &[0, 1, 4, 1, 2, 4]).unwrap();
    assert_eq!(list.triangles, vec![[0, 1, 4], [1, 2, 4]]);
    assert_eq!(list.positions, POSITIONS.to_vec());
    // Strip 0 1 3 2: (0 1 3), then (1 2 3): its index 1, 3, 2
    // (§3.7.2.1), so that both turn the same way.
    let strip = [0, 1, 3, 2];
    let m = read_doc(&doc(&strip, 5, json!({})), &strip).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 3], [1, 2, 3]]);
    let fan = [4, 0, 1, 2, 3];
    let m = read_doc(&doc(&fan, 6, json!({})), &fan).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 4], [1, 2, 4], [2, 3, 4]]);
    // Too short to draw anything: an empty file, as other readers say
    // (the vertices of primitives that draw nothing are not a mesh).
    let m = read_doc(&doc(&[0, 1], 5, json!({})), &[0, 1]);
    assert_eq!(malformed(m), Malformed::Empty);
    let m = read_doc(&doc(&[0, 1, 2, 3], 4, json!({})), &[0, 1, 2, 3]);
    assert!(matches!(malformed(m), Malformed::BadSyntax(_)));
}

#[test]
fn points_and_lines_are_refused_by_mode() {
    for mode in 0..4 {
        let m = read_doc(&doc(&[0, 1, 2], mode, json!({})), &[0, 1, 2]);
        assert_eq!(malformed(m), Malformed::UnsupportedPrimitive { mode });
    }
    let message = Malformed::UnsupportedPrimitive { mode: 1 }.to_string();
    assert!(message.contains("LINES"), "{message}");
}

#[test]
fn mirroring_flips_triangles() {
    let t = [0, 1, 4];
    let m = read_doc(&doc(&t, 4, json!({"scale": [-1, 1, 1]})), &t).unwrap();
    assert_eq!(m.triangles, vec![[0, 4, 1]]);
    assert_eq!(m.positions[1], [-1.0, 0.0, 0.0]);
    // A rotation by a quarter turn about z: (1, 0, 0) -> (0, 1, 0).
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let m = read_doc(&doc(&t, 4, json!({"rotation": [0, 0, h, h]})), &t).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 4]]);
    let [x, y, z] = m.positions[1];
    assert!(
        x.abs() < 1e-6 && (y - 1.0).abs() < 1e-6 && z == 0.0,
        "{x} {y} {z}"
    );
}

#[test]
fn scene_choice_and_hierarchy() {
    let t = [0, 1, 4];
    let mut d = doc(&t, 4, json!({}));
    // Two scenes, the default one second; node 1 moves node 0's mesh.
    d["nodes"] = json!([{"mesh": 0}, {"mesh": 0, "translation": [0, 0, 5]}]);
    d["scenes"] = json!([{"nodes": [0]}, {"nodes": [1]}]);
    d["scene"] = json!(1);
    let m = read_doc(&d, &t).unwrap();
    assert_eq!(m.positions[0], [0.0, 0.0, 5.0]);
    // No scene: every root node (node 1 is node 0's child).
    d.as_object_mut().unwrap().remove("scene");
    d.as_object_mut().unwrap().remove("scenes");
    d["nodes"][0]["children"] = json!([1]);
    let m = read_doc(&d, &t).unwrap();
    assert_eq!(m.face_count(), 2);
    // A cycle, and a node with two parents: refused, not walked forever.
    d["scenes"] = json!([{"nodes": [0]}]);
    d["nodes"][1]["children"] = json!([0]);
    assert!(matches!(
        malformed(read_doc(&d, &t)),
        Malformed::BadSyntax(_)
    ));
    d["nodes"] = json!([{"mesh": 0, "children": [2]}, {"children": [2]}, {}]);
    d["scenes"] = json!([{"nodes": [0, 1]}]);
    assert!(matches!(
        malformed(read_doc(&d, &t)),
        Malformed::BadSyntax(_)
    ));
    // No mesh anywhere: the empty-file error of every reader.
    d["nodes"] = json!([{}]);
    d["scenes"] = json!([{"nodes": [0]}]);
    assert_eq!(malformed(read_doc(&d, &t)), Malformed::Empty);
}

#[test]
fn bad_indices_and_accessors() {
    let t = [0, 1, 5];
    let m = read_doc(&doc(&t, 4, json!({})), &t);
    let what = Malformed::IndexOutOfRange {
        index: 5,
        vertices: 5,
    };
    assert_eq!(malformed(m), what);

    let t = [0, 1, 4];
    let edits: [(&str, usize, &str, Value); 8] = [
        ("accessors", 0, "count", json!(6)),
        ("accessors", 0, "byteOffset", json!(u32::MAX)),
        ("bufferViews", 0, "byteLength", json!(1000)),
        ("bufferViews", 0, "byteStride", json!(4)),
        ("bufferViews", 1, "byteOffset", json!(u64::MAX)),
        ("accessors", 1, "componentType", json!(5126)),
        ("accessors", 0, "componentType", json!(5123)),
        ("accessors", 1, "type", json!("VEC2")),
    ];
    for (list, k, key, value) in edits {
        let mut d = doc(&t, 4, json!({}));
        d[list][k][key] = value.clone();
        let r = read_doc(&d, &t);
        assert!(
            matches!(r, Err(Error::Format(_))),
            "{list}[{k}].{key} = {value}: {r:?}"
        );
    }
    // A count past the limits is refused before anything is allocated.
    let mut d = doc(&t, 4, json!({}));
    d["accessors"][0]["count"] = json!(1u64 << 40);
    match read_doc(&d, &t) {
        Err(Error::LimitExceeded(e)) => assert_eq!(e.what, Limited::Vertices),
        other => panic!("{other:?}"),
    }
}

#[test]
fn sparse_and_viewless_accessors() {
    let t = [0, 1, 4];
    let mut d = doc(&t, 4, json!({}));
    // Positions all zero but vertex 1, given by a sparse value that
    // reuses the bytes of POSITIONS[2] (offset 24) as its value and
    // index 1 (the u32 at offset 64, in the indices) as its index.
    d["accessors"][0] = json!({
        "componentType": 5126, "count": 5, "type": "VEC3",
        "sparse": {"count": 1,
            "indices": {"bufferView": 1, "byteOffset": 4, "componentType": 5125},
            "values": {"bufferView": 0, "byteOffset": 24}}
    });
    let m = read_doc(&d, &t).unwrap();
    assert_eq!(m.positions[0], [0.0; 3]);
    assert_eq!(m.positions[1], POSITIONS[2]);
    // A sparse index past the count.
    d["accessors"][0]["count"] = json!(1);
    assert!(matches!(
        malformed(read_doc(&d, &t)),
        Malformed::BadSyntax(_)
    ));
}

#[test]
fn document_errors() {
    let t = [0, 1, 4];
    let mut d = doc(&t, 4, json!({}));
    d["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    assert!(matches!(
        malformed(read_doc(&d, &t)),
        Malformed::Unsupported(_)
    ));
    let gltf = |s: &str| read_mesh_bytes(s.as_bytes(), MeshFormat::Gltf, &Limits::default());
    assert_eq!(malformed(gltf("{\"asset\":")), Malformed::Truncated);
    assert!(matches!(malformed(gltf("{\n]")), Malformed::BadSyntax(_)));
    assert!(matches!(malformed(gltf("{}")), Malformed::BadSyntax(_)));
    assert_eq!(malformed(gltf("")), Malformed::Empty);
    // Nodes naming a mesh the file does not have.
    let mut d = doc(&t, 4, json!({}));
    d["nodes"][0]["mesh"] = json!(3);
    assert!(matches!(
        malformed(read_doc(&d, &t)),
        Malformed::BadSyntax(_)
    ));
}

/// No prefix of a valid GLB file panics; each is an error or, cut past
/// the buffer's end, a shorter mesh.
#[test]
fn every_truncation() {
    let t = [0, 1, 4, 1, 2, 4];
    let whole = glb(&doc(&t, 4, json!({})), &bin(&t));
    for cut in 0..whole.len() {
        let mut cut_file = whole[..cut].to_vec();
        // Keep the header's length honest, so the chunks are what is cut.
        if cut >= 12 {
            cut_file[8..12].copy_from_slice(&(cut as u32).to_le_bytes());
        }
        assert!(read(&cut_file).is_err(), "cut at {cut}");
    }
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("swm-gltf-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn external_buffers() {
    let t = [0, 1, 4];
    let dir = scratch("external");
    std::fs::write(dir.join("b.bin"), bin(&t)).unwrap();
    std::fs::create_dir(dir.join("folder.bin")).unwrap();
    let path = dir.join("m.gltf");
    let with_uri = |uri: &str| {
        let mut d = doc(&t, 4, json!({}));
        d["buffers"][0]["uri"] = json!(uri);
        std::fs::write(&path, serde_json::to_vec(&d).unwrap()).unwrap();
    };
    with_uri("b.bin");
    assert_eq!(read_mesh(&path).unwrap().face_count(), 1);
    with_uri("./sub/../b.bin");
    std::fs::create_dir(dir.join("sub")).unwrap();
    assert_eq!(read_mesh(&path).unwrap().face_count(), 1);

    with_uri("folder.bin");
    match read_mesh(&path) {
        Err(Error::ExternalFile { path, error }) => {
            assert!(path.ends_with("folder.bin"));
            assert!(matches!(*error, Error::Input(_)), "{error:?}");
        }
        other => panic!("{other:?}"),
    }
    for refused in [
        "/etc/hosts",
        "http://example.com/b.bin",
        "file:///b.bin",
        "data:,abc",
    ] {
        with_uri(refused);
        let what = match read_mesh(&path) {
            Err(Error::Format(e)) => e.what,
            other => panic!("{refused}: {other:?}"),
        };
        assert!(matches!(what, Malformed::Unsupported(_)), "{refused}");
    }
    // One budget for the document and its buffers.
    with_uri("b.bin");
    let doc_len = std::fs::metadata(&path).unwrap().len();
    let tight = Limits {
        max_input_bytes: doc_len + 72 - 1,
        ..Limits::default()
    };
    match super::super::read_mesh_with(&path, &tight) {
        Err(Error::ExternalFile { error, .. }) => {
            assert!(matches!(*error, Error::LimitExceeded(_)), "{error:?}")
        }
        other => panic!("{other:?}"),
    }
    let enough = Limits {
        max_input_bytes: doc_len + 72,
        ..Limits::default()
    };
    assert!(super::super::read_mesh_with(&path, &enough).is_ok());
    let _ = std::fs::remove_dir_all(&dir);
}

/// NORMAL, TEXCOORD_n and COLOR_n of a drawn primitive are reported as
/// dropped; a file with POSITION alone drops nothing.
#[test]
fn reports_dropped_attributes() {
    let dropped = |attributes: Value| {
        let mut d = doc(&[0, 1, 2], 4, json!({}));
        d["meshes"][0]["primitives"][0]["attributes"] = attributes;
        // Texture coordinates: two floats for each of the 5 vertices.
        d["accessors"]
            .as_array_mut()
            .unwrap()
            .push(json!({"bufferView": 0, "componentType": 5126, "count": 5, "type": "VEC2"}));
        let bytes = glb(&d, &bin(&[0, 1, 2]));
        crate::io::read_mesh_bytes_with_report(&bytes, MeshFormat::Glb, &Limits::default())
            .unwrap()
            .1
            .dropped
    };
    assert!(dropped(json!({"POSITION": 0})).is_empty());
    let d = dropped(json!({"POSITION": 0, "TEXCOORD_0": 2}));
    assert!(d.uv && !d.normals && !d.colors, "{d:?}");
    let d = dropped(json!({"POSITION": 0, "NORMAL": 0, "COLOR_0": 0}));
    assert!(!d.uv && d.normals && d.colors, "{d:?}");
}
