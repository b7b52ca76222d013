//! The scene encoder: each codable primitive of a glTF document coded as
//! an swm file inside `SWM_mesh_compression`, one size budget split
//! between them (format-spec/09-gltf.md).
//!
//! Which coder: every primitive by the requested mode, with its
//! attributes (NORMAL, TEXCOORD_n, COLOR_n; `encode_attributed`,
//! quantized as `EncodeOptions::attributes` says): the automatic mode
//! runs only methods whose files keep them (the simplified method with
//! its seams, displaced subdivision and SwingWrapper for normals and
//! colours). Normals
//! are coded even where they follow the geometry (the primitive had a
//! NORMAL accessor, and keeps one), and a share too small for a file
//! with the streams gets the smallest file that keeps them (a material
//! needs its texture coordinates). A mode whose file cannot carry them
//! (`--mode swing` or displaced, with texture coordinates) codes such a
//! primitive losslessly instead, at `SceneOptions::attributes_qp`, and
//! so does `SceneOptions::lossy_attributes` off (the command line's
//! choice when no size, rate or error bound is given).
//!
//! The split of a size (`--size`: the budget of all the swm files;
//! `--bpv`: the lossless files plus the rate over the distinct positions
//! of the primitives coded at a size): lossless primitives' files come
//! first, as they are; the rest of the budget goes to the other
//! primitives by the rule the method per component uses for the
//! components of one mesh (`encoder::mixed`): share
//! `b_i = F + (B − n·F)·a_i / Σa`, where `a_i` is the primitive's area
//! in world space summed over the nodes that draw it (its local area
//! when no node of the scene does), the area a uniform retiling's
//! triangle count follows, and `F` the bytes of a file's own frame. A
//! primitive whose share is below its smallest file gets that smallest
//! file (and says so). The split is filled like water: a primitive whose
//! file is at most 90% of its share keeps it, its share becomes what it
//! took, and the others are coded again at their shares of what is left
//! (at most [`SPLIT_ROUNDS`] rounds). An error bound or an edge length applies to every
//! primitive as it is, relative to each one's own bounding box.
//!
//! Invariants: the output's accessors of a coded primitive are filled
//! from the file decoded as a decoder will decode it (plain, split into
//! GPU vertices), so the counts and bounds are the decoder's; a
//! primitive that swm fails to code is kept as written and reported,
//! never dropped; primitives are coded in document order.

use super::super::accessor::Context;
use super::super::scene;
use super::document::{self, Input, ViewData};
use super::read::{self, Uncoded};
use super::shared::{
    float_accessor, index_accessor, position_accessor, semantic, SceneFormat, ARRAY_BUFFER,
    ELEMENT_ARRAY_BUFFER, SCENE_EXTENSION,
};
use crate::options::{EncodeMode, EncodeOptions, SwingTarget};
use crate::{AttributedMesh, DecodeOptions, Error, Limits, Malformed, Method};
use glam::{DVec3, Vec3};
use serde_json::{json, Map, Value};
use std::path::Path;

/// Bytes a file of its own spends on its frame and header, added to each
/// primitive's share (as `encoder::mixed::FRAME`).
const FRAME: u64 = 40;
/// Rounds of the budget's split at most (`code`): each codes the
/// primitives still open again.
const SPLIT_ROUNDS: u32 = 3;

/// What [`encode_scene`] is asked.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneOptions {
    /// The mode and target for primitives of positions only (the target
    /// is the whole scene's, split as the module header says), and the
    /// attribute quantization, effort and limits for all.
    pub encode: EncodeOptions,
    /// Bits per coordinate of a primitive with attributes that
    /// `encode.mode` names a method for that cannot carry them (SwingWrapper
    /// or displaced subdivision, with texture coordinates), coded losslessly
    /// with them instead. Default 12.
    pub attributes_qp: u8,
    /// Code primitives with attributes by `encode.mode` at their share
    /// (true), or losslessly at [`attributes_qp`](Self::attributes_qp)
    /// (false: what `swm encode scene.glb` does without a size, a rate
    /// or an error bound, since the default rate counts positions
    /// only). Default true.
    pub lossy_attributes: bool,
    /// Keep uncompressed data beside each swm file (the extension is then
    /// only in `extensionsUsed`, and viewers without swm draw the
    /// decoded mesh's plain copy). Default off.
    pub fallback: bool,
    /// The output container. Default GLB.
    pub format: SceneFormat,
    /// Caps for reading the input (and decoding each file back).
    pub limits: Limits,
}

impl Default for SceneOptions {
    fn default() -> Self {
        SceneOptions {
            encode: EncodeOptions::default(),
            attributes_qp: 12,
            lossy_attributes: true,
            fallback: false,
            format: SceneFormat::Glb,
            limits: Limits::default(),
        }
    }
}

/// What a coded primitive became.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Coded {
    /// The method that wrote its file.
    pub method: Method,
    /// The swm file's size.
    pub bytes: u64,
    /// Its share of the scene's size, when it had one.
    pub share: Option<u64>,
    /// Vertices of the primitive as read.
    pub input_vertices: u64,
    /// Triangles of the primitive as read.
    pub input_triangles: u64,
    /// Vertices it decodes to (GPU vertices, split at seams).
    pub vertices: u64,
    /// Triangles it decodes to.
    pub triangles: u64,
    /// The attributes coded with it, by glTF semantic.
    pub attributes: Vec<String>,
}

/// One primitive's fate.
#[derive(Clone, Debug, PartialEq)]
pub enum PrimitiveOutcome {
    /// Coded in the extension.
    Coded(Coded),
    /// Kept as written, and why.
    Uncoded(Uncoded),
}

/// A primitive and its fate.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveReport {
    /// Index of its mesh.
    pub mesh: usize,
    /// Index of it in the mesh.
    pub primitive: usize,
    /// Its mesh's name, if any.
    pub name: Option<String>,
    /// Coded or kept, and how.
    pub outcome: PrimitiveOutcome,
}

impl PrimitiveReport {
    /// `mesh 2 "Fox" primitive 0`.
    pub fn label(&self) -> String {
        match &self.name {
            Some(n) => format!("mesh {} {n:?} primitive {}", self.mesh, self.primitive),
            None => format!("mesh {} primitive {}", self.mesh, self.primitive),
        }
    }
}

/// What [`encode_scene`] did.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct SceneReport {
    /// Every primitive of the document, in order.
    pub primitives: Vec<PrimitiveReport>,
    /// The scene's size budget for its coded primitives, when one was set.
    pub requested: Option<u64>,
    /// Extensions passed through that swm does not know: with them,
    /// replaced data is kept (see the module header of `scene_codec`).
    pub unknown_extensions: Vec<String>,
}

impl SceneReport {
    /// Bytes of all swm files.
    pub fn coded_bytes(&self) -> u64 {
        self.coded().map(|(_, c)| c.bytes).sum()
    }

    /// The coded primitives.
    pub fn coded(&self) -> impl Iterator<Item = (&PrimitiveReport, &Coded)> {
        self.primitives.iter().filter_map(|p| match &p.outcome {
            PrimitiveOutcome::Coded(c) => Some((p, c)),
            PrimitiveOutcome::Uncoded(_) => None,
        })
    }

    /// The primitives kept as written, with why.
    pub fn uncoded(&self) -> impl Iterator<Item = (&PrimitiveReport, &Uncoded)> {
        self.primitives.iter().filter_map(|p| match &p.outcome {
            PrimitiveOutcome::Uncoded(u) => Some((p, u)),
            PrimitiveOutcome::Coded(_) => None,
        })
    }
}

/// A compressed scene.
#[derive(Clone, Debug)]
pub struct SceneEncoded {
    /// The output file.
    pub bytes: Vec<u8>,
    /// What became of each primitive.
    pub report: SceneReport,
}

/// Compresses the triangle primitives of a `.glb` or `.gltf` document
/// (`base`: the folder its external buffers are read from), keeping
/// everything else (module header). Deterministic.
///
/// # Errors
/// A malformed document, or one already using `SWM_mesh_compression` or
/// `EXT_meshopt_compression` (whose bufferViews hold compressed bytes);
/// a bad option; the limits. A primitive swm cannot code is not an error:
/// it is kept and reported ([`Uncoded`]).
pub fn encode_scene(
    bytes: &[u8],
    base: Option<&Path>,
    options: &SceneOptions,
) -> Result<SceneEncoded, Error> {
    let input = document::read(bytes, base, &options.limits)?;
    for (name, why) in [
        (
            SCENE_EXTENSION,
            "a scene already compressed by swm (decode it first)",
        ),
        (
            "EXT_meshopt_compression",
            "the extension EXT_meshopt_compression (bufferViews of compressed bytes)",
        ),
    ] {
        if document::strings(&input.json["extensionsUsed"]).any(|n| n == name) {
            return Err(input.bad(Malformed::Unsupported(why)));
        }
    }
    let cx = Context {
        buffers: &input.buffers,
        limits: &options.limits,
        format: input.format,
    };
    let mut read = Vec::new();
    for mesh in input.doc.meshes() {
        for p in mesh.primitives() {
            let json = &input.json["meshes"][mesh.index()]["primitives"][p.index()];
            read.push((mesh.index(), p.index(), read::primitive(&p, json, &cx)?));
        }
    }
    let (coded, requested) = code(&input, &read, options)?;

    let mut json = input.json.clone();
    let mut data: Vec<ViewData> = (0..input.doc.views().len()).map(ViewData::Old).collect();
    let mut report = SceneReport {
        requested,
        unknown_extensions: input.unknown_extensions(),
        ..Default::default()
    };
    for ((m, k, _), outcome) in read.iter().zip(coded) {
        let outcome = match outcome {
            Ok((bytes, method, share)) => {
                let mesh = &read_mesh(&read, *m, *k);
                let c = rewrite(&mut json, &mut data, *m, *k, bytes, options, mesh)?;
                PrimitiveOutcome::Coded(Coded { method, share, ..c })
            }
            Err(u) => PrimitiveOutcome::Uncoded(u),
        };
        let name = input.json["meshes"][*m]["name"].as_str().map(str::to_owned);
        report.primitives.push(PrimitiveReport {
            mesh: *m,
            primitive: *k,
            name,
            outcome,
        });
    }
    if report.coded().next().is_some() {
        document::list_extension(&mut json, "extensionsUsed", SCENE_EXTENSION);
        if !options.fallback {
            document::list_extension(&mut json, "extensionsRequired", SCENE_EXTENSION);
        }
    }
    let prune = report.unknown_extensions.is_empty();
    let bytes = document::write(&input, json, data, prune, options.format)?;
    Ok(SceneEncoded { bytes, report })
}

type Read = Vec<(usize, usize, Result<AttributedMesh, Uncoded>)>;

fn read_mesh(read: &Read, m: usize, k: usize) -> AttributedMesh {
    read.iter()
        .find(|r| r.0 == m && r.1 == k)
        .and_then(|r| r.2.as_ref().ok())
        .cloned()
        .unwrap_or_default()
}

/// The scene's byte budget for a size or a rate: a size is the whole
/// scene's; a rate counts the distinct positions of the primitives coded
/// at a size (`lossy`), and the lossless files (`spent` bytes, whose
/// size no rate controls) come on top.
fn budget(mode: &EncodeMode, read: &Read, lossy: &[usize], spent: u64) -> Option<u64> {
    match target(mode)? {
        SwingTarget::Bytes(b) => Some(b),
        SwingTarget::BitsPerVertex(r) => {
            let n: usize = lossy
                .iter()
                .filter_map(|&i| read[i].2.as_ref().ok())
                .map(|m| m.mesh.distinct_positions())
                .sum();
            Some(spent + (r * n as f64 / 8.0).ceil() as u64)
        }
        _ => None,
    }
}

fn target(mode: &EncodeMode) -> Option<SwingTarget> {
    match *mode {
        EncodeMode::Lossless { .. } => None,
        EncodeMode::Swing { target, .. }
        | EncodeMode::Simplified { target, .. }
        | EncodeMode::Displaced { target, .. }
        | EncodeMode::Auto { target, .. } => Some(target),
    }
}

/// `mode` aimed at `target`, with no cap of its own (the scene's cap is
/// its budget).
fn aimed(mode: &EncodeMode, target: SwingTarget) -> EncodeMode {
    match *mode {
        EncodeMode::Lossless { qp } => EncodeMode::Lossless { qp },
        EncodeMode::Swing { angle_bits, .. } => EncodeMode::Swing {
            target,
            angle_bits,
            max_bytes: None,
        },
        EncodeMode::Simplified { .. } => EncodeMode::Simplified {
            target,
            max_bytes: None,
        },
        EncodeMode::Displaced { .. } => EncodeMode::Displaced {
            target,
            max_bytes: None,
        },
        EncodeMode::Auto { .. } => EncodeMode::Auto {
            target,
            max_bytes: None,
        },
    }
}

type Outcome = Result<(Vec<u8>, Method, Option<u64>), Uncoded>;

/// Codes every readable primitive: lossless ones first, then the others
/// at their shares of what is left.
/// Also returns the scene's budget, when it has one.
fn code(
    input: &Input,
    read: &Read,
    options: &SceneOptions,
) -> Result<(Vec<Outcome>, Option<u64>), Error> {
    let mode = &options.encode.mode;
    // Streams the named method's file cannot carry: coded losslessly.
    let uncarried = |m: &AttributedMesh| -> bool {
        let uvs = (m.streams.iter()).any(|s| matches!(s.kind, crate::AttributeKind::TexCoord(_)));
        !m.streams.is_empty()
            && match mode {
                EncodeMode::Swing { .. } | EncodeMode::Displaced { .. } => uvs,
                _ => false,
            }
    };
    let lossless = |m: &AttributedMesh| -> bool {
        matches!(mode, EncodeMode::Lossless { .. })
            || uncarried(m)
            || (!options.lossy_attributes && !m.streams.is_empty())
    };
    let mut out: Vec<Outcome> = Vec::with_capacity(read.len());
    let mut spent = 0u64;
    for (_, _, r) in read {
        out.push(match r {
            Err(u) => Err(u.clone()),
            Ok(m) if lossless(m) => {
                let qp = match *mode {
                    EncodeMode::Lossless { qp } => qp,
                    _ => options.attributes_qp,
                };
                let o = EncodeOptions {
                    mode: EncodeMode::Lossless { qp },
                    ..options.encode.clone()
                };
                let r = failed(crate::encode_attributed(m, &o))?
                    .map(|e| (e.bytes, Method::Lossless, None));
                spent += r.as_ref().map_or(0, |r| r.0.len() as u64);
                r
            }
            // Coded below, at its share.
            Ok(_) => Err(Uncoded::NoTriangles),
        });
    }
    let lossy: Vec<usize> = (0..read.len())
        .filter(|&i| read[i].2.as_ref().is_ok_and(|m| !lossless(m)))
        .collect();
    let budget = budget(mode, read, &lossy, spent);
    if lossy.is_empty() {
        return Ok((out, budget));
    }
    let weights = areas(input, read, &lossy)?;
    // Each lossy primitive coded at `share` bytes (or at the mode's own
    // target without a budget).
    let code_at = |i: usize, share: Option<u64>| -> Result<Outcome, Error> {
        let Ok(m) = &read[i].2 else {
            return Ok(Err(Uncoded::NoTriangles));
        };
        let target = match (share, target(mode)) {
            (Some(s), _) => SwingTarget::Bytes(s),
            (None, Some(t)) => t,
            (None, None) => unreachable!("lossless modes code every primitive above"),
        };
        let mut o = EncodeOptions {
            mode: aimed(mode, target),
            // The primitive had its NORMAL accessor, and keeps one.
            keep_smooth_normals: true,
            ..options.encode.clone()
        };
        // A decoder of the extension decodes plain: no hint to measure.
        o.swing.post_hint = false;
        let encode = |o: &EncodeOptions| match m.streams.is_empty() {
            true => crate::encode(&m.mesh, o),
            false => crate::encode_attributed(m, o),
        };
        // A share below the smallest file: that file, searched again in
        // the same encode (`EncodeOptions::or_smallest`).
        let mut encoded = encode(&EncodeOptions {
            or_smallest: true,
            ..o.clone()
        });
        // A share too small for the streams: the smallest file with them.
        let no_room =
            encoded
                .as_ref()
                .ok()
                .and_then(|e| match e.stats.attributes.dropped_because {
                    Some(crate::AttributesDropped::NoRoom { smallest }) => Some(smallest),
                    _ => None,
                });
        if let Some(smallest) = no_room {
            o.mode = aimed(mode, SwingTarget::Bytes(smallest));
            encoded = encode(&o);
        }
        Ok(failed(encoded)?.map(|e| (e.bytes, e.stats.chosen(), share)))
    };
    // The split, filled like water: the budget left goes to the
    // primitives still open in proportion to their areas; one whose file
    // comes out well under its share (it is whole at the finest grid, or
    // its method found nothing better to spend on) keeps that file and
    // its share becomes what it took, and the others are coded again at
    // their shares of what is left, at most `SPLIT_ROUNDS` times. Without
    // this, a scene whose largest primitive by area is a small mesh left
    // most of its budget unspent (the shared-corpus scene at 108 KB: 30
    // KB written, the bunny coarse at 5.8 KB).
    let mut open: Vec<usize> = (0..lossy.len()).collect();
    let mut left = budget.map(|b| b.saturating_sub(spent));
    for round in 1..=SPLIT_ROUNDS {
        let total: f64 = open.iter().map(|&j| weights[j]).sum();
        let n = open.len() as u64;
        let mut coded = Vec::with_capacity(open.len());
        for &j in &open {
            let share = left.map(|b| {
                let w = if total > 0.0 {
                    weights[j] / total
                } else {
                    1.0 / n as f64
                };
                FRAME + (b.saturating_sub(n * FRAME) as f64 * w) as u64
            });
            coded.push(code_at(lossy[j], share)?);
        }
        let under = |o: &Outcome| match o {
            Ok((bytes, _, Some(share))) => 10 * bytes.len() as u64 <= 9 * share,
            _ => false,
        };
        if round == SPLIT_ROUNDS || coded.iter().all(under) || !coded.iter().any(under) {
            for (&j, o) in open.iter().zip(coded) {
                out[lossy[j]] = o;
            }
            break;
        }
        let mut still = Vec::with_capacity(open.len());
        for (&j, o) in open.iter().zip(coded) {
            if under(&o) {
                let took = o.as_ref().map_or(0, |r| r.0.len() as u64);
                left = left.map(|b| b.saturating_sub(took));
                out[lossy[j]] = o.map(|(bytes, method, _)| (bytes, method, Some(took)));
            } else {
                still.push(j);
            }
        }
        open = still;
    }
    Ok((out, budget))
}

/// An encode's result, its failure as a reason to keep the primitive
/// (but for I/O errors, which are the machine's, not the primitive's).
fn failed(r: Result<crate::Encoded, Error>) -> Result<Result<crate::Encoded, Uncoded>, Error> {
    match r {
        Ok(e) => Ok(Ok(e)),
        Err(Error::Io(e)) => Err(Error::Io(e)),
        Err(e) => Ok(Err(Uncoded::Failed(e.to_string()))),
    }
}

/// Each listed primitive's area in world space, over the nodes of the
/// scene that draw it; its local area when none does.
fn areas(input: &Input, read: &Read, which: &[usize]) -> Result<Vec<f64>, Error> {
    let draws = scene::draws(&input.doc, input.format, true)?;
    let area = |m: &AttributedMesh, world: Option<&glam::DMat4>| -> f64 {
        let p = |i: u32| {
            let v = DVec3::from(Vec3::from(m.mesh.positions[i as usize]));
            world.map_or(v, |w| w.transform_point3(v))
        };
        m.mesh
            .triangles
            .iter()
            .map(|t| 0.5 * (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])).length())
            .sum()
    };
    Ok(which
        .iter()
        .map(|&i| {
            let (mi, ki, Ok(m)) = &read[i] else {
                return 0.0;
            };
            let mut sum = 0.0;
            let mut drawn = false;
            for d in draws
                .iter()
                .filter(|d| d.mesh == *mi && d.primitive.index() == *ki)
            {
                sum += area(m, Some(&d.world));
                drawn = true;
            }
            if drawn {
                sum
            } else {
                area(m, None)
            }
        })
        .collect())
}

/// Points primitive `k` of mesh `m` at the swm file `bytes`: new
/// accessors with the decoded mesh's counts (and data, with fallback),
/// the file in a new bufferView, the extension object.
fn rewrite(
    json: &mut Value,
    data: &mut Vec<ViewData>,
    m: usize,
    k: usize,
    bytes: Vec<u8>,
    options: &SceneOptions,
    input: &AttributedMesh,
) -> Result<Coded, Error> {
    let plain = DecodeOptions {
        limits: options.limits,
        ..DecodeOptions::plain()
    };
    let decoded = crate::decode_attributed(&bytes, &plain)?.split_vertices();
    let file_bytes = bytes.len() as u64;
    let view = document::push(json, "bufferViews", json!({ "byteLength": bytes.len() }));
    data.push(ViewData::New(bytes));

    let fallback = options.fallback;
    // The original accessor of each role (a semantic, or "indices"),
    // whose `name` and `extras` the new one keeps.
    let original = json["meshes"][m]["primitives"][k].clone();
    let mut add = |json: &mut Value, role: &str, accessor: Value, payload: Vec<u8>, target: u32| {
        let mut accessor = accessor;
        let old = match role {
            "indices" => &original["indices"],
            _ => &original["attributes"][role],
        };
        if let Some(old) = old.as_u64().map(|a| json["accessors"][a as usize].clone()) {
            for key in ["name", "extras"] {
                if let Some(v) = old.get(key) {
                    accessor[key] = v.clone();
                }
            }
        }
        if fallback {
            let v = document::push(
                json,
                "bufferViews",
                json!({ "byteLength": payload.len(), "target": target }),
            );
            data.push(ViewData::New(payload));
            accessor["bufferView"] = v.into();
        }
        document::push(json, "accessors", accessor)
    };
    let mut attributes = Map::new();
    let mut ids = Map::new();
    let (position, bytes) = position_accessor(&decoded.mesh.positions);
    attributes.insert(
        "POSITION".into(),
        add(json, "POSITION", position, bytes, ARRAY_BUFFER).into(),
    );
    let mut names = Vec::new();
    for (j, s) in decoded.streams.iter().enumerate() {
        let Some(name) = semantic(s.kind) else {
            continue;
        };
        let (accessor, bytes) = float_accessor(s);
        attributes.insert(
            name.clone(),
            add(json, &name, accessor, bytes, ARRAY_BUFFER).into(),
        );
        ids.insert(name.clone(), j.into());
        names.push(name);
    }
    let (indices, bytes) = index_accessor(&decoded.mesh);
    let indices = add(json, "indices", indices, bytes, ELEMENT_ARRAY_BUFFER);

    let p = &mut json["meshes"][m]["primitives"][k];
    p["attributes"] = Value::Object(attributes);
    p["indices"] = indices.into();
    if let Some(o) = p.as_object_mut() {
        // The coded mesh is a triangle list (§3.7.2.1: mode 4 is the default).
        o.remove("mode");
    }
    p["extensions"] = json!({ SCENE_EXTENSION: { "bufferView": view, "attributes": ids } });
    Ok(Coded {
        method: Method::Lossless,
        bytes: file_bytes,
        share: None,
        input_vertices: input.mesh.positions.len() as u64,
        input_triangles: input.mesh.triangles.len() as u64,
        vertices: decoded.mesh.positions.len() as u64,
        triangles: decoded.mesh.triangles.len() as u64,
        attributes: names,
    })
}
