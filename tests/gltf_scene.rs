//! Whole glTF scenes (issue 47, item 4; format-spec/09-gltf.md): `swm
//! encode scene.glb -o out.glb` codes each triangle primitive inside
//! `SWM_mesh_compression` and keeps the rest; `swm decode out.glb -o
//! plain.glb` expands it. The scene is built here: a textured mesh with
//! normals and UVs drawn by two nodes, a mesh of positions only, a
//! skinned mesh (JOINTS_0, WEIGHTS_0, kept uncompressed and said so), two
//! materials, an embedded PNG image, an animation. After the round trip
//! the node tree, materials, textures, images, skin and animation are
//! identical, positions lie within the quantization and UVs within one
//! quantization step.

mod common;
use common::*;
use serde_json::{json, Value};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A 1×1 PNG (a valid image, so that validators can read it).
const PNG: &[u8] = &[
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
    0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53,
    0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x08, 0xd7, 0x63, 0xf8, 0xcf, 0xc0, 0x00,
    0x00, 0x03, 0x01, 0x01, 0x00, 0x18, 0xdd, 0x8d, 0xb0, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e,
    0x44, 0xae, 0x42, 0x60, 0x82,
];

/// Builds the JSON and BIN of a GLB, one tightly packed bufferView per
/// accessor.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = t.into();
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn floats(&mut self, values: &[f32], ty: &str, target: Option<u32>, bounds: bool) -> usize {
        let dims = match ty {
            "SCALAR" => 1,
            "VEC2" => 2,
            "VEC3" => 3,
            "VEC4" => 4,
            _ => 16,
        };
        let bytes: Vec<u8> = values.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, target);
        let mut a = json!({ "bufferView": view, "componentType": 5126, "count": values.len() / dims, "type": ty });
        if bounds {
            let mut min = vec![f32::INFINITY; dims];
            let mut max = vec![f32::NEG_INFINITY; dims];
            for v in values.chunks(dims) {
                for k in 0..dims {
                    min[k] = min[k].min(v[k]);
                    max[k] = max[k].max(v[k]);
                }
            }
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn indices(&mut self, triangles: &[[u32; 3]]) -> usize {
        let bytes: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|&i| (i as u16).to_le_bytes())
            .collect();
        let view = self.view(&bytes, Some(34963));
        self.accessors.push(json!({ "bufferView": view, "componentType": 5123, "count": triangles.len() * 3, "type": "SCALAR" }));
        self.accessors.len() - 1
    }
}

/// The scene: see the module header.
fn scene() -> (Value, Vec<u8>) {
    let mut b = Builder::default();
    // Mesh 0: a sphere with normals and spherical UVs.
    let sphere = swm_corpus::icosphere(1.0, 3);
    let pos: Vec<f32> = sphere.positions.iter().flatten().copied().collect();
    let uv: Vec<f32> = sphere
        .positions
        .iter()
        .flat_map(|p| {
            [
                0.5 + p[1].atan2(p[0]) / std::f32::consts::TAU,
                0.5 - p[2] / 2.0,
            ]
        })
        .collect();
    let p0 = b.floats(&pos, "VEC3", Some(34962), true);
    b.accessors[p0]["name"] = "ball positions".into();
    let n0 = b.floats(&pos, "VEC3", Some(34962), false);
    let t0 = b.floats(&uv, "VEC2", Some(34962), false);
    let i0 = b.indices(&sphere.triangles);
    // Mesh 1: positions only, a coarser sphere, stretched.
    let blob = swm_corpus::icosphere(1.0, 2);
    let pos1: Vec<f32> = blob
        .positions
        .iter()
        .flat_map(|p| [p[0] * 2.0, p[1], p[2] * 0.5])
        .collect();
    let p1 = b.floats(&pos1, "VEC3", Some(34962), true);
    let i1 = b.indices(&blob.triangles);
    // Mesh 2: a skinned quad strip of 8 vertices, two joints.
    let strip: Vec<f32> = (0..8)
        .flat_map(|i| [(i / 2) as f32, (i % 2) as f32, 0.0])
        .collect();
    let p2 = b.floats(&strip, "VEC3", Some(34962), true);
    let joints: Vec<u8> = (0..8).flat_map(|i| [u8::from(i >= 4), 0, 0, 0]).collect();
    let jv = b.view(&joints, Some(34962));
    b.accessors
        .push(json!({ "bufferView": jv, "componentType": 5121, "count": 8, "type": "VEC4" }));
    let j2 = b.accessors.len() - 1;
    let weights: Vec<f32> = (0..8).flat_map(|_| [1.0, 0.0, 0.0, 0.0]).collect();
    let w2 = b.floats(&weights, "VEC4", Some(34962), false);
    let strip_tris: Vec<[u32; 3]> = (0..6u32)
        .map(|i| {
            if i % 2 == 0 {
                [i, i + 1, i + 2]
            } else {
                [i + 1, i, i + 2]
            }
        })
        .collect();
    let i2 = b.indices(&strip_tris);
    let ibm: Vec<f32> = [[
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0f32,
    ]; 2]
        .concat();
    let inverse_bind = b.floats(&ibm, "MAT4", None, false);
    // The animation: node 1 moves along x.
    let times = b.floats(&[0.0, 1.0, 2.0], "SCALAR", None, true);
    let moves = b.floats(
        &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        "VEC3",
        None,
        false,
    );
    let image = b.view(PNG, None);
    let doc = json!({
        "asset": { "version": "2.0", "generator": "swm test" },
        "scene": 0,
        "scenes": [{ "name": "world", "nodes": [0] }],
        "nodes": [
            { "name": "root", "children": [1, 2, 3, 4, 5] },
            { "name": "ball", "mesh": 0, "translation": [3.0, 0.0, 0.0] },
            { "name": "ball again", "mesh": 0, "rotation": [0.0, 0.0, 0.7071068, 0.7071068], "scale": [0.5, 0.5, 0.5] },
            { "name": "blob", "mesh": 1, "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -4.0, 0.0, 1.0] },
            { "name": "skinned", "mesh": 2, "skin": 0 },
            { "name": "bone", "children": [6], "extras": { "kept": [1, 2, 3] } },
            { "name": "bone tip", "translation": [2.0, 0.0, 0.0] }
        ],
        "meshes": [
            { "name": "ball", "primitives": [{ "attributes": { "POSITION": p0, "NORMAL": n0, "TEXCOORD_0": t0 }, "indices": i0, "material": 0 }] },
            { "name": "blob", "primitives": [{ "attributes": { "POSITION": p1 }, "indices": i1, "material": 1 }] },
            { "name": "strip", "primitives": [{ "attributes": { "POSITION": p2, "JOINTS_0": j2, "WEIGHTS_0": w2 }, "indices": i2, "material": 1 }] }
        ],
        "skins": [{ "joints": [5, 6], "inverseBindMatrices": inverse_bind, "skeleton": 5 }],
        "materials": [
            { "name": "textured", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0 } },
            { "name": "red", "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.1, 0.1, 1.0] }, "doubleSided": true }
        ],
        "textures": [{ "sampler": 0, "source": 0 }],
        "samplers": [{ "magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497 }],
        "images": [{ "bufferView": image, "mimeType": "image/png", "name": "checker" }],
        "animations": [{ "name": "slide", "channels": [{ "sampler": 0, "target": { "node": 1, "path": "translation" } }],
                         "samplers": [{ "input": times, "output": moves, "interpolation": "LINEAR" }] }],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{ "byteLength": b.bin.len() }],
        "extras": { "author": "test" }
    });
    (doc, b.bin)
}

/// A GLB file's JSON and BIN chunk.
fn chunks(bytes: &[u8]) -> (Value, Vec<u8>) {
    assert_eq!(&bytes[..4], b"glTF");
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let doc = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
    let bin = if bytes.len() > 20 + len {
        let n = u32::from_le_bytes(bytes[20 + len..24 + len].try_into().unwrap()) as usize;
        bytes[28 + len..28 + len + n].to_vec()
    } else {
        Vec::new()
    };
    (doc, bin)
}

/// The bytes of bufferView `v`.
fn view(doc: &Value, bin: &[u8], v: &Value) -> Vec<u8> {
    let v = &doc["bufferViews"][v.as_u64().unwrap() as usize];
    let at = v["byteOffset"].as_u64().unwrap_or(0) as usize;
    bin[at..at + v["byteLength"].as_u64().unwrap() as usize].to_vec()
}

/// The bytes of accessor `a` (tightly packed), with its description.
fn accessor(doc: &Value, bin: &[u8], a: &Value) -> (Value, Vec<u8>) {
    let acc = doc["accessors"][a.as_u64().unwrap() as usize].clone();
    let mut data = view(doc, bin, &acc["bufferView"]);
    data.drain(..acc["byteOffset"].as_u64().unwrap_or(0) as usize);
    let mut desc = acc.clone();
    for key in ["bufferView", "byteOffset"] {
        desc.as_object_mut().unwrap().remove(key);
    }
    (desc, data)
}

fn floats(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
        .collect()
}

fn indices(doc: &Value, bin: &[u8], a: &Value) -> Vec<u32> {
    let (desc, data) = accessor(doc, bin, a);
    match desc["componentType"].as_u64().unwrap() {
        5123 => data
            .chunks_exact(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]).into())
            .collect(),
        5125 => data
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
            .collect(),
        t => panic!("index type {t}"),
    }
}

/// Everything of the scene but its buffers, bufferViews, accessors and
/// the coded primitives' attributes: what must come back identical.
fn kept(doc: &Value) -> Value {
    let mut d = doc.clone();
    let o = d.as_object_mut().unwrap();
    for key in [
        "buffers",
        "bufferViews",
        "accessors",
        "extensionsUsed",
        "extensionsRequired",
    ] {
        o.remove(key);
    }
    for img in d["images"].as_array_mut().unwrap() {
        img.as_object_mut().unwrap().remove("bufferView");
    }
    for skin in d["skins"].as_array_mut().unwrap() {
        skin.as_object_mut().unwrap().remove("inverseBindMatrices");
    }
    for a in d["animations"].as_array_mut().unwrap() {
        for s in a["samplers"].as_array_mut().unwrap() {
            let s = s.as_object_mut().unwrap();
            s.remove("input");
            s.remove("output");
        }
    }
    for m in d["meshes"].as_array_mut().unwrap() {
        for p in m["primitives"].as_array_mut().unwrap() {
            let p = p.as_object_mut().unwrap();
            for key in ["attributes", "indices", "extensions", "mode"] {
                p.remove(key);
            }
        }
    }
    d
}

/// The buffer data the kept objects refer to: image, inverse bind
/// matrices, animation samplers, the skinned primitive's accessors.
fn kept_data(doc: &Value, bin: &[u8]) -> Vec<(Value, Vec<u8>)> {
    let mut out = vec![(Value::Null, view(doc, bin, &doc["images"][0]["bufferView"]))];
    out.push(accessor(doc, bin, &doc["skins"][0]["inverseBindMatrices"]));
    for s in doc["animations"][0]["samplers"].as_array().unwrap() {
        out.push(accessor(doc, bin, &s["input"]));
        out.push(accessor(doc, bin, &s["output"]));
    }
    let p = &doc["meshes"][2]["primitives"][0];
    for name in ["POSITION", "JOINTS_0", "WEIGHTS_0"] {
        out.push(accessor(doc, bin, &p["attributes"][name]));
    }
    out.push(accessor(doc, bin, &p["indices"]));
    out
}

#[test]
fn a_scene_round_trips_with_everything_but_its_geometry_identical() {
    let dir = scratch("gltf-scene");
    let (doc, bin) = scene();
    let input = dir.join("scene.glb");
    std::fs::write(&input, glb(&doc, &bin)).unwrap();
    let out = dir.join("out.glb");
    let run = swm(&["encode", s(&input), "-o", s(&out), "--json"]);
    let report = json(&run);
    let stderr = String::from_utf8_lossy(&run.stderr);
    // The skinned primitive is kept, and said so in one line, by name.
    let line = "kept uncompressed: mesh 2 \"strip\" primitive 0 (JOINTS_0, WEIGHTS_0)";
    assert!(stderr.contains(line), "{stderr}");
    assert_eq!(
        stderr
            .lines()
            .filter(|l| l.contains("kept uncompressed"))
            .count(),
        1
    );
    assert_eq!(
        report["uncompressed"],
        json!(["mesh 2 \"strip\" primitive 0 (JOINTS_0, WEIGHTS_0)"])
    );
    let prims = report["primitives"].as_array().unwrap();
    // Without a size, rate or error bound (the default rate counts
    // positions only), a textured primitive keeps its own triangles.
    assert_eq!(
        prims[0]["method"], "lossless",
        "attributes are coded losslessly without a target"
    );
    assert_eq!(prims[0]["attributes"], json!(["NORMAL", "TEXCOORD_0"]));
    assert_eq!(prims[1]["coded"], true);
    assert_eq!(prims[2]["coded"], false);

    // The coded file: the extension is required, the accessors of coded
    // primitives have no data, the rest is as it was.
    let encoded = std::fs::read(&out).unwrap();
    let (edoc, ebin) = chunks(&encoded);
    assert_eq!(edoc["extensionsRequired"], json!(["SWM_mesh_compression"]));
    assert_eq!(edoc["extensionsUsed"], json!(["SWM_mesh_compression"]));
    let e0 = &edoc["meshes"][0]["primitives"][0];
    let ext = &e0["extensions"]["SWM_mesh_compression"];
    assert!(ext["bufferView"].is_u64());
    assert_eq!(ext["attributes"], json!({ "NORMAL": 0, "TEXCOORD_0": 1 }));
    let pa = &edoc["accessors"][e0["attributes"]["POSITION"].as_u64().unwrap() as usize];
    assert!(pa.get("bufferView").is_none() && pa["min"].is_array());
    assert_eq!(kept(&edoc), kept(&doc));
    assert_eq!(kept_data(&edoc, &ebin), kept_data(&doc, &bin));
    assert!(
        encoded.len() < glb(&doc, &bin).len() / 2,
        "{} bytes",
        encoded.len()
    );

    // `info` lists the primitives and their sizes.
    let info = json(&swm(&["info", s(&out), "--json"]));
    let list = info["primitives"].as_array().unwrap();
    assert_eq!(list.len(), 3);
    assert_eq!(list[0]["swm_bytes"], prims[0]["bytes"]);
    assert!(list[2]["swm_bytes"].is_null());

    // Decoded: plain accessors, no extension, everything else identical.
    let plain = dir.join("plain.glb");
    ok(&swm(&["decode", s(&out), "-o", s(&plain)]));
    let (pdoc, pbin) = chunks(&std::fs::read(&plain).unwrap());
    assert!(pdoc.get("extensionsUsed").is_none() && pdoc.get("extensionsRequired").is_none());
    assert_eq!(kept(&pdoc), kept(&doc));
    assert_eq!(kept_data(&pdoc, &pbin), kept_data(&doc, &bin));
    gltf::Gltf::from_slice(&std::fs::read(&plain).unwrap()).expect("a valid document");

    // The ball: its own triangles (as many), positions within half a step
    // of 12 bits of its box, UVs within one step of 10 bits.
    let p = &pdoc["meshes"][0]["primitives"][0];
    let (desc, _) = accessor(&pdoc, &pbin, &p["attributes"]["POSITION"]);
    assert_eq!(desc["name"], "ball positions", "an accessor's name is kept");
    let pos = floats(&accessor(&pdoc, &pbin, &p["attributes"]["POSITION"]).1);
    let uv = floats(&accessor(&pdoc, &pbin, &p["attributes"]["TEXCOORD_0"]).1);
    let normal = floats(&accessor(&pdoc, &pbin, &p["attributes"]["NORMAL"]).1);
    assert_eq!(indices(&pdoc, &pbin, &p["indices"]).len(), 1280 * 3);
    let sphere = swm_corpus::icosphere(1.0, 3);
    let step = 2.0 / 4095.0;
    for (k, q) in pos.chunks_exact(3).enumerate() {
        let (i, d) = sphere
            .positions
            .iter()
            .enumerate()
            .map(|(i, p)| {
                (
                    i,
                    (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0f32, f32::max),
                )
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(d <= step, "vertex {k} is {d} from the input");
        let p = sphere.positions[i];
        let want = [
            0.5 + p[1].atan2(p[0]) / std::f32::consts::TAU,
            0.5 - p[2] / 2.0,
        ];
        for c in 0..2 {
            let du = (uv[2 * k + c] - want[c]).abs();
            assert!(du <= 1.0 / 1023.0 + 1e-6, "vertex {k}: UV {c} off by {du}");
        }
        let n = &normal[3 * k..3 * k + 3];
        assert!(((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() - 1.0).abs() < 1e-3);
    }
}

#[test]
fn strict_refuses_to_leave_a_primitive_uncompressed_and_writes_nothing() {
    let dir = scratch("gltf-scene-strict");
    let (doc, bin) = scene();
    let input = dir.join("scene.glb");
    std::fs::write(&input, glb(&doc, &bin)).unwrap();
    let out = dir.join("out.glb");
    let run = swm(&["encode", s(&input), "-o", s(&out), "--strict"]);
    assert_eq!(run.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&run.stderr).contains("JOINTS_0, WEIGHTS_0"));
    assert!(!out.exists());
}

#[test]
fn a_size_is_split_and_gltf_output_with_fallback_decodes_the_same() {
    let dir = scratch("gltf-scene-size");
    let (doc, bin) = scene();
    let input = dir.join("scene.glb");
    std::fs::write(&input, glb(&doc, &bin)).unwrap();
    // Lossless mode: every codable primitive keeps its triangles.
    let out = dir.join("out.gltf");
    let report = json(&swm(&[
        "encode",
        s(&input),
        "-o",
        s(&out),
        "--mode",
        "lossless",
        "--gltf-fallback",
        "--json",
    ]));
    assert_eq!(report["primitives"][1]["method"], "lossless");
    let text: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert!(
        text.get("extensionsRequired").is_none(),
        "a fallback needs no requirement"
    );
    assert_eq!(text["extensionsUsed"], json!(["SWM_mesh_compression"]));
    assert!(text["buffers"][0]["uri"]
        .as_str()
        .unwrap()
        .starts_with("data:"));
    let plain = dir.join("plain.glb");
    ok(&swm(&["decode", s(&out), "-o", s(&plain)]));
    let (pdoc, _) = chunks(&std::fs::read(&plain).unwrap());
    assert_eq!(kept(&pdoc), kept(&doc));

    // A size for the whole scene, split by area between the textured
    // ball (coded at its share by a method that keeps its normals and
    // texture coordinates, their bytes counted in it) and the blob.
    let sized = dir.join("sized.glb");
    let report = json(&swm(&[
        "encode",
        s(&input),
        "-o",
        s(&sized),
        "--size",
        "6000",
        "--json",
    ]));
    assert_eq!(report["requested"], 6000);
    let shares: Vec<u64> = (0..2)
        .map(|k| report["primitives"][k]["share"].as_u64().unwrap())
        .collect();
    assert!(shares.iter().sum::<u64>() <= 6000 && shares.iter().sum::<u64>() >= 5990);
    for (k, &share) in shares.iter().enumerate() {
        let bytes = report["primitives"][k]["bytes"].as_u64().unwrap();
        // Within rate control's 3%, or short of it when the whole
        // primitive fits.
        assert!(bytes * 100 <= share * 103, "{bytes} bytes for {share}");
    }
    assert_eq!(
        report["primitives"][0]["attributes"],
        json!(["NORMAL", "TEXCOORD_0"])
    );
    assert_eq!(report["primitives"][0]["method"], "simplified");
    // The file decodes to the same scene as the unsized one, textured.
    let plain = dir.join("sized-plain.glb");
    ok(&swm(&["decode", s(&sized), "-o", s(&plain)]));
    let (pdoc, _) = chunks(&std::fs::read(&plain).unwrap());
    assert_eq!(kept(&pdoc), kept(&doc));
    assert!(pdoc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].is_u64());
}

/// A scene whose largest primitive by area is two triangles: the
/// budget its share leaves unspent goes to the detailed one (the split
/// is filled like water), so the scene spends what it was given.
#[test]
fn a_share_one_primitive_cannot_use_goes_to_the_others() {
    let dir = scratch("gltf-scene-water");
    let mut b = Builder::default();
    let quad: Vec<f32> = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    let p0 = b.floats(&quad, "VEC3", Some(34962), true);
    let i0 = b.indices(&[[0, 1, 2], [0, 2, 3]]);
    // A bumpy ball: a regular sphere codes whole in a few bytes a face.
    let ball = swm_corpus::icosphere(1.0, 5);
    let mut seed = 12345u32;
    let pos: Vec<f32> = (ball.positions.iter())
        .flat_map(|p| {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let r = 1.0 + 0.05 * (seed >> 8) as f32 / (1u32 << 24) as f32;
            p.map(|c| c * r)
        })
        .collect();
    let p1 = b.floats(&pos, "VEC3", Some(34962), true);
    let i1 = b.indices(&ball.triangles);
    let doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0, 1] }],
        "nodes": [
            { "name": "floor", "mesh": 0, "scale": [40.0, 40.0, 1.0] },
            { "name": "ball", "mesh": 1 }
        ],
        "meshes": [
            { "primitives": [{ "attributes": { "POSITION": p0 }, "indices": i0 }] },
            { "primitives": [{ "attributes": { "POSITION": p1 }, "indices": i1 }] }
        ],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{ "byteLength": b.bin.len() }]
    });
    let input = dir.join("scene.glb");
    std::fs::write(&input, glb(&doc, &b.bin)).unwrap();
    let size = 8_000u64;
    let report = json(&swm(&[
        "encode",
        s(&input),
        "-o",
        s(&dir.join("out.glb")),
        "--size",
        &size.to_string(),
        "--json",
    ]));
    let prims = report["primitives"].as_array().unwrap();
    let bytes: Vec<u64> = prims.iter().map(|p| p["bytes"].as_u64().unwrap()).collect();
    let shares: Vec<u64> = prims.iter().map(|p| p["share"].as_u64().unwrap()).collect();
    // The floor is whole in a few dozen bytes; the ball gets the rest.
    assert_eq!(prims[0]["triangles"], 2);
    assert!(
        prims[1]["triangles"].as_u64().unwrap() < prims[1]["input_triangles"].as_u64().unwrap()
    );
    let spent: u64 = bytes.iter().sum();
    assert!(
        spent * 10 >= size * 9 && spent <= size * 103 / 100,
        "{spent} of {size}: {prims:?}"
    );
    // Shares: what the floor took, and the rest of the budget.
    assert_eq!(shares[0], bytes[0]);
    assert!(
        shares.iter().sum::<u64>() <= size && shares.iter().sum::<u64>() + 2 >= size,
        "{shares:?}"
    );
}

/// The Khronos glTF-Validator's error count for each file (npm package
/// `gltf-validator`, installed by `.ci/setup-gltf-validator`), and its
/// report's messages; `None` (a reported skip) without Node or the package.
fn validator_errors(files: &[&Path]) -> Option<Vec<(u64, String)>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/gltf-validator");
    let module = root.join("node_modules/gltf-validator/index.js");
    let node = std::process::Command::new("node").arg("--version").output();
    if !node.is_ok_and(|o| o.status.success()) || !module.is_file() {
        common::skip("gltf-validator not found (node and .ci/setup-gltf-validator)");
        return None;
    }
    let script = format!(
        r#"const v = require({module:?}); const fs = require("fs");
(async () => {{ for (const f of process.argv.slice(1)) {{
  const r = await v.validateBytes(new Uint8Array(fs.readFileSync(f)));
  const errors = r.issues.messages.filter(m => m.severity === 0).map(m => m.code + " " + m.pointer + " " + m.message);
  console.log(JSON.stringify([r.issues.numErrors, errors.join("; ")]));
}} }})();"#
    );
    let out = std::process::Command::new("node")
        .arg("-e")
        .arg(script)
        .args(files)
        .output()
        .expect("run node");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect(),
    )
}

#[test]
fn the_khronos_validator_reports_no_errors_on_any_output() {
    let dir = scratch("gltf-scene-validator");
    let (doc, bin) = scene();
    let input = dir.join("scene.glb");
    std::fs::write(&input, glb(&doc, &bin)).unwrap();
    let files = [
        ("out.glb", vec![]),
        ("lossless.glb", vec!["--mode", "lossless"]),
        ("fallback.gltf", vec!["--gltf-fallback"]),
        ("sized.glb", vec!["--size", "5000"]),
    ];
    let mut outputs = vec![input.clone()];
    for (name, extra) in &files {
        let out = dir.join(name);
        let mut args = vec!["encode", s(&input), "-o", s(&out)];
        args.extend(extra);
        ok(&swm(&args));
        let plain = dir.join(format!("plain-{name}"));
        ok(&swm(&["decode", s(&out), "-o", s(&plain)]));
        outputs.push(out);
        outputs.push(plain);
    }
    // The ball with normals and no texture coordinates, by SwingWrapper,
    // whose files carry normals (format 1.2's ATTR over a retiled mesh).
    let mut normals_only = doc.clone();
    let ball = &mut normals_only["meshes"][0]["primitives"][0];
    ball["attributes"]
        .as_object_mut()
        .unwrap()
        .remove("TEXCOORD_0");
    ball.as_object_mut().unwrap().remove("material");
    let input = dir.join("normals.glb");
    std::fs::write(&input, glb(&normals_only, &bin)).unwrap();
    let (out, plain) = (dir.join("swing.glb"), dir.join("plain-swing.glb"));
    let report = json(&swm(&[
        "encode",
        s(&input),
        "-o",
        s(&out),
        "--mode",
        "swing",
        "--bpv",
        "12",
        "--json",
    ]));
    assert_eq!(report["primitives"][0]["method"], "swing", "{report}");
    ok(&swm(&["decode", s(&out), "-o", s(&plain)]));
    let (pdoc, _) = chunks(&std::fs::read(&plain).unwrap());
    assert!(pdoc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].is_u64());
    outputs.extend([input, out, plain]);
    let paths: Vec<&Path> = outputs.iter().map(|p| p.as_path()).collect();
    let Some(errors) = validator_errors(&paths) else {
        return;
    };
    for (path, (count, messages)) in paths.iter().zip(errors) {
        assert_eq!(count, 0, "{}: {messages}", path.display());
    }
}

/// The scene decoder treats every byte as hostile: every truncation, and
/// an extension or accessor that lies, is an error, never a panic.
#[test]
fn the_scene_decoder_refuses_lies_and_truncations() {
    let (doc, bin) = scene();
    let options = swm::io::SceneOptions {
        encode: swm::EncodeOptions {
            mode: swm::EncodeMode::Lossless { qp: 11 },
            ..Default::default()
        },
        ..Default::default()
    };
    let encoded = swm::io::encode_scene(&glb(&doc, &bin), None, &options).unwrap();
    // Deterministic.
    let again = swm::io::encode_scene(&glb(&doc, &bin), None, &options).unwrap();
    assert_eq!(encoded.bytes, again.bytes);
    let decode = |bytes: &[u8]| {
        swm::io::decode_scene(
            bytes,
            None,
            &swm::DecodeOptions::default(),
            swm::io::SceneFormat::Glb,
        )
    };
    decode(&encoded.bytes).unwrap();
    for cut in (0..encoded.bytes.len()).step_by(7) {
        assert!(decode(&encoded.bytes[..cut]).is_err(), "cut at {cut}");
    }
    let (edoc, ebin) = chunks(&encoded.bytes);
    let p = "/meshes/0/primitives/0";
    let lies: Vec<(&str, Value)> = vec![
        (
            "/extensions/SWM_mesh_compression/attributes/NORMAL",
            json!(7),
        ),
        (
            "/extensions/SWM_mesh_compression/attributes/NORMAL",
            json!(1),
        ),
        ("/extensions/SWM_mesh_compression/bufferView", json!(0)),
        ("/extensions/SWM_mesh_compression/bufferView", json!(999)),
        ("/mode", json!(5)),
    ];
    for (at, value) in lies {
        let mut d = edoc.clone();
        let (parent, key) = at.rsplit_once('/').unwrap();
        d.pointer_mut(&format!("{p}{parent}")).unwrap()[key] = value;
        assert!(decode(&glb(&d, &ebin)).is_err(), "{at}");
    }
    let position = edoc
        .pointer(&format!("{p}/attributes/POSITION"))
        .unwrap()
        .as_u64()
        .unwrap();
    for (key, value) in [
        ("count", json!(3)),
        ("type", json!("VEC4")),
        ("componentType", json!(5123)),
    ] {
        let mut d = edoc.clone();
        d["accessors"][position as usize][key] = value;
        assert!(decode(&glb(&d, &ebin)).is_err(), "{key}");
    }
    // Two primitives naming one accessor.
    let mut d = edoc.clone();
    let index = d.pointer(&format!("{p}/indices")).unwrap().clone();
    d["meshes"][1]["primitives"][0]["indices"] = index;
    assert!(decode(&glb(&d, &ebin)).is_err());
}
