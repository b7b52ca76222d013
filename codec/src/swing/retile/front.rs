//! The active loops of the growing M′ and the Edgebreaker labelling of a
//! snap (design notes §6 step 6d, g).
//!
//! A loop is a cycle of nodes, one node per appearance of an M′ vertex on
//! the border of the processed region, which lies on the *left* of
//! `node → next`. A vertex appears twice after an S, so loops are made of
//! nodes, not vertices. A gate is a node `gr` with `gl = next(gr)`:
//!
//! ```text
//!   … → prev(GR) → GR → GL → next(GL) → …      processed region on the left
//!                    \   /
//!                     tip                      new triangle (tip, GL, GR)
//!
//!   C  tip new:            … GR → X → GL …       next gate (X, GR)
//!   L  tip = next(GL):     … GR → W …            next gate (W, GR)
//!   R  tip = prev(GR):     … W → GL …            next gate (GL, W)
//!   E  tip = both:         loop closes           pop a gate
//!   S  tip further on:     GR → W' → …  and  … → W → GL
//!                          right loop first: gate (W', GR); push (GL, W)
//! ```

use super::surface::NONE;
use crate::edgebreaker::Symbol;

#[derive(Clone, Copy, Debug)]
struct Node {
    vertex: u32,
    next: u32,
    prev: u32,
    /// Which loop the node is on.
    lp: u32,
}

/// All loops of one component.
#[derive(Default, Debug)]
pub struct Front {
    nodes: Vec<Node>,
    /// Per M′ vertex: its live nodes (usually one).
    at: Vec<Vec<u32>>,
    /// Loop ids handed out so far.
    loops: u32,
}

/// Where the snapped tip sits relative to the gate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// On this loop: the label (L, R, E or S) and the tip's node.
    Loop(Symbol, u32),
    /// Not on this loop: on another one (the tip's node there), which
    /// only a handle makes possible; the triangle is an S\* that merges
    /// the two loops.
    Other(u32),
    /// On no active loop.
    Nowhere,
}

impl Front {
    fn push(&mut self, vertex: u32, lp: u32) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            vertex,
            next: NONE,
            prev: NONE,
            lp,
        });
        if self.at.len() <= vertex as usize {
            self.at.resize(vertex as usize + 1, Vec::new());
        }
        self.at[vertex as usize].push(id);
        id
    }

    fn kill(&mut self, n: u32) {
        let v = self.nodes[n as usize].vertex as usize;
        self.at[v].retain(|&k| k != n);
    }

    fn link(&mut self, a: u32, b: u32) {
        self.nodes[a as usize].next = b;
        self.nodes[b as usize].prev = a;
    }

    /// Starts a loop through `verts` (the first triangle, CCW); returns
    /// the node of each vertex.
    pub fn start(&mut self, verts: &[u32]) -> Vec<u32> {
        let lp = self.loops;
        self.loops += 1;
        let ids: Vec<u32> = verts.iter().map(|&v| self.push(v, lp)).collect();
        for i in 0..ids.len() {
            self.link(ids[i], ids[(i + 1) % ids.len()]);
        }
        ids
    }

    pub fn vertex(&self, n: u32) -> u32 {
        self.nodes[n as usize].vertex
    }

    pub fn next(&self, n: u32) -> u32 {
        self.nodes[n as usize].next
    }

    pub fn prev(&self, n: u32) -> u32 {
        self.nodes[n as usize].prev
    }

    /// The loop of node `n`.
    pub fn loop_of(&self, n: u32) -> u32 {
        self.nodes[n as usize].lp
    }

    /// The M′ vertex is on loop `lp`.
    pub fn is_on(&self, v: u32, lp: u32) -> bool {
        self.at
            .get(v as usize)
            .is_some_and(|ns| ns.iter().any(|&n| self.nodes[n as usize].lp == lp))
    }

    /// Classifies tip vertex `w` for gate `gr` (GL = next(gr)).
    pub fn place(&self, gr: u32, w: u32) -> Place {
        let gl = self.next(gr);
        let (after, before) = (self.next(gl), self.prev(gr));
        let (is_after, is_before) = (self.vertex(after) == w, self.vertex(before) == w);
        match (is_after, is_before) {
            (true, true) => return Place::Loop(Symbol::E, after),
            (true, false) => return Place::Loop(Symbol::L, after),
            (false, true) => return Place::Loop(Symbol::R, before),
            _ => {}
        }
        // Further along this loop? Walk it once (S is rare).
        let mut n = self.next(after);
        while n != gr && n != gl {
            if self.vertex(n) == w {
                return Place::Loop(Symbol::S, n);
            }
            n = self.next(n);
        }
        let lp = self.loop_of(gr);
        self.at
            .get(w as usize)
            .and_then(|ns| {
                ns.iter()
                    .copied()
                    .find(|&k| self.nodes[k as usize].lp != lp)
            })
            .map_or(Place::Nowhere, Place::Other)
    }

    /// The M′ vertex is on some active loop.
    pub fn is_active(&self, v: u32) -> bool {
        self.at.get(v as usize).is_some_and(|ns| !ns.is_empty())
    }

    /// Applies an S\* with the tip's node `w` on another loop: the same
    /// relinking as an S, which here joins the two loops into one
    ///
    /// ```text
    ///   … → GR → GL → …   and   … → W → W⁺ → …
    ///   become  … → GR → W' → W⁺ → … (the other loop) … → W → GL → …
    /// ```
    ///
    /// Returns the gate to continue with (GR, right first, as Edgebreaker)
    /// and the one to remember (W → GL).
    pub fn apply_merge(&mut self, gr: u32, w: u32) -> (u32, u32) {
        let gl = self.next(gr);
        let lp = self.loop_of(gr);
        let vertex = self.vertex(w);
        let after = self.next(w);
        let w2 = self.push(vertex, lp);
        self.link(gr, w2);
        self.link(w2, after);
        self.link(w, gl);
        // The other loop's nodes, now between W' and W, join this loop.
        let mut n = after;
        while n != gl {
            self.nodes[n as usize].lp = lp;
            n = self.next(n);
        }
        (gr, w)
    }

    /// Applies a C: inserts new vertex `x` into the gate; returns the next
    /// gate (the node of GR, now followed by X).
    pub fn apply_c(&mut self, gr: u32, x: u32) -> u32 {
        let gl = self.next(gr);
        let nx = self.push(x, self.loop_of(gr));
        self.link(gr, nx);
        self.link(nx, gl);
        gr
    }

    /// Applies L, R, E or S with the tip's node `w`; returns the gate to
    /// continue with (`None` after E) and, for S, the gate to remember.
    pub fn apply(&mut self, gr: u32, symbol: Symbol, w: u32) -> (Option<u32>, Option<u32>) {
        let gl = self.next(gr);
        match symbol {
            Symbol::L => {
                self.kill(gl);
                self.link(gr, w);
                (Some(gr), None)
            }
            Symbol::R => {
                self.kill(gr);
                self.link(w, gl);
                (Some(w), None)
            }
            Symbol::E => {
                for n in [gr, gl, w] {
                    self.kill(n);
                }
                (None, None)
            }
            Symbol::S => {
                let vertex = self.vertex(w);
                let after = self.next(w);
                let w2 = self.push(vertex, self.loop_of(gr));
                self.link(gr, w2);
                self.link(w2, after);
                self.link(w, gl);
                self.relabel_smaller(gr, w);
                (Some(gr), Some(w))
            }
            Symbol::C => unreachable!("C goes through apply_c"),
        }
    }

    /// Gives a new id to the shorter of the loops through `a` and `b`,
    /// walking both in step so the cost is that of the shorter one.
    fn relabel_smaller(&mut self, a: u32, b: u32) {
        let (mut x, mut y) = (self.next(a), self.next(b));
        let shorter = loop {
            if x == a {
                break a;
            }
            if y == b {
                break b;
            }
            x = self.next(x);
            y = self.next(y);
        };
        let lp = self.loops;
        self.loops += 1;
        let mut n = shorter;
        loop {
            self.nodes[n as usize].lp = lp;
            n = self.next(n);
            if n == shorter {
                break;
            }
        }
    }
}
