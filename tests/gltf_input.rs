//! glTF 2.0 input: `.gltf` with an external `.bin` or an embedded
//! `data:` URI, and `.glb`, all holding the same scene: one tetrahedron
//! instanced by two nodes, one moved by a `matrix`, the other the child
//! of a scaled node and moved by its own `translation`. Each reads as
//! both instances merged, in world space; `swm encode` takes them.

mod common;
use common::*;
use serde_json::{json, Value};
use std::path::Path;

/// The tetrahedron every file instances.
const POSITIONS: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];
const TRIANGLES: [[u16; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// Where each instance's vertex lands: node 0 is translated by (10, 0, 0)
/// through its matrix; node 2 by (0, 1, 0), under node 1's scale of 2.
fn expected() -> Vec<[f32; 3]> {
    let a = POSITIONS.map(|[x, y, z]| [x + 10.0, y, z]);
    let b = POSITIONS.map(|[x, y, z]| [2.0 * x, 2.0 * (y + 1.0), 2.0 * z]);
    a.into_iter().chain(b).collect()
}

/// The buffer: positions (48 bytes) then u16 indices (24 bytes).
fn bin() -> Vec<u8> {
    let mut b: Vec<u8> = POSITIONS
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    b.extend(TRIANGLES.iter().flatten().flat_map(|i| i.to_le_bytes()));
    b
}

/// The document, its one buffer given by `buffer` (a `uri`, or nothing
/// for a GLB's BIN chunk).
fn document(buffer: Value) -> Value {
    let mut buffer = buffer;
    buffer["byteLength"] = json!(72);
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 10,0,0,1]},
            {"scale": [2, 2, 2], "children": [2]},
            {"mesh": 0, "translation": [0, 1, 0]}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 24}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}
        ]
    })
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = c
            .iter()
            .enumerate()
            .fold(0u32, |n, (k, &b)| n | u32::from(b) << (16 - 8 * k));
        for k in 0..4 {
            s.push(if k <= c.len() {
                A[(n >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}

/// The three files, written into `dir`: external buffer (with a space in
/// its name, so its URI is percent-encoded), data URI, GLB.
fn write_files(dir: &Path) -> [std::path::PathBuf; 3] {
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(dir.join("data/tet buffer.bin"), bin()).unwrap();
    let external = dir.join("external.gltf");
    let doc = document(json!({"uri": "data/tet%20buffer.bin"}));
    std::fs::write(&external, serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    let embedded = dir.join("embedded.gltf");
    let uri = format!("data:application/octet-stream;base64,{}", base64(&bin()));
    std::fs::write(
        &embedded,
        serde_json::to_vec(&document(json!({"uri": uri}))).unwrap(),
    )
    .unwrap();
    let binary = dir.join("binary.glb");
    std::fs::write(&binary, glb(&document(json!({})), &bin())).unwrap();
    [external, embedded, binary]
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn instances_are_merged_in_world_space() {
    let dir = scratch("gltf_input");
    for path in write_files(&dir) {
        let mesh = swm::io::read_mesh(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
        assert_eq!(mesh.vertex_count(), 8, "{path:?}");
        assert_eq!(mesh.face_count(), 8, "{path:?}");
        assert_eq!(mesh.positions, expected(), "{path:?}");
        let tri: Vec<[u32; 3]> = TRIANGLES.iter().map(|t| t.map(u32::from)).collect();
        let shifted = tri.iter().map(|t| t.map(|i| i + 4));
        let all: Vec<[u32; 3]> = tri.iter().copied().chain(shifted).collect();
        assert_eq!(mesh.triangles, all, "{path:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The bytes alone: a GLB or an embedded `.gltf` reads the same; a
/// `.gltf` whose buffer is another file cannot be resolved.
#[test]
fn from_bytes() {
    let limits = swm::Limits::default();
    let read = |b: &[u8], f| swm::io::read_mesh_bytes(b, f, &limits);
    let mesh = read(&glb(&document(json!({})), &bin()), swm::io::MeshFormat::Glb).unwrap();
    assert_eq!(mesh.positions, expected());
    let external = serde_json::to_vec(&document(json!({"uri": "tet.bin"}))).unwrap();
    match read(&external, swm::io::MeshFormat::Gltf) {
        Err(swm::Error::Format(e)) => {
            assert!(matches!(e.what, swm::Malformed::Unsupported(_)), "{e}")
        }
        other => panic!("{other:?}"),
    }
}

/// The CLI: encode a GLB and a `.gltf`, decode, and get both instances.
#[test]
fn cli_encodes_gltf_and_glb() {
    let dir = scratch("gltf_cli");
    let [external, _, binary] = write_files(&dir);
    for input in [&binary, &external] {
        let swm_file = dir.join("out.swm");
        ok(&swm(&[
            "encode",
            s(input),
            "-o",
            s(&swm_file),
            "--mode",
            "lossless",
        ]));
        let obj = dir.join("out.obj");
        ok(&swm(&["decode", s(&swm_file), "-o", s(&obj)]));
        let back = swm::io::read_mesh(&obj).unwrap();
        assert_eq!(
            (back.vertex_count(), back.face_count()),
            (8, 8),
            "{input:?}"
        );
        let info = json(&swm(&["info", s(input), "--json"]));
        assert_eq!(info["components"], 2, "{input:?}");
    }
    // A missing external buffer names the file that is missing.
    std::fs::remove_file(dir.join("data/tet buffer.bin")).unwrap();
    let o = swm(&["info", s(&external)]);
    assert!(!o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("tet buffer.bin"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A primitive that draws no triangles (`LINES` here) is refused by
/// `swm encode` with one line naming the file and the mode, rather
/// than read as triangles or skipped.
#[test]
fn cli_refuses_other_primitive_modes() {
    let dir = scratch("gltf_modes");
    let mut doc = document(json!({}));
    doc["meshes"][0]["primitives"][0]["mode"] = json!(1);
    let lines = dir.join("lines.glb");
    std::fs::write(&lines, glb(&doc, &bin())).unwrap();
    let out = dir.join("out.swm");
    let o = swm(&["encode", s(&lines), "-o", s(&out), "--mode", "lossless"]);
    assert_eq!(o.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("swm: error: {}: ", s(&lines))) && stderr.contains("LINES"),
        "{stderr}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
