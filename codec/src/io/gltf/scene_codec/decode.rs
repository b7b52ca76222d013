//! The scene decoder: every primitive carrying `SWM_mesh_compression`
//! expanded back to plain accessors (format-spec/09-gltf.md, "Decoding"),
//! and the description of a scene's primitives for `swm info`.
//!
//! Each swm file is decoded plain (no post-processing, whatever a hint
//! says) with its attribute streams and split into GPU vertices
//! ([`AttributedMesh::split_vertices`]); its positions fill the
//! primitive's POSITION accessor, stream `id` the accessor of the
//! semantic the extension maps to `id`, its triangles the indices.
//!
//! Every byte is hostile: every index the extension names is checked,
//! every accessor's `count`, `type` and `componentType` must be the
//! decoded mesh's exactly (or the file is malformed), each swm file is
//! decoded under the [`Limits`], and so are the totals over all of them,
//! so a document of many small files cannot add up to more than one
//! large one may. No accessor is filled twice.
//!
//! [`AttributedMesh::split_vertices`]: crate::AttributedMesh::split_vertices

use super::document::{self, ViewData};
use super::shared::{
    float_accessor, index_accessor, position_accessor, semantic, SceneFormat, ARRAY_BUFFER,
    ELEMENT_ARRAY_BUFFER, FLOAT, SCENE_EXTENSION, UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT,
};
use crate::{DecodeOptions, Error, Limits, Malformed};
use serde_json::{json, Value};
use std::path::Path;

/// What [`decode_scene`] made.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SceneDecoded {
    /// The output file.
    pub bytes: Vec<u8>,
    /// Primitives expanded.
    pub primitives: usize,
    /// Their vertices, summed.
    pub vertices: u64,
    /// Their triangles, summed.
    pub triangles: u64,
}

/// One primitive of a scene, as [`scene_info`] describes it.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ScenePrimitive {
    /// Index of its mesh.
    pub mesh: usize,
    /// Index of it in the mesh.
    pub primitive: usize,
    /// Its mesh's name, if any.
    pub name: Option<String>,
    /// Bytes of its swm file; `None` when it is not coded.
    pub swm_bytes: Option<u64>,
    /// Its POSITION accessor's count, and its triangles (from the index
    /// count, or the vertex count without indices; list primitives only).
    pub vertices: u64,
    /// Its triangles (0 for a primitive that is not a triangle list).
    pub triangles: u64,
    /// Its attributes by semantic, POSITION first.
    pub attributes: Vec<String>,
}

/// Expands every primitive coded in `SWM_mesh_compression` to plain
/// accessors and removes the extension; the rest of the document is
/// written back as it was (`base`: the folder external buffers are read
/// from). `options.limits` bound each file and all of them together.
///
/// # Errors
/// A malformed document or swm file, an accessor that does not describe
/// the decoded mesh, the limits.
pub fn decode_scene(
    bytes: &[u8],
    base: Option<&Path>,
    options: &DecodeOptions,
    format: SceneFormat,
) -> Result<SceneDecoded, Error> {
    let limits = &options.limits;
    let input = document::read(bytes, base, limits)?;
    let bad = |what: &'static str| input.bad(Malformed::BadSyntax(what));
    let mut json = input.json.clone();
    let mut data: Vec<ViewData> = (0..input.doc.views().len()).map(ViewData::Old).collect();
    let accessors = json["accessors"].as_array().map_or(0, Vec::len);
    let mut filled = vec![false; accessors];
    let (mut primitives, mut vertices, mut triangles) = (0, 0u64, 0u64);
    let plain = DecodeOptions {
        limits: *limits,
        ..DecodeOptions::plain()
    };
    let meshes = json["meshes"].as_array().map_or(0, Vec::len);
    for m in 0..meshes {
        let count = json["meshes"][m]["primitives"]
            .as_array()
            .map_or(0, Vec::len);
        for k in 0..count {
            let p = json["meshes"][m]["primitives"][k].clone();
            let Some(ext) = p.pointer(&format!("/extensions/{SCENE_EXTENSION}")) else {
                continue;
            };
            let view = ext["bufferView"]
                .as_u64()
                .ok_or_else(|| bad("SWM_mesh_compression without a bufferView"))?;
            let file = input.view(view as usize)?;
            let decoded = crate::decode_attributed(file, &plain)?.split_vertices();
            let mesh = &decoded.mesh;
            vertices += mesh.positions.len() as u64;
            triangles += mesh.triangles.len() as u64;
            limits.check_vertices(vertices)?;
            limits.check_faces(triangles)?;
            if p.get("mode").is_some_and(|m| m.as_u64() != Some(4)) {
                return Err(bad(
                    "an SWM_mesh_compression primitive is not a triangle list",
                ));
            }
            let mut fill = |name: &str, (want, payload): (Value, Vec<u8>), target: u32| {
                let a = p["attributes"][name]
                    .as_u64()
                    .or_else(|| (name == "indices").then(|| p["indices"].as_u64()).flatten())
                    .filter(|&a| (a as usize) < accessors)
                    .ok_or_else(|| bad("an SWM_mesh_compression attribute has no accessor"))?
                    as usize;
                if std::mem::replace(&mut filled[a], true) {
                    return Err(bad(
                        "an accessor is filled by two SWM_mesh_compression files",
                    ));
                }
                fill_accessor(&mut json, a, &want, payload, &mut data, target)
                    .map_err(|_| bad("an accessor does not describe its decoded mesh"))
            };
            fill("POSITION", position_accessor(&mesh.positions), ARRAY_BUFFER)?;
            let ids = ext["attributes"].as_object().cloned().unwrap_or_default();
            for (name, id) in &ids {
                let stream = id
                    .as_u64()
                    .and_then(|id| decoded.streams.get(id as usize))
                    .filter(|s| semantic(s.kind).as_deref() == Some(name.as_str()))
                    .ok_or_else(|| {
                        bad("an SWM_mesh_compression attribute id names no stream of its semantic")
                    })?;
                fill(name, float_accessor(stream), ARRAY_BUFFER)?;
            }
            // The indices go through `fill` under the name "indices".
            fill("indices", index_accessor(mesh), ELEMENT_ARRAY_BUFFER)?;
            // Attributes the extension does not carry keep their data,
            // which must then have the decoded vertex count.
            for (name, a) in p["attributes"].as_object().into_iter().flatten() {
                if name != "POSITION" && !ids.contains_key(name) {
                    let n = a
                        .as_u64()
                        .and_then(|a| json["accessors"][a as usize]["count"].as_u64());
                    if n != Some(mesh.positions.len() as u64) {
                        return Err(bad(
                            "an attribute's count differs from the decoded vertex count",
                        ));
                    }
                }
            }
            let p = &mut json["meshes"][m]["primitives"][k];
            if let Some(e) = p.get_mut("extensions").and_then(Value::as_object_mut) {
                e.remove(SCENE_EXTENSION);
                if e.is_empty() {
                    p.as_object_mut().map(|o| o.remove("extensions"));
                }
            }
            primitives += 1;
        }
    }
    document::unlist_extension(&mut json, "extensionsUsed", SCENE_EXTENSION);
    document::unlist_extension(&mut json, "extensionsRequired", SCENE_EXTENSION);
    let prune = input.unknown_extensions().is_empty();
    let bytes = document::write(&input, json, data, prune, format)?;
    Ok(SceneDecoded {
        bytes,
        primitives,
        vertices,
        triangles,
    })
}

/// Checks accessor `a` against `want` (count, type; float components,
/// or for indices any unsigned type wide enough), then points it at a
/// new bufferView of `payload` (u32s for indices, narrowed here) and
/// sets its bounds as `want` has them.
fn fill_accessor(
    json: &mut Value,
    a: usize,
    want: &Value,
    mut payload: Vec<u8>,
    data: &mut Vec<ViewData>,
    target: u32,
) -> Result<(), ()> {
    let accessor = &json["accessors"][a];
    let count = accessor["count"].as_u64().ok_or(())?;
    if count != want["count"].as_u64().ok_or(())? || accessor["type"] != want["type"] {
        return Err(());
    }
    let ty = accessor["componentType"].as_u64().ok_or(())?;
    if target == ELEMENT_ARRAY_BUFFER {
        let width = match ty {
            UNSIGNED_BYTE => 1,
            UNSIGNED_SHORT => 2,
            UNSIGNED_INT => 4,
            _ => return Err(()),
        };
        let mut out = Vec::with_capacity(payload.len() / 4 * width);
        for i in payload.chunks_exact(4) {
            let i = u32::from_le_bytes([i[0], i[1], i[2], i[3]]);
            if width < 4 && i >> (8 * width) != 0 {
                return Err(());
            }
            out.extend_from_slice(&i.to_le_bytes()[..width]);
        }
        payload = out;
    } else if ty != FLOAT {
        return Err(());
    }
    let view = json!({ "byteLength": payload.len(), "target": target });
    let view = document::push(json, "bufferViews", view);
    data.push(ViewData::New(payload));
    let o = json["accessors"][a].as_object_mut().ok_or(())?;
    for key in ["byteOffset", "sparse", "normalized"] {
        o.remove(key);
    }
    for key in ["min", "max"] {
        match want.get(key) {
            Some(v) => o.insert(key.into(), v.clone()),
            None => o.remove(key),
        };
    }
    o.insert("bufferView".into(), view.into());
    Ok(())
}

/// The primitives of a glTF document, coded or not, from its JSON alone
/// (nothing is decoded).
///
/// # Errors
/// A malformed document.
pub fn scene_info(
    bytes: &[u8],
    base: Option<&Path>,
    limits: &Limits,
) -> Result<Vec<ScenePrimitive>, Error> {
    let input = document::read(bytes, base, limits)?;
    let json = &input.json;
    let mut out = Vec::new();
    for (m, mesh) in json["meshes"].as_array().into_iter().flatten().enumerate() {
        let name = mesh["name"].as_str().map(str::to_owned);
        for (k, p) in mesh["primitives"]
            .as_array()
            .into_iter()
            .flatten()
            .enumerate()
        {
            let count = |a: &Value| {
                a.as_u64()
                    .and_then(|a| json["accessors"][a as usize]["count"].as_u64())
            };
            let vertices = count(&p["attributes"]["POSITION"]).unwrap_or(0);
            let corners = count(&p["indices"]).unwrap_or(vertices);
            let swm_bytes = p
                .pointer(&format!("/extensions/{SCENE_EXTENSION}/bufferView"))
                .and_then(Value::as_u64)
                .and_then(|v| json["bufferViews"][v as usize]["byteLength"].as_u64());
            let mut attributes: Vec<String> = p["attributes"]
                .as_object()
                .into_iter()
                .flatten()
                .map(|(n, _)| n.clone())
                .collect();
            attributes.sort_by_key(|n| (n != "POSITION", n.clone()));
            out.push(ScenePrimitive {
                mesh: m,
                primitive: k,
                name: name.clone(),
                swm_bytes,
                vertices,
                triangles: if p["mode"].as_u64().unwrap_or(4) == 4 {
                    corners / 3
                } else {
                    0
                },
                attributes,
            });
        }
    }
    Ok(out)
}
