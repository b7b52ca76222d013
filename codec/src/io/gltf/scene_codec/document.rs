//! A glTF document kept whole: read as JSON values beside the `gltf`
//! crate's validated model, and written back with its buffer data
//! gathered into one buffer (glTF 2.0 §3.6 "Binary Data Storage", §4.4
//! "GLB File Format Specification").
//!
//! Why two views of one document: the crate's model checks every index
//! and required property (so the codec never indexes out of range), but
//! drops what it does not model; the JSON values keep every property and
//! extension for the output.
//!
//! References by index that glTF 2.0 defines, and that renumbering
//! follows (`Refs`): accessors from mesh primitives (`attributes`,
//! `indices`, `targets`), skins (`inverseBindMatrices`), animation
//! samplers (`input`, `output`) and `EXT_mesh_gpu_instancing`; bufferViews
//! from accessors (and their `sparse` parts), images, and the
//! `bufferView` of `KHR_draco_mesh_compression` and of this codec's
//! extension; buffers from bufferViews. An extension outside
//! [`KNOWN`] may refer to any of them, so with one in the document
//! nothing is dropped or renumbered.
//!
//! Invariant: every bufferView of the output starts on a multiple of 4
//! bytes of its buffer (§3.6.2.4 asks it of accessor data), and the GLB
//! chunks are padded to 4 bytes (JSON with spaces, BIN with zeros).

use super::super::buffers::{Buffers, Origin};
use super::super::container::{self, CHUNK_BIN, CHUNK_JSON, MAGIC, VERSION};
use super::super::read::{invalid, json_error};
use super::shared::{SceneFormat, SCENE_EXTENSION};
use crate::{Error, FormatError, Limits, Malformed};
use ::gltf::json::validation::Error as Invalid;
use serde_json::{Map, Value};
use std::path::Path;

/// The format name in errors about JSON glTF files.
const GLTF: &str = "GLTF";

/// Extensions that refer to no accessor, bufferView or buffer beyond
/// those `Refs` follows (names ending in `*` are prefixes). With only
/// these, unused data is dropped.
const KNOWN: &[&str] = &[
    SCENE_EXTENSION,
    "KHR_materials_*",
    "KHR_texture_transform",
    "KHR_texture_basisu",
    "KHR_lights_punctual",
    "KHR_mesh_quantization",
    "KHR_xmp_json_ld",
    "KHR_animation_pointer",
    "KHR_draco_mesh_compression",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "EXT_mesh_gpu_instancing",
];

/// A document as read.
pub(super) struct Input<'a> {
    /// Every property as written.
    pub json: Value,
    /// The validated model of the same JSON.
    pub doc: ::gltf::Document,
    /// The buffers that bufferViews use, loaded.
    pub buffers: Buffers<'a>,
    /// "GLB" or "GLTF", for errors.
    pub format: &'static str,
}

impl Input<'_> {
    pub fn bad(&self, what: Malformed) -> Error {
        FormatError::new(self.format, what).into()
    }

    /// The bytes of bufferView `index`, checked against its buffer.
    pub fn view(&self, index: usize) -> Result<&[u8], Error> {
        let view =
            self.doc.views().nth(index).ok_or_else(|| {
                self.bad(Malformed::BadSyntax("a bufferView index is out of range"))
            })?;
        let buffer = self.buffers.get(view.buffer().index());
        view.offset()
            .checked_add(view.length())
            .filter(|&end| end <= view.buffer().length())
            .and_then(|end| buffer.get(view.offset()..end))
            .ok_or_else(|| self.bad(Malformed::BadSyntax("a bufferView runs past its buffer")))
    }

    /// Extensions the document uses that [`KNOWN`] does not list.
    pub fn unknown_extensions(&self) -> Vec<String> {
        let known = |name: &str| {
            KNOWN.iter().any(|k| match k.strip_suffix('*') {
                Some(prefix) => name.starts_with(prefix),
                None => name == *k,
            })
        };
        strings(&self.json["extensionsUsed"])
            .filter(|n| !known(n))
            .map(str::to_owned)
            .collect()
    }
}

/// The strings of a JSON array (none for anything else).
pub(super) fn strings(v: &Value) -> impl Iterator<Item = &str> {
    v.as_array().into_iter().flatten().filter_map(Value::as_str)
}

/// Reads a `.glb` or `.gltf` document: its JSON, validated (with
/// `extensionsRequired` set aside, since this codec passes required
/// extensions through), and the buffers its bufferViews use.
pub(super) fn read<'a>(
    bytes: &'a [u8],
    base: Option<&Path>,
    limits: &Limits,
) -> Result<Input<'a>, Error> {
    let (format, json, bin) = if container::is_glb(bytes) {
        let chunks = container::split(bytes)?;
        (container::FORMAT, chunks.json, chunks.bin)
    } else {
        (GLTF, bytes, None)
    };
    let bad = |what| Error::from(FormatError::new(format, what));
    let mut root = ::gltf::json::Root::from_slice(json).map_err(|e| json_error(format, &e))?;
    root.extensions_required.clear();
    if let Some(e) = validate(&root) {
        return Err(bad(Malformed::BadSyntax(invalid(&e))));
    }
    let value: Value =
        serde_json::from_slice(json).map_err(|_| bad(Malformed::BadSyntax("not valid JSON")))?;
    let doc = ::gltf::Document::from_json_without_validation(root);
    let mut needed = vec![false; doc.buffers().len()];
    for view in doc.views() {
        needed[view.buffer().index()] = true;
    }
    let origin = Origin { bin, base, format };
    let buffers = Buffers::load(&doc, &needed, &origin, limits, bytes.len() as u64)?;
    Ok(Input {
        json: value,
        doc,
        buffers,
        format,
    })
}

/// The first thing wrong with the document as the `gltf` crate checks
/// it, but for two rules it adds to glTF 2.0: POSITION's `min` and `max`
/// (as `read::validate`), and a bufferView (or `sparse`) on every
/// accessor, which §3.6.2 does not require (an accessor without one is
/// zeros, or filled by an extension: this one, Draco's).
fn validate(root: &::gltf::json::Root) -> Option<Invalid> {
    use ::gltf::json::validation::Validate;
    let mut first = None;
    root.validate(root, ::gltf::json::Path::new, &mut |path, e| {
        let path = path();
        let p = path.as_str();
        let lenient = p.ends_with(".min")
            || p.ends_with(".max")
            || (p.starts_with("accessors[")
                && p.ends_with("].bufferView")
                && e == Invalid::Missing);
        if first.is_none() && !lenient {
            first = Some(e);
        }
    });
    first
}

/// Calls `f` on every JSON value that holds an accessor index.
fn accessor_refs(json: &mut Value, f: &mut impl FnMut(&mut Value)) {
    for mesh in array_mut(json, "meshes") {
        for p in array_mut(mesh, "primitives") {
            object_values(&mut p["attributes"], f);
            if let Some(i) = p.get_mut("indices") {
                f(i);
            }
            for t in array_mut(p, "targets") {
                object_values(t, f);
            }
        }
    }
    for skin in array_mut(json, "skins") {
        if let Some(i) = skin.get_mut("inverseBindMatrices") {
            f(i);
        }
    }
    for a in array_mut(json, "animations") {
        for s in array_mut(a, "samplers") {
            for key in ["input", "output"] {
                if let Some(i) = s.get_mut(key) {
                    f(i);
                }
            }
        }
    }
    for node in array_mut(json, "nodes") {
        if let Some(ext) = node.pointer_mut("/extensions/EXT_mesh_gpu_instancing/attributes") {
            object_values(ext, f);
        }
    }
}

/// Calls `f` on every JSON value that holds a bufferView index.
fn view_refs(json: &mut Value, f: &mut impl FnMut(&mut Value)) {
    for a in array_mut(json, "accessors") {
        if let Some(v) = a.get_mut("bufferView") {
            f(v);
        }
        for part in ["/sparse/indices/bufferView", "/sparse/values/bufferView"] {
            if let Some(v) = a.pointer_mut(part) {
                f(v);
            }
        }
    }
    for image in array_mut(json, "images") {
        if let Some(v) = image.get_mut("bufferView") {
            f(v);
        }
    }
    for mesh in array_mut(json, "meshes") {
        for p in array_mut(mesh, "primitives") {
            for ext in [SCENE_EXTENSION, "KHR_draco_mesh_compression"] {
                if let Some(v) = p.pointer_mut(&format!("/extensions/{ext}/bufferView")) {
                    f(v);
                }
            }
        }
    }
}

fn array_mut<'v>(v: &'v mut Value, key: &str) -> impl Iterator<Item = &'v mut Value> {
    v.get_mut(key)
        .and_then(Value::as_array_mut)
        .into_iter()
        .flatten()
}

fn object_values(v: &mut Value, f: &mut impl FnMut(&mut Value)) {
    if let Some(o) = v.as_object_mut() {
        o.values_mut().for_each(f);
    }
}

/// Which of `n` objects `refs` reaches, then renumbers the references:
/// the kept objects in their order. Returns the kept old indices.
fn compact(
    json: &mut Value,
    key: &str,
    refs: fn(&mut Value, &mut dyn FnMut(&mut Value)),
) -> Vec<usize> {
    let n = json.get(key).and_then(Value::as_array).map_or(0, Vec::len);
    let mut live = vec![false; n];
    refs(json, &mut |v| {
        if let Some(i) = v.as_u64().filter(|&i| (i as usize) < n) {
            live[i as usize] = true;
        }
    });
    let mut new = vec![0u64; n];
    let kept: Vec<usize> = (0..n).filter(|&i| live[i]).collect();
    for (k, &i) in kept.iter().enumerate() {
        new[i] = k as u64;
    }
    refs(json, &mut |v| {
        if let Some(i) = v.as_u64().filter(|&i| (i as usize) < n) {
            *v = new[i as usize].into();
        }
    });
    if let Some(list) = json.get_mut(key).and_then(Value::as_array_mut) {
        let old = std::mem::take(list);
        *list = old
            .into_iter()
            .enumerate()
            .filter(|(i, _)| live[*i])
            .map(|(_, v)| v)
            .collect();
    }
    kept
}

/// The bytes of a bufferView of the output: new data, or an input view's.
pub(super) enum ViewData {
    New(Vec<u8>),
    Old(usize),
}

/// Writes the document: `json` with its bufferViews' data (`data[i]` for
/// view `i`, one per view) gathered into one buffer. With `prune`,
/// accessors and bufferViews that nothing refers to are dropped and the
/// rest renumbered (see the module header for when that is safe).
pub(super) fn write(
    input: &Input,
    mut json: Value,
    mut data: Vec<ViewData>,
    prune: bool,
    format: SceneFormat,
) -> Result<Vec<u8>, Error> {
    if prune {
        compact(&mut json, "accessors", |j, f| {
            accessor_refs(j, &mut |v| f(v))
        });
        let kept = compact(&mut json, "bufferViews", |j, f| view_refs(j, &mut |v| f(v)));
        let mut old: Vec<Option<ViewData>> = data.into_iter().map(Some).collect();
        data = kept
            .iter()
            .filter_map(|&i| old.get_mut(i)?.take())
            .collect();
    }
    let mut bin = Vec::new();
    let views = json
        .get_mut("bufferViews")
        .and_then(Value::as_array_mut)
        .map(std::mem::take)
        .unwrap_or_default();
    let mut out_views = Vec::with_capacity(views.len());
    for (mut view, d) in views.into_iter().zip(&data) {
        let bytes = match d {
            ViewData::New(b) => b.as_slice(),
            ViewData::Old(i) => input.view(*i)?,
        };
        bin.resize(bin.len().next_multiple_of(4), 0);
        let o = view
            .as_object_mut()
            .ok_or_else(|| input.bad(Malformed::BadSyntax("a bufferView is not an object")))?;
        o.insert("buffer".into(), 0.into());
        o.remove("byteOffset");
        if !bin.is_empty() {
            o.insert("byteOffset".into(), bin.len().into());
        }
        o.insert("byteLength".into(), bytes.len().into());
        bin.extend_from_slice(bytes);
        out_views.push(view);
    }
    let root = json
        .as_object_mut()
        .ok_or_else(|| input.bad(Malformed::BadSyntax("the document is not a JSON object")))?;
    if out_views.is_empty() {
        root.remove("bufferViews");
        root.remove("buffers");
    } else {
        root.insert("bufferViews".into(), Value::Array(out_views));
        let mut buffer = Map::new();
        buffer.insert("byteLength".into(), bin.len().into());
        if format == SceneFormat::Gltf {
            let uri = format!("data:application/octet-stream;base64,{}", base64(&bin));
            buffer.insert("uri".into(), uri.into());
        }
        root.insert("buffers".into(), Value::Array(vec![Value::Object(buffer)]));
    }
    for key in ["accessors", "extensionsUsed", "extensionsRequired"] {
        if root
            .get(key)
            .and_then(Value::as_array)
            .is_some_and(Vec::is_empty)
        {
            root.remove(key);
        }
    }
    let text = serde_json::to_vec(&json).map_err(|e| Error::Io(e.into()))?;
    Ok(match format {
        SceneFormat::Gltf => text,
        SceneFormat::Glb => glb(text, bin)?,
    })
}

/// A GLB file of a JSON text and a BIN chunk (none when empty); an
/// error when it would not fit GLB's u32 length ([`container::glb_length`]).
fn glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Result<Vec<u8>, Error> {
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);
    let bin_len = (!bin.is_empty()).then_some(bin.len() as u64);
    let total = container::glb_length(json.len() as u64, bin_len)?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(CHUNK_JSON);
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(CHUNK_BIN);
        out.extend_from_slice(&bin);
    }
    Ok(out)
}

/// Standard base64 with padding (RFC 4648 §4), for `data:` URIs.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Appends `value` to the array `key` of the root, made if missing;
/// returns its index.
pub(super) fn push(json: &mut Value, key: &str, value: Value) -> usize {
    let list = json
        .as_object_mut()
        .map(|o| o.entry(key).or_insert_with(|| Value::Array(Vec::new())));
    match list.and_then(Value::as_array_mut) {
        Some(list) => {
            list.push(value);
            list.len() - 1
        }
        None => 0,
    }
}

/// Adds `name` to the root's string array `key` unless it is there.
#[cfg(feature = "encoder")]
pub(super) fn list_extension(json: &mut Value, key: &str, name: &str) {
    if strings(&json[key]).any(|n| n == name) {
        return;
    }
    push(json, key, name.into());
}

/// Removes `name` from the root's string array `key`.
pub(super) fn unlist_extension(json: &mut Value, key: &str, name: &str) {
    if let Some(list) = json.get_mut(key).and_then(Value::as_array_mut) {
        list.retain(|n| n.as_str() != Some(name));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_encodes_rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, text) in cases {
            assert_eq!(base64(plain.as_bytes()), text, "{plain}");
        }
    }

    #[test]
    fn glb_chunks_are_padded_and_split_back() {
        let bytes = glb(b"{}".to_vec(), vec![1, 2, 3]).unwrap();
        assert_eq!(bytes.len() % 4, 0);
        let c = container::split(&bytes).unwrap();
        assert_eq!(c.json, b"{}  ");
        assert_eq!(c.bin, Some(&[1u8, 2, 3, 0][..]));
        let json_only = glb(b"{}".to_vec(), Vec::new()).unwrap();
        assert_eq!(container::split(&json_only).unwrap().bin, None);
    }
}
