//! Metro's distance from a fixed share of its samples (issue 45, item 7:
//! "the error encode reports is the error `swm distance` measures, within
//! 2%").
//!
//! Metro ([`DistanceOptions::default`](super::DistanceOptions)) samples
//! every vertex, points along every edge at `√D` per unit length and `D`
//! points per unit area (`D`: ten per face of the larger mesh over the
//! sampled surface's area). On a scan that is millions of queries a side;
//! the area-uniform samples the chooser measures with are cheap but leave
//! out the vertex and edge samples, which on a simplified scan weigh
//! 5-10% more (its vertices are where the input bulges most from the
//! coarse surface). This module keeps every kind at Metro's weight and
//! thins all of them by one factor `p`, chosen so that about `samples`
//! points remain on each side:
//!
//! * a vertex is kept when its seeded hash is below `p`;
//! * an edge expecting `c = p·√D·length` points gets `⌊c⌋` points, plus
//!   one when its hash is below `c − ⌊c⌋`, each at a seeded random place
//!   along it (Metro spaces them evenly: the same expected mean);
//! * faces get `p·D` points per unit area, carried in leaf order as
//!   Metro's own.
//!
//! Each kind keeps its expected share of the samples, so the mean squared
//! distance over the kept points estimates Metro's without bias; the
//! maximum is the maximum over the kept points (a lower bound of
//! Metro's). An edge is found from each face that holds it; the hash of
//! its unordered end points decides for every copy alike, and the copies
//! are merged before measuring, so an edge counts once as in Metro.
//!
//! Invariants: as `distance_between`, the result depends only on the two
//! surfaces and the sample count, never on the thread count: fixed
//! chunks, each summed in order, the chunk sums added in order.

use super::sample::{carried_counts, face_points, SplitMix};
use super::{OneSided, Scratch, Sums, Surface, SurfaceDistance};
use crate::Error;
use rayon::prelude::*;

/// Seeds of the three kinds' decisions (any fixed values).
const VERTEX_SEED: u64 = 0x5157_4d45_7472_6f31;
const EDGE_SEED: u64 = 0x5157_4d45_7472_6f32;
const FACE_SEED: u64 = 0x5157_4d45_7472_6f33;

/// Points measured per chunk (the unit of parallel work).
const CHUNK: usize = 2048;

/// Faces whose points are picked per chunk (the picking's unit of work).
const PICK_CHUNK: usize = 16_384;

/// The number of corner `k` of face `f`.
fn corner(f: usize, k: usize) -> usize {
    3 * f + k
}

/// Both one-sided distances between `reference` and `other` as Metro
/// measures them, estimated from about `samples` points on each side.
/// With `samples` at or above Metro's own count the kinds are not thinned
/// (`p` = 1), though edge points then lie at random places along each
/// edge rather than evenly spaced.
pub fn metro_estimate(
    reference: &Surface,
    other: &Surface,
    samples: u64,
) -> Result<SurfaceDistance, Error> {
    if samples == 0 {
        return Err(crate::ParameterError::OutOfRange {
            name: "samples",
            value: 0.0,
            min: 1.0,
            max: f64::INFINITY,
        }
        .into());
    }
    let faces = 10 * reference.face_count().max(other.face_count()) as u64;
    let (forward, backward) = rayon::join(
        || thinned(reference, other, faces, samples),
        || thinned(other, reference, faces, samples),
    );
    Ok(SurfaceDistance {
        forward,
        backward,
        diagonal: reference.diagonal,
    })
}

/// A point to measure.
#[derive(Clone, Copy)]
enum Point {
    Vertex(u32),
    /// End points, and how many random points to place along the edge
    /// (seeded by the edge).
    Edge(u32, u32, u32),
}

/// Samples `from` as Metro would with `faces` face samples, thinned to
/// about `samples` points, and measures each against `to`.
fn thinned(from: &Surface, to: &Surface, faces: u64, samples: u64) -> OneSided {
    let density = if from.area > 0.0 {
        faces as f64 / from.area
    } else {
        0.0
    };
    let edge_density = density.sqrt();
    // Metro's count, to set `p`: the used vertices, the edge points (each
    // interior edge is held by two faces) and the face points.
    // Each vertex's first corner in leaf order: where it is considered.
    let mut first = vec![usize::MAX; from.positions.len()];
    let mut used = 0u64;
    let mut half_length = 0.0f64;
    for (f, t) in from.faces.iter().enumerate() {
        for k in 0..3 {
            let slot = &mut first[t[k] as usize];
            if *slot == usize::MAX {
                *slot = corner(f, k);
                used += 1;
            }
            half_length += 0.5 * length(from, t[k], t[(k + 1) % 3]);
        }
    }
    let metro = used as f64 + edge_density * half_length + faces as f64;
    let p = (samples as f64 / metro.max(1.0)).min(1.0);
    // Vertices and edges picked by their hashes, each once. The faces in
    // chunks side by side (a hash per vertex and per edge copy: on a
    // million-face reference most of this function's time), the chunks'
    // lists joined in order: the same lists as one pass in leaf order.
    let picked: Vec<(Vec<(u32, Point)>, Vec<(u64, u32, Point)>)> = from
        .faces
        .par_chunks(PICK_CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut points = Vec::new();
            let mut edges = Vec::new();
            for (j, t) in chunk.iter().enumerate() {
                let f = c * PICK_CHUNK + j;
                for k in 0..3 {
                    let v = t[k];
                    if first[v as usize] == corner(f, k)
                        && unit(SplitMix::new(VERTEX_SEED, v as u64).next_u64()) < p
                    {
                        points.push((f as u32, Point::Vertex(v)));
                    }
                    let (a, b) = (v.min(t[(k + 1) % 3]), v.max(t[(k + 1) % 3]));
                    if a == b {
                        continue;
                    }
                    let c = p * edge_density * length(from, a, b);
                    let key = (a as u64) << 32 | b as u64;
                    let extra = unit(SplitMix::new(EDGE_SEED, key).next_u64()) < c.fract();
                    let n = c.floor() as u64 + extra as u64;
                    if n > 0 {
                        let n = n.min(u32::MAX as u64) as u32;
                        edges.push((key, f as u32, Point::Edge(a, b, n)));
                    }
                }
            }
            (points, edges)
        })
        .collect();
    let mut points: Vec<(u32, Point)> = Vec::new();
    let mut edges: Vec<(u64, u32, Point)> = Vec::new();
    for (p, e) in picked {
        points.extend(p);
        edges.extend(e);
    }
    // One copy per edge (its first face in leaf order), then every point
    // in leaf order, so that consecutive queries lie close together.
    edges.sort_unstable_by_key(|e| (e.0, e.1));
    edges.dedup_by_key(|e| e.0);
    points.extend(edges.into_iter().map(|(_, f, e)| (f, e)));
    points.sort_by_key(|e| e.0);
    let face_counts = if from.area > 0.0 {
        carried_counts(from.areas.iter().copied(), p * density)
    } else {
        vec![0; from.face_count()]
    };
    let point_chunks = points.chunks(CHUNK).map(Work::Points);
    // Face chunks of about CHUNK samples each (boundaries from the counts
    // alone).
    let mut face_work = Vec::new();
    let (mut start, mut acc) = (0usize, 0u64);
    for (f, &n) in face_counts.iter().enumerate() {
        acc += n;
        if acc >= CHUNK as u64 {
            face_work.push(Work::Faces(start, f + 1));
            (start, acc) = (f + 1, 0);
        }
    }
    if acc > 0 {
        face_work.push(Work::Faces(start, face_counts.len()));
    }
    let work: Vec<Work> = point_chunks.chain(face_work).collect();
    let parts: Vec<Sums> = work
        .par_iter()
        .map_init(Scratch::default, |scratch, w| {
            let mut sums = Sums::default();
            let mut hint = None;
            let mut measure = |q: [f64; 3]| {
                if let Some(hit) = to.bvh.nearest(q, hint, scratch) {
                    hint = Some(hit.slot);
                    sums.add(hit.distance2.sqrt());
                }
            };
            match *w {
                Work::Points(list) => {
                    for &(_, point) in list {
                        match point {
                            Point::Vertex(v) => measure(wide(from.positions[v as usize])),
                            Point::Edge(a, b, n) => {
                                let (pa, pb) = (
                                    wide(from.positions[a as usize]),
                                    wide(from.positions[b as usize]),
                                );
                                let key = (a as u64) << 32 | b as u64;
                                let mut rng = SplitMix::new(EDGE_SEED ^ 1, key);
                                for i in 0..n {
                                    let t = (i as f64 + rng.unit()) / n as f64;
                                    measure(core::array::from_fn(|k| pa[k] + t * (pb[k] - pa[k])));
                                }
                            }
                        }
                    }
                }
                Work::Faces(a, b) => {
                    for (f, &n) in face_counts.iter().enumerate().take(b).skip(a) {
                        let mut rng = SplitMix::new(FACE_SEED, from.face_ids[f] as u64);
                        face_points(&from.triangle(f), n, &mut rng, &mut measure);
                    }
                }
            }
            sums
        })
        .collect();
    Sums::total(&parts)
}

/// A slice of the measuring work.
#[derive(Clone, Copy)]
enum Work<'a> {
    Points(&'a [(u32, Point)]),
    Faces(usize, usize),
}

fn wide(p: [f32; 3]) -> [f64; 3] {
    p.map(|c| c as f64)
}

fn length(s: &Surface, a: u32, b: u32) -> f64 {
    let (a, b) = (s.positions[a as usize], s.positions[b as usize]);
    (0..3)
        .map(|k| (a[k] as f64 - b[k] as f64).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// 64 random bits as a share of 1.
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edgebreaker::tests_support::{icosahedron, subdivided};
    use crate::metrics::{distance_between, DistanceOptions};
    use crate::TriMesh;

    /// A bumpy sphere against a coarse one: Metro's full count and the
    /// estimate from a tenth of it agree within 2% on L2, and the estimate
    /// takes about the number of samples asked for.
    #[test]
    fn estimates_metros_l2() {
        let fine = bumpy(sphere(5));
        let coarse = sphere(2);
        let (a, b) = (Surface::new(&fine).unwrap(), Surface::new(&coarse).unwrap());
        let full = distance_between(&a, &b, &DistanceOptions::default()).unwrap();
        let n = full.forward.samples / 10;
        let est = metro_estimate(&a, &b, n).unwrap();
        let rel = est.l2() / full.l2() - 1.0;
        assert!(rel.abs() < 0.02, "{} against {}", est.l2(), full.l2());
        for side in [est.forward, est.backward] {
            let ratio = side.samples as f64 / n as f64;
            assert!((0.8..1.25).contains(&ratio), "{} for {n}", side.samples);
        }
        assert!(est.hausdorff() <= full.hausdorff() * 1.0001);
        // Deterministic.
        assert_eq!(est, metro_estimate(&a, &b, n).unwrap());
    }

    /// With more samples than Metro's, every kind is kept: the counts are
    /// Metro's (up to the edges' carried fractions).
    #[test]
    fn unthinned_counts_are_metros() {
        let fine = bumpy(sphere(3));
        let coarse = sphere(1);
        let (a, b) = (Surface::new(&fine).unwrap(), Surface::new(&coarse).unwrap());
        let full = distance_between(&a, &b, &DistanceOptions::default()).unwrap();
        let est = metro_estimate(&a, &b, u64::MAX).unwrap();
        for (e, f) in [(est.forward, full.forward), (est.backward, full.backward)] {
            let ratio = e.samples as f64 / f.samples as f64;
            assert!(
                (0.99..1.01).contains(&ratio),
                "{} against {}",
                e.samples,
                f.samples
            );
        }
        assert!((est.l2() / full.l2() - 1.0).abs() < 0.01);
        assert!(metro_estimate(&a, &b, 0).is_err());
    }

    /// An icosahedron on the unit sphere, subdivided `levels` times.
    fn sphere(levels: u32) -> TriMesh {
        let unit = |p: [f64; 3]| {
            let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            p.map(|c| c / n)
        };
        let (p, f) = icosahedron((1.0 + 5f64.sqrt()) / 2.0);
        let p = p.into_iter().map(unit).collect();
        let (p, f) = subdivided((p, f), levels, |a, b| {
            unit(core::array::from_fn(|i| a[i] + b[i]))
        });
        TriMesh::new(p.iter().map(|q| q.map(|c| c as f32)).collect(), f)
    }

    /// Every vertex moved along its radius by a deterministic bump.
    fn bumpy(mut m: TriMesh) -> TriMesh {
        for (i, v) in m.positions.iter_mut().enumerate() {
            let s = 1.0 + 0.02 * ((i as f32 * 0.7).sin() + (i as f32 * 1.3).cos());
            *v = v.map(|c| c * s);
        }
        m
    }
}
