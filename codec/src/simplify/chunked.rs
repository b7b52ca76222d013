//! meshoptimizer's simplification of a large input in spatial chunks on
//! several cores (effort `fast`, [`super::Simplifier::quick`]).
//!
//! meshoptimizer's simplifier is single-threaded and its first pass over
//! the input costs about a microsecond a face: on a million-triangle scan
//! it was most of `fast`'s encode (1.2 of 2.2-2.4 s at 2 b/v, against a
//! bar of twice Draco's 1.2 s). Beyond the library (whose chunked use,
//! with `LockBorder`, is documented for terrain levels of detail):
//!
//! ```text
//!   input faces ──► CHUNKS pieces, split at the median face centre
//!                   along the longest side of their box, recursively
//!        │
//!        ├─ piece k: simplified to target · faces_k / faces, its cut
//!        │           vertices (used by another piece) locked  ─┐ in
//!        ├─ ...                                                 │ parallel
//!        ▼                                                      ┘
//!   the pieces' triangles together, then one plain pass to the target:
//!   the cut's strip, left at the input's resolution, collapses there
//! ```
//!
//! Only the cut vertices are locked (not `LockBorder`, which would also
//! pin the input's own holes). The pieces are simplified with `Sparse`,
//! so each costs its own faces, not the whole vertex array.
//!
//! Invariants: the pieces and their order depend only on the mesh (the
//! median is taken by a total order on (coordinate, face index)), and
//! each piece's simplification is meshoptimizer's deterministic one, so
//! the result depends only on the mesh and the target, never on the
//! thread count. Below [`CHUNKED_FACES`] faces the plain single pass is
//! used, unchanged.

use crate::TriMesh;
use rayon::prelude::*;

/// Inputs with at least this many faces are simplified in chunks: below
/// it the single pass takes under a fifth of a second and the last pass
/// over the joined pieces would eat most of the saving.
pub(super) const CHUNKED_FACES: usize = 200_000;
/// How far above its share of the target each piece stops, so that the
/// last pass has faces to take from the cuts' strips (left at the
/// input's resolution, they are its cheapest collapses).
const PIECE_SLACK: f64 = 1.1;
/// Pieces: a power of two, fixed (never the thread count, which would
/// change the result). Four keep two cores busy when the pieces' costs
/// differ, for three cuts' strips.
const CHUNKS: usize = 4;

/// The triangles (indices into `mesh.positions`) of `mesh` simplified by
/// meshoptimizer to about `target` faces, in chunks when the mesh is
/// large (see the module's docs); `None` when meshoptimizer cannot read
/// the positions.
pub(super) fn simplified_indices(mesh: &TriMesh, target: u32) -> Option<Vec<u32>> {
    let bytes = meshopt::typed_to_bytes(&mesh.positions);
    let vertices = meshopt::VertexDataAdapter::new(bytes, 12, 0).ok()?;
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    // (meshoptimizer asserts that a target is no more than its input.)
    let plain = |indices: &[u32], options: meshopt::SimplifyOptions| {
        let aim = (3 * target as usize).min(indices.len());
        meshopt::simplify(indices, &vertices, aim, 1.0, options, None)
    };
    let faces = mesh.triangles.len();
    if faces < CHUNKED_FACES || (target as usize) >= faces {
        return Some(plain(&indices, meshopt::SimplifyOptions::None));
    }
    let pieces = pieces(mesh);
    let locks = cut_vertices(mesh, &pieces);
    let simplified: Vec<Vec<u32>> = pieces
        .par_iter()
        .map(|piece| {
            let piece_indices: Vec<u32> = piece
                .iter()
                .flat_map(|&f| mesh.triangles[f as usize])
                .collect();
            let piece_target = ((target as f64 * PIECE_SLACK * piece.len() as f64 / faces as f64)
                as usize)
                .clamp(1, piece.len());
            meshopt::simplify_with_locks(
                &piece_indices,
                &vertices,
                &locks,
                3 * piece_target,
                1.0,
                meshopt::SimplifyOptions::Sparse,
                None,
            )
        })
        .collect();
    let joined: Vec<u32> = simplified.concat();
    // (meshoptimizer asserts that a target is no more than its input.)
    if joined.len() <= 3 * target as usize {
        return Some(joined);
    }
    Some(plain(&joined, meshopt::SimplifyOptions::Sparse))
}

/// The faces of `mesh` in [`CHUNKS`] pieces of about equal count, each
/// piece's faces in increasing order: halves at the median face centre
/// along the longest side of the faces' box, recursively.
pub(super) fn pieces(mesh: &TriMesh) -> Vec<Vec<u32>> {
    // Three times the centre: the order is what matters.
    let centres: Vec<[f32; 3]> = mesh
        .triangles
        .par_iter()
        .map(|t| {
            let p = t.map(|v| mesh.positions[v as usize]);
            core::array::from_fn(|k| p[0][k] + p[1][k] + p[2][k])
        })
        .collect();
    let mut pieces = vec![(0..mesh.triangles.len() as u32).collect::<Vec<u32>>()];
    while pieces.len() < CHUNKS {
        pieces = pieces
            .into_par_iter()
            .flat_map_iter(|mut faces| {
                let axis = longest_axis(faces.iter().map(|&f| centres[f as usize]));
                let mid = faces.len() / 2;
                faces.select_nth_unstable_by(mid, |&a, &b| {
                    let (ca, cb) = (centres[a as usize][axis], centres[b as usize][axis]);
                    ca.total_cmp(&cb).then(a.cmp(&b))
                });
                let mut right = faces.split_off(mid);
                faces.sort_unstable();
                right.sort_unstable();
                [faces, right]
            })
            .collect();
    }
    pieces
}

/// The axis along which `points` spread most (0 for none).
fn longest_axis(points: impl Iterator<Item = [f32; 3]>) -> usize {
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])).then(b.cmp(&a)))
        .unwrap_or(0)
}

/// Per vertex of `mesh`: used by faces of more than one piece.
pub(super) fn cut_vertices(mesh: &TriMesh, pieces: &[Vec<u32>]) -> Vec<bool> {
    const UNSEEN: u32 = u32::MAX;
    let mut owner = vec![UNSEEN; mesh.positions.len()];
    let mut cut = vec![false; mesh.positions.len()];
    for (k, piece) in pieces.iter().enumerate() {
        for &f in piece {
            for v in mesh.triangles[f as usize] {
                let o = &mut owner[v as usize];
                if *o == UNSEEN {
                    *o = k as u32;
                } else if *o != k as u32 {
                    cut[v as usize] = true;
                }
            }
        }
    }
    cut
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_shapes::uv_sphere;

    #[test]
    fn pieces_cover_every_face_once_in_equal_counts() {
        let mesh = uv_sphere(60, 80);
        let pieces = pieces(&mesh);
        assert_eq!(pieces.len(), CHUNKS);
        let mut all: Vec<u32> = pieces.concat();
        all.sort_unstable();
        assert_eq!(all, (0..mesh.triangles.len() as u32).collect::<Vec<_>>());
        let (min, max) = pieces.iter().fold((usize::MAX, 0), |(a, b), p| {
            (a.min(p.len()), b.max(p.len()))
        });
        assert!(max - min <= 2, "{min}..{max}");
        // Cut vertices exist (the pieces touch) and are a small share.
        let cut = cut_vertices(&mesh, &pieces).iter().filter(|&&c| c).count();
        assert!(cut > 0 && cut * 10 < mesh.positions.len(), "{cut}");
    }

    #[test]
    fn a_chunked_simplification_reaches_its_target_without_holes_at_the_cuts() {
        // Above the threshold: a closed sphere of about 200k faces.
        let mesh = uv_sphere(320, 320);
        assert!(mesh.triangles.len() >= CHUNKED_FACES);
        let target = 5_000u32;
        let indices = simplified_indices(&mesh, target).unwrap();
        let faces = indices.len() / 3;
        assert!(
            faces <= target as usize && faces * 10 >= 9 * target as usize,
            "{faces}"
        );
        // Closed: every directed edge has its twin.
        let mut edges: Vec<(u32, u32)> = indices
            .chunks_exact(3)
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .collect();
        edges.sort_unstable();
        for &(a, b) in &edges {
            assert!(edges.binary_search(&(b, a)).is_ok(), "open edge {a}-{b}");
        }
        // The same at any thread count.
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| simplified_indices(&mesh, target).unwrap());
        assert_eq!(one, indices);
    }
}
