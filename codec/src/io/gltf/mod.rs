//! glTF 2.0: a reader for `.gltf` (JSON, buffers external or embedded as
//! `data:` URIs) and `.glb` (binary) files, and a GLB writer, after the
//! Khronos "glTF 2.0 Specification" (§3.5 "Scenes", §3.6 "Binary Data
//! Storage", §3.7 "Geometry", §4.4 "GLB File Format Specification").
//!
//! Reading goes in steps, one file each:
//! - `container`: a GLB file is split into its JSON and BIN chunks here
//!   (the `gltf` crate's own splitter subtracts before it checks and so
//!   panics on a short length field);
//! - the JSON is parsed and validated by the `gltf` crate (every index
//!   in range, every required field present), which gives the document
//!   model: scenes, nodes and their transforms, meshes, accessors;
//! - `scene` walks the scene graph to the list of triangle primitives to
//!   draw, each with its world transform;
//! - `buffers` loads the buffers those primitives use, and `accessor`
//!   reads their positions and indices with checked arithmetic (the
//!   crate's accessor reader trusts counts, offsets and component types
//!   enough to panic on a hostile file);
//! - `read` merges the primitives into one [`TriMesh`](crate::TriMesh).
//!
//! What is read: every TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN
//! primitive of the default scene (scene 0 when `scene` is absent; every
//! root node when the file has no scene), once per node that instances
//! its mesh, with the node's world transform applied. Strips and fans are
//! converted to triangles (§3.7.2.1); a node whose world transform has a
//! negative determinant mirrors its mesh, so its triangles are flipped to
//! keep their front faces (§3.7.2.1, "winding order"). Points and lines
//! are refused ([`Malformed::UnsupportedPrimitive`]). Skins, morph
//! targets and instancing extensions are not applied: the mesh is read in
//! its bind pose with its base positions. When attributes are asked for,
//! NORMAL, every TEXCOORD_n and COLOR_0 become per-vertex streams (float
//! or normalized integer accessors, §3.11), normals turned with their
//! node; a stream that not every drawn primitive has is dropped and
//! reported, as are COLOR_n past 0. Tangents, joints, weights and custom
//! attributes are ignored; otherwise normals, texture coordinates and
//! colours are reported as dropped (`read::dropped`).
//!
//! Memory: a file cannot make the reader allocate beyond the [`Limits`],
//! which every primitive's counts are checked against before its
//! vertices and triangles are allocated. But unlike the other formats,
//! glTF can describe more mesh than it holds bytes: a mesh instanced by
//! many nodes is added once per node, and an accessor without a
//! bufferView is all zeros whatever its count. For untrusted files, set
//! the limits to what the application can afford.
//!
//! [`Malformed::UnsupportedPrimitive`]: crate::Malformed::UnsupportedPrimitive
//! [`Limits`]: crate::Limits

mod accessor;
mod buffers;
mod container;
mod read;
mod scene;
pub(super) mod scene_codec;
mod write;

pub(super) use read::read;
pub(super) use write::{write, write_attributed};

#[cfg(test)]
pub(super) mod tests;
