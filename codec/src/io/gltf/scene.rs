//! The primitives a glTF scene draws, each with its world transform
//! (glTF 2.0 §3.5 "Scenes", §3.5.3 "Transformations").
//!
//! ```text
//! scene ── node A (T_A) ── node B (T_B) ── mesh m: world = T_A · T_B
//!      └── node C (T_C) ── mesh m        (the same mesh, instanced again)
//! ```
//!
//! Which scene: `scene` if the file names one, else scene 0; a file
//! without scenes is, per §3.5.1, a library of parts, and gives every
//! root node (nodes nobody lists as a child), in index order.
//!
//! A node's local transform is its `matrix` or its translation, rotation
//! and scale (`T · R · S`); world transforms are composed in `f64`.
//!
//! Invariant: §3.5.2 requires the nodes to form disjoint trees; a node
//! reached twice (two parents, or its own ancestor) is an error, checked
//! as the walk goes, so a cyclic file cannot make it loop, and the walk
//! uses its own stack, so a deep one cannot overflow the thread's.

use crate::{Error, FormatError, Malformed};
use ::gltf::mesh::Mode;
use ::gltf::scene::Transform;
use ::gltf::{Document, Node, Primitive};
use glam::{DMat4, DQuat, DVec3};

/// A primitive to draw and where.
pub(super) struct Draw<'a> {
    pub primitive: Primitive<'a>,
    /// The index of the primitive's mesh.
    #[cfg_attr(not(feature = "encoder"), allow(dead_code))]
    pub mesh: usize,
    pub world: DMat4,
}

/// The triangle primitives of the scene to read, in depth-first node
/// order; an error for a primitive that is not made of triangles, or,
/// with `skip_others`, that primitive left out (a scene that is kept
/// whole, `scene_codec`, only weighs its triangles).
pub(super) fn draws<'a>(
    doc: &'a Document,
    format: &'static str,
    skip_others: bool,
) -> Result<Vec<Draw<'a>>, Error> {
    let bad = |what| Error::from(FormatError::new(format, what));
    let roots: Vec<Node<'a>> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut child = vec![false; doc.nodes().len()];
            for c in doc.nodes().flat_map(|n| n.children()) {
                child[c.index()] = true;
            }
            doc.nodes().filter(|n| !child[n.index()]).collect()
        }
    };
    let mut seen = vec![false; doc.nodes().len()];
    let mut stack: Vec<(Node<'a>, DMat4)> = roots
        .into_iter()
        .rev()
        .map(|n| (n, DMat4::IDENTITY))
        .collect();
    let mut out = Vec::new();
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut seen[node.index()], true) {
            return Err(bad(Malformed::BadSyntax(
                "a node is reached twice: the node hierarchy is not a tree",
            )));
        }
        let world = parent * local(&node);
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                let mode = primitive.mode();
                if !matches!(
                    mode,
                    Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
                ) {
                    if skip_others {
                        continue;
                    }
                    let mode = mode.as_gl_enum();
                    return Err(bad(Malformed::UnsupportedPrimitive { mode }));
                }
                out.push(Draw {
                    primitive,
                    mesh: mesh.index(),
                    world,
                });
            }
        }
        let children: Vec<Node<'a>> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, world)));
    }
    Ok(out)
}

/// The node's local transform, composed in `f64` from the file's `f32`s.
fn local(node: &Node) -> DMat4 {
    match node.transform() {
        // Column-major in glTF and in glam alike.
        Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|col| col.map(f64::from)))
        }
        Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let v = |a: [f32; 3]| DVec3::from_array(a.map(f64::from));
            let [x, y, z, w] = rotation.map(f64::from);
            DMat4::from_scale_rotation_translation(
                v(scale),
                DQuat::from_xyzw(x, y, z, w),
                v(translation),
            )
        }
    }
}
