//! Attribute streams through the readers and writers: round trips of
//! generated meshes with seams and colours in every writable format, the
//! statements and properties each reader takes, what is dropped and
//! reported, hostile counts, and spot.obj from the shared corpus.

use super::*;
use crate::mesh::test_shapes::{coloured_sphere, seamed_cube};
use crate::{AttributeKind, AttributeStream, FaceId, LimitError, Limited};

fn read_attributed(bytes: &[u8], format: MeshFormat) -> (AttributedMesh, ReadReport) {
    read_attributed_mesh_bytes(bytes, format, &Limits::default())
        .unwrap_or_else(|e| panic!("{format:?}: {e}"))
}

fn written(m: &AttributedMesh, format: MeshFormat) -> (Vec<u8>, WriteReport) {
    let mut bytes = Vec::new();
    let report = write_attributed_mesh_to(&mut bytes, format, m).unwrap();
    (bytes, report)
}

/// Every corner's position bits and, stream by stream in kind order, its
/// value bits: equal for two meshes with the same surface and attributes,
/// whatever their indexing.
fn corners(m: &AttributedMesh) -> Vec<Vec<u32>> {
    let mut streams: Vec<&AttributeStream> = m.streams.iter().collect();
    streams.sort_by_key(|s| s.kind);
    let mut out = Vec::new();
    for (f, t) in m.mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let mut c: Vec<u32> = m.mesh.positions[t[k] as usize].map(f32::to_bits).to_vec();
            for s in &streams {
                c.push(s.dims.into());
                c.extend(
                    s.corner_value(FaceId(f as u32), k)
                        .iter()
                        .map(|x| x.to_bits()),
                );
            }
            out.push(c);
        }
    }
    out
}

fn kinds(m: &AttributedMesh) -> Vec<AttributeKind> {
    let mut k: Vec<AttributeKind> = m.streams.iter().map(|s| s.kind).collect();
    k.sort();
    k
}

#[test]
fn generated_meshes_round_trip_exactly_in_every_format() {
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Off,
        MeshFormat::Glb,
    ] {
        for m in [seamed_cube(), coloured_sphere()] {
            let (bytes, report) = written(&m, format);
            // OBJ keeps RGB only; the sphere's colours are RGBA.
            let rgba_in_obj =
                format == MeshFormat::Obj && m.stream(AttributeKind::Color(0)).is_some();
            assert_eq!(report.unwritten.colors, rgba_in_obj, "{format:?}");
            let (back, read) = read_attributed(&bytes, format);
            back.validate().unwrap();
            if rgba_in_obj {
                assert!(back.streams.is_empty());
                continue;
            }
            assert!(read.dropped.is_empty(), "{format:?}: {:?}", read.dropped);
            let mut expected = m.clone();
            if format == MeshFormat::Glb && m.stream(AttributeKind::Normal).is_none() {
                // GLB always carries normals: computed ones.
                expected
                    .streams
                    .push(back.stream(AttributeKind::Normal).unwrap().clone());
                expected.streams.last_mut().unwrap().corners = expected.mesh.triangles.clone();
                let n = expected.mesh.positions.len();
                expected.streams.last_mut().unwrap().values.truncate(3 * n);
            }
            assert_eq!(kinds(&back), kinds(&expected), "{format:?}");
            if format != MeshFormat::Glb || m.stream(AttributeKind::Normal).is_some() {
                assert_eq!(corners(&back), corners(&expected), "{format:?}");
            }
            // The positions-only reader sees the same mesh.
            let plain = read_mesh_bytes(&bytes, format, &Limits::default()).unwrap();
            assert_eq!(plain, back.mesh, "{format:?}");
            // Written again: the same file.
            assert!(written(&back, format).0 == bytes, "{format:?}");
        }
    }
}

#[test]
fn obj_keeps_seams_without_splitting_positions() {
    let cube = seamed_cube();
    let (bytes, _) = written(&cube, MeshFormat::Obj);
    let text = String::from_utf8(bytes.clone()).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 8);
    assert_eq!(text.lines().filter(|l| l.starts_with("vt ")).count(), 24);
    assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), 6);
    assert!(text.contains("\nf 1/1/1 3/2/1 7/3/1\n"), "{text}");
    let (back, _) = read_attributed(&bytes, MeshFormat::Obj);
    assert_eq!(back, cube);
    // PLY and GLB split: 24 vertices.
    for format in [MeshFormat::Ply, MeshFormat::Glb] {
        let (back, _) = read_attributed(&written(&cube, format).0, format);
        assert_eq!(back.mesh.positions.len(), 24, "{format:?}");
        assert_eq!(corners(&back.weld()), corners(&cube));
    }
}

#[test]
fn obj_statements() {
    let v = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 0.5 0.5 0.5\n";
    let text = format!("{v}vt 0 0\nvt 1 0 0.5\nvt 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/-3/-1\n");
    let (m, report) = read_attributed(text.as_bytes(), MeshFormat::Obj);
    assert!(report.dropped.is_empty());
    assert_eq!(m.mesh.triangles, [[0, 1, 2], [0, 2, 3]]);
    let uv = m.stream(AttributeKind::TexCoord(0)).unwrap();
    // A third component anywhere makes them all 3; missing ones are 0.
    assert_eq!(uv.dims, 3);
    assert_eq!(uv.values, [0.0, 0.0, 0.0, 1.0, 0.0, 0.5, 1.0, 0.0, 0.0]);
    // `-3` of three is the first.
    assert_eq!(uv.corners, [[0, 1, 2], [0, 2, 0]]);
    let n = m.stream(AttributeKind::Normal).unwrap();
    assert_eq!(n.corners, [[0, 0, 0], [0, 0, 0]]);
    let c = m.stream(AttributeKind::Color(0)).unwrap();
    assert_eq!((c.dims, &c.corners), (3, &m.mesh.triangles));
    assert_eq!(&c.values[9..], &[0.5, 0.5, 0.5]);
    // Not every corner names a texture coordinate, a normal index out of
    // range, a vertex without a colour: each stream dropped, reported,
    // and the mesh still read.
    for (text, uv, normals, colors) in [
        (
            format!("{v}vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3//1\n"),
            true,
            false,
            false,
        ),
        (
            format!("{v}vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/2 3/1/1\n"),
            false,
            true,
            false,
        ),
        (
            format!("{v}v 0 0 1\nvt 0 0\nf 1/1 2/1 3/1\n"),
            false,
            false,
            true,
        ),
        (
            format!("{v}vn 0 nan 1\nf 1//1 2//1 3//1\n"),
            false,
            true,
            false,
        ),
        (
            format!("{v}vn 0 x 1\nf 1//1 2//1 3//1\n"),
            false,
            true,
            false,
        ),
    ] {
        let (m, report) = read_attributed(text.as_bytes(), MeshFormat::Obj);
        let d = report.dropped;
        assert_eq!((d.uv, d.normals, d.colors), (uv, normals, colors), "{text}");
        assert_eq!(
            m.mesh,
            read_mesh_bytes(text.as_bytes(), MeshFormat::Obj, &Limits::default()).unwrap()
        );
        m.validate().unwrap();
    }
}

#[test]
fn ply_properties() {
    let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
        property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n\
        element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n";
    let body = "0 0 0 255 0 51 0 0 1 0 0\n1 0 0 0 255 0 0 0 1 1 0\n0 1 0 0 0 255 0 0 1 0 1\n\
        3 0 1 2 6 0.5 0.5 1 0.5 0.5 1\n";
    let text = format!("{header}{body}");
    let (m, report) = read_attributed(text.as_bytes(), MeshFormat::Ply);
    assert!(report.dropped.is_empty());
    assert_eq!(
        kinds(&m),
        [
            AttributeKind::Normal,
            AttributeKind::TexCoord(0),
            AttributeKind::TexCoord(1),
            AttributeKind::Color(0)
        ]
    );
    let c = m.stream(AttributeKind::Color(0)).unwrap();
    assert_eq!(&c.values[..3], &[1.0, 0.0, 0.2]);
    let st = m.stream(AttributeKind::TexCoord(0)).unwrap();
    assert_eq!(st.values, [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    let per_corner = m.stream(AttributeKind::TexCoord(1)).unwrap();
    assert_eq!(per_corner.corners, [[0, 1, 2]]);
    assert_eq!(per_corner.values, [0.5, 0.5, 1.0, 0.5, 0.5, 1.0]);
    // A lone `nx`, and a texcoord list of the wrong length: dropped.
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nproperty float nx\nelement face 1\nproperty list uchar int vertex_indices\n\
        property list uchar float texcoord\nend_header\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2 2 0 0\n";
    let (m, report) = read_attributed(text.as_bytes(), MeshFormat::Ply);
    assert!(m.streams.is_empty());
    assert!(report.dropped.normals && report.dropped.uv);
    // 8-bit colours are written as uchar and read back bit for bit.
    let mut sphere = coloured_sphere();
    for c in &mut sphere.streams[0].values {
        *c = ((f64::from(*c) * 255.0).round() / 255.0) as f32;
    }
    let (bytes, _) = written(&sphere, MeshFormat::Ply);
    assert!(String::from_utf8_lossy(&bytes).contains("property uchar alpha\n"));
    let (back, _) = read_attributed(&bytes, MeshFormat::Ply);
    assert_eq!(corners(&back), corners(&sphere));
}

#[test]
fn off_prefixes() {
    let text =
        "CNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0\n1 0 0 0 0 1 0 255 0\n0 1 0 0 0 1 0 0 255\n3 0 1 2\n";
    let (m, report) = read_attributed(text.as_bytes(), MeshFormat::Off);
    assert!(report.dropped.is_empty());
    assert_eq!(kinds(&m), [AttributeKind::Normal, AttributeKind::Color(0)]);
    assert_eq!(
        &m.stream(AttributeKind::Color(0)).unwrap().values[..3],
        &[1.0, 0.0, 0.0]
    );
    let text = "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0 7\n0 1 0 0 1\n3 0 1 2\n";
    let (m, report) = read_attributed(text.as_bytes(), MeshFormat::Off);
    assert!(m.streams.is_empty() && report.dropped.uv);
}

#[test]
fn gltf_normalized_accessors_and_partial_streams() {
    use serde_json::json;
    // A triangle with u16 texture coordinates and u8 RGBA colours, both
    // normalized; a second primitive without colours.
    let mut bin: Vec<u8> = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    for uv in [0u16, 0, 65535, 0, 0, 65535] {
        bin.extend(uv.to_le_bytes());
    }
    bin.extend([255u8, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 51]);
    let primitive = |colours: bool| {
        let mut a = json!({"POSITION": 0, "TEXCOORD_0": 1});
        if colours {
            a["COLOR_0"] = json!(2);
        }
        json!({"attributes": a})
    };
    let doc = |second: bool| {
        let mut primitives = vec![primitive(true)];
        if second {
            primitives.push(primitive(false));
        }
        json!({
            "asset": {"version": "2.0"},
            "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": primitives}],
            "buffers": [{"byteLength": 60}],
            "bufferViews": [
                {"buffer": 0, "byteLength": 36},
                {"buffer": 0, "byteOffset": 36, "byteLength": 12},
                {"buffer": 0, "byteOffset": 48, "byteLength": 12}
            ],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"}
            ]
        })
    };
    let glb = |doc: &serde_json::Value| super::gltf::tests::glb(doc, &bin);
    let (m, report) = read_attributed(&glb(&doc(false)), MeshFormat::Glb);
    assert!(report.dropped.is_empty());
    assert_eq!(
        m.stream(AttributeKind::TexCoord(0)).unwrap().values,
        [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]
    );
    let c = m.stream(AttributeKind::Color(0)).unwrap();
    assert_eq!((c.dims, &c.values[8..]), (4, &[0.0, 0.0, 1.0, 0.2][..]));
    let (m, report) = read_attributed(&glb(&doc(true)), MeshFormat::Glb);
    assert_eq!(kinds(&m), [AttributeKind::TexCoord(0)]);
    assert!(report.dropped.colors && !report.dropped.uv);
    // The positions-only reader reports all of them, as before.
    let (_, report) =
        read_mesh_bytes_with_report(&glb(&doc(true)), MeshFormat::Glb, &Limits::default()).unwrap();
    assert!(report.dropped.colors && report.dropped.uv);
}

fn alloc_limit<T: std::fmt::Debug>(r: Result<T, Error>) -> LimitError {
    match r {
        Err(Error::LimitExceeded(e)) => e,
        other => panic!("expected a limit error, got {other:?}"),
    }
}

/// Attribute memory counts against `max_alloc_bytes` before it is
/// allocated, in every reader; the positions-only readers need less.
#[test]
fn attribute_memory_is_within_the_limits() {
    let cube = seamed_cube();
    for format in [
        MeshFormat::Obj,
        MeshFormat::Ply,
        MeshFormat::Off,
        MeshFormat::Glb,
    ] {
        let (bytes, _) = written(&cube, format);
        let plain = |limit| Limits {
            max_alloc_bytes: limit,
            ..Limits::default()
        };
        // The least the positions-only reader needs.
        let least = (1..100_000u64)
            .find(|&l| read_mesh_bytes(&bytes, format, &plain(l)).is_ok())
            .unwrap();
        let e = alloc_limit(read_attributed_mesh_bytes(&bytes, format, &plain(least)));
        assert_eq!(e.what, Limited::AllocBytes, "{format:?}");
    }
}

#[test]
fn hostile_counts_are_refused_before_allocation() {
    // A PLY vertex count no data could hold, with attributes.
    let text = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n\
        property float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
        element face 0\nproperty list uchar int vertex_indices\nend_header\n";
    let r = read_attributed_mesh_bytes(text.as_bytes(), MeshFormat::Ply, &Limits::default());
    assert!(
        matches!(&r, Err(Error::Format(e)) if matches!(e.what, Malformed::CountTooLarge { .. })),
        "{r:?}"
    );
    // A texcoord list that says it is huge: the data ends first.
    let text = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
        property list int float texcoord\nend_header\n";
    let mut bytes = text.as_bytes().to_vec();
    bytes.extend([0u8; 36]);
    bytes.push(3);
    for i in 0..3i32 {
        bytes.extend(i.to_le_bytes());
    }
    bytes.extend(i32::MAX.to_le_bytes());
    let r = read_attributed_mesh_bytes(&bytes, MeshFormat::Ply, &Limits::default());
    assert!(
        matches!(&r, Err(Error::Format(e)) if e.what == Malformed::Truncated),
        "{r:?}"
    );
    // Many `vt` lines against a small allocation limit.
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    text.push_str(&"vt 0 0\n".repeat(100_000));
    text.push_str("f 1/1 2/2 3/3\n");
    let limits = Limits {
        max_alloc_bytes: 200_000,
        ..Limits::default()
    };
    read_mesh_bytes(text.as_bytes(), MeshFormat::Obj, &limits).unwrap();
    let e = alloc_limit(read_attributed_mesh_bytes(
        text.as_bytes(),
        MeshFormat::Obj,
        &limits,
    ));
    assert_eq!(e.what, Limited::AllocBytes);
    // A glTF attribute accessor whose count runs past its view.
    let cube = seamed_cube();
    let (bytes, _) = written(&cube, MeshFormat::Glb);
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&bytes[20..20 + json_len]).unwrap();
    let lying = json.replacen(
        r#""count":24,"type":"VEC2""#,
        r#""count":99,"type":"VEC2""#,
        1,
    );
    assert_ne!(lying, json);
    let mut bad = bytes.clone();
    bad[20..20 + json_len].copy_from_slice(lying.as_bytes());
    let r = read_attributed_mesh_bytes(&bad, MeshFormat::Glb, &Limits::default());
    assert!(
        matches!(&r, Err(Error::Format(_))) || r.as_ref().is_ok_and(|m| m.1.dropped.uv),
        "{r:?}"
    );
}

/// spot.obj: texture coordinates with seams, through OBJ, PLY and GLB.
#[test]
fn spot_round_trips() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus/spot.obj");
    if !path.is_file() {
        crate::test_skip::skip("../shared/corpus not found");
        return;
    }
    let (spot, report) = read_attributed_mesh_with(&path, None, &Limits::default()).unwrap();
    assert!(report.dropped.is_empty(), "{report:?}");
    let uv = spot
        .stream(AttributeKind::TexCoord(0))
        .expect("spot has texture coordinates");
    assert_eq!(spot.mesh, read_mesh(&path).unwrap());
    // Seams: some positions carry more than one texture coordinate.
    let mut uv_of = vec![None; spot.mesh.positions.len()];
    let mut seams = 0;
    for (t, u) in spot.mesh.triangles.iter().zip(&uv.corners) {
        for k in 0..3 {
            match uv_of[t[k] as usize] {
                None => uv_of[t[k] as usize] = Some(u[k]),
                Some(v) if v != u[k] => seams += 1,
                _ => {}
            }
        }
    }
    assert!(seams > 0);
    for format in [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Glb] {
        let (bytes, report) = written(&spot, format);
        assert!(report.unwritten.is_empty());
        let (back, _) = read_attributed(&bytes, format);
        let mut expected = spot.clone();
        if format == MeshFormat::Glb && spot.stream(AttributeKind::Normal).is_none() {
            expected
                .streams
                .push(back.weld().stream(AttributeKind::Normal).unwrap().clone());
            let welded = back.weld();
            assert_eq!(
                corners(&AttributedMesh::new(
                    welded.mesh.clone(),
                    vec![welded.stream(AttributeKind::TexCoord(0)).unwrap().clone()]
                )),
                corners(&AttributedMesh::new(spot.mesh.clone(), vec![uv.clone()])),
                "{format:?}"
            );
            continue;
        }
        assert_eq!(corners(&back), corners(&expected), "{format:?}");
    }
}

/// suzanne and beetle: normals with their own indices (`f v//vn`),
/// exact through OBJ and PLY, unit and within rounding through GLB.
#[test]
fn suzanne_and_beetle_normals_round_trip() {
    for name in ["suzanne.obj", "beetle.obj"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../shared/corpus")
            .join(name);
        if !path.is_file() {
            crate::test_skip::skip("../shared/corpus not found");
            return;
        }
        let (m, report) = read_attributed_mesh_with(&path, None, &Limits::default()).unwrap();
        assert!(report.dropped.is_empty(), "{name}: {report:?}");
        assert_eq!(kinds(&m), [AttributeKind::Normal], "{name}");
        for format in [MeshFormat::Obj, MeshFormat::Ply] {
            let (back, _) = read_attributed(&written(&m, format).0, format);
            assert_eq!(corners(&back), corners(&m), "{name} {format:?}");
        }
        let (back, _) = read_attributed(&written(&m, MeshFormat::Glb).0, MeshFormat::Glb);
        let (n, back_n) = (
            m.stream(AttributeKind::Normal).unwrap(),
            back.stream(AttributeKind::Normal).unwrap(),
        );
        for f in 0..m.mesh.triangles.len() as u32 {
            for k in 0..3 {
                let a = glam::Vec3::from_slice(n.corner_value(FaceId(f), k)).normalize();
                let b = glam::Vec3::from_slice(back_n.corner_value(FaceId(f), k));
                assert!(
                    (b.length() - 1.0).abs() < 1e-5 && a.dot(b) > 1.0 - 1e-6,
                    "{name} face {f}"
                );
            }
        }
    }
}

/// A node that mirrors and stretches its mesh turns its normals by the
/// inverse transpose and keeps them unit; texture coordinates stay.
#[test]
fn gltf_normals_follow_the_node_transform() {
    let cube = seamed_cube();
    let (bytes, _) = written(&cube, MeshFormat::Glb);
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&bytes[20..20 + json_len]).unwrap();
    let moved = json.replacen(
        r#""nodes":[{"mesh":0}]"#,
        r#""nodes":[{"mesh":0,"scale":[-1,2,1]}]"#,
        1,
    );
    let mut moved = moved.trim_end().as_bytes().to_vec();
    moved.resize(moved.len().div_ceil(4) * 4, b' ');
    let bin = &bytes[20 + json_len..];
    let mut glb = b"glTF".to_vec();
    glb.extend(2u32.to_le_bytes());
    glb.extend((20 + moved.len() as u32 + bin.len() as u32).to_le_bytes());
    glb.extend((moved.len() as u32).to_le_bytes());
    glb.extend(b"JSON");
    glb.extend(&moved);
    glb.extend(bin);
    let (m, _) = read_attributed(&glb, MeshFormat::Glb);
    let (n, uv) = (
        m.stream(AttributeKind::Normal).unwrap(),
        m.stream(AttributeKind::TexCoord(0)).unwrap(),
    );
    let (n0, uv0) = (
        written_back(&cube, AttributeKind::Normal),
        written_back(&cube, AttributeKind::TexCoord(0)),
    );
    assert_eq!(uv.values, uv0.values);
    for (a, b) in n.values.chunks_exact(3).zip(n0.values.chunks_exact(3)) {
        assert_eq!(a, [-b[0], b[1], b[2]]);
    }
    // Mirrored: the triangles are flipped, and the streams with them.
    let (plain, _) = read_attributed(&bytes, MeshFormat::Glb);
    let t = plain.mesh.triangles[0];
    assert_eq!(m.mesh.triangles[0], [t[0], t[2], t[1]]);
    assert_eq!(n.corners, m.mesh.triangles);
}

/// The stream of `kind` of `m` written as GLB and read back.
fn written_back(m: &AttributedMesh, kind: AttributeKind) -> AttributeStream {
    let (back, _) = read_attributed(&written(m, MeshFormat::Glb).0, MeshFormat::Glb);
    back.stream(kind).unwrap().clone()
}
