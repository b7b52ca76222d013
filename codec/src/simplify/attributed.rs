//! Simplification that carries attribute streams (issue 47, item 3):
//! meshoptimizer's `meshopt_simplifyWithAttributes` on the split form of
//! the mesh ([`AttributedMesh::split_vertices`]), welded back.
//!
//! Sources: Garland & Heckbert, "Simplifying surfaces with color and
//! texture using quadric error metrics" (1998) and Hoppe, "New quadric
//! metric for simplifying meshes with appearance attributes" (1999): the
//! attributes join the quadric, so a collapse that stretches a texture
//! or bends a normal costs what it distorts; meshoptimizer implements
//! Hoppe's form (one gradient per attribute component) and its seam
//! rules.
//!
//! Seams: the split form has one vertex per distinct (position, value of
//! each stream), so a UV or normal seam is a run of vertex pairs at equal
//! positions. meshoptimizer finds them by position itself and classifies
//! such vertices as seam vertices: one collapses only along its seam,
//! onto another seam vertex, with its twin on the other side collapsing
//! the same way, so chart boundaries stay where they were and both sides
//! of a seam move together. Nothing is ever collapsed across a seam, and
//! no value is interpolated: every kept vertex is an input vertex with its
//! position and values as they were (meshoptimizer keeps a subset of the
//! vertices in place). Welding back ([`AttributedMesh::weld`]) merges the
//! split copies again.
//!
//! Why meshoptimizer and not swm's own collapse (`qem`): its attribute
//! quadrics and seam classification are what issue 47 asks for and have
//! been in production in gltfpack for years; extending `qem`'s quadrics
//! with per-attribute gradients and its link checks with seam pairs would
//! duplicate both. Measured on spot (the `engines` test below; L2 in 1e-4
//! of the diagonal, each refitted, at 150 / 300 / 600 / 1,200 / 2,400
//! faces): the own collapse 51.9 / 27.2 / 14.9 / 7.6 / 3.1, meshoptimizer
//! without attributes 66.2 / 38.1 / 19.4 / 10.9 / 4.5, with them 68.4 /
//! 37.7 / 20.5 / 10.8 / 4.7. Keeping the seams costs almost nothing; the
//! gap (about 1.4x) is meshoptimizer keeping each vertex where it was
//! instead of at its quadric's minimum, the price of this route until
//! `qem` learns seams. Inputs without streams keep the own engine.
//!
//! The refit (`refit`, each vertex moved along its normal toward the
//! input) keeps each vertex's values, the collapse's: it moves the
//! vertex off the surface, not along it, so the texture stays where it
//! was to first order. Measured on spot, texture coordinates' RMS error
//! in texels at 1024 before and after the refit: 20.7 / 8.9 / 6.2 / 3.5 /
//! 1.7 and 22.8 / 9.2 / 5.3 / 3.5 / 1.7 at the same face counts, no
//! reason to resample them from the input. A seam vertex is one position
//! in the welded mesh, so both sides of a seam move together.
//!
//! Weights ([`weight`]): meshoptimizer measures position error relative
//! to the mesh's extent and attribute error as given, so a weight says
//! how much one unit of attribute difference costs in units of the
//! extent. A texture coordinate step of one texel of a
//! [`TEXTURE_SIZE`]-texel texture (1/1024) costs as a position error of
//! 1/1024 of the extent: weight 1. Unit normals: 0.5 (a 30° bend, 0.52,
//! costs as a quarter of the extent: normals matter where the geometry
//! does not already say them). Colours 1 (a step of 1/255 costs as
//! 1/255 of the extent), generic streams 0.5.

use crate::mesh::{AttributeKind, AttributeStream, AttributedMesh};
use crate::TriMesh;

pub use crate::metrics::texcoord::TEXTURE_SIZE;

/// What one texel (RMS, of a [`TEXTURE_SIZE`] texture) of texture
/// coordinate error weighs beside L2 where the simplified method compares
/// its files (`Simplifier::attribute_error`), as a fraction of the
/// diagonal: 1e-4. A texture that covers a model about once puts a texel
/// about 1e-3 of the diagonal along its surface; a texture sliding along
/// the surface by that much shows about as little as the surface leaving
/// its place by a tenth of it. On spot at 2-8 b/v the simplified files'
/// L2 is 11-60e-4 and their texture coordinates 3.6-15.5 texels off
/// (BENCHMARKS.md, "Lossy encodes that keep attributes"): both terms
/// count.
pub const TEXEL_WEIGHT: f64 = 1e-4;

/// What one 8-bit step (RMS, 1/255 over all components) of colour error
/// weighs beside L2, as a fraction of the diagonal: 1e-4, as a texel: a
/// step is at the edge of what shows, as is an error of 1e-4 of the
/// diagonal.
pub const COLOUR_STEP_WEIGHT: f64 = 1e-4;

/// meshoptimizer's limit on attribute components (`kMaxAttributes`);
/// components past it get no weight (their seams still hold: seams come
/// from the split, not from the weights).
const MAX_COMPONENTS: usize = 32;

/// The weight of each component of a stream of `kind` in the
/// simplification's error (see the module header).
pub fn weight(kind: AttributeKind) -> f32 {
    match kind {
        AttributeKind::TexCoord(_) => 1.0,
        AttributeKind::Normal => 0.5,
        AttributeKind::Color(_) => 1.0,
        _ => 0.5,
    }
}

/// `mesh` with its streams simplified toward `target` faces (it may stop
/// above where a collapse would break the topology or cross a seam).
/// Deterministic. Every vertex of the result is a vertex of `mesh`, every
/// value a value of its stream.
pub fn simplified(mesh: &AttributedMesh, target: u32) -> AttributedMesh {
    let split = mesh.split_vertices();
    let n = split.mesh.positions.len();
    // Components, interleaved per vertex, as many as meshoptimizer takes.
    let mut weights: Vec<f32> = Vec::new();
    let mut taken: Vec<(usize, usize)> = Vec::new();
    for (k, s) in split.streams.iter().enumerate() {
        for d in 0..usize::from(s.dims) {
            if weights.len() < MAX_COMPONENTS {
                weights.push(weight(s.kind));
                taken.push((k, d));
            }
        }
    }
    let stride = weights.len().max(1);
    let mut values = vec![0f32; n * stride];
    for v in 0..n {
        for (j, &(k, d)) in taken.iter().enumerate() {
            let s = &split.streams[k];
            values[v * stride + j] = s.values[v * usize::from(s.dims) + d];
        }
    }
    let indices: Vec<u32> = split.mesh.triangles.iter().flatten().copied().collect();
    // meshoptimizer asserts (and aborts the process) on a target above
    // its input: an anchor may stop below its nominal count, so a target
    // between the two reaches here (beetle's third anchor: 253 faces of
    // 256, asked for 254).
    if 3 * target as usize >= indices.len() {
        return mesh.clone();
    }
    let bytes = meshopt::typed_to_bytes(&split.mesh.positions);
    let Ok(vertices) = meshopt::VertexDataAdapter::new(bytes, 12, 0) else {
        return mesh.clone();
    };
    // No vertex locked; meshoptimizer reads one flag per vertex.
    let locks = vec![false; n];
    let kept = if weights.is_empty() {
        meshopt::simplify(
            &indices,
            &vertices,
            3 * target as usize,
            f32::MAX,
            meshopt::SimplifyOptions::None,
            None,
        )
    } else {
        meshopt::simplify_with_attributes_and_locks(
            &indices,
            &vertices,
            &values,
            &weights,
            stride * core::mem::size_of::<f32>(),
            &locks,
            3 * target as usize,
            f32::MAX,
            meshopt::SimplifyOptions::None,
            None,
        )
    };
    let triangles: Vec<[u32; 3]> = kept.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    compact(&split, &triangles).weld()
}

/// The split mesh's vertices `triangles` use, in order of first use, with
/// their values: still in split form, for [`AttributedMesh::weld`].
fn compact(split: &AttributedMesh, triangles: &[[u32; 3]]) -> AttributedMesh {
    let mut remap = vec![u32::MAX; split.mesh.positions.len()];
    let mut order: Vec<u32> = Vec::new();
    let tris: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| {
            t.map(|v| {
                let slot = &mut remap[v as usize];
                if *slot == u32::MAX {
                    *slot = order.len() as u32;
                    order.push(v);
                }
                *slot
            })
        })
        .collect();
    let positions = order
        .iter()
        .map(|&v| split.mesh.positions[v as usize])
        .collect();
    let streams = split
        .streams
        .iter()
        .map(|s| {
            let dims = usize::from(s.dims);
            let values = order
                .iter()
                .flat_map(|&v| s.values[v as usize * dims..(v as usize + 1) * dims].iter())
                .copied()
                .collect();
            AttributeStream::new(s.kind, s.dims, values, tris.clone())
        })
        .collect();
    AttributedMesh::new(TriMesh::new(positions, tris), streams)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_shapes::textured_sphere as uv_sphere;

    /// meshoptimizer aborts the process on a target above its input; an
    /// anchor that stopped below its nominal count passes such targets.
    #[test]
    fn a_target_at_or_above_the_faces_keeps_the_mesh() {
        let m = uv_sphere(12, 8);
        let faces = m.mesh.face_count() as u32;
        for target in [faces, faces + 1, 2 * faces] {
            let same = simplified(&m, target);
            assert_eq!(same.mesh.face_count(), m.mesh.face_count());
        }
    }

    #[test]
    fn every_kept_corner_keeps_an_input_corner_of_its_position() {
        let m = uv_sphere(24, 16);
        let small = simplified(&m, 200);
        assert!(small.mesh.face_count() <= 220 && small.mesh.face_count() > 50);
        small.validate().unwrap();
        // (position, uv) pairs of the input's corners.
        let uv = m.stream(AttributeKind::TexCoord(0)).unwrap();
        let mut pairs = Vec::new();
        for (f, t) in m.mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let p = m.mesh.positions[t[k] as usize].map(f32::to_bits);
                let q = uv.value(uv.corners[f][k]);
                pairs.push((p, [q[0].to_bits(), q[1].to_bits()]));
            }
        }
        let out = small.stream(AttributeKind::TexCoord(0)).unwrap();
        for (f, t) in small.mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let p = small.mesh.positions[t[k] as usize].map(f32::to_bits);
                let q = out.value(out.corners[f][k]);
                assert!(
                    pairs.contains(&(p, [q[0].to_bits(), q[1].to_bits()])),
                    "a corner's (position, uv) pair is not the input's"
                );
            }
        }
    }

    #[test]
    fn the_seam_stays_a_seam_and_no_face_spans_it() {
        let m = uv_sphere(24, 16);
        let small = simplified(&m, 150);
        let uv = small.stream(AttributeKind::TexCoord(0)).unwrap();
        // The sphere's seam is at u = 0 / u = 1: no face mixes corners of
        // both ends (it would be stretched across the whole texture).
        for f in 0..small.mesh.face_count() {
            let us: Vec<f32> = (0..3).map(|k| uv.value(uv.corners[f][k])[0]).collect();
            let (lo, hi) = us
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &u| (a.min(u), b.max(u)));
            assert!(hi - lo < 0.5, "face {f} spans the seam: {us:?}");
        }
        // And the seam is still there: some position has two u values.
        assert!(uv.value_count() > small.mesh.positions.len());
    }

    #[test]
    fn deterministic() {
        let m = uv_sphere(20, 12);
        assert_eq!(simplified(&m, 100), simplified(&m, 100));
    }
}

/// The measurements behind the module header's choices, on spot from
/// `../shared/corpus` (`cargo test -p swm --release --lib engines --
/// --ignored --nocapture`): L2 (1e-4 of the diagonal) of swm's collapse
/// sequence, of meshoptimizer without attributes and with them, each
/// refitted, at several face counts; and the texture coordinates' error
/// of the attributed one before and after the refit, which keeps each
/// vertex's values.
#[cfg(test)]
mod engines {
    use super::*;
    use crate::metrics::{distance_between, DistanceOptions, Surface};
    use crate::simplify::Simplifier;

    #[test]
    #[ignore]
    fn engines() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus");
        let path = dir.join("spot.obj");
        if !path.is_file() {
            crate::test_skip::skip("../shared/corpus not found");
            return;
        }
        let (input, _) = crate::io::read_attributed_mesh_with(&path, None, &Default::default())
            .expect("spot reads");
        let (cleaned, streams) =
            crate::clean_attributed(&input, &Default::default()).expect("spot cleans");
        let attributed = AttributedMesh::new(cleaned.mesh.clone(), streams);
        let reference = Surface::new(&cleaned.mesh).unwrap();
        let framing = crate::Framing::default();
        let own = Simplifier::new(&cleaned.mesh, framing);
        let quick = Simplifier::quick(&cleaned.mesh, framing);
        let l2 = |m: &TriMesh| {
            let d = distance_between(
                &reference,
                &Surface::new(m).unwrap(),
                &DistanceOptions::default(),
            )
            .unwrap();
            1e4 * d.l2_relative()
        };
        let uv = |m: &AttributedMesh| {
            crate::metrics::texcoord::texcoord_error(&attributed, &reference, m)
                .map_or(f64::NAN, |e| e.rms_texels)
        };
        std::println!("faces | own qem | meshopt | meshopt+uv | uv rms texels (unrefit, refit)");
        for faces in [150u32, 300, 600, 1200, 2400] {
            let mut a = own.simplify(faces);
            own.refit(&mut a);
            let mut b = quick.simplify(faces);
            own.refit(&mut b);
            let c0 = simplified(&attributed, faces);
            let mut c = c0.clone();
            own.refit(&mut c.mesh);
            std::println!(
                "{faces} ({}) | {:.2} | {:.2} | {:.2} | {:.2}, {:.2}",
                c.mesh.face_count(),
                l2(&a),
                l2(&b),
                l2(&c.mesh),
                uv(&c0),
                uv(&c)
            );
        }
    }
}
