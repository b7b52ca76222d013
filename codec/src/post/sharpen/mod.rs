//! EdgeSharpener (M. Attene, *Surface Remeshing and Applications*, 2004,
//! §8.3; design notes, ALGORITHMS.md §7): restores the sharp edges and
//! corners that a feature-insensitive retiling cut into chamfers, from the
//! geometry of the decoded mesh alone.
//!
//! The steps, one module each:
//! 1. `classify`: smooth edges by the 2ε rule, the six colouring filters
//!    and filter 3bis (which vertices are tagged sharp);
//! 2. `snap`: where a new vertex goes, as the intersection of the planes
//!    extrapolated from the smooth regions beside it;
//! 3. `split`: a vertex in the middle of every chamfer (blue) edge and
//!    corner (green) triangle, snapped, and the chamfer triangles re-cut;
//! 4. `cleanup`: triangles with an angle under 1° (the zero-area triangles
//!    that snapping makes where four or more sharp edges meet, and any the
//!    input had) are removed by edge collapses.
//!
//! Below the passes: `options` (what the caller asks, the unmoved counts)
//! and `geometry` (face normals, the sliver test, corner angles), which
//! the passes share and which import none of them.
//!
//! Two rules are not in the thesis nor the notes. The colouring's flood
//! is bounded by the normal of the face it starts from (`classify`: the
//! thesis's flood paints whole chamfer strips smooth). And a new vertex also stays
//! unmoved when snapping would move it farther than
//! [`SharpenOptions::max_snap_ratio`] times its chamfer edge. Thin wedges
//! (the fandisk's slab, narrower than three samples) and blends smaller
//! than the sampling (horse, bunny) put the planes' intersection far out;
//! on the corpus every snap longer than 0.7 |AB| made the surface worse,
//! while right-angle creases move by about 0.5 |AB|.
//!
//! Invariants of [`sharpen`]'s output:
//! * it is an oriented manifold mesh (a corner table can be built) with
//!   the input's orientation, boundaries and components;
//! * no triangle has an angle under [`SharpenOptions::min_angle_degrees`]
//!   (none has zero area) unless the report counts it in
//!   [`SharpenReport::slivers_left`]: nothing could remove it and keep the
//!   mesh manifold, which takes contrived input for a zero-area face;
//! * input vertex `i` is output vertex `i` and new vertices come after the
//!   input's, unless the cleanup removed vertices: then the survivors are
//!   renumbered in the same order (the report says how many went);
//! * `sharp` names edges of the output mesh.
//!
//! Cost: linear in the mesh size; flat arrays indexed by corner, face or
//! vertex, and no hashing.

use crate::prelude::*;

mod classify;
mod cleanup;
mod geometry;
mod options;
mod snap;
mod split;
#[cfg(test)]
mod tests;

use super::SharpEdges;
use crate::mesh::CornerTable;
use crate::{Error, LimitError, Limited, TriMesh};
use geometry::FaceGeometry;
pub use options::{SharpenOptions, Unmoved};

/// What [`sharpen`] found and did.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct SharpenReport {
    /// ε: the mean angle, in radians, between the normals of the two
    /// faces of an interior edge (boundary edges and edges of zero-area
    /// faces left out).
    pub mean_normal_angle: f64,
    /// Interior edges found smooth (brown).
    pub smooth_edges: u64,
    /// Chamfer (blue) edges, each split at a new vertex.
    pub chamfer_edges: u64,
    /// Corner (green) triangles, each split around a new vertex.
    pub corners: u64,
    /// New vertices snapped onto a sharp edge or corner.
    pub snapped: u64,
    /// New vertices left unmoved, by reason.
    pub unmoved: Unmoved,
    /// Input faces dropped because a vertex appeared twice in them.
    pub repeated_index_faces: u64,
    /// Edges collapsed to remove triangles with a tiny angle.
    pub slivers_collapsed: u64,
    /// Vertices the collapses removed (the output is renumbered if > 0).
    pub vertices_removed: u64,
    /// Triangles with a tiny angle that nothing valid could remove.
    pub slivers_left: u64,
    /// Components of at most 16 faces removed because they had collapsed
    /// flat (no edge of theirs could go without tearing them).
    pub components_removed: u64,
    /// Edges of the output tagged sharp.
    pub sharp_edges: u64,
}

/// The sharpened mesh, its sharp edges and the report.
#[derive(Clone, Debug, PartialEq)]
pub struct Sharpened {
    /// The mesh: the input's vertices, then the new ones (see the module
    /// docs for the renumbering after collapses).
    pub mesh: TriMesh,
    /// Edges of `mesh` tagged sharp (thesis §8.4, "Tagging the sharp
    /// edges"): edges whose two endpoints were tagged by filter 3bis or
    /// inserted by the subdivision.
    pub sharp: SharpEdges,
    /// What was found and done.
    pub report: SharpenReport,
}

/// Runs EdgeSharpener on a decoded mesh: finds the chamfers that a
/// feature-insensitive retiling left where the original had sharp edges,
/// splits them and snaps the new vertices onto the restored edges and
/// corners (see the module docs).
///
/// The mesh must be an oriented manifold (boundaries and several
/// components are fine). Fails with [`Error::Topology`] if it is not,
/// with [`Error::Format`] if a position is not finite or an index is out
/// of range, with [`Error::Parameter`] for options out of range. Faces
/// that repeat a vertex are dropped. An empty mesh gives an empty mesh.
pub fn sharpen(mesh: &TriMesh, options: &SharpenOptions) -> Result<Sharpened, Error> {
    options.check()?;
    mesh.validate()?;
    let mut report = SharpenReport::default();

    // Faces that repeat a vertex have no area and no valid corner-table
    // place; nothing is lost by dropping them.
    let kept: Vec<[u32; 3]>;
    let triangles: &[[u32; 3]] = if mesh
        .triangles
        .iter()
        .any(|t| t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
        kept = mesh
            .triangles
            .iter()
            .copied()
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
            .collect();
        report.repeated_index_faces = (mesh.triangles.len() - kept.len()) as u64;
        &kept
    } else {
        &mesh.triangles
    };
    let table = CornerTable::new(triangles, mesh.positions.len())?;

    let geometry = FaceGeometry::new(
        &mesh.positions,
        triangles,
        geometry::sliver_sin2(options.min_angle_degrees),
    );
    let classes = classify::classify(&table, &geometry.normals, options.smooth_factor);
    report.mean_normal_angle = classes.mean_normal_angle;
    report.smooth_edges = classes.smooth_edges;
    report.chamfer_edges = classes.blue_edges;
    report.corners = classes.green_faces;

    let new_vertices = classes.blue_edges + classes.green_faces;
    let total = mesh.positions.len() as u64 + new_vertices;
    if total >= u64::from(u32::MAX) {
        return Err(LimitError {
            what: Limited::Vertices,
            requested: total,
            limit: u64::from(u32::MAX) - 1,
        }
        .into());
    }

    let split = split::subdivide(
        &mesh.positions,
        &table,
        &geometry,
        &classes,
        options,
        geometry.longest_edge * options.max_edge_factor,
    );
    report.snapped = split.snapped;
    report.unmoved = split.unmoved;

    let mut candidates = geometry.slivers;
    candidates.extend(split.changed);
    let cleaned = cleanup::cleanup(
        split.positions,
        split.triangles,
        split.tagged,
        mesh.positions.len(),
        options.min_angle_degrees,
        candidates,
    );
    report.slivers_collapsed = cleaned.collapsed;
    report.vertices_removed = cleaned.vertices_removed;
    report.slivers_left = cleaned.left;
    report.components_removed = cleaned.components_removed;

    let sharp = sharp_edges(&cleaned.triangles, &cleaned.tagged);
    report.sharp_edges = sharp.len() as u64;

    Ok(Sharpened {
        mesh: TriMesh::new(cleaned.positions, cleaned.triangles),
        sharp,
        report,
    })
}

/// Thesis §8.4: an edge joining two tagged vertices is sharp. Each
/// interior edge shows up twice, once per face: the pairs are radix
/// sorted as 64-bit keys and deduplicated first (a scanned mesh can tag
/// a fair share of its edges, and a comparison sort of them all would
/// cost more than the rest of the cleanup).
fn sharp_edges(triangles: &[[u32; 3]], tagged: &[bool]) -> SharpEdges {
    let mut keys: Vec<u64> = triangles
        .iter()
        .flat_map(|t| {
            (0..3).filter_map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                (tagged[a as usize] && tagged[b as usize]).then_some(key)
            })
        })
        .collect();
    radix_sort(&mut keys);
    keys.dedup();
    // Already sorted and unique: `SharpEdges::new`'s sort is one pass.
    SharpEdges::new(keys.into_iter().map(|k| [(k >> 32) as u32, k as u32]))
}

/// LSD radix sort by bytes, skipping the bytes in which all keys agree.
fn radix_sort(keys: &mut Vec<u64>) {
    if keys.len() < 64 {
        crate::sort::sort_unstable(keys);
        return;
    }
    let (or, and) = keys
        .iter()
        .fold((0u64, u64::MAX), |(o, a), &k| (o | k, a & k));
    let differ = or ^ and;
    let mut buffer = vec![0u64; keys.len()];
    for shift in (0..64).step_by(8) {
        if (differ >> shift) & 0xff == 0 {
            continue;
        }
        let mut count = [0usize; 257];
        for &k in keys.iter() {
            count[((k >> shift) & 0xff) as usize + 1] += 1;
        }
        for i in 0..256 {
            count[i + 1] += count[i];
        }
        for &k in keys.iter() {
            let slot = &mut count[((k >> shift) & 0xff) as usize];
            buffer[*slot] = k;
            *slot += 1;
        }
        core::mem::swap(keys, &mut buffer);
    }
}
