//! Edgebreaker compression over a corner table (SMI 2001 form), right
//! branch first at S, with Draco-style events for handles.
//!
//! Per component: mark the start triangle and its three vertices, then
//! visit triangles from the gate facing corner n(c0). For a visited tip
//! corner c, with r(c) = O[n(c)] and l(c) = O[p(c)]:
//!
//! ```text
//! tip unvisited            -> C, continue at r(c)
//! right done, left done    -> E, pop a remembered gate
//! right done               -> R, continue at l(c)
//! left done                -> L, continue at r(c)
//! neither                  -> S, remember l(c), continue at r(c)
//! ```
//!
//! A remembered gate whose triangle was visited meanwhile belongs to an
//! S* (a handle): the right branch came round to the S triangle's left
//! edge. It is skipped, and a [`SplitEvent`] tells the decoder which later
//! triangle that edge is glued to. On genus 0 this never happens.

use crate::prelude::*;

use super::shared::{Connectivity, Side, SplitEvent, Symbol};
use crate::{CornerId, CornerTable, TopologyError, VertexId};

/// Result of [`encode`]: the coded connectivity and how it maps the input.
#[derive(Clone, Debug)]
pub struct Encoded {
    /// Symbols and side information.
    pub connectivity: Connectivity,
    /// Decoded vertex k is input vertex `vertex_order[k]`.
    pub vertex_order: Vec<VertexId>,
    /// Decoded triangle t is the input triangle of `tip_corners[t]`, with
    /// that corner first (decoded corner 3t), then its next and previous.
    pub tip_corners: Vec<CornerId>,
}

/// Compresses a closed (no boundary), oriented manifold.
///
/// Components are taken in order of their lowest face; each starts at
/// corner 0 of that face. Fails if the table has a boundary edge.
pub fn encode(table: &CornerTable) -> Result<Encoded, TopologyError> {
    if table.opposites().iter().any(|o| o.is_none()) {
        // fill_holes first; a boundary here is the caller's mistake.
        let edges = table.opposites().iter().filter(|o| o.is_none()).count() as u64;
        return Err(TopologyError::NonManifold { edges, vertices: 0 });
    }
    let nf = table.face_count();
    let mut face_visit = vec![u32::MAX; nf]; // visit number per face
    let mut vertex_seen = vec![false; table.vertex_count()];
    let mut symbols = Vec::with_capacity(nf);
    let mut splits = Vec::new();
    let mut vertex_order = Vec::with_capacity(table.vertex_count());
    let mut tip_corners = Vec::with_capacity(nf);
    let mut components = 0u32;
    // Remembered left gates: (corner, symbol index of the S that left it).
    let mut stack: Vec<(CornerId, u32)> = Vec::new();

    for f0 in 0..nf {
        if face_visit[f0] != u32::MAX {
            continue;
        }
        components += 1;
        let c0 = CornerId(3 * f0 as u32);
        face_visit[f0] = tip_corners.len() as u32;
        tip_corners.push(c0);
        for c in [c0, c0.next(), c0.prev()] {
            vertex_seen[table.vertex(c).idx()] = true;
            vertex_order.push(table.vertex(c));
        }
        let mut next = Some(table.opposite(c0.next()));
        while let Some(mut c) = next.take() {
            loop {
                let t = c.face().idx();
                face_visit[t] = tip_corners.len() as u32;
                tip_corners.push(c);
                let here = symbols.len() as u32;
                let v = table.vertex(c);
                if !vertex_seen[v.idx()] {
                    vertex_seen[v.idx()] = true;
                    vertex_order.push(v);
                    symbols.push(Symbol::C);
                    c = table.right(c);
                    continue;
                }
                let right_done = face_visit[table.right(c).face().idx()] != u32::MAX;
                let left_done = face_visit[table.left(c).face().idx()] != u32::MAX;
                match (right_done, left_done) {
                    (true, true) => {
                        symbols.push(Symbol::E);
                        break;
                    }
                    (true, false) => {
                        symbols.push(Symbol::R);
                        c = table.left(c);
                    }
                    (false, true) => {
                        symbols.push(Symbol::L);
                        c = table.right(c);
                    }
                    (false, false) => {
                        symbols.push(Symbol::S);
                        stack.push((table.left(c), here));
                        c = table.right(c);
                    }
                }
            }
            // Resume at the most recent open gate, skipping S* gates.
            while let Some((gate, split)) = stack.pop() {
                let visit = face_visit[gate.face().idx()];
                if visit == u32::MAX {
                    next = Some(gate);
                    break;
                }
                // The gate's triangle was reached round a handle; `gate` is
                // its corner facing the S triangle's left edge.
                let source_tip = tip_corners[visit as usize];
                let side = if gate == source_tip.next() {
                    Side::Right
                } else {
                    Side::Left
                };
                // Symbol index of a visited triangle = visit number minus the
                // first triangles of the components so far (all started
                // before it, as they are in visiting order).
                let source = visit - components;
                splits.push(SplitEvent {
                    split,
                    source,
                    side,
                });
            }
        }
    }
    splits.sort_unstable();
    Ok(Encoded {
        connectivity: Connectivity {
            symbols,
            splits,
            components,
            vertices: vertex_order.len() as u32,
        },
        vertex_order,
        tip_corners,
    })
}
