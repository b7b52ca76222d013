//! Cleaning: turns any triangle soup into an oriented manifold mesh that
//! the corner table, Edgebreaker and the retiler can walk, and reports
//! every change it made.
//!
//! Steps, in order (each only sees the previous step's output):
//! 1. merge vertices at exactly the same position (`-0.0` equals `0.0`);
//! 2. drop faces with a repeated vertex, faces of zero area (exactly
//!    collinear corners in `f64`), and duplicate faces (the same three
//!    vertices in either orientation; the first one is kept);
//! 3. drop vertices no face uses;
//! 4. orient each connected component consistently, across edges shared
//!    by exactly two faces, keeping the orientation of the majority of its
//!    faces; a component that cannot be oriented is an error;
//! 5. cut non-manifold edges (three or more faces): the two oppositely
//!    oriented faces that meet most smoothly stay joined (then the next
//!    two), the others get boundary edges there;
//! 6. split non-manifold vertices: a vertex whose faces form several fans
//!    gets one copy per fan (Draco does the same in `BreakNonManifoldEdges`).
//!    After the split, two faces left on a formerly cut edge are the two ends
//!    of one fan at both endpoints, so pairing them again only closes fans:
//!    the loop below ends after at most two rounds, and the result has a
//!    valid corner table.
//!
//! Vertex order is kept (a stable compaction), and so is face order, so a
//! clean mesh passes through unchanged.
//!
//! Attributes ([`clean_attributed`]): each output face remembers its
//! input face and whether step 4 flipped it ([`FaceOrigin`]); its
//! attribute triples are the input face's, with corners 1 and 2 swapped
//! when the face was (the only corner permutation any step makes).
//! Merging and splitting vertices change positions only: attribute
//! streams index their own values per corner, so they need nothing else.

use super::corner::{pair_edges, vertex_fans, Pairing};
use super::{AttributeStream, AttributedMesh, CornerId, CornerTable, FaceId, TriMesh, VertexId};
use crate::{Error, TopologyError};

/// Options for [`clean`]. The defaults do everything listed in the module docs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CleanOptions {
    /// Merge vertices with bit-identical positions. Default: true.
    pub merge_coincident: bool,
}

impl Default for CleanOptions {
    fn default() -> Self {
        CleanOptions {
            merge_coincident: true,
        }
    }
}

/// What [`clean`] changed; every count is zero for a clean mesh.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CleanReport {
    /// Vertices in the input.
    pub input_vertices: u64,
    /// Triangles in the input.
    pub input_faces: u64,
    /// Vertices removed because another vertex had the same position.
    pub merged_vertices: u64,
    /// Vertices no face referred to (after merging), removed.
    pub unreferenced_vertices: u64,
    /// Faces dropped because a vertex appeared twice in them (after merging).
    pub repeated_index_faces: u64,
    /// Faces dropped because their area is exactly zero.
    pub zero_area_faces: u64,
    /// Faces dropped because an earlier face had the same three vertices.
    pub duplicate_faces: u64,
    /// Faces whose orientation was reversed to agree with their component.
    pub flipped_faces: u64,
    /// Edges shared by three or more faces, cut into boundary edges.
    pub non_manifold_edges: u64,
    /// Vertices whose faces formed several fans, split into one per fan.
    pub non_manifold_vertices: u64,
    /// Vertices added by those splits.
    pub split_vertices_added: u64,
    /// Connected components of the input (after merging and dropping
    /// degenerate faces), with faces joined by every shared edge, manifold
    /// or not: the count a user sees in the file. Cutting non-manifold
    /// edges can split these further.
    pub input_components: u64,
}

impl CleanReport {
    /// Faces dropped as degenerate (repeated vertex or zero area).
    pub fn degenerate_faces(&self) -> u64 {
        self.repeated_index_faces + self.zero_area_faces
    }

    /// True if cleaning changed nothing.
    pub fn is_clean(&self) -> bool {
        self.merged_vertices
            + self.unreferenced_vertices
            + self.repeated_index_faces
            + self.zero_area_faces
            + self.duplicate_faces
            + self.flipped_faces
            + self.non_manifold_edges
            + self.non_manifold_vertices
            == 0
    }
}

/// A cleaned mesh, its corner table and the report of what changed.
#[derive(Clone, Debug)]
pub struct Cleaned {
    /// The oriented manifold mesh.
    pub mesh: TriMesh,
    /// Its corner table (face `f` of `mesh` is triangle `f` of the table).
    pub table: CornerTable,
    /// What was changed.
    pub report: CleanReport,
    /// Vertices after merging (step 1), unreferenced ones included: the
    /// count other tools (and the corpus README) give for "how many
    /// vertices has this mesh".
    pub distinct_vertices: u64,
}

/// Where a face of a cleaned mesh came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceOrigin {
    /// The input face.
    pub face: FaceId,
    /// Whether its orientation was reversed: output corners (0, 1, 2)
    /// are input corners (0, 2, 1).
    pub flipped: bool,
}

impl FaceOrigin {
    /// The output face's corners, from the input face's `corners`.
    pub fn corners<T: Copy>(&self, corners: [T; 3]) -> [T; 3] {
        let [a, b, c] = corners;
        if self.flipped {
            [a, c, b]
        } else {
            [a, b, c]
        }
    }
}

/// Cleans a mesh (see the module docs). The input must be valid
/// ([`TriMesh::validate`]); readers guarantee that.
pub fn clean(mesh: &TriMesh, options: &CleanOptions) -> Result<Cleaned, Error> {
    clean_with_origins(mesh, options).map(|(cleaned, _)| cleaned)
}

/// [`clean`] of a mesh with attributes: the cleaned mesh (as [`clean`]
/// gives it for `mesh.mesh`) and the streams made to follow its faces,
/// each triple taken from the face's input face and permuted as its
/// corners were ([`FaceOrigin`]); values are kept as they are, used or
/// not. The input must be valid ([`AttributedMesh::validate`]).
pub fn clean_attributed(
    mesh: &AttributedMesh,
    options: &CleanOptions,
) -> Result<(Cleaned, Vec<AttributeStream>), Error> {
    mesh.validate()?;
    let (cleaned, origins) = clean_with_origins(&mesh.mesh, options)?;
    let streams = mesh
        .streams
        .iter()
        .map(|s| AttributeStream {
            corners: origins
                .iter()
                .map(|o| o.corners(s.corners[o.face.idx()]))
                .collect(),
            ..s.clone()
        })
        .collect();
    Ok((cleaned, streams))
}

/// [`clean`], and for each face of the result where it came from.
pub fn clean_with_origins(
    mesh: &TriMesh,
    options: &CleanOptions,
) -> Result<(Cleaned, Vec<FaceOrigin>), Error> {
    mesh.validate()?;
    let mut report = CleanReport {
        input_vertices: mesh.positions.len() as u64,
        input_faces: mesh.triangles.len() as u64,
        ..Default::default()
    };
    let remap = if options.merge_coincident {
        merge_coincident(&mesh.positions)
    } else {
        (0..mesh.positions.len() as u32).collect()
    };
    report.merged_vertices = remap
        .iter()
        .enumerate()
        .filter(|&(i, &r)| r as usize != i)
        .count() as u64;

    let (mut triangles, kept) = drop_degenerate(mesh, &remap, &mut report);
    // Step 3: drop the vertices no face uses, keeping the others' order.
    let positions = super::compact_vertices(&mesh.positions, &mut triangles);
    // Merged-away vertices are unreferenced too; count only the others.
    report.unreferenced_vertices =
        (mesh.positions.len() - positions.len()) as u64 - report.merged_vertices;
    let distinct_vertices = report.input_vertices - report.merged_vertices;
    if triangles.is_empty() {
        return Err(TopologyError::NoTriangles.into());
    }
    let mut flipped = vec![false; triangles.len()];
    let (manifold_components, pairing) =
        orient(&mut triangles, positions.len(), &mut report, &mut flipped)?;
    // Steps 5 and 6 keep every face, in order, with its corners in order.
    let origins = kept
        .iter()
        .zip(&flipped)
        .map(|(&face, &flipped)| FaceOrigin {
            face: FaceId(face),
            flipped,
        })
        .collect();
    // Without non-manifold edges the orientation pass already saw every
    // edge; otherwise count again through the edges it had to leave out.
    report.input_components = if report.non_manifold_edges == 0 {
        manifold_components
    } else {
        edge_components(&triangles, &pairing.o)
    };
    let mut mesh = TriMesh {
        positions,
        triangles,
    };
    let table = if report.non_manifold_edges == 0 {
        split_non_manifold(&mut mesh, pairing, &mut report)?
    } else {
        // A rejoined pair can leave a detached face in the same fan as
        // the pair (reached around the vertex by other edges), which no
        // vertex split separates: then cut every face there after all.
        let mut rejoined = pairing.clone();
        rejoin_smoothest(&mesh.triangles, &mesh.positions, &mut rejoined.o);
        let (mut first, mut first_report) = (mesh.clone(), report.clone());
        match split_non_manifold(&mut first, rejoined, &mut first_report) {
            Ok(table) => {
                (mesh, report) = (first, first_report);
                table
            }
            Err(_) => split_non_manifold(&mut mesh, pairing, &mut report)?,
        }
    };
    let cleaned = Cleaned {
        mesh,
        table,
        report,
        distinct_vertices,
    };
    Ok((cleaned, origins))
}

/// The bits of a position, with -0.0 turned into +0.0 (adding 0.0 does
/// that), so that the two zeros compare equal.
pub(crate) fn position_key(p: &[f32; 3]) -> [u32; 3] {
    [
        (p[0] + 0.0).to_bits(),
        (p[1] + 0.0).to_bits(),
        (p[2] + 0.0).to_bits(),
    ]
}

/// The vertices of a mesh by position ([`position_key`]): which vertex
/// stands at a position another mesh carries (cleaning, simplification by
/// a subset of vertices and a refit's numbering move none).
pub(crate) struct PositionIndex {
    /// (key, vertex), sorted: the lowest-numbered vertex of a key first.
    sorted: Vec<([u32; 3], u32)>,
}

impl PositionIndex {
    pub(crate) fn new(positions: &[[f32; 3]]) -> PositionIndex {
        let mut sorted: Vec<([u32; 3], u32)> = positions
            .iter()
            .enumerate()
            .map(|(v, p)| (position_key(p), v as u32))
            .collect();
        sorted.sort_unstable();
        PositionIndex { sorted }
    }

    /// The lowest-numbered vertex at `p`, if any.
    pub(crate) fn find(&self, p: &[f32; 3]) -> Option<u32> {
        let k = position_key(p);
        let i = self.sorted.partition_point(|e| e.0 < k);
        self.sorted.get(i).filter(|e| e.0 == k).map(|e| e.1)
    }
}

/// Maps each vertex to the lowest-numbered vertex at the same position.
///
/// A hash table (open addressing, at most half full) visited in vertex
/// order, so the first vertex seen at a position is its representative:
/// linear time, where sorting the positions cost most of the cleaning.
/// The hash is fixed, so input crafted to collide could make probing
/// quadratic; past a probe budget the sort takes over, which gives the
/// same answer in O(n log n) whatever the input.
fn merge_coincident(positions: &[[f32; 3]]) -> Vec<u32> {
    const EMPTY: u32 = u32::MAX;
    let bits = (2 * positions.len())
        .max(2)
        .next_power_of_two()
        .trailing_zeros();
    let mask = (1usize << bits) - 1;
    let mut slots = vec![EMPTY; mask + 1];
    let mut remap = Vec::with_capacity(positions.len());
    let mut budget = 8 * positions.len() + 64;
    for (i, p) in positions.iter().enumerate() {
        let key = position_key(p);
        // A multiply-xorshift mix of the 96 bits; its top bits pick a slot.
        let mut h =
            (u64::from(key[0]) | u64::from(key[1]) << 32) ^ u64::from(key[2]).rotate_left(21);
        h = h.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        h ^= h >> 29;
        h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        let mut slot = (h >> (64 - bits)) as usize & mask;
        loop {
            match slots[slot] {
                EMPTY => {
                    slots[slot] = i as u32;
                    remap.push(i as u32);
                    break;
                }
                j if position_key(&positions[j as usize]) == key => {
                    remap.push(j);
                    break;
                }
                _ => slot = (slot + 1) & mask,
            }
            budget = match budget.checked_sub(1) {
                Some(b) => b,
                None => return merge_coincident_by_sorting(positions),
            };
        }
    }
    remap
}

/// [`merge_coincident`] by sorting the positions: the fallback for input
/// that defeats the hash, and the reference the tests compare it with.
fn merge_coincident_by_sorting(positions: &[[f32; 3]]) -> Vec<u32> {
    let mut keyed: Vec<([u32; 3], u32)> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| (position_key(p), i as u32))
        .collect();
    keyed.sort_unstable();
    let mut remap = vec![0u32; positions.len()];
    let mut rep = 0;
    for (i, &(key, v)) in keyed.iter().enumerate() {
        if i == 0 || keyed[i - 1].0 != key {
            rep = v; // the lowest index of its run, as ties sort by index
        }
        remap[v as usize] = rep;
    }
    remap
}

/// Step 2: remaps indices and drops repeated-index, zero-area and
/// duplicate faces; the faces kept, and the input face of each.
fn drop_degenerate(
    mesh: &TriMesh,
    remap: &[u32],
    report: &mut CleanReport,
) -> (Vec<[u32; 3]>, Vec<u32>) {
    let mut kept: Vec<[u32; 3]> = Vec::with_capacity(mesh.triangles.len());
    let mut origin: Vec<u32> = Vec::with_capacity(mesh.triangles.len());
    for (f, t) in mesh.triangles.iter().enumerate() {
        let t = [
            remap[t[0] as usize],
            remap[t[1] as usize],
            remap[t[2] as usize],
        ];
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            report.repeated_index_faces += 1;
            continue;
        }
        let p = |i: u32| mesh.point(VertexId(i));
        if (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])) == glam::DVec3::ZERO {
            report.zero_area_faces += 1;
            continue;
        }
        kept.push(t);
        origin.push(f as u32);
    }
    let drop = duplicate_faces(&kept, mesh.positions.len());
    let before = kept.len();
    let mut f = 0;
    kept.retain(|_| {
        f += 1;
        !drop[f - 1]
    });
    let mut f = 0;
    origin.retain(|_| {
        f += 1;
        !drop[f - 1]
    });
    report.duplicate_faces = (before - kept.len()) as u64;
    (kept, origin)
}

/// Marks every face whose three vertices (in any order) are those of an
/// earlier face.
///
/// Faces are grouped by their lowest vertex with a counting sort (stable,
/// so each group lists its faces in order), and compared only inside
/// their group: linear time on any mesh whose vertices have bounded
/// valence, where sorting every face cost a large share of the cleaning.
/// A group bigger than a few faces is sorted instead, so a vertex of
/// huge valence costs O(k log k), not O(k²).
fn duplicate_faces(triangles: &[[u32; 3]], vertex_count: usize) -> Vec<bool> {
    let sorted = |t: &[u32; 3]| {
        let mut k = *t;
        k.sort_unstable();
        k
    };
    let mut start = vec![0u32; vertex_count + 1];
    for t in triangles {
        start[sorted(t)[0] as usize + 1] += 1;
    }
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    // Entries (middle vertex, highest vertex, face).
    let mut entries = vec![(0u32, 0u32, 0u32); triangles.len()];
    for (f, t) in triangles.iter().enumerate() {
        let [lo, mid, hi] = sorted(t);
        let slot = &mut start[lo as usize];
        entries[*slot as usize] = (mid, hi, f as u32);
        *slot += 1;
    }
    // `start[v]` now ends group v, which begins where group v - 1 ends.
    let mut drop = vec![false; triangles.len()];
    let mut begin = 0;
    for &end in &start[..vertex_count] {
        let group = &mut entries[begin..end as usize];
        begin = end as usize;
        if group.len() <= 8 {
            for i in 1..group.len() {
                let (mid, hi, f) = group[i];
                if group[..i].iter().any(|e| (e.0, e.1) == (mid, hi)) {
                    drop[f as usize] = true;
                }
            }
        } else {
            group.sort_unstable();
            for w in group.windows(2) {
                if (w[0].0, w[0].1) == (w[1].0, w[1].1) {
                    drop[w[1].2 as usize] = true;
                }
            }
        }
    }
    drop
}

/// Counts components of faces joined through any shared edge, given the
/// orientation pass's pairing `o` of the same triangles.
///
/// An undirected edge is either paired (two faces) or left with all its
/// corners unpaired (a boundary, or three faces and more: `pair_edges`
/// cuts such an edge whole). So the pairs join what they join, and only
/// the unpaired corners' edges need matching by their ends: sorting those
/// few instead of all 3F edges took the count from a third of the
/// cleaning of a simplified scan (meshoptimizer leaves a few
/// non-manifold edges) to a union per pair.
fn edge_components(triangles: &[[u32; 3]], o: &[CornerId]) -> u64 {
    let mut parent: Vec<u32> = (0..triangles.len() as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    let mut components = triangles.len() as u64;
    let mut union = |parent: &mut [u32], f: u32, g: u32| {
        let (a, b) = (find(parent, f), find(parent, g));
        if a != b {
            parent[a.max(b) as usize] = a.min(b);
            components -= 1;
        }
    };
    let mut loose: Vec<(u32, u32, u32)> = Vec::new();
    for (c, &d) in o.iter().enumerate() {
        let f = c as u32 / 3;
        if d.is_some() {
            if d.idx() > c {
                union(&mut parent, f, d.0 / 3);
            }
        } else {
            // Corner k faces the edge between the face's other two.
            let t = triangles[f as usize];
            let (a, b) = (t[(c + 1) % 3], t[(c + 2) % 3]);
            loose.push((a.min(b), a.max(b), f));
        }
    }
    loose.sort_unstable();
    for w in loose.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) {
            union(&mut parent, w[0].2, w[1].2);
        }
    }
    components
}

/// The number of components of faces joined by the pairs of `o`.
///
/// A union-find over the pairs in corner order rather than a walk from
/// face to face: a walk waits at every face for the cache misses of the
/// one before (on large meshes, whose faces are rarely stored near their
/// neighbours, that was most of the cleaning), while the unions' loads
/// are independent of each other.
fn count_components(o: &[CornerId], faces: usize) -> u64 {
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    let find = |parent: &mut [u32], mut x: u32| {
        while parent[x as usize] != x {
            let up = parent[parent[x as usize] as usize];
            parent[x as usize] = up;
            x = up;
        }
        x
    };
    let mut components = faces as u64;
    for (c, &d) in o.iter().enumerate() {
        if d.is_some() && d.idx() > c {
            let (a, b) = (find(&mut parent, c as u32 / 3), find(&mut parent, d.0 / 3));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
                components -= 1;
            }
        }
    }
    components
}

/// Step 4: orients every component consistently across its two-face
/// edges; returns the number of components joined by those edges, and
/// the half-edge pairing of the oriented mesh.
///
/// That pairing is the undirected one this step builds anyway, with the
/// corners of flipped faces renumbered: once every component is oriented,
/// each edge it pairs has two half-edges of opposite direction, which is
/// exactly what [`pair_half_edges`](super::corner::pair_half_edges) would
/// pair (and the edges it cuts, shared by three faces or more, are cut
/// there too), so step 5 need not pair the edges again.
fn orient(
    triangles: &mut [[u32; 3]],
    vertex_count: usize,
    report: &mut CleanReport,
    flipped: &mut [bool],
) -> Result<(u64, Pairing), Error> {
    let pairing = pair_edges(triangles, vertex_count, true);
    report.non_manifold_edges = pairing.cut_edges;
    // With no pair running the same way, the faces agree already: no face
    // needs flipping and no component can fail to orient, so only the
    // components are left to count.
    if pairing.same_direction == 0 {
        let components = count_components(&pairing.o, triangles.len());
        return Ok((components, pairing));
    }
    let mut o = pairing.o;
    // Direction bit of the half-edge V[n(c)] -> V[p(c)] facing corner c.
    let dir = |t: &[[u32; 3]], c: CornerId| {
        let tri = t[c.face().idx()];
        let k = (c.0 % 3) as usize;
        tri[(k + 1) % 3] > tri[(k + 2) % 3]
    };
    let nf = triangles.len();
    let mut flip = vec![false; nf];
    let mut comp = vec![u32::MAX; nf];
    let mut stack = Vec::new();
    let mut members = Vec::new();
    let mut ncomp = 0u32;
    for f0 in 0..nf {
        if comp[f0] != u32::MAX {
            continue;
        }
        comp[f0] = ncomp;
        stack.push(f0 as u32);
        members.clear();
        while let Some(f) = stack.pop() {
            members.push(f);
            for k in 0..3 {
                let c = FaceId(f).corner(k);
                let d = o[c.idx()];
                if d.is_none() {
                    continue;
                }
                let g = d.face().idx();
                // g must run along the shared edge opposite to f.
                let want = dir(triangles, c) ^ flip[f as usize] ^ dir(triangles, d) ^ true;
                if comp[g] == u32::MAX {
                    comp[g] = ncomp;
                    flip[g] = want;
                    stack.push(g as u32);
                } else if flip[g] != want {
                    return Err(TopologyError::NonOrientable {
                        component: ncomp,
                        face: g as u32,
                    }
                    .into());
                }
            }
        }
        let flipped = members.iter().filter(|&&f| flip[f as usize]).count();
        if 2 * flipped > members.len() {
            for &f in &members {
                flip[f as usize] = !flip[f as usize];
            }
        }
        ncomp += 1;
    }
    for (t, &fl) in triangles.iter_mut().zip(&flip) {
        if fl {
            t.swap(1, 2);
            report.flipped_faces += 1;
        }
    }
    flipped.copy_from_slice(&flip);
    if report.flipped_faces > 0 {
        // Swapping vertices 1 and 2 of a face swaps the edges its corners
        // 1 and 2 face; renumber those corners on both sides of each pair.
        let moved = |c: CornerId| match c.0 % 3 {
            0 => c,
            _ if !flip[c.face().idx()] => c,
            1 => CornerId(c.0 + 1),
            _ => CornerId(c.0 - 1),
        };
        let mut flipped_o = vec![CornerId::NONE; o.len()];
        for (c, &d) in o.iter().enumerate() {
            if d.is_some() {
                flipped_o[moved(CornerId(c as u32)).idx()] = moved(d);
            }
        }
        o = flipped_o;
    }
    let pairing = Pairing {
        o,
        cut_edges: report.non_manifold_edges,
        same_direction: 0,
    };
    Ok((ncomp as u64, pairing))
}

/// Step 5: at each edge that three or more faces share, pairs again the
/// two oppositely oriented faces that meet most smoothly (largest dot
/// product of unit normals), then the next two, and leaves the rest cut.
///
/// Cutting every face of such an edge would slit a closed body open along
/// a fin's root and shatter the fin into faces that each become a
/// component of their own (beetle.obj: 31 one- to three-face pieces and
/// 23 slits); keeping the smoothest pair keeps the body whole and detaches
/// only what sticks out of it. Any two faces running the edge in opposite
/// directions make a manifold pair, so the choice is only about shape.
fn rejoin_smoothest(triangles: &[[u32; 3]], positions: &[[f32; 3]], o: &mut [CornerId]) {
    // Unpaired corners, keyed by the undirected edge they face.
    let mut open: Vec<([u32; 2], u32)> = (0..o.len() as u32)
        .filter(|&c| o[c as usize].is_none())
        .map(|c| {
            let t = triangles[(c / 3) as usize];
            let k = (c % 3) as usize;
            let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
            ([a.min(b), a.max(b)], c)
        })
        .collect();
    open.sort_unstable();
    let p = |v: u32| glam::DVec3::from(positions[v as usize].map(f64::from));
    let normal = |c: u32| {
        let [a, b, d] = triangles[(c / 3) as usize].map(p);
        (b - a).cross(d - a).normalize_or_zero()
    };
    // Direction of the half-edge facing corner c: low → high or not.
    let up = |c: u32| {
        let t = triangles[(c / 3) as usize];
        let k = (c % 3) as usize;
        t[(k + 1) % 3] < t[(k + 2) % 3]
    };
    for group in open.chunk_by(|x, y| x.0 == y.0).filter(|g| g.len() >= 3) {
        let mut free: Vec<u32> = group.iter().map(|&(_, c)| c).collect();
        loop {
            let mut best: Option<(f64, usize, usize)> = None;
            for i in 0..free.len() {
                for j in i + 1..free.len() {
                    let (a, b) = (free[i], free[j]);
                    if up(a) == up(b) {
                        continue;
                    }
                    let d = normal(a).dot(normal(b));
                    // Ties (and NaN normals) go to the lowest corners.
                    if best.is_none_or(|(bd, _, _)| d > bd) {
                        best = Some((d, i, j));
                    }
                }
            }
            let Some((_, i, j)) = best else { break };
            let (a, b) = (free[i], free[j]);
            o[a as usize] = CornerId(b);
            o[b as usize] = CornerId(a);
            free.swap_remove(j);
            free.swap_remove(i);
        }
    }
}

/// Steps 5 and 6: pairs half-edges (cutting non-manifold edges) and gives
/// every extra fan of a vertex its own copy of the vertex; returns the
/// corner table of the result, built by the last round.
///
/// `pairing` is the half-edge pairing of `mesh` as it comes in (from
/// [`orient`]); later rounds pair the edges of the split mesh again.
fn split_non_manifold(
    mesh: &mut TriMesh,
    pairing: Pairing,
    report: &mut CleanReport,
) -> Result<CornerTable, Error> {
    let mut split = vec![false; mesh.positions.len()];
    let mut given = Some(pairing);
    // Each round adds at least one vertex, so this bound is never reached;
    // it only guards against a logic error turning into a hang.
    for _round in 0..mesh.triangles.len() + 1 {
        let pairing = match given.take() {
            Some(p) => p,
            None => super::corner::pair_half_edges(&mesh.triangles, mesh.positions.len()),
        };
        let v: Vec<VertexId> = mesh
            .triangles
            .iter()
            .flat_map(|t| t.iter().map(|&i| VertexId(i)))
            .collect();
        let (first, extra) = vertex_fans(&v, &pairing.o, mesh.positions.len());
        if extra.is_empty() {
            if pairing.cut_edges > 0 {
                // Impossible by the argument in the module docs; refuse
                // rather than hand out a table with a cut edge.
                let (edges, vertices) = (pairing.cut_edges, 0);
                return Err(TopologyError::NonManifold { edges, vertices }.into());
            }
            return Ok(CornerTable::from_raw(v, pairing.o, first));
        }
        for (vertex, start) in extra {
            if !split[vertex.idx()] {
                split[vertex.idx()] = true;
                report.non_manifold_vertices += 1;
            }
            let copy = mesh.positions.len() as u32;
            mesh.positions.push(mesh.positions[vertex.idx()]);
            split.push(true);
            report.split_vertices_added += 1;
            // Swing left over this fan (as vertex_fans did) and relabel it.
            let mut c = start;
            loop {
                mesh.triangles[c.face().idx()][(c.0 % 3) as usize] = copy;
                let l = pairing.o[c.next().idx()];
                if l.is_none() || l.next() == start {
                    break;
                }
                c = l.next();
            }
        }
    }
    // Every round splits a vertex and there are at most 3F corners, so this
    // is never reached; an error is still better than a panic.
    Err(TopologyError::NonManifold {
        edges: 0,
        vertices: report.non_manifold_vertices,
    }
    .into())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(p: &[[f32; 3]], t: &[[u32; 3]]) -> TriMesh {
        TriMesh::new(p.to_vec(), t.to_vec())
    }

    /// A tetrahedron with outward faces.
    fn tetra() -> TriMesh {
        mesh(
            &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            &[[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        )
    }

    #[test]
    fn clean_mesh_passes_unchanged() {
        let m = tetra();
        let c = clean(&m, &CleanOptions::default()).unwrap();
        assert!(c.report.is_clean(), "{:?}", c.report);
        assert_eq!(c.mesh, m);
        c.table.check().unwrap();
        let comps = c.table.components();
        assert_eq!(
            (comps.len(), comps[0].genus, comps[0].boundary_loops),
            (1, 0, 0)
        );
    }

    #[test]
    fn merges_coincident_vertices_including_signed_zero() {
        // Two triangles of a square, each with its own copy of the diagonal.
        let m = mesh(
            &[
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 1., 0.],
                [-0.0, 0., 0.],
                [1., 1., 0.],
                [0., 1., 0.],
            ],
            &[[0, 1, 2], [3, 4, 5]],
        );
        let c = clean(&m, &CleanOptions::default()).unwrap();
        assert_eq!(c.report.merged_vertices, 2);
        assert_eq!(c.mesh.positions.len(), 4);
        assert_eq!(c.table.components()[0].boundary_loops, 1);
        assert!(
            c.table.opposite(CornerId(1)).is_some(),
            "the diagonal must be shared"
        );
    }

    #[test]
    fn drops_degenerate_and_duplicate_faces() {
        let mut m = tetra();
        m.positions.push([0.5, 0.0, 0.0]); // on edge 0-1: collinear
        m.triangles.push([0, 0, 1]); // repeated index
        m.triangles.push([0, 4, 1]); // zero area
        m.triangles.push([2, 1, 0]); // duplicate of face 0
        m.triangles.push([0, 1, 2]); // duplicate, opposite orientation
        let c = clean(&m, &CleanOptions::default()).unwrap();
        let r = &c.report;
        assert_eq!(
            (r.repeated_index_faces, r.zero_area_faces, r.duplicate_faces),
            (1, 1, 2)
        );
        assert_eq!(r.unreferenced_vertices, 1);
        assert_eq!(c.mesh.triangles, tetra().triangles);
    }

    #[test]
    fn orients_by_majority() {
        let mut m = tetra();
        m.triangles[2].swap(0, 1);
        let c = clean(&m, &CleanOptions::default()).unwrap();
        assert_eq!(c.report.flipped_faces, 1);
        assert_eq!(c.mesh.triangles[2], [2, 3, 1]); // [1, 2, 3] rotated
        c.table.check().unwrap();
    }

    #[test]
    fn non_orientable_strip_is_an_error() {
        // A Moebius strip: a band of 6 quads whose ends are glued with a twist.
        let n = 6u32;
        let mut p = Vec::new();
        for i in 0..n {
            let a = i as f32 / n as f32 * std::f32::consts::TAU;
            let tw = a / 2.0;
            for s in [-1.0f32, 1.0] {
                let r = 2.0 + 0.5 * s * tw.cos();
                p.push([r * a.cos(), r * a.sin(), 0.5 * s * tw.sin()]);
            }
        }
        let mut t = Vec::new();
        for i in 0..n {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 < n {
                (2 * i + 2, 2 * i + 3)
            } else {
                (1, 0)
            };
            t.push([a, c, b]);
            t.push([b, c, d]);
        }
        let err = clean(&mesh(&p, &t), &CleanOptions::default()).unwrap_err();
        assert!(
            matches!(err, Error::Topology(TopologyError::NonOrientable { .. })),
            "{err}"
        );
    }

    #[test]
    fn bowtie_vertex_is_split() {
        // Two triangles touching at one vertex.
        let m = mesh(
            &[
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 1., 0.],
                [-1., 0., 0.],
                [-1., -1., 0.],
            ],
            &[[0, 1, 2], [0, 3, 4]],
        );
        let c = clean(&m, &CleanOptions::default()).unwrap();
        assert_eq!(
            (
                c.report.non_manifold_vertices,
                c.report.split_vertices_added
            ),
            (1, 1)
        );
        assert_eq!(c.mesh.positions.len(), 6);
        assert_eq!(c.table.components().len(), 2);
        assert_eq!(c.report.input_components, 2);
        c.table.check().unwrap();
    }

    /// Components joined through any shared edge, by sorting every edge
    /// (what `edge_components` computed before it used the pairing).
    fn components_by_sorting(triangles: &[[u32; 3]]) -> u64 {
        let mut edges: Vec<(u32, u32, u32)> = Vec::new();
        for (f, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edges.push((a.min(b), a.max(b), f as u32));
            }
        }
        edges.sort_unstable();
        let mut label: Vec<u32> = (0..triangles.len() as u32).collect();
        // Relabel to a fixed point: slow and obviously right.
        loop {
            let mut changed = false;
            for w in edges.windows(2) {
                if (w[0].0, w[0].1) == (w[1].0, w[1].1) {
                    let (a, b) = (label[w[0].2 as usize], label[w[1].2 as usize]);
                    if a != b {
                        let low = a.min(b);
                        label[w[0].2 as usize] = low;
                        label[w[1].2 as usize] = low;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        let mut roots = label.clone();
        roots.sort_unstable();
        roots.dedup();
        roots.len() as u64
    }

    #[test]
    fn components_through_cut_edges_match_a_full_edge_sort() {
        // A sphere with fins on some edges (three and four faces on an
        // edge), fins whose far vertex is shared with another fin, and
        // loose triangles hanging off fins or off nothing.
        let sphere = crate::mesh::test_shapes::uv_sphere(10, 7);
        let n = sphere.positions.len() as u32;
        for fins in [1usize, 2, 5, 9] {
            let mut m = sphere.clone();
            let mut extra = 0u32;
            for (i, t) in sphere.triangles.iter().enumerate().step_by(7).take(fins) {
                let tip = n + extra;
                m.positions.push([3.0 + i as f32, 0.1 * i as f32, 0.5]);
                m.triangles.push([t[0], t[1], tip]);
                if i % 2 == 0 {
                    // A second page on the same edge, the other way round.
                    m.positions.push([-3.0 - i as f32, 0.2, 0.1 * i as f32]);
                    m.triangles.push([t[1], t[0], tip + 1]);
                    extra += 1;
                }
                extra += 1;
            }
            // A lone triangle, and one sharing an edge with the first fin.
            let base = m.positions.len() as u32;
            m.positions
                .extend([[9., 9., 9.], [9., 10., 9.], [10., 9., 9.], [5., 5., 5.]]);
            m.triangles.push([base, base + 1, base + 2]);
            let fin = m.triangles[sphere.triangles.len()];
            m.triangles.push([fin[1], fin[2], base + 3]);
            let c = clean(&m, &CleanOptions::default()).unwrap();
            assert_eq!(
                c.report.input_components,
                components_by_sorting(&m.triangles),
                "{fins} fins"
            );
            assert!(c.report.non_manifold_edges > 0);
        }
    }

    #[test]
    fn fin_edge_is_cut() {
        // Three triangles on edge 0-1 (a book with three pages).
        let m = mesh(
            &[
                [0., 0., 0.],
                [0., 0., 1.],
                [1., 0., 0.],
                [0., 1., 0.],
                [-1., -1., 0.],
            ],
            &[[0, 1, 2], [1, 0, 3], [0, 1, 4]],
        );
        let c = clean(&m, &CleanOptions::default()).unwrap();
        assert_eq!(c.report.non_manifold_edges, 1);
        assert_eq!(c.report.input_components, 1);
        c.table.check().unwrap();
        // Whatever was split, every edge is now used by at most two faces.
        let total_faces: u64 = c.table.components().iter().map(|k| k.faces).sum();
        assert_eq!(total_faces, 3);
        // Pages 1 and 2 run the edge in opposite directions and meet at
        // 45° (page 0 meets page 1 at 90°): they stay joined, page 0 goes.
        assert_eq!(c.table.components().len(), 2);
        let joined = |f: u32, g: u32| {
            (0..3).any(|k| c.table.opposite(FaceId(f).corner(k)).face() == FaceId(g))
        };
        assert!(joined(1, 2) && !joined(0, 1) && !joined(0, 2));
    }

    #[test]
    fn nothing_left_is_an_error() {
        let m = mesh(&[[0., 0., 0.], [1., 0., 0.], [2., 0., 0.]], &[[0, 1, 2]]);
        assert!(matches!(
            clean(&m, &CleanOptions::default()),
            Err(Error::Topology(TopologyError::NoTriangles))
        ));
    }

    use crate::mesh::test_rng::Rng;

    #[test]
    fn merging_by_hash_matches_sorting() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for n in [0usize, 1, 2, 7, 100, 5000] {
            // Few distinct values, so many positions coincide; -0.0 too.
            let values = [0.0f32, -0.0, 1.0, -1.5, 3.25e-8, f32::MAX];
            let p: Vec<[f32; 3]> = (0..n)
                .map(|_| [0; 3].map(|_| values[rng.below(values.len() as u64) as usize]))
                .collect();
            assert_eq!(
                merge_coincident(&p),
                merge_coincident_by_sorting(&p),
                "n = {n}"
            );
        }
    }

    #[test]
    fn duplicate_faces_match_sorting() {
        let mut rng = Rng(7);
        for round in 0..300 {
            // Small vertex counts make duplicates and big groups common.
            let vertices = 3 + rng.below(if round % 2 == 0 { 5 } else { 40 }) as usize;
            let tris: Vec<[u32; 3]> = (0..1 + rng.below(60))
                .map(|_| [0; 3].map(|_| rng.below(vertices as u64)))
                .filter(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
                .collect();
            // The reference: sort the faces by their sorted triples and
            // drop all but the first of each run.
            let mut keyed: Vec<([u32; 3], usize)> = tris
                .iter()
                .enumerate()
                .map(|(f, t)| {
                    let mut k = *t;
                    k.sort_unstable();
                    (k, f)
                })
                .collect();
            keyed.sort_unstable();
            let mut expected = vec![false; tris.len()];
            for w in keyed.windows(2) {
                if w[0].0 == w[1].0 {
                    expected[w[1].1] = true;
                }
            }
            assert_eq!(duplicate_faces(&tris, vertices), expected, "{tris:?}");
        }
    }

    /// Messy copies of a torus (faces flipped one by one and whole
    /// components at once, duplicated faces, split vertices, a fin)
    /// clean to a mesh whose table is the one built from scratch: the
    /// pairing that orientation hands on is the real one.
    #[test]
    fn cleaned_table_is_the_table_of_the_result() {
        let torus = crate::edgebreaker::tests_support::torus(9, 6);
        let mut rng = Rng(11);
        let (mut flipped, mut cut) = (0, 0);
        for round in 0..60 {
            let mut m = torus.clone();
            let n = m.positions.len() as u32;
            // A second, whole copy, flipped in even rounds.
            m.positions
                .extend(torus.positions.iter().map(|p| [p[0] + 10.0, p[1], p[2]]));
            for f in 0..torus.triangles.len() {
                let mut t = torus.triangles[f].map(|v| v + n);
                if round % 2 == 0 {
                    t.swap(0, 1);
                }
                m.triangles.push(t);
            }
            for _ in 0..rng.below(6) {
                let f = rng.below(m.triangles.len() as u64) as usize;
                m.triangles[f].swap(1, 2);
            }
            for _ in 0..rng.below(3) {
                let f = rng.below(m.triangles.len() as u64) as usize;
                let t = m.triangles[f];
                m.triangles.push([t[1], t[0], t[2]]);
            }
            if round % 3 == 0 {
                // A fin on the first edge of face 0, and a vertex copy.
                let t = m.triangles[0];
                m.positions.push([9.0, 9.0, 9.0]);
                m.triangles.push([t[0], t[1], m.positions.len() as u32 - 1]);
                m.positions.push(m.positions[t[2] as usize]);
            }
            let c = clean(&m, &CleanOptions::default()).unwrap();
            let fresh = CornerTable::new(&c.mesh.triangles, c.mesh.vertex_count()).unwrap();
            assert_eq!(c.table, fresh, "round {round}: {:?}", c.report);
            assert_eq!(c.report.input_components, 2, "round {round}");
            flipped += usize::from(c.report.flipped_faces > 0);
            cut += usize::from(c.report.non_manifold_edges > 0);
        }
        assert!(
            flipped > 20 && cut > 10,
            "{flipped} rounds flipped, {cut} cut"
        );
    }
}
