//! The encoder of mode 2: a base mesh and a plan in, the file and the
//! decoder's exact reconstruction out.
//!
//! Closed loop: the base is coded by the lossless mode and decoded again,
//! and every level is predicted from the previous level as the decoder
//! holds it (the same `refine` the decoder runs), so quantization errors
//! never accumulate unseen. Each level's step is `c` times the mean edge
//! of the level it refines, stored in `HEAD` as an `f32`, so the decoder
//! never recomputes it.
//!
//! Rate control can also give the finest step that the error it expects
//! of the file asks for ([`Plan::step`], in the mesh's units;
//! `encoder::displaced`'s `STEP_ERROR`): no level's step is then finer
//! than its share of it (the coarser levels' shares follow by
//! `step_decay`, as the edge rule's steps do).

use super::bend;
use super::fit::{self, Fallback, Target};
use super::predict::{self, Frame, Rule};
use super::subdivide::Edges;
use super::{refine, Head, MAX_LEVELS};
use crate::container::{parse_container, write_container, Framing, Header, Mode, Tag};
use crate::{CleanOptions, Error, Limits, ParameterError, TriMesh};
use rayon::prelude::*;

/// How a file is made from its base: the level count and framing of
/// this file, and the method's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plan {
    /// Subdivision levels, 1..=[`MAX_LEVELS`].
    pub levels: usize,
    pub settings: Settings,
    pub framing: Framing,
    /// The finest level's step the expected error asks for, in the mesh's
    /// units: no step is finer ([`at_least`]); `None`: the edge rule's.
    pub step: Option<f64>,
}

/// The encoder's choices that are not the file's size: the method's
/// settings (`encoder::displaced::Displaced` holds one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings {
    pub rule: Rule,
    /// Step of the finest level over its mean edge length (`c`).
    pub step_scale: f64,
    /// How much finer than `c` times its own mean edge a coarser level's
    /// step is: level `l` of `k` gets `c · mean_l / 2^(decay · (k − 1 − l))`.
    /// 0 is the oracle's rule (each level its own mean edge); 1 gives
    /// every level about the finest level's step, since edges halve.
    pub step_decay: f64,
    /// Move the base's vertices to the input's nearest points before
    /// coding: the scheme interpolates them, so they stay in the result.
    pub snap_base: bool,
    /// Reach of a crossing over the level's mean edge length.
    pub reach_scale: f64,
    pub fallback: Fallback,
    /// Only crossings with input triangles facing the normal's way.
    pub facing: bool,
    /// Bits per coordinate of the base; `None`: [`base_qp`]'s rule.
    pub qp: Option<u8>,
    /// The rule's quantization step of the base over the finest level's
    /// step, as a power of two.
    pub qp_slack: f64,
    /// Fit each level's bend (`bend`); `false`: none, as files before
    /// bends.
    pub bend: bool,
    /// Write `BASE` bare (`BARE_BASE` of `HEAD`); `false`: a whole mode-0
    /// file, as files before bare bases.
    pub bare_base: bool,
    /// The finest step over the error expected of the file, once rate
    /// control has measured one (`encoder::displaced`); `None`: the edge
    /// rule always.
    pub step_error: Option<f64>,
}

/// A file and what it is made of.
pub(crate) struct Written {
    pub bytes: Vec<u8>,
    /// What the decoder gives for `bytes`, bit for bit.
    pub mesh: TriMesh,
    /// Bytes of `BASE` and of each level's chunk.
    pub base_bytes: usize,
    pub level_bytes: Vec<usize>,
    /// Faces of the base.
    pub base_faces: usize,
    /// Bits per coordinate of the base.
    pub qp: u8,
    /// The finest level's step, in the mesh's units.
    pub step: f64,
    /// New vertices whose normal line missed the input, per level.
    pub misses: Vec<usize>,
    /// The face count the base was simplified to (`Simplifier::simplify`'s
    /// target; 0 until the caller sets it): where its vertices' origins
    /// start (`encoder::provenance`).
    pub base_target: u32,
}

/// The mode-2 file of `base` (a simplification of the input) refined
/// towards `target`.
pub(crate) fn write(base: &TriMesh, target: &Target<'_>, plan: &Plan) -> Result<Written, Error> {
    if !(1..=MAX_LEVELS).contains(&plan.levels) {
        return Err(ParameterError::OutOfRange {
            name: "subdivision levels",
            value: plan.levels as f64,
            min: 1.0,
            max: MAX_LEVELS as f64,
        }
        .into());
    }
    let snapped;
    let base = if plan.settings.snap_base {
        snapped = snap(base, target);
        &snapped
    } else {
        base
    };
    let cleaned = crate::clean(base, &CleanOptions::default())?;
    let qp = plan
        .settings
        .qp
        .unwrap_or_else(|| base_qp(&cleaned.mesh, plan));
    // A bare base is the compact file's sections without its frame
    // (`BARE_BASE`): the same mode-0 sections, decoded the same.
    let framing = match plan.settings.bare_base {
        true => Framing::Compact,
        false => plan.framing,
    };
    let (base_file, _, _) = crate::lossless::encode(&cleaned.table, &cleaned.mesh, qp, framing)?;
    let limits = Limits::default();
    let base_container = parse_container(&base_file, &limits)?;
    let mut mesh = crate::lossless::decode(&base_container, &limits)?;
    let bare = match plan.settings.bare_base {
        true => {
            let sections: Vec<(Tag, &[u8])> = base_container
                .sections()
                .map(|s| (s.tag, s.bytes))
                .collect();
            Some(crate::container::write_bare(
                &base_container.header,
                &sections,
            )?)
        }
        false => None,
    };
    let base_section: &[u8] = bare.as_deref().unwrap_or(&base_file);
    let base_faces = mesh.triangles.len();
    let mut steps = Vec::with_capacity(plan.levels);
    let mut bends = Vec::with_capacity(plan.levels);
    let mut disp = Vec::new();
    let (mut level_bytes, mut misses) = (Vec::new(), Vec::new());
    // The level below's scalars and its first new vertex: the parents'
    // contexts (`scalars::parent_contexts`).
    let (mut below, mut first) = (Vec::new(), mesh.positions.len());
    for level in 0..plan.levels {
        let edges = Edges::new(&mesh.triangles);
        // As `predict::frames`, in parallel (each frame is a pure
        // function of the level, so the same bits).
        let crosses: Vec<[f64; 3]> = mesh
            .triangles
            .par_iter()
            .map(|t| predict::cross(t, &mesh.positions))
            .collect();
        let frames: Vec<Frame> = (0..edges.len())
            .into_par_iter()
            .with_min_len(1024)
            .map(|e| {
                let (t, p) = (&mesh.triangles, &mesh.positions);
                let plain = predict::Stencil::plain(plan.settings.rule);
                predict::frame(e, &edges, t, p, &crosses, plain)
            })
            .collect();
        let mean = mean_edge(&edges, &mesh);
        let below_finest = (plan.levels - 1 - level) as f64;
        let edge =
            plan.settings.step_scale * mean / (below_finest * plan.settings.step_decay).exp2();
        // Each level coarser asks 2^(1 − decay) times the step (edges
        // halve from level to level, so this is the edge rule's ratio).
        let step = match plan.step {
            Some(finest) => at_least(
                edge,
                finest * (below_finest * (1.0 - plan.settings.step_decay)).exp2(),
            ),
            None => edge,
        };
        let step = step as f32;
        let step = if step.is_finite() && step > 0.0 {
            step
        } else {
            f32::MIN_POSITIVE
        };
        let (t, missed) = fit::offsets(
            &frames,
            target,
            plan.settings.reach_scale * mean,
            plan.settings.fallback,
            plan.settings.facing,
        );
        // The level's bend, fitted to its offsets, moves every frame's
        // point and so every offset (`bend`). Not on the finest level of
        // a file of several: it holds three quarters of the edges (of the
        // decoder's placement work: bends cost it 4% a triangle when every
        // level has one) and the least lean, the coarser levels' bends having
        // taken most of it from the surface it refines (offline, bunny at
        // 8 b/v: scalar bytes −4.3% with the first level's bend alone,
        // −5.0% with both).
        let finest_of_several = plan.levels > 1 && level + 1 == plan.levels;
        let contexts = super::scalars::contexts(&edges, &mesh.triangles, first, &below);
        let code = match plan.settings.bend && !finest_of_several {
            true => {
                let lifts = bend::lifts(&frames, &edges, &mesh);
                bend::choose(&lifts, &t, step, |t| {
                    let qs: Vec<i32> = t.iter().map(|&t| fit::quantize(t, step)).collect();
                    super::scalars::encode_level(&qs, &contexts).len()
                })
            }
            false => 0,
        };
        let (frames, t) = bend::apply(frames, &edges, &mesh, t, code);
        let qs: Vec<i32> = t.iter().map(|&t| fit::quantize(t, step)).collect();
        let chunk = super::scalars::encode_level(&qs, &contexts);
        crate::varint::put(&mut disp, chunk.len() as u64);
        disp.extend_from_slice(&chunk);
        level_bytes.push(chunk.len());
        misses.push(missed);
        steps.push(step);
        bends.push(code);
        first = mesh.positions.len();
        mesh.triangles = refine(
            &mut mesh.positions,
            &mesh.triangles,
            &edges,
            &frames,
            step,
            &qs,
        )?;
        below = qs;
    }
    let finest_step = steps.last().map_or(0.0, |&s| f64::from(s));
    let head = Head {
        rule: plan.settings.rule,
        steps,
        bends,
        bare: plan.settings.bare_base,
    }
    .write();
    let h = &base_container.header;
    let mut header = Header::new(
        Mode::Displaced,
        mesh.positions.len() as u32,
        mesh.triangles.len() as u32,
        h.component_count,
    )
    .with_framing(plan.framing);
    header.minor = 2;
    let sections: [(Tag, &[u8]); 3] = [
        (Tag::HEAD, &head),
        (Tag::BASE, base_section),
        (Tag::DISP, &disp),
    ];
    let bytes = write_container(&header, &sections)?;
    Ok(Written {
        bytes,
        mesh,
        base_bytes: base_section.len(),
        level_bytes,
        base_faces,
        qp,
        step: finest_step,
        misses,
        base_target: 0,
    })
}

/// The base's bits per coordinate: base vertices are never corrected
/// (the scheme interpolates them), so their quantization step should be
/// about the finest level's step, `2^slack` times it: the finest step is
/// `c` times the finest coarse level's mean edge, about the base's over
/// `2^(k − 1)`. Within the lossless mode's 6..=16 bits.
fn base_qp(base: &TriMesh, plan: &Plan) -> u8 {
    let edges = Edges::new(&base.triangles);
    let finest =
        plan.settings.step_scale * mean_edge(&edges, base) / ((plan.levels - 1) as f64).exp2();
    let finest = plan.step.map_or(finest, |asked| at_least(finest, asked));
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &base.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let range = (0..3).map(|k| f64::from(hi[k] - lo[k])).fold(0.0, f64::max);
    let bits = (range / (finest * plan.settings.qp_slack.exp2()))
        .log2()
        .ceil();
    if bits.is_finite() {
        bits.clamp(6.0, 16.0) as u8
    } else {
        12
    }
}

/// The edge rule's step `edge`, or `asked` where that is coarser: a
/// step finer than the expected error asks for spends bits on precision
/// the file's other errors drown (measured: bunny and horse's edge-rule
/// steps are 1.8-3.0 times their files' L2 at 0.5-8 b/v and a step
/// closer to 2 L2 there was no better, bunny at 8 b/v 0.782 against
/// 0.733; spot, homer and cheburashka at 0.5-1 b/v had a quarter to half
/// of 2 L2, and the floor cut their L2 by 7-37%).
pub(crate) fn at_least(edge: f64, asked: f64) -> f64 {
    if asked.is_finite() {
        edge.max(asked)
    } else {
        edge
    }
}

/// `base` with each vertex at the input's nearest point.
fn snap(base: &TriMesh, target: &Target<'_>) -> TriMesh {
    let positions = base
        .positions
        .par_iter()
        .map(|p| {
            let mut scratch = crate::metrics::NearestScratch::default();
            match target
                .surface
                .nearest_point(p.map(f64::from), None, &mut scratch)
            {
                Some((_, q, _)) => q.map(|c| c as f32),
                None => *p,
            }
        })
        .collect();
    TriMesh::new(positions, base.triangles.clone())
}

/// The mean length of a level's edges (encoder only: the decoder reads
/// the step).
fn mean_edge(edges: &Edges, mesh: &TriMesh) -> f64 {
    if edges.len() == 0 {
        return 0.0;
    }
    let mut sum = 0.0;
    for e in 0..edges.len() {
        let [a, b, _] = super::subdivide::corner_vertices(edges.corners(e)[0], &mesh.triangles);
        let (p, q) = (mesh.positions[a as usize], mesh.positions[b as usize]);
        let d2: f64 = (0..3)
            .map(|k| (f64::from(p[k]) - f64::from(q[k])).powi(2))
            .sum();
        sum += d2.sqrt();
    }
    sum / edges.len() as f64
}
