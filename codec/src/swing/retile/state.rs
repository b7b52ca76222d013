//! The state of one retiling run (`Retiler`): the surface M as it is
//! split and claimed, the retiled mesh M′ grown so far with each edge's
//! path in M, the front, the file's streams, and the scratch and limits
//! of the passes; with the bookkeeping that keeps M′'s per-vertex and
//! per-triangle arrays in step.
//!
//! Why a file of its own: the run's work is spread over files by step
//! (the first triangle and the growth in `mod.rs`, a loop's fan in
//! `boundary`, a gate in `gate`, its tip in `crease` and `fit`, the
//! triangle's paths and triangloid in `triangle`), which all hold
//! `impl Retiler` blocks. With the state here, below all of them, and
//! the types its fields hold below it, each of those files depends
//! downward only (issue 45, "No import cycles").
//!
//! Invariants: `xhat`, `level`, `msample` and `adj` have one entry per
//! M′ vertex: `add_vertex` adds one to each, `pop_vertex` removes one
//! from each, and nothing else changes their lengths; `half_edges` holds
//! the three directed edges of every triangle in `triangles`
//! (`push_triangle`); `paths` runs each M′ edge's path from its lower id
//! to its higher (a loop fan's edges to D have an empty one).

use super::budget::Budget;
use super::density;
use super::fit_cost;
use super::front::Front;
use super::offset;
use super::path;
use super::region;
use super::surface::{Surface, NONE};
use crate::edgebreaker::Symbol;
use crate::swing::AngleTable;
use glam::DVec3;
use std::collections::HashMap;

/// An explicit vertex (p1, p2, p3; a loop's b0, b1, D) as the decoder
/// reads it: the file stores it as f32, and every tip is built from
/// decoded positions only.
pub(super) fn f32_exact(p: DVec3) -> DVec3 {
    p.as_vec3().as_dvec3()
}

/// A gate to process: the node of GR (GL follows it) and the previous tip.
pub(super) type Gate = (u32, u32);

/// One retiling run: M, M′ so far, and what the passes share.
pub(super) struct Retiler<'b> {
    pub(super) s: Surface,
    pub(super) table: AngleTable,
    /// The edge length of the gate at hand: `l0` scaled by its level.
    pub(super) l: f64,
    /// The base edge length (level 0): the first edge's.
    pub(super) l0: f64,
    /// `l` is an earlier component's and must not change.
    pub(super) fixed: bool,
    /// M has handles: a tip may snap to another loop (an S\*).
    pub(super) handles: bool,
    /// The tip radius of the gate at hand, `radius0` scaled by its level
    /// exactly as the decoder scales it.
    pub(super) radius: f64,
    pub(super) radius0: f64,
    /// Per M′ vertex: its level (`swing::density`).
    pub(super) level: Vec<i8>,
    /// Per C tip: its level step.
    pub(super) steps: Vec<i8>,
    /// Per C tip: its radius code (`crease`).
    pub(super) stretch: Vec<i32>,
    /// Put tips on creases ([`super::RetileOptions::crease_tips`]).
    pub(super) creases: bool,
    /// The step and level a C at the gate at hand takes.
    pub(super) tip_step: (i8, i8),
    /// The target levels, when the density adapts.
    pub(super) density: Option<density::Field>,
    /// Per M′ vertex: decoded position.
    pub(super) xhat: Vec<DVec3>,
    /// Per M′ vertex: the vertex of M where its paths meet.
    pub(super) msample: Vec<u32>,
    /// Per M′ vertex: its neighbours in M′.
    pub(super) adj: Vec<Vec<u32>>,
    /// Per M′ edge (low id, high id): its path in M, from low to high.
    pub(super) paths: HashMap<(u32, u32), Vec<u32>>,
    pub(super) front: Front,
    pub(super) triangles: Vec<[u32; 3]>,
    /// Directed edge (a, b) of M′ to the triangle holding it CCW.
    pub(super) half_edges: HashMap<(u32, u32), u32>,
    pub(super) symbols: Vec<Symbol>,
    pub(super) codes: Vec<u32>,
    pub(super) scratch: path::Scratch,
    pub(super) flood: region::Flood,
    /// Scale of the edge and area limits: 1, or `gate::SLACK` for a
    /// gate's last resort.
    pub(super) slack: f64,
    /// The last resort is allowed ([`super::RetileOptions::last_resort`]).
    pub(super) last_resort: bool,
    /// Aim C tips off M by the curvature offset (`offset`).
    pub(super) approximate: bool,
    /// Choose C codes by `fit`.
    pub(super) fit: bool,
    pub(super) offsets: offset::Scratch,
    /// Scratch of `fit`: the region just claimed (`fit_cost`).
    pub(super) fit_region: fit_cost::Region,
    pub(super) cap: usize,
    /// The two angle codes of each loop point (`boundary`), in order.
    pub(super) loop_codes: Vec<[u32; 2]>,
    /// Steps this run may still take before it counts as running away.
    pub(super) run_steps: u64,
    /// Bytes this run may hold before it counts as running away.
    pub(super) run_bytes: u64,
    pub(super) budget: &'b Budget,
}

impl Retiler<'_> {
    /// Adds an M′ vertex at decoded position `xhat` whose paths meet at
    /// vertex `m` of M (`NONE`: not yet known); returns its id.
    pub(super) fn add_vertex(&mut self, xhat: DVec3, m: u32) -> u32 {
        let id = self.xhat.len() as u32;
        self.xhat.push(xhat);
        self.level.push(self.tip_step.1);
        self.msample.push(m);
        self.adj.push(Vec::new());
        if m != NONE {
            self.s.sample[m as usize] = id;
        }
        id
    }

    /// Undoes the last `add_vertex`.
    pub(super) fn pop_vertex(&mut self) {
        if let Some(m) = self.msample.pop() {
            if m != NONE {
                self.s.sample[m as usize] = NONE;
            }
        }
        self.xhat.pop();
        self.level.pop();
        self.adj.pop();
    }

    pub(super) fn push_triangle(&mut self, t: [u32; 3]) {
        let id = self.triangles.len() as u32;
        for k in 0..3 {
            self.half_edges.insert((t[k], t[(k + 1) % 3]), id);
        }
        self.triangles.push(t);
    }

    pub(super) fn normal(&self, t: [u32; 3]) -> DVec3 {
        let [a, b, c] = t.map(|v| self.xhat[v as usize]);
        (b - a).cross(c - a)
    }

    /// Triangle `t` (CCW) would fold back (normals over 120° apart) onto
    /// an existing triangle across one of its edges.
    pub(super) fn folds(&self, t: [u32; 3]) -> bool {
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

    /// The path of M′ edge a–b as stored (from the lower id to the
    /// higher), and whether that runs from b to a.
    pub(super) fn path(&self, a: u32, b: u32) -> (&[u32], bool) {
        (&self.paths[&(a.min(b), a.max(b))], a > b)
    }

    /// The consecutive vertex pairs of the path of M′ edge a–b, in order
    /// from a to b.
    pub(super) fn path_steps(&self, a: u32, b: u32) -> impl Iterator<Item = (u32, u32)> + '_ {
        let (chain, reversed) = self.path(a, b);
        let n = chain.len();
        (1..n).map(move |i| {
            if reversed {
                (chain[n - i], chain[n - i - 1])
            } else {
                (chain[i - 1], chain[i])
            }
        })
    }
}
