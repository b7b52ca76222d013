//! One gate of the retiling front (thesis §7.3 "To build the other
//! triangles of M′"; design notes §6 step 6): the candidate tip on the
//! circle, the snap that decides the label, the triangle's paths and
//! triangloid (both laid by `triangle`), and the fallbacks this
//! implementation adds where the thesis's rules leave a gate without a
//! valid triangle.
//!
//! Order of the choices at a gate, first that builds a valid triangle:
//! 1. an ear: a loop neighbour at under [`EAR_ANGLE`] from the gate;
//! 2. the thesis's snap: the nearest border vertex within `SNAP`·L of V
//!    (along M), or a C at V when there is none;
//! 3. a forced snap: up to [`SNAP_TRIES`] border vertices within
//!    [`FORCED_SNAP`]·L of V, nearest first (the thesis snaps without a
//!    limit when V fell in a claimed triangloid);
//! 4. the same around the gate's own crossing, when the circle missed;
//! 5. the gate's loop neighbours, strictly, then allowing folds and
//!    edges up to twice [`MAX_EDGE`];
//! 6. on a piece's last start only (`RetileOptions::last_resort`), the
//!    same with [`SLACK`] times longer edges and larger triangloids.
//!
//! "Strictly" means: no new edge longer than [`MAX_EDGE`]·L, no triangle
//! folded (normals over 120° apart) onto a neighbour, and no L or R that
//! leaves a loop of three whose E would fold.

use super::front::Place;
use super::snap;
use super::state::{Gate, Retiler};
use super::surface::NONE;
use super::walk::Plane;
use super::Failure;
use crate::edgebreaker::Symbol;
use crate::swing::{gate_level, level_ratio, quantize, stretch_apply, stretch_code, Frame};
use glam::DVec3;

/// The thesis's snap radius, in L (surface distance from the candidate).
pub(super) const SNAP: f64 = 0.5;
/// Angles (degrees) below which a loop neighbour closes the gate as an
/// ear; measured on horse: 90° gives 85% valence-6 vertices against 73%
/// without ears, and fewer failed runs; above 90° runs fail far more.
pub(super) const EAR_ANGLE: f64 = 90.0;
/// The longest edge a snap may create, in L.
pub(super) const MAX_EDGE: f64 = 2.0;
/// Border vertices tried as a forced snap before a gate fails.
pub(super) const SNAP_TRIES: usize = 6;
/// The last resort at a gate that no other choice closes: a loop
/// neighbour with new edges up to `SLACK` times the relaxed limit and a
/// triangloid up to `SLACK²` times [`MAX_REGION_AREA`](super::triangle::MAX_REGION_AREA). Measured on horse
/// at 1 b/v: of the gates that failed a run, the refusals were "edge too
/// long" (43%) and "triangloid too large" (28%) far more often than a
/// path or a region that could not be built; a failed run costs a whole
/// new run from another start, a large triangle costs a little error
/// where it lies.
pub(super) const SLACK: f64 = 2.0;
/// How far (in L) a forced snap looks. The thesis sets no limit; a border
/// vertex this far from the tip could not make a usable triangle anyway.
pub(super) const FORCED_SNAP: f64 = 3.0;

impl Retiler<'_> {
    /// One gate: tip, snap, label, paths, triangloid, loops.
    pub(super) fn step(
        &mut self,
        gr: u32,
        tip: u32,
    ) -> Result<(Option<Gate>, Option<Gate>), Failure> {
        let id = self.triangles.len() as u32;
        let gl = self.front.next(gr);
        let (vl, vr) = (self.front.vertex(gl), self.front.vertex(gr));
        let (xl, xr) = (self.xhat[vl as usize], self.xhat[vr as usize]);
        self.set_level(vl, vr);
        let centre = (xl + xr) * 0.5;
        let plane = Plane {
            origin: centre,
            normal: xr - xl,
        };
        let t = self.xhat[tip as usize];
        let (hits, crossing) = self.circle(vl, vr, plane, centre);
        let crossing_face = crossing.map(|(c, p)| (super::surface::face(c), p));
        // The thesis keeps the hit farther from the previous tip T. After
        // snaps T can sit beside the gate rather than behind it, so the
        // side is first judged by the surface itself: the free side of
        // GR → GL is on its right, seen along the normal of M.
        let free_side =
            |(p, f): (DVec3, u32)| (p - centre).dot((xl - xr).cross(self.s.normal(f))) > 0.0;
        let sides = hits.map(|h| h.map(free_side));
        let tip_point = match (hits, sides) {
            ([Some(a), _], [Some(true), Some(false) | None]) => Some(a),
            ([_, Some(b)], [Some(false) | None, Some(true)]) => Some(b),
            _ => hits
                .into_iter()
                .flatten()
                .max_by(|a, b| a.0.distance_squared(t).total_cmp(&b.0.distance_squared(t))),
        };
        // A crease crossing the plane near the circle takes the tip
        // (`crease`): it is then on the crease, off the circle.
        let on_crease = match (tip_point, crossing) {
            (Some((v, _)), Some(c)) if self.creases => self.crease_tip(plane, centre, c, v),
            _ => None,
        };
        let crease = on_crease.is_some();
        if let Some((v, f)) = on_crease.or(tip_point) {
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
                let near = self.snap(gr, f, v, SNAP * self.l, 1);
                if let Some(&w) = near.first() {
                    if let Some(out) = self.try_snap((gr, tip), w, id, true) {
                        return Ok(out);
                    }
                } else if let Some(gate) = self.try_c(gr, gl, tip, (v, f), crease, id) {
                    return Ok((Some(gate), None));
                }
            }
            // V is claimed already, or no triangloid of this gate can reach
            // it (it lies in another free disk): the thesis's snap without
            // a limit, to the nearest border vertex that gives a valid
            // triangle.
            for w in self.snap(gr, f, v, FORCED_SNAP * self.l, SNAP_TRIES) {
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
        if let Some((f, p)) = crossing_face {
            for w in self.snap(gr, f, p, FORCED_SNAP * self.l, SNAP_TRIES) {
                if let Some(out) = self.try_snap((gr, tip), w, id, true) {
                    return Ok(out);
                }
            }
        }
        // The neighbour whose new edge is shorter first; strict, then
        // allowing folds and edges up to twice as long, and last with
        // [`SLACK`] times longer edges and larger triangloids.
        let mut near: Vec<(f64, u32)> = [(self.front.next(gl), xr), (self.front.prev(gr), xl)]
            .into_iter()
            .map(|(n, other)| (self.xhat[self.front.vertex(n) as usize].distance(other), n))
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        let tiers: &[(bool, f64)] = if self.last_resort {
            &[(true, 1.0), (false, 1.0), (false, SLACK)]
        } else {
            &[(true, 1.0), (false, 1.0)]
        };
        for &(strict, slack) in tiers {
            self.slack = slack;
            for &(_, n) in &near {
                let w = self.front.vertex(n);
                if w != vl && w != vr {
                    if let Some(out) = self.try_snap((gr, tip), w, id, strict) {
                        self.slack = 1.0;
                        return Ok(out);
                    }
                }
            }
        }
        self.slack = 1.0;
        Err(Failure::NoTip { triangle: id })
    }

    /// The level of the gate GL = `vl`, GR = `vr` (`swing::density`):
    /// the mean of its vertices' levels rounded down, stepped towards the
    /// density's target when it adapts; sets the edge length and tip
    /// radius of this gate's triangle.
    fn set_level(&mut self, vl: u32, vr: u32) {
        let gate = gate_level(self.level[vl as usize], self.level[vr as usize]);
        let (ml, mr) = (self.msample[vl as usize], self.msample[vr as usize]);
        let d = match &mut self.density {
            Some(field) => field.step(&self.s, gate, ml, mr),
            None => 0,
        };
        let level = gate + d;
        self.tip_step = (d, level);
        let ratio = level_ratio(level);
        self.l = self.l0 * ratio;
        self.radius = self.radius0 * ratio;
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

    /// Up to `count` border vertices of the loop of gate `gr` within
    /// `limit` of point `v` of face `f` along M, nearest first, other than
    /// the gate's own two. Only this loop on a genus-0 surface, where
    /// another loop bounds a separate free disk reachable only across
    /// claimed triangloids; any loop when M has handles (an S\*).
    fn snap(&mut self, gr: u32, f: u32, v: DVec3, limit: f64, count: usize) -> Vec<u32> {
        let front = &self.front;
        let (lp, vl, vr) = (
            front.loop_of(gr),
            front.vertex(front.next(gr)),
            front.vertex(gr),
        );
        let handles = self.handles;
        snap::nearest(&self.s, f, v, limit, count, &mut self.scratch, |m| {
            m != vl && m != vr && (front.is_on(m, lp) || (handles && front.is_active(m)))
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
        let (symbol, wn, merge) = match self.front.place(gr, w) {
            Place::Loop(symbol, wn) => (symbol, wn, false),
            Place::Other(wn) if self.handles => (Symbol::S, wn, true),
            _ => return None,
        };
        // An S that leaves a pocket of one vertex (W two steps from the
        // gate along the loop) would close it at once with an E folded
        // back over the S: take that vertex first, as an R or an L.
        if symbol == Symbol::S && !merge {
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
        let max_edge = if strict { MAX_EDGE } else { 2.0 * MAX_EDGE } * self.slack;
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
        let (next, push) = if merge {
            let (next, push) = self.front.apply_merge(gr, wn);
            (Some(next), Some(push))
        } else {
            self.front.apply(gr, symbol, wn)
        };
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

    /// A C: quantize the dihedral angle of V (moved by its curvature
    /// offset when tips approximate) and continue from X̂. A tip on a
    /// `crease` keeps V itself: its radius code puts it at V's distance
    /// from the gate, and neither offset nor fit moves it off the crease.
    /// `None` when V cannot anchor a triangloid of this gate.
    fn try_c(
        &mut self,
        gr: u32,
        gl: u32,
        tip: u32,
        (v, f): (DVec3, u32),
        crease: bool,
        id: u32,
    ) -> Option<Gate> {
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
        let aim = if self.approximate && !crease {
            v + super::offset::offset(&self.s, f, v, self.l, &mut self.offsets)
        } else {
            v
        };
        let bits = self.table.bits();
        let q = quantize(bits, frame.angle(aim.to_array()));
        // The radius code of a crease tip (V lies in the gate's plane:
        // its distance from m, in steps of 2^(3−K)·r), and the frame the
        // decoder builds with it (the radius enters `Frame::new`'s
        // degenerate-gate test).
        let j = if crease {
            let m = DVec3::from_array(frame.m);
            stretch_code(bits, v.distance(m) / self.radius - 1.0)
        } else {
            0
        };
        let frame = if j == 0 {
            frame
        } else {
            Frame::new(
                self.xhat[vl as usize].to_array(),
                self.xhat[vr as usize].to_array(),
                self.xhat[tip as usize].to_array(),
                stretch_apply(bits, self.radius, j),
            )
        };
        let xhat = DVec3::from_array(frame.point(&self.table, q));
        let x = self.add_vertex(xhat, m);
        if !self.attempt([x, vl, vr], &[(x, vl), (vr, x)], id) {
            self.pop_vertex();
            return None;
        }
        // The region is claimed: the code can now be chosen by how well
        // the triangle covers it (`fit`).
        let q = if self.fit && !crease {
            let fitted = self.fit_code(&frame, q, vl, vr);
            self.xhat[x as usize] = DVec3::from_array(frame.point(&self.table, fitted));
            fitted
        } else {
            q
        };
        self.push_triangle([x, vl, vr]);
        self.symbols.push(Symbol::C);
        self.codes.push(q);
        self.steps.push(self.tip_step.0);
        self.stretch.push(j);
        Some((self.front.apply_c(gr, x), vl))
    }
}
