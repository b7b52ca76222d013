//! The quadric collapse sequence of a large input made in spatial pieces
//! on several cores, then finished over the whole mesh (the collapse of
//! `qem`, beyond Garland & Heckbert's single greedy loop).
//!
//! On a million-triangle scan the single loop takes 5-7 s of one core,
//! most of `default`'s encode and of the displaced method's (issue 46).
//! The pieces' loops cost about what their share of it did (5.5 s of
//! the 6.8 on bunny-1m, one thread, a loaded machine), so the gain is
//! the cores': on two, the sequence in about half the time. Here:
//!
//! ```text
//!   input ──► the pieces of `chunked` (median cuts, the cut vertices:
//!             those used by faces of two pieces)
//!     │
//!     ├─ piece k, its own greedy loop in the whole mesh's frame, its cut
//!     │  vertices locked, down to PIECE_SHARE of its faces     ┐ in parallel
//!     ├─ ...                                                   ┘
//!     ▼
//!   the pieces' collapses merged into one sequence, cheapest next first
//!   (ties: the lower piece), each step's face count the whole mesh's;
//!   then the greedy loop over the whole mesh so reached (quadrics made
//!   anew from its faces, the cuts free) down to the floor
//! ```
//!
//! Why it is still a collapse sequence [`Collapses::replay`] can cut
//! anywhere: a piece's collapses touch only its own vertices (those of a
//! cut are locked and never move), so any interleaving of the pieces'
//! sequences is one the whole mesh could have taken, and every prefix is
//! a manifold. A non-cut vertex's faces all lie in its piece, so its
//! quadric, ring, link and boundary tests are the whole mesh's; a cut
//! vertex seen from a piece has fewer neighbours and looks like a
//! boundary, which only makes the tests around it stricter.
//!
//! The second phase starts from fresh quadrics, as meshoptimizer's own
//! chunked use does: the memory of the first phase's error is dropped at
//! an eighth of the input's faces, below which the encoder's files lie
//! (bunny-1m: 14k-faces bases, 50-100k-faces simplifications at 1-2 b/v).
//!
//! Invariants: the pieces, their sequences and the merge depend only on
//! the mesh, so the sequence is the same at any thread count; face counts
//! along it fall strictly, as `replay` needs.

use super::chunked::{cut_vertices, pieces};
use super::qem::{greedy, Collapses, Frame, State, Step};
use crate::TriMesh;
use rayon::prelude::*;

/// Inputs with at least this many faces are collapsed in pieces: the
/// size where `chunked` pays for meshoptimizer's pass too.
pub(super) const PIECEWISE_FACES: usize = super::chunked::CHUNKED_FACES;
/// Each piece collapses to this share of its faces before the whole mesh
/// takes over.
const PIECE_SHARE: f64 = 0.125;

/// The collapse sequence of `mesh` down to `floor` faces: in pieces (see
/// the module's docs) from [`PIECEWISE_FACES`] faces, else
/// [`Collapses::run`]'s single loop.
pub(super) fn collapses(mesh: &TriMesh, floor: u32) -> Collapses {
    if mesh.face_count() < PIECEWISE_FACES {
        return Collapses::run(mesh, floor);
    }
    run(mesh, floor)
}

/// The piecewise sequence of `mesh` down to `floor` faces.
fn run(mesh: &TriMesh, floor: u32) -> Collapses {
    let frame = Frame::of(mesh);
    let pieces = pieces(mesh);
    let cut = cut_vertices(mesh, &pieces);
    let runs: Vec<(Vec<Step>, Vec<f64>)> = pieces
        .par_iter()
        .map(|piece| piece_run(mesh, piece, &cut, frame, floor))
        .collect();
    let total = mesh.face_count() as u32;
    let mut steps: Vec<Step> = Vec::with_capacity(runs.iter().map(|r| r.0.len()).sum());
    // Merge: the piece whose next collapse costs least goes first.
    let mut next = vec![0usize; runs.len()];
    let mut before: Vec<u32> = pieces.iter().map(|p| p.len() as u32).collect();
    let mut faces = total;
    loop {
        let pick = (0..runs.len())
            .filter(|&k| next[k] < runs[k].0.len())
            .min_by(|&a, &b| runs[a].1[next[a]].total_cmp(&runs[b].1[next[b]]));
        let Some(k) = pick else {
            break;
        };
        let step = runs[k].0[next[k]];
        next[k] += 1;
        faces -= before[k] - step.faces_after;
        before[k] = step.faces_after;
        steps.push(Step {
            faces_after: faces,
            ..step
        });
    }
    drop(runs);
    let mut collapses = Collapses {
        faces: total,
        steps,
    };
    if faces <= floor {
        return collapses;
    }
    // The whole mesh as the pieces left it, and the loop over it.
    let middle = collapses.replay(mesh, faces);
    let mut state = State::new(&middle, frame, None);
    drop(middle);
    greedy(&mut state, floor, |step, _| collapses.steps.push(step));
    collapses
}

/// One piece's greedy sequence (vertices numbered as in `mesh`, face
/// counts the piece's) and each collapse's cost.
fn piece_run(
    mesh: &TriMesh,
    piece: &[u32],
    cut: &[bool],
    frame: Frame,
    floor: u32,
) -> (Vec<Step>, Vec<f64>) {
    // The piece as a mesh of its own, its vertices in order of first use.
    let mut local = vec![u32::MAX; mesh.positions.len()];
    let mut global: Vec<u32> = Vec::new();
    let triangles: Vec<[u32; 3]> = piece
        .iter()
        .map(|&f| {
            mesh.triangles[f as usize].map(|v| {
                let slot = &mut local[v as usize];
                if *slot == u32::MAX {
                    *slot = global.len() as u32;
                    global.push(v);
                }
                *slot
            })
        })
        .collect();
    let positions = global.iter().map(|&v| mesh.positions[v as usize]).collect();
    let locked = global.iter().map(|&v| cut[v as usize]).collect();
    let sub = TriMesh::new(positions, triangles);
    let mut state = State::new(&sub, frame, Some(locked));
    let stop = ((piece.len() as f64 * PIECE_SHARE) as u32).max(floor);
    let (mut steps, mut costs) = (Vec::new(), Vec::new());
    greedy(&mut state, stop, |step, cost| {
        steps.push(Step {
            keep: global[step.keep as usize],
            gone: global[step.gone as usize],
            ..step
        });
        costs.push(cost);
    });
    (steps, costs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_shapes::uv_sphere;

    #[test]
    fn a_piecewise_sequence_replays_to_closed_manifolds_at_any_thread_count() {
        let mesh = uv_sphere(320, 320);
        assert!(mesh.face_count() >= PIECEWISE_FACES);
        let c = collapses(&mesh, 4);
        // Face counts fall strictly along the sequence.
        assert!(c
            .steps
            .windows(2)
            .all(|w| w[1].faces_after < w[0].faces_after));
        for target in [150_000u32, 30_000, 2_000, 100] {
            let m = c.replay(&mesh, target);
            assert!(m.face_count() <= target as usize, "{target}");
            assert!(m.face_count() + 4 >= target as usize, "{target}");
            // Closed and manifold: every directed edge once, its twin once.
            let mut edges: Vec<(u32, u32)> = m
                .triangles
                .iter()
                .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
                .collect();
            edges.sort_unstable();
            assert!(edges.windows(2).all(|w| w[0] != w[1]), "{target}");
            for &(a, b) in &edges {
                assert!(edges.binary_search(&(b, a)).is_ok(), "{target}: {a}-{b}");
            }
            // Still the sphere: every vertex near radius 1.
            for t in &m.triangles {
                for &v in t {
                    let p = m.positions[v as usize];
                    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                    assert!((r - 1.0).abs() < 0.05, "{target}: r {r}");
                }
            }
        }
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| collapses(&mesh, 4));
        assert_eq!(one.steps.len(), c.steps.len());
        assert!(one.steps.iter().zip(&c.steps).all(|(a, b)| (
            a.keep,
            a.gone,
            a.pos,
            a.faces_after
        ) == (
            b.keep,
            b.gone,
            b.pos,
            b.faces_after
        )));
    }
}
