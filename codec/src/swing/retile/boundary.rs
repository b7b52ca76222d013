//! Starting a retiling on a boundary loop (issue 20, open surfaces;
//! beyond the thesis, which retiles closed surfaces only; the file side
//! is `swing::chain`, section `LOOP`).
//!
//! A component with holes is closed by patches (`fill`) so that the
//! retiler can work on a closed surface. Started inside, the front
//! crosses every patch and covers it with triangles the decoder then
//! drops: on a sheet the patch is as large as the sheet. Started on the
//! longest loop instead, the retiling begins with a fan over that loop's
//! patch: b1 is a vertex of the loop, b0 the point of the loop at L from
//! it, and each further point is where the loop leaves the sphere of
//! radius ρ = |b0 − b1| around the decoded previous point, reached as a
//! C tip on gate (previous point, D) by two angle codes
//! (`chain::place`, `chain::aim`), until less than 1.5 ρ of the loop is
//! left; an R closes the fan on b1. M is split on the loop where a point
//! falls inside an edge. The fan claims the whole patch at once (one
//! region bounded by the loop's edges), so the front that remains is the
//! loop, and every later triangle lies on the input's own surface. The
//! fan's triangles are masked like a patch's (`mask`), with D they leave
//! exactly the loop as the decoded boundary.
//!
//! ```text
//!   chain order (against the patch faces' own direction):
//!     c0 = b1 → c1 = b0 → c2 = x1 → … → c(n−1) = x(n−2) → back to b1
//!   M′ ids: b0 = 0, b1 = 1, D = 2, x_k = 2 + k
//! ```
//!
//! Invariants: the loop points' positions are the decoder's
//! (`chain::place` on decoded positions only); the fan's paths are the
//! loop's own edges, so the claimed patch is exactly the hole; a loop that
//! touches itself (a pinched hole) is not used.

use super::path::{self, Point};
use super::region;
use super::state::{f32_exact, Gate, Retiler};
use super::surface::{face, next, prev, Surface, NONE};
use super::Failure;
use crate::edgebreaker::Symbol;
use crate::swing::chain;
use crate::swing::{first_edge_length, tip_radius};
use glam::DVec3;
use std::collections::HashMap;

/// A loop point that would fall this close (in shares of its edge) to
/// an end of the edge takes that end instead of splitting it.
const END_SHARE: f64 = 0.05;

/// A hole's loop: its M vertices in chain order from the lowest id, and
/// the lengths along it (`arc[i]` from `vertices[0]` to `vertices[i]`,
/// `arc[n]` the perimeter).
pub(super) struct Rim {
    pub hole: u32,
    vertices: Vec<u32>,
    arc: Vec<f64>,
}

/// The longest hole loop of M (by perimeter); `None` without a usable
/// one. One pass over M's faces for all holes.
pub(super) fn longest_loop(s: &Surface) -> Option<Rim> {
    // Per hole, its rim edges: patch edges u → w with the input's
    // surface across, so that the chain runs w → u; `None` once a vertex
    // starts two of them (a pinched loop).
    let mut rims: HashMap<u32, Option<HashMap<u32, u32>>> = HashMap::new();
    for f in 0..s.face_count() as u32 {
        let h = s.patch(f);
        if h == NONE {
            continue;
        }
        for c in Surface::corners(f) {
            let o = s.opp[c as usize];
            if o == NONE || s.patch(face(o)) != NONE {
                continue;
            }
            let (u, w) = (s.v[next(c) as usize], s.v[prev(c) as usize]);
            let rim = rims.entry(h).or_insert_with(|| Some(HashMap::new()));
            if let Some(map) = rim {
                if map.insert(w, u).is_some() {
                    *rim = None;
                }
            }
        }
    }
    let mut holes: Vec<u32> = rims.keys().copied().collect();
    holes.sort_unstable();
    let mut best: Option<Rim> = None;
    for hole in holes {
        let Some(vertices) = rims[&hole].as_ref().and_then(chain) else {
            continue;
        };
        let arc = arc_lengths(s, &vertices);
        if best.as_ref().is_none_or(|b| arc.last() > b.arc.last()) {
            best = Some(Rim {
                hole,
                vertices,
                arc,
            });
        }
    }
    best
}

/// The rim edges `chain_next` as one loop from its lowest vertex id;
/// `None` unless they form exactly one.
fn chain(chain_next: &HashMap<u32, u32>) -> Option<Vec<u32>> {
    let start = *chain_next.keys().min()?;
    let mut lp = vec![start];
    let mut x = chain_next[&start];
    while x != start {
        if lp.len() > chain_next.len() {
            return None;
        }
        lp.push(x);
        x = *chain_next.get(&x)?;
    }
    (lp.len() == chain_next.len()).then_some(lp)
}

/// 0, then the length along closed loop `lp` to each next vertex, back
/// to `lp[0]`.
fn arc_lengths(s: &Surface, lp: &[u32]) -> Vec<f64> {
    let mut arc = Vec::with_capacity(lp.len() + 1);
    arc.push(0.0);
    for i in 0..lp.len() {
        let (a, b) = (lp[i], lp[(i + 1) % lp.len()]);
        arc.push(arc[i] + s.pos[a as usize].distance(s.pos[b as usize]));
    }
    arc
}

/// A place on the loop: segment `seg` (from `lp[seg]` to the next
/// vertex) at share `at` of it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct OnLoop {
    seg: usize,
    at: f64,
}

/// Where the loop `lp`, walked from `from`, first leaves the sphere of
/// radius `rho` around `centre`, with the loop's length still ahead of
/// that place (to the end of the loop, back at `lp[0]`; `arc[i]` is the
/// length from `lp[0]` to `lp[i]`, `arc[n]` the perimeter); `None` when
/// it does not leave it before the end.
fn leave(
    s: &Surface,
    lp: &[u32],
    arc: &[f64],
    from: OnLoop,
    centre: DVec3,
    rho: f64,
) -> Option<(OnLoop, DVec3, f64)> {
    let n = lp.len();
    let pos = |i: usize| s.pos[lp[i % n] as usize];
    for seg in from.seg..n {
        let (a, b) = (pos(seg), pos(seg + 1));
        let start = if seg == from.seg { from.at } else { 0.0 };
        let d = b - a;
        let (qa, qb, qc) = (
            d.length_squared(),
            2.0 * (a - centre).dot(d),
            (a - centre).length_squared() - rho * rho,
        );
        if qa <= 0.0 {
            continue;
        }
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 {
            continue;
        }
        // The larger root: where the segment goes from inside to outside.
        let t = (-qb + disc.sqrt()) / (2.0 * qa);
        if t > start && t <= 1.0 {
            let ahead = arc[n] - arc[seg] - t * d.length();
            return Some((OnLoop { seg, at: t }, a + d * t, ahead));
        }
    }
    None
}

/// The M vertex at place `p` of the loop, splitting its edge when `p`
/// falls inside it; `splits` lists the split vertices so far with their
/// segments (places come in loop order), `last` the last one and its
/// share on its segment.
fn vertex_at(
    s: &mut Surface,
    lp: &[u32],
    p: OnLoop,
    splits: &mut Vec<(usize, u32)>,
    last: &mut (usize, u32, f64),
) -> Option<u32> {
    let n = lp.len();
    let b = lp[(p.seg + 1) % n];
    if p.at >= 1.0 - END_SHARE {
        return Some(b);
    }
    let (from, share) = if last.0 == p.seg {
        (last.1, last.2)
    } else {
        (lp[p.seg], 0.0)
    };
    if p.at - share <= END_SHARE * (1.0 - share) {
        return Some(from);
    }
    let t = (p.at - share) / (1.0 - share);
    let c = s.edge(from, b)?;
    let t = if s.v[next(c) as usize] == from {
        t
    } else {
        1.0 - t
    };
    let w = s.split_edge(c, t);
    splits.push((p.seg, w));
    *last = (p.seg, w, p.at);
    Some(w)
}

/// A laid fan: the first gate, the explicit vertices (b0, b1, D) and
/// the fan's triangle count.
pub(super) type Fan = (Gate, [[f64; 3]; 3], u32);

impl Retiler<'_> {
    /// Lays the fan over the patch of `rim`'s hole; returns the first
    /// gate, the explicit vertices (b0, b1, D) and the fan's triangle
    /// count. `None` when the loop takes fewer than three points at this
    /// L or two points fall on one vertex of M.
    pub(super) fn first_loop(&mut self, rim: &Rim) -> Result<Option<Fan>, Failure> {
        let (lp, arc) = (&rim.vertices[..], &rim.arc[..]);
        let l = self.l;
        if arc[lp.len()] < 3.0 * l {
            return Ok(None);
        }
        // The points first, on the decoded positions only; M is not
        // touched until the loop is known to take three points.
        let table = crate::swing::AngleTable::new(self.table.bits());
        let p1 = self.s.pos[lp[0] as usize];
        let start = OnLoop { seg: 0, at: 0.0 };
        let Some((at0, p0, _)) = leave(&self.s, lp, arc, start, p1, l) else {
            return Ok(None);
        };
        let (xb1, xb0) = (f32_exact(p1), f32_exact(p0));
        let rho = chain::step_of(&[xb0.to_array(), xb1.to_array(), [0.0; 3]]);
        if rho.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Ok(None);
        }
        let mut xs = vec![xb1, xb0];
        let mut places = vec![start, at0];
        let mut codes: Vec<[u32; 2]> = Vec::new();
        // D stands for the hole: L from b0, towards the loop's middle.
        let centre = lp.iter().map(|&v| self.s.pos[v as usize]).sum::<DVec3>() / lp.len() as f64;
        let toward = (centre - xb0)
            .normalize_or((xb0 - xb1).any_orthonormal_vector().normalize_or(DVec3::X));
        let xd = f32_exact(xb0 + toward * l);
        if xd == xb0 {
            return Ok(None);
        }
        let mut from = at0;
        loop {
            let k = xs.len();
            let (gl, p) = (xs[k - 1], xs[k - 2]);
            let Some((at, target, ahead)) = leave(&self.s, lp, arc, from, gl, rho) else {
                break;
            };
            if ahead < 0.5 * rho {
                break;
            }
            let a = [gl, p, xd, target].map(|v| v.to_array());
            let Some(q) = chain::aim(a[0], a[1], a[2], rho, &table, a[3]) else {
                break;
            };
            let x = chain::place(a[0], a[1], a[2], rho, &table, q).map(DVec3::from_array);
            let Some(x) = x else { break };
            xs.push(x);
            places.push(at);
            codes.push(q);
            from = at;
            if xs.len() > 4 * lp.len() + 8 {
                return Ok(None);
            }
        }
        let n = xs.len();
        if n < 3 {
            return Ok(None);
        }
        // Now M: the loop's vertices at the points.
        let mut splits = Vec::new();
        let mut last = (usize::MAX, NONE, 0.0);
        let mut points = Vec::with_capacity(n);
        for &at in &places {
            let v = if at == start {
                lp[0]
            } else {
                vertex_at(&mut self.s, lp, at, &mut splits, &mut last)
                    .ok_or(Failure::NoThirdVertex)?
            };
            // Two points on one vertex of M (a loop edge far shorter than
            // the share snapped to): no fan; start inside (the splits
            // change no triangloid).
            if points.last() == Some(&v) || (points.len() + 1 == n && v == points[0]) {
                return Ok(None);
            }
            points.push(v);
        }
        // The loop with the splits, in order.
        let mut full = Vec::with_capacity(lp.len() + splits.len());
        let mut at = splits.iter().peekable();
        for (seg, &v) in lp.iter().enumerate() {
            full.push(v);
            while let Some(&(_, w)) = at.next_if(|x| x.0 == seg) {
                full.push(w);
            }
        }
        if !self.fixed {
            // The decoder's L: |b0 − D|, as for a first triangle.
            self.l = first_edge_length(&[xb0.to_array(), xb1.to_array(), xd.to_array()]);
            self.radius = tip_radius(self.l);
            (self.l0, self.radius0) = (self.l, self.radius);
        }
        // M′ vertices: b0, b1, D, then the loop points.
        let b0 = self.add_vertex(xb0, points[1]);
        let b1 = self.add_vertex(xb1, points[0]);
        let d = self.add_vertex(xd, NONE);
        let mut ids = vec![b1, b0];
        self.push_triangle([b0, b1, d]);
        let nodes = self.front.start(&[b0, b1, d]);
        let gr = nodes[2];
        for k in 2..n {
            let gl = ids[k - 1];
            let id = self.add_vertex(xs[k], points[k]);
            ids.push(id);
            self.push_triangle([id, gl, d]);
            self.symbols.push(Symbol::C);
            self.codes.push(0);
            self.steps.push(0);
            self.stretch.push(0);
            self.loop_codes.push(codes[k - 2]);
            self.front.apply_c(gr, id);
        }
        let last = ids[n - 1];
        self.push_triangle([b1, last, d]);
        self.symbols.push(Symbol::R);
        let w = self.front.prev(gr);
        let (next_gate, _) = self.front.apply(gr, Symbol::R, w);
        // Paths: the loop's own edges between consecutive points; none
        // from D, which stands for the patch as a whole.
        let at: HashMap<u32, usize> = full.iter().enumerate().map(|(i, &v)| (v, i)).collect();
        for k in 0..n {
            let (a, b) = (points[k], points[(k + 1) % n]);
            let (i, j) = (at[&a], at[&b]);
            let mut run: Vec<Point> = Vec::new();
            let mut x = i;
            loop {
                run.push(Point::Vertex(full[x]));
                if x == j {
                    break;
                }
                x = (x + 1) % full.len();
            }
            let mut chain = path::insert(&mut self.s, &run).ok_or(Failure::NoSecondVertex)?;
            let (u, v) = (ids[k], ids[(k + 1) % n]);
            if u > v {
                chain.reverse();
            }
            self.paths.insert((u.min(v), u.max(v)), chain);
            self.adj[u as usize].push(v);
            self.adj[v as usize].push(u);
            self.paths.insert((d.min(u), d.max(u)), Vec::new());
            self.adj[u as usize].push(d);
            self.adj[d as usize].push(u);
        }
        // The whole patch is the fan's: the region left of the loop
        // taken in the patch faces' direction.
        let boundary: Vec<u32> = full.iter().rev().copied().collect();
        region::claim(&mut self.s, &boundary, 0, f64::INFINITY, &mut self.flood)
            .map_err(|_| Failure::NoThirdVertex)?;
        let first = [xb0, xb1, xd].map(|p| p.to_array());
        Ok(Some((
            (next_gate.ok_or(Failure::NoThirdVertex)?, d),
            first,
            n as u32,
        )))
    }
}
