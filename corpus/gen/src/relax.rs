//! Clean-up of a triangle mesh that approximates an implicit surface:
//! short-edge collapses, angle-improving edge flips, and tangential
//! Laplacian relaxation with projection back onto the surface.
//!
//! This is the improvement loop of isotropic remeshing (Botsch & Kobbelt,
//! "A remeshing approach to multiresolution modeling", SGP 2004) without
//! the edge splits, which marching-tetrahedra output does not need: its
//! edges are at most a grid diagonal long, while its flaws are tiny edges
//! and slivers where the surface passes close to grid nodes.
//!
//! Topology is preserved: a collapse is only done when the edge's two
//! endpoints share exactly the two neighbours opposite the edge (the link
//! condition of Dey et al., "Topology preserving edge contraction", 1999),
//! and a flip only when the new edge does not exist yet. Every operation
//! that would make a triangle tiny or turn it away from the surface normal
//! is refused (or undone, for relaxation), so the result keeps the input's
//! consistent orientation.

use crate::vec::{
    add, cross, dist, dot, length, lerp, min_angle, normalize, scale, sub, tri_normal, V3,
};

/// A surface given as the zero set of a function, negative inside.
pub(crate) trait Implicit {
    /// Value and gradient at `p`.
    fn eval(&self, p: V3) -> (f64, V3);

    /// Newton steps along the gradient onto the zero set. Starting within a
    /// fraction of the feature size, this converges in two or three steps
    /// for a distance-like function.
    fn project(&self, p: V3) -> V3 {
        let mut q = p;
        for _ in 0..8 {
            let (v, g) = self.eval(q);
            let gg = dot(g, g);
            if v.abs() < 1e-13 || gg < 1e-24 {
                break;
            }
            q = sub(q, scale(g, v / gg));
        }
        q
    }

    /// Unit outward normal at `p` (the normalized gradient).
    fn normal(&self, p: V3) -> V3 {
        normalize(self.eval(p).1)
    }
}

/// A triangle may not turn further than this from the surface normal
/// (cosine of 60 degrees).
const MIN_NORMAL_COS: f64 = 0.5;

/// An indexed triangle mesh on an implicit surface, improved in place.
pub(crate) struct Relax<'a, S: Implicit> {
    surf: &'a S,
    pos: Vec<V3>,
    /// Unit surface normal at each vertex, kept in step with `pos`.
    nrm: Vec<V3>,
    tris: Vec<[u32; 3]>,
    dead: Vec<bool>,
    /// Triangles smaller than this (twice the area) count as degenerate.
    tiny_area2: f64,
}

impl<'a, S: Implicit> Relax<'a, S> {
    /// Projects every vertex onto the surface and prepares the clean-up.
    /// `len` is the typical edge length (it scales the tolerances).
    pub(crate) fn new(surf: &'a S, pos: Vec<V3>, tris: Vec<[u32; 3]>, len: f64) -> Self {
        let pos: Vec<V3> = pos.into_iter().map(|p| surf.project(p)).collect();
        let nrm = pos.iter().map(|&p| surf.normal(p)).collect();
        let dead = vec![false; tris.len()];
        Relax {
            surf,
            pos,
            nrm,
            tris,
            dead,
            tiny_area2: 1e-6 * len * len,
        }
    }

    /// True if triangle `abc` has a sane area and faces the way the surface
    /// does around it.
    fn face_ok(&self, t: [u32; 3], pos: &[V3], nrm: &[V3]) -> bool {
        let [a, b, c] = t.map(|v| v as usize);
        let n = tri_normal(pos[a], pos[b], pos[c]);
        let l = length(n);
        if l <= self.tiny_area2 {
            return false;
        }
        let reference = normalize(add(add(nrm[a], nrm[b]), nrm[c]));
        dot(n, reference) > MIN_NORMAL_COS * l
    }

    fn vertex_faces(&self) -> Vec<Vec<u32>> {
        let mut vf = vec![Vec::new(); self.pos.len()];
        for (f, t) in self.tris.iter().enumerate() {
            if !self.dead[f] {
                for &v in t {
                    vf[v as usize].push(f as u32);
                }
            }
        }
        vf
    }

    fn neighbours(&self, vf: &[Vec<u32>], v: u32) -> Vec<u32> {
        let mut out: Vec<u32> = vf[v as usize]
            .iter()
            .flat_map(|&f| self.tris[f as usize])
            .filter(|&w| w != v)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Collapses edges shorter than `min_len` to their midpoint (projected
    /// onto the surface), unless that changes the topology, makes an edge
    /// longer than `max_len`, or spoils a triangle. Returns the number done.
    pub(crate) fn collapse_short(&mut self, min_len: f64, max_len: f64) -> usize {
        let mut vf = self.vertex_faces();
        let mut done = 0;
        for f in 0..self.tris.len() {
            for k in 0..3 {
                if self.dead[f] {
                    break;
                }
                let t = self.tris[f];
                let (u, v) = (t[k], t[(k + 1) % 3]);
                if dist(self.pos[u as usize], self.pos[v as usize]) < min_len
                    && self.try_collapse(&mut vf, u, v, max_len)
                {
                    done += 1;
                }
            }
        }
        done
    }

    fn try_collapse(&mut self, vf: &mut [Vec<u32>], u: u32, v: u32, max_len: f64) -> bool {
        let (ui, vi) = (u as usize, v as usize);
        let shared: Vec<u32> = vf[ui]
            .iter()
            .copied()
            .filter(|&f| self.tris[f as usize].contains(&v))
            .collect();
        if shared.len() != 2 {
            return false;
        }
        // Link condition: u and v may only share the two vertices opposite
        // their edge, or the collapse would pinch the surface.
        let (nu, nv) = (self.neighbours(vf, u), self.neighbours(vf, v));
        if nu.iter().filter(|w| nv.binary_search(w).is_ok()).count() != 2 {
            return false;
        }
        let p = self.surf.project(lerp(self.pos[ui], self.pos[vi], 0.5));
        let pn = self.surf.normal(p);
        // Try the new position in place; restore it if a triangle objects.
        let (old_pu, old_nu) = (self.pos[ui], self.nrm[ui]);
        self.pos[ui] = p;
        self.nrm[ui] = pn;
        let mut ok = true;
        for &f in vf[ui].iter().chain(vf[vi].iter()) {
            if shared.contains(&f) {
                continue;
            }
            let t = self.tris[f as usize].map(|w| if w == v { u } else { w });
            if !self.face_ok(t, &self.pos, &self.nrm)
                || t.iter()
                    .any(|&w| w != u && dist(self.pos[w as usize], p) > max_len)
            {
                ok = false;
                break;
            }
        }
        if !ok {
            self.pos[ui] = old_pu;
            self.nrm[ui] = old_nu;
            return false;
        }
        for &f in &vf[vi] {
            for w in self.tris[f as usize].iter_mut() {
                if *w == v {
                    *w = u;
                }
            }
        }
        for &f in &shared {
            self.dead[f as usize] = true;
        }
        let moved = std::mem::take(&mut vf[vi]);
        vf[ui].retain(|f| !shared.contains(f));
        vf[ui].extend(moved.into_iter().filter(|f| !shared.contains(f)));
        for &f in &shared {
            for w in self.tris[f as usize] {
                if w != u && w != v {
                    vf[w as usize].retain(|g| *g != f);
                }
            }
        }
        true
    }

    /// Flips every edge whose flip raises the smallest angle of its two
    /// triangles (the max-min angle criterion, which in the plane gives the
    /// Delaunay triangulation). Returns the number of flips.
    pub(crate) fn flip_pass(&mut self) -> usize {
        let mut vf = self.vertex_faces();
        let mut done = 0;
        for f in 0..self.tris.len() {
            for k in 0..3 {
                if self.dead[f] {
                    break;
                }
                let t = self.tris[f];
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let Some(&g) = vf[a as usize]
                    .iter()
                    .find(|&&g| g as usize != f && self.tris[g as usize].contains(&b))
                else {
                    continue;
                };
                let tg = self.tris[g as usize];
                let d = *tg.iter().find(|&&w| w != a && w != b).unwrap();
                // Cheap filter first: in the plane, a flip raises the
                // smallest angle exactly when the two angles facing the edge
                // sum to more than pi, i.e. their cotangents sum below 0.
                let [pa, pb, pc, pd] = [a, b, c, d].map(|w| self.pos[w as usize]);
                let cot = |apex: V3| {
                    let (u, v) = (sub(pa, apex), sub(pb, apex));
                    dot(u, v) / length(cross(u, v)).max(1e-300)
                };
                if cot(pc) + cot(pd) >= 0.0 {
                    continue;
                }
                // Keep valence >= 3 at a and b, and never duplicate an edge.
                if c == d
                    || vf[a as usize].len() <= 3
                    || vf[b as usize].len() <= 3
                    || vf[c as usize]
                        .iter()
                        .any(|&h| self.tris[h as usize].contains(&d))
                {
                    continue;
                }
                let q = |t: [u32; 3]| {
                    let [x, y, z] = t.map(|w| self.pos[w as usize]);
                    min_angle(x, y, z)
                };
                let (n1, n2) = ([a, d, c], [d, b, c]);
                let before = q([a, b, c]).min(q(tg));
                let after = q(n1).min(q(n2));
                // The margin keeps flips from cycling on near-ties.
                if after <= before + 1e-3
                    || !self.face_ok(n1, &self.pos, &self.nrm)
                    || !self.face_ok(n2, &self.pos, &self.nrm)
                {
                    continue;
                }
                self.tris[f] = n1;
                self.tris[g as usize] = n2;
                vf[a as usize].retain(|&h| h != g);
                vf[b as usize].retain(|&h| h as usize != f);
                vf[c as usize].push(g);
                vf[d as usize].push(f as u32);
                done += 1;
            }
        }
        done
    }

    /// One Jacobi step of tangential uniform Laplacian relaxation: each
    /// vertex moves `lambda` of the way to its neighbours' centroid, within
    /// its tangent plane, then back onto the surface. Moves that would spoil
    /// a triangle are undone.
    pub(crate) fn smooth(&mut self, lambda: f64) {
        let n = self.pos.len();
        let mut sum = vec![[0.0; 3]; n];
        let mut cnt = vec![0u32; n];
        for (f, t) in self.tris.iter().enumerate() {
            if self.dead[f] {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                sum[a] = add(sum[a], self.pos[b]);
                sum[b] = add(sum[b], self.pos[a]);
                cnt[a] += 1;
                cnt[b] += 1;
            }
        }
        let (old_pos, old_nrm) = (self.pos.clone(), self.nrm.clone());
        for v in 0..n {
            if cnt[v] == 0 {
                continue;
            }
            let (p, nv) = (old_pos[v], old_nrm[v]);
            let d = sub(scale(sum[v], 1.0 / cnt[v] as f64), p);
            let d = sub(d, scale(nv, dot(d, nv)));
            let q = self.surf.project(add(p, scale(d, lambda)));
            self.pos[v] = q;
            self.nrm[v] = self.surf.normal(q);
        }
        loop {
            let mut undone = false;
            for (f, &t) in self.tris.iter().enumerate() {
                if self.dead[f]
                    || self.face_ok(t, &self.pos, &self.nrm)
                    || !self.face_ok(t, &old_pos, &old_nrm)
                {
                    continue;
                }
                for w in t.map(|w| w as usize) {
                    if self.pos[w] != old_pos[w] {
                        self.pos[w] = old_pos[w];
                        self.nrm[w] = old_nrm[w];
                        undone = true;
                    }
                }
            }
            if !undone {
                break;
            }
        }
    }

    /// The live triangles over the referenced vertices, renumbered in
    /// their original order.
    pub(crate) fn finish(self) -> (Vec<V3>, Vec<[u32; 3]>) {
        let mut map = vec![u32::MAX; self.pos.len()];
        let live: Vec<[u32; 3]> = self
            .tris
            .iter()
            .zip(&self.dead)
            .filter(|(_, &d)| !d)
            .map(|(t, _)| *t)
            .collect();
        for t in &live {
            for &v in t {
                map[v as usize] = 0;
            }
        }
        let mut pos = Vec::new();
        for (v, m) in map.iter_mut().enumerate() {
            if *m == 0 {
                *m = pos.len() as u32;
                pos.push(self.pos[v]);
            }
        }
        let tris = live
            .into_iter()
            .map(|t| t.map(|v| map[v as usize]))
            .collect();
        (pos, tris)
    }
}
