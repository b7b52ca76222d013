//! The front of the forward pass that codes `CLRF` (format 1.1): the
//! loops of the decoded region's border, built triangle by triangle in
//! Edgebreaker order, so that each symbol is coded knowing the shape of
//! the front around its gate (the angles the retiler decided by).
//!
//! A loop is a cycle of nodes, one per appearance of a vertex on the
//! border, with the decoded region on the *left* of `node → next`
//! (the retiler's `retile::front` keeps the same loops; this one adds
//! what the coder needs and checks every step, as it reads hostile data).
//! A gate is a node `gr` with `gl = next(gr)`; each node also keeps the
//! third vertex of the decoded triangle on its edge (`behind`), which
//! fixes the frame of a C tip and the plane of the context, and that
//! triangle's number (`face`), which makes the pass's triangles a mesh
//! with no corner table: each new triangle's neighbours across the front
//! edges it takes are the faces of those edges.
//!
//! ```text
//!   … → prev(GR) → GR → GL → next(GL) → …      decoded region on the left
//!                    \   /
//!                     tip                      new triangle (tip, GL, GR)
//!
//!   C  tip new:            … GR → X → GL …       next gate GR (edge GR → X)
//!   L  tip = next(GL):     … GR → W …            next gate GR
//!   R  tip = prev(GR):     … W → GL …            next gate W
//!   E  tip = both:         the loop closes       pop a remembered gate
//!   S  tip node W:         GR → W → …  and  … → W' → GL
//!                          next gate GR; remember W' (edge W → GL)
//! ```
//!
//! Invariant: a node's outgoing edge changes only when a triangle is
//! built on it (at S the tip's node keeps its edge and a new node W'
//! takes W → GL), so a remembered gate is consumed exactly when its node
//! died or its next vertex changed: Edgebreaker's "the gate's triangle
//! was visited meanwhile" (an S\* round a handle), without a face map.
//!
//! Every operation is O(1): nothing walks a loop, so a hostile stream
//! cannot make the pass slower than linear.

use crate::prelude::*;

use super::angle::{cross, dot, sub};
use crate::edgebreaker::Symbol;
use crate::{Error, FormatError, Malformed};

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// The loops of one mesh (all components; nodes are never reused).
#[derive(Default, Debug)]
pub(super) struct Loops {
    vertex: Vec<u32>,
    next: Vec<u32>,
    prev: Vec<u32>,
    behind: Vec<u32>,
    face: Vec<u32>,
    alive: Vec<bool>,
}

/// The triangle a symbol builds at its gate, before the front moves:
/// its vertices (tip, GL, GR) and its neighbours decoded before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Built {
    pub tri: [u32; 3],
    /// The triangle across the gate.
    pub parent: u32,
    /// The triangles across the front edges the tip closes (an L's
    /// GL → tip, an R's tip → GR, an E's both), `None` for a new edge.
    pub sides: [Option<u32>; 2],
}

impl Loops {
    fn push(&mut self, vertex: u32, behind: u32, face: u32) -> u32 {
        let id = self.vertex.len() as u32;
        self.vertex.push(vertex);
        self.next.push(id);
        self.prev.push(id);
        self.behind.push(behind);
        self.face.push(face);
        self.alive.push(true);
        id
    }

    fn link(&mut self, a: u32, b: u32) {
        self.next[a as usize] = b;
        self.prev[b as usize] = a;
    }

    /// Nodes made so far.
    pub(super) fn count(&self) -> usize {
        self.vertex.len()
    }

    pub(super) fn vertex(&self, n: u32) -> u32 {
        self.vertex[n as usize]
    }

    pub(super) fn next(&self, n: u32) -> u32 {
        self.next[n as usize]
    }

    pub(super) fn prev(&self, n: u32) -> u32 {
        self.prev[n as usize]
    }

    pub(super) fn is_alive(&self, n: u32) -> bool {
        self.alive.get(n as usize).copied().unwrap_or(false)
    }

    /// The third vertex of the decoded triangle on the edge `n → next(n)`.
    pub(super) fn behind(&self, n: u32) -> u32 {
        self.behind[n as usize]
    }

    /// The number of the decoded triangle on the edge `n → next(n)`.
    pub(super) fn face(&self, n: u32) -> u32 {
        self.face[n as usize]
    }

    /// The triangle that `symbol` builds at the live gate `gr`, with
    /// `tip` the new vertex of a C and the tip node of an S (checked by
    /// [`Loops::check_s`] first; unused otherwise). Read before the front
    /// moves, so for an L, R or E before that move's own checks: the
    /// caller uses it only once they passed. Every node it reads exists
    /// (links only name nodes already made), so a hostile front cannot
    /// make it panic.
    pub(super) fn built(&self, gr: u32, symbol: Symbol, tip: u32) -> Built {
        let gl = self.next(gr);
        let (vl, vr) = (self.vertex(gl), self.vertex(gr));
        let (tip, sides) = match symbol {
            Symbol::C => (tip, [None, None]),
            Symbol::S => (self.vertex(tip), [None, None]),
            Symbol::L => (self.vertex(self.next(gl)), [Some(self.face(gl)), None]),
            Symbol::R => {
                let w = self.prev(gr);
                (self.vertex(w), [Some(self.face(w)), None])
            }
            Symbol::E => {
                let w = self.next(gl);
                (self.vertex(w), [Some(self.face(gl)), Some(self.face(w))])
            }
        };
        Built {
            tri: [tip, vl, vr],
            parent: self.face(gr),
            sides,
        }
    }

    /// A component's first triangle (a, b, c), counter-clockwise, the
    /// `t`-th triangle; returns its first gate, the node of c (edge
    /// c → a, facing b).
    pub(super) fn start(&mut self, [a, b, c]: [u32; 3], t: u32) -> u32 {
        let na = self.push(a, c, t);
        let nb = self.push(b, a, t);
        let nc = self.push(c, b, t);
        self.link(na, nb);
        self.link(nb, nc);
        self.link(nc, na);
        nc
    }

    /// Checks that `gr` is a live gate; returns GL.
    pub(super) fn gate(&self, gr: u32) -> Result<u32, Error> {
        let gl = self.next(gr);
        if self.is_alive(gr) && self.is_alive(gl) && gl != gr {
            Ok(gl)
        } else {
            Err(bad("a gate of the forward pass is not on the front"))
        }
    }

    /// C, triangle `t`: new vertex `x` between GR and GL; the next gate
    /// is GR.
    pub(super) fn c(&mut self, gr: u32, x: u32, t: u32) -> u32 {
        let gl = self.next(gr);
        let (vl, vr) = (self.vertex(gl), self.vertex(gr));
        let nx = self.push(x, vr, t);
        self.link(gr, nx);
        self.link(nx, gl);
        self.behind[gr as usize] = vl;
        self.face[gr as usize] = t;
        gr
    }

    /// L, triangle `t`: the tip is next(GL), GL leaves the front; the
    /// next gate is GR.
    pub(super) fn l(&mut self, gr: u32, t: u32) -> Result<u32, Error> {
        let gl = self.next(gr);
        let w = self.next(gl);
        if !self.is_alive(w) || w == gr {
            return Err(bad("an L without a vertex after its gate"));
        }
        self.alive[gl as usize] = false;
        self.behind[gr as usize] = self.vertex(gl);
        self.face[gr as usize] = t;
        self.link(gr, w);
        Ok(gr)
    }

    /// R, triangle `t`: the tip is prev(GR), GR leaves the front; the
    /// next gate is the tip's node.
    pub(super) fn r(&mut self, gr: u32, t: u32) -> Result<u32, Error> {
        let gl = self.next(gr);
        let w = self.prev(gr);
        if !self.is_alive(w) || w == gl {
            return Err(bad("an R without a vertex before its gate"));
        }
        self.alive[gr as usize] = false;
        self.behind[w as usize] = self.vertex(gr);
        self.face[w as usize] = t;
        self.link(w, gl);
        Ok(w)
    }

    /// E: the loop GR → GL → next(GL) closes.
    pub(super) fn e(&mut self, gr: u32) -> Result<(), Error> {
        let gl = self.next(gr);
        let w = self.next(gl);
        if !self.is_alive(w) || self.prev(gr) != w || w == gr {
            return Err(bad("an E on a loop of more than three vertices"));
        }
        for n in [gr, gl, w] {
            self.alive[n as usize] = false;
        }
        Ok(())
    }

    /// Checks that node `w` may be the tip of an S at the live gate `gr`.
    pub(super) fn check_s(&self, gr: u32, w: u32) -> Result<(), Error> {
        let gl = self.next(gr);
        let bad_tip = !self.is_alive(w)
            || w == gr
            || w == gl
            || w == self.next(gl)
            || w == self.prev(gr)
            || !self.is_alive(self.prev(w));
        if bad_tip {
            return Err(bad("an S whose tip is not a vertex of the front"));
        }
        Ok(())
    }

    /// S (or S\*: `w` on another loop, which joins this one), triangle
    /// `t`: the tip is node `w`. Returns the next gate (GR) and the
    /// remembered one, as its node and the vertex its edge leads to.
    pub(super) fn s(&mut self, gr: u32, w: u32, t: u32) -> Result<(u32, (u32, u32)), Error> {
        self.check_s(gr, w)?;
        let gl = self.next(gr);
        let (vl, vr) = (self.vertex(gl), self.vertex(gr));
        let before = self.prev(w);
        let w2 = self.push(self.vertex(w), vr, t);
        self.link(before, w2);
        self.link(w2, gl);
        self.link(gr, w);
        self.behind[gr as usize] = vl;
        self.face[gr as usize] = t;
        Ok((gr, (w2, vl)))
    }

    /// A remembered gate (node `g`, its edge leading to vertex `v`) had
    /// its triangle built meanwhile.
    pub(super) fn consumed(&self, g: u32, v: u32) -> bool {
        !self.is_alive(g) || self.vertex(self.next(g)) != v
    }

    /// The context of the symbol at gate `gr` (`x` the decoded positions
    /// by vertex): 4 × the quadrant of the front's angle at GR (from the
    /// gate to prev(GR)) plus the quadrant of the angle at GL (from the
    /// gate to next(GL)), both measured around the normal of the triangle
    /// behind the gate. The retiler closes a gate with an ear when such
    /// an angle is sharp on the free side and grows a C when both are
    /// wide, so the two quadrants predict most symbols
    /// (format-spec/05-swing.md, "CLRF"). Measured against octants on
    /// horse, bunny and spot: quadrants cost 10-30% fewer bits, most on
    /// small meshes, whose 64 octant models would still be learning.
    pub(super) fn context(&self, gr: u32, x: &[[f64; 3]]) -> usize {
        let gl = self.next(gr);
        let p = |n: u32| x[self.vertex(n) as usize];
        let (xl, xr, xt) = (p(gl), p(gr), x[self.behind(gr) as usize]);
        let n = cross(sub(xl, xr), sub(xt, xr));
        let at_r = quadrant(n, sub(xl, xr), sub(p(self.prev(gr)), xr));
        let at_l = quadrant(n, sub(xr, xl), sub(p(self.next(gl)), xl));
        at_r * 4 + at_l
    }
}

/// Contexts of the symbol model: [`Loops::context`]'s range.
pub(super) const CONTEXTS: usize = 16;

/// The quadrant 0…3 of the angle θ ∈ (−180°, 180°] from `u` to `w`
/// around `n`: 0 for θ < −90°, 1 for −90° ≤ θ < 0, 2 for 0 ≤ θ < 90°,
/// 3 for θ ≥ 90° (up to where exact zeros fall), from the signs of
/// n·(u × w) (sin θ) and u·w (cos θ): only additions and
/// multiplications decide it, so every IEEE 754 machine finds the same
/// quadrant, as the coder needs.
fn quadrant(n: [f64; 3], u: [f64; 3], w: [f64; 3]) -> usize {
    let s = dot(n, cross(u, w));
    let c = dot(u, w);
    match (s >= 0.0, c >= 0.0) {
        (false, false) => 0,
        (false, true) => 1,
        (true, true) => 2,
        (true, false) => 3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadrants_follow_the_angle() {
        let n = [0.0, 0.0, 1.0];
        let u = [2.0, 0.0, 0.0];
        for (deg, want) in [
            (-170.0, 0),
            (-100.0, 0),
            (-80.0, 1),
            (-10.0, 1),
            (10.0, 2),
            (80.0, 2),
            (100.0, 3),
            (170.0, 3),
        ] {
            let a = f64::to_radians(deg);
            let w = [3.0 * a.cos(), 3.0 * a.sin(), 0.0];
            assert_eq!(quadrant(n, u, w), want, "{deg}");
            // Flipping the normal mirrors the angle.
            assert_eq!(quadrant([0.0, 0.0, -1.0], u, w), 3 - want, "{deg}");
        }
    }

    #[test]
    fn a_tetrahedron_closes_and_remembered_gates_follow_their_edges() {
        let mut f = Loops::default();
        let g = f.start([0, 1, 2], 0);
        assert_eq!(f.gate(g).unwrap(), 0);
        // C: the loop becomes 0 → 1 → 2 → 3 → 0, gate 2 → 3.
        let g = f.c(g, 3, 3);
        assert_eq!((f.vertex(g), f.vertex(f.next(g))), (2, 3));
        assert_eq!(f.behind(g), 0);
        // Loop now 0 → 1 → 2 → 3 → 0; gate 2 → 3, prev(2) = 1: an R
        // makes the triangle (1, 3, 2) and the gate 1 → 3.
        let g = f.r(g, 9).unwrap();
        assert_eq!((f.vertex(g), f.vertex(f.next(g))), (1, 3));
        // Loop 0 → 1 → 3 → 0: an E closes it.
        f.e(g).unwrap();
        assert!(f.gate(g).is_err());
    }

    #[test]
    fn an_s_splits_the_loop_and_keeps_the_tip_node_edge() {
        let mut f = Loops::default();
        let g = f.start([0, 1, 2], 0);
        // Grow a loop of six: 0 → 1 → 2 → 3 → 4 → 5 → 0 (C at 2 → 0 three times).
        let g = f.c(g, 3, 3); // 2 → 3 → 0
        let g2 = f.next(g); // node of 3, edge 3 → 0
        let g2 = f.c(g2, 4, 4); // 3 → 4 → 0
        let g3 = f.next(g2);
        let g3 = f.c(g3, 5, 5); // 4 → 5 → 0
        assert_eq!(f.vertex(f.next(f.next(g3))), 0);
        // Gate 4 → 5 (GR = 4, GL = 5), S with tip node of 1.
        let n1 = f.prev(f.prev(f.prev(g3)));
        assert_eq!(f.vertex(n1), 1);
        let (next, (w2, v)) = f.s(g3, n1, 9).unwrap();
        assert_eq!(next, g3);
        assert_eq!((f.vertex(f.next(g3)), v, f.vertex(w2)), (1, 5, 1));
        // Right loop 4 → 1 → 2 → 3 → 4, left loop 1' → 5 → 0 → 1'.
        assert_eq!(f.vertex(f.next(f.next(g3))), 2);
        assert_eq!(f.vertex(f.next(f.next(w2))), 0);
        assert_eq!(f.next(f.next(f.next(w2))), w2);
        assert!(!f.consumed(w2, 5));
        // An L at gate 1' → 5 consumes it.
        f.l(w2, 9).unwrap();
        assert!(f.consumed(w2, 5));
    }
}
