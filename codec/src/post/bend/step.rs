//! One Bender step: every triangle split 1→4, every edge given a new
//! point by the stencil its ends call for (M. Attene, *Surface Remeshing
//! and Applications*, 2004, §8.4; D. Zorin, P. Schröder, W. Sweldens,
//! SIGGRAPH 1996; `../shared/design/ALGORITHMS.md` §8).
//!
//! Which stencil ([`stencil`]):
//! * a hard edge (tagged or boundary) V–W: R2 along the chain when both
//!   ends are 1-manifold sharp vertices, R6 when only one is, else the
//!   midpoint (§8.4.1.1);
//! * any other edge: each end is smooth (valence k) or, with two or more
//!   hard edges, the edge lies in one sector of it (k triangles) — the
//!   topological cut of §8.4.1.2, read off the ring instead of copying the
//!   vertex. When both ends are regular (k = 6, or a sector of 3) the
//!   regular rule for the pair applies: R1 (smooth–smooth), R4
//!   (crease–smooth), R5 (crease–crease with an ear) or R3 (the other
//!   crease–crease case). Otherwise E1 (smooth) or E2 (sector) at the
//!   irregular end, averaged when both are.
//!
//! Invariants kept: old vertices keep their index and position; edge e's
//! point is vertex `n + e` (n old vertices, edges numbered as in
//! [`classify`](super::classify)); triangle t becomes triangles 4t … 4t+3
//! with t's orientation:
//!
//! ```text
//!                 v2
//!                /  \              4t   : v0, m2, m1
//!              m1 -- m0            4t+1 : m2, v1, m0
//!             /  \  /  \           4t+2 : m1, m0, v2
//!           v0 -- m2 -- v1         4t+3 : m0, m1, m2   (m_k faces v_k)
//! ```
//!
//! and both halves of a tagged edge are tagged. Everything is linear in
//! the mesh: fans of more than `direct_max` triangles use stencil sums
//! shared by the whole fan ([`stencil::e1_all`], [`stencil::e2_all`])
//! instead of summing each edge's stencil.

use crate::prelude::*;

use glam::DVec3;

use super::super::SharpEdges;
use super::classify::{Classes, End, HARD, TAGGED};
use super::stencil;
use crate::{CornerId, CornerTable, TriMesh};

/// Fans (or sectors) of up to this many triangles are summed stencil by
/// stencil; larger ones, rare and only quadratic if summed so, from
/// shared sums.
pub(super) const DIRECT_MAX: usize = 16;

/// Subdivides `mesh` once. `table` is its corner table and `tags` its
/// sharp edges; returns the refined mesh and its tags.
pub(super) fn step(
    mesh: &TriMesh,
    table: &CornerTable,
    tags: &SharpEdges,
    direct_max: usize,
) -> (TriMesh, SharpEdges) {
    let classes = Classes::new(table, tags);
    let largest = classes.faces.iter().copied().max().unwrap_or(0) as usize;
    let cap = direct_max.min(largest);
    let points = Points {
        classes: &classes,
        pos: &mesh.positions,
        large: large_fans(&classes, &mesh.positions, cap),
        cap,
    };
    let n = mesh.positions.len();
    let ne = classes.edge_count();
    let mut positions = Vec::with_capacity(n + ne);
    positions.extend_from_slice(&mesh.positions);
    let (mut buf_v, mut buf_w) = (vec![0u32; cap + 1], vec![0u32; cap + 1]);
    for e in 0..ne {
        let p = points.edge_point(e, &mut buf_v, &mut buf_w);
        positions.push([p.x as f32, p.y as f32, p.z as f32]);
    }
    let mut triangles = Vec::with_capacity(4 * table.face_count());
    let (v, m) = (table.vertices(), &classes.edge_of);
    for t in 0..table.face_count() {
        let c = 3 * t;
        let [v0, v1, v2] = [v[c].0, v[c + 1].0, v[c + 2].0];
        let [m0, m1, m2] = [m[c], m[c + 1], m[c + 2]].map(|e| (n + e as usize) as u32);
        triangles.extend_from_slice(&[[v0, m2, m1], [m2, v1, m0], [m1, m0, v2], [m0, m1, m2]]);
    }
    let mut pairs = Vec::new();
    for (e, &f) in classes.flags.iter().enumerate() {
        if f & TAGGED != 0 {
            let c = classes.edge_corner[e];
            let mid = (n + e) as u32;
            pairs.push([classes.at(c.next()), mid]);
            pairs.push([classes.at(c.prev()), mid]);
        }
    }
    (TriMesh::new(positions, triangles), SharpEdges::new(pairs))
}

/// What the edge points are computed from.
struct Points<'a> {
    classes: &'a Classes<'a>,
    pos: &'a [[f32; 3]],
    /// E1/E2 points of the ends at fans larger than `cap`, by the corner
    /// of the end's vertex whose right edge is the edge; sorted.
    large: Vec<(u32, DVec3)>,
    cap: usize,
}

impl Points<'_> {
    #[inline]
    fn p(&self, v: u32) -> DVec3 {
        let [x, y, z] = self.pos[v as usize];
        DVec3::new(x as f64, y as f64, z as f64)
    }

    /// `Σ w·P` over a stencil whose vertices all exist; `None` if one is
    /// missing (never under the dispatch's conditions).
    fn combine(&self, verts: &[Option<u32>], weights: &[f64]) -> Option<DVec3> {
        let mut s = DVec3::ZERO;
        for (v, &w) in verts.iter().zip(weights) {
            s += self.p((*v)?) * w;
        }
        Some(s)
    }

    /// The new point of edge `e`.
    fn edge_point(&self, e: usize, buf_v: &mut [u32], buf_w: &mut [u32]) -> DVec3 {
        let cl = self.classes;
        let c = cl.edge_corner[e];
        let (v, w) = (cl.at(c.next()), cl.at(c.prev()));
        if cl.flags[e] & HARD != 0 {
            return self.sharp_point(v, w);
        }
        // Not hard, so interior: the opposite corner exists. The corners
        // of V and W whose right edge is V–W:
        let o = cl.table.opposite(c);
        let (xv, xw) = (c.next(), o.next());
        let end_v = cl.end(xv, self.cap, buf_v);
        let end_w = cl.end(xw, self.cap, buf_w);
        let found = match (end_v.is_regular(), end_w.is_regular()) {
            (true, true) => self.regular(c, o, end_v, end_w),
            (false, true) => self.irregular(xv, end_v, buf_v),
            (true, false) => self.irregular(xw, end_w, buf_w),
            (false, false) => self
                .irregular(xv, end_v, buf_v)
                .zip(self.irregular(xw, end_w, buf_w))
                .map(|(a, b)| 0.5 * (a + b)),
        };
        found.unwrap_or_else(|| {
            debug_assert!(false, "stencil of edge {e} incomplete");
            0.5 * (self.p(v) + self.p(w))
        })
    }

    /// R2, R6 or the midpoint for a hard edge V–W (§8.4.1.1).
    fn sharp_point(&self, v: u32, w: u32) -> DVec3 {
        let cl = self.classes;
        let (pv, pw) = (self.p(v), self.p(w));
        let r2 = |v2: DVec3, w2: DVec3| {
            let k = stencil::r2();
            k[0] * v2 + k[1] * pv + k[2] * pw + k[3] * w2
        };
        match (cl.chain_next(v, w), cl.chain_next(w, v)) {
            (Some(v2), Some(w2)) => r2(self.p(v2), self.p(w2)),
            (None, Some(w2)) => {
                let w2 = self.p(w2);
                stencil::r6_mirror(pv, pw, w2).map_or(0.5 * (pv + pw), |v2| r2(v2, w2))
            }
            (Some(v2), None) => {
                let v2 = self.p(v2);
                stencil::r6_mirror(pw, pv, v2).map_or(0.5 * (pv + pw), |w2| r2(v2, w2))
            }
            (None, None) => 0.5 * (pv + pw),
        }
    }

    /// R1, R3, R4 or R5, both ends regular. `c` is the edge's corner (V =
    /// `V[n(c)]`, W = `V[p(c)]`, wing A = `V[c]`), `o` its opposite (wing B).
    fn regular(&self, c: CornerId, o: CornerId, end_v: End, end_w: End) -> Option<DVec3> {
        let cl = self.classes;
        let at = |x: CornerId| Some(cl.at(x));
        match (end_v, end_w) {
            (End::Smooth { .. }, End::Smooth { .. }) => {
                let verts = [
                    at(c.next()),
                    at(c.prev()),
                    at(c),
                    at(o),
                    cl.across(c.prev()),
                    cl.across(c.next()),
                    cl.across(o.next()),
                    cl.across(o.prev()),
                ];
                self.combine(&verts, &stencil::r1())
            }
            (End::Sector { .. }, End::Smooth { .. }) => self.r4(c, o),
            (End::Smooth { .. }, End::Sector { .. }) => self.r4(o, c),
            _ => {
                let ear = |x: CornerId| cl.hard_facing(x.next()) && cl.hard_facing(x.prev());
                // R5 names the ear A, the other wing B, and the vertices
                // across V–B and W–B.
                let verts = if ear(c) {
                    [
                        at(c.next()),
                        at(c.prev()),
                        at(c),
                        at(o),
                        cl.across(o.next()),
                        cl.across(o.prev()),
                    ]
                } else if ear(o) {
                    [
                        at(c.next()),
                        at(c.prev()),
                        at(o),
                        at(c),
                        cl.across(c.prev()),
                        cl.across(c.next()),
                    ]
                } else {
                    return self.combine(&[at(c.next()), at(c.prev())], &stencil::r3());
                };
                self.combine(&verts, &stencil::r5())
            }
        }
    }

    /// R4 with V = `V[n(c)]` the crease end and W = `V[p(c)]` the smooth one.
    fn r4(&self, c: CornerId, o: CornerId) -> Option<DVec3> {
        let cl = self.classes;
        let at = |x: CornerId| Some(cl.at(x));
        // A is the wing on V's crease: V[c] if V–V[c] (facing p(c)) is
        // hard, else V[o]. C1 is across W–A, C2 across V–B, C3 across W–B.
        let verts = if cl.hard_facing(c.prev()) {
            [
                at(c.next()),
                at(c.prev()),
                at(c),
                at(o),
                cl.across(c.next()),
                cl.across(o.next()),
                cl.across(o.prev()),
            ]
        } else {
            [
                at(c.next()),
                at(c.prev()),
                at(o),
                at(c),
                cl.across(o.prev()),
                cl.across(c.prev()),
                cl.across(c.next()),
            ]
        };
        self.combine(&verts, &stencil::r4())
    }

    /// E1 or E2 at the end V = `V[x]` of the edge V–R(x).
    fn irregular(&self, x: CornerId, end: End, sector: &[u32]) -> Option<DVec3> {
        let cl = self.classes;
        let v = cl.at(x);
        match end {
            End::Smooth { valence } if valence <= self.cap => {
                // s_0 = W = R(x), then round V; an interior vertex's fan
                // is closed, so every swing exists.
                let mut s = self.p(v) * stencil::e1_center(valence);
                let mut y = x;
                for j in 0..valence {
                    s += self.p(cl.at(y.next())) * stencil::e1(valence, j);
                    y = cl.table.swing_left(y);
                }
                Some(s)
            }
            End::Sector { k, i } => {
                let s = self.p(v) * stencil::e2_center(k, i);
                Some(
                    sector[..=k]
                        .iter()
                        .enumerate()
                        .fold(s, |s, (j, &u)| s + self.p(u) * stencil::e2(k, i, j)),
                )
            }
            End::Smooth { .. } | End::LargeSector => self
                .large
                .binary_search_by_key(&x.0, |l| l.0)
                .ok()
                .map(|i| self.large[i].1),
        }
    }
}

/// E1 and E2 points for the ends at fans of more than `cap` triangles,
/// keyed by the corner of the end's vertex whose right edge is the edge,
/// sorted by corner: O(fan) per fan instead of O(fan²).
fn large_fans(cl: &Classes, pos: &[[f32; 3]], cap: usize) -> Vec<(u32, DVec3)> {
    let p = |v: u32| {
        let [x, y, z] = pos[v as usize];
        DVec3::new(x as f64, y as f64, z as f64)
    };
    let mut out = Vec::new();
    let (mut corners, mut pts, mut res) = (Vec::new(), Vec::new(), Vec::new());
    for (v, &faces) in cl.faces.iter().enumerate() {
        if faces as usize <= cap {
            continue;
        }
        let v = v as u32;
        corners.clear();
        cl.for_each_corner(v, |x| corners.push(x));
        if cl.is_smooth(v) {
            // The whole ring, ring[m] = R(x_m): edge V–ring[m] is the
            // right edge of x_m.
            pts.clear();
            pts.extend(corners.iter().map(|&x| p(cl.at(x.next()))));
            res.clear();
            res.resize(pts.len(), DVec3::ZERO);
            stencil::e1_all(p(v), &pts, &mut res);
            out.extend(corners.iter().zip(&res).map(|(x, &r)| (x.0, r)));
            continue;
        }
        // Sectors: the corners from one whose right edge is hard to the
        // next whose left edge is (for_each_corner starts at the former).
        let mut start = 0;
        for end in 0..corners.len() {
            if !cl.hard_facing(corners[end].next()) {
                continue;
            }
            let sector = &corners[start..=end];
            start = end + 1;
            let k = sector.len();
            if k <= cap {
                continue;
            }
            // s_0 = R(f_1), s_j = L(f_j); the inner edge V–s_i is the
            // right edge of f_{i+1} = sector[i].
            pts.clear();
            pts.push(p(cl.at(sector[0].next())));
            pts.extend(sector.iter().map(|&x| p(cl.at(x.prev()))));
            res.clear();
            res.resize(pts.len(), DVec3::ZERO);
            stencil::e2_all(p(v), &pts, &mut res);
            out.extend((1..k).map(|i| (sector[i].0, res[i])));
        }
    }
    out.sort_unstable_by_key(|l| l.0);
    out
}
