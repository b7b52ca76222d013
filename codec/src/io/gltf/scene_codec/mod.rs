//! Whole glTF 2.0 scenes, compressed primitive by primitive inside the
//! glTF extension `SWM_mesh_compression` (format-spec/09-gltf.md, its
//! JSON schema in format-spec/gltf/), everything else kept as written.
//!
//! Sources: the Khronos "glTF 2.0 Specification" (§3.6 "Binary Data
//! Storage", §3.7.2 "Meshes", §3.12 "Extensions", §4.4 GLB), and, for
//! the shape of the extension and its fallback policy, the Khronos
//! extensions `KHR_draco_mesh_compression` (a primitive's extension
//! object names a bufferView of compressed bytes and maps attribute
//! semantics to the coder's attribute ids; accessors keep their
//! `count`, `type`, `componentType`, `min` and `max` and may lack a
//! bufferView) and `EXT_meshopt_compression` (without uncompressed data
//! the extension is listed in `extensionsRequired`; with it, only in
//! `extensionsUsed`).
//!
//! ```text
//!  scene.glb ──► JSON (serde_json values: every object, unknown ones too)
//!       │        + the `gltf` crate's validated model (indices in range)
//!       ├─ each TRIANGLES/STRIP/FAN primitive with POSITION, NORMAL,
//!       │  TEXCOORD_n, COLOR_n only ──► swm file (lossless with its
//!       │  attributes, or at its share of the size) ──► bufferView
//!       │  + fresh accessors with the *decoded* mesh's counts
//!       ├─ every other primitive (skins, morph targets, tangents, lines,
//!       │  extensions) ──► kept as written, and reported by name
//!       └─ accessors and bufferViews nobody refers to any more dropped,
//!          the rest renumbered; one buffer (GLB BIN, or a data: URI)
//! ```
//!
//! Invariants:
//! - every object the codec does not rewrite is written back as it was
//!   read (JSON values, not the crate's model), but for the indices of
//!   accessors, bufferViews and buffers, which are renumbered wherever
//!   glTF 2.0 or a known extension refers to them (`document`);
//! - an accessor of a coded primitive describes the mesh the primitive's
//!   swm file decodes to plain (no post-processing), split into GPU
//!   vertices by [`AttributedMesh::split_vertices`]: the decoder fills
//!   exactly those counts, or the file is malformed;
//! - when the document uses an extension swm does not know, it may refer
//!   to accessors or bufferViews by index: nothing is dropped or
//!   renumbered then (new objects are appended), at the cost of keeping
//!   the replaced data, and the extension is reported by name;
//! - encoding is deterministic (primitives in document order, one thread
//!   of control; each swm encode is deterministic).
//!
//! [`AttributedMesh::split_vertices`]: crate::AttributedMesh::split_vertices

mod decode;
mod document;
#[cfg(feature = "encoder")]
mod encode;
#[cfg(feature = "encoder")]
mod read;
mod shared;

pub use decode::{decode_scene, scene_info, SceneDecoded, ScenePrimitive};
#[cfg(feature = "encoder")]
pub use encode::{
    encode_scene, Coded, PrimitiveOutcome, PrimitiveReport, SceneEncoded, SceneOptions, SceneReport,
};
#[cfg(feature = "encoder")]
pub use read::Uncoded;
pub use shared::{SceneFormat, SCENE_EXTENSION};
