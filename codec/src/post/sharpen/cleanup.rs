//! Removal of sliver triangles (thesis §8.3, end of "Snapping the new
//! vertices", Fig. 8.9; ALGORITHMS.md §7, "Cleanup").
//!
//! Where four or more sharp edges meet, neighbouring chamfer and corner
//! vertices snap to the same point and leave zero-area triangles; the
//! input may have some too. Every triangle with an angle below the
//! threshold loses the edge facing that angle by an edge collapse; the
//! faces around the kept vertex are examined again, until none is left
//! or nothing valid remains.
//!
//! A collapse of u into v is done only if it keeps the mesh an oriented
//! manifold (Dey, Edelsbrunner, Guha & Nekhayev, "Topology preserving
//! edge contraction", 1999, with the boundary treated as a vertex joined
//! to every boundary vertex):
//! * the vertices adjacent to both u and v are exactly the third vertices
//!   of the one or two faces of the edge (the link condition);
//! * u and v are not both on the boundary unless the edge is;
//! * no third vertex is an interior vertex of valence 3 (a tetrahedron
//!   would flatten into two faces glued back to back);
//! * no surviving face around u turns over.
//!
//! The kept endpoint is the one tagged sharp, else the one that was in
//! the input, else the lower index; it keeps its place. When every such
//! collapse is invalid, three fallbacks follow (not in the thesis or the
//! notes; they matter only for degenerate input): a cap (a flat angle
//! between two tiny ones) has its long edge flipped, or is removed if
//! that edge is a boundary edge and its apex is not on the boundary; then
//! the collapses are tried keeping the other endpoint; and a face without
//! area in a component of at most [`SMALL_COMPONENT`] faces takes the
//! component with it. A zero-area face survives only if none of these is
//! valid, which takes contrived input (a boundary vertex lying on another
//! boundary edge, say); the report counts it among the slivers left.
//!
//! Invariants: faces only lose or swap vertices, never change orientation;
//! the output references no vertex that the collapses removed, and the
//! survivors keep their order. Cost: one sweep when there is no sliver;
//! otherwise a vertex-to-face index (a counting sort) plus work local to
//! the slivers. Every collapse deletes a face; flips do not, so a budget
//! of operations bounds the loop.

use crate::prelude::*;

use glam::DVec3;

use super::geometry::{angle_at, is_sliver, point, sliver_sin2};

const NONE: u32 = u32::MAX;

/// The largest component that may be removed for having collapsed flat
/// (a tetrahedron has 4 faces; some slack for a few more).
const SMALL_COMPONENT: usize = 16;

/// The mesh after the cleanup, compacted.
pub(super) struct Cleaned {
    pub positions: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
    pub tagged: Vec<bool>,
    /// Edges collapsed.
    pub collapsed: u64,
    /// Vertices no face references any more (dropped).
    pub vertices_removed: u64,
    /// Slivers nothing valid could remove.
    pub left: u64,
    /// Small components removed because they had collapsed flat.
    pub components_removed: u64,
}

/// Removes slivers (module docs). `original` is the input's vertex count:
/// vertices below it were in the input. `candidates` are the faces that
/// may be slivers (the input's slivers and every face the subdivision
/// made), so that a mesh without any costs no sweep here.
pub(super) fn cleanup(
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    tagged: Vec<bool>,
    original: usize,
    min_angle_degrees: f64,
    candidates: Vec<u32>,
) -> Cleaned {
    let theta = min_angle_degrees.to_radians();
    let sin2 = sliver_sin2(min_angle_degrees);
    let pts = |t: [u32; 3]| t.map(|v| point(&positions, v));
    let mut work: Vec<u32> = candidates
        .into_iter()
        .filter(|&f| is_sliver(pts(triangles[f as usize]), sin2))
        .collect();
    if work.is_empty() {
        return Cleaned {
            positions,
            triangles,
            tagged,
            collapsed: 0,
            vertices_removed: 0,
            left: 0,
            components_removed: 0,
        };
    }

    let mut touched = work.clone();
    let mut m = Dynamic::new(triangles, positions.len());
    let mut collapsed = 0u64;
    let mut components_removed = 0u64;
    let rank = |v: u32| 2 * u8::from(tagged[v as usize]) + u8::from((v as usize) < original);
    let mut around = Vec::new();
    // Every collapse deletes faces, but flips do not: a budget keeps any
    // flip-collapse cycle finite (none has been seen).
    let mut budget = 8 * m.tris.len() + 64;
    while let Some(f) = work.pop() {
        let f = f as usize;
        if !m.alive[f] || !is_sliver(pts(m.tris[f]), sin2) || budget == 0 {
            continue;
        }
        budget -= 1;
        let t = m.tris[f];
        let p = pts(t);
        // The corners by angle, then by the length of the edge they face
        // (so that of coincident points, their short edge goes first).
        let angle = [0, 1, 2].map(|k| {
            let (q, r) = (p[(k + 1) % 3], p[(k + 2) % 3]);
            // At a point that coincides with another the angle is
            // undefined (atan2 would say 0 or π): call it 0.
            if q == p[k] || r == p[k] {
                0.0
            } else {
                angle_at(p[k], q, r)
            }
        });
        let facing = [0, 1, 2].map(|k| (p[(k + 1) % 3] - p[(k + 2) % 3]).length());
        let mut order = [0usize, 1, 2];
        order.sort_by(|&i, &j| {
            angle[i]
                .total_cmp(&angle[j])
                .then(facing[i].total_cmp(&facing[j]))
        });
        let tiny: Vec<usize> = order
            .into_iter()
            .enumerate()
            .filter(|&(i, k)| i == 0 || angle[k] <= theta)
            .map(|(_, k)| k)
            .collect();
        // The notes' rule first: collapse the edge facing a tiny angle,
        // keeping the tagged or original endpoint. A cap (a flat angle
        // between two tiny ones) whose collapses all fail has its long
        // edge flipped instead; failing that, a triangle without area may
        // keep the other endpoint (there is no shape to lose).
        let flat = is_sliver(p, 0.0);
        let mut fixed = false;
        'fix: for strict in [true, false] {
            if !strict && !flat {
                break;
            }
            for &k in &tiny {
                let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
                let (remove, keep) = match rank(a).cmp(&rank(b)) {
                    core::cmp::Ordering::Greater => (b, a),
                    core::cmp::Ordering::Less => (a, b),
                    core::cmp::Ordering::Equal => (a.max(b), a.min(b)),
                };
                let (remove, keep) = if strict {
                    (remove, keep)
                } else {
                    (keep, remove)
                };
                if m.collapse(remove, keep, &positions) {
                    collapsed += 1;
                    m.faces_of(keep, &mut around);
                    work.extend(around.iter().copied());
                    touched.extend(around.iter().copied());
                    fixed = true;
                    break 'fix;
                }
            }
            let wide = order[2];
            if strict && angle[wide] > core::f64::consts::FRAC_PI_2 {
                if let Some(g) = m.flip(f, wide, &positions) {
                    work.extend([f as u32, g]);
                    touched.push(g);
                    fixed = true;
                    break 'fix;
                }
            }
        }
        // A face without area that nothing could fix lies, as far as has
        // been seen, in a component too small to lose an edge (a flattened
        // tetrahedron): the component goes, which keeps the rest manifold.
        if !fixed && flat && m.alive[f] {
            components_removed += u64::from(m.remove_small_component(f));
        }
    }

    // Slivers left: only faces that were examined can be.
    crate::sort::sort_unstable(&mut touched);
    touched.dedup();
    let left = touched
        .iter()
        .filter(|&&f| m.alive[f as usize] && is_sliver(pts(m.tris[f as usize]), sin2))
        .count() as u64;

    // Compact: drop the dead faces, and the vertices no face references
    // any more, which can only be vertices of dead faces (vertices the
    // input left unreferenced stay).
    let mut dropped: Vec<u32> = m.killed.iter().flat_map(|&f| m.tris[f as usize]).collect();
    crate::sort::sort_unstable(&mut dropped);
    dropped.dedup();
    dropped.retain(|&v| {
        m.faces_of(v, &mut around);
        around.is_empty()
    });
    let Dynamic { tris, alive, .. } = m;
    let live = tris
        .into_iter()
        .zip(alive)
        .filter(|&(_, a)| a)
        .map(|(t, _)| t);
    if dropped.is_empty() {
        return Cleaned {
            triangles: live.collect(),
            positions,
            tagged,
            collapsed,
            vertices_removed: 0,
            left,
            components_removed,
        };
    }
    let nv = positions.len();
    let mut remap = vec![NONE; nv];
    let mut out_positions = Vec::with_capacity(nv - dropped.len());
    let mut out_tagged = Vec::with_capacity(nv - dropped.len());
    let mut next_dropped = dropped.iter().peekable();
    for v in 0..nv {
        if next_dropped.peek() == Some(&&(v as u32)) {
            next_dropped.next();
            continue;
        }
        remap[v] = out_positions.len() as u32;
        out_positions.push(positions[v]);
        out_tagged.push(tagged[v]);
    }
    Cleaned {
        triangles: live.map(|t| t.map(|v| remap[v as usize])).collect(),
        vertices_removed: dropped.len() as u64,
        positions: out_positions,
        tagged: out_tagged,
        collapsed,
        left,
        components_removed,
    }
}

/// A triangle list that supports edge collapses, with the faces of each
/// vertex found through a vertex-to-face index of the faces as they were
/// at the start: a vertex that absorbed others by collapses chains their
/// lists to its own, and a listed face counts if it is alive and now
/// names the vertex.
struct Dynamic {
    tris: Vec<[u32; 3]>,
    alive: Vec<bool>,
    start: Vec<u32>,
    list: Vec<u32>,
    chain_next: Vec<u32>,
    chain_tail: Vec<u32>,
    /// Scratch marks per vertex, valid when equal to `stamp`.
    mark: Vec<u32>,
    stamp: u32,
    /// Per vertex, the faces that flips gave it (not in `list`); empty
    /// until the first flip. Indexed by vertex, not one list scanned
    /// whole: a hostile file made a flip cycle that ran until the
    /// operation budget, and a whole scan per `faces_of` turned that
    /// into seconds (fuzz finding, issue 8).
    extra: Vec<Vec<u32>>,
    /// Faces deleted, in order.
    killed: Vec<u32>,
    scratch: [Vec<u32>; 3],
}

impl Dynamic {
    fn new(tris: Vec<[u32; 3]>, nv: usize) -> Self {
        let mut start = vec![0u32; nv + 1];
        for t in &tris {
            for &v in t {
                start[v as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut list = vec![0u32; start[nv] as usize];
        for (f, t) in tris.iter().enumerate() {
            for &v in t {
                list[fill[v as usize] as usize] = f as u32;
                fill[v as usize] += 1;
            }
        }
        Dynamic {
            alive: vec![true; tris.len()],
            tris,
            start,
            list,
            chain_next: vec![NONE; nv],
            chain_tail: (0..nv as u32).collect(),
            mark: vec![0; nv],
            stamp: 0,
            extra: Vec::new(),
            killed: Vec::new(),
            scratch: [Vec::new(), Vec::new(), Vec::new()],
        }
    }

    /// The live faces around `v`, into `out` (cleared first).
    fn faces_of(&self, v: u32, out: &mut Vec<u32>) {
        out.clear();
        let live = |f: u32| self.alive[f as usize] && self.tris[f as usize].contains(&v);
        let mut w = v;
        while w != NONE {
            let range = self.start[w as usize] as usize..self.start[w as usize + 1] as usize;
            out.extend(self.list[range].iter().copied().filter(|&f| live(f)));
            w = self.chain_next[w as usize];
        }
        if !self.extra.is_empty() {
            // A flip may have given a face back a vertex it had at the
            // start: skip faces already listed.
            let mut w = v;
            while w != NONE {
                for &f in &self.extra[w as usize] {
                    if live(f) && !out.contains(&f) {
                        out.push(f);
                    }
                }
                w = self.chain_next[w as usize];
            }
        }
    }

    /// Whether `v`, with live faces `faces`, is on the boundary: a closed
    /// fan has as many neighbours as faces, an open one more.
    fn is_boundary(&mut self, v: u32, faces: &[u32]) -> bool {
        self.neighbours(v, faces).0 > faces.len()
    }

    /// Removes the component of face `f` if it has at most
    /// [`SMALL_COMPONENT`] faces; returns whether it did.
    fn remove_small_component(&mut self, f: usize) -> bool {
        let mut seen = vec![f as u32];
        let mut around = Vec::new();
        let mut i = 0;
        while i < seen.len() {
            let t = self.tris[seen[i] as usize];
            for v in t {
                self.faces_of(v, &mut around);
                for &g in &around {
                    if !seen.contains(&g) {
                        if seen.len() == SMALL_COMPONENT {
                            return false;
                        }
                        seen.push(g);
                    }
                }
            }
            i += 1;
        }
        for &g in &seen {
            self.alive[g as usize] = false;
            self.killed.push(g);
        }
        true
    }

    /// Flips the edge facing corner `k` of face `f`, a cap whose corner
    /// `k` is flat: (a, b, c) and the face (y, c, b) across b–c become
    /// (a, b, y) and (a, y, c). Returns the other face, or `None` when
    /// a–y is already an edge, b or c would be left with two faces, or a
    /// new face would have no area or turn over. When b–c is a boundary
    /// edge and a is not on the boundary, the face is removed instead
    /// (and returned).
    fn flip(&mut self, f: usize, k: usize, positions: &[[f32; 3]]) -> Option<u32> {
        self.with_scratch(|this, fb, fa, fx| this.try_flip(f, k, positions, fb, fa, fx))
    }

    /// Runs `op` with the three reusable face lists, lent out of `self`
    /// for the call so that `op` can also borrow `self` mutably.
    fn with_scratch<R>(
        &mut self,
        op: impl FnOnce(&mut Self, &mut Vec<u32>, &mut Vec<u32>, &mut Vec<u32>) -> R,
    ) -> R {
        let [mut a, mut b, mut c] = core::mem::take(&mut self.scratch);
        let result = op(self, &mut a, &mut b, &mut c);
        self.scratch = [a, b, c];
        result
    }

    fn try_flip(
        &mut self,
        f: usize,
        k: usize,
        positions: &[[f32; 3]],
        fb: &mut Vec<u32>,
        fa: &mut Vec<u32>,
        fx: &mut Vec<u32>,
    ) -> Option<u32> {
        let t = self.tris[f];
        let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        self.faces_of(a, fa);
        self.faces_of(b, fb);
        let across = fb.iter().copied().find(|&g| {
            let u = self.tris[g as usize];
            g as usize != f && (0..3).any(|i| u[i] == c && u[(i + 1) % 3] == b)
        });
        let Some(g) = across else {
            // b–c is a boundary edge: with a inside the surface, the face
            // can simply go (a joins the boundary, b and c keep one fan);
            // the caller only asks for slivers.
            if self.is_boundary(a, fa) {
                return None;
            }
            self.alive[f] = false;
            self.killed.push(f as u32);
            return Some(f as u32);
        };
        let u = self.tris[g as usize];
        let y = u.into_iter().find(|&x| x != b && x != c)?;
        if y == a || fa.iter().any(|&h| self.tris[h as usize].contains(&y)) {
            return None;
        }
        for v in [b, c] {
            self.faces_of(v, fx);
            if fx.len() <= 3 && !self.is_boundary(v, fx) {
                return None;
            }
        }
        let cross = |t: [u32; 3]| {
            let p = t.map(|x| point(positions, x));
            (p[1] - p[0]).cross(p[2] - p[0])
        };
        let old = cross(u);
        let (nf, ng) = ([a, b, y], [a, y, c]);
        for n in [cross(nf), cross(ng)] {
            if n == DVec3::ZERO || n.dot(old) <= 0.0 {
                return None;
            }
        }
        self.tris[f] = nf;
        self.tris[g as usize] = ng;
        if self.extra.is_empty() {
            self.extra = vec![Vec::new(); self.chain_next.len()];
        }
        for (x, h) in [(y, f as u32), (a, g)] {
            // A flip cycle gives the same face to the same vertex again.
            if !self.extra[x as usize].contains(&h) {
                self.extra[x as usize].push(h);
            }
        }
        Some(g)
    }

    fn next_stamp(&mut self) -> u32 {
        if self.stamp >= u32::MAX - 2 {
            self.mark.fill(0);
            self.stamp = 0;
        }
        self.stamp += 1;
        self.stamp
    }

    /// Distinct vertices other than `v` in `faces`, marking them with a
    /// fresh stamp (returned).
    fn neighbours(&mut self, v: u32, faces: &[u32]) -> (usize, u32) {
        let s = self.next_stamp();
        let mut count = 0;
        for &f in faces {
            for x in self.tris[f as usize] {
                if x != v && self.mark[x as usize] != s {
                    self.mark[x as usize] = s;
                    count += 1;
                }
            }
        }
        (count, s)
    }

    /// Collapses `remove` into `keep` if that is valid (module docs).
    fn collapse(&mut self, remove: u32, keep: u32, positions: &[[f32; 3]]) -> bool {
        self.with_scratch(|this, fu, fv, fx| this.try_collapse(remove, keep, positions, fu, fv, fx))
    }

    fn try_collapse(
        &mut self,
        u: u32,
        v: u32,
        positions: &[[f32; 3]],
        fu: &mut Vec<u32>,
        fv: &mut Vec<u32>,
        fx: &mut Vec<u32>,
    ) -> bool {
        self.faces_of(u, fu);
        self.faces_of(v, fv);
        let shared: Vec<u32> = fu
            .iter()
            .copied()
            .filter(|&f| self.tris[f as usize].contains(&v))
            .collect();
        let third = |t: [u32; 3]| t.into_iter().find(|&x| x != u && x != v).unwrap_or(NONE);
        let opposite: Vec<u32> = shared
            .iter()
            .map(|&f| third(self.tris[f as usize]))
            .collect();
        match opposite[..] {
            [x] if x != NONE => {}
            [x, y] if x != NONE && y != NONE && x != y => {}
            _ => return false,
        }

        // Link condition: the common neighbours are the opposite vertices.
        let (nu, su) = self.neighbours(u, fu);
        let s = self.next_stamp();
        let mut nv = 0;
        let mut common = 0;
        for &f in fv.iter() {
            for x in self.tris[f as usize] {
                if x == v {
                    continue;
                }
                let m = &mut self.mark[x as usize];
                if *m == s {
                    continue;
                }
                if *m == su && x != u {
                    common += 1;
                }
                *m = s;
                nv += 1;
            }
        }
        if common != opposite.len() {
            return false;
        }
        // A closed fan has as many neighbours as faces; an open one more.
        let (u_boundary, v_boundary) = (nu > fu.len(), nv > fv.len());
        if shared.len() == 2 && u_boundary && v_boundary {
            return false;
        }
        for &x in &opposite {
            self.faces_of(x, fx);
            let (n, _) = self.neighbours(x, fx);
            let interior = n == fx.len();
            if interior && fx.len() <= 3 {
                return false;
            }
        }

        // No surviving face around u may turn over.
        let pv = point(positions, v);
        for &f in fu.iter() {
            let t = self.tris[f as usize];
            if t.contains(&v) {
                continue;
            }
            let p = t.map(|x| point(positions, x));
            let q = t.map(|x| if x == u { pv } else { point(positions, x) });
            let before = (p[1] - p[0]).cross(p[2] - p[0]);
            let after = (q[1] - q[0]).cross(q[2] - q[0]);
            if before.dot(after) < 0.0 {
                return false;
            }
        }

        for &f in &shared {
            self.alive[f as usize] = false;
            self.killed.push(f);
        }
        for &f in fu.iter() {
            if self.alive[f as usize] {
                for x in self.tris[f as usize].iter_mut() {
                    if *x == u {
                        *x = v;
                    }
                }
            }
        }
        let tail = self.chain_tail[v as usize];
        self.chain_next[tail as usize] = u;
        self.chain_tail[v as usize] = self.chain_tail[u as usize];
        true
    }
}
