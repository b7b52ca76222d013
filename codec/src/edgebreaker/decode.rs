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
//! The decoder can take its symbols from a stream as it goes
//! ([`decode_from`] with a [`SymbolSource`]), telling the source the
//! state each symbol is decoded in: the triangles already built around
//! the active gate's start vertex (the tip a C would close) and its end
//! vertex, counted per union-find class, which `CLRD` (format 1.1) uses
//! as the symbol's context. Plain [`decode`] keeps no counts.
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
    /// Corners of each provisional vertex so far (kept only when contexts
    /// are asked for; valid at union-find roots).
    corners: Vec<u32>,
    /// Whether `corners` is kept.
    counting: bool,
    stack: Vec<u32>,
}

/// Largest count of corners a context tells apart ([`State::context`]).
const DEGREE_CAP: u32 = 7;

/// Contexts of [`SymbolSource::symbol`]: 0 when no gate is open (the
/// symbol can only be an E), else one per pair of capped corner counts.
pub const CONTEXTS: usize = 1 + ((DEGREE_CAP + 1) * (DEGREE_CAP + 1)) as usize;

/// Where the decoder takes the symbols from, last to first.
pub trait SymbolSource {
    /// Whether the decoder works out each symbol's context (otherwise it
    /// passes 0).
    const CONTEXTS: bool;
    /// Symbol `i`, in the decoder's state `ctx` (see [`CONTEXTS`]).
    fn symbol(&mut self, i: usize, ctx: usize) -> Result<Symbol, FormatError>;
}

/// The symbols of a [`Connectivity`], no contexts.
struct Known<'a>(&'a [Symbol]);

impl SymbolSource for Known<'_> {
    const CONTEXTS: bool = false;
    #[inline]
    fn symbol(&mut self, i: usize, _ctx: usize) -> Result<Symbol, FormatError> {
        Ok(self.0[i])
    }
}

/// The symbols of a [`Connectivity`], each context recorded.
struct Recorded<'a> {
    symbols: &'a [Symbol],
    contexts: Vec<u8>,
}

impl SymbolSource for Recorded<'_> {
    const CONTEXTS: bool = true;
    #[inline]
    fn symbol(&mut self, i: usize, ctx: usize) -> Result<Symbol, FormatError> {
        self.contexts.push(ctx as u8);
        Ok(self.symbols[i])
    }
}

impl State {
    fn fresh(&mut self) -> u32 {
        let id = self.parent.len() as u32;
        self.parent.push(id);
        if self.counting {
            self.corners.push(0);
        }
        id
    }

    /// Gives the unassigned corner `c` a new provisional vertex.
    #[inline]
    fn fresh_at(&mut self, c: u32) {
        let id = self.fresh();
        self.v[c as usize] = id;
        if self.counting {
            self.corners[id as usize] = 1;
        }
    }

    /// The decoder's state at the active gate, as a context: the corners
    /// already built around the gate's two vertices (its start, the pivot
    /// a C closes, then its end), each capped at [`DEGREE_CAP`]. Read
    /// backwards, a C is the triangle that completes its tip's fan, so on
    /// a mesh of regular valence the count at the pivot all but names the
    /// symbol.
    fn context(&mut self) -> usize {
        let Some(&top) = self.stack.last() else {
            return 0;
        };
        let mut count = |c: u32| {
            let id = self.v[c as usize];
            if id == UNSET {
                return 0;
            }
            let r = self.find(id);
            self.corners[r as usize].min(DEGREE_CAP)
        };
        let start = count(CornerId(top).next().0);
        let end = count(CornerId(top).prev().0);
        1 + (start * (DEGREE_CAP + 1) + end) as usize
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
            if self.counting {
                let r = self.find(id);
                self.corners[r as usize] += 1;
            }
        } else {
            let (a, b) = (self.find(cur), self.find(id));
            if a != b {
                self.parent[a.max(b) as usize] = a.min(b);
                if self.counting {
                    let moved = self.corners[a.max(b) as usize];
                    self.corners[a.min(b) as usize] += moved;
                }
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
    let ranges = conn
        .component_ranges()
        .ok_or(bad("connectivity symbols do not match the component count"))?;
    let mut symbols = Vec::new();
    decode_from(conn, &ranges, &mut Known(&conn.symbols), &mut symbols)
}

/// [`decode`], also returning the context of every symbol in the order
/// the decoder asks for them (components last to first, each from its
/// last symbol to its first): what `CLRD` codes them with.
pub fn decode_recording(conn: &Connectivity) -> Result<(CornerTable, Vec<u8>), FormatError> {
    let ranges = conn
        .component_ranges()
        .ok_or(bad("connectivity symbols do not match the component count"))?;
    let mut src = Recorded {
        symbols: &conn.symbols,
        contexts: Vec::with_capacity(conn.symbols.len()),
    };
    let mut symbols = Vec::new();
    let table = decode_from(conn, &ranges, &mut src, &mut symbols)?;
    Ok((table, src.contexts))
}

/// Symbol ranges of components whose symbol counts are `counts`, or
/// `None` if they do not add up to `total`.
pub fn ranges_of(counts: &[u64], total: usize) -> Option<Vec<(usize, usize)>> {
    let mut ranges = Vec::with_capacity(counts.len());
    let mut start = 0usize;
    for &n in counts {
        let end = start.checked_add(usize::try_from(n).ok()?)?;
        ranges.push((start, end));
        start = end;
    }
    (start == total).then_some(ranges)
}

/// The decoder proper: `conn`'s symbols are ignored and taken from `src`
/// instead, for components `ranges` (which must cover `0..symbol count`
/// in order); `conn.symbols.len()` is not used either, the count being
/// the end of the last range. `symbols` receives every symbol decoded.
/// The ranges are checked against the decoded symbols.
pub fn decode_from<S: SymbolSource>(
    conn: &Connectivity,
    ranges: &[(usize, usize)],
    src: &mut S,
    symbols: &mut Vec<Symbol>,
) -> Result<CornerTable, FormatError> {
    let count = ranges.last().map_or(0, |r| r.1);
    if ranges.len() != conn.components as usize {
        return Err(bad("connectivity symbols do not match the component count"));
    }
    for (k, e) in conn.splits.iter().enumerate() {
        let ordered = k == 0 || conn.splits[k - 1].split < e.split;
        let in_range = e.split < e.source && (e.source as usize) < count;
        if !ordered || !in_range {
            return Err(bad("invalid handle event"));
        }
    }
    symbols.clear();
    symbols.resize(count, Symbol::C);
    let nf = count + ranges.len();
    let mut st = State {
        v: vec![UNSET; 3 * nf],
        o: vec![UNSET; 3 * nf],
        parent: Vec::with_capacity(nf + 2 * ranges.len()),
        corners: Vec::with_capacity(if S::CONTEXTS {
            nf + 2 * ranges.len()
        } else {
            0
        }),
        counting: S::CONTEXTS,
        stack: Vec::new(),
    };
    // Corner facing the source edge of each event, filled when the source
    // (a later symbol, so decoded earlier) is built.
    let mut event_corner = vec![UNSET; conn.splits.len()];
    let mut events_by_source: Vec<u32> = (0..conn.splits.len() as u32).collect();
    // `e` makes the key unique.
    crate::sort::sort_by_unique_key(&mut events_by_source, |&e| {
        (conn.splits[e as usize].source, e)
    });
    let mut next_source = events_by_source.len(); // walks backwards
    let mut next_split = conn.splits.len();

    for (k, &(start, end)) in ranges.iter().enumerate().rev() {
        st.stack.clear();
        for i in (start..end).rev() {
            let t = (i + k + 1) as u32;
            let (a, b, c) = (3 * t, 3 * t + 1, 3 * t + 2);
            let ctx = if S::CONTEXTS { st.context() } else { 0 };
            let symbol = src.symbol(i, ctx)?;
            symbols[i] = symbol;
            match symbol {
                Symbol::E => {
                    for x in [a, b, c] {
                        st.fresh_at(x);
                    }
                    st.stack.push(a);
                }
                Symbol::L => {
                    let top = st.top()?;
                    st.fresh_at(b);
                    st.glue(b, top)?;
                    *st.stack.last_mut().expect("top exists") = a;
                }
                Symbol::R => {
                    let top = st.top()?;
                    st.fresh_at(c);
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
    if S::CONTEXTS {
        // Coded ranges must be the ones the symbols imply.
        let decoded = Connectivity {
            symbols: core::mem::take(symbols),
            splits: conn.splits.clone(),
            components: conn.components,
            vertices: conn.vertices,
        };
        if decoded.component_ranges().as_deref() != Some(ranges) {
            return Err(bad("component lengths do not match the symbols"));
        }
        *symbols = decoded.symbols;
    }
    finish(symbols, conn.vertices, ranges, st)
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
    symbols: &[Symbol],
    vertices: u32,
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
        for (i, &s) in symbols.iter().enumerate().take(end).skip(start) {
            if s == Symbol::C {
                visit(3 * (i + k + 1) as u32)?;
            }
        }
    }
    if next != vertices {
        return Err(FormatError::new(
            "SWM",
            Malformed::CountMismatch {
                element: "vertices",
                declared: vertices.into(),
                found: next.into(),
            },
        ));
    }
    // Each closed fan's start is its lowest corner (as `vertex_fans`
    // chooses it), i.e. the first corner of the vertex in corner order.
    let mut vertex_corner = vec![CornerId::NONE; next as usize];
    // Provisional ids become vertex numbers in place: the corner array is
    // the largest the decoder holds, and a second one would be fresh
    // memory the kernel must fault in and zero.
    let mut v = st.v;
    for (c, id) in v.iter_mut().enumerate() {
        let n = root
            .get(*id as usize)
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
        *id = n;
    }
    // Same size and alignment: collected in place.
    let v: Vec<VertexId> = v.into_iter().map(VertexId).collect();
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
