//! Analytic checks of the surface distance: cases whose answer is known in
//! closed form or by an independent quadrature.

use super::*;
use crate::edgebreaker::tests_support::{grid, icosahedron, subdivided};

fn lifted(m: &TriMesh, dz: f32) -> TriMesh {
    let mut m = m.clone();
    for p in &mut m.positions {
        p[2] += dz;
    }
    m
}

/// An icosahedron inscribed in the unit sphere, subdivided `levels` times
/// with every new vertex pushed out onto the sphere.
fn sphere(levels: u32) -> TriMesh {
    let (p, f) = icosahedron((1.0 + 5f64.sqrt()) / 2.0);
    let p = p.into_iter().map(unit).collect();
    let (p, f) = subdivided((p, f), levels, |a, b| {
        unit(core::array::from_fn(|i| a[i] + b[i]))
    });
    TriMesh::new(p.iter().map(|q| q.map(|c| c as f32)).collect(), f)
}

fn unit(p: [f64; 3]) -> [f64; 3] {
    let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    p.map(|c| c / n)
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

#[test]
fn identical_meshes_are_at_distance_zero() {
    let m = sphere(2);
    let d = distance(&m, &m, &DistanceOptions::default()).unwrap();
    // Vertex samples are exactly on the other mesh; face and edge samples
    // are off only by the rounding of their own coordinates.
    assert!(d.hausdorff() < 1e-12, "{d:?}");
    assert!(d.l2() < 1e-12);
    assert!(d.forward.samples > 10 * 320);
    assert_eq!(d.forward.samples, d.backward.samples);
}

#[test]
fn offset_planes_are_exactly_the_offset_apart() {
    let a = grid(4, 4);
    let b = lifted(&a, 0.5);
    for options in [
        DistanceOptions::default(),
        DistanceOptions::area_uniform(5000),
    ] {
        let d = distance(&a, &b, &options).unwrap();
        for one in [d.forward, d.backward] {
            assert!((one.max - 0.5).abs() < 1e-12);
            assert!((one.mean - 0.5).abs() < 1e-12);
            assert!((one.rms - 0.5).abs() < 1e-12);
        }
        assert!((d.l2_relative() - 0.5 / 32f64.sqrt()).abs() < 1e-12);
        assert!((d.hausdorff_relative() - 0.5 / 32f64.sqrt()).abs() < 1e-12);
    }
}

#[test]
fn one_raised_vertex_is_the_hausdorff_distance() {
    let flat = grid(6, 6);
    let mut bumped = flat.clone();
    bumped.positions[3 * 7 + 3][2] = 0.75;
    let d = distance(&flat, &bumped, &DistanceOptions::default()).unwrap();
    // The raised vertex is a sample of the bumped mesh, 0.75 above the
    // plane; nothing on the flat mesh is that far from the bump.
    assert_eq!(d.backward.max, 0.75);
    assert!(d.forward.max < 0.75);
    assert_eq!(d.hausdorff(), 0.75);
}

#[test]
fn unreferenced_vertices_are_not_samples() {
    // Distance is a property of the surfaces: a stray vertex that no face
    // uses is neither a sample nor part of the reference's bounding box
    // (MeshLab's filter, which samples every vertex of the list, differs
    // here; tools/metro/compare.py removes such vertices before it runs).
    let a = grid(4, 4);
    let b = lifted(&a, 0.5);
    let stray = |m: &TriMesh| {
        let mut m = m.clone();
        m.positions.push([2.0, 2.0, 100.0]);
        m
    };
    let plain = distance(&a, &b, &DistanceOptions::default()).unwrap();
    let with_strays = distance(&stray(&a), &stray(&b), &DistanceOptions::default()).unwrap();
    assert_eq!(plain, with_strays);
    assert!((with_strays.hausdorff() - 0.5).abs() < 1e-12);
}

/// Icosahedron inscribed in the unit sphere: its inradius is
/// `√((5 + 2√5)/15)` times the circumradius, so the farthest point of a
/// face from the sphere is its centre, `1 − inradius` away; the RMS over
/// a face of `1 − |p|` comes from an independent midpoint quadrature.
#[test]
fn sphere_against_inscribed_icosahedron() {
    let inradius = ((5.0 + 2.0 * 5f64.sqrt()) / 15.0).sqrt();
    let expected_max = 1.0 - inradius;
    let ico = sphere(0);
    let t = ico.triangles[0].map(|v| ico.positions[v as usize].map(|c| c as f64));
    let n = 600;
    let (mut sum2, mut count) = (0.0, 0u64);
    for i in 0..n {
        for j in 0..n - i {
            // Midpoints of the upright cells of an n × n barycentric grid
            // (equal areas).
            let (u, v) = (
                (i as f64 + 1.0 / 3.0) / n as f64,
                (j as f64 + 1.0 / 3.0) / n as f64,
            );
            let p: [f64; 3] = core::array::from_fn(|k| {
                t[0][k] + u * (t[1][k] - t[0][k]) + v * (t[2][k] - t[0][k])
            });
            let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            sum2 += (1.0 - r).powi(2);
            count += 1;
        }
    }
    let expected_rms = (sum2 / count as f64).sqrt();

    // The sphere as a fine mesh: 20,480 faces, within 3e-4 of the sphere.
    let fine = sphere(5);
    let d = distance(&ico, &fine, &DistanceOptions::area_uniform(200_000)).unwrap();
    assert!(
        close(d.forward.max, expected_max, 3e-3),
        "{} vs {expected_max}",
        d.forward.max
    );
    assert!(
        close(d.forward.rms, expected_rms, 3e-3),
        "{} vs {expected_rms}",
        d.forward.rms
    );
    // From the sphere's side the farthest points are above the face
    // centres too.
    assert!(
        close(d.backward.max, expected_max, 3e-3),
        "{}",
        d.backward.max
    );
    assert!(close(d.hausdorff(), expected_max, 3e-3));
}

#[test]
fn independent_of_the_thread_count() {
    let a = sphere(3);
    let b = lifted(&sphere(2), 0.01);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| distance(&a, &b, &DistanceOptions::default()).unwrap())
    };
    let one = run(1);
    assert_eq!(one, run(3));
    assert_eq!(one, run(8));
    // And the seed matters only to the face samples' positions.
    let other_seed = distance(
        &a,
        &b,
        &DistanceOptions {
            seed: 9,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(other_seed.forward.samples, one.forward.samples);
    assert_ne!(other_seed.forward.rms, one.forward.rms);
}

#[test]
fn sample_counts_follow_the_options() {
    let a = grid(10, 10);
    let b = lifted(&a, 0.1);
    let faces_only = distance(&a, &b, &DistanceOptions::area_uniform(1000)).unwrap();
    assert_eq!(faces_only.forward.samples, 1000);
    let default = distance(&a, &b, &DistanceOptions::default()).unwrap();
    // 121 vertices, 320 edges of lengths 1 and √2 at √(2000/100) points
    // per unit length, 2000 face samples.
    let edges = 220.0 * 20f64.sqrt() + 100.0 * (2.0 * 20f64).sqrt();
    let expected = 121.0 + edges + 2000.0;
    assert!((default.forward.samples as f64 - expected).abs() < 2.0);
    assert!(distance(
        &a,
        &b,
        &DistanceOptions {
            face_samples: Some(0),
            vertex_samples: false,
            edge_samples: false,
            seed: 0
        }
    )
    .is_err());
}

#[test]
fn bad_meshes_are_errors() {
    let good = grid(2, 2);
    let empty = TriMesh::new(vec![[0.0; 3]], vec![]);
    assert!(matches!(
        distance(&good, &empty, &DistanceOptions::default()),
        Err(Error::Topology(TopologyError::NoTriangles))
    ));
    let dangling = TriMesh::new(vec![[0.0; 3]; 2], vec![[0, 1, 2]]);
    assert!(matches!(
        distance(&dangling, &good, &DistanceOptions::default()),
        Err(Error::Format(_))
    ));
    let nan = TriMesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, f32::NAN, 0.0]],
        vec![[0, 1, 2]],
    );
    assert!(matches!(
        distance(&good, &nan, &DistanceOptions::default()),
        Err(Error::Format(_))
    ));
    // A degenerate (zero-area) surface is measurable.
    let flat = TriMesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
        vec![[0, 1, 2]],
    );
    let d = distance(&good, &flat, &DistanceOptions::default()).unwrap();
    assert!(d.hausdorff().is_finite() && d.hausdorff() > 0.0);
}

fn scaled(m: &TriMesh, s: f64) -> TriMesh {
    let mut m = m.clone();
    for p in &mut m.positions {
        *p = p.map(|c| (c as f64 * s) as f32);
    }
    m
}

/// Nodes the nearest-point searches read when every vertex of `from`
/// and the centroid of every face is measured against `to`, as the
/// samples are (in leaf order, warm-started).
fn visits(from: &Surface, to: &Surface) -> u64 {
    let mut scratch = Scratch::default();
    let mut hint = None;
    for f in 0..from.face_count() {
        let t = from.triangle(f);
        let c = core::array::from_fn(|k| t.iter().map(|v| v[k] as f64).sum::<f64>() / 3.0);
        for p in t.iter().map(|v| v.map(|c| c as f64)).chain([c]) {
            hint = to.bvh.nearest(p, hint, &mut scratch).map(|n| n.slot);
        }
    }
    scratch.visits()
}

/// Issue 18: distances do not depend on the units. A mesh in units of
/// 1e30 or 1e-30 (or near the ends of `f32`'s range) gives the same
/// relative figures as in its own units, for the same work: the tree's
/// box tests used to overflow to infinity or underflow to zero there, so
/// nothing was pruned and every query read every node.
#[test]
fn distances_do_not_depend_on_the_units() {
    let (a, b) = (sphere(4), lifted(&sphere(2), 0.01));
    let options = DistanceOptions {
        face_samples: Some(1000),
        ..Default::default()
    };
    let base = distance(&a, &b, &options).unwrap();
    let own = distance(&a, &a, &options).unwrap();
    let work = |a: &TriMesh, b: &TriMesh| {
        let (a, b) = (Surface::new(a).unwrap(), Surface::new(b).unwrap());
        visits(&a, &b) + visits(&b, &a)
    };
    let base_work = work(&a, &b);
    for s in [1e30, 1e-30, 1e37, 1e-36, 0.75] {
        let (sa, sb) = (scaled(&a, s), scaled(&b, s));
        let d = distance(&sa, &sb, &options).unwrap();
        // Edge sample counts carry fractions, which rounding may tip.
        let n = |x: &SurfaceDistance| x.forward.samples as i64;
        assert!((n(&d) - n(&base)).abs() <= 2, "scale {s}: {d:?}");
        for (x, y) in [
            (d.l2_relative(), base.l2_relative()),
            (d.hausdorff_relative(), base.hausdorff_relative()),
            (d.mean() / d.diagonal, base.mean() / base.diagonal),
        ] {
            // The f32 rounding of the scaled coordinates, no more.
            assert!(close(x, y, 1e-4), "scale {s}: {x} against {y}");
        }
        let self_d = distance(&sa, &sa, &options).unwrap();
        assert!(self_d.hausdorff_relative() < 1e-9, "scale {s}: {self_d:?}");
        assert!(own.hausdorff_relative() < 1e-9);
        let w = work(&sa, &sb);
        assert!(
            w < base_work * 3 / 2 && w > base_work * 2 / 3,
            "scale {s}: {w} node visits against {base_work}"
        );
    }
    // Two meshes in units 1e30 apart: every sample of the huge one is far
    // from the small one, and measured without reading every node each
    // time. (Beside it: from the centre of a sphere every triangle is
    // equally near, and any search reads them all, whatever the units.)
    let mut huge = scaled(&b, 1e30);
    for p in &mut huge.positions {
        p[0] += 3e30;
    }
    let d = distance(&a, &huge, &options).unwrap();
    assert!(d.l2().is_finite() && d.l2() > 1e29, "{d:?}");
    let (sa, sh) = (Surface::new(&a).unwrap(), Surface::new(&huge).unwrap());
    assert_eq!(visits(&sh, &sa), 0);
    let near = visits(&sa, &sh);
    assert!(near < 20 * 4 * sa.face_count() as u64, "{near}");
}

/// A power-of-two change of units changes nothing at all: the tree, the
/// samples and every figure scale exactly.
#[test]
fn power_of_two_units_scale_exactly() {
    let (a, b) = (sphere(3), lifted(&sphere(2), 0.01));
    let base = distance(&a, &b, &DistanceOptions::default()).unwrap();
    for s in [2f64.powi(100), 2f64.powi(-100), 0.5] {
        let d = distance(&scaled(&a, s), &scaled(&b, s), &DistanceOptions::default()).unwrap();
        assert_eq!(d.forward.samples, base.forward.samples);
        assert_eq!(d.l2(), base.l2() * s, "scale {s}");
        assert_eq!(d.hausdorff(), base.hausdorff() * s, "scale {s}");
        assert_eq!(d.backward.mean, base.backward.mean * s, "scale {s}");
    }
}

/// The original one-chunk loop over a face range: each sample measured
/// in turn from the previous one's triangle, added in order.
fn sequential_faces(
    from: &Surface,
    to: &Surface,
    faces: u64,
    options: &DistanceOptions,
) -> OneSided {
    let counts = carried_counts(from.areas.iter().copied(), faces as f64 / from.area);
    let mut scratch = Scratch::default();
    let (mut sums, mut hint) = (Sums::default(), None);
    for (f, &n) in counts.iter().enumerate() {
        let mut rng = SplitMix::new(options.seed, from.face_ids[f] as u64);
        face_points(&from.triangle(f), n, &mut rng, |p| {
            let hit = to.bvh.nearest(p, hint, &mut scratch).unwrap();
            hint = Some(hit.slot);
            sums.add(hit.distance2.sqrt());
        });
    }
    Sums::total(&[sums])
}

#[test]
fn a_chunk_of_many_samples_measured_on_all_threads_sums_the_same_bits() {
    // Two triangles (one chunk) holding 50,000 samples: the split path,
    // three blocks, against the loop it replaces, on 1 and 4 threads.
    let square = grid(1, 1);
    let (from, to) = (
        Surface::new(&square).unwrap(),
        Surface::new(&lifted(&sphere(3), 0.2)).unwrap(),
    );
    let options = DistanceOptions::area_uniform(50_000);
    let want = sequential_faces(&from, &to, 50_000, &options);
    assert!(want.samples > SPLIT_SAMPLES);
    for threads in [1, 4] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let got = pool.install(|| one_sided(&from, &to, 50_000, &options));
        assert_eq!(got.samples, want.samples);
        assert_eq!(got.rms.to_bits(), want.rms.to_bits());
        assert_eq!(got.mean.to_bits(), want.mean.to_bits());
        assert_eq!(got.max.to_bits(), want.max.to_bits());
    }
}
