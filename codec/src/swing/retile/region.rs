//! Marking a triangloid and checking it (thesis §7.3, "Validity tests";
//! design notes §6 step 8).
//!
//! The triangloid of an M′ triangle is the part of M bounded by its three
//! paths, taken counterclockwise. Its faces are found by marking the face
//! on the left of every boundary edge, then flooding across edges that
//! are not path edges. It is valid when
//! * no seed face is owned already (the paths run through free surface);
//! * every path edge the flood meets is one of its own boundary edges,
//!   met from the left: touching any other path, or its own boundary from
//!   the right, means the three paths do not enclose a disk of free faces
//!   (the "handle end" case of thesis Fig. 7.5);
//! * its Euler characteristic V − E + F is 1 (a handle lying wholly
//!   inside passes the previous test but not this one);
//! * its area stays below a bound the caller sets from L: a region much
//!   larger than its triangle means the front closed around free surface
//!   (a check the thesis does not need, as it never closes a gate by
//!   force; this retiler's fallbacks can).

use super::marks::Marks;
use super::surface::{face, prev, Surface, NONE};

/// Why a triangloid was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Invalid {
    /// A boundary edge is not an edge of M.
    Broken,
    /// The region reaches a face that is not free or not its own.
    Leaks,
    /// The region is not a disk.
    NotDisk,
    /// The region is far larger than a triangle of edge L: the paths
    /// closed around free surface that other triangles should take.
    TooLarge,
}

/// Reusable buffers.
#[derive(Default)]
pub struct Flood {
    stack: Vec<u32>,
    faces: Vec<u32>,
    vertices: Marks,
}

impl Flood {
    /// The faces of the region last claimed.
    pub fn faces(&self) -> &[u32] {
        &self.faces
    }
}

/// Claims for triangle `id` the region left of the closed chain `boundary`
/// (M vertices, first not repeated at the end). On failure the claim is
/// left half done: the caller abandons the whole retiling.
pub fn claim(
    s: &mut Surface,
    boundary: &[u32],
    id: u32,
    max_area: f64,
    fl: &mut Flood,
) -> Result<usize, Invalid> {
    fl.stack.clear();
    fl.faces.clear();
    let n = boundary.len();
    for i in 0..n {
        let (a, b) = (boundary[i], boundary[(i + 1) % n]);
        let k = s.corner_before(a, b).ok_or(Invalid::Broken)?;
        if !s.path[prev(k) as usize] {
            return Err(Invalid::Broken);
        }
        let f = face(k);
        match s.owner[f as usize] {
            NONE => {
                s.owner[f as usize] = id;
                fl.stack.push(f);
            }
            o if o == id => {}
            _ => return Err(Invalid::Leaks),
        }
    }
    let mut boundary_edges = 0usize;
    let mut area2 = 0.0;
    while let Some(f) = fl.stack.pop() {
        s.tick(1);
        fl.faces.push(f);
        area2 += s.double_area(f);
        if area2 > 2.0 * max_area {
            return Err(Invalid::TooLarge);
        }
        for c in Surface::corners(f) {
            let g = face(s.opp[c as usize]);
            if s.path[c as usize] {
                boundary_edges += 1;
                if s.owner[g as usize] == id {
                    // Own faces on both sides of a path edge.
                    return Err(Invalid::Leaks);
                }
                continue;
            }
            match s.owner[g as usize] {
                NONE => {
                    s.owner[g as usize] = id;
                    fl.stack.push(g);
                }
                o if o == id => {}
                _ => return Err(Invalid::Leaks),
            }
        }
    }
    if boundary_edges != n {
        return Err(Invalid::Leaks);
    }
    // Euler characteristic: E = (3F + n) / 2 as every inner edge is seen
    // twice and every boundary edge once.
    fl.vertices.clear(s.vertex_count());
    let mut vertices = 0usize;
    for &f in &fl.faces {
        for c in Surface::corners(f) {
            if fl.vertices.insert(s.v[c as usize]) {
                vertices += 1;
            }
        }
    }
    let faces = fl.faces.len();
    let edges = (3 * faces + n) / 2;
    if vertices + faces != edges + 1 {
        return Err(Invalid::NotDisk);
    }
    Ok(faces)
}

/// Gives back the faces a failed `claim` for `id` marked.
pub fn release(s: &mut Surface, id: u32, fl: &mut Flood) {
    for &f in fl.faces.iter().chain(&fl.stack) {
        if s.owner[f as usize] == id {
            s.owner[f as usize] = NONE;
        }
    }
    fl.faces.clear();
    fl.stack.clear();
}
