//! Surface-to-surface distance, as Metro measures it (Cignoni, Rocchini &
//! Scopigno, "Metro: measuring error on simplified surfaces", CGF 1998),
//! and as the SwingWrapper thesis reports it (Attene, §7.2): the
//! symmetric L2 distance `max(d(A, B), d(B, A))`, where the one-sided
//! `d(X, Y)` is the root mean square, over points `x` sampled on `X`, of
//! the distance from `x` to the nearest point of `Y`; and the Hausdorff
//! distance, the larger of the two one-sided maxima.
//!
//! * Samples (`sample`): every vertex, points along every edge, and
//!   stratified points on the faces in proportion to area, seeded and
//!   deterministic. Which kinds are taken, and how many face samples, is
//!   set by [`DistanceOptions`]; the default is Metro's (all three kinds,
//!   ten face samples per face of the larger mesh).
//! * Nearest points (`bvh`, `triangle`): exact point-to-triangle
//!   distances through a bounding-volume hierarchy; no grid and no search
//!   radius, so the maximum is the true maximum over the samples.
//! * Relative values divide by the bounding-box diagonal of the
//!   *reference* (first) mesh — the thesis's convention; Metro divides by
//!   the diagonal of the two meshes' union box, which differs only when
//!   the meshes disagree grossly.
//!
//! Invariants: the result depends only on the two meshes and the options —
//! not on the thread count nor on scheduling. The work is cut into fixed
//! chunks, each chunk's sums are formed in order, and the chunk sums are
//! added in chunk order. Memory is linear in the meshes' sizes, never in
//! the sample count: samples are generated, measured and dropped chunk by
//! chunk.

mod bvh;
pub mod estimate;
#[cfg(feature = "encoder")]
pub(crate) mod ray;
mod sample;
#[cfg(test)]
mod tests;
#[cfg(feature = "encoder")]
pub mod texcoord;
mod triangle;

use rayon::prelude::*;

use crate::{Error, FormatError, Malformed, ParameterError, TopologyError, TriMesh};
pub use bvh::Build;
use bvh::{Bvh, Scratch};
#[cfg(feature = "encoder")]
pub(crate) use bvh::{Bvh as NearestTree, Scratch as NearestScratch};
use sample::{area, carried_counts, edge_points, face_points, SplitMix};
use triangle::Tri;
#[cfg(feature = "encoder")]
pub(crate) use triangle::{
    barycentric, closest_point as closest_on_triangle, distance2, triangle_distance2_f64,
};

/// What to sample. Defaults are Metro's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DistanceOptions {
    /// Area-proportional face samples on each mesh. `None` (the default):
    /// ten per face of the mesh with more faces, as Metro does.
    pub face_samples: Option<u64>,
    /// Sample every vertex (default `true`).
    pub vertex_samples: bool,
    /// Sample along every edge, `√(face density)` points per unit length
    /// (default `true`).
    pub edge_samples: bool,
    /// Seed of the face samples' random positions (default 0).
    pub seed: u64,
}

impl Default for DistanceOptions {
    fn default() -> Self {
        DistanceOptions {
            face_samples: None,
            vertex_samples: true,
            edge_samples: true,
            seed: 0,
        }
    }
}

impl DistanceOptions {
    /// Face samples only, `n` of them on each mesh: the area-uniform
    /// estimate of the thesis's L2 (and of MeshLab's Hausdorff filter with
    /// face sampling).
    pub fn area_uniform(n: u64) -> Self {
        DistanceOptions {
            face_samples: Some(n),
            vertex_samples: false,
            edge_samples: false,
            seed: 0,
        }
    }
}

/// One direction: samples on one surface, distances to the other.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OneSided {
    /// Number of samples.
    pub samples: u64,
    /// Mean distance.
    pub mean: f64,
    /// Root mean square distance.
    pub rms: f64,
    /// Largest distance.
    pub max: f64,
}

/// Both directions between a reference mesh and another.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceDistance {
    /// Samples on the reference, distances to the other mesh.
    pub forward: OneSided,
    /// Samples on the other mesh, distances to the reference.
    pub backward: OneSided,
    /// Bounding-box diagonal of the reference.
    pub diagonal: f64,
}

impl SurfaceDistance {
    /// Symmetric L2: the larger one-sided RMS.
    pub fn l2(&self) -> f64 {
        self.forward.rms.max(self.backward.rms)
    }

    /// Hausdorff: the larger one-sided maximum.
    pub fn hausdorff(&self) -> f64 {
        self.forward.max.max(self.backward.max)
    }

    /// The larger one-sided mean.
    pub fn mean(&self) -> f64 {
        self.forward.mean.max(self.backward.mean)
    }

    /// [`Self::l2`] over the reference's diagonal (0 for a zero diagonal).
    pub fn l2_relative(&self) -> f64 {
        relative(self.l2(), self.diagonal)
    }

    /// [`Self::hausdorff`] over the reference's diagonal.
    pub fn hausdorff_relative(&self) -> f64 {
        relative(self.hausdorff(), self.diagonal)
    }
}

fn relative(x: f64, diagonal: f64) -> f64 {
    if diagonal > 0.0 {
        x / diagonal
    } else {
        0.0
    }
}

/// A mesh prepared for distance queries and for sampling: its faces in a
/// spatially coherent order inside a bounding-volume hierarchy.
#[derive(Clone, Debug)]
pub struct Surface {
    bvh: Bvh,
    /// Faces (vertex indices) in the hierarchy's leaf order.
    faces: Vec<[u32; 3]>,
    /// Original index of each entry of `faces`.
    face_ids: Vec<u32>,
    positions: Vec<[f32; 3]>,
    /// Area of each entry of `faces`: every measure spreads its face
    /// samples by them, and on a million-face reference computing them
    /// again took 40 ms of each of effort `fast`'s 2,000-sample measures.
    areas: Vec<f64>,
    area: f64,
    diagonal: f64,
}

impl Surface {
    /// Prepares `mesh`. Fails if it has no triangles, a triangle names a
    /// missing vertex, or a vertex used by a triangle is not finite.
    pub fn new(mesh: &TriMesh) -> Result<Surface, Error> {
        Surface::with_build(mesh, Build::Sah)
    }

    /// [`Surface::new`] with its tree built as `how` says: the same
    /// distances, samples in another order.
    pub fn with_build(mesh: &TriMesh, how: Build) -> Result<Surface, Error> {
        if mesh.triangles.is_empty() {
            return Err(TopologyError::NoTriangles.into());
        }
        let n = mesh.positions.len();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for t in &mesh.triangles {
            for &v in t {
                let Some(p) = mesh.positions.get(v as usize) else {
                    return Err(FormatError::new(
                        "mesh",
                        Malformed::IndexOutOfRange {
                            index: v as i64,
                            vertices: n as u64,
                        },
                    )
                    .into());
                };
                if !p.iter().all(|c| c.is_finite()) {
                    return Err(FormatError::new(
                        "mesh",
                        Malformed::NonFinite { vertex: v as u64 },
                    )
                    .into());
                }
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k] as f64);
                    hi[k] = hi[k].max(p[k] as f64);
                }
            }
        }
        let tris: Vec<Tri> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| mesh.positions[v as usize]))
            .collect();
        let bvh = Bvh::with_build(&tris, how);
        let face_ids = bvh.order().to_vec();
        let faces: Vec<[u32; 3]> = face_ids
            .iter()
            .map(|&f| mesh.triangles[f as usize])
            .collect();
        // In the mesh's own units (the tree keeps its triangles scaled).
        let areas: Vec<f64> = faces
            .iter()
            .map(|f| area(&f.map(|v| mesh.positions[v as usize])))
            .collect();
        let area = areas.iter().sum();
        let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        Ok(Surface {
            bvh,
            faces,
            face_ids,
            positions: mesh.positions.clone(),
            areas,
            area,
            diagonal,
        })
    }

    /// Face `f` (in the tree's leaf order) as a triangle, in the mesh's
    /// units.
    fn triangle(&self, f: usize) -> Tri {
        self.faces[f].map(|v| self.positions[v as usize])
    }

    /// The point of the surface nearest to `p`: the face it lies on (its
    /// index in the mesh the surface was made from), the point, and the
    /// hint for a next query nearby. `None` only for an empty surface.
    #[cfg(feature = "encoder")]
    pub(crate) fn nearest_point(
        &self,
        p: [f64; 3],
        hint: Option<u32>,
        scratch: &mut Scratch,
    ) -> Option<(u32, [f64; 3], u32)> {
        let hit = self.bvh.nearest(p, hint, scratch)?;
        let t = self.triangle(hit.slot as usize);
        Some((hit.triangle, triangle::closest_point(p, &t), hit.slot))
    }

    /// The `t` of smallest magnitude in `[−reach, reach]` where the line
    /// `p + t·d` crosses the surface, if any; with `facing`, only faces
    /// whose normal points along `d` (`bvh::crossing`). `stack` is
    /// scratch space.
    #[cfg(feature = "encoder")]
    pub(crate) fn nearest_crossing(
        &self,
        p: [f64; 3],
        d: [f64; 3],
        reach: f64,
        facing: bool,
        stack: &mut Vec<(u32, f64)>,
    ) -> Option<f64> {
        self.bvh.nearest_crossing(p, d, reach, facing, stack)
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// Total area.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Diagonal of the bounding box of the vertices the faces use.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }
}

/// [`distance_between`] two meshes, each prepared here.
pub fn distance(
    reference: &TriMesh,
    other: &TriMesh,
    options: &DistanceOptions,
) -> Result<SurfaceDistance, Error> {
    let (a, b) = rayon::join(|| Surface::new(reference), || Surface::new(other));
    distance_between(&a?, &b?, options)
}

/// Both one-sided distances between prepared surfaces (prepare the
/// reference once when measuring many candidates against it).
///
/// Fails with [`Error::Parameter`] if the options ask for no samples at all.
pub fn distance_between(
    reference: &Surface,
    other: &Surface,
    options: &DistanceOptions,
) -> Result<SurfaceDistance, Error> {
    let faces = options
        .face_samples
        .unwrap_or(10 * reference.face_count().max(other.face_count()) as u64);
    if faces == 0 && !options.vertex_samples && !options.edge_samples {
        return Err(ParameterError::OutOfRange {
            name: "samples",
            value: 0.0,
            min: 1.0,
            max: f64::INFINITY,
        }
        .into());
    }
    let (forward, backward) = rayon::join(
        || one_sided(reference, other, faces, options),
        || one_sided(other, reference, faces, options),
    );
    Ok(SurfaceDistance {
        forward,
        backward,
        diagonal: reference.diagonal,
    })
}

/// Running sums of one chunk of samples.
#[derive(Clone, Copy, Debug, Default)]
struct Sums {
    n: u64,
    sum: f64,
    sum2: f64,
    max: f64,
}

impl Sums {
    fn add(&mut self, d: f64) {
        self.n += 1;
        self.sum += d;
        self.sum2 += d * d;
        self.max = self.max.max(d);
    }

    /// The one-sided figures of all the chunks' sums, added in chunk
    /// order.
    fn total(parts: &[Sums]) -> OneSided {
        let total = parts.iter().fold(Sums::default(), |acc, s| acc.merge(s));
        if total.n == 0 {
            return OneSided::default();
        }
        OneSided {
            samples: total.n,
            mean: total.sum / total.n as f64,
            rms: (total.sum2 / total.n as f64).sqrt(),
            max: total.max,
        }
    }

    fn merge(mut self, o: &Sums) -> Sums {
        self.n += o.n;
        self.sum += o.sum;
        self.sum2 += o.sum2;
        self.max = self.max.max(o.max);
        self
    }
}

/// A fixed slice of the sampling work. Chunk boundaries depend only on the
/// mesh, never on the thread count.
#[derive(Clone, Copy, Debug)]
enum Work {
    Vertices(usize, usize),
    Edges(usize, usize),
    Faces(usize, usize),
}

const VERTEX_CHUNK: usize = 4096;
const EDGE_CHUNK: usize = 2048;
const FACE_CHUNK: usize = 512;
/// A face chunk holding more samples than this measures them in blocks
/// of [`SPLIT_BLOCK`] points, [`SPLIT_SLICE`] to a task. The sums are
/// the same bits (each distance is exact whatever the warm start, and
/// they are added in the chunk's order); only a far query's answer
/// (the hint's triangle, within 2^-30 of the minimum, see `bvh`) can
/// differ, and the split depends on the counts alone, never on the
/// thread count.
const SPLIT_SAMPLES: u64 = 8192;
const SPLIT_BLOCK: usize = 16_384;
const SPLIT_SLICE: usize = 1024;

/// Each point's distance to `to` (`None` for an empty tree), in order,
/// slices of the points on rayon's threads.
fn measured_in_parallel(points: &[[f64; 3]], to: &Surface) -> Vec<Option<f64>> {
    let parts: Vec<Vec<Option<f64>>> = points
        .par_chunks(SPLIT_SLICE)
        .map_init(Scratch::default, |scratch, slice| {
            let mut hint = None;
            slice
                .iter()
                .map(|&p| {
                    let hit = to.bvh.nearest(p, hint, scratch)?;
                    hint = Some(hit.slot);
                    Some(hit.distance2.sqrt())
                })
                .collect()
        })
        .collect();
    parts.into_iter().flatten().collect()
}

fn chunks(n: usize, size: usize, f: fn(usize, usize) -> Work) -> impl Iterator<Item = Work> {
    (0..n.div_ceil(size)).map(move |i| f(i * size, ((i + 1) * size).min(n)))
}

/// Samples `from` (with `faces` face samples and the options' other kinds)
/// and measures each sample's distance to `to`.
pub fn one_sided(from: &Surface, to: &Surface, faces: u64, options: &DistanceOptions) -> OneSided {
    let n_faces = from.face_count();
    let density = if from.area > 0.0 {
        faces as f64 / from.area
    } else {
        0.0
    };
    // A zero-area surface still gets its face samples: spread them evenly.
    let face_counts = if from.area > 0.0 {
        carried_counts(from.areas.iter().copied(), density)
    } else {
        carried_counts((0..n_faces).map(|_| 1.0), faces as f64 / n_faces as f64)
    };
    let vertices = if options.vertex_samples {
        used_vertices(from)
    } else {
        Vec::new()
    };
    let (edges, edge_counts) = if options.edge_samples {
        let edges = unique_edges(&from.faces);
        let p = &from.positions;
        let lengths = edges.iter().map(|&(a, b)| {
            let (a, b) = (p[a as usize], p[b as usize]);
            (0..3)
                .map(|k| (a[k] as f64 - b[k] as f64).powi(2))
                .sum::<f64>()
                .sqrt()
        });
        let counts = carried_counts(lengths, density.sqrt());
        (edges, counts)
    } else {
        (Vec::new(), Vec::new())
    };
    let work: Vec<Work> = chunks(vertices.len(), VERTEX_CHUNK, Work::Vertices)
        .chain(chunks(edges.len(), EDGE_CHUNK, Work::Edges))
        .chain(chunks(n_faces, FACE_CHUNK, Work::Faces))
        .collect();
    let parts: Vec<Sums> = work
        .par_iter()
        .map_init(Scratch::default, |scratch, &w| {
            let mut sums = Sums::default();
            let mut hint = None;
            let mut measure = |p: [f64; 3]| {
                if let Some(hit) = to.bvh.nearest(p, hint, scratch) {
                    hint = Some(hit.slot);
                    sums.add(hit.distance2.sqrt());
                }
            };
            match w {
                Work::Vertices(a, b) => {
                    for &v in &vertices[a..b] {
                        let p = from.positions[v as usize];
                        measure(p.map(|c| c as f64));
                    }
                }
                Work::Edges(a, b) => {
                    for (&(u, v), &n) in edges[a..b].iter().zip(&edge_counts[a..b]) {
                        let (p, q) = (from.positions[u as usize], from.positions[v as usize]);
                        edge_points(p, q, n, &mut measure);
                    }
                }
                Work::Faces(a, b) if face_counts[a..b].iter().sum::<u64>() > SPLIT_SAMPLES => {
                    // A few large faces holding many samples (the decoded
                    // side of a small file: one chunk, one thread, for all
                    // of them): their points in blocks, each measured on
                    // every thread and added in order.
                    let mut block = Vec::with_capacity(SPLIT_BLOCK);
                    let mut flush = |block: &mut Vec<[f64; 3]>| {
                        for d in measured_in_parallel(block, to).into_iter().flatten() {
                            sums.add(d);
                        }
                        block.clear();
                    };
                    for (f, &n) in face_counts.iter().enumerate().take(b).skip(a) {
                        let mut rng = SplitMix::new(options.seed, from.face_ids[f] as u64);
                        face_points(&from.triangle(f), n, &mut rng, |p| {
                            block.push(p);
                            if block.len() == SPLIT_BLOCK {
                                flush(&mut block);
                            }
                        });
                    }
                    flush(&mut block);
                }
                Work::Faces(a, b) => {
                    for (f, &n) in face_counts.iter().enumerate().take(b).skip(a) {
                        let mut rng = SplitMix::new(options.seed, from.face_ids[f] as u64);
                        face_points(&from.triangle(f), n, &mut rng, &mut measure);
                    }
                }
            }
            sums
        })
        .collect();
    Sums::total(&parts)
}

/// The vertices the faces use, each once, in order of first use.
fn used_vertices(s: &Surface) -> Vec<u32> {
    let mut seen = vec![false; s.positions.len()];
    let mut out = Vec::new();
    for &v in s.faces.iter().flatten() {
        if !core::mem::replace(&mut seen[v as usize], true) {
            out.push(v);
        }
    }
    out
}

/// Every edge once (however many faces share it, in whichever direction),
/// in order of first use.
fn unique_edges(faces: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut keyed: Vec<(u64, u32)> = faces
        .iter()
        .enumerate()
        .flat_map(|(f, t)| {
            (0..3).map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (a.min(b) as u64) << 32 | a.max(b) as u64;
                (key, (3 * f + k) as u32)
            })
        })
        .collect();
    keyed.sort_unstable();
    keyed.dedup_by_key(|e| e.0);
    let mut first: Vec<u32> = keyed.iter().map(|e| e.1).collect();
    first.sort_unstable();
    first
        .into_iter()
        .map(|e| {
            let t = faces[e as usize / 3];
            let k = e as usize % 3;
            (t[k], t[(k + 1) % 3])
        })
        .filter(|(a, b)| a != b)
        .collect()
}
