//! glTF 2.0 binary (GLB) writer, after the Khronos "glTF 2.0
//! Specification" (§4.4 "GLB File Format Specification", §3.6 "Binary
//! Data Storage", §3.7 "Geometry").
//!
//! ```text
//! header   magic "glTF" | version 2 | total length          12 bytes, u32 LE
//! chunk 0  length | "JSON" | JSON text, padded with spaces
//! chunk 1  length | "BIN\0" | POSITION | NORMAL | indices, padded with zeros
//!                            12 B/vertex  12 B/vertex  12 B/triangle
//! ```
//!
//! The document is one scene, one node, one mesh with one triangle
//! primitive (mode 4): POSITION and NORMAL as `VEC3` float accessors
//! (bufferView target 34962, ARRAY_BUFFER) and the indices as `SCALAR`
//! unsigned int (target 34963, ELEMENT_ARRAY_BUFFER), each in its own
//! tightly packed bufferView, so no `byteStride` is needed.
//!
//! Invariants:
//! - every chunk starts and ends on a multiple of 4 bytes, and so does
//!   every bufferView and accessor (each element is 4-byte aligned: 12
//!   bytes per vertex or triangle), as §3.6.2.4 requires;
//! - the POSITION accessor carries `min` and `max` (required by §3.7.2.1),
//!   equal to the positions' exact bounds;
//! - every NORMAL is unit length (required by §3.7.2.1);
//! - the JSON holds only finite numbers: a non-finite position is refused
//!   with the error [`TriMesh::validate`] gives, never written;
//! - a mesh without triangles gives a valid file whose scene holds one
//!   node without a mesh, and no buffer: glTF accessors and bufferViews
//!   cannot be empty (`count` and `byteLength` ≥ 1), and a triangle
//!   primitive needs triangles. Its vertices, which nothing draws, are not
//!   written.
//!
//! The reader (`read`) reads these files back to the same positions and
//! triangles.

use crate::io::Attributes;
use crate::mesh::vertex_normals;
use crate::{
    AttributeKind, AttributeStream, AttributedMesh, Error, FormatError, Malformed, TriMesh,
};
use core::fmt::Write as _;
use std::io::Write;

use super::container::{glb_length, CHUNK_BIN, CHUNK_JSON, MAGIC, VERSION};

/// bufferView targets (the WebGL buffer binding points).
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// accessor componentTypes.
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
/// primitive mode TRIANGLES.
const TRIANGLES: u32 = 4;

/// The normal of a vertex that has none. `vertex_normals` gives zero
/// only to vertices that no triangle uses or whose every triangle has
/// zero area: such a vertex shades no pixel, so any unit vector is right,
/// and glTF requires unit normals. A fixed one keeps the file a function
/// of the mesh alone.
const FALLBACK_NORMAL: [f32; 3] = [0.0, 0.0, 1.0];

/// Writes `mesh` as a GLB file. The mesh's indices must be in range
/// (`write_mesh_to` validates it first); non-finite positions are refused
/// here too, since they would make the JSON invalid.
pub(in crate::io) fn write<W: Write>(w: &mut W, mesh: &TriMesh) -> Result<(), Error> {
    let normals = vertex_normals(mesh);
    let attributes = [
        Attribute {
            name: "POSITION".into(),
            dims: 3,
            values: mesh.positions.as_flattened(),
        },
        Attribute {
            name: "NORMAL".into(),
            dims: 3,
            values: normals.as_flattened(),
        },
    ];
    write_vertices(w, mesh, &attributes)
}

/// Writes `m` as a GLB file with its attributes, one vertex per distinct
/// position and values (`AttributedMesh::split_vertices`): NORMAL (the
/// normal stream made unit, or, without one, angle-weighted normals of
/// the positions as [`write`] gives), TEXCOORD_n for texture set n of 2
/// components, COLOR_n for colour set n. Returns what glTF cannot hold
/// (3-component texture coordinates, generic streams), which is not
/// written. `m` must be valid.
pub(in crate::io) fn write_attributed<W: Write>(
    w: &mut W,
    m: &AttributedMesh,
) -> Result<Attributes, Error> {
    let kept = |s: &AttributeStream| match s.kind {
        AttributeKind::Normal | AttributeKind::Color(_) => true,
        AttributeKind::TexCoord(_) => s.dims == 2,
        _ => false,
    };
    let mut unwritten = Attributes::default();
    for s in m.streams.iter().filter(|s| !kept(s)) {
        unwritten = unwritten.union(Attributes::of(s.kind));
    }
    let mut streams: Vec<AttributeStream> = m.streams.iter().filter(|s| kept(s)).cloned().collect();
    match streams.iter_mut().find(|s| s.kind == AttributeKind::Normal) {
        Some(n) => {
            for v in n.values.chunks_exact_mut(3) {
                // Unit within rounding already (what a glTF file read
                // back holds): kept bit for bit, so files round-trip.
                let n = glam::Vec3::from_slice(v);
                if (n.length_squared() - 1.0).abs() > 1e-6 {
                    let u = n.normalize_or_zero();
                    let u = if u == glam::Vec3::ZERO {
                        FALLBACK_NORMAL
                    } else {
                        u.to_array()
                    };
                    v.copy_from_slice(&u);
                }
            }
        }
        // Computed on the file's own indexing, before the split, so that
        // a texture seam does not crease the shading.
        None => streams.push(AttributeStream::new(
            AttributeKind::Normal,
            3,
            vertex_normals(&m.mesh).into_iter().flatten().collect(),
            m.mesh.triangles.clone(),
        )),
    }
    streams.sort_by_key(|s| s.kind);
    let split = AttributedMesh::new(m.mesh.clone(), streams).split_vertices();
    let mut attributes = vec![Attribute {
        name: "POSITION".into(),
        dims: 3,
        values: split.mesh.positions.as_flattened(),
    }];
    for s in &split.streams {
        let name = match s.kind {
            AttributeKind::Normal => "NORMAL".into(),
            AttributeKind::TexCoord(n) => format!("TEXCOORD_{n}"),
            AttributeKind::Color(n) => format!("COLOR_{n}"),
            _ => unreachable!("not kept"),
        };
        attributes.push(Attribute {
            name,
            dims: s.dims,
            values: &s.values,
        });
    }
    write_vertices(w, &split.mesh, &attributes)?;
    Ok(unwritten)
}

/// A vertex attribute to write: `dims` floats per vertex.
struct Attribute<'a> {
    name: String,
    dims: u8,
    values: &'a [f32],
}

/// Writes a GLB file of the positions' `mesh` triangles and per-vertex
/// `attributes`, POSITION first (its bounds are taken from it). A
/// zero normal (a vertex on no triangle of nonzero area) is written as
/// [`FALLBACK_NORMAL`].
fn write_vertices<W: Write>(
    w: &mut W,
    mesh: &TriMesh,
    attributes: &[Attribute],
) -> Result<(), Error> {
    let (min, max) = bounds(&mesh.positions)?;
    let vertices = mesh.positions.len() as u64;
    let triangles = mesh.triangles.len() as u64;
    let json = json(attributes, vertices, triangles, min, max);
    let floats: u64 = attributes.iter().map(|a| u64::from(a.dims)).sum();
    let len = lengths(json.len() as u64, vertices, triangles, floats)?;

    w.write_all(MAGIC)?;
    w.write_all(&VERSION.to_le_bytes())?;
    w.write_all(&len.total.to_le_bytes())?;

    // Both chunk lengths are below `total`, so they fit a u32 too.
    w.write_all(&(padded(len.json) as u32).to_le_bytes())?;
    w.write_all(CHUNK_JSON)?;
    w.write_all(json.as_bytes())?;
    w.write_all(&b"   "[..(padded(len.json) - len.json) as usize])?;

    if triangles == 0 {
        return Ok(());
    }
    w.write_all(&(padded(len.bin) as u32).to_le_bytes())?;
    w.write_all(CHUNK_BIN)?;
    for a in attributes {
        let normal = a.name == "NORMAL";
        for v in a.values.chunks_exact(usize::from(a.dims)) {
            let v = match normal && v == [0.0; 3] {
                true => &FALLBACK_NORMAL[..],
                false => v,
            };
            for c in v {
                w.write_all(&c.to_le_bytes())?;
            }
        }
    }
    for t in &mesh.triangles {
        let mut record = [0u8; 12];
        for (chunk, v) in record.chunks_exact_mut(4).zip(t) {
            chunk.copy_from_slice(&v.to_le_bytes());
        }
        w.write_all(&record)?;
    }
    // Every element is a multiple of 4 bytes: the BIN chunk needs no
    // padding today, but write it should the layout change.
    w.write_all(&[0u8; 3][..(padded(len.bin) - len.bin) as usize])?;
    Ok(())
}

/// Unpadded chunk data lengths and the whole file's length.
#[derive(Debug, PartialEq)]
struct Lengths {
    json: u64,
    /// 0 when there is no BIN chunk (no triangles).
    bin: u64,
    total: u32,
}

/// The lengths of a file whose JSON text is `json` bytes long, with
/// `floats` attribute floats per vertex; an error if the file would not
/// fit the u32 length fields of GLB.
fn lengths(json: u64, vertices: u64, triangles: u64, floats: u64) -> Result<Lengths, Error> {
    // The attributes, then the indices; no BIN chunk without triangles.
    let bin = match triangles {
        0 => 0,
        _ => (4 * floats)
            .saturating_mul(vertices)
            .saturating_add(12 * triangles),
    };
    let total = glb_length(json, (triangles > 0).then_some(bin))?;
    Ok(Lengths { json, bin, total })
}

/// `n` rounded up to a multiple of 4.
fn padded(n: u64) -> u64 {
    n.div_ceil(4) * 4
}

/// Per-axis least and greatest position (zeros for no vertices, which
/// are then not written); the error of [`TriMesh::validate`] for a
/// non-finite one.
fn bounds(positions: &[[f32; 3]]) -> Result<([f32; 3], [f32; 3]), Error> {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for (i, p) in positions.iter().enumerate() {
        if !p.iter().all(|c| c.is_finite()) {
            let what = Malformed::NonFinite { vertex: i as u64 };
            return Err(FormatError::new("mesh", what).into());
        }
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    if positions.is_empty() {
        return Ok(([0.0; 3], [0.0; 3]));
    }
    Ok((min, max))
}

/// The JSON chunk's text, unpadded: one accessor and one bufferView per
/// attribute, in order, then the indices'. With no triangles: the asset
/// and a scene of one empty node.
fn json(
    attributes: &[Attribute],
    vertices: u64,
    triangles: u64,
    min: [f32; 3],
    max: [f32; 3],
) -> String {
    let mut s = String::with_capacity(1024);
    // `write!` into a String cannot fail.
    let _ = write!(
        s,
        r#"{{"asset":{{"version":"2.0","generator":"swm {}"}},"scene":0,"#,
        env!("CARGO_PKG_VERSION")
    );
    if triangles == 0 {
        // `scene.nodes` is optional in the glTF schema, but readers such as
        // the `gltf` crate (1.4) require it; an empty node satisfies both.
        s.push_str(r#""scenes":[{"nodes":[0]}],"nodes":[{}]}"#);
        return s;
    }
    let n = attributes.len();
    let index_len = 12 * triangles;
    let _ = write!(s, r#""scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"#);
    s.push_str(r#""meshes":[{"primitives":[{"attributes":{"#);
    for (k, a) in attributes.iter().enumerate() {
        let comma = if k > 0 { "," } else { "" };
        let _ = write!(s, r#"{comma}"{}":{k}"#, a.name);
    }
    let _ = write!(s, r#"}},"indices":{n},"mode":{TRIANGLES}}}]}}],"#);
    let lens: Vec<u64> = attributes
        .iter()
        .map(|a| 4 * u64::from(a.dims) * vertices)
        .collect();
    let attribute_bytes: u64 = lens.iter().sum();
    let _ = write!(
        s,
        r#""buffers":[{{"byteLength":{}}}],"#,
        attribute_bytes + index_len
    );
    s.push_str(r#""bufferViews":["#);
    let mut offset = 0;
    for len in &lens {
        let _ = write!(
            s,
            r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{len},"target":{ARRAY_BUFFER}}},"#
        );
        offset += len;
    }
    let _ = write!(
        s,
        r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{index_len},"target":{ELEMENT_ARRAY_BUFFER}}}],"#
    );
    s.push_str(r#""accessors":["#);
    for (k, a) in attributes.iter().enumerate() {
        let ty = match a.dims {
            2 => "VEC2",
            3 => "VEC3",
            _ => "VEC4",
        };
        let _ = write!(
            s,
            r#"{{"bufferView":{k},"componentType":{FLOAT},"count":{vertices},"type":"{ty}""#
        );
        if k == 0 {
            let _ = write!(s, r#","min":{},"max":{}"#, json_vec3(min), json_vec3(max));
        }
        s.push_str("},");
    }
    let _ = write!(
        s,
        r#"{{"bufferView":{n},"componentType":{UNSIGNED_INT},"count":{},"type":"SCALAR"}}]}}"#,
        3 * triangles
    );
    s
}

/// `[x,y,z]` as JSON numbers. Each is the `f32` widened to `f64` and
/// written with the shortest decimals that give that `f64` back (Rust's
/// `Display`: no exponent, so never `1e38`-style tokens some parsers
/// mishandle, and `-0` is valid JSON). The text then names the `f32`
/// exactly whether a reader compares in `f64` or in `f32` (validators
/// check the bounds against the data); the shortest `f32` decimals
/// (`0.1`) would equal the data only after rounding to `f32`. Callers
/// pass finite values only.
fn json_vec3(v: [f32; 3]) -> String {
    let [x, y, z] = v.map(f64::from);
    format!("[{x},{y},{z}]")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ParameterError;
    use serde_json::Value;

    fn glb(mesh: &TriMesh) -> Vec<u8> {
        let mut bytes = Vec::new();
        write(&mut bytes, mesh).unwrap();
        bytes
    }

    fn u32_at(bytes: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
    }

    fn f32s(bytes: &[u8]) -> Vec<f32> {
        bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }

    /// The JSON text (padding included) and the BIN chunk's data, checked
    /// against the header and chunk lengths on the way.
    fn chunks(bytes: &[u8]) -> (&str, Option<&[u8]>) {
        assert_eq!(&bytes[..4], b"glTF");
        assert_eq!(u32_at(bytes, 4), 2);
        assert_eq!(u32_at(bytes, 8) as usize, bytes.len());
        assert_eq!(bytes.len() % 4, 0);
        let json_len = u32_at(bytes, 12) as usize;
        assert_eq!(json_len % 4, 0);
        assert_eq!(&bytes[16..20], b"JSON");
        let json = std::str::from_utf8(&bytes[20..20 + json_len]).unwrap();
        let rest = &bytes[20 + json_len..];
        if rest.is_empty() {
            return (json, None);
        }
        let bin_len = u32_at(rest, 0) as usize;
        assert_eq!(bin_len % 4, 0);
        assert_eq!(&rest[4..8], b"BIN\0");
        assert_eq!(rest.len(), 8 + bin_len, "nothing after the BIN chunk");
        (json, Some(&rest[8..]))
    }

    /// A tetrahedron-like fan with an isolated vertex and awkward numbers.
    fn sample() -> TriMesh {
        TriMesh::new(
            vec![
                [0.0, -0.0, 0.1],
                [1.0, 0.0, 3.4028235e38],
                [0.0, 1.0, -1e-45],
                [-2.5, 7.0, 0.3], // isolated
                [0.25, 0.25, 1.0],
            ],
            vec![[0, 1, 2], [0, 1, 4], [1, 2, 4], [2, 0, 4]],
        )
    }

    #[test]
    fn header_chunks_and_padding() {
        let mesh = sample();
        let bytes = glb(&mesh);
        let (json, bin) = chunks(&bytes);
        // Spaces pad the JSON; the text itself ends with its closing brace.
        assert_eq!(json.trim_end_matches(' ').chars().last(), Some('}'));
        assert!(json.len() - json.trim_end_matches(' ').len() < 4);
        let bin = bin.unwrap();
        assert_eq!(bin.len(), 24 * 5 + 12 * 4);
    }

    #[test]
    fn json_padding_for_every_length() {
        // The JSON length varies with the counts' digits; every remainder
        // mod 4 must pad to a multiple of 4.
        let mut remainders = [false; 4];
        let mut positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        for extra in 0..40 {
            let mesh = TriMesh::new(positions.clone(), vec![[0, 1, 2]; 1 + extra % 7]);
            let bytes = glb(&mesh);
            let (json, _) = chunks(&bytes);
            remainders[json.trim_end_matches(' ').len() % 4] = true;
            positions.push([extra as f32 * 0.37, 1.0 / (extra as f32 + 1.0), 2.0]);
        }
        assert_eq!(remainders, [true; 4]);
    }

    #[test]
    fn json_structure_and_bounds() {
        let mesh = sample();
        let bytes = glb(&mesh);
        let (json, bin) = chunks(&bytes);
        let bin = bin.unwrap();
        let doc: Value = serde_json::from_str(json).unwrap();
        assert_eq!(doc["asset"]["version"], "2.0");
        assert_eq!(
            doc["asset"]["generator"],
            format!("swm {}", env!("CARGO_PKG_VERSION"))
        );
        assert_eq!(doc["scene"], 0);
        assert_eq!(doc["scenes"][0]["nodes"], serde_json::json!([0]));
        assert_eq!(doc["nodes"][0]["mesh"], 0);
        let primitives = doc["meshes"][0]["primitives"].as_array().unwrap();
        assert_eq!(primitives.len(), 1);
        let p = &primitives[0];
        assert_eq!(p["mode"], 4);
        assert_eq!(p["indices"], 2);
        assert_eq!(p["attributes"]["POSITION"], 0);
        assert_eq!(p["attributes"]["NORMAL"], 1);
        assert_eq!(doc["buffers"][0]["byteLength"], bin.len());
        assert!(doc["buffers"][0].get("uri").is_none());

        let views = doc["bufferViews"].as_array().unwrap();
        let expected = [(0, 60, 34962), (60, 60, 34962), (120, 48, 34963)];
        for (view, (offset, len, target)) in views.iter().zip(expected) {
            assert_eq!(view["buffer"], 0);
            assert_eq!(view["byteOffset"], offset);
            assert_eq!(view["byteLength"], len);
            assert_eq!(view["target"], target);
            assert!(view.get("byteStride").is_none());
        }
        let accessors = doc["accessors"].as_array().unwrap();
        let expected = [(5126, 5, "VEC3"), (5126, 5, "VEC3"), (5125, 12, "SCALAR")];
        for (k, (a, (component, count, kind))) in accessors.iter().zip(expected).enumerate() {
            assert_eq!(a["bufferView"], k);
            assert_eq!(a["componentType"], component);
            assert_eq!(a["count"], count);
            assert_eq!(a["type"], kind);
            // Offset 0 in a view that starts on a multiple of 4.
            assert_eq!(a.get("byteOffset").map_or(0, |o| o.as_u64().unwrap()), 0);
        }

        // The bounds, read with Rust's correctly rounded parser: exact in
        // f64, so exact in f32.
        let bound = |key: &str| -> Vec<f64> {
            let start = json.find(&format!("\"{key}\":[")).unwrap() + key.len() + 4;
            let end = start + json[start..].find(']').unwrap();
            json[start..end]
                .split(',')
                .map(|x| x.parse().unwrap())
                .collect()
        };
        let positions = f32s(&bin[..60]);
        for k in 0..3 {
            let axis = positions.iter().skip(k).step_by(3);
            let lo = axis.clone().copied().fold(f32::INFINITY, f32::min);
            let hi = axis.copied().fold(f32::NEG_INFINITY, f32::max);
            assert_eq!(bound("min")[k], f64::from(lo), "min {k}");
            assert_eq!(bound("max")[k], f64::from(hi), "max {k}");
        }
        assert_eq!(bound("max")[2], f64::from(f32::MAX));
        assert_eq!(bound("min")[2], f64::from(-1e-45f32));
    }

    #[test]
    fn buffer_holds_positions_unit_normals_and_indices() {
        let mesh = sample();
        let bytes = glb(&mesh);
        let bin = chunks(&bytes).1.unwrap();
        let positions = f32s(&bin[..60]);
        let flat: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
        assert_eq!(
            positions.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            flat.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        let normals = f32s(&bin[60..120]);
        let computed = vertex_normals(&mesh);
        for (v, n) in normals.chunks_exact(3).enumerate() {
            let len = n.iter().map(|c| c * c).sum::<f32>().sqrt();
            assert!((len - 1.0).abs() < 1e-5, "vertex {v}: {n:?}");
            if computed[v] != [0.0; 3] {
                assert_eq!(n, computed[v]);
            }
        }
        // The isolated vertex gets the fallback.
        assert_eq!(&normals[9..12], &FALLBACK_NORMAL);
        let indices: Vec<u32> = bin[120..]
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        let flat: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
        assert_eq!(indices, flat);
    }

    #[test]
    fn no_triangles_is_a_scene_without_a_mesh() {
        for mesh in [
            TriMesh::default(),
            TriMesh::new(vec![[1.0, 2.0, 3.0]], vec![]),
        ] {
            let bytes = glb(&mesh);
            let (json, bin) = chunks(&bytes);
            assert!(bin.is_none());
            let doc: Value = serde_json::from_str(json).unwrap();
            assert_eq!(doc["asset"]["version"], "2.0");
            assert_eq!(doc["scene"], 0);
            assert_eq!(doc["scenes"], serde_json::json!([{"nodes": [0]}]));
            assert_eq!(doc["nodes"], serde_json::json!([{}]));
            for key in ["meshes", "buffers", "bufferViews", "accessors"] {
                assert!(doc.get(key).is_none(), "{key}");
            }
        }
    }

    #[test]
    fn non_finite_positions_are_refused() {
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let mesh = TriMesh::new(
                vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, bad, 0.0]],
                vec![[0, 1, 2]],
            );
            let mut bytes = Vec::new();
            match write(&mut bytes, &mesh) {
                Err(Error::Format(e)) => {
                    assert_eq!(e.what, Malformed::NonFinite { vertex: 2 })
                }
                other => panic!("{other:?}"),
            }
            assert!(bytes.is_empty(), "nothing written");
        }
    }

    #[test]
    fn files_over_4_gib_are_refused() {
        // The largest mesh that fits: 24 bytes per vertex, 12 per triangle.
        let json = 1001;
        let fixed = 12 + 8 + 1004 + 8;
        let triangles = (u64::from(u32::MAX) - fixed) / 12;
        let fits = lengths(json, 0, triangles, 6).unwrap();
        assert_eq!(fits.json, json);
        assert_eq!(fits.bin, 12 * triangles);
        assert_eq!(u64::from(fits.total), fixed + 12 * triangles);
        match lengths(json, 1, triangles, 6) {
            Err(Error::Parameter(ParameterError::FileTooLarge { format, bytes, max })) => {
                assert_eq!((format, max), ("GLB", u64::from(u32::MAX)));
                assert_eq!(bytes, fixed + 24 + 12 * triangles);
            }
            other => panic!("{other:?}"),
        }
        // No triangles: no BIN chunk, whatever the vertex count.
        let empty = lengths(json, u64::MAX / 64, 0, 6).unwrap();
        assert_eq!((empty.bin, empty.total), (0, 12 + 8 + 1004));
    }

    #[test]
    fn deterministic() {
        assert_eq!(glb(&sample()), glb(&sample()));
    }
}
