//! Where every decoded vertex came from (issue 45, item 3): for each
//! vertex of the file as decoded plainly (no post-processing, the
//! vertices the file itself places), a face of the input *as the caller
//! gave it* and barycentric coordinates on it, so that texture
//! coordinates, normals and colours can be resampled from the input
//! without asking the method that made the file.
//!
//! How, in two steps:
//! 1. A point of the job's reference surface (the cleaned input, which
//!    the chooser and the check already hold in a tree): the nearest one,
//!    unless a descent over the surface finds one on the sheet the vertex
//!    was made from. The descent starts at the method's *seed* where it
//!    gave one: for the simplified method, and displaced subdivision for
//!    its base's vertices, the survivor of the collapses that made the
//!    vertex (`Simplifier::sources`); for SwingWrapper, the retiler's own
//!    record, a corner of the input face holding the on-surface sample
//!    each tip was fitted from (`retile::compose::seed`, numbered as the
//!    decoder numbers the vertices once the hole mask drops some). Else it
//!    starts at the face where the vertex's parent was found: its
//!    lowest-numbered neighbour in the decoded mesh, made before it (a
//!    subdivided vertex's edge end, the lossless traversal's earlier
//!    vertex). It takes the nearest point of the faces around a corner of
//!    the best face so far while that gets nearer. Its answer stands if it
//!    is no farther than the nearest point by more than a quarter of the
//!    vertex's shortest edge: across a part thinner than the file's error
//!    (a leaf, a shell, a coarse grid's cell spanning both sides) the
//!    nearest point is on the wrong sheet, and the descent keeps the right
//!    one; a descent stuck behind a fold is off by an edge or more, and
//!    the nearest point is taken. A vertex with neither seed nor parent (a
//!    component's first, `REST`'s kept components' first) takes the
//!    nearest point.
//! 2. The caller's face of that point, through the positions of its
//!    corners. Cleaning never moves a vertex (it merges coincident ones,
//!    drops degenerate and repeated faces, reorients and splits), so a
//!    cleaned face has the same three positions as the face of the input
//!    it came from: a sorted table of position triples finds it. A
//!    reference face with no such twin (a wide fan the simplifier
//!    rebuilt, `Simplifier::reference`) is replaced by the input face
//!    nearest the point among those sharing a corner position with it.
//!
//! Invariants: one origin per decoded vertex, in the decoder's vertex
//! order; `face` indexes the caller's triangles; the barycentric
//! coordinates are non-negative, sum to one, and follow the caller's
//! corner order of that face. The descent strictly shortens the distance
//! at each step and takes at most [`MAX_STEPS`]. Deterministic (queries in
//! vertex order, one thread; ties go to the lower face number).

use super::stats::Origin;
use crate::mesh::clean::position_key as key;
use crate::metrics::{barycentric, NearestScratch, Surface};
use crate::TriMesh;
use alloc::vec::Vec;

/// Steps of the descent from a seed at most: each visits the faces
/// around three vertices. A simplified vertex stands a few rings from its
/// survivor's place even at the coarsest rates; the bound only keeps a
/// hostile case linear.
pub(crate) const MAX_STEPS: usize = 256;

/// The origin of every vertex of the file `bytes` decoded plainly;
/// `seeds`, when the method gave them, the reference vertex each decoded
/// vertex stands for (`u32::MAX`, or past the list's end: none).
pub(crate) fn of_file(
    job: &super::method::Job<'_, '_>,
    bytes: &[u8],
    seeds: Option<&[u32]>,
) -> Result<Vec<Origin>, crate::Error> {
    let decoded = crate::decoder::decode(bytes, &crate::options::DecodeOptions::plain())?;
    Ok(origins(
        job.services_input(),
        job.simplifier().reference(),
        job.reference()?,
        &decoded,
        seeds.filter(|s| s.len() <= decoded.vertex_count()),
    ))
}

/// The origin of every vertex of `decoded` on `input`, through the
/// surface `reference` made from `reference_mesh` (the cleaned input),
/// from `seeds` where given (see the module's docs).
pub(crate) fn origins(
    input: &TriMesh,
    reference_mesh: &TriMesh,
    reference: &Surface,
    decoded: &TriMesh,
    seeds: Option<&[u32]>,
) -> Vec<Origin> {
    let twins = Twins::new(input);
    let fans = Fans::new(reference_mesh);
    let near = Neighbours::new(decoded);
    let mut around: Option<Around> = None;
    let mut scratch = NearestScratch::default();
    let mut hint = None;
    // The reference face each decoded vertex's point is on, as found.
    let mut on: Vec<u32> = Vec::with_capacity(decoded.positions.len());
    let mut out = Vec::with_capacity(decoded.positions.len());
    for (i, p) in decoded.positions.iter().enumerate() {
        let q = p.map(|c| c as f64);
        let nearest = reference.nearest_point(q, hint, &mut scratch);
        let Some((f, point, slot)) = nearest else {
            on.push(u32::MAX);
            out.push(Origin {
                face: 0,
                barycentric: [1.0, 0.0, 0.0],
            });
            continue;
        };
        hint = Some(slot);
        // Where the descent starts: the method's seed, else a corner of
        // the face the vertex's parent (its lowest-numbered neighbour,
        // made before it) was found on.
        let start = match seeds.and_then(|s| s.get(i).copied()).unwrap_or(u32::MAX) {
            u32::MAX => near.parent[i]
                .and_then(|u| on.get(u as usize))
                .filter(|&&g| g != u32::MAX)
                .map(|&g| reference_mesh.triangles[g as usize][0]),
            seed => Some(seed),
        };
        let global = crate::metrics::distance2(q, point).sqrt();
        let (f, point) = match start.and_then(|v| descend(reference_mesh, &fans, q, v)) {
            Some((g, x)) if crate::metrics::distance2(q, x).sqrt() <= global + near.reach[i] => {
                (g, x)
            }
            _ => (f, point),
        };
        on.push(f);
        let corners =
            reference_mesh.triangles[f as usize].map(|v| reference_mesh.positions[v as usize]);
        let face = match twins.find(&corners) {
            Some(face) => face,
            None => around
                .get_or_insert_with(|| Around::new(input))
                .nearest(input, &corners, point),
        };
        let t = input.triangles[face as usize].map(|v| input.positions[v as usize]);
        out.push(Origin {
            face,
            barycentric: barycentric(&t, point),
        });
    }
    out
}

/// What the descent needs of the decoded mesh's connectivity.
struct Neighbours {
    /// Each vertex's lowest-numbered neighbour below it, if any: made
    /// before it (a retiled tip's gate, a subdivided vertex's edge end, a
    /// traversal's earlier vertex).
    parent: Vec<Option<u32>>,
    /// How much farther than the nearest point a descent's answer may be
    /// and still be taken: a quarter of the vertex's shortest edge. A
    /// sheet on the other side of a thin part is nearer by at most the
    /// part's thickness; a descent stuck behind a fold is off by about
    /// the distance it had to go, an edge or more, and gives way.
    reach: Vec<f64>,
}

impl Neighbours {
    fn new(mesh: &TriMesh) -> Neighbours {
        let n = mesh.vertex_count();
        let mut parent: Vec<Option<u32>> = vec![None; n];
        let mut shortest = vec![f64::INFINITY; n];
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let (lo, hi) = (a.min(b), a.max(b));
                let (Some(pa), Some(pb)) = (
                    mesh.positions.get(a as usize),
                    mesh.positions.get(b as usize),
                ) else {
                    continue;
                };
                let d = crate::metrics::distance2(pa.map(f64::from), pb.map(f64::from)).sqrt();
                for v in [a, b] {
                    shortest[v as usize] = shortest[v as usize].min(d);
                }
                if lo != hi {
                    let slot = &mut parent[hi as usize];
                    *slot = Some(slot.map_or(lo, |p| p.min(lo)));
                }
            }
        }
        let reach = shortest
            .into_iter()
            .map(|d| if d.is_finite() { 0.25 * d } else { 0.0 })
            .collect();
        Neighbours { parent, reach }
    }
}

/// The faces around each vertex of a mesh.
struct Fans {
    /// Where each vertex's faces start in `faces` (one more entry than
    /// vertices).
    start: Vec<u32>,
    faces: Vec<u32>,
}

impl Fans {
    fn new(mesh: &TriMesh) -> Fans {
        let n = mesh.vertex_count();
        let mut start = vec![0u32; n + 1];
        for &v in mesh.triangles.iter().flatten() {
            if let Some(s) = start.get_mut(v as usize + 1) {
                *s += 1;
            }
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut next = start.clone();
        let mut faces = vec![0u32; start[n] as usize];
        for (f, t) in mesh.triangles.iter().enumerate() {
            for &v in t {
                if let Some(slot) = next.get_mut(v as usize) {
                    faces[*slot as usize] = f as u32;
                    *slot += 1;
                }
            }
        }
        Fans { start, faces }
    }

    fn of(&self, v: u32) -> &[u32] {
        match (self.start.get(v as usize), self.start.get(v as usize + 1)) {
            (Some(&a), Some(&b)) => &self.faces[a as usize..b as usize],
            _ => &[],
        }
    }
}

/// The nearest point to `p` found by descent over `mesh`'s faces from
/// those around `seed` (see the module's docs): its face and the point;
/// `None` when the seed has no face.
fn descend(mesh: &TriMesh, fans: &Fans, p: [f64; 3], seed: u32) -> Option<(u32, [f64; 3])> {
    let mut best: Option<(f64, u32, [f64; 3])> = None;
    let consider = |faces: &[u32], best: &mut Option<(f64, u32, [f64; 3])>| {
        for &f in faces {
            let t = mesh.triangles[f as usize].map(|v| mesh.positions[v as usize]);
            let q = crate::metrics::closest_on_triangle(p, &t);
            let d = crate::metrics::distance2(p, q);
            if best.is_none_or(|(bd, bf, _)| d < bd || (d == bd && f < bf)) {
                *best = Some((d, f, q));
            }
        }
    };
    consider(fans.of(seed), &mut best);
    for _ in 0..MAX_STEPS {
        let (d, f, _) = best?;
        for v in mesh.triangles[f as usize] {
            consider(fans.of(v), &mut best);
        }
        if best.is_some_and(|(nd, ..)| nd >= d) {
            break;
        }
    }
    best.map(|(_, f, q)| (f, q))
}

/// Input faces by their sorted corner positions.
struct Twins {
    /// (sorted corner keys, face), sorted; the first face of a repeated
    /// triple wins.
    sorted: Vec<([[u32; 3]; 3], u32)>,
}

impl Twins {
    fn new(input: &TriMesh) -> Twins {
        let mut sorted: Vec<([[u32; 3]; 3], u32)> = input
            .triangles
            .iter()
            .enumerate()
            .filter_map(|(f, t)| {
                let mut k = [[0u32; 3]; 3];
                for (slot, &v) in k.iter_mut().zip(t) {
                    *slot = key(input.positions.get(v as usize)?);
                }
                k.sort_unstable();
                Some((k, f as u32))
            })
            .collect();
        sorted.sort_unstable();
        sorted.dedup_by_key(|e| e.0);
        Twins { sorted }
    }

    fn find(&self, corners: &[[f32; 3]; 3]) -> Option<u32> {
        let mut k = corners.map(|p| key(&p));
        k.sort_unstable();
        let i = self.sorted.binary_search_by(|e| e.0.cmp(&k)).ok()?;
        Some(self.sorted[i].1)
    }
}

/// Input faces by the positions of their corners, for reference faces
/// with no twin.
struct Around {
    /// (corner key, face), sorted.
    sorted: Vec<([u32; 3], u32)>,
}

impl Around {
    fn new(input: &TriMesh) -> Around {
        let mut sorted: Vec<([u32; 3], u32)> = input
            .triangles
            .iter()
            .enumerate()
            .flat_map(|(f, t)| t.iter().map(move |&v| (v, f as u32)))
            .filter_map(|(v, f)| Some((key(input.positions.get(v as usize)?), f)))
            .collect();
        sorted.sort_unstable();
        Around { sorted }
    }

    /// The input face nearest `point` among those with a corner at one
    /// of `corners` (the first such face on a tie; face 0 if none).
    fn nearest(&self, input: &TriMesh, corners: &[[f32; 3]; 3], point: [f64; 3]) -> u32 {
        let mut best: Option<(f64, u32)> = None;
        for c in corners {
            let k = key(c);
            let start = self.sorted.partition_point(|e| e.0 < k);
            for &(_, f) in self.sorted[start..].iter().take_while(|e| e.0 == k) {
                let t = input.triangles[f as usize].map(|v| input.positions[v as usize]);
                let d = crate::metrics::distance2(
                    point,
                    crate::metrics::closest_on_triangle(point, &t),
                );
                if best.is_none_or(|(b, g)| d < b || (d == b && f < g)) {
                    best = Some((d, f));
                }
            }
        }
        best.map_or(0, |(_, f)| f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point inside a face gives its barycentric coordinates in the
    /// face's corner order; outside, clamped onto the triangle.
    #[test]
    fn barycentric_coordinates() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        let b = barycentric(&t, [0.5, 1.0, 0.3]);
        for (x, y) in b.iter().zip([0.25, 0.25, 0.5]) {
            assert!((x - y).abs() < 1e-6, "{b:?}");
        }
        let b = barycentric(&t, [3.0, 3.0, 0.0]);
        assert!((b[0]).abs() < 1e-6 && (b[1] - 0.5).abs() < 1e-6, "{b:?}");
        let flat = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert_eq!(barycentric(&flat, [1.0, 0.0, 0.0]), [1.0, 0.0, 0.0]);
    }
}

#[cfg(test)]
mod file_tests {
    use crate::mesh::test_shapes::uv_sphere;
    use crate::{EncodeMode, EncodeOptions, SwingTarget, TriMesh};

    /// A hollow ball: a unit sphere and, facing inwards, one of radius
    /// `1 - thickness`, as two components.
    fn shell(thickness: f32) -> (TriMesh, usize) {
        let outer = uv_sphere(64, 32);
        let n = outer.vertex_count() as u32;
        let mut positions = outer.positions.clone();
        positions.extend(
            outer
                .positions
                .iter()
                .map(|p| p.map(|c| c * (1.0 - thickness))),
        );
        let mut triangles = outer.triangles.clone();
        triangles.extend(
            outer
                .triangles
                .iter()
                .map(|t| [t[0] + n, t[2] + n, t[1] + n]),
        );
        (TriMesh::new(positions, triangles), outer.face_count())
    }

    /// The simplified method's origins come from the sheet each vertex
    /// was made from (through its collapses), not the nearest one: in a
    /// shell thinner than the grid of a small file, many outer vertices
    /// are nearer the inner sheet, and the nearest-point rule, measured
    /// here too, takes them there.
    #[test]
    fn origins_stay_on_their_sheet_through_the_collapses() {
        let (input, outer_faces) = shell(0.004);
        // The collapse sequence (`max`) and meshoptimizer (`fast`).
        for effort in [crate::Effort::Max, crate::Effort::Fast] {
            let options = EncodeOptions {
                mode: EncodeMode::Simplified {
                    target: SwingTarget::Bytes(300),
                    max_bytes: None,
                },
                origins: true,
                effort,
                ..Default::default()
            };
            let crossed = on_their_sheet(&input, outer_faces, &options);
            assert!(
                crossed > 0,
                "{effort:?}: the shell is not thin enough to tell"
            );
        }
        // Displaced subdivision: its base through the collapses, its
        // levels from their edges' ends.
        let options = EncodeOptions {
            mode: EncodeMode::Displaced {
                target: SwingTarget::Bytes(600),
                max_bytes: None,
            },
            origins: true,
            ..Default::default()
        };
        let crossed = on_their_sheet(&input, outer_faces, &options);
        assert!(
            crossed > 0,
            "displaced: the shell is not thin enough to tell"
        );
        // SwingWrapper: each tip from the face it was fitted in. Its tips stay on
        // the outer side of this shell (measured down to a thickness of
        // 3e-4 with 4-bit angles), so the nearest point does not cross
        // here and only the descent's answer is checked.
        let (input, outer_faces) = shell(0.001);
        let options = EncodeOptions {
            mode: EncodeMode::Swing {
                target: SwingTarget::Bytes(600),
                angle_bits: Some(4),
                max_bytes: None,
            },
            origins: true,
            ..Default::default()
        };
        on_their_sheet(&input, outer_faces, &options);
    }

    /// Checks that every origin is on its vertex's sheet; returns how
    /// many the nearest point alone would put on the other one.
    fn on_their_sheet(input: &TriMesh, outer_faces: usize, options: &EncodeOptions) -> usize {
        let encoded = crate::encode(input, options).unwrap();
        let plain = crate::decode(&encoded.bytes, &crate::DecodeOptions::plain()).unwrap();
        let origins = &encoded.stats.origins;
        assert_eq!(origins.len(), plain.vertex_count());
        // Which sheet each decoded vertex was made from: its component's
        // (the collapses never join the two), the outer one the larger.
        let mut part: Vec<u32> = (0..plain.vertex_count() as u32).collect();
        fn root(part: &mut [u32], mut v: u32) -> u32 {
            while part[v as usize] != v {
                v = part[v as usize];
            }
            v
        }
        for t in &plain.triangles {
            for k in 0..3 {
                let (a, b) = (root(&mut part, t[k]), root(&mut part, t[(k + 1) % 3]));
                part[a.max(b) as usize] = a.min(b);
            }
        }
        let part: Vec<u32> = (0..plain.vertex_count() as u32)
            .map(|v| root(&mut part, v))
            .collect();
        let mut radius: Vec<(u32, f64, usize)> = Vec::new();
        for (v, p) in plain.positions.iter().enumerate() {
            let r = p.iter().map(|&c| (c as f64).powi(2)).sum::<f64>().sqrt();
            match radius.iter_mut().find(|e| e.0 == part[v]) {
                Some(e) => {
                    e.1 += r;
                    e.2 += 1;
                }
                None => radius.push((part[v], r, 1)),
            }
        }
        assert_eq!(radius.len(), 2, "two sheets decoded");
        let mean = |e: &(u32, f64, usize)| e.1 / e.2 as f64;
        let outer_part = if mean(&radius[0]) > mean(&radius[1]) {
            radius[0].0
        } else {
            radius[1].0
        };
        let on_outer = |face: u32| (face as usize) < outer_faces;
        let wrong = |origins: &[super::Origin]| {
            origins
                .iter()
                .enumerate()
                .filter(|(v, o)| (part[*v] == outer_part) != on_outer(o.face))
                .count()
        };
        let effort = options.effort;
        assert_eq!(wrong(origins), 0, "{effort:?}: origins on the other sheet");
        let cleaned = crate::clean(input, &Default::default()).unwrap();
        let surface = crate::metrics::Surface::new(&cleaned.mesh).unwrap();
        let nearest = super::origins(input, &cleaned.mesh, &surface, &plain, None);
        wrong(&nearest)
    }

    /// SwingWrapper's seeds are the retiler's own record: each decoded
    /// tip lies within a quarter of an edge of a face around its seed, the
    /// face its sample was fitted in (a seed numbered off by one vertex
    /// would stand an edge or more away: the input is finer than the
    /// retiling here). A hole (masked triangles, vertices the decoder
    /// drops and renumbers) and a component too small to retile (`REST`,
    /// after the retiled vertices, without seeds) are in the file.
    #[test]
    fn retiled_tips_are_seeded_where_they_were_fitted() {
        let sphere = uv_sphere(128, 64);
        let open: Vec<[u32; 3]> = sphere
            .triangles
            .iter()
            .filter(|t| t.iter().any(|&v| sphere.positions[v as usize][2] < 0.8))
            .copied()
            .collect();
        let small = uv_sphere(6, 4);
        let mut positions = sphere.positions.clone();
        positions.extend(
            small
                .positions
                .iter()
                .map(|p| p.map(|c| 0.01 * c))
                .map(|p| [p[0] + 3.0, p[1], p[2]]),
        );
        let mut triangles = open;
        let n = sphere.positions.len() as u32;
        triangles.extend(small.triangles.iter().map(|t| t.map(|v| v + n)));
        let input = TriMesh::new(positions, triangles);
        let cleaned = crate::clean(&input, &Default::default()).unwrap();
        let options = EncodeOptions::default();
        let ask = crate::encoder::method::Ask {
            target: SwingTarget::Bytes(700),
            max_bytes: None,
        };
        let file = crate::encoder::swing::encode(
            &cleaned,
            cleaned.mesh.vertex_count(),
            &options,
            ask,
            None,
            None,
        )
        .unwrap();
        let masked: u64 = file
            .report
            .pieces
            .iter()
            .map(|p| match p.outcome {
                crate::PieceOutcome::Retiled {
                    masked,
                    loop_points,
                    ..
                } => masked + u64::from(loop_points),
                _ => 0,
            })
            .sum();
        assert!(
            masked > 0,
            "the hole is masked or fanned: {:?}",
            file.report.pieces
        );
        assert!(file
            .report
            .pieces
            .iter()
            .any(|p| p.outcome == crate::PieceOutcome::Lossless));
        let plain = crate::decode(&file.bytes, &crate::DecodeOptions::plain()).unwrap();
        let rest = plain.vertex_count() - small.vertex_count();
        assert_eq!(file.seeds.len(), rest, "one seed per retiled vertex kept");
        let l = file.report.rate.edge_length;
        let mesh = &cleaned.mesh;
        let mut around: Vec<Vec<u32>> = vec![Vec::new(); mesh.vertex_count()];
        for (f, t) in mesh.triangles.iter().enumerate() {
            for &v in t {
                around[v as usize].push(f as u32);
            }
        }
        let mut seeded = 0;
        for (p, &seed) in plain.positions.iter().zip(&file.seeds) {
            if seed == u32::MAX {
                continue;
            }
            seeded += 1;
            let q = p.map(f64::from);
            let d = around[seed as usize]
                .iter()
                .map(|&f| {
                    let t = mesh.triangles[f as usize]
                        .map(|v| mesh.positions[v as usize].map(f64::from));
                    crate::metrics::triangle_distance2_f64(q, &t).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.25 * l, "a tip {d} from its seed's faces (L {l})");
        }
        assert!(
            seeded * 100 >= file.seeds.len() * 99,
            "{seeded} of {} seeded",
            file.seeds.len()
        );
    }

    /// The point each origin names lies where its decoded vertex is,
    /// within the file's error, on a face of the mesh as given: here with
    /// a degenerate face and an unused vertex first (so cleaned and given
    /// face numbers differ) and with poles of 96 spokes, which the
    /// simplifier's reference rebuilds (faces with no twin in the input).
    #[test]
    fn every_decoded_vertex_points_at_the_input_where_it_stands() {
        for (segments, mode) in [(24, "auto"), (96, "auto"), (24, "swing")] {
            let sphere = uv_sphere(segments, 16);
            let mut positions = vec![[5.0f32, 5.0, 5.0]];
            positions.extend(&sphere.positions);
            let mut triangles = vec![[1u32, 1, 2]];
            triangles.extend(sphere.triangles.iter().map(|t| t.map(|v| v + 1)));
            let input = TriMesh::new(positions, triangles);
            let target = SwingTarget::BitsPerVertex(4.0);
            let options = EncodeOptions {
                mode: match mode {
                    "swing" => EncodeMode::Swing {
                        target,
                        angle_bits: None,
                        max_bytes: None,
                    },
                    _ => EncodeMode::Auto {
                        target,
                        max_bytes: None,
                    },
                },
                origins: true,
                ..Default::default()
            };
            let without = EncodeOptions {
                origins: false,
                ..options.clone()
            };
            assert!(crate::encode(&input, &without)
                .unwrap()
                .stats
                .origins
                .is_empty());
            let encoded = crate::encode(&input, &options).unwrap();
            let plain = crate::decode(&encoded.bytes, &crate::DecodeOptions::plain()).unwrap();
            let origins = &encoded.stats.origins;
            assert_eq!(origins.len(), plain.vertex_count(), "{segments} {mode}");
            for (p, o) in plain.positions.iter().zip(origins) {
                assert!(o.face >= 1, "the degenerate face 0 holds no point");
                let t = input.triangles[o.face as usize];
                let b = o.barycentric;
                assert!(b.iter().all(|&x| x >= 0.0) && (b.iter().sum::<f32>() - 1.0).abs() < 1e-5);
                let x: [f32; 3] = core::array::from_fn(|k| {
                    (0..3)
                        .map(|i| b[i] * input.positions[t[i] as usize][k])
                        .sum()
                });
                let d = (0..3).map(|k| (x[k] - p[k]).powi(2)).sum::<f32>().sqrt();
                assert!(d < 0.05, "{segments} {mode}: {d} from {p:?}");
            }
        }
    }
}
