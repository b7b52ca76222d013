//! Chamfer detection (thesis §8.3, "Identification of the chamfer
//! triangles", the filter approach; §8.4, filter 3bis; ALGORITHMS.md §7).
//!
//! Everything starts gray; smooth edges are painted brown. Then:
//! 1. a vertex whose incident edges are all brown is red;
//! 2. a triangle with a red vertex is red;
//! 3. red floods across brown edges;
//!
//!    (swm's rule, not the thesis's: only into triangles whose normal
//!    is within the smooth threshold 2ε of the normal of the triangle
//!    the flood started from. Consecutive triangles of a chamfer strip
//!    are alike, so the edges between them are brown; where one strip
//!    triangle is nearly flat the thesis's flood enters the strip and
//!    paints all of it red, and the crease is never restored. On the
//!    generated cube at L = 0.08: centroid RMS error after sharpening
//!    0.00180 → 0.00111, largest 0.0229 → 0.0159; fandisk 0.91-0.98x L2.)
//!
//!    3bis. the endpoints of a non-brown edge between two red triangles
//!    are tagged, and so is a vertex whose red triangles form two or more
//!    separate runs around it (a non-manifold red neighbourhood);
//! 4. the edges and vertices of red triangles are red;
//! 5. a non-red edge joining two red vertices is blue (a chamfer edge);
//! 6. a triangle with three blue edges is green (a corner).
//!
//! Invariants: an interior edge's two corners carry the same colours;
//! boundary edges are never brown (they have one normal) and never blue
//! (a chamfer is a strip between two smooth regions, which a boundary
//! edge cannot cross); a face with a blue edge is never red (all edges of
//! a red face are red), so red faces are never split.
//!
//! Every filter is one or two sweeps over flat arrays indexed by corner,
//! face or vertex; the flood visits each face at most once.

use crate::math;
use crate::prelude::*;

use glam::Vec3;

use crate::mesh::{CornerId, CornerTable, FaceId};

/// Edge colours, per corner (the edge facing the corner).
const BROWN: u8 = 1;
/// See [`BROWN`].
const RED: u8 = 2;
/// See [`BROWN`].
const BLUE: u8 = 4;

/// The colours of every element.
pub(super) struct Classes {
    /// Colour bits of the edge facing each corner.
    pub edge: Vec<u8>,
    /// Red faces (after filter 3).
    pub face_red: Vec<bool>,
    /// Vertices tagged by filter 3bis.
    pub tagged: Vec<bool>,
    /// ε, radians.
    pub mean_normal_angle: f64,
    /// Brown (interior) edges.
    pub smooth_edges: u64,
    /// Blue edges.
    pub blue_edges: u64,
    /// Green faces.
    pub green_faces: u64,
}

impl Classes {
    /// Whether the edge facing `c` is blue.
    #[inline(always)]
    pub fn blue(&self, c: CornerId) -> bool {
        self.edge[c.idx()] & BLUE != 0
    }
}

/// Colours the mesh: smooth edges, filters 1-6 and 3bis (module docs).
/// `normals` are the unit face normals, zero for faces without area.
pub(super) fn classify(table: &CornerTable, normals: &[Vec3], smooth_factor: f64) -> Classes {
    let nc = table.corner_count();
    let nf = table.face_count();
    let nv = table.vertex_count();
    let vs = table.vertices();
    let os = table.opposites();
    let face = |c: usize| c / 3;
    let next = |c: usize| CornerId(c as u32).next().idx();
    let prev = |c: usize| CornerId(c as u32).prev().idx();

    // ε: mean angle between the normals of an interior edge's faces. An
    // edge beside a face without area has no angle: it counts neither in
    // the mean nor as smooth. The cosine goes to both corners of the edge
    // so that the smooth test below is one sequential sweep.
    let mut cosine = vec![f32::NAN; nc];
    let mut sum = 0.0f64;
    let mut counted = 0u64;
    for c in 0..nc {
        let o = os[c];
        if o.is_none() || o.idx() < c {
            continue;
        }
        let (n1, n2) = (normals[face(c)], normals[face(o.idx())]);
        if n1 == Vec3::ZERO || n2 == Vec3::ZERO {
            continue;
        }
        let d = n1.as_dvec3().dot(n2.as_dvec3()).clamp(-1.0, 1.0);
        sum += acos(d);
        counted += 1;
        cosine[c] = d as f32;
        cosine[o.idx()] = d as f32;
    }
    let mean = if counted > 0 {
        sum / counted as f64
    } else {
        0.0
    };
    // angle < t  ⇔  cos(angle) > cos(t) for t in [0, π]; NaN (no angle)
    // compares false. With t = 0 nothing is smooth.
    let threshold = (smooth_factor * mean).min(core::f64::consts::PI);
    let cos_threshold = if threshold > 0.0 {
        math::cos(threshold) as f32
    } else {
        f32::INFINITY
    };
    let mut edge: Vec<u8> = cosine
        .iter()
        .map(|&d| if d > cos_threshold { BROWN } else { 0 })
        .collect();
    drop(cosine);
    let smooth_edges = edge.iter().filter(|&&e| e == BROWN).count() as u64 / 2;

    // Filter 1. State per vertex: 0 unseen, 1 all brown so far, 2 not.
    // The two edges of a triangle at corner c face n(c) and p(c).
    let mut state = vec![0u8; nv];
    for c in 0..nc {
        let all_brown = edge[next(c)] & edge[prev(c)] & BROWN != 0;
        let s = &mut state[vs[c].idx()];
        *s = (*s).max(if all_brown { 1 } else { 2 });
    }
    let mut vertex_red: Vec<bool> = state.iter().map(|&s| s == 1).collect();
    drop(state);

    // Filter 2: 1 = red, not yet flooded from; 2 = red and flooded from.
    let mut red: Vec<u8> = (0..nf)
        .map(|f| {
            let [a, b, c] = [0, 1, 2].map(|k| vertex_red[vs[3 * f + k].idx()]);
            u8::from(a || b || c)
        })
        .collect();

    // Filter 3: depth-first flood across brown edges from each core
    // face, into faces whose normal is within the smooth threshold of
    // the core face's (swm's rule, module docs: a chamfer strip's faces
    // are alike, so the edges between them are brown, and an unbounded
    // flood that reaches one paints the whole strip red). With t = 0
    // nothing is brown and nothing floods.
    let cos_flood = cos_threshold.min(1.0);
    let mut stack: Vec<u32> = Vec::new();
    for f0 in 0..nf {
        if red[f0] != 1 {
            continue;
        }
        red[f0] = 2;
        stack.push(f0 as u32);
        let seed = normals[f0];
        while let Some(f) = stack.pop() {
            for c in 3 * f as usize..3 * f as usize + 3 {
                // The face across a brown edge with a red endpoint is red
                // by filter 2 already: only the others need a look.
                if edge[c] & BROWN == 0
                    || vertex_red[vs[next(c)].idx()]
                    || vertex_red[vs[prev(c)].idx()]
                {
                    continue;
                }
                // A brown edge is interior.
                let g = face(os[c].idx());
                if red[g] == 0 && normals[g].dot(seed) > cos_flood {
                    red[g] = 2;
                    stack.push(g as u32);
                }
            }
        }
    }
    drop(stack);
    let face_red: Vec<bool> = red.iter().map(|&r| r != 0).collect();
    drop(red);

    // Filter 4, with the second rule of filter 3bis on the way: count
    // the runs of red faces around each vertex. A run starts at a red
    // face whose clockwise neighbour around the vertex, across the edge
    // facing p(c), is missing (boundary) or not red; a fan that is red
    // all round has no start and is one run.
    let mut runs = vec![0u8; nv];
    for f in 0..nf {
        if !face_red[f] {
            continue;
        }
        for c in 3 * f..3 * f + 3 {
            edge[c] |= RED;
            let o = os[c];
            if o.is_some() {
                edge[o.idx()] |= RED;
            }
            let v = vs[c].idx();
            vertex_red[v] = true;
            let l = os[prev(c)];
            if l.is_none() || !face_red[face(l.idx())] {
                runs[v] = runs[v].saturating_add(1);
            }
        }
    }
    let mut tagged: Vec<bool> = runs.iter().map(|&r| r >= 2).collect();
    drop(runs);

    // Filter 3bis, first rule: a non-brown edge between two red faces
    // tags both its endpoints. Filter 5: a non-red interior edge between
    // two red vertices is blue.
    let mut blue_edges = 0u64;
    for c in 0..nc {
        let o = os[c];
        if o.is_none() || o.idx() < c {
            continue;
        }
        let (a, b) = (vs[next(c)].idx(), vs[prev(c)].idx());
        let e = edge[c];
        if e & BROWN == 0 && face_red[face(c)] && face_red[face(o.idx())] {
            tagged[a] = true;
            tagged[b] = true;
        }
        if e & RED == 0 && vertex_red[a] && vertex_red[b] {
            edge[c] |= BLUE;
            edge[o.idx()] |= BLUE;
            blue_edges += 1;
        }
    }

    // Filter 6: green faces are counted here and recognised by `split`
    // from their three blue edges.
    let green_faces = edge
        .chunks_exact(3)
        .filter(|e| e[0] & e[1] & e[2] & BLUE != 0)
        .count() as u64;

    Classes {
        edge,
        face_red,
        tagged,
        mean_normal_angle: mean,
        smooth_edges,
        blue_edges,
        green_faces,
    }
}

/// acos to within 2·10⁻⁸ (Abramowitz & Stegun 4.4.46), several times
/// faster than the library's: ε is a mean over every edge, and this is
/// the only transcendental function per edge.
#[inline]
pub(super) fn acos(x: f64) -> f64 {
    const A: [f64; 8] = [
        1.570_796_305_0,
        -0.214_598_801_6,
        0.088_978_987_4,
        -0.050_174_304_6,
        0.030_891_881_0,
        -0.017_088_125_6,
        0.006_670_090_1,
        -0.001_262_491_1,
    ];
    let t = x.abs();
    let poly = A.iter().rev().fold(0.0, |acc, &a| acc * t + a);
    let r = math::sqrt((1.0 - t).max(0.0)) * poly;
    if x < 0.0 {
        core::f64::consts::PI - r
    } else {
        r
    }
}

/// Whether face `f` is green (three blue edges).
#[inline]
pub(super) fn is_green(classes: &Classes, f: FaceId) -> bool {
    (0..3).all(|k| classes.blue(f.corner(k)))
}
