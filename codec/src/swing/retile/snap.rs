//! Snapping a candidate tip to a nearby border vertex (thesis §7.3: "we
//! move by adjacencies on M in a spiral-like manner, and we stop when we
//! reach the threshold distance in all the directions"; design notes §6
//! step 6c).
//!
//! The spiral is a Dijkstra search over the edges of M started from the
//! three corners of the face holding the candidate, so "near" means near
//! along the surface, never across a gap in space. It stops at the first
//! settled vertex that carries an active M′ vertex (the nearest one), or
//! once every open direction is past the limit.

use super::path::{Near, Scratch};
use super::surface::{next, Surface, NONE};
use glam::DVec3;
use std::collections::BinaryHeap;

/// The `count` nearest vertices of M, within `limit` along edges from
/// point `p` of face `f`, whose M′ vertex satisfies `wanted`; returns
/// those M′ vertices, nearest first.
pub fn nearest(
    s: &Surface,
    f: u32,
    p: DVec3,
    limit: f64,
    count: usize,
    scratch: &mut Scratch,
    wanted: impl Fn(u32) -> bool,
) -> Vec<u32> {
    let mut found = Vec::new();
    scratch.begin(s.vertex_count());
    let mut heap = BinaryHeap::new();
    for c in Surface::corners(f) {
        let x = s.v[c as usize];
        let d = p.distance(s.pos[x as usize]);
        if scratch.relax(x, d, NONE) {
            heap.push(Near(d, x));
        }
    }
    while let Some(Near(d, x)) = heap.pop() {
        s.tick(1);
        if d > limit || found.len() >= count {
            break;
        }
        if scratch.get(x) != Some(d) {
            continue;
        }
        let m = s.sample[x as usize];
        if m != NONE && wanted(m) && !found.contains(&m) {
            found.push(m);
        }
        for k in s.fan(x) {
            let y = s.v[next(k) as usize];
            let nd = d + s.pos[x as usize].distance(s.pos[y as usize]);
            if nd <= limit && scratch.relax(y, nd, x) {
                heap.push(Near(nd, y));
            }
        }
    }
    found
}
