//! The glTF reader: a `.gltf` or `.glb` file's scene, merged into one
//! [`TriMesh`] (see the module header of `gltf` for what is read).
//!
//! Each drawn primitive adds its own vertices, transformed to world
//! space, and its triangles: a list as written (§3.7.2.1: `3k`, `3k+1`,
//! `3k+2`), a strip as `(i, i+1, i+2)` with every other triangle's first
//! two corners swapped to keep one orientation, a fan as `(0, i+1, i+2)`.
//! A primitive without indices uses its vertices in order. A mesh that
//! two nodes instance is added twice, once per node.
//!
//! Invariants: the limits are checked for each primitive before its
//! vertices and triangles are allocated (`Builder`); every index is
//! checked against its primitive's vertex count; a transformed position
//! that overflows `f32` is [`Malformed::NonFinite`]; a primitive under
//! no transform keeps its positions bit for bit.

use super::accessor::{self, Context};
use super::buffers::{Buffers, Origin};
use super::container;
use super::scene::{self, Draw};
use crate::io::builder::Builder;
use crate::io::Attributes;
use crate::{AttributeKind, AttributedMesh, Error, FormatError, Limits, Location, Malformed};
use ::gltf::json::validation::Error as Invalid;
use ::gltf::mesh::Mode;
use ::gltf::Semantic;
use glam::{DMat4, DVec3};
use std::path::Path;

/// The format name in errors about JSON glTF files.
const FORMAT: &str = "GLTF";

/// Reads a glTF file, JSON or binary; `base` is the folder its external
/// buffers are resolved against (`None` refuses them).
pub(in crate::io) fn read(
    bytes: &[u8],
    base: Option<&Path>,
    limits: &Limits,
    keep: bool,
) -> Result<(AttributedMesh, Attributes), Error> {
    let (format, json, bin) = if container::is_glb(bytes) {
        let chunks = container::split(bytes)?;
        (container::FORMAT, chunks.json, chunks.bin)
    } else {
        (FORMAT, bytes, None)
    };
    let bad = |what| Error::from(FormatError::new(format, what));
    let root = ::gltf::json::Root::from_slice(json).map_err(|e| json_error(format, &e))?;
    if let Some(name) = root.extensions_required.first() {
        return Err(bad(Malformed::Unsupported(extension(name))));
    }
    if let Some(e) = validate(&root) {
        return Err(bad(Malformed::BadSyntax(invalid(&e))));
    }
    let doc = ::gltf::Document::from_json_without_validation(root);
    let draws = scene::draws(&doc, format, false)?;

    let mut needed = vec![false; doc.buffers().len()];
    let kinds = if keep { kinds(&draws) } else { Vec::new() };
    for d in &draws {
        let p = &d.primitive;
        for a in p.get(&Semantic::Positions).into_iter().chain(p.indices()) {
            accessor::mark_buffers(&a, &mut needed);
        }
        for (_, semantic) in &kinds {
            if let Some(a) = p.get(semantic) {
                accessor::mark_buffers(&a, &mut needed);
            }
        }
    }
    let origin = Origin { bin, base, format };
    let buffers = Buffers::load(&doc, &needed, &origin, limits, bytes.len() as u64)?;
    let cx = Context {
        buffers: &buffers,
        limits,
        format,
    };
    let mut out = Builder::new(limits);
    // Streams in the order of `kinds`; their dimension is set by the
    // first primitive that has them.
    let mut dims: Vec<Option<usize>> = vec![None; kinds.len()];
    for d in &draws {
        let before = out.mesh.positions.len();
        add(&mut out, d, &cx)?;
        let added = out.mesh.positions.len() - before;
        if keep {
            add_attributes(&mut out, d, &cx, &kinds, &mut dims, added)?;
        }
        let mut unread = dropped(&d.primitive);
        if keep {
            // COLOR_n past 0 is not read; the rest is, or is reported
            // by `finish` if not every primitive has it.
            unread = Attributes {
                colors: d
                    .primitive
                    .attributes()
                    .any(|(s, _)| matches!(s, Semantic::Colors(n) if n > 0)),
                ..Attributes::default()
            };
        }
        out.dropped = out.dropped.union(unread);
    }
    let (mesh, dropped) = out.finish();
    // Vertices that no triangle uses are not a scene: a file that draws
    // no triangle is empty, as for the other formats (`read_mesh_bytes`).
    if mesh.mesh.triangles.is_empty() {
        return Ok((AttributedMesh::default(), dropped));
    }
    Ok((mesh, dropped))
}

/// The attributes read, over all drawn primitives: NORMAL, every
/// TEXCOORD_n and COLOR_0, each with its stream kind, in that order.
fn kinds(draws: &[Draw]) -> Vec<(AttributeKind, Semantic)> {
    let mut kinds: Vec<(AttributeKind, Semantic)> = Vec::new();
    for d in draws {
        for (semantic, _) in d.primitive.attributes() {
            let kind = match semantic {
                Semantic::Normals => AttributeKind::Normal,
                Semantic::TexCoords(n) => match u8::try_from(n) {
                    Ok(n) => AttributeKind::TexCoord(n),
                    Err(_) => continue,
                },
                Semantic::Colors(0) => AttributeKind::Color(0),
                _ => continue,
            };
            if !kinds.iter().any(|k| k.0 == kind) {
                kinds.push((kind, semantic));
            }
        }
    }
    kinds.sort_by_key(|k| k.0);
    kinds
}

/// Adds the attribute values of one drawn primitive, `added` vertices
/// (none when it has no POSITION): a stream the primitive lacks, or whose
/// accessor is not of the stream's type, is marked broken and dropped at
/// the end. Normals are turned by the inverse transpose of the node's
/// linear part and made unit again (kept bit for bit under no transform).
fn add_attributes(
    out: &mut Builder,
    d: &Draw,
    cx: &Context,
    kinds: &[(AttributeKind, Semantic)],
    dims: &mut [Option<usize>],
    added: usize,
) -> Result<(), Error> {
    if added == 0 {
        return Ok(());
    }
    let identity = d.world == DMat4::IDENTITY;
    let normal_matrix = glam::DMat3::from_mat4(d.world).inverse().transpose();
    for (k, &(kind, ref semantic)) in kinds.iter().enumerate() {
        let allowed: &[usize] = match kind {
            AttributeKind::Normal => &[3],
            AttributeKind::TexCoord(_) => &[2],
            _ => &[3, 4],
        };
        let values = match d.primitive.get(semantic) {
            Some(a) => match accessor::floats(&a, cx, allowed) {
                Ok(v) => Some(v),
                Err(Error::Format(_)) => None,
                Err(e) => return Err(e),
            },
            None => None,
        };
        let stream = match out.streams.iter().position(|p| p.stream.kind == kind) {
            Some(s) => s,
            None => {
                let width = values.as_ref().map_or(allowed[0], |v| v.0);
                dims[k] = Some(width);
                out.add_stream(kind, width as u8, true)
            }
        };
        match values {
            Some((width, v)) if Some(width) == dims[k] && v.len() == added * width => {
                out.reserve_values(stream, added as u64, 0)?;
                let values = &mut out.streams[stream].stream.values;
                if kind == AttributeKind::Normal && !identity {
                    for n in v.chunks_exact(3) {
                        let n = normal_matrix * DVec3::new(n[0].into(), n[1].into(), n[2].into());
                        values.extend_from_slice(&n.normalize_or_zero().as_vec3().to_array());
                    }
                } else {
                    values.extend_from_slice(&v);
                }
            }
            _ => out.streams[stream].broken = true,
        }
    }
    Ok(())
}

/// The attributes of a drawn primitive that are not read: normals,
/// texture coordinates and colours (§3.7.2.1's NORMAL, TEXCOORD_n and
/// COLOR_n). Tangents, joints, weights and custom `_NAME` attributes
/// serve normals and skins, which are not read either, and go unsaid.
fn dropped(primitive: &::gltf::Primitive) -> Attributes {
    let mut dropped = Attributes::default();
    for (semantic, _) in primitive.attributes() {
        match semantic {
            Semantic::Normals => dropped.normals = true,
            Semantic::TexCoords(_) => dropped.uv = true,
            Semantic::Colors(_) => dropped.colors = true,
            _ => {}
        }
    }
    dropped
}

/// Adds one drawn primitive to the mesh.
fn add(out: &mut Builder, d: &Draw, cx: &Context) -> Result<(), Error> {
    let bad = |what| Error::from(FormatError::new(cx.format, what));
    let Some(a) = d.primitive.get(&Semantic::Positions) else {
        // §3.7.2.1 lets a primitive omit POSITION (an extension may
        // supply it); there is nothing to draw then.
        return Ok(());
    };
    let positions = accessor::positions(&a, cx)?;
    let n = positions.len();
    let indices = match d.primitive.indices() {
        Some(i) => accessor::indices(&i, cx)?,
        None => (0..n as u32).collect(),
    };
    let triangles = triangles(d.primitive.mode(), &indices).ok_or_else(|| {
        bad(Malformed::BadSyntax(
            "a triangle list's index count is not a multiple of 3",
        ))
    })?;

    out.reserve_vertices(n as u64)?;
    let base = out.mesh.positions.len() as u64;
    // Untransformed positions are kept bit for bit (-0.0 + 0.0 would be
    // +0.0), so that a GLB this crate writes reads back exactly.
    let identity = d.world == DMat4::IDENTITY;
    for p in positions {
        let p = match identity {
            true => p,
            false => {
                let w = d
                    .world
                    .transform_point3(DVec3::from_array(p.map(f64::from)));
                w.as_vec3().to_array()
            }
        };
        if !p.iter().all(|c| c.is_finite()) {
            let vertex = out.mesh.positions.len() as u64;
            return Err(bad(Malformed::NonFinite { vertex }));
        }
        out.mesh.positions.push(p);
    }
    out.reserve_triangles(triangles.len() as u64)?;
    // A mirroring transform turns counter-clockwise front faces clockwise
    // (§3.7.2.1): swap two corners to keep them in front.
    let mirrored = d.world.determinant() < 0.0;
    for t in triangles {
        if let Some(&index) = t.iter().find(|&&i| i as usize >= n) {
            let what = Malformed::IndexOutOfRange {
                index: index.into(),
                vertices: n as u64,
            };
            return Err(bad(what));
        }
        // base + i < 2^32: reserve_vertices checked the total.
        let [a, b, c] = t.map(|i| (base + u64::from(i)) as u32);
        out.mesh
            .triangles
            .push(if mirrored { [a, c, b] } else { [a, b, c] });
    }
    Ok(())
}

/// The triangles of a primitive's index sequence; `None` for a list whose
/// length is not a multiple of 3. Strips and fans with fewer than three
/// indices draw nothing.
pub(super) fn triangles(mode: Mode, idx: &[u32]) -> Option<Vec<[u32; 3]>> {
    let n = idx.len();
    Some(match mode {
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                // §3.7.2.1: p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}.
                let odd = i % 2;
                [idx[i], idx[i + 1 + odd], idx[i + 2 - odd]]
            })
            .collect(),
        Mode::TriangleFan => (0..n.saturating_sub(2))
            .map(|i| [idx[i + 1], idx[i + 2], idx[0]])
            .collect(),
        _ if !n.is_multiple_of(3) => return None,
        _ => idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    })
}

/// A JSON parse error: located by line (of the JSON chunk in a GLB).
pub(super) fn json_error(format: &'static str, e: &::gltf::json::Error) -> Error {
    let what = if e.is_eof() {
        Malformed::Truncated
    } else if e.is_data() {
        Malformed::BadSyntax("the JSON does not follow the glTF 2.0 schema")
    } else {
        Malformed::BadSyntax("not valid JSON")
    };
    FormatError::new(format, what)
        .at(Location::Line(e.line() as u64))
        .into()
}

/// The first thing wrong with the document, as the `gltf` crate checks
/// it, but for missing or malformed `min` and `max` of a POSITION
/// accessor: the schema requires them, many writers leave them out, and
/// nothing here needs them.
pub(super) fn validate(root: &::gltf::json::Root) -> Option<Invalid> {
    use ::gltf::json::validation::Validate;
    let mut first = None;
    root.validate(root, ::gltf::json::Path::new, &mut |path, e| {
        let path = path();
        let bounds = path.as_str().ends_with(".min") || path.as_str().ends_with(".max");
        if first.is_none() && !bounds {
            first = Some(e);
        }
    });
    first
}

/// What a validation error means, in words.
pub(super) fn invalid(e: &Invalid) -> &'static str {
    match e {
        Invalid::IndexOutOfBounds => "an index refers to an object the file does not have",
        Invalid::Invalid => "a property has a value the glTF 2.0 schema does not allow",
        Invalid::Missing => "a required property is missing",
        Invalid::Oversize => "a size or offset is too large",
        Invalid::Unsupported => "a required extension is not supported",
    }
}

/// The name of a required extension, for the error that refuses it.
fn extension(name: &str) -> &'static str {
    match name {
        "KHR_draco_mesh_compression" => "the required extension KHR_draco_mesh_compression",
        "EXT_meshopt_compression" => "the required extension EXT_meshopt_compression",
        "KHR_mesh_quantization" => "the required extension KHR_mesh_quantization",
        _ => "a required glTF extension",
    }
}
