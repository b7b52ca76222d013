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

use crate::math;
use crate::prelude::*;

mod classify;
mod cleanup;
mod snap;
mod split;
#[cfg(test)]
mod tests;

use glam::{DVec3, Vec3};

use super::SharpEdges;
use crate::mesh::CornerTable;
use crate::{Error, LimitError, Limited, ParameterError, TriMesh};

/// Options of [`sharpen`]. The defaults are the thesis's and the design
/// notes' values, but for `max_snap_ratio` (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SharpenOptions {
    /// An interior edge is smooth when the angle between its two face
    /// normals is below this multiple of ε, the mean of that angle over
    /// the mesh's interior edges. Default 2.0 (the thesis's "2ε": ε alone
    /// makes the filters too sensitive to noise).
    pub smooth_factor: f64,
    /// Triangles with an angle below this many degrees are removed by
    /// collapsing the edge opposite the angle. Default 1.0. Zero-area
    /// triangles are removed whatever the value.
    pub min_angle_degrees: f64,
    /// A chamfer-edge vertex stays at the edge's midpoint when the two
    /// plane normals N, M are this close to parallel: `1 − (N·M)² <` this.
    /// Default 1e-4.
    pub parallel_tolerance: f64,
    /// A corner vertex stays at the triangle's centroid when its three
    /// plane normals are this close to coplanar: `|det[N; M; S]| <` this.
    /// Default 1e-3.
    pub coplanar_tolerance: f64,
    /// A new vertex stays unmoved when snapping it would make an edge
    /// longer than this multiple of the longest edge of the input mesh.
    /// Default 1.0 (the thesis: the algorithm is tailored for nearly
    /// uniform triangulations).
    pub max_edge_factor: f64,
    /// A new vertex stays unmoved when snapping would move it farther
    /// than this multiple of its chamfer edge's length (for a corner: of
    /// its triangle's longest edge). Default 0.7; `f64::INFINITY` (or any
    /// large value) gives the thesis's rules alone.
    pub max_snap_ratio: f64,
}

impl Default for SharpenOptions {
    fn default() -> Self {
        SharpenOptions {
            smooth_factor: 2.0,
            min_angle_degrees: 1.0,
            parallel_tolerance: 1e-4,
            coplanar_tolerance: 1e-3,
            max_edge_factor: 1.0,
            max_snap_ratio: 0.7,
        }
    }
}

impl SharpenOptions {
    fn check(&self) -> Result<(), ParameterError> {
        let ranges: [(&'static str, f64, f64, f64); 6] = [
            ("smooth_factor", self.smooth_factor, 0.0, 1e6),
            ("min_angle_degrees", self.min_angle_degrees, 0.0, 30.0),
            ("parallel_tolerance", self.parallel_tolerance, 0.0, 1.0),
            ("coplanar_tolerance", self.coplanar_tolerance, 0.0, 1.0),
            ("max_edge_factor", self.max_edge_factor, 0.0, 1e6),
            ("max_snap_ratio", self.max_snap_ratio, 0.0, f64::INFINITY),
        ];
        for (name, value, min, max) in ranges {
            // Written so that NaN fails too.
            if !(value >= min && value <= max) {
                return Err(ParameterError::OutOfRange {
                    name,
                    value,
                    min,
                    max,
                });
            }
        }
        Ok(())
    }
}

/// Why new vertices were left where they were inserted (the middle of
/// their chamfer edge or corner triangle) instead of being snapped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Unmoved {
    /// The two planes are nearly parallel (`1 − c² <` the tolerance).
    pub parallel: u64,
    /// The three planes of a corner have nearly coplanar normals.
    pub coplanar: u64,
    /// The snapped position would make an edge longer than allowed.
    pub too_long: u64,
    /// The snapped position is too far from the inserted one.
    pub too_far: u64,
    /// The chamfer mixes a concave and a convex side (`a·b ≥ 0`).
    pub mixed: u64,
    /// An endpoint's red triangles give no normal (they cancel out or
    /// have no area).
    pub no_normal: u64,
}

impl Unmoved {
    /// All unmoved vertices, whatever the reason.
    pub fn total(&self) -> u64 {
        self.parallel + self.coplanar + self.too_long + self.too_far + self.mixed + self.no_normal
    }
}

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
        cleanup::sliver_sin2(options.min_angle_degrees),
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
        keys.sort_unstable();
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

/// Per-face unit normals and the longest edge, computed in one pass.
struct FaceGeometry {
    /// Unit normal of each face; zero for a face without area. Single
    /// precision (1e-7 is far below any angle the filters compare) halves
    /// the memory that the per-edge sweep reads out of order.
    pub normals: Vec<Vec3>,
    /// Length of the longest edge of the mesh.
    pub longest_edge: f64,
    /// Faces that are slivers already (`cleanup::is_sliver` with `sin2`).
    pub slivers: Vec<u32>,
}

impl FaceGeometry {
    fn new(positions: &[[f32; 3]], triangles: &[[u32; 3]], sin2: f64) -> Self {
        let mut longest2 = 0.0f64;
        let mut slivers = Vec::new();
        let normals = triangles
            .iter()
            .enumerate()
            .map(|(f, t)| {
                let p = t.map(|v| point(positions, v));
                let (ab, bc, ca) = (p[1] - p[0], p[2] - p[1], p[0] - p[2]);
                longest2 = longest2
                    .max(ab.length_squared())
                    .max(bc.length_squared())
                    .max(ca.length_squared());
                if cleanup::is_sliver(p, sin2) {
                    slivers.push(f as u32);
                }
                unit_normal(ab, -ca).as_vec3()
            })
            .collect();
        FaceGeometry {
            normals,
            longest_edge: math::sqrt(longest2),
            slivers,
        }
    }
}

/// The unit normal of a triangle with edge vectors `u`, `v` from one
/// corner, or zero when the triangle has no area to speak of (its cross
/// product is lost in the rounding of its edges' lengths).
#[inline]
fn unit_normal(u: DVec3, v: DVec3) -> DVec3 {
    let n = u.cross(v);
    let len2 = n.length_squared();
    let scale = u.length_squared() * v.length_squared();
    if len2 > 1e-24 * scale && len2 > 0.0 {
        n / math::sqrt(len2)
    } else {
        DVec3::ZERO
    }
}

/// A position in double precision.
#[inline(always)]
fn point(positions: &[[f32; 3]], v: u32) -> DVec3 {
    let p = positions[v as usize];
    DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
}

/// The angle at `p` between the directions to `q` and `r`, accurate for
/// small and flat angles alike (0 or π when `q` or `r` is `p` itself).
#[inline]
fn angle_at(p: DVec3, q: DVec3, r: DVec3) -> f64 {
    let (u, v) = (q - p, r - p);
    math::atan2(u.cross(v).length(), u.dot(v))
}
