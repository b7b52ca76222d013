//! Subdivision of the chamfer triangles (thesis §8.3, "Subdivision of the
//! chamfer triangles" and "Snapping the new vertices onto sharp
//! features"; ALGORITHMS.md §7).
//!
//! A new vertex goes in the middle of every blue edge and at the centroid
//! of every green triangle, and is snapped (`snap`) unless a degenerate
//! case, the edge-length rule or the distance rule (`max_snap_ratio`)
//! keeps it there. Then each face is re-cut
//! by its number of blue edges k (a, b, d its corners counter-clockwise,
//! m the new vertices, g the centroid):
//!
//! ```text
//!    k = 1             k = 2                   k = 3 (green)
//!      a                 a                          a
//!     /|\               / \                        /|\
//!    / | \        m_ab +---+ m_da           m_ab +-g-+ m_da
//!   /  |  \          /     \                    /  |  \      g is joined
//!  b---m---d        b-------d                  b---m---d     to all six
//! ```
//!
//! For k = 1 the blue edge b–d is split and a joined to m. For k = 2,
//! a–b and d–a are blue: the corner a, m_ab, m_da is cut off and the quad
//! m_ab, b, d, m_da is cut along m_ab–d or b–m_da, whichever gives the
//! larger smallest angle after snapping (the notes' choice).
//!
//! Invariants: every triangle keeps its face's orientation, red faces are
//! never split, an interior blue edge is split by one vertex shared by
//! both its faces (so the mesh stays closed and manifold), and no snapped
//! vertex makes an edge longer than `max_edge`: a face whose new edges
//! would be too long has its new vertices put back (a worklist, since
//! putting a chamfer vertex back changes the face across the edge).

use crate::prelude::*;

use glam::DVec3;

use super::classify::{is_green, Classes};
use super::geometry::{angle_at, point, FaceGeometry};
use super::options::{SharpenOptions, Unmoved};
use super::snap::{snap_corner, snap_edge, Refusal};
use crate::mesh::{CornerId, CornerTable, FaceId};

/// "No new vertex" in the per-corner and per-face id arrays.
const NONE: u32 = 0;

/// The subdivided mesh, before the cleanup.
pub(super) struct Subdivided {
    /// Input positions, then the new vertices'.
    pub positions: Vec<[f32; 3]>,
    /// The triangles: the input's, each split face replaced by its first
    /// triangle, then the split faces' other triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Vertices tagged by filter 3bis, and every new vertex.
    pub tagged: Vec<bool>,
    /// New vertices snapped.
    pub snapped: u64,
    /// New vertices left where they were inserted, by reason.
    pub unmoved: Unmoved,
    /// The triangles the split wrote (in a split face's place or after
    /// the input's), for the cleanup to examine.
    pub changed: Vec<u32>,
}

/// What a new vertex splits.
#[derive(Clone, Copy)]
enum Owner {
    /// The blue edge facing this corner (the lower of its two corners).
    Edge(CornerId),
    /// This green face.
    Face(FaceId),
}

struct NewVertex {
    owner: Owner,
    /// Where it was inserted: the edge's midpoint or the face's centroid.
    rest: DVec3,
    /// Where it is now.
    pos: DVec3,
    /// Why it was not snapped; `None` once snapped.
    refusal: Option<Refusal>,
}

/// Inserts, snaps and re-triangulates (module docs).
pub(super) fn subdivide(
    positions: &[[f32; 3]],
    table: &CornerTable,
    geometry: &FaceGeometry,
    classes: &Classes,
    options: &SharpenOptions,
    max_edge: f64,
) -> Subdivided {
    let nv = positions.len();
    let nc = table.corner_count();
    let nf = table.face_count();
    let vs = table.vertices();
    let os = table.opposites();
    let p = |c: CornerId| point(positions, vs[c.idx()].0);

    let mut triangles = table.triangles();
    let mut tagged = classes.tagged.clone();
    if classes.blue_edges == 0 {
        return Subdivided {
            positions: positions.to_vec(),
            triangles,
            tagged,
            snapped: 0,
            unmoved: Unmoved::default(),
            changed: Vec::new(),
        };
    }

    // New vertex ids: chamfer vertices in corner order, then corners.
    // Zero means none: new ids are at least nv, and nv > 0 when there
    // are faces (zeroed arrays cost nothing until touched).
    let mut mid = vec![NONE; nc];
    let mut centre = vec![NONE; if classes.green_faces > 0 { nf } else { 0 }];
    let mut news: Vec<NewVertex> = Vec::new();
    let add = |owner: Owner, rest: DVec3, news: &mut Vec<NewVertex>| {
        news.push(NewVertex {
            owner,
            rest,
            pos: rest,
            refusal: None,
        });
        (nv + news.len() - 1) as u32
    };
    for c in 0..nc as u32 {
        let c = CornerId(c);
        let o = os[c.idx()];
        if classes.blue(c) && o.0 > c.0 {
            let id = add(Owner::Edge(c), 0.5 * (p(c.next()) + p(c.prev())), &mut news);
            mid[c.idx()] = id;
            mid[o.idx()] = id;
        }
    }
    if classes.green_faces > 0 {
        for f in 0..nf as u32 {
            let f = FaceId(f);
            if is_green(classes, f) {
                let [a, b, d] = [0, 1, 2].map(|k| p(f.corner(k)));
                centre[f.idx()] = add(Owner::Face(f), (a + b + d) / 3.0, &mut news);
            }
        }
    }

    // The plane normal at a corner's vertex: the angle-weighted sum of
    // its red faces' normals, found by walking its fan (only endpoints of
    // blue edges ask, a few per chamfer edge).
    let normal = |c: CornerId| {
        let v = vs[c.idx()];
        let mut sum = DVec3::ZERO;
        for d in table.ring(v) {
            if classes.face_red[d.face().idx()] {
                let w = angle_at(p(d), p(d.next()), p(d.prev()));
                sum += w * geometry.normals[d.face().idx()].as_dvec3();
            }
        }
        // The weights sum to at most 2π, and the normals are unit
        // vectors: a sum this short means they cancel out.
        let len = sum.length();
        if len > 1e-9 {
            sum / len
        } else {
            DVec3::ZERO
        }
    };

    // Snap the chamfer vertices, then the corners (whose new edges reach
    // the chamfer vertices' final places).
    let too_long = |x: DVec3, ends: &[DVec3]| ends.iter().any(|&e| (x - e).length() > max_edge);
    for n in news.iter_mut() {
        let Owner::Edge(c) = n.owner else { continue };
        let (a, b) = (c.next(), c.prev());
        let o = os[c.idx()];
        let far = options.max_snap_ratio * (p(b) - p(a)).length();
        match snap_edge(p(a), p(b), normal(a), normal(b), options.parallel_tolerance) {
            Ok(x) if (x - n.rest).length() > far => n.refusal = Some(Refusal::TooFar),
            Ok(x) if too_long(x, &[p(a), p(b), p(c), p(o)]) => n.refusal = Some(Refusal::TooLong),
            Ok(x) => n.pos = x,
            Err(r) => n.refusal = Some(r),
        }
    }
    for i in 0..news.len() {
        let Owner::Face(f) = news[i].owner else {
            continue;
        };
        let cs = [0, 1, 2].map(|k| f.corner(k));
        let ps = cs.map(p);
        let ns = cs.map(normal);
        let mids = cs.map(|c| news[mid[c.idx()] as usize - nv].pos);
        let longest = (0..3)
            .map(|k| (ps[k] - ps[(k + 1) % 3]).length())
            .fold(0.0, f64::max);
        match snap_corner(ps, ns, options.coplanar_tolerance) {
            Ok(x) if (x - news[i].rest).length() > options.max_snap_ratio * longest => {
                news[i].refusal = Some(Refusal::TooFar)
            }
            Ok(x) if too_long(x, &ps) || too_long(x, &mids) => {
                news[i].refusal = Some(Refusal::TooLong)
            }
            Ok(x) => news[i].pos = x,
            Err(r) => news[i].refusal = Some(r),
        }
    }

    // Edges between two new vertices (the m–m edge of a k = 2 face, the
    // g–m edges of a green face): put a face's new vertices back while
    // one is too long. A chamfer vertex put back changes the face across
    // its edge, which is checked again.
    let new_of = |c: CornerId| mid[c.idx()];
    let blue_count = |f: FaceId| (0..3).filter(|&k| new_of(f.corner(k)) != NONE).count();
    let mut work: Vec<u32> = Vec::new();
    for n in &news {
        if let Owner::Edge(c) = n.owner {
            for f in [c.face(), os[c.idx()].face()] {
                if blue_count(f) >= 2 {
                    work.push(f.0);
                }
            }
        }
    }
    while let Some(f) = work.pop() {
        let f = FaceId(f);
        let cs = [0, 1, 2].map(|k| f.corner(k));
        let g = centre.get(f.idx()).copied().unwrap_or(NONE);
        let ids: Vec<u32> = cs
            .iter()
            .map(|&c| new_of(c))
            .chain([g])
            .filter(|&id| id != NONE)
            .collect();
        let at = |id: u32| news[id as usize - nv].pos;
        let long = if g != NONE {
            cs.iter()
                .any(|&c| (at(g) - at(new_of(c))).length() > max_edge)
        } else {
            // k = 2: the two chamfer vertices are joined.
            (at(ids[0]) - at(ids[1])).length() > max_edge
        };
        if !long {
            continue;
        }
        for &id in &ids {
            let n = &mut news[id as usize - nv];
            if n.refusal.is_some() {
                continue;
            }
            n.pos = n.rest;
            n.refusal = Some(Refusal::TooLong);
            if let Owner::Edge(c) = n.owner {
                let o = os[c.idx()];
                let other = if c.face() == f { o.face() } else { c.face() };
                if blue_count(other) >= 2 {
                    work.push(other.0);
                }
            }
        }
    }

    // Re-triangulate: each split face's first triangle takes its place,
    // the others go at the end.
    let new_pos = |id: u32| {
        if (id as usize) < nv {
            point(positions, id)
        } else {
            news[id as usize - nv].pos
        }
    };
    let split = |f: FaceId, triangles: &mut Vec<[u32; 3]>, changed: &mut Vec<u32>| {
        let cs = [0, 1, 2].map(|k| f.corner(k));
        let v = cs.map(|c| vs[c.idx()].0);
        let m = cs.map(new_of);
        let mut out: [[u32; 3]; 6] = [[0; 3]; 6];
        let count = match m.iter().filter(|&&x| x != NONE).count() {
            0 => return,
            1 => {
                // The blue edge b–d faces a.
                let i = (0..3).find(|&k| m[k] != NONE).unwrap_or(0);
                let (a, b, d) = (v[i], v[(i + 1) % 3], v[(i + 2) % 3]);
                out[0] = [a, b, m[i]];
                out[1] = [a, m[i], d];
                2
            }
            2 => {
                // The edge b–d facing a is not blue; a–b and d–a are.
                let i = (0..3).find(|&k| m[k] == NONE).unwrap_or(0);
                let (a, b, d) = (v[i], v[(i + 1) % 3], v[(i + 2) % 3]);
                let (mab, mda) = (m[(i + 2) % 3], m[(i + 1) % 3]);
                out[0] = [a, mab, mda];
                let smallest = |t: [[u32; 3]; 2]| {
                    t.iter()
                        .map(|t| min_angle(t.map(new_pos)))
                        .fold(f64::INFINITY, f64::min)
                };
                let along = [[mab, b, d], [mab, d, mda]];
                let across = [[mab, b, mda], [b, d, mda]];
                let pick = if smallest(across) > smallest(along) {
                    across
                } else {
                    along
                };
                out[1] = pick[0];
                out[2] = pick[1];
                3
            }
            _ => {
                let g = centre[f.idx()];
                for k in 0..3 {
                    // Around g: the corner, then the middle of the edge
                    // from it to the next corner (which faces the corner
                    // after), then the next corner.
                    let (a, b) = (v[k], v[(k + 1) % 3]);
                    let mab = m[(k + 2) % 3];
                    out[2 * k] = [g, a, mab];
                    out[2 * k + 1] = [g, mab, b];
                }
                6
            }
        };
        triangles[f.idx()] = out[0];
        changed.push(f.0);
        changed.extend(triangles.len() as u32..(triangles.len() + count - 1) as u32);
        triangles.extend_from_slice(&out[1..count]);
    };
    let mut changed = Vec::new();
    // Every split face has a blue edge: visit the faces of the blue
    // edges, each once (the face's lowest blue corner does it).
    for n in &news {
        let Owner::Edge(c) = n.owner else { continue };
        for c in [c, os[c.idx()]] {
            let f = c.face();
            let first = (0..3)
                .map(|k| f.corner(k))
                .find(|&d| new_of(d) != NONE)
                .unwrap_or(c);
            if first == c {
                split(f, &mut triangles, &mut changed);
            }
        }
    }

    let mut unmoved = Unmoved::default();
    let mut snapped = 0u64;
    for n in &news {
        match n.refusal {
            None => snapped += 1,
            Some(Refusal::Parallel) => unmoved.parallel += 1,
            Some(Refusal::Coplanar) => unmoved.coplanar += 1,
            Some(Refusal::Mixed) => unmoved.mixed += 1,
            Some(Refusal::NoNormal) => unmoved.no_normal += 1,
            Some(Refusal::TooLong) => unmoved.too_long += 1,
            Some(Refusal::TooFar) => unmoved.too_far += 1,
        }
    }
    let mut out_positions = Vec::with_capacity(nv + news.len());
    out_positions.extend_from_slice(positions);
    out_positions.extend(news.iter().map(|n| n.pos.as_vec3().to_array()));
    tagged.resize(nv + news.len(), true);
    Subdivided {
        positions: out_positions,
        triangles,
        tagged,
        snapped,
        unmoved,
        changed,
    }
}

/// The smallest angle of a triangle, radians.
pub(super) fn min_angle([a, b, c]: [DVec3; 3]) -> f64 {
    angle_at(a, b, c)
        .min(angle_at(b, c, a))
        .min(angle_at(c, a, b))
}
