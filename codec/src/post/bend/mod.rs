//! Bender: crease-preserving modified butterfly subdivision (M. Attene,
//! *Surface Remeshing and Applications*, 2004, §8.4; D. Zorin, P.
//! Schröder, W. Sweldens, "Interpolating subdivision for meshes with
//! arbitrary topology", SIGGRAPH 1996; design notes, ALGORITHMS.md §8).
//!
//! Each step splits every triangle into four. Old vertices stay where
//! they are (the scheme interpolates); each edge gets a new point from a
//! stencil of old vertices: the modified butterfly away from sharp edges,
//! the four-point scheme along chains of sharp edges, and crease rules
//! for the edges that reach a sharp edge, so that sharp edges stay sharp
//! while their polylines bend into smooth curves. Mesh boundaries are
//! treated as sharp edges. One module per concern: `stencil` (the
//! weights), `classify` (sharp edges, vertex classes, sectors),
//! `step` (one 1→4 step).
//!
//! Invariants kept, per step: vertex `i < n` of the output is vertex `i`
//! of the input, unmoved; edge `e` of the input (edges numbered by their
//! lower corner) becomes vertex `n + e`; triangle `t` becomes triangles
//! `4t … 4t+3`, oriented as `t`; both halves of a tagged edge are tagged
//! and no other edge is. So `bend(bend(m, s, 1), 1) == bend(m, s, 2)`.

mod classify;
mod stencil;
mod step;

#[cfg(test)]
pub(crate) mod tests;

use super::SharpEdges;
use crate::{CornerTable, Error, FormatError, Limits, Malformed, TopologyError, TriMesh};

/// A bent mesh and its sharp edges, ready for another step.
#[derive(Clone, Debug, PartialEq)]
pub struct Bent {
    /// The refined mesh: the input's vertices first, unmoved, then one new
    /// vertex per input edge (per step).
    pub mesh: TriMesh,
    /// The halves of the tagged edges (tags that named no edge of the
    /// input are dropped).
    pub sharp: SharpEdges,
}

/// Refines `mesh` by `steps` 1→4 subdivisions of Bender, keeping the
/// edges tagged in `sharp` (and the mesh boundaries) sharp; the tags are
/// propagated so steps can repeat.
///
/// The mesh must be manifold and consistently oriented; boundaries and
/// several components are fine, and so are unreferenced vertices (kept,
/// unmoved). Positions that are not finite only spoil the points whose
/// stencils read them. `steps = 0` returns the mesh unchanged.
///
/// # Errors
/// * [`Error::Format`] if a triangle names a vertex that does not exist;
/// * [`Error::Topology`] if the mesh is not manifold, or a triangle uses
///   a vertex twice;
/// * [`Error::LimitExceeded`] if the output would have more faces or
///   vertices, or the work would need more bytes, than `limits` allow, or
///   more than 32-bit indices can number. Checked before anything is
///   allocated for the output.
pub fn bend(
    mesh: &TriMesh,
    sharp: &SharpEdges,
    steps: u32,
    limits: &Limits,
) -> Result<Bent, Error> {
    let n = mesh.positions.len() as u64;
    let mut repeated = 0u64;
    for t in &mesh.triangles {
        if let Some(&v) = t.iter().find(|&&v| u64::from(v) >= n) {
            return Err(FormatError::new(
                "mesh",
                Malformed::IndexOutOfRange {
                    index: i64::from(v),
                    vertices: n,
                },
            )
            .into());
        }
        repeated += u64::from(t[0] == t[1] || t[1] == t[2] || t[2] == t[0]);
    }
    if repeated > 0 {
        // Such a triangle has an edge from a vertex to itself: no manifold
        // has one, and the corner table would pair it with itself.
        return Err(TopologyError::NonManifold {
            edges: repeated,
            vertices: 0,
        }
        .into());
    }
    let f0 = mesh.triangles.len() as u128;
    // The face count needs no corner table: refuse hopeless requests
    // before building one.
    if steps > 0 && f0 > 0 {
        let f = f0.saturating_mul(1u128 << (2 * steps.min(60)));
        face_limits(limits).check_faces(clamp(f))?;
    }
    let table = CornerTable::new(&mesh.triangles, mesh.positions.len())?;
    if steps == 0 || f0 == 0 {
        return Ok(Bent {
            mesh: mesh.clone(),
            sharp: classify::existing_tags(&table, sharp),
        });
    }
    check_limits(mesh, &table, sharp, steps, limits)?;
    let (mut out, mut tags) = step::step(mesh, &table, sharp, step::DIRECT_MAX);
    for _ in 1..steps {
        // A 1→4 split of a manifold mesh is manifold, so this cannot fail.
        let table = CornerTable::new(&out.triangles, out.positions.len())?;
        (out, tags) = step::step(&out, &table, &tags, step::DIRECT_MAX);
    }
    Ok(Bent {
        mesh: out,
        sharp: tags,
    })
}

/// Most faces 32-bit corner numbers allow (corner `u32::MAX` means none).
const MAX_FACES: u64 = (u32::MAX as u64 - 1) / 3;

/// `limits` with the face cap lowered to what corner numbers allow.
fn face_limits(limits: &Limits) -> Limits {
    Limits {
        max_faces: limits.max_faces.min(MAX_FACES),
        // Vertex `u32::MAX` means none too.
        max_vertices: limits.max_vertices.min(u64::from(u32::MAX)),
        ..*limits
    }
}

fn clamp(x: u128) -> u64 {
    u64::try_from(x).unwrap_or(u64::MAX)
}

/// Counts faces, vertices, edges and tags step by step (F' = 4F,
/// V' = V + E, E' = 2E + 3F, T' = 2T) and checks the output and the last
/// step's working memory against `limits`.
fn check_limits(
    mesh: &TriMesh,
    table: &CornerTable,
    sharp: &SharpEdges,
    steps: u32,
    limits: &Limits,
) -> Result<(), Error> {
    let boundary = table.opposites().iter().filter(|o| o.is_none()).count() as u128;
    let (mut v, mut f) = (mesh.positions.len() as u128, mesh.triangles.len() as u128);
    let mut e = (3 * f + boundary) / 2;
    // Tags can only name edges.
    let mut t = (sharp.len() as u128).min(e);
    let mut bytes = 0u128;
    for _ in 0..steps {
        bytes = step_bytes(v, f, e, t);
        (v, f, e, t) = (v + e, 4 * f, 2 * e + 3 * f, 2 * t);
        // Every later count is larger still; f ≥ 1 quadruples, so this
        // ends the loop within 64 steps.
        if f > u128::from(u64::MAX) {
            break;
        }
    }
    let l = face_limits(limits);
    l.check_faces(clamp(f))?;
    l.check_vertices(clamp(v))?;
    l.check_alloc(clamp(bytes))?;
    Ok(())
}

/// Bytes one step needs at most, for an input of `v` vertices, `f` faces,
/// `e` edges and `t` tags: the output mesh (12 bytes a vertex, 12 a face)
/// and tags (8 bytes a pair, twice while they are sorted); the input when
/// it is an intermediate result; its corner table with the peak of its
/// construction (about 64 bytes a face, 24 a vertex); edge numbers (12 a
/// face), edge records (5 an edge) and vertex classes (13 a vertex).
fn step_bytes(v: u128, f: u128, e: u128, t: u128) -> u128 {
    let output = 12 * (v + e) + 12 * 4 * f + 16 * 2 * t;
    let input = 12 * v + 12 * f + 8 * t;
    let work = (64 + 12) * f + 5 * e + (24 + 13) * v;
    output + input + work
}
