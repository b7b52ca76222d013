//! Splitting the cleaned input into the closed surfaces the retiler works
//! on (design notes §6, ambiguity iii).
//!
//! The retiler needs a closed manifold: it grows M′ until every face of M
//! is claimed. Each connected component is therefore retiled on its own,
//! and each boundary loop of a component is first closed by a temporary
//! **patch**: a membrane of rings spanning the loop, relaxed towards a
//! discrete harmonic surface with the loop held fixed, so the retiler
//! meets a smooth cap rather than a cone. Patch faces carry their hole's
//! number; the retiled triangles that land mostly on a patch become the
//! hole mask (`mask`), and the decoder drops them again. The patch of
//! the longest loop is claimed at once by the fan a retiling starts
//! with (`boundary`), whose triangles are that hole's mask.
//!
//! ```text
//!   loop a_0 … a_{n−1} (edges a_i → a_{i+1} belong to the input)
//!
//!   ring 0 (the loop)   a_i ───────── a_{i+1}
//!                        │  ╲           │        quad split into
//!   ring 1              P_1,i ─────── P_1,i+1    [O_{i+1}, O_i, I_i]
//!                        …                       [O_{i+1}, I_i, I_{i+1}]
//!   ring R              the centre g (one vertex, a fan)
//! ```
//!
//! Invariants: every patch edge has exactly one partner (the result is a
//! closed oriented manifold when the component was an oriented manifold
//! with boundary); the input's own faces come first, in their order, so
//! face numbers of the component are unchanged.

use crate::{CornerTable, TopologyError, TriMesh};
use glam::DVec3;

use super::surface::NONE;

/// Rings of a patch at most (the centre included).
const MAX_RINGS: usize = 24;
/// New vertices a patch or shell wall may add beyond its loop's own: a
/// loop of n vertices gets at most this many over n rows (but at least
/// one), so a 100,000-gon's patch stays linear in its loop, not 24 or 96
/// times it. Only loops of more than about 680 vertices are affected.
const PATCH_VERTICES: usize = 1 << 16;
/// Relaxation sweeps over the patch's inner vertices.
const SWEEPS: usize = 60;
/// Height of the patch's dome over its membrane, in loop radii. A flat
/// membrane can lie on the surface it closes; the dome keeps the two
/// sheets apart and caps a hole in a round shape roughly as the missing
/// part would. Its profile is a quarter circle, steep at the loop: a
/// profile flat at the loop (sin², tried first) leaves the patch at a
/// knife edge along the loop, where the retiler found no tips.
const DOME: f64 = 0.4;

/// One connected component, closed.
#[derive(Clone, Debug)]
pub struct Piece {
    /// The component's faces, then its patches.
    pub mesh: TriMesh,
    /// The closed corner table of `mesh`.
    pub table: CornerTable,
    /// Per face of `mesh`: the hole it patches (numbered within the
    /// piece), or `NONE`.
    pub patch: Vec<u32>,
    /// Boundary loops the component had.
    pub holes: u32,
    /// Genus of the closed surface.
    pub genus: i64,
    /// The component as the input had it (open), for the lossless
    /// fallback.
    pub original: TriMesh,
    /// Area of `mesh` (patches included).
    pub area: f64,
    /// The vertex of the cleaned input each of `original`'s vertices is
    /// (they come first in `mesh` too; patches' and rebuilt fans' own
    /// vertices follow).
    pub cleaned: Vec<u32>,
    /// Set by the automatic mode when the simplified method serves this
    /// component better than retiling: its simplification, which goes to
    /// `REST` unretiled, and the quantization whose resolution over the
    /// simplification's own bounding box it keeps at least.
    pub keep: Option<(TriMesh, u8)>,
}

/// Splits a clean mesh into its components and closes each one.
pub fn pieces(mesh: &TriMesh, table: &CornerTable) -> Result<Vec<Piece>, TopologyError> {
    let (label, count) = table.component_labels();
    let mut faces: Vec<Vec<u32>> = vec![Vec::new(); count as usize];
    for (f, &k) in label.iter().enumerate() {
        faces[k as usize].push(f as u32);
    }
    faces.iter().map(|fs| piece(mesh, fs)).collect()
}

fn piece(mesh: &TriMesh, faces: &[u32]) -> Result<Piece, TopologyError> {
    // The component alone, its vertices in their input order (a mesh of
    // one component keeps its numbering, so its start vertex too).
    let mut used: Vec<u32> = faces
        .iter()
        .flat_map(|&f| mesh.triangles[f as usize])
        .collect();
    used.sort_unstable();
    used.dedup();
    let remap: std::collections::HashMap<u32, u32> = used
        .iter()
        .enumerate()
        .map(|(k, &v)| (v, k as u32))
        .collect();
    let positions = used.iter().map(|&v| mesh.positions[v as usize]).collect();
    let triangles: Vec<[u32; 3]> = faces
        .iter()
        .map(|&f| mesh.triangles[f as usize].map(|v| remap[&v]))
        .collect();
    let original = TriMesh::new(positions, triangles);
    let open = CornerTable::new(&original.triangles, original.vertex_count())?;
    let loops = open.boundary_loops();
    let mut closed = original.clone();
    let mut patch = vec![NONE; closed.face_count()];
    for (h, lp) in loops.iter().enumerate() {
        // Corner c faces the input edge V[n(c)] → V[p(c)]; consecutive
        // corners of a loop chain these edges head to tail.
        let ring: Vec<u32> = lp.iter().map(|&c| open.vertex(c.next()).0).collect();
        let before = closed.face_count();
        match flat_disk(&original, loops.len()) {
            Some(normal) => add_shell(&mut closed, &ring, normal),
            None => add_patch(&mut closed, &ring),
        }
        patch.resize(closed.face_count(), NONE);
        patch[before..].iter_mut().for_each(|p| *p = h as u32);
    }
    super::valence::cap(&mut closed, &mut patch);
    let table = CornerTable::new(&closed.triangles, closed.vertex_count())?;
    if table.opposites().iter().any(|o| o.is_none()) {
        let edges = table.opposites().iter().filter(|o| o.is_none()).count() as u64;
        return Err(TopologyError::NonManifold { edges, vertices: 0 });
    }
    let (v, f) = (closed.vertex_count() as i64, closed.face_count() as i64);
    let genus = (2 - (v - 3 * f / 2 + f)) / 2;
    let area = closed.area();
    Ok(Piece {
        mesh: closed,
        table,
        patch,
        holes: loops.len() as u32,
        genus,
        original,
        area,
        cleaned: used,
        keep: None,
    })
}

/// The unit normal of a component that is one flat disk (a single
/// boundary loop, every vertex within `FLAT`·(its extent) of one plane),
/// facing the side its faces face; `None` otherwise.
fn flat_disk(m: &TriMesh, loops: usize) -> Option<DVec3> {
    if loops != 1 {
        return None;
    }
    let cross: DVec3 = (0..m.face_count() as u32)
        .map(|f| m.face_cross(crate::FaceId(f)))
        .sum();
    let n = cross.normalize_or_zero();
    let (lo, hi) = m.bbox()?;
    let extent = (hi - lo).length();
    let heights = m
        .positions
        .iter()
        .map(|p| DVec3::from(p.map(f64::from)).dot(n));
    let (min, max) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| {
        (a.min(h), b.max(h))
    });
    (n != DVec3::ZERO && max - min <= FLAT * extent).then_some(n)
}

/// A disk flatter than this (height range over bounding-box diagonal) is
/// closed by a shell rather than a membrane.
const FLAT: f64 = 0.02;
/// Thickness of a flat disk's shell, in loop radii.
const SHELL: f64 = 0.25;

fn point(mesh: &TriMesh, v: u32) -> DVec3 {
    DVec3::from(mesh.positions[v as usize].map(f64::from))
}

/// A boundary loop as both closers measure it: its points, their centroid,
/// mean distance to it, and mean edge length.
struct Loop {
    outer: Vec<DVec3>,
    centre: DVec3,
    radius: f64,
    edge: f64,
}

impl Loop {
    fn new(mesh: &TriMesh, ring: &[u32]) -> Loop {
        let outer: Vec<DVec3> = ring.iter().map(|&v| point(mesh, v)).collect();
        let n = outer.len() as f64;
        let centre = outer.iter().sum::<DVec3>() / n;
        let radius = outer.iter().map(|p| p.distance(centre)).sum::<f64>() / n;
        let edge = (0..outer.len())
            .map(|i| outer[i].distance(outer[(i + 1) % outer.len()]))
            .sum::<f64>()
            / n;
        Loop {
            outer,
            centre,
            radius,
            edge,
        }
    }

    /// Steps of about one loop edge across `length`, 1 to `max`.
    fn steps(&self, length: f64, max: usize) -> usize {
        if self.edge > 0.0 {
            ((length / self.edge).ceil() as usize).clamp(1, max)
        } else {
            1
        }
    }
}

/// Appends to `mesh` (one flat disk facing `normal`) a shell closing its
/// loop `ring`: a wall down from the loop and a mirror copy of the disk
/// at its foot, faces reversed. A membrane spanning a flat disk's loop
/// would lie on the disk itself, and for a loop that is not convex the
/// membrane folds over itself; the copy of the disk is the one closing
/// surface that never folds, and the wall keeps the two sheets
/// `SHELL` radii apart.
///
/// ```text
///   a_i ──── a_{i+1}      the disk (input)
///    │ ╲       │          wall rows of about one loop edge each,
///   a'_i ─── a'_{i+1}     quads split [a_{i+1}, a_i, a'_i], [a_{i+1}, a'_i, a'_{i+1}]
///                         the copy at the foot, reversed
/// ```
fn add_shell(mesh: &mut TriMesh, ring: &[u32], normal: DVec3) {
    let lp = Loop::new(mesh, ring);
    let (n, outer) = (ring.len(), &lp.outer);
    let depth = SHELL * lp.radius;
    let budget = (4 * MAX_RINGS).min(PATCH_VERTICES / n).max(1);
    let rows = lp.steps(depth, 4 * MAX_RINGS);
    let disk_vertices = mesh.vertex_count() as u32;
    let disk_faces = mesh.face_count();
    // The copy: vertex v becomes v + disk_vertices.
    for v in 0..disk_vertices {
        let p = point(mesh, v) - normal * depth;
        mesh.positions.push(p.as_vec3().to_array());
    }
    for f in 0..disk_faces {
        let [a, b, c] = mesh.triangles[f];
        mesh.triangles
            .push([a + disk_vertices, c + disk_vertices, b + disk_vertices]);
    }
    let copy: Vec<u32> = ring.iter().map(|&v| v + disk_vertices).collect();
    if rows > budget {
        // The budget cuts the rows: full rows would be slivers that every
        // path across the wall crosses one by one.
        graded_wall(mesh, ring, &copy, outer, normal, depth);
        return;
    }
    // Wall rows: row 0 is the loop, row `rows` the copy's loop.
    let mut ids: Vec<Vec<u32>> = vec![ring.to_vec()];
    for k in 1..rows {
        let drop = normal * (depth * k as f64 / rows as f64);
        ids.push(
            outer
                .iter()
                .map(|&p| {
                    mesh.positions.push((p - drop).as_vec3().to_array());
                    mesh.positions.len() as u32 - 1
                })
                .collect(),
        );
    }
    ids.push(copy);
    for k in 0..rows {
        let (o, inn) = (&ids[k], &ids[k + 1]);
        for i in 0..n {
            let j = (i + 1) % n;
            mesh.triangles.push([o[j], o[i], inn[i]]);
            mesh.triangles.push([o[j], inn[i], inn[j]]);
        }
    }
}

/// Fewest loop vertices at the middle of a graded wall.
const WALL_WAIST: usize = 64;

/// The wall of a shell whose loop is too long for full rows (more than
/// about 680 vertices): rows that halve the loop's vertex count down to
/// the middle of the wall and double it back to the copy's loop, each as
/// high as its vertices are apart, so the wall's triangles are about as
/// high as wide and a path across the wall crosses a few of them, not
/// one sliver per loop edge. Each halving keeps every other vertex (the
/// last group spans three edges when the count is odd), as the fans of
/// `valence` do.
fn graded_wall(
    mesh: &mut TriMesh,
    ring: &[u32],
    copy: &[u32],
    outer: &[DVec3],
    normal: DVec3,
    depth: f64,
) {
    // Loop indices kept at each level, level 0 = all.
    let mut levels: Vec<Vec<usize>> = vec![(0..ring.len()).collect()];
    while levels[levels.len() - 1].len() / 2 >= WALL_WAIST {
        let last = &levels[levels.len() - 1];
        levels.push(
            last.iter()
                .step_by(2)
                .take(last.len() / 2)
                .copied()
                .collect(),
        );
    }
    let h = levels.len() - 1;
    // Row j (0..=2h) sits at level min(j, 2h − j); its height above the
    // next row grows as the level's spacing, 2^level.
    let level = |j: usize| j.min(2 * h - j);
    let weight = |j: usize| 2f64.powi(level(j).min(level(j + 1)) as i32);
    let total: f64 = (0..2 * h).map(weight).sum();
    let mut rows: Vec<Vec<u32>> = vec![ring.to_vec()];
    let mut z = 0.0;
    for j in 1..2 * h {
        z += depth * weight(j - 1) / total;
        let drop = normal * z;
        rows.push(
            levels[level(j)]
                .iter()
                .map(|&i| {
                    mesh.positions.push((outer[i] - drop).as_vec3().to_array());
                    mesh.positions.len() as u32 - 1
                })
                .collect(),
        );
    }
    rows.push(copy.to_vec());
    for j in 0..2 * h {
        let (fine, coarse, down) = if level(j) < level(j + 1) {
            (&rows[j], &rows[j + 1], true)
        } else {
            (&rows[j + 1], &rows[j], false)
        };
        let (n, m) = (fine.len(), coarse.len());
        for g in 0..m {
            let (p, q) = (coarse[g], coarse[(g + 1) % m]);
            let end = if g + 1 == m { n } else { 2 * g + 2 };
            // Seen from outside, the loop runs right to left on the
            // upper row (as the full rows' [o_{i+1}, o_i, inner_i]).
            for k in 2 * g..end {
                let (a, b) = (fine[k], fine[(k + 1) % n]);
                mesh.triangles
                    .push(if down { [p, b, a] } else { [p, a, b] });
            }
            let e = fine[end % n];
            mesh.triangles
                .push(if down { [p, q, e] } else { [p, e, q] });
        }
    }
}

/// Appends to `mesh` a patch closing the loop `ring` (the input's edges
/// run ring[i] → ring[i+1]).
fn add_patch(mesh: &mut TriMesh, ring: &[u32]) {
    let lp = Loop::new(mesh, ring);
    let (n, outer, centre, radius) = (ring.len(), &lp.outer, lp.centre, lp.radius);
    let rings = lp.steps(radius, MAX_RINGS.min(PATCH_VERTICES / n).max(1));
    // grid[k][i]: ring k (0 = the loop), i around; ring `rings` is the
    // centre alone.
    let mut grid: Vec<Vec<DVec3>> = (0..rings)
        .map(|k| {
            let s = k as f64 / rings as f64;
            outer.iter().map(|&p| p + (centre - p) * s).collect()
        })
        .collect();
    let mut g = centre;
    for _ in 0..SWEEPS {
        for k in 1..rings {
            for i in 0..n {
                let inner = if k + 1 == rings { g } else { grid[k + 1][i] };
                grid[k][i] =
                    (grid[k - 1][i] + inner + grid[k][(i + n - 1) % n] + grid[k][(i + 1) % n])
                        / 4.0;
            }
        }
        g = grid[rings - 1].iter().sum::<DVec3>() / n as f64;
    }
    // The dome rises against the loop's vector area: the input's edges
    // run with the surface on their left, so that area points away from
    // the missing part.
    let area: DVec3 = (0..n).map(|i| outer[i].cross(outer[(i + 1) % n])).sum();
    let up = -area.normalize_or_zero() * (DOME * radius);
    let lift = |k: usize| {
        let s = 1.0 - k as f64 / rings as f64;
        up * (1.0 - s * s).sqrt()
    };
    for (k, row) in grid.iter_mut().enumerate().skip(1) {
        row.iter_mut().for_each(|p| *p += lift(k));
    }
    let g = g + lift(rings);
    let mut ids: Vec<Vec<u32>> = vec![ring.to_vec()];
    for row in grid.iter().skip(1) {
        ids.push(
            row.iter()
                .map(|p| {
                    mesh.positions.push(p.as_vec3().to_array());
                    mesh.positions.len() as u32 - 1
                })
                .collect(),
        );
    }
    mesh.positions.push(g.as_vec3().to_array());
    let centre_id = mesh.positions.len() as u32 - 1;
    for k in 0..rings {
        let (o, last) = (&ids[k], k + 1 == rings);
        for i in 0..n {
            let j = (i + 1) % n;
            if last {
                mesh.triangles.push([o[j], o[i], centre_id]);
            } else {
                let inn = &ids[k + 1];
                mesh.triangles.push([o[j], o[i], inn[i]]);
                mesh.triangles.push([o[j], inn[i], inn[j]]);
            }
        }
    }
}
