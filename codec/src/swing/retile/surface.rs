//! The input surface M as the retiler edits it: a closed, oriented
//! manifold in a corner table that grows by edge and face splits (thesis
//! §7.3, "tracking a path may require the insertion of new vertices where
//! the path crosses edges of M"; Appendix A's split operators).
//!
//! Corner `c` belongs to face `c / 3`; `next(c)` and `prev(c)` turn CCW
//! inside the face; `opp[c]` is the corner across the edge facing `c`.
//! An *edge* is named by any corner facing it.
//!
//! ```text
//!   split_edge(c, t)                 split_face(f, p)
//!          x                              a
//!         /|\                            /|\
//!        / | \                          / | \
//!       y--w--z     (w on y..z)        /  w  \
//!        \ | /                        / /   \ \
//!         \|/                        b---------c
//!          x'
//! ```
//!
//! Invariants kept by every operation (checked by `check` in tests):
//! * `opp` is an involution without fixed points, and opposite corners
//!   face the same two vertices in reverse order (closed and oriented);
//! * new faces inherit their parent's unit normal, owner and patch, so slivers
//!   made by splits never need a normal of their own (thesis §7.3);
//! * a path flag is set on both corners facing an edge or on neither, and
//!   `on_path[v]` counts the path edges at `v`.

use glam::DVec3;

/// "No value" for the u32 fields below.
pub const NONE: u32 = u32::MAX;

/// The dynamic mesh M.
#[derive(Clone, Debug)]
pub struct Surface {
    /// Vertex positions.
    pub pos: Vec<DVec3>,
    /// Corner to vertex.
    pub v: Vec<u32>,
    /// Corner to opposite corner.
    pub opp: Vec<u32>,
    /// Per face: the face of M it is a piece of (itself for M's own
    /// faces): splits keep the plane and the patch of the face they cut,
    /// so both are kept once per face of M and looked up through this
    /// (4 bytes per face of the refined surface instead of 28: the
    /// surface grows to several times M's faces as paths cut it; issue 22).
    origin: Vec<u32>,
    /// Per face of M: unit normal ([`Surface::normal`]).
    base_normal: Vec<DVec3>,
    /// Per face: the M′ triangle whose triangloid holds it, or `NONE`.
    pub owner: Vec<u32>,
    /// Per face of M: the filled hole it patches, or `NONE` for the
    /// input's own surface ([`Surface::patch`]).
    base_patch: Vec<u32>,
    /// Per corner: the edge it faces lies on a triangloid boundary path.
    pub path: Vec<bool>,
    /// Per vertex: one corner at it.
    pub corner_of: Vec<u32>,
    /// Per vertex: the M′ vertex sampled here, or `NONE`.
    pub sample: Vec<u32>,
    /// Per vertex: number of path edges incident to it.
    pub on_path: Vec<u32>,
    /// Elementary steps taken on this surface since the retiler last
    /// collected them (`budget`): turns around vertices here, walk steps,
    /// search pops and floods in the other modules.
    pub work: std::cell::Cell<u64>,
}

#[inline]
pub fn next(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

#[inline]
pub fn prev(c: u32) -> u32 {
    if c.is_multiple_of(3) {
        c + 2
    } else {
        c - 1
    }
}

#[inline]
pub fn face(c: u32) -> u32 {
    c / 3
}

impl Surface {
    /// Builds M from positions, triangles and the opposite corners of a
    /// closed oriented manifold (a `clean` result without boundary).
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]], opposites: &[u32]) -> Surface {
        let nv = positions.len();
        let mut corner_of = vec![NONE; nv];
        let mut v = Vec::with_capacity(3 * triangles.len());
        for (f, t) in triangles.iter().enumerate() {
            for (k, &x) in t.iter().enumerate() {
                corner_of[x as usize] = 3 * f as u32 + k as u32;
                v.push(x);
            }
        }
        let normal: Vec<DVec3> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| positions[i as usize]);
                (b - a).cross(c - a).normalize_or_zero()
            })
            .collect();
        Surface {
            pos: positions.to_vec(),
            opp: opposites.to_vec(),
            origin: (0..triangles.len() as u32).collect(),
            base_normal: normal,
            owner: vec![NONE; triangles.len()],
            base_patch: vec![NONE; triangles.len()],
            path: vec![false; v.len()],
            v,
            corner_of,
            sample: vec![NONE; nv],
            on_path: vec![0; nv],
            work: std::cell::Cell::new(0),
        }
    }

    pub fn face_count(&self) -> usize {
        self.v.len() / 3
    }

    /// The unit normal of face `f`: that of the face of M it is a piece of.
    #[inline]
    pub fn normal(&self, f: u32) -> DVec3 {
        self.base_normal[self.origin[f as usize] as usize]
    }

    /// The face of M that face `f` is a piece of.
    #[inline]
    pub fn base_face(&self, f: u32) -> u32 {
        self.origin[f as usize]
    }

    /// The filled hole face `f` patches, or `NONE` for the input's own
    /// surface: that of the face of M it is a piece of.
    #[inline]
    pub fn patch(&self, f: u32) -> u32 {
        self.base_patch[self.origin[f as usize] as usize]
    }

    /// Sets the patch of each face of M (`patch`, one per face of M).
    pub fn set_patches(&mut self, patch: &[u32]) {
        self.base_patch.copy_from_slice(patch);
    }

    /// Whether some face patches a hole.
    pub fn has_patches(&self) -> bool {
        self.base_patch.iter().any(|&p| p != NONE)
    }

    pub fn vertex_count(&self) -> usize {
        self.pos.len()
    }

    /// Counts `n` elementary steps (see `work`).
    #[inline]
    pub fn tick(&self, n: u64) {
        self.work.set(self.work.get() + n);
    }

    /// Bytes held by the surface's buffers.
    pub fn memory(&self) -> u64 {
        use core::mem::size_of;
        let per_corner = self.v.capacity() * 4 + self.opp.capacity() * 4 + self.path.capacity();
        let per_face = self.base_normal.capacity() * size_of::<DVec3>()
            + (self.owner.capacity() + self.origin.capacity() + self.base_patch.capacity()) * 4;
        let per_vertex = self.pos.capacity() * size_of::<DVec3>()
            + (self.corner_of.capacity() + self.sample.capacity() + self.on_path.capacity()) * 4;
        (per_corner + per_face + per_vertex) as u64
    }

    /// The three corners of face `f`.
    #[inline]
    pub fn corners(f: u32) -> [u32; 3] {
        [3 * f, 3 * f + 1, 3 * f + 2]
    }

    #[inline]
    pub fn p(&self, c: u32) -> DVec3 {
        self.pos[self.v[c as usize] as usize]
    }

    /// Twice the area of face `f`.
    #[inline]
    pub fn double_area(&self, f: u32) -> f64 {
        let [a, b, c] = Self::corners(f).map(|k| self.p(k));
        (b - a).cross(c - a).length()
    }

    /// The next corner at the same vertex, turning across the edge from
    /// `v(c)` to `v(prev(c))`.
    #[inline]
    pub fn swing(&self, c: u32) -> u32 {
        next(self.opp[next(c) as usize])
    }

    /// The corners at vertex `x`, once around its fan.
    pub fn fan(&self, x: u32) -> Fan<'_> {
        let start = self.corner_of[x as usize];
        Fan {
            s: self,
            start,
            at: start,
            done: false,
            left: self.v.len(),
        }
    }

    /// The corner at `a` whose face has `a` then `b` counterclockwise.
    ///
    /// Turns around `a` and `b` in step, one corner each, and stops at
    /// whichever meets the face first: its corner at `b` follows the
    /// corner at `a`. Splits by paths raise the valence of the corners of
    /// large input triangles in proportion to their size over L (every
    /// path across one splits an edge facing them), while an edge a path
    /// crosses has, after its first split, one end of valence about 4;
    /// turning around `a` alone cost the valence of the far end, and the
    /// whole run grew as 1/L³ (a flat 100,000-gon, 80,000 triangles:
    /// over 150 s). In an oriented manifold the face holding a → b is
    /// unique, so the answer does not depend on the side that finds it.
    pub fn corner_before(&self, a: u32, b: u32) -> Option<u32> {
        let (mut at_a, mut at_b) = (self.fan(a), self.fan(b));
        loop {
            let k = at_a.next()?;
            if self.v[next(k) as usize] == b {
                return Some(k);
            }
            let k = at_b.next()?;
            if self.v[prev(k) as usize] == a {
                return Some(prev(k));
            }
        }
    }

    /// A corner facing the edge between `a` and `b`, if it exists.
    pub fn edge(&self, a: u32, b: u32) -> Option<u32> {
        self.corner_before(a, b).map(prev)
    }

    /// Average of the unit normals of the faces around `x`.
    pub fn vertex_normal(&self, x: u32) -> DVec3 {
        let sum: DVec3 = self.fan(x).map(|k| self.normal(face(k))).sum();
        sum.normalize_or_zero()
    }

    /// Marks the edge facing `c` (both its corners) as a path edge.
    pub fn set_path(&mut self, c: u32) {
        if self.path[c as usize] {
            return;
        }
        let o = self.opp[c as usize];
        self.path[c as usize] = true;
        self.path[o as usize] = true;
        self.on_path[self.v[next(c) as usize] as usize] += 1;
        self.on_path[self.v[prev(c) as usize] as usize] += 1;
    }

    fn push_face(&mut self, verts: [u32; 3], parent: u32) -> u32 {
        let f = self.face_count() as u32;
        self.v.extend_from_slice(&verts);
        self.opp.extend_from_slice(&[NONE; 3]);
        self.path.extend_from_slice(&[false; 3]);
        self.origin.push(self.origin[parent as usize]);
        self.owner.push(self.owner[parent as usize]);
        f
    }

    fn push_vertex(&mut self, p: DVec3) -> u32 {
        self.pos.push(p);
        self.corner_of.push(NONE);
        self.sample.push(NONE);
        self.on_path.push(0);
        self.pos.len() as u32 - 1
    }

    #[inline]
    fn link(&mut self, a: u32, b: u32) {
        self.opp[a as usize] = b;
        self.opp[b as usize] = a;
    }

    /// Splits the edge facing `c` at `y + t(z − y)`, y = v(next c),
    /// z = v(prev c); returns the new vertex w. Both faces at the edge
    /// become two; a path edge stays a path edge on both halves.
    pub fn split_edge(&mut self, c: u32, t: f64) -> u32 {
        let c2 = self.opp[c as usize];
        let (nc, pc, nc2, pc2) = (next(c), prev(c), next(c2), prev(c2));
        let [x, y, z] = [c, nc, pc].map(|k| self.v[k as usize]);
        let x2 = self.v[c2 as usize];
        let (py, pz) = (self.pos[y as usize], self.pos[z as usize]);
        let w = self.push_vertex(py + (pz - py) * t);
        let was_path = self.path[c as usize];
        let (a_out, c_out) = (self.opp[nc as usize], self.opp[nc2 as usize]);
        let (path_nc, path_nc2) = (self.path[nc as usize], self.path[nc2 as usize]);
        let (f, g) = (face(c), face(c2));
        // F = (x, y, z) -> F1 = (x, y, w) in place, F2 = (x, w, z).
        // G = (x2, z, y) -> G1 = (x2, z, w) in place, G2 = (x2, w, y).
        self.v[pc as usize] = w;
        self.v[pc2 as usize] = w;
        let f2 = self.push_face([x, w, z], f);
        let g2 = self.push_face([x2, w, y], g);
        let [f20, f21, f22] = Self::corners(f2);
        let [g20, g21, g22] = Self::corners(g2);
        self.link(c, g20); // y-w
        self.link(nc, f22); // w-x
        self.link(f20, c2); // w-z
        self.link(f21, a_out); // z-x
        self.link(nc2, g22); // w-x2
        self.link(g21, c_out); // y-x2
        for (k, flag) in [
            (c, was_path),
            (nc, false),
            (f20, was_path),
            (f21, path_nc),
            (f22, false),
            (c2, was_path),
            (nc2, false),
            (g20, was_path),
            (g21, path_nc2),
            (g22, false),
        ] {
            self.path[k as usize] = flag;
        }
        if was_path {
            self.on_path[w as usize] = 2;
        }
        self.corner_of[w as usize] = pc;
        self.corner_of[y as usize] = nc;
        self.corner_of[z as usize] = nc2;
        w
    }

    /// Splits face `f` at the interior point `p` into three; returns the
    /// new vertex.
    pub fn split_face(&mut self, f: u32, p: DVec3) -> u32 {
        let [c0, c1, c2] = Self::corners(f);
        let [a, b, c] = [c0, c1, c2].map(|k| self.v[k as usize]);
        let w = self.push_vertex(p);
        let (o0, o1) = (self.opp[c0 as usize], self.opp[c1 as usize]);
        let (p0, p1) = (self.path[c0 as usize], self.path[c1 as usize]);
        // F0 = (a, b, w) in place; F1 = (b, c, w); F2 = (c, a, w).
        self.v[c2 as usize] = w;
        let f1 = self.push_face([b, c, w], f);
        let f2 = self.push_face([c, a, w], f);
        let [k0, k1, k2] = Self::corners(f1);
        let [m0, m1, m2] = Self::corners(f2);
        self.link(c0, k1); // b-w
        self.link(c1, m0); // w-a
        self.link(k0, m1); // c-w
        self.link(k2, o0); // b-c
        self.link(m2, o1); // c-a
        self.path[c0 as usize] = false;
        self.path[c1 as usize] = false;
        self.path[k2 as usize] = p0;
        self.path[m2 as usize] = p1;
        self.corner_of[a as usize] = c0;
        self.corner_of[b as usize] = c1;
        self.corner_of[c as usize] = k1;
        self.corner_of[w as usize] = c2;
        w
    }

    /// Inserts the point `p` of face `f` as a vertex: an existing corner
    /// vertex if `p` is within `snap` of it, a split edge if within
    /// `snap` of an edge, else a split face. Returns the vertex, or `None`
    /// if `p` lies on a path edge or on a vertex with a sample or a path
    /// (the chains of paths are never split).
    pub fn insert_point(&mut self, f: u32, p: DVec3, snap: f64) -> Option<u32> {
        let cs = Self::corners(f);
        for &k in &cs {
            if self.p(k).distance_squared(p) <= snap * snap {
                let x = self.v[k as usize];
                let busy = self.sample[x as usize] != NONE || self.on_path[x as usize] > 0;
                return (!busy).then_some(x);
            }
        }
        for &k in &cs {
            let (y, z) = (self.p(next(k)), self.p(prev(k)));
            let d = z - y;
            let len2 = d.length_squared();
            if len2 == 0.0 {
                continue;
            }
            let t = ((p - y).dot(d) / len2).clamp(0.0, 1.0);
            if (y + d * t).distance_squared(p) <= snap * snap {
                return (!self.path[k as usize]).then(|| self.split_edge(k, t));
            }
        }
        Some(self.split_face(f, p))
    }

    /// Clears the path flag of the edge facing `c`.
    pub fn clear_path(&mut self, c: u32) {
        if !self.path[c as usize] {
            return;
        }
        let o = self.opp[c as usize];
        self.path[c as usize] = false;
        self.path[o as usize] = false;
        self.on_path[self.v[next(c) as usize] as usize] -= 1;
        self.on_path[self.v[prev(c) as usize] as usize] -= 1;
    }

    /// Verifies the invariants listed in the module header.
    #[cfg(test)]
    pub fn check(&self) -> Result<(), String> {
        for c in 0..self.v.len() as u32 {
            let o = self.opp[c as usize];
            if o == NONE || o == c || self.opp[o as usize] != c {
                return Err(format!("corner {c}: opposite {o}"));
            }
            let (y, z) = (self.v[next(c) as usize], self.v[prev(c) as usize]);
            let (y2, z2) = (self.v[next(o) as usize], self.v[prev(o) as usize]);
            if (y, z) != (z2, y2) {
                return Err(format!("corner {c}: edge {y}-{z} vs {y2}-{z2}"));
            }
            if self.path[c as usize] != self.path[o as usize] {
                return Err(format!("corner {c}: path flag differs"));
            }
        }
        let mut count = vec![0u32; self.pos.len()];
        for c in 0..self.v.len() as u32 {
            if self.path[c as usize] {
                // Each edge counted from both corners: half per endpoint.
                count[self.v[next(c) as usize] as usize] += 1;
            }
        }
        if count != self.on_path {
            return Err("on_path counts differ".into());
        }
        for (x, &c) in self.corner_of.iter().enumerate() {
            if self.v[c as usize] != x as u32 {
                return Err(format!("vertex {x}: corner {c} is elsewhere"));
            }
        }
        Ok(())
    }
}

/// Corners around a vertex; see [`Surface::fan`]. Stops after one turn,
/// or after visiting every corner once (a broken table cannot loop it).
pub struct Fan<'a> {
    s: &'a Surface,
    start: u32,
    at: u32,
    done: bool,
    left: usize,
}

impl Iterator for Fan<'_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        if self.done || self.left == 0 {
            return None;
        }
        self.left -= 1;
        self.s.tick(1);
        let here = self.at;
        self.at = self.s.swing(here);
        self.done = self.at == self.start;
        Some(here)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CornerTable;

    /// Two cones over one ring of `n` vertices: apexes 0 and 1 have
    /// valence n, the ring's vertices 4.
    fn double_cone(n: u32) -> Surface {
        let mut pos = vec![DVec3::Z, -DVec3::Z];
        let mut triangles = Vec::new();
        for i in 0..n {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
            pos.push(DVec3::new(a.cos(), a.sin(), 0.0));
            let (p, q) = (2 + i, 2 + (i + 1) % n);
            triangles.push([0, p, q]);
            triangles.push([1, q, p]);
        }
        let table = CornerTable::new(&triangles, pos.len()).unwrap();
        let opp: Vec<u32> = table.opposites().iter().map(|c| c.0).collect();
        Surface::new(&pos, &triangles, &opp)
    }

    #[test]
    fn an_edge_at_a_vertex_of_high_valence_is_found_from_its_low_end() {
        let n = 2000;
        let s = double_cone(n);
        for x in 0..s.vertex_count() as u32 {
            let neighbours: Vec<u32> = s.fan(x).map(|k| s.v[next(k) as usize]).collect();
            for y in neighbours {
                // What turning around x alone finds.
                let whole = s.fan(x).find(|&k| s.v[next(k) as usize] == y);
                s.work.set(0);
                let k = s.corner_before(x, y);
                assert_eq!(k, whole, "{x} → {y}");
                let k = k.unwrap();
                assert_eq!((s.v[k as usize], s.v[next(k) as usize]), (x, y));
                // Every edge has an end of valence 4: a few turns, not
                // up to n around an apex.
                assert!(s.work.get() <= 10, "{x} → {y}: {} turns", s.work.get());
            }
        }
        // Vertices not joined: no corner, after turning around the smaller
        // fan once.
        s.work.set(0);
        assert_eq!(s.corner_before(0, 1), None);
        assert_eq!(s.corner_before(2, 4), None);
        assert!(s.work.get() <= 2 * n as u64 + 20);
    }
}
