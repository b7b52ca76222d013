//! What the scene encoder and decoder share (format-spec/09-gltf.md):
//! the extension's name, the output container, the glTF names of the
//! coded streams, and the accessors that describe a decoded primitive,
//! which the encoder declares and the decoder fills: the two must match
//! exactly, so they are made here, once.

use crate::{AttributeStream, TriMesh};
use serde_json::{json, Value};

/// accessor componentTypes (§3.6.2.2).
pub(super) const UNSIGNED_BYTE: u64 = 5121;
pub(super) const UNSIGNED_SHORT: u64 = 5123;
pub(super) const UNSIGNED_INT: u64 = 5125;
pub(super) const FLOAT: u64 = 5126;

/// The extension's name, in `extensionsUsed` (and `extensionsRequired`
/// without fallback data) and on each coded primitive.
pub const SCENE_EXTENSION: &str = "SWM_mesh_compression";

/// bufferView targets (the WebGL buffer binding points).
pub(super) const ARRAY_BUFFER: u32 = 34962;
pub(super) const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// The container a scene is written in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SceneFormat {
    /// Binary glTF (`.glb`): the JSON chunk and one BIN chunk.
    #[default]
    Glb,
    /// JSON glTF (`.gltf`) with its one buffer embedded as a base64
    /// `data:` URI, so that the output is one file.
    Gltf,
}

/// The glTF semantic of an attribute stream, as §3.7.2.1 spells it;
/// `None` for generic streams, which the extension does not carry.
pub(crate) fn semantic(kind: crate::AttributeKind) -> Option<String> {
    use crate::AttributeKind as K;
    match kind {
        K::Normal => Some("NORMAL".into()),
        K::TexCoord(n) => Some(format!("TEXCOORD_{n}")),
        K::Color(n) => Some(format!("COLOR_{n}")),
        _ => None,
    }
}

/// A POSITION accessor (float VEC3, exact bounds) and its data.
pub(super) fn position_accessor(positions: &[[f32; 3]]) -> (Value, Vec<u8>) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    let mut bytes = Vec::with_capacity(positions.len() * 12);
    for p in positions {
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
            bytes.extend_from_slice(&p[k].to_le_bytes());
        }
    }
    let a = json!({
        "count": positions.len(), "type": "VEC3", "componentType": FLOAT,
        "min": min.map(f64::from), "max": max.map(f64::from),
    });
    (a, bytes)
}

/// A float accessor of a split stream's values, and its data.
pub(super) fn float_accessor(s: &AttributeStream) -> (Value, Vec<u8>) {
    let ty = ["SCALAR", "VEC2", "VEC3", "VEC4"][usize::from(s.dims.clamp(1, 4)) - 1];
    let bytes = s.values.iter().flat_map(|x| x.to_le_bytes()).collect();
    let a = json!({ "count": s.value_count(), "type": ty, "componentType": FLOAT });
    (a, bytes)
}

/// The indices accessor of a triangle list (unsigned short below 65,535
/// vertices, the primitive-restart value, else unsigned int) and its data
/// as u32s (`fill_accessor` narrows them).
pub(super) fn index_accessor(mesh: &TriMesh) -> (Value, Vec<u8>) {
    let ty = if mesh.positions.len() < 65_535 {
        UNSIGNED_SHORT
    } else {
        UNSIGNED_INT
    };
    let bytes = mesh
        .triangles
        .iter()
        .flatten()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let a = json!({ "count": mesh.triangles.len() * 3, "type": "SCALAR", "componentType": ty });
    (a, bytes)
}
