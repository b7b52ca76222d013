//! The simplifier of the module's method ([`super`]): a welded mesh,
//! its collapse sequence made once (`qem`) or meshoptimizer's simplifier
//! (effort `fast`), the refit, the mode-0 files of its simplifications,
//! and the distance every candidate file is measured with.
//!
//! Invariants: a simplification depends only on the mesh and the face
//! count asked; the whole mesh's cleaning, its coded connectivity
//! (`lossless::Prepared`) and its files are made once and kept
//! (`Simplifier::whole_file`): a search over quantizations of the whole
//! mesh pays for its connectivity once, not once per quantization.

use super::{attributed, collapse_pieces, qem, refit};
use crate::container::Framing;
use crate::metrics::{DistanceOptions, Surface, SurfaceDistance};
use crate::swing::retile::valence::{max_valence, MAX_VALENCE};
use crate::{CleanOptions, Error, LosslessStats, TopologyError, TriMesh};
use alloc::borrow::Cow;
use core::ops::RangeInclusive;
use std::sync::OnceLock;

/// Quantizations considered: the lossless mode's coarsest (small meshes
/// at low rates want it: spot and cow chose 7, the old floor, at 0.5-2
/// b/v) to two bits finer than the peers' 14.
pub const QPS: RangeInclusive<u8> = 6..=16;
/// Samples per direction with which the quick search (effort `fast`)
/// tells its two fits apart: enough to rank a quantization several bits
/// off against one near the best, not to choose between neighbours.
pub const QUICK_SAMPLES: u64 = 2_000;
/// The qp of the first fit, whose face count predicts the best qp.
pub(super) const START_QP: u8 = 10;
/// Fewer faces than a tetrahedron's make no surface worth coding.
pub(super) const MIN_FACES: u32 = 4;
/// Refits of each simplification to the input ([`refit`]): one; three
/// measured no better.
const REFIT_SWEEPS: usize = 1;

/// How much more error a file on size (within rate control's 3% of the
/// request) may have than one short of it and still be preferred: the
/// issue's "no worse than the better method by more than 5%".
pub(crate) const ON_SIZE_SLACK: f64 = 1.05;

/// A welded mesh and, once made, its collapse sequence.
pub struct Simplifier<'a> {
    pub(super) mesh: &'a TriMesh,
    /// What is simplified and what distances are measured against:
    /// `mesh`, or its copy with high-valence fans rebuilt (see `new`).
    work: Cow<'a, TriMesh>,
    /// The greedy collapse sequence of `work`, made on first use (an
    /// automatic encode whose retiling wins early may never need it).
    collapses: OnceLock<qem::Collapses>,
    /// Simplify with meshoptimizer instead of the collapse sequence
    /// ([`Simplifier::quick`]).
    quick: bool,
    /// The quick engine's simplifications so far, by target: a target
    /// asked again is answered from here, and a new one is simplified
    /// from the smallest of them that is still above it (or from the
    /// input), so a size search simplifies the input about once.
    /// Deterministic, as the search's sequence of probes is.
    made: std::sync::Mutex<Vec<(u32, TriMesh)>>,
    /// The framing of the files it writes.
    pub(super) framing: Framing,
    /// The input cleaned as every probe is (`lossless_bytes`), once:
    /// each quantization's search starts with the whole mesh's file, and
    /// cleaning a million triangles again for each took 0.45 s.
    whole: OnceLock<Option<crate::Cleaned>>,
    /// The cleaning `mesh` came from, when the caller has it
    /// ([`Simplifier::of_cleaned`]): used instead of `whole`.
    given: Option<&'a crate::Cleaned>,
    /// The whole mesh's connectivity coded, once (`lossless::Prepared`):
    /// each quantization's file then costs only its positions, about a
    /// quarter of an encode (on a million triangles 0.08 s, not 0.33 s).
    prepared: OnceLock<Option<crate::lossless::Prepared>>,
    /// The whole mesh's file and figures by quantization, once made (the
    /// error target runs the same searches at several sizes, and the
    /// winner's figures come from here).
    whole_files: std::sync::Mutex<Vec<(u8, Vec<u8>, LosslessStats)>>,
    /// The input's attribute streams, when it has any
    /// ([`Simplifier::with_attributes`]): every simplification carries
    /// them ([`attributed`]) and every file codes them (`ATTR`).
    attrs: Option<Attrs<'a>>,
}

/// What a simplifier of an attributed input keeps.
struct Attrs<'a> {
    /// One triple per face of the simplifier's mesh, in each stream.
    streams: &'a [crate::AttributeStream],
    /// How the files quantize them.
    quantization: crate::AttributeQuantization,
    /// The input with its streams.
    input: crate::AttributedMesh,
    /// Simplifications so far, by target (each a function of its target
    /// alone, so which search asked first does not matter).
    made: std::sync::Mutex<Vec<(u32, crate::AttributedMesh)>>,
    /// Anchor `k` (from 1): the input simplified toward `faces >> k`
    /// faces from anchor `k − 1` (the input for 1), made on first use. A
    /// target is simplified from the smallest anchor above it, so a size
    /// search does not simplify the whole input at every probe, and the
    /// result never depends on the order of probes (two searches of the
    /// lean climb run side by side): unlike the quick engine's chain
    /// from whatever was made last, the anchors are fixed by the input.
    anchors: Vec<OnceLock<crate::AttributedMesh>>,
    /// The whole mesh's connectivity coded with what `ATTR` needs.
    prepared: OnceLock<Option<crate::lossless::Prepared>>,
    /// The input's surface, for [`Simplifier::attribute_error`]
    /// (`None`: no surface).
    measured: OnceLock<Option<Surface>>,
}

impl<'a> Simplifier<'a> {
    /// The framing of the files it writes.
    pub fn framing(&self) -> Framing {
        self.framing
    }

    /// `mesh` must be welded (what [`clean`](crate::clean) returns).
    ///
    /// A mesh with a vertex of valence above the retiler's cap (a fanned
    /// polygon face, a cone's apex) is simplified from a copy whose fans
    /// are rebuilt as the retiler's are (`retile::valence`, the same
    /// surface within about 1e-4 of a spoke): a collapse's checks walk the
    /// rings of its ends, so their time grows as the square of the
    /// valence, and a distance measured against the fan's slivers visits
    /// all of them for each sample. Other meshes are used as they are.
    pub fn new(mesh: &'a TriMesh, framing: Framing) -> Simplifier<'a> {
        let work = if max_valence(mesh) > MAX_VALENCE {
            let mut copy = mesh.clone();
            let mut labels = vec![0u32; copy.face_count()];
            crate::swing::retile::valence::cap(&mut copy, &mut labels);
            Cow::Owned(copy)
        } else {
            Cow::Borrowed(mesh)
        };
        Simplifier {
            mesh,
            work,
            collapses: OnceLock::new(),
            quick: false,
            made: std::sync::Mutex::new(Vec::new()),
            framing,
            whole: OnceLock::new(),
            given: None,
            prepared: OnceLock::new(),
            whole_files: std::sync::Mutex::new(Vec::new()),
            attrs: None,
        }
    }

    /// The same simplifier for a mesh with attribute `streams` (one
    /// triple per face of its mesh, as `clean_attributed` gives them),
    /// quantized in its files as `quantization` says. Its
    /// simplifications are meshoptimizer's with attributes, whatever the
    /// engine ([`attributed`]: the collapse sequence knows no seams); its
    /// files carry the streams in `ATTR`, so every size it measures
    /// counts them. No streams: the simplifier as it was.
    pub fn with_attributes(
        self,
        streams: &'a [crate::AttributeStream],
        quantization: crate::AttributeQuantization,
    ) -> Simplifier<'a> {
        if streams.is_empty() {
            return self;
        }
        let levels = (32 - self.faces().max(1).leading_zeros()) as usize;
        Simplifier {
            attrs: Some(Attrs {
                streams,
                quantization,
                input: crate::AttributedMesh::new(self.mesh.clone(), streams.to_vec()),
                anchors: (0..levels).map(|_| OnceLock::new()).collect(),
                made: std::sync::Mutex::new(Vec::new()),
                prepared: OnceLock::new(),
                measured: OnceLock::new(),
            }),
            ..self
        }
    }

    /// The error of the file `bytes`'s attribute streams against the
    /// input's, in the mesh's units, to add to its L2 distance where
    /// files are compared (the climb over quantizations, the quick
    /// search): texture coordinates' RMS texels times
    /// [`TEXEL_WEIGHT`](attributed::TEXEL_WEIGHT) and colours' RMS 8-bit
    /// steps times [`COLOUR_STEP_WEIGHT`](attributed::COLOUR_STEP_WEIGHT),
    /// of the input's diagonal (`metrics::texcoord`). Zero without
    /// streams, and for streams of other kinds (normals follow the
    /// surface, which L2 measures).
    pub fn attribute_error(&self, bytes: &[u8]) -> Result<f64, Error> {
        let Some((texels, steps, diagonal)) = self.stream_errors(bytes)? else {
            return Ok(0.0);
        };
        Ok(weighed(texels, steps) * diagonal)
    }

    /// [`attribute_error`](Self::attribute_error) as a fraction of the
    /// input's diagonal, as the automatic mode's chooser adds it to each
    /// candidate's relative L2.
    pub fn attribute_error_relative(&self, bytes: &[u8]) -> Result<f64, Error> {
        let Some((texels, steps, _)) = self.stream_errors(bytes)? else {
            return Ok(0.0);
        };
        Ok(weighed(texels, steps))
    }

    /// The texture coordinates' error of the file `bytes` against the
    /// input's (`metrics::texcoord`), as the encoder reports it; `None`
    /// without texture coordinates.
    pub fn texcoord_error(
        &self,
        bytes: &[u8],
    ) -> Result<Option<crate::metrics::texcoord::TexcoordError>, Error> {
        Ok(self.stream_errors(bytes)?.and_then(|(t, _, _)| t))
    }

    /// The file's texture coordinates' error, its colours' RMS 8-bit
    /// steps and the input's diagonal; `None` without streams.
    #[allow(clippy::type_complexity)]
    fn stream_errors(
        &self,
        bytes: &[u8],
    ) -> Result<
        Option<(
            Option<crate::metrics::texcoord::TexcoordError>,
            Option<f64>,
            f64,
        )>,
        Error,
    > {
        let Some(a) = &self.attrs else {
            return Ok(None);
        };
        let measured = a.measured.get_or_init(|| Surface::new(&a.input.mesh).ok());
        let Some(surface) = measured else {
            return Ok(None);
        };
        let decoded = crate::decoder::decode_attributed(bytes, &Default::default())?;
        use crate::metrics::texcoord::{colour_error_steps, texcoord_error};
        Ok(Some((
            texcoord_error(&a.input, surface, &decoded),
            colour_error_steps(&a.input, surface, &decoded),
            surface.diagonal(),
        )))
    }

    /// Whether its files carry attribute streams.
    pub fn has_attributes(&self) -> bool {
        self.attrs.is_some()
    }

    /// The input's streams (empty without any).
    pub fn streams(&self) -> &[crate::AttributeStream] {
        self.attrs.as_ref().map_or(&[], |a| a.streams)
    }

    /// [`simplify`](Self::simplify) with the streams: the input itself at
    /// `target` or more faces. Deterministic: a function of `target`
    /// alone, simplified from the smallest anchor above it (`Attrs`).
    /// Without streams, the simplification with none.
    pub fn simplify_attributed(&self, target: u32) -> crate::AttributedMesh {
        let Some(a) = &self.attrs else {
            return crate::AttributedMesh::from(self.simplify(target));
        };
        if target >= self.faces() {
            return a.input.clone();
        }
        let lock = || a.made.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, m)) = lock().iter().find(|(t, _)| *t == target) {
            return m.clone();
        }
        // The deepest anchor whose target is above this one.
        let k = (1..=a.anchors.len())
            .take_while(|&k| self.faces() >> k > target)
            .last()
            .unwrap_or(0);
        let mesh = attributed::simplified(self.anchor(a, k), target);
        let mut made = lock();
        if made.iter().all(|(t, _)| *t != target) {
            made.push((target, mesh.clone()));
        }
        mesh
    }

    /// Anchor `k` of `a` (0: the input).
    fn anchor<'s>(&'s self, a: &'s Attrs<'a>, k: usize) -> &'s crate::AttributedMesh {
        if k == 0 {
            return &a.input;
        }
        a.anchors[k - 1]
            .get_or_init(|| attributed::simplified(self.anchor(a, k - 1), self.faces() >> k))
    }

    /// The file of `mesh` (simplification `faces` of the input, refitted
    /// or not: the same triangles) at `qp`, with the streams when the
    /// input has them; `None` when it cleans to nothing (every face of
    /// zero area).
    pub(super) fn code(
        &self,
        faces: u32,
        mesh: &TriMesh,
        qp: u8,
    ) -> Result<Option<(Vec<u8>, LosslessStats)>, Error> {
        match self.file(faces, mesh, qp) {
            Ok((b, stats, _, _)) => Ok(Some((b, stats))),
            Err(Error::Topology(TopologyError::NoTriangles)) => Ok(None),
            Err(e) => Err(e),
        }
    }

    /// [`code`](Self::code)'s file with its figures, the cleaned mesh it
    /// codes and the vertex of that mesh each decoded vertex is.
    pub fn file(
        &self,
        faces: u32,
        mesh: &TriMesh,
        qp: u8,
    ) -> Result<(Vec<u8>, LosslessStats, Vec<u32>, TriMesh), Error> {
        let Some(a) = &self.attrs else {
            let cleaned = crate::clean(mesh, &CleanOptions::default())?;
            let (b, st, source) =
                crate::lossless::encode(&cleaned.table, &cleaned.mesh, qp, self.framing)?;
            return Ok((b, st, source, cleaned.mesh));
        };
        let streams = self.simplify_attributed(faces).streams;
        let with = crate::AttributedMesh::new(mesh.clone(), streams);
        let (cleaned, streams) = crate::clean_attributed(&with, &CleanOptions::default())?;
        let (b, st, source) = crate::lossless::encode_attributed(
            &cleaned.table,
            &cleaned.mesh,
            &streams,
            &a.quantization,
            qp,
            self.framing,
        )?;
        Ok((b, st, source, cleaned.mesh))
    }

    /// The same simplifier, told that its mesh is `cleaned`'s (the
    /// encoder's cleaning of the input): the whole mesh's files use that
    /// corner table instead of cleaning the mesh again, 0.45 s on a
    /// million triangles. Cleaning a cleaned mesh changes nothing (on
    /// every mesh of the shared corpus: the same mesh, the same files),
    /// so neither do the files.
    pub fn of_cleaned(self, cleaned: &'a crate::Cleaned) -> Simplifier<'a> {
        debug_assert!(core::ptr::eq(self.mesh, &cleaned.mesh));
        Simplifier {
            given: Some(cleaned),
            ..self
        }
    }

    /// The whole mesh's file at `qp`: [`lossless_bytes`] of the input,
    /// from the cached cleaning and file (the same bytes).
    pub(super) fn whole_bytes(&self, qp: u8) -> Result<Vec<u8>, Error> {
        Ok(self.whole_file(qp)?.0)
    }

    /// The whole mesh's file at `qp` and its figures, from the cached
    /// cleaning, connectivity and files (the bytes of [`lossless_bytes`]).
    pub fn whole_file(&self, qp: u8) -> Result<(Vec<u8>, LosslessStats), Error> {
        let lock = || self.whole_files.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, b, st)) = lock().iter().find(|(q, _, _)| *q == qp) {
            return Ok((b.clone(), st.clone()));
        }
        let cleaned = match self.given {
            Some(given) => Some(given),
            None => self
                .whole
                .get_or_init(|| crate::clean(self.mesh, &CleanOptions::default()).ok())
                .as_ref(),
        };
        let Some(c) = cleaned else {
            // The error, made again.
            let (b, st, _) = lossless_file(self.mesh, qp, self.framing)?;
            return Ok((b, st));
        };
        if let Some(a) = &self.attrs {
            // The streams follow the given cleaning's faces; without it,
            // the mesh is cleaned with them (`file`).
            let prepared = self.given.and_then(|c| {
                a.prepared
                    .get_or_init(|| {
                        crate::lossless::Prepared::with_attributes(&c.table, &c.mesh, self.framing)
                            .ok()
                    })
                    .as_ref()
            });
            let (bytes, stats) = match prepared {
                Some(p) => {
                    p.file_with(&c.mesh.positions, qp, Some((a.streams, &a.quantization)))?
                }
                None => {
                    let (b, st, _, _) = self.file(self.faces(), self.mesh, qp)?;
                    (b, st)
                }
            };
            lock().push((qp, bytes.clone(), stats.clone()));
            return Ok((bytes, stats));
        }
        let prepared = self
            .prepared
            .get_or_init(|| crate::lossless::Prepared::new(&c.table, &c.mesh, self.framing).ok());
        let (bytes, stats) = match prepared {
            Some(p) => p.file(&c.mesh.positions, qp)?,
            // The error, made again.
            None => {
                let (b, st, _) = crate::lossless::encode(&c.table, &c.mesh, qp, self.framing)?;
                (b, st)
            }
        };
        lock().push((qp, bytes.clone(), stats.clone()));
        Ok((bytes, stats))
    }

    /// The same, simplifying with meshoptimizer's `meshopt_simplify`
    /// (effort `fast`): about a tenth of the time of the quadric collapse
    /// sequence, which it does not make, for a coarser placement (each
    /// vertex stays at one of its ends' positions before the refit;
    /// BENCHMARKS.md, "Effort levels"); a large input in spatial pieces
    /// on all cores (`chunked`).
    pub fn quick(mesh: &'a TriMesh, framing: Framing) -> Simplifier<'a> {
        Simplifier {
            quick: true,
            ..Simplifier::new(mesh, framing)
        }
    }

    /// Faces of the input.
    pub fn faces(&self) -> u32 {
        self.mesh.triangles.len() as u32
    }

    /// The surface simplified files are measured against: the input, or
    /// the copy with rebuilt fans (see [`new`](Self::new)).
    pub fn reference(&self) -> &TriMesh {
        &self.work
    }

    /// Whether [`reference`](Self::reference) is the mesh it was made
    /// from, as it was given (no fan rebuilt).
    pub fn measures_against_its_mesh(&self) -> bool {
        matches!(self.work, Cow::Borrowed(_))
    }

    /// The input simplified to at most `target` faces (the input itself
    /// when it has no more), before its refit ([`refit`](Self::refit)):
    /// what the size search probes. Deterministic.
    pub fn simplify(&self, target: u32) -> TriMesh {
        if target >= self.faces() {
            return self.mesh.clone();
        }
        if self.attrs.is_some() {
            return self.simplify_attributed(target).mesh;
        }
        if self.quick {
            let mut made = self.made.lock().unwrap_or_else(|p| p.into_inner());
            if let Some((_, m)) = made.iter().find(|(t, _)| *t == target) {
                return m.clone();
            }
            let from = made
                .iter()
                .map(|(_, m)| m)
                .filter(|m| m.face_count() as u32 > target)
                .min_by_key(|m| m.face_count())
                .unwrap_or(&*self.work);
            let mesh = meshopt_simplified(from, target);
            made.push((target, mesh.clone()));
            return mesh;
        }
        let c = self
            .collapses
            .get_or_init(|| collapse_pieces::collapses(&self.work, MIN_FACES));
        let r = c.replay(&self.work, target);
        compact(&r.positions, &r.triangles)
    }

    /// For each vertex of [`simplify`](Self::simplify)`(target)`'s mesh,
    /// the vertex of [`reference`](Self::reference) it stands for: the
    /// survivor of its collapses (the collapse sequence keeps one end of
    /// each collapsed edge and moves it), or for the quick engine, which
    /// keeps a subset of the vertices where they were, the vertex at its
    /// position (`u32::MAX` where none is: never for a mesh `simplify`
    /// made). What the method's provenance starts from
    /// (`encoder::provenance`); a refit moves vertices but keeps their
    /// numbers, so it holds for the refitted mesh too.
    pub fn sources(&self, target: u32) -> Vec<u32> {
        if target < self.faces() && !self.quick && self.attrs.is_none() {
            let c = self
                .collapses
                .get_or_init(|| collapse_pieces::collapses(&self.work, MIN_FACES));
            let r = c.replay(&self.work, target);
            // The order `compact` numbers them in: first use.
            let mut seen = vec![false; r.positions.len()];
            let mut out = Vec::new();
            for &v in r.triangles.iter().flatten() {
                if !core::mem::replace(&mut seen[v as usize], true) {
                    out.push(v);
                }
            }
            return out;
        }
        let mesh = self.simplify(target);
        let work = crate::mesh::clean::PositionIndex::new(&self.work.positions);
        mesh.positions
            .iter()
            .map(|p| work.find(p).unwrap_or(u32::MAX))
            .collect()
    }

    /// How far above the predicted face count a size search's first
    /// probe aims. The collapse sequence replays any count at the same
    /// cost: 1. The quick engine simplifies each count from the smallest
    /// simplification above it, so a probe below the answer makes every
    /// later one start again from the input (on a million triangles a
    /// second each): it aims a third high, where a bits-per-face model's
    /// miss rarely leaves it short, and the rest of the search steps down.
    pub(super) fn first_probe_factor(&self) -> f64 {
        if self.quick {
            1.3
        } else {
            1.0
        }
    }

    /// `mesh` (a simplification) refitted to the input (`refit`).
    pub fn refit(&self, mesh: &mut TriMesh) {
        refit::refit(mesh, &self.work, REFIT_SWEEPS);
    }
}

/// The distance from `reference` to what the file `bytes` decodes to,
/// with `samples` area-uniform face samples per direction: how every
/// candidate file of the encoder is measured.
pub(crate) fn file_distance(
    bytes: &[u8],
    reference: &Surface,
    samples: u64,
) -> Result<SurfaceDistance, Error> {
    let decoded = crate::decoder::decode(bytes, &Default::default())?;
    // The decoded surface answers `samples` queries only: effort `fast`'s
    // 2,000 against tens of thousands of faces take the Morton tree (the
    // same distances, bit for bit; `metrics::bvh::morton`).
    let how = crate::metrics::Build::for_queries(decoded.face_count(), samples);
    crate::metrics::distance_between(
        reference,
        &Surface::with_build(&decoded, how)?,
        &DistanceOptions::area_uniform(samples),
    )
}

/// The mode-0 file of `mesh` at `qp`, as [`encode`](crate::encode) writes
/// it (cleaned first: a simplification may leave a degenerate face).
pub fn lossless_bytes(mesh: &TriMesh, qp: u8, framing: Framing) -> Result<Vec<u8>, Error> {
    Ok(lossless_file(mesh, qp, framing)?.0)
}

/// The same file with its figures and the source of each decoded vertex
/// (an index into the cleaned mesh's vertices).
fn lossless_file(
    mesh: &TriMesh,
    qp: u8,
    framing: Framing,
) -> Result<(Vec<u8>, LosslessStats, Vec<u32>), Error> {
    let cleaned = crate::clean(mesh, &CleanOptions::default())?;
    crate::lossless::encode(&cleaned.table, &cleaned.mesh, qp, framing)
}

/// `mesh` simplified by meshoptimizer toward `target` faces (it may stop
/// above where a collapse would break the topology). No error bound: the
/// count decides.
fn meshopt_simplified(mesh: &TriMesh, target: u32) -> TriMesh {
    let Some(kept) = super::chunked::simplified_indices(mesh, target) else {
        return mesh.clone();
    };
    let triangles: Vec<[u32; 3]> = kept.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    compact(&mesh.positions, &triangles)
}

/// Keeps the vertices `triangles` use, renumbered in order of first use.
fn compact(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> TriMesh {
    let mut remap = vec![u32::MAX; positions.len()];
    let mut out = TriMesh::new(Vec::new(), Vec::with_capacity(triangles.len()));
    for t in triangles {
        let tri = t.map(|v| {
            let slot = &mut remap[v as usize];
            if *slot == u32::MAX {
                *slot = out.positions.len() as u32;
                out.positions.push(positions[v as usize]);
            }
            *slot
        });
        out.triangles.push(tri);
    }
    out
}

/// The smallest file this method writes for the input: [`MIN_FACES`]
/// faces at the coarsest qp.
///
/// A mesh so thin that its simplification to a few faces leaves only
/// zero-area triangles (a torus whose tube is a thousandth of its ring)
/// has no file at [`MIN_FACES`]: the face count doubles until cleaning
/// leaves a triangle (the whole mesh always does).
pub fn smallest_bytes(s: &Simplifier<'_>) -> Result<u64, Error> {
    let mut faces = MIN_FACES;
    loop {
        match s.code(faces, &s.simplify(faces), *QPS.start())? {
            Some((bytes, _)) => return Ok(bytes.len() as u64),
            None if faces >= s.faces() => return Err(TopologyError::NoTriangles.into()),
            None => faces = faces.saturating_mul(2).min(s.faces()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simplify::{best_fit, Climb};

    /// One polygon face of `n` vertices on the unit circle, fanned from its
    /// vertex 0 as the mesh readers triangulate it.
    fn fanned_polygon(n: u32) -> TriMesh {
        let positions = (0..n)
            .map(|i| {
                let a = core::f32::consts::TAU * i as f32 / n as f32;
                [a.cos(), a.sin(), 0.0]
            })
            .collect();
        TriMesh::new(positions, (1..n - 1).map(|i| [0, i, i + 1]).collect())
    }

    #[test]
    fn a_fanned_polygon_is_simplified_from_rebuilt_fans_and_stays_on_its_plane() {
        let m = fanned_polygon(3000);
        let s = Simplifier::new(&m, Framing::default());
        assert_eq!(s.faces(), 2998);
        assert!(max_valence(s.reference()) <= MAX_VALENCE);
        assert!((s.reference().area() - m.area()).abs() < 1e-6 * m.area());
        let small = s.simplify(200);
        assert!(small.face_count() <= 200 && small.face_count() > 0);
        assert!(small.positions.iter().all(|p| p[2] == 0.0));
        // The whole mesh asked for: the input itself, not the rebuilt copy.
        assert_eq!(s.simplify(2998), m);
    }

    #[test]
    fn an_ordinary_mesh_is_its_own_reference() {
        let m = fanned_polygon(100);
        let s = Simplifier::new(&m, Framing::default());
        assert!(core::ptr::eq(s.reference(), &m));
    }

    /// A torus of ring radius 1 whose tube has radius `r`.
    fn torus(r: f32, nu: u32, nv: u32) -> TriMesh {
        let mut positions = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                let (a, b) = (
                    core::f32::consts::TAU * i as f32 / nu as f32,
                    core::f32::consts::TAU * j as f32 / nv as f32,
                );
                let rho = 1.0 + r * b.cos();
                positions.push([rho * a.cos(), rho * a.sin(), r * b.sin()]);
            }
        }
        let id = |i: u32, j: u32| (i % nu) * nv + j % nv;
        let mut triangles = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        TriMesh::new(positions, triangles)
    }

    #[test]
    fn a_mesh_whose_coarse_simplifications_are_degenerate_still_fits() {
        // The tube is a thousandth of the ring: simplified to a few faces,
        // every triangle has zero area and cleaning leaves nothing. The
        // search steps over those counts instead of failing (issue 20).
        let m = crate::clean(&torus(0.001, 24, 6), &CleanOptions::default())
            .unwrap()
            .mesh;
        let s = Simplifier::new(&m, Framing::default());
        let smallest = smallest_bytes(&s).unwrap();
        let reference = Surface::new(s.reference()).unwrap();
        let (fit, _) = best_fit(&s, smallest, &|| Ok(&reference), Climb::Full(2000))
            .unwrap()
            .unwrap();
        assert!(fit.bytes.len() as u64 <= smallest);
        let (fit, _) = best_fit(&s, 3 * smallest, &|| Ok(&reference), Climb::Full(2000))
            .unwrap()
            .unwrap();
        assert!(fit.bytes.len() as u64 <= 3 * smallest);
        crate::decode(&fit.bytes, &Default::default()).unwrap();
    }
}

/// The streams' error terms weighed as a fraction of the diagonal:
/// texture coordinates' RMS texels and colours' RMS 8-bit steps at their
/// weights (`simplify::attributed`).
fn weighed(texels: Option<crate::metrics::texcoord::TexcoordError>, steps: Option<f64>) -> f64 {
    let texels = texels.map_or(0.0, |e| e.rms_texels);
    attributed::TEXEL_WEIGHT * texels + attributed::COLOUR_STEP_WEIGHT * steps.unwrap_or(0.0)
}
