//! Which primitives of a scene swm codes, and their meshes in their own
//! local space (glTF 2.0 §3.7.2.1 "Meshes", "Overview" and "Morph
//! Targets"; §3.7.3 "Skins").
//!
//! A primitive is coded when it draws triangles (TRIANGLES, or a strip
//! or fan, converted as `read` converts them), has POSITION, carries no
//! extension and no morph targets, and has only the attributes the
//! lossless coder keeps: NORMAL, TEXCOORD_n, COLOR_n, each a float or
//! normalized integer accessor of the usual type. Everything else is
//! kept as written, with its reason ([`Uncoded`]): a skin's JOINTS_n and
//! WEIGHTS_n, TANGENT and custom `_NAME` attributes would have to follow
//! the coder's vertex order and quantization, which it does not do for
//! them.
//!
//! Invariant: a coded primitive's mesh holds its vertices in accessor
//! order, every stream in the split form (one value per vertex, the
//! triangles as its triples), so that `encode_attributed` sees exactly
//! what a renderer draws.

use super::super::accessor::{self, Context};
use super::super::read::triangles;
use crate::{AttributeKind, AttributeStream, AttributedMesh, Error, Malformed, TriMesh};
use ::gltf::mesh::Mode;
use ::gltf::Semantic;
use core::fmt;

/// Why a primitive is kept as written.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Uncoded {
    /// It draws points or lines (the glTF mode number).
    Mode(u32),
    /// It carries this extension.
    Extension(String),
    /// It has morph targets.
    MorphTargets,
    /// It has attributes swm does not code (JOINTS_n, WEIGHTS_n, TANGENT,
    /// custom ones), by name.
    Attributes(Vec<String>),
    /// It has no POSITION.
    NoPosition,
    /// It draws no triangle.
    NoTriangles,
    /// This attribute's accessor has a type the reader does not take
    /// (quantized, not normalized, another count).
    AccessorType(String),
    /// swm could not code it; the error, in words.
    Failed(String),
}

impl fmt::Display for Uncoded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Uncoded::Mode(0) => write!(f, "points"),
            Uncoded::Mode(m) if *m < 4 => write!(f, "lines (mode {m})"),
            Uncoded::Mode(m) => write!(f, "mode {m}"),
            Uncoded::Extension(e) => write!(f, "extension {e}"),
            Uncoded::MorphTargets => write!(f, "morph targets"),
            Uncoded::Attributes(a) => write!(f, "{}", a.join(", ")),
            Uncoded::NoPosition => write!(f, "no POSITION"),
            Uncoded::NoTriangles => write!(f, "no triangles"),
            Uncoded::AccessorType(a) => write!(f, "{a} of an accessor type swm does not read"),
            Uncoded::Failed(e) => write!(f, "not coded: {e}"),
        }
    }
}

/// A read value, or for a type the readers do not take (quantized
/// positions, integer attributes that are not normalized) the reason to
/// keep the primitive as written rather than to refuse the scene.
fn kept<T>(r: Result<T, Error>, name: String) -> Result<Result<T, Uncoded>, Error> {
    match r {
        Ok(v) => Ok(Ok(v)),
        Err(Error::Format(_)) => Ok(Err(Uncoded::AccessorType(name))),
        Err(e) => Err(e),
    }
}

/// A primitive's mesh, or why it is kept as written.
pub(super) fn primitive(
    p: &::gltf::Primitive,
    json: &serde_json::Value,
    cx: &Context,
) -> Result<Result<AttributedMesh, Uncoded>, Error> {
    let mode = p.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return Ok(Err(Uncoded::Mode(mode.as_gl_enum())));
    }
    if let Some(ext) = json.get("extensions").and_then(|e| e.as_object()) {
        if let Some(name) = ext.keys().next() {
            return Ok(Err(Uncoded::Extension(name.clone())));
        }
    }
    if p.morph_targets().next().is_some() {
        return Ok(Err(Uncoded::MorphTargets));
    }
    let others: Vec<String> = p
        .attributes()
        .filter(|(s, _)| {
            !matches!(
                s,
                Semantic::Positions
                    | Semantic::Normals
                    | Semantic::TexCoords(_)
                    | Semantic::Colors(_)
            )
        })
        .map(|(s, _)| s.to_string())
        .collect();
    if !others.is_empty() {
        return Ok(Err(Uncoded::Attributes(others)));
    }
    let Some(a) = p.get(&Semantic::Positions) else {
        return Ok(Err(Uncoded::NoPosition));
    };
    let positions = match kept(accessor::positions(&a, cx), "POSITION".into())? {
        Ok(p) => p,
        Err(u) => return Ok(Err(u)),
    };
    let n = positions.len();
    let indices = match p.indices() {
        Some(i) => accessor::indices(&i, cx)?,
        None => (0..n as u32).collect(),
    };
    let bad = |what| Error::from(crate::FormatError::new(cx.format, what));
    let tris = triangles(mode, &indices).ok_or_else(|| {
        bad(Malformed::BadSyntax(
            "a triangle list's index count is not a multiple of 3",
        ))
    })?;
    if let Some(&index) = tris.iter().flatten().find(|&&i| i as usize >= n) {
        let vertices = n as u64;
        let index = index.into();
        return Err(bad(Malformed::IndexOutOfRange { index, vertices }));
    }
    if tris.is_empty() {
        return Ok(Err(Uncoded::NoTriangles));
    }
    let mut streams = Vec::new();
    for (semantic, a) in p.attributes() {
        let (kind, allowed): (AttributeKind, &[usize]) = match semantic {
            Semantic::Normals => (AttributeKind::Normal, &[3]),
            Semantic::TexCoords(k) => match u8::try_from(k) {
                Ok(k) => (AttributeKind::TexCoord(k), &[2]),
                Err(_) => return Ok(Err(Uncoded::Attributes(vec![semantic.to_string()]))),
            },
            Semantic::Colors(k) => match u8::try_from(k) {
                Ok(k) => (AttributeKind::Color(k), &[3, 4]),
                Err(_) => return Ok(Err(Uncoded::Attributes(vec![semantic.to_string()]))),
            },
            _ => continue,
        };
        let (dims, values) = match kept(accessor::floats(&a, cx, allowed), semantic.to_string())? {
            Ok(v) => v,
            Err(u) => return Ok(Err(u)),
        };
        if values.len() != n * dims {
            // §3.7.2.1: every attribute accessor has the same count.
            return Ok(Err(Uncoded::AccessorType(semantic.to_string())));
        }
        if values.iter().any(|x| !x.is_finite()) {
            return Ok(Err(Uncoded::AccessorType(semantic.to_string())));
        }
        streams.push(AttributeStream::new(kind, dims as u8, values, tris.clone()));
    }
    // The coder's stream order is by kind; sorting here makes a file's
    // stream ids independent of the order the JSON lists attributes in.
    streams.sort_by_key(|s| s.kind);
    Ok(Ok(AttributedMesh::new(
        TriMesh::new(positions, tris),
        streams,
    )))
}
