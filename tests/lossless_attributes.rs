//! The lossless mode keeps vertex attributes (issue 47, item 2; format
//! 1.2's `ATTR`): round trips of the shared corpus's textured and
//! normal-carrying meshes and of a generated coloured mesh, through the
//! library and through `swm encode` / `swm decode` / `swm info`. Each
//! checks every corner's value against the input's (texture coordinates
//! and colours within half a quantization step, normals within the
//! octahedral grid's angle) and that corners at a vertex share a value
//! exactly when they did in the input: no value smeared across a seam.

mod common;
use common::*;
use std::collections::HashMap;
use swm::{AttributeKind, AttributedMesh, DecodeOptions, EncodeMode, EncodeOptions};

fn options(qp: u8) -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Lossless { qp },
        ..Default::default()
    }
}

fn angle(a: &[f32], b: &[f32]) -> f64 {
    let dot: f64 = (0..3).map(|k| f64::from(a[k]) * f64::from(b[k])).sum();
    let n = |x: &[f32]| (0..3).map(|k| f64::from(x[k]).powi(2)).sum::<f64>().sqrt();
    (dot / n(a) / n(b)).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Checks `decoded` against `input` (cleaned as the encoder cleans it):
/// per corner, the value within its quantization's error; per vertex,
/// the same corners sharing a value. Returns the most any texture
/// coordinate moved, in texels of a 1024² texture over [0, 1]².
fn check(
    input: &AttributedMesh,
    decoded: &AttributedMesh,
    qp: u8,
    q: &swm::AttributeQuantization,
) -> f64 {
    let (cleaned, streams) = swm::clean_attributed(input, &Default::default()).unwrap();
    let coded = AttributedMesh::new(cleaned.mesh, streams);
    assert_eq!(decoded.mesh.triangles.len(), coded.mesh.triangles.len());
    assert_eq!(decoded.streams.len(), coded.streams.len());
    // Decoded corner -> coded corner, through the corners' grid points.
    let grid = swm::geometry::Quantizer::from_positions(&coded.mesh.positions, qp).unwrap();
    let key = |m: &swm::TriMesh, t: &[u32; 3]| t.map(|v| grid.quantize(m.positions[v as usize]));
    let mut faces = HashMap::new();
    for (f, t) in coded.mesh.triangles.iter().enumerate() {
        let k = key(&coded.mesh, t);
        for r in 0..3 {
            faces.insert([k[r], k[(r + 1) % 3], k[(r + 2) % 3]], (f, r));
        }
    }
    let map: Vec<(usize, usize)> = decoded
        .mesh
        .triangles
        .iter()
        .map(|t| faces[&key(&decoded.mesh, t)])
        .collect();
    let mut texels = 0f64;
    for (a, b) in coded.streams.iter().zip(&decoded.streams) {
        assert_eq!((a.kind, a.dims), (b.kind, b.dims));
        let d = usize::from(a.dims);
        let bits = match a.kind {
            AttributeKind::Normal => q.normal_bits,
            AttributeKind::TexCoord(_) => q.texcoord_bits,
            AttributeKind::Color(_) => q.color_bits,
            _ => q.generic_bits,
        };
        let extent = (0..d)
            .map(|k| {
                let xs = a.values.iter().skip(k).step_by(d);
                let lo = xs.clone().fold(f32::INFINITY, |x, &y| x.min(y));
                f64::from(xs.fold(f32::NEG_INFINITY, |x, &y| x.max(y)) - lo)
            })
            .fold(0f64, f64::max);
        let half_step = extent / ((1u64 << bits) - 1) as f64 / 2.0 + 1e-6;
        let mut at_vertex: Vec<Vec<(u32, u32)>> = vec![Vec::new(); decoded.mesh.positions.len()];
        for (t, &(f, r)) in map.iter().enumerate() {
            for k in 0..3 {
                let (vi, vo) = (a.corners[f][(r + k) % 3], b.corners[t][k]);
                let (x, y) = (a.value(vi), b.value(vo));
                if a.kind == AttributeKind::Normal {
                    assert!(angle(x, y) <= 1.0, "normal {x:?} decoded as {y:?}");
                } else {
                    for c in 0..d {
                        let e = (f64::from(x[c]) - f64::from(y[c])).abs();
                        assert!(e <= half_step, "{:?} {x:?} decoded as {y:?}", a.kind);
                        if matches!(a.kind, AttributeKind::TexCoord(_)) {
                            texels = texels.max(e * 1024.0);
                        }
                    }
                }
                at_vertex[decoded.mesh.triangles[t][k] as usize].push((vi, vo));
            }
        }
        // Seams intact: at each vertex, two corners share a decoded value
        // exactly when they shared an input value.
        for pairs in &at_vertex {
            for x in pairs {
                for y in pairs {
                    assert_eq!(
                        x.0 == y.0,
                        x.1 == y.1,
                        "{:?} across a seam: {pairs:?}",
                        a.kind
                    );
                }
            }
        }
    }
    texels
}

/// spot (texture coordinates with seams), suzanne and beetle (normals),
/// through the library at Draco's defaults.
#[test]
fn corpus_meshes_round_trip_with_their_attributes() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    for (name, kind) in [
        ("spot.obj", AttributeKind::TexCoord(0)),
        ("suzanne.obj", AttributeKind::Normal),
        ("beetle.obj", AttributeKind::Normal),
    ] {
        let (input, _) =
            swm::io::read_attributed_mesh_with(&corpus.join(name), None, &Default::default())
                .unwrap();
        assert!(input.stream(kind).is_some(), "{name}");
        let o = options(11);
        let encoded = swm::encode_attributed(&input, &o).unwrap();
        let decoded = swm::decode_attributed(&encoded.bytes, &DecodeOptions::default()).unwrap();
        let texels = check(&input, &decoded, 11, &o.attributes);
        // qt = 10 over spot's charts (about [0, 1]): within one texel of
        // a 1024² texture (half a step of 1/1023 of the extent).
        assert!(texels <= 1.0, "{name}: {texels} texels");
        // The plain decoder reads the same file to the same mesh.
        let plain = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
        assert_eq!(plain, decoded.mesh);
    }
}

/// A generated torus with a smooth RGB colour per vertex, as PLY, through
/// `swm encode --mode lossless`, `swm info` and `swm decode` to PLY.
#[test]
fn a_coloured_mesh_through_the_command_line() {
    let dir = scratch("lossless-colours");
    let mesh = swm_corpus::torus(1.0, 0.35, 48, 16);
    let colours = mesh
        .positions
        .iter()
        .flat_map(|p| {
            let r = 0.5 + 0.5 * (3.0 * p[0]).sin();
            let g = 0.5 + 0.5 * (2.0 * p[1] + p[2]).cos();
            [r, g, (0.5 + p[2]).clamp(0.0, 1.0)].map(|c| (c * 255.0).round() / 255.0)
        })
        .collect();
    let corners = mesh.triangles.clone();
    let input = AttributedMesh::new(
        mesh,
        vec![swm::AttributeStream::new(
            AttributeKind::Color(0),
            3,
            colours,
            corners,
        )],
    );
    let ply = dir.join("painted.ply");
    swm::io::write_attributed_mesh(&ply, &input).unwrap();
    let file = dir.join("painted.swm");
    let out = swm(&[
        "encode",
        ply.to_str().unwrap(),
        "-o",
        file.to_str().unwrap(),
        "--mode",
        "lossless",
        "--qp",
        "12",
        "--qg",
        "10",
    ]);
    ok(&out);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning"));
    let info = ok(&swm(&["info", file.to_str().unwrap()]));
    assert!(
        info.contains("attribute             colours 0, 3 components, 10 bits per component"),
        "{info}"
    );
    assert!(info.contains("format version        1.2"), "{info}");
    let back = dir.join("back.ply");
    ok(&swm(&[
        "decode",
        file.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]));
    let (read, _) = swm::io::read_attributed_mesh_with(&back, None, &Default::default()).unwrap();
    let (input_read, _) =
        swm::io::read_attributed_mesh_with(&ply, None, &Default::default()).unwrap();
    let q = swm::AttributeQuantization {
        color_bits: 10,
        ..Default::default()
    };
    check(&input_read, &read, 12, &q);
    let _ = std::fs::remove_dir_all(&dir);
}

/// spot through the command line: `--qt`, `swm info`'s stream line, and
/// `swm decode` to OBJ keeping its `vt` seams.
#[test]
fn spot_through_the_command_line() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    let dir = scratch("lossless-spot");
    let spot = corpus.join("spot.obj");
    let file = dir.join("spot.swm");
    let json = json(&swm(&[
        "encode",
        spot.to_str().unwrap(),
        "-o",
        file.to_str().unwrap(),
        "--mode",
        "lossless",
        "--qp",
        "11",
        "--qt",
        "12",
        "--json",
    ]));
    assert_eq!(json["attributes"][0]["kind"], "texture coordinates 0");
    assert_eq!(json["attributes"][0]["bits"], 12);
    let back = dir.join("spot.obj");
    ok(&swm(&[
        "decode",
        file.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]));
    let (input, _) = swm::io::read_attributed_mesh_with(&spot, None, &Default::default()).unwrap();
    let (read, _) = swm::io::read_attributed_mesh_with(&back, None, &Default::default()).unwrap();
    let q = swm::AttributeQuantization {
        texcoord_bits: 12,
        ..Default::default()
    };
    let texels = check(&input, &read, 11, &q);
    assert!(texels <= 0.25, "{texels}");
    // Options of the lossless mode's attributes are refused elsewhere.
    let out = swm(&[
        "encode",
        spot.to_str().unwrap(),
        "-o",
        file.to_str().unwrap(),
        "--force",
        "--mode",
        "swing",
        "--qt",
        "12",
    ]);
    assert!(!out.status.success());
    let _ = std::fs::remove_dir_all(&dir);
}
