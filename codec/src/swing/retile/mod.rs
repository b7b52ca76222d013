//! The SwingWrapper retiler (Attene, Falcidieno, Spagnuolo, Rossignac,
//! "SwingWrapper: retiling triangle meshes for better Edgebreaker
//! compression", ACM TOG 2003; thesis chapter 7; design notes §6).
//!
//! M′ grows from a first triangle in Edgebreaker order, right branch
//! first; on a piece with holes, from a fan over its longest boundary
//! loop instead (`boundary`, beyond the thesis), so that the front starts
//! on the loop and never covers that hole. For every gate (GL, GR) with previous tip T the candidate tip V
//! is where the circle of radius L√3/2 in the gate's bisecting plane
//! meets M, on the side farther from T. V snaps to a border vertex W
//! within L/2 along the surface (always, if V fell in a claimed
//! triangloid), which makes the triangle an L, R, E or S; otherwise it is
//! a C and V's dihedral angle is quantized, aimed off M by the offset
//! that cancels the mean chord error there (`offset`, beyond the thesis:
//! M′ then approximates M instead of interpolating it; issue 19), then
//! moved to the nearby code whose triangle lies nearest the region it
//! covers (`fit`). Each M′ triangle claims the
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
//!
//! Here: the options, one piece's run (`retile_piece`), its first
//! triangle, the growth gate by gate, and the start vertex. The run's
//! state (`Retiler`) is in `state`, below every file that holds one of
//! its steps (`triangle`, `crease`, `fit`, `gate`, `boundary` and this
//! one), so that each of them depends downward only.

mod boundary;
mod budget;
pub mod compose;
mod crease;
pub(crate) use crease::crease_length;
mod density;
pub mod fill;
mod fit;
mod fit_cost;
mod front;
mod gate;
mod marks;
mod mask;
mod offset;
mod path;
pub mod rate;
mod refine;
mod region;
mod snap;
mod state;
mod surface;
mod triangle;
pub(crate) mod valence;
mod walk;

#[cfg(test)]
mod boundary_tests;
#[cfg(test)]
mod pieces_tests;
#[cfg(test)]
pub(crate) mod tests;

use crate::swing::Retiled;
use crate::swing::{first_edge_length, tip_radius, AngleTable};
use crate::{CornerTable, TriMesh};
pub use budget::Budget;
use front::Front;
use glam::DVec3;
use state::{f32_exact, Gate, Retiler};
use std::collections::HashMap;
use surface::{next, Surface, NONE};
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
    /// With no `start_vertex`: among vertices equally flat but for
    /// rounding, rank by the ring's narrowest corner, widest first,
    /// instead of by id. Default `false`; `compose` sets it for one more
    /// start when every start of a piece failed to lay its first triangle.
    pub start_by_shape: bool,
    /// Aim each C tip off M by the offset that cancels the mean chord
    /// error of its triangles (`offset`), instead of at M itself as the
    /// thesis does. Default `true`.
    pub approximate_tips: bool,
    /// Choose each C's angle code by how near its triangle lies to the
    /// region it claims (`fit`), instead of the code nearest the aim.
    /// Default `true`.
    pub fit_tips: bool,
    /// Let the edge length follow M's curvature (`density`; the file
    /// then carries `DENS`, format 1.1) instead of one L everywhere.
    pub adaptive_density: bool,
    /// Close a gate that nothing else closes with a loop neighbour
    /// allowed [`gate::SLACK`] times longer edges and larger triangloids,
    /// instead of failing the run. Default `false`; the retries of
    /// `compose` set it on a piece's last start.
    pub last_resort: bool,
    /// On a piece with holes, start on its longest boundary loop
    /// (`boundary`; the file carries `LOOP`, format 1.1) instead of on
    /// a first triangle inside, so that no triangle covers that hole's
    /// patch but the fan over it. Runs with an odd `start_rank` start
    /// inside, as an independent retry. Default `true`.
    pub loop_start: bool,
    /// Put C tips on the input's creases where the gate's bisecting plane
    /// crosses one near the circle (`crease`; radius codes, `RADS`,
    /// format 1.1). Default `false`.
    pub crease_tips: bool,
}

pub use crate::error::RetileFailure as Failure;

/// Retiles one closed piece. `patch` labels the faces that close a hole
/// (`fill`); `fixed` is the L of an earlier component of the same file,
/// which this one must use as it is (the decoder has one radius per
/// file); `handles`: M has genus > 0; the run's work is charged to
/// `budget`. Returns the piece as a one-component [`Retiled`] without mask,
/// per triangle the hole patch that covers most of its triangloid (a
/// loop's fan wholly its hole's), and per vertex the face of `mesh` its
/// on-surface sample lies in (`placement_faces`).
fn retile_piece(
    mesh: &TriMesh,
    table: &CornerTable,
    patch: Option<&[u32]>,
    opt: &RetileOptions,
    fixed: Option<f64>,
    handles: bool,
    budget: &Budget,
) -> Result<(Retiled, Vec<mask::Cover>, Vec<u32>), Failure> {
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
    let mut s = Surface::new(&positions, &mesh.triangles, &opposites);
    if let Some(p) = patch {
        s.set_patches(p);
    }
    let l = fixed.unwrap_or(opt.edge_length);
    let area = mesh.area();
    let tri_area = l * l * 3f64.sqrt() / 4.0;
    let cap = (8.0 * area / tri_area) as usize + 64;
    // Elements the run's bounds scale with: M's corners and those of the
    // most triangles the run may make.
    let elements = 3 * (mesh.face_count() + cap) as u64;
    let run_bytes = budget::RUN_BYTES_PER_ELEMENT.saturating_mul(elements);
    // Faces many L across, above all long thin ones, defeat the paths'
    // length bounds (`refine`); at most `cap` splits, as many as the
    // retiled triangles the run may make, and under the run's and the
    // encoder's memory and work limits whatever L is asked.
    refine::refine(&mut s, refine::MAX_EDGE * l, cap, |s| {
        let memory = s.memory();
        if memory > run_bytes {
            Err(Failure::Runaway)
        } else if budget.charge(s.work.replace(0), memory) {
            Ok(())
        } else {
            Err(Failure::Limit)
        }
    })?;
    let density = opt.adaptive_density.then(|| density::Field::new(&s, l));
    let mut r = Retiler {
        s,
        table: AngleTable::new(opt.angle_bits),
        l,
        l0: l,
        fixed: fixed.is_some(),
        handles,
        radius: tip_radius(l),
        radius0: tip_radius(l),
        level: Vec::new(),
        steps: Vec::new(),
        stretch: Vec::new(),
        creases: opt.crease_tips,
        tip_step: (0, 0),
        density,
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
        slack: 1.0,
        last_resort: opt.last_resort,
        approximate: opt.approximate_tips,
        fit: opt.fit_tips,
        offsets: offset::Scratch::default(),
        fit_region: fit_cost::Region::default(),
        run_steps: budget::RUN_STEPS_PER_ELEMENT.saturating_mul(elements),
        run_bytes,
        budget,
        cap,
        loop_codes: Vec::new(),
    };
    let on_loop = if opt.loop_start
        && opt.start_vertex.is_none()
        && !opt.start_by_shape
        && opt.start_rank.is_multiple_of(2)
    {
        match boundary::longest_loop(&r.s) {
            Some(rim) => r
                .first_loop(&rim)?
                .map(|(g, f, t)| (g, f, Some((rim.hole, t)))),
            None => None,
        }
    } else {
        None
    };
    let (first_gate, first, fan) = match on_loop {
        Some(started) => started,
        None => {
            let start = opt
                .start_vertex
                .unwrap_or_else(|| start_vertex(&r.s, opt.start_rank, opt.start_by_shape, l));
            let (g, f) = r.first_triangle(start)?;
            (g, f, None)
        }
    };
    r.grow(first_gate)?;
    let uncovered = r.s.owner.iter().filter(|&&o| o == NONE).count();
    if uncovered > 0 {
        return Err(Failure::Uncovered {
            faces: uncovered as u32,
        });
    }
    let mut cover = r.cover();
    // The fan over the starting loop's patch is that hole's mask.
    if let Some((hole, t)) = fan {
        for c in cover.iter_mut().take(t as usize) {
            *c = (hole, 1.0);
        }
    }
    // A fan has one triangle per loop point.
    let loops = crate::swing::chain::Loops {
        entries: fan.map(|(_, t)| (0, t)).into_iter().collect(),
    };
    let placed = r.placement_faces();
    let retiled = Retiled {
        angle_bits: opt.angle_bits,
        first: vec![first],
        triangles: r.triangles,
        positions: r.xhat.iter().map(|p| p.to_array()).collect(),
        symbols: r.symbols,
        codes: r.codes,
        edge_length: r.l0,
        steps: r.steps,
        stretch: r.stretch,
        hole_mask: Vec::new(),
        rest: None,
        loops,
        loop_codes: r.loop_codes,
    };
    Ok((retiled, cover, placed))
}

impl Retiler<'_> {
    /// Per M′ vertex, the face of M (the piece's mesh before refinement)
    /// that holds its on-surface sample V, the point its tip was fitted
    /// from (`NONE` where no sample was recorded): where the input's
    /// attributes are read for it (`encoder::provenance`).
    fn placement_faces(&self) -> Vec<u32> {
        self.msample
            .iter()
            .map(|&m| match self.s.corner_of.get(m as usize) {
                Some(&c) if m != NONE => self.s.base_face(surface::face(c)),
                _ => NONE,
            })
            .collect()
    }

    /// Per M′ triangle: the hole patch holding most of its triangloid's
    /// area, and that share of the area.
    fn cover(&self) -> Vec<mask::Cover> {
        let s = &self.s;
        let n = self.triangles.len();
        let mut total = vec![0.0f64; n];
        let mut on: HashMap<(u32, u32), f64> = HashMap::new();
        for f in 0..s.face_count() as u32 {
            let o = s.owner[f as usize];
            if o == NONE {
                continue;
            }
            let area = 0.5 * s.double_area(f);
            total[o as usize] += area;
            let h = s.patch(f);
            if h != NONE {
                *on.entry((o, h)).or_default() += area;
            }
        }
        let mut cover = vec![(NONE, 0.0); n];
        let mut best: Vec<((u32, u32), f64)> = on.into_iter().collect();
        // Deterministic: by triangle, then hole.
        best.sort_unstable_by_key(|&(k, _)| k);
        for ((o, h), area) in best {
            let share = if total[o as usize] > 0.0 {
                area / total[o as usize]
            } else {
                0.0
            };
            if share > cover[o as usize].1 {
                cover[o as usize] = (h, share);
            }
        }
        cover
    }

    /// p1, p2, p3 and the first triangloid (design notes §6 steps 2–5).
    /// Returns the first gate and the explicit vertices (p1, p3, p2).
    fn first_triangle(&mut self, p1: u32) -> Result<(Gate, [[f64; 3]; 3]), Failure> {
        let s = &self.s;
        let c1 = s.pos[p1 as usize];
        let n1 = s.vertex_normal(p1);
        let axis = least_parallel_axis(n1);
        let axis = (axis - n1 * axis.dot(n1)).normalize_or_zero();
        // The plane through p1 along the first direction may close in a
        // loop shorter than L (near a rim, across a thin part); the next
        // directions turn by 90° each.
        let (p2, f2) = [axis, n1.cross(axis), -axis, -n1.cross(axis)]
            .into_iter()
            .find_map(|tangent| {
                let plane = Plane {
                    origin: c1,
                    normal: n1.cross(tangent),
                };
                let (k, x) = leave_vertex(s, &plane, p1)
                    .into_iter()
                    .filter(|&(_, x)| (x - c1).dot(tangent) > 0.0)
                    .max_by(|a, b| (a.1 - c1).dot(tangent).total_cmp(&(b.1 - c1).dot(tangent)))?;
                // The walk leaves p1 across face(k) and enters the next
                // face at x. Where face(k) itself reaches the sphere (an
                // input face wider than L), p2 lies on p1–x and belongs to
                // face(k): handed to the walker, it would be measured on
                // p1–x but split into the face beyond, folding M there.
                let d = x.distance(c1);
                if d >= self.l {
                    return Some((c1 + (x - c1) * (self.l / d), surface::face(k)));
                }
                let mut w = Walker::across(s, plane, k, s.face_count());
                walk_to_radius(&mut w, x, c1, self.l, 4.0 * self.l - d)
            })
            .ok_or(Failure::NoSecondVertex)?;
        let (x1, x2) = (f32_exact(c1), f32_exact(p2));
        if !self.fixed {
            // The decoder's L: the distance of the explicit p1 and p2.
            self.l = first_edge_length(&[x1.to_array(), DVec3::ZERO.to_array(), x2.to_array()]);
            self.radius = tip_radius(self.l);
            (self.l0, self.radius0) = (self.l, self.radius);
        }
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
        let orient = |p: DVec3, f: u32| (p - x1).cross(x2 - x1).dot(self.s.normal(f));
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

    /// Processes gates in Edgebreaker order until every loop closed.
    ///
    /// Remembered gates are kept with their two vertices: after an S\*
    /// the merged loop can consume a remembered gate before it is popped,
    /// and Edgebreaker then skips it (its triangle is visited), which is
    /// where the decoder needs the handle event.
    fn grow(&mut self, first: Gate) -> Result<(), Failure> {
        let mut stack: Vec<(Gate, [u32; 2])> = Vec::new();
        let mut gate = Some(first);
        while let Some((gr, tip)) = gate {
            if self.triangles.len() > self.cap {
                return Err(Failure::Runaway);
            }
            self.account()?;
            let (next, push) = self.step(gr, tip)?;
            if let Some(g) = push {
                let ends = [
                    self.front.vertex(g.0),
                    self.front.vertex(self.front.next(g.0)),
                ];
                stack.push((g, ends));
            }
            gate = next;
            while gate.is_none() {
                let Some((g, [w, gl])) = stack.pop() else {
                    break;
                };
                // Consumed: the triangle on its free side holds GL → W.
                if !self.half_edges.contains_key(&(gl, w)) {
                    gate = Some(g);
                }
            }
        }
        Ok(())
    }

    /// Hands the steps taken since the last call to the budget.
    fn account(&mut self) -> Result<(), Failure> {
        let steps = self.s.work.replace(0);
        self.run_steps = self.run_steps.checked_sub(steps).ok_or(Failure::Runaway)?;
        let memory = self.memory();
        if memory > self.run_bytes {
            return Err(Failure::Runaway);
        }
        if self.budget.charge(steps, memory) {
            Ok(())
        } else {
            Err(Failure::Limit)
        }
    }

    /// Bytes held by the run: the surface, and about 150 per M′ triangle
    /// (position, adjacency, paths, half-edge map, symbols).
    fn memory(&self) -> u64 {
        self.s.memory() + 150 * self.triangles.capacity() as u64
    }
}

/// Placeholder sample of p3 until it is found.
const NONE_PLACEHOLDER: u32 = NONE;

/// The `rank`-th best start vertex (0 = first). On a piece with hole
/// patches: among the
/// [`START_CANDIDATES`] vertices whose own ring is flattest (largest
/// |mean normal|; rings of five faces or more, as a tip of three or four
/// faces can be flat and still thin), the one whose surroundings within
/// `START_REACH`·L are flattest, lowest id on ties. The first triangle is
/// L across, so flatness at that scale is what decides whether p2 and p3
/// exist: a finely tessellated rim (a teapot's spout) is flat ring by
/// ring and still turns within L. Vertices nearer than `RIM_HOPS` edges
/// to a hole patch are left out (unless none is farther), and a
/// neighbourhood that reaches a patch scores lowest: the patch is smooth
/// by construction but not the input, and a plane through a start near
/// the rim can close in a loop shorter than L. On a closed piece: the
/// vertex whose own ring is flattest.
fn start_vertex(s: &Surface, rank: u32, by_shape: bool, l: f64) -> u32 {
    // A closed input has no rim to keep away from; there the ring's own
    // flatness was measured better (rd generated table: the wider score
    // made 21 of 29 swing rows worse, by 2-37%).
    let patched = s.has_patches();
    let hops = if patched { patch_hops(s) } else { Vec::new() };
    let far = hops.iter().copied().max().unwrap_or(0).min(RIM_HOPS);
    let ring_flatness = |x: u32| {
        let (mut sum, mut n) = (DVec3::ZERO, 0u32);
        for k in s.fan(x) {
            sum += s.normal(surface::face(k));
            n += 1;
        }
        (n >= 5).then(|| sum.length() / n as f64)
    };
    let scored: Vec<(f64, u32)> = (0..s.vertex_count() as u32)
        .filter(|&x| s.corner_of[x as usize] != NONE && (!patched || hops[x as usize] >= far))
        .filter_map(|x| ring_flatness(x).map(|f| (f, x)))
        .collect();
    if scored.is_empty() {
        return 0;
    }
    // Flattest first, lowest id on ties. By shape, flatness values equal
    // but for rounding (a CAD part's planes) are ties, and among them the
    // vertex whose ring has the widest narrowest corner comes first: on a
    // planar face triangulated as a fan, the lowest-id inner vertex is,
    // after refinement, a midpoint among the fan's apex needles, where no
    // first triangle could be laid (a 200-gon fanned from one corner, and
    // a cylinder with fanned caps, failed every run at L = 1.5% of their
    // diameter). As the first choice this order made 10 of 35 generated
    // swing rows worse (2-25%) and none better, so it is only the
    // fallback (`RetileOptions::start_by_shape`).
    let mut scored: Vec<(f64, u32, f64)> = scored
        .into_iter()
        .map(|(f, x)| (f, x, if by_shape { ring_width(s, x) } else { 0.0 }))
        .collect();
    let level = |f: f64| if by_shape { (f * FLAT_TIE).round() } else { f };
    let order = |a: &(f64, u32, f64), b: &(f64, u32, f64)| {
        level(b.0)
            .total_cmp(&level(a.0))
            .then(b.2.total_cmp(&a.2))
            .then(a.1.cmp(&b.1))
    };
    if !patched {
        let k = (rank as usize).min(scored.len() - 1);
        scored.select_nth_unstable_by(k, order);
        return scored[k].1;
    }
    let keep = START_CANDIDATES.min(scored.len());
    if keep < scored.len() {
        scored.select_nth_unstable_by(keep - 1, order);
        scored.truncate(keep);
    }
    let mut mark = vec![0u32; s.face_count()];
    for (i, entry) in scored.iter_mut().enumerate() {
        entry.0 = flatness_around(s, entry.1, START_REACH * l, &mut mark, i as u32 + 1);
    }
    scored.sort_unstable_by(order);
    scored[(rank as usize).min(scored.len() - 1)].1
}

/// Flatness values equal once multiplied by this and rounded are ties
/// (by shape).
const FLAT_TIE: f64 = 1e9;

/// How wide the narrowest corner of the faces around vertex `x` is: minus
/// its cosine (larger is wider; -1 with a zero-length edge).
fn ring_width(s: &Surface, x: u32) -> f64 {
    let cos = |u: DVec3, v: DVec3| u.dot(v) / (u.length() * v.length());
    let mut narrowest = -1.0f64;
    for k in s.fan(x) {
        let [a, b, c] = Surface::corners(surface::face(k)).map(|q| s.p(q));
        for t in [cos(b - a, c - a), cos(c - b, a - b), cos(a - c, b - c)] {
            narrowest = if t.is_nan() { 1.0 } else { narrowest.max(t) };
        }
    }
    -narrowest
}

/// Ring-flattest vertices whose wider surroundings are measured.
const START_CANDIDATES: usize = 64;
/// Radius of those surroundings, in L.
const START_REACH: f64 = 1.5;
/// Faces a surroundings flood visits at most.
const START_FACES: usize = 4096;

/// |area-weighted mean normal| of the faces around vertex `x` whose
/// corners all lie within `radius` of it (flooded across edges, at most
/// [`START_FACES`]); -1 when the flood meets a hole patch. Faces visited
/// are stamped `stamp` in `mark`.
fn flatness_around(s: &Surface, x: u32, radius: f64, mark: &mut [u32], stamp: u32) -> f64 {
    let centre = s.pos[x as usize];
    let r2 = radius * radius;
    let inside = |f: u32| {
        Surface::corners(f)
            .iter()
            .all(|&c| s.p(c).distance_squared(centre) <= r2)
    };
    let mut stack: Vec<u32> = s.fan(x).map(surface::face).collect();
    stack.iter().for_each(|&f| mark[f as usize] = stamp);
    let mut visited = stack.len();
    let (mut sum, mut area) = (DVec3::ZERO, 0.0);
    while let Some(f) = stack.pop() {
        if s.patch(f) != NONE {
            return -1.0;
        }
        let a = s.double_area(f);
        sum += s.normal(f) * a;
        area += a;
        if visited >= START_FACES {
            continue;
        }
        for c in Surface::corners(f) {
            let g = surface::face(s.opp[c as usize]);
            if mark[g as usize] != stamp && inside(g) {
                mark[g as usize] = stamp;
                visited += 1;
                stack.push(g);
            }
        }
    }
    if area > 0.0 {
        sum.length() / area
    } else {
        0.0
    }
}

/// How far (in edges) a start vertex should keep from a hole patch.
const RIM_HOPS: u32 = 8;

/// Per vertex: edges to the nearest vertex of a patch face (breadth
/// first), `u32::MAX` without patches or when unreachable.
fn patch_hops(s: &Surface) -> Vec<u32> {
    let mut hops = vec![u32::MAX; s.vertex_count()];
    let mut queue = std::collections::VecDeque::new();
    for f in 0..s.face_count() {
        if s.patch(f as u32) == NONE {
            continue;
        }
        for c in Surface::corners(f as u32) {
            let v = s.v[c as usize];
            if hops[v as usize] != 0 {
                hops[v as usize] = 0;
                queue.push_back(v);
            }
        }
    }
    while let Some(x) = queue.pop_front() {
        let d = hops[x as usize] + 1;
        for k in s.fan(x) {
            let y = s.v[next(k) as usize];
            if hops[y as usize] > d {
                hops[y as usize] = d;
                queue.push_back(y);
            }
        }
    }
    hops
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
