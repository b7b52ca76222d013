//! Spirale Reversi (Isenburg and Snoeyink, CGTA 2001): Edgebreaker
//! decompression in linear time, symbols read from last to first.
//!
//! Read backwards, the encoder's traversal builds the *unvisited* part of
//! the mesh: a triangle joins it along the edges it shares with triangles
//! visited after it, and the edge it was entered through becomes the
//! "active" gate that the previous symbol's triangle attaches to.
//!
//! ```text
//! E  new triangle, three provisional vertices; its gate is pushed
//! L  attach the right edge to the active gate (one new vertex)
//! R  attach the left edge to the active gate (one new vertex)
//! C  attach the right edge to the active gate and the left edge to the
//!    next free edge around the tip, which becomes interior
//! S  attach the right edge to the active gate, pop it, and the left edge
//!    to the gate below it (or, for an S*, to the edge its event names)
//! ```
//!
//! Finally each component's first triangle closes the remaining hole.
//! Vertices are provisional ids joined by a union-find at every glue, so
//! an S, which joins two copies of its tip, costs one union. The decoded
//! triangles then get the encoder's vertex numbers: the first triangle's
//! three vertices, then each C tip in symbol order.
//!
//! Every step is checked: the decoder reads hostile data, so a stream that
//! does not describe a closed manifold gives an error, never a panic, a
//! loop or an allocation beyond the declared (and limit-checked) counts.

use crate::prelude::*;

use super::shared::{Connectivity, Side, Symbol};
use crate::{CornerId, CornerTable, FormatError, Malformed, VertexId};

const UNSET: u32 = u32::MAX;

fn bad(why: &'static str) -> FormatError {
    FormatError::new("SWM", Malformed::BadSyntax(why))
}

struct State {
    v: Vec<u32>,
    o: Vec<u32>,
    parent: Vec<u32>,
    stack: Vec<u32>,
}

impl State {
    fn fresh(&mut self) -> u32 {
        let id = self.parent.len() as u32;
        self.parent.push(id);
        id
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let g = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = g;
            x = g;
        }
        x
    }

    /// Gives corner `c` the vertex `id`, or joins the two if it has one.
    fn assign(&mut self, c: u32, id: u32) {
        let cur = self.v[c as usize];
        if cur == UNSET {
            self.v[c as usize] = id;
        } else {
            let (a, b) = (self.find(cur), self.find(id));
            if a != b {
                self.parent[a.max(b) as usize] = a.min(b);
            }
        }
    }

    /// Glues the edge facing new corner `x` to the free edge facing `y`.
    fn glue(&mut self, x: u32, y: u32) -> Result<(), FormatError> {
        if self.o[y as usize] != UNSET || self.o[x as usize] != UNSET || x / 3 == y / 3 {
            return Err(bad("connectivity glues an edge twice"));
        }
        self.o[x as usize] = y;
        self.o[y as usize] = x;
        // x's edge runs V[n(x)] -> V[p(x)]; y's runs the other way.
        let (nx, px) = (CornerId(x).next().0, CornerId(x).prev().0);
        let (ny, py) = (CornerId(y).next().0, CornerId(y).prev().0);
        let (vy_n, vy_p) = (self.v[ny as usize], self.v[py as usize]);
        if vy_n == UNSET || vy_p == UNSET {
            return Err(bad("connectivity glues to an unfinished edge"));
        }
        self.assign(nx, vy_p);
        self.assign(px, vy_n);
        Ok(())
    }

    /// From a corner whose edge starts at a pivot vertex, turns round the
    /// pivot through glued edges to the free edge that ends at it.
    fn free_edge_ending_at_pivot(&self, mut cur: u32) -> Result<u32, FormatError> {
        for _ in 0..self.o.len() / 3 + 1 {
            let e = CornerId(cur).prev().0;
            let across = self.o[e as usize];
            if across == UNSET {
                return Ok(e);
            }
            cur = across;
        }
        Err(bad("connectivity closes a vertex fan on itself"))
    }

    fn top(&self) -> Result<u32, FormatError> {
        self.stack
            .last()
            .copied()
            .ok_or(bad("connectivity symbol with no open gate"))
    }
}

/// Rebuilds the corner table coded by `conn` (see the module docs).
///
/// The caller has checked `conn`'s counts against its `Limits`; the result
/// has `conn.triangles()` faces and `conn.vertices` vertices, numbered as
/// the encoder visited them.
pub fn decode(conn: &Connectivity) -> Result<CornerTable, FormatError> {
    for (k, e) in conn.splits.iter().enumerate() {
        let ordered = k == 0 || conn.splits[k - 1].split < e.split;
        let in_range = e.split < e.source && (e.source as usize) < conn.symbols.len();
        if !ordered || !in_range || conn.symbols[e.split as usize] != Symbol::S {
            return Err(bad("invalid handle event"));
        }
    }
    let ranges = conn
        .component_ranges()
        .ok_or(bad("connectivity symbols do not match the component count"))?;
    let nf = conn.triangles() as usize;
    let mut st = State {
        v: vec![UNSET; 3 * nf],
        o: vec![UNSET; 3 * nf],
        parent: Vec::with_capacity(nf + 2 * ranges.len()),
        stack: Vec::new(),
    };
    // Corner facing the source edge of each event, filled when the source
    // (a later symbol, so decoded earlier) is built.
    let mut event_corner = vec![UNSET; conn.splits.len()];
    let mut events_by_source: Vec<u32> = (0..conn.splits.len() as u32).collect();
    events_by_source.sort_unstable_by_key(|&e| (conn.splits[e as usize].source, e));
    let mut next_source = events_by_source.len(); // walks backwards
    let mut next_split = conn.splits.len();

    for (k, &(start, end)) in ranges.iter().enumerate().rev() {
        st.stack.clear();
        for i in (start..end).rev() {
            let t = (i + k + 1) as u32;
            let (a, b, c) = (3 * t, 3 * t + 1, 3 * t + 2);
            match conn.symbols[i] {
                Symbol::E => {
                    for x in [a, b, c] {
                        st.v[x as usize] = st.fresh();
                    }
                    st.stack.push(a);
                }
                Symbol::L => {
                    let top = st.top()?;
                    st.v[b as usize] = st.fresh();
                    st.glue(b, top)?;
                    *st.stack.last_mut().expect("top exists") = a;
                }
                Symbol::R => {
                    let top = st.top()?;
                    st.v[c as usize] = st.fresh();
                    st.glue(c, top)?;
                    *st.stack.last_mut().expect("top exists") = a;
                }
                Symbol::C => {
                    let top = st.top()?;
                    st.glue(b, top)?;
                    let y = st.free_edge_ending_at_pivot(top)?;
                    st.glue(c, y)?;
                    *st.stack.last_mut().expect("top exists") = a;
                }
                Symbol::S => {
                    let right = st.stack.pop().ok_or(bad("S with no open gate"))?;
                    st.glue(b, right)?;
                    let is_split =
                        next_split > 0 && conn.splits[next_split - 1].split as usize == i;
                    let left = if is_split {
                        next_split -= 1;
                        match event_corner[next_split] {
                            UNSET => {
                                return Err(bad("handle event names a triangle not yet built"))
                            }
                            y => y,
                        }
                    } else {
                        st.stack.pop().ok_or(bad("S with one open gate"))?
                    };
                    st.glue(c, left)?;
                    st.stack.push(a);
                }
            }
            // Record the free edges later S* triangles will glue to.
            while next_source > 0
                && conn.splits[events_by_source[next_source - 1] as usize].source as usize == i
            {
                next_source -= 1;
                let e = events_by_source[next_source] as usize;
                event_corner[e] = match conn.splits[e].side {
                    Side::Right => b,
                    Side::Left => c,
                };
            }
        }
        // Close the component with its first triangle.
        let t = (start + k) as u32;
        let (c0, c1, c2) = (3 * t, 3 * t + 1, 3 * t + 2);
        let top = st
            .stack
            .pop()
            .ok_or(bad("component ends with no open gate"))?;
        if !st.stack.is_empty() {
            return Err(bad("component ends with gates left open"));
        }
        st.glue(c1, top)?;
        let y = st.free_edge_ending_at_pivot(top)?;
        st.glue(c2, y)?;
        let z = st.free_edge_ending_at_pivot(y)?;
        st.glue(c0, z)?;
    }
    if next_source != 0 || next_split != 0 {
        return Err(bad("handle events do not match the symbols"));
    }
    finish(conn, &ranges, st)
}

/// Resolves provisional vertices and numbers them in encoder order.
///
/// Why no manifold check (no fan walk) is needed here: every vertex
/// identification the decoder makes is a [`State::glue`], which joins the
/// corner `n(x)` with `p(y)` and `p(x)` with `n(y)` for a glued pair
/// `(x, y)` — exactly the steps `c -> swing_left(c)` of the finished
/// table. Once every edge is glued (checked below), `swing_left` is a
/// permutation of the corners, so the union-find classes are precisely
/// its cycles: every vertex is one closed fan, opposite corners see the
/// same edge reversed, and `O` is an involution without fixed triangles
/// (`glue` refuses to glue an edge twice or to its own triangle). The
/// checks left are the ones the construction cannot give: a closed
/// surface, distinct vertices per triangle, and the encoder's numbering.
/// Debug builds still run the full [`CornerTable::check`].
fn finish(
    conn: &Connectivity,
    ranges: &[(usize, usize)],
    st: State,
) -> Result<CornerTable, FormatError> {
    // A union makes the larger root point to the smaller one and path
    // halving only moves a parent lower, so parent[x] <= x: one forward
    // pass turns the forest into a root per id, with no chasing.
    let mut root = st.parent;
    for x in 0..root.len() {
        root[x] = root[root[x] as usize];
    }
    let root_of = |corner: u32| -> Result<usize, FormatError> {
        let id = *st
            .v
            .get(corner as usize)
            .ok_or(bad("corner out of range"))?;
        root.get(id as usize)
            .map(|&r| r as usize)
            .ok_or(bad("a corner has no vertex"))
    };
    let mut number = vec![UNSET; root.len()];
    let mut next = 0u32;
    let mut visit = |corner: u32| -> Result<(), FormatError> {
        let r = root_of(corner)?;
        if number[r] != UNSET {
            return Err(bad("a C tip is a vertex seen before"));
        }
        number[r] = next;
        next += 1;
        Ok(())
    };
    for (k, &(start, end)) in ranges.iter().enumerate() {
        let t = (start + k) as u32;
        for x in [3 * t, 3 * t + 1, 3 * t + 2] {
            visit(x)?;
        }
        for i in start..end {
            if conn.symbols[i] == Symbol::C {
                visit(3 * (i + k + 1) as u32)?;
            }
        }
    }
    if next != conn.vertices {
        return Err(FormatError::new(
            "SWM",
            Malformed::CountMismatch {
                element: "vertices",
                declared: conn.vertices.into(),
                found: next.into(),
            },
        ));
    }
    // Each closed fan's start is its lowest corner (as `vertex_fans`
    // chooses it), i.e. the first corner of the vertex in corner order.
    let mut vertex_corner = vec![CornerId::NONE; next as usize];
    let mut v = Vec::with_capacity(st.v.len());
    for (c, &id) in st.v.iter().enumerate() {
        let n = root
            .get(id as usize)
            .and_then(|&r| number.get(r as usize))
            .copied()
            .unwrap_or(UNSET);
        if n == UNSET {
            return Err(bad("a vertex is neither a first vertex nor a C tip"));
        }
        let first = &mut vertex_corner[n as usize];
        if first.is_none() {
            *first = CornerId(c as u32);
        }
        v.push(VertexId(n));
    }
    for t in v.chunks_exact(3) {
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            return Err(bad("decoded triangle repeats a vertex"));
        }
    }
    if st.o.contains(&UNSET) {
        return Err(bad("decoded surface is not closed"));
    }
    let o: Vec<CornerId> = st.o.into_iter().map(CornerId).collect();
    let table = CornerTable::from_raw(v, o, vertex_corner);
    debug_assert_eq!(table.check(), Ok(()), "decoder built an invalid table");
    Ok(table)
}
