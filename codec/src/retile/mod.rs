//! The SwingWrapper retiler (Attene, Falcidieno, Spagnuolo, Rossignac,
//! "SwingWrapper: retiling triangle meshes for better Edgebreaker
//! compression", ACM TOG 2003; thesis chapter 7; design notes §6).
//!
//! M′ grows from a first triangle in Edgebreaker order, right branch
//! first. For every gate (GL, GR) with previous tip T the candidate tip V
//! is where the circle of radius L√3/2 in the gate's bisecting plane
//! meets M, on the side farther from T. V snaps to a border vertex W
//! within L/2 along the surface (always, if V fell in a claimed
//! triangloid), which makes the triangle an L, R, E or S; otherwise it is
//! a C and V's dihedral angle is quantized. Each M′ triangle claims the
//! region of M bounded by three approximate geodesics (its triangloid).
//!
//! Invariants:
//! * tips are built from *decoded* positions X̂ only (the Frame of
//!   `swing::angle`, shared with the decoder), so `Retiled::positions` is
//!   what the decoder rebuilds, bit for bit; the on-surface sample V of a
//!   C only anchors its paths;
//! * triangloids are disjoint disks of M bounded by path edges, and at
//!   the end they cover M: M′ is then a closed manifold of M's topology;
//! * the CLERS string recorded here is the one Edgebreaker produces on M′
//!   from its first corner (checked by the writer);
//! * any failure abandons the run (thesis: "the validity check may fail
//!   for an excessive desired edge length L"); rate control then searches
//!   a smaller L.
//!
//! All searches move by adjacency on M (`walk`, `path`, `snap`,
//! `region`); there is no spatial index, so self-intersecting input
//! cannot confuse them.

mod front;
mod path;
pub mod rate;
mod region;
mod snap;
mod surface;
mod walk;

#[cfg(test)]
mod tests;

use crate::edgebreaker::Symbol;
use crate::swing::Retiled;
use crate::swing::{first_edge_length, quantize, tip_radius, AngleTable, Frame};
use crate::{CornerTable, TriMesh};
use front::{Front, Place};
use glam::DVec3;
use std::collections::HashMap;
use surface::{Surface, NONE};
use walk::{leave_vertex, walk_to_radius, Plane, Walker};

/// Options of one retiling run.
#[derive(Clone, Debug, PartialEq)]
pub struct RetileOptions {
    /// Target edge length L, in the mesh's units. No default.
    pub edge_length: f64,
    /// Bits per dihedral angle (K). Default 8.
    pub angle_bits: u8,
    /// The input vertex p1 grows from. Default (`None`): the vertex whose
    /// ring is flattest, so the first triangles never sit on a thin tip.
    pub start_vertex: Option<u32>,
    /// With no `start_vertex`: take the `start_rank`-th flattest vertex
    /// (0 = the flattest). A run that failed is an independent new trial
    /// from another start. Default 0.
    pub start_rank: u32,
}

pub use crate::error::RetileFailure as Failure;

/// Retiles a closed, oriented manifold (a `clean` result whose table has
/// no boundary). Deterministic: same input, same output.
pub fn retile(
    mesh: &TriMesh,
    table: &CornerTable,
    opt: &RetileOptions,
) -> Result<Retiled, Failure> {
    if mesh.face_count() == 0
        || !(opt.edge_length.is_finite() && opt.edge_length > 0.0)
        || opt
            .start_vertex
            .is_some_and(|v| v as usize >= mesh.vertex_count())
    {
        return Err(Failure::BadInput);
    }
    let positions: Vec<DVec3> = mesh
        .positions
        .iter()
        .map(|p| p.map(f64::from).into())
        .collect();
    let opposites: Vec<u32> = table.opposites().iter().map(|c| c.0).collect();
    let s = Surface::new(&positions, &mesh.triangles, &opposites);
    let area = mesh.area();
    let tri_area = opt.edge_length * opt.edge_length * 3f64.sqrt() / 4.0;
    let cap = (8.0 * area / tri_area) as usize + 64;
    let mut r = Retiler {
        s,
        table: AngleTable::new(opt.angle_bits),
        l: opt.edge_length,
        radius: 0.0,
        xhat: Vec::new(),
        msample: Vec::new(),
        adj: Vec::new(),
        paths: HashMap::new(),
        front: Front::default(),
        triangles: Vec::new(),
        half_edges: HashMap::new(),
        symbols: Vec::new(),
        codes: Vec::new(),
        scratch: path::Scratch::default(),
        flood: region::Flood::default(),
        cap,
    };
    let start = opt
        .start_vertex
        .unwrap_or_else(|| flattest_vertex(&r.s, opt.start_rank));
    let (first_gate, first) = r.first_triangle(start)?;
    r.grow(first_gate)?;
    let uncovered = r.s.owner.iter().filter(|&&o| o == NONE).count();
    if uncovered > 0 {
        return Err(Failure::Uncovered {
            faces: uncovered as u32,
        });
    }
    Ok(Retiled {
        angle_bits: opt.angle_bits,
        first,
        triangles: r.triangles,
        positions: r.xhat.iter().map(|p| p.to_array()).collect(),
        symbols: r.symbols,
        codes: r.codes,
        edge_length: r.l,
    })
}

fn f32_exact(p: DVec3) -> DVec3 {
    p.as_vec3().as_dvec3()
}

/// A gate to process: the node of GR (GL follows it) and the previous tip.
type Gate = (u32, u32);

struct Retiler {
    s: Surface,
    table: AngleTable,
    l: f64,
    radius: f64,
    /// Per M′ vertex: decoded position.
    xhat: Vec<DVec3>,
    /// Per M′ vertex: the vertex of M where its paths meet.
    msample: Vec<u32>,
    /// Per M′ vertex: its neighbours in M′.
    adj: Vec<Vec<u32>>,
    /// Per M′ edge (low id, high id): its path in M, from low to high.
    paths: HashMap<(u32, u32), Vec<u32>>,
    front: Front,
    triangles: Vec<[u32; 3]>,
    /// Directed edge (a, b) of M′ to the triangle holding it CCW.
    half_edges: HashMap<(u32, u32), u32>,
    symbols: Vec<Symbol>,
    codes: Vec<u32>,
    scratch: path::Scratch,
    flood: region::Flood,
    cap: usize,
}

/// The thesis's snap radius, in L (surface distance from the candidate).
const SNAP: f64 = 0.5;
/// Angles (degrees) below which a loop neighbour closes the gate as an
/// ear; measured on horse: 90° gives 85% valence-6 vertices against 73%
/// without ears, and fewer failed runs; above 90° runs fail far more.
const EAR_ANGLE: f64 = 90.0;
/// The longest edge a snap may create, in L.
const MAX_EDGE: f64 = 2.0;
/// The largest triangloid, in L² (an equilateral triangle is 0.43 L²).
const MAX_REGION_AREA: f64 = 3.0;
/// Border vertices tried as a forced snap before a gate fails.
const SNAP_TRIES: usize = 6;
/// How far (in L) a forced snap looks. The thesis sets no limit; a border
/// vertex this far from the tip could not make a usable triangle anyway.
const FORCED_SNAP: f64 = 3.0;

impl Retiler {
    fn add_vertex(&mut self, xhat: DVec3, m: u32) -> u32 {
        let id = self.xhat.len() as u32;
        self.xhat.push(xhat);
        self.msample.push(m);
        self.adj.push(Vec::new());
        if m != NONE {
            self.s.sample[m as usize] = id;
        }
        id
    }

    fn push_triangle(&mut self, t: [u32; 3]) {
        let id = self.triangles.len() as u32;
        for k in 0..3 {
            self.half_edges.insert((t[k], t[(k + 1) % 3]), id);
        }
        self.triangles.push(t);
    }

    fn normal(&self, t: [u32; 3]) -> DVec3 {
        let [a, b, c] = t.map(|v| self.xhat[v as usize]);
        (b - a).cross(c - a)
    }

    /// Triangle `t` (CCW) would fold back (normals over 120° apart) onto
    /// an existing triangle across one of its edges.
    fn folds(&self, t: [u32; 3]) -> bool {
        let n = self.normal(t);
        (0..3).any(|k| {
            self.half_edges
                .get(&(t[(k + 1) % 3], t[k]))
                .is_some_and(|&u| {
                    let m = self.normal(self.triangles[u as usize]);
                    n.dot(m) < -0.5 * n.length() * m.length()
                })
        })
    }

    /// Undoes the last `add_vertex`.
    fn pop_vertex(&mut self) {
        if let Some(m) = self.msample.pop() {
            if m != NONE {
                self.s.sample[m as usize] = NONE;
            }
        }
        self.xhat.pop();
        self.adj.pop();
    }

    /// The path of M′ edge a–b, from a to b.
    fn chain(&self, a: u32, b: u32) -> Vec<u32> {
        let mut c = self.paths[&(a.min(b), a.max(b))].clone();
        if a > b {
            c.reverse();
        }
        c
    }

    /// Builds triangle `tri` = (tip, GL, GR) as M′ triangle `id`: traces
    /// the paths of its `new` edges, then claims its triangloid. On any
    /// failure everything it marked is undone and `false` returned (splits
    /// of M stay: they change no triangloid).
    fn attempt(&mut self, tri: [u32; 3], new: &[(u32, u32)], id: u32) -> bool {
        let mut made: Vec<(u32, u32)> = Vec::new();
        let mut ok = true;
        for &(a, b) in new {
            let (ma, mb) = (self.msample[a as usize], self.msample[b as usize]);
            let chain = path::find(&self.s, ma, mb, &mut self.scratch)
                .and_then(|pts| path::insert(&mut self.s, &pts));
            let Some(mut chain) = chain else {
                ok = false;
                break;
            };
            if chain[0] != self.msample[a.min(b) as usize] {
                chain.reverse();
            }
            self.paths.insert((a.min(b), a.max(b)), chain);
            made.push((a, b));
        }
        if ok {
            let mut boundary = Vec::new();
            for (a, b) in [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])] {
                let c = self.chain(a, b);
                boundary.extend_from_slice(&c[..c.len() - 1]);
            }
            let max_area = MAX_REGION_AREA * self.l * self.l;
            match region::claim(&mut self.s, &boundary, id, max_area, &mut self.flood) {
                Ok(_) => {
                    for &(a, b) in &made {
                        self.adj[a as usize].push(b);
                        self.adj[b as usize].push(a);
                    }
                    return true;
                }
                Err(_) => region::release(&mut self.s, id, &mut self.flood),
            }
        }
        for (a, b) in made {
            let chain = self.paths.remove(&(a.min(b), a.max(b))).unwrap_or_default();
            path::unmark(&mut self.s, &chain);
        }
        false
    }

    /// p1, p2, p3 and the first triangloid (design notes §6 steps 2–5).
    /// Returns the first gate and the explicit vertices (p1, p3, p2).
    fn first_triangle(&mut self, p1: u32) -> Result<(Gate, [[f64; 3]; 3]), Failure> {
        let s = &self.s;
        let c1 = s.pos[p1 as usize];
        let n1 = s.vertex_normal(p1);
        let tangent = least_parallel_axis(n1);
        let tangent = (tangent - n1 * tangent.dot(n1)).normalize_or_zero();
        let plane = Plane {
            origin: c1,
            normal: n1.cross(tangent),
        };
        let (k, _) = leave_vertex(s, &plane, p1)
            .into_iter()
            .filter(|&(_, x)| (x - c1).dot(tangent) > 0.0)
            .max_by(|a, b| (a.1 - c1).dot(tangent).total_cmp(&(b.1 - c1).dot(tangent)))
            .ok_or(Failure::NoSecondVertex)?;
        let mut w = Walker::across(s, plane, k, s.face_count());
        let (p2, f2) =
            walk_to_radius(&mut w, c1, c1, self.l, 4.0 * self.l).ok_or(Failure::NoSecondVertex)?;
        let (x1, x2) = (f32_exact(c1), f32_exact(p2));
        // The decoder's L: the distance of the explicit p1 and p2.
        self.l = first_edge_length(&[x1.to_array(), DVec3::ZERO.to_array(), x2.to_array()]);
        self.radius = tip_radius(self.l);
        let snap = 1e-9 * self.l;
        let m2 = self
            .s
            .insert_point(f2, p2, snap)
            .ok_or(Failure::NoSecondVertex)?;
        if m2 == p1 {
            return Err(Failure::NoSecondVertex);
        }
        // Ids: p1 = 0, p3 = 1, p2 = 2 (p3 is filled in below).
        self.add_vertex(x1, p1);
        let id3 = self.add_vertex(DVec3::ZERO, NONE_PLACEHOLDER);
        self.add_vertex(x2, m2);
        let first_path = path::find(&self.s, p1, m2, &mut self.scratch)
            .and_then(|pts| path::insert(&mut self.s, &pts))
            .ok_or(Failure::NoSecondVertex)?;
        self.paths.insert((0, 2), first_path);
        // p3: on the circle of edge p1p2, the side that makes (p1, p3, p2)
        // counterclockwise seen from outside.
        let centre = (x1 + x2) * 0.5;
        let plane = Plane {
            origin: centre,
            normal: x2 - x1,
        };
        let (cands, _) = self.circle(0, 2, plane, centre);
        let orient = |p: DVec3, f: u32| (p - x1).cross(x2 - x1).dot(self.s.normal[f as usize]);
        let (p3, f3) = cands
            .into_iter()
            .flatten()
            .max_by(|a, b| orient(a.0, a.1).total_cmp(&orient(b.0, b.1)))
            .ok_or(Failure::NoThirdVertex)?;
        let m3 = self
            .s
            .insert_point(f3, p3, snap)
            .ok_or(Failure::NoThirdVertex)?;
        let x3 = f32_exact(p3);
        self.xhat[id3 as usize] = x3;
        self.msample[id3 as usize] = m3;
        self.s.sample[m3 as usize] = id3;
        self.adj[0].push(2);
        self.adj[2].push(0);
        if !self.attempt([0, 1, 2], &[(0, 1), (1, 2)], 0) {
            return Err(Failure::NoThirdVertex);
        }
        self.push_triangle([0, 1, 2]);
        let nodes = self.front.start(&[0, 1, 2]);
        // First gate: GR = p2, GL = p1, previous tip p3.
        Ok(((nodes[2], 1), [x1, x3, x2].map(|p| p.to_array())))
    }

    /// Where the circle of radius L√3/2 around the midpoint of edge a–b,
    /// in `plane`, meets M: walking both ways from the crossing of the
    /// edge's path with the plane. Also returns that crossing (a face and
    /// the point), or `None` if the path does not cross the plane.
    #[allow(clippy::type_complexity)]
    fn circle(
        &self,
        a: u32,
        b: u32,
        plane: Plane,
        centre: DVec3,
    ) -> ([Option<(DVec3, u32)>; 2], Option<(u32, DVec3)>) {
        let chain = self.chain(a, b);
        let s = &self.s;
        // The path may cross the bisecting plane more than once; start
        // from the crossing nearest the circle's centre.
        let crossing = chain
            .windows(2)
            .filter(|w| {
                plane.positive(s.pos[w[0] as usize]) != plane.positive(s.pos[w[1] as usize])
            })
            .filter_map(|w| s.edge(w[0], w[1]))
            .map(|c| (c, plane.crossing(s, c).1))
            .min_by(|a, b| {
                a.1.distance_squared(centre)
                    .total_cmp(&b.1.distance_squared(centre))
            });
        let Some((c, start)) = crossing else {
            return ([None, None], None);
        };
        let budget = s.face_count();
        let max_len = 6.0 * self.radius;
        let hits = [c, s.opp[c as usize]].map(|side| {
            let mut walker = Walker::across(s, plane, side, budget);
            walk_to_radius(&mut walker, start, centre, self.radius, max_len)
        });
        (hits, Some((surface::face(c), start)))
    }

    /// Processes gates in Edgebreaker order until every loop closed.
    fn grow(&mut self, first: Gate) -> Result<(), Failure> {
        let mut stack: Vec<Gate> = Vec::new();
        let mut gate = Some(first);
        while let Some((gr, tip)) = gate {
            if self.triangles.len() > self.cap {
                return Err(Failure::Runaway);
            }
            let (next, push) = self.step(gr, tip)?;
            if let Some(g) = push {
                stack.push(g);
            }
            gate = next.or_else(|| stack.pop());
        }
        Ok(())
    }

    /// One gate: tip, snap, label, paths, triangloid, loops.
    fn step(&mut self, gr: u32, tip: u32) -> Result<(Option<Gate>, Option<Gate>), Failure> {
        let id = self.triangles.len() as u32;
        let gl = self.front.next(gr);
        let (vl, vr) = (self.front.vertex(gl), self.front.vertex(gr));
        let (xl, xr) = (self.xhat[vl as usize], self.xhat[vr as usize]);
        let centre = (xl + xr) * 0.5;
        let plane = Plane {
            origin: centre,
            normal: xr - xl,
        };
        let t = self.xhat[tip as usize];
        let (hits, crossing) = self.circle(vl, vr, plane, centre);
        // The thesis keeps the hit farther from the previous tip T. After
        // snaps T can sit beside the gate rather than behind it, so the
        // side is first judged by the surface itself: the free side of
        // GR → GL is on its right, seen along the normal of M.
        let free_side = |(p, f): (DVec3, u32)| {
            (p - centre).dot((xl - xr).cross(self.s.normal[f as usize])) > 0.0
        };
        let sides = hits.map(|h| h.map(free_side));
        let tip_point = match (hits, sides) {
            ([Some(a), _], [Some(true), Some(false) | None]) => Some(a),
            ([_, Some(b)], [Some(false) | None, Some(true)]) => Some(b),
            _ => hits
                .into_iter()
                .flatten()
                .max_by(|a, b| a.0.distance_squared(t).total_cmp(&b.0.distance_squared(t))),
        };
        // Candidates: border vertices of this gate's own loop. On a genus-0
        // surface another loop bounds a separate free disk, reachable only
        // across claimed triangloids (handles are the next issue's S*).
        let lp = self.front.loop_of(gr);
        if let Some((v, f)) = tip_point {
            // Ears: a loop neighbour of the gate that makes a sharp angle
            // with it on the free side is closed at once (an R or an L).
            // The thesis's L/2 snap alone leaves such spikes, and the
            // pinched fronts they grow into end in folded triangles or in
            // gates with no valid triangle at all.
            if let Some(w) = self.ear(gr, v) {
                if let Some(out) = self.try_snap((gr, tip), w, id, true) {
                    return Ok(out);
                }
            }
            if self.s.owner[f as usize] == NONE {
                let near = self.snap(f, v, SNAP * self.l, lp, vl, vr, 1);
                if let Some(&w) = near.first() {
                    if let Some(out) = self.try_snap((gr, tip), w, id, true) {
                        return Ok(out);
                    }
                } else if let Some(gate) = self.try_c(gr, gl, tip, v, f, id) {
                    return Ok((Some(gate), None));
                }
            }
            // V is claimed already, or no triangloid of this gate can reach
            // it (it lies in another free disk): the thesis's snap without
            // a limit, to the nearest border vertex that gives a valid
            // triangle.
            for w in self.snap(f, v, FORCED_SNAP * self.l, lp, vl, vr, SNAP_TRIES) {
                if let Some(out) = self.try_snap((gr, tip), w, id, true) {
                    return Ok(out);
                }
            }
        }
        // No usable tip on the circle (the surface is thinner than the
        // circle here, or every nearby choice failed): close the front
        // with the border vertices nearest to the gate itself, and last
        // with the gate's loop neighbours (an L or an R always shortens
        // the loop where it is).
        if let Some((f, p)) = crossing {
            for w in self.snap(f, p, FORCED_SNAP * self.l, lp, vl, vr, SNAP_TRIES) {
                if let Some(out) = self.try_snap((gr, tip), w, id, true) {
                    return Ok(out);
                }
            }
        }
        // The neighbour whose new edge is shorter first; strict, then
        // allowing folds and edges up to twice as long.
        let mut near: Vec<(f64, u32)> = [(self.front.next(gl), xr), (self.front.prev(gr), xl)]
            .into_iter()
            .map(|(n, other)| (self.xhat[self.front.vertex(n) as usize].distance(other), n))
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        for strict in [true, false] {
            for &(_, n) in &near {
                let w = self.front.vertex(n);
                if w != vl && w != vr {
                    if let Some(out) = self.try_snap((gr, tip), w, id, strict) {
                        return Ok(out);
                    }
                }
            }
        }
        Err(Failure::NoTip { triangle: id })
    }

    /// The loop neighbour of gate `gr` (prev(GR) or next(GL)) whose angle
    /// with the gate, on the side of the candidate tip `v`, is below
    /// [`EAR_ANGLE`]; the sharper one if both are.
    fn ear(&self, gr: u32, v: DVec3) -> Option<u32> {
        let f = &self.front;
        let gl = f.next(gr);
        let x = |n: u32| self.xhat[f.vertex(n) as usize];
        let (xl, xr) = (x(gl), x(gr));
        let m = (xl + xr) * 0.5;
        let cos_limit = EAR_ANGLE.to_radians().cos();
        let mut best: Option<(f64, u32)> = None;
        for (apex, other, n) in [(xr, xl, f.prev(gr)), (xl, xr, f.next(gl))] {
            let w = f.vertex(n);
            if w == f.vertex(gl) || w == f.vertex(gr) {
                continue;
            }
            let (a, b) = (
                (other - apex).normalize_or_zero(),
                (x(n) - apex).normalize_or_zero(),
            );
            let cos = a.dot(b);
            let free_side = (x(n) - m).dot(v - m) > 0.0;
            if free_side && cos > cos_limit && best.is_none_or(|(c, _)| cos > c) {
                best = Some((cos, w));
            }
        }
        best.map(|(_, w)| w)
    }

    /// Up to `count` border vertices of loop `lp` within `limit` of V
    /// along M, nearest first, other than the gate's.
    #[allow(clippy::too_many_arguments)]
    fn snap(
        &mut self,
        f: u32,
        v: DVec3,
        limit: f64,
        lp: u32,
        vl: u32,
        vr: u32,
        count: usize,
    ) -> Vec<u32> {
        let front = &self.front;
        snap::nearest(&self.s, f, v, limit, count, &mut self.scratch, |m| {
            m != vl && m != vr && front.is_on(m, lp)
        })
    }

    /// The triangle (W, GL, GR) with W a border vertex of the gate's loop,
    /// labelled by where W sits; `None` if it cannot be built.
    fn try_snap(
        &mut self,
        (gr, tip): Gate,
        w: u32,
        id: u32,
        strict: bool,
    ) -> Option<(Option<Gate>, Option<Gate>)> {
        let gl = self.front.next(gr);
        let (vl, vr) = (self.front.vertex(gl), self.front.vertex(gr));
        let Place::Loop(symbol, wn) = self.front.place(gr, w) else {
            return None;
        };
        // An S that leaves a pocket of one vertex (W two steps from the
        // gate along the loop) would close it at once with an E folded
        // back over the S: take that vertex first, as an R or an L.
        if symbol == Symbol::S {
            let (before, after) = (self.front.prev(gr), self.front.next(gl));
            let pocket = if self.front.prev(before) == wn {
                Some(before)
            } else if self.front.next(after) == wn {
                Some(after)
            } else {
                None
            };
            if let Some(n) = pocket {
                let out = self.try_snap((gr, tip), self.front.vertex(n), id, strict);
                if out.is_some() {
                    return out;
                }
            }
        }
        let max_edge = if strict { MAX_EDGE } else { 2.0 * MAX_EDGE };
        // A triangle folded back onto a neighbour (normals more than 120°
        // apart) is a crease the surface does not have; so is the E that a
        // snap leaving a loop of three would force next.
        if strict && (self.folds([w, vl, vr]) || self.forced_e_folds(gr, symbol, wn)) {
            return None;
        }
        // A new edge that exists already, not along the loop, would make
        // M′ non-manifold.
        let has = |a: u32, b: u32| self.adj[a as usize].contains(&b);
        // A snap that makes an edge far longer than L starts a fan of
        // ever longer triangles (a corridor zipped from one apex): refuse
        // it, so the gate takes a C or a nearer border vertex instead.
        let long = |a: u32, b: u32| {
            self.xhat[a as usize].distance(self.xhat[b as usize]) > max_edge * self.l
        };
        let too_long = match symbol {
            Symbol::L => long(vr, w),
            Symbol::R => long(w, vl),
            Symbol::S => long(vr, w) || long(w, vl),
            _ => false,
        };
        if too_long {
            return None;
        }
        let new: &[(u32, u32)] = match symbol {
            Symbol::L if !has(vr, w) => &[(vr, w)],
            Symbol::R if !has(w, vl) => &[(w, vl)],
            Symbol::S if !has(vr, w) && !has(w, vl) => &[(w, vl), (vr, w)],
            Symbol::E => &[],
            _ => return None,
        };
        if !self.attempt([w, vl, vr], new, id) {
            return None;
        }
        self.push_triangle([w, vl, vr]);
        self.symbols.push(symbol);
        let (next, push) = self.front.apply(gr, symbol, wn);
        // After L and S the gate keeps GR and its previous tip is GL;
        // after R it keeps GL and the previous tip is GR.
        let next = next.map(|n| (n, if symbol == Symbol::R { vr } else { vl }));
        Some((next, push.map(|n| (n, vr))))
    }

    /// Whether applying `symbol` with tip node `wn` at gate `gr` leaves a
    /// loop of three whose closing E would fold.
    fn forced_e_folds(&self, gr: u32, symbol: Symbol, wn: u32) -> bool {
        let f = &self.front;
        let gl = f.next(gr);
        let v = |n: u32| f.vertex(n);
        // Each case: the three vertices (tip, GL, GR) of the E to come.
        // Loop GR → W → a → GR left by an L. (Checking the loops an S
        // leaves as well, or trying a C when a snap folds, was measured to
        // make runs fail far more often: the pinched fronts behind most
        // folds then have no valid triangle at all.)
        let right = symbol == Symbol::L && f.next(f.next(wn)) == gr;
        // Loop W → GL → b → W left by an R.
        let left = symbol == Symbol::R && f.next(f.next(gl)) == wn;
        (right && self.folds([v(f.next(wn)), v(wn), v(gr)]))
            || (left && self.folds([v(f.next(gl)), v(gl), v(wn)]))
    }

    /// A C: quantize V's dihedral angle and continue from X̂. `None` when
    /// V cannot anchor a triangloid of this gate.
    fn try_c(&mut self, gr: u32, gl: u32, tip: u32, v: DVec3, f: u32, id: u32) -> Option<Gate> {
        let (vl, vr) = (self.front.vertex(gl), self.front.vertex(gr));
        // Splitting M at V changes no triangloid, so it needs no undo.
        let m = self.s.insert_point(f, v, 1e-9 * self.l)?;
        if self.s.sample[m as usize] != NONE || self.s.on_path[m as usize] > 0 {
            return None;
        }
        let frame = Frame::new(
            self.xhat[vl as usize].to_array(),
            self.xhat[vr as usize].to_array(),
            self.xhat[tip as usize].to_array(),
            self.radius,
        );
        let q = quantize(self.table.bits(), frame.angle(v.to_array()));
        let xhat = DVec3::from_array(frame.point(&self.table, q));
        let x = self.add_vertex(xhat, m);
        if !self.attempt([x, vl, vr], &[(x, vl), (vr, x)], id) {
            self.pop_vertex();
            return None;
        }
        self.push_triangle([x, vl, vr]);
        self.symbols.push(Symbol::C);
        self.codes.push(q);
        Some((self.front.apply_c(gr, x), vl))
    }
}

/// Placeholder sample of p3 until it is found.
const NONE_PLACEHOLDER: u32 = NONE;

/// The `rank`-th vertex (0 = first) by how well its face normals agree
/// (largest |mean normal|), lowest id on ties. Only vertices with a ring
/// of at least five faces count, as a tip of three or four faces can be
/// flat and still thin.
fn flattest_vertex(s: &Surface, rank: u32) -> u32 {
    let mut scored: Vec<(f64, u32)> = (0..s.vertex_count() as u32)
        .filter(|&x| s.corner_of[x as usize] != NONE)
        .filter_map(|x| {
            let (mut sum, mut n) = (DVec3::ZERO, 0u32);
            for k in s.fan(x) {
                sum += s.normal[surface::face(k) as usize];
                n += 1;
            }
            (n >= 5).then(|| (sum.length() / n as f64, x))
        })
        .collect();
    // Flattest first, lowest id on ties.
    let order = |a: &(f64, u32), b: &(f64, u32)| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1));
    let k = (rank as usize).min(scored.len().saturating_sub(1));
    if scored.is_empty() {
        return 0;
    }
    scored.select_nth_unstable_by(k, order);
    scored[k].1
}

/// The coordinate axis least parallel to `n` (lowest index on ties).
fn least_parallel_axis(n: DVec3) -> DVec3 {
    let a = n.abs();
    if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    }
}
