//! Odd meshes given to the encoder in both modes: it either succeeds, and
//! then the file decodes to a valid mesh, or it fails with an
//! `swm::Error`; never a panic, never a hang. The meshes are small so that
//! each case runs in well under a second.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};
use swm::{DecodeOptions, EncodeMode, EncodeOptions, SwingTarget, TriMesh};

/// Generous for meshes of at most a few thousand triangles in a debug
/// build; a hang shows up as a case far beyond it.
const PER_CASE: Duration = Duration::from_secs(60);

/// Lossless, swing at 4 bits per vertex (which a tiny mesh cannot meet)
/// and swing at an edge length of a tenth of the bounding box diagonal
/// (which retiles even a tiny mesh).
fn modes(mesh: &TriMesh) -> [(&'static str, EncodeMode); 3] {
    [
        ("lossless", EncodeMode::Lossless { qp: 12 }),
        (
            "swing L = diagonal / 10",
            EncodeMode::Swing {
                target: SwingTarget::EdgeLength(mesh.bbox_diagonal() / 10.0),
                angle_bits: Some(8),
                max_bytes: None,
            },
        ),
        (
            "swing",
            EncodeMode::Swing {
                target: SwingTarget::BitsPerVertex(4.0),
                angle_bits: Some(8),
                max_bytes: None,
            },
        ),
    ]
}

/// Encodes `mesh` in both modes; returns which modes succeeded.
fn encode_both(name: &str, mesh: &TriMesh) -> Vec<&'static str> {
    let mut ok = Vec::new();
    for (mode_name, mode) in modes(mesh) {
        let what = format!("{name}, {mode_name}");
        let options = EncodeOptions {
            mode,
            ..Default::default()
        };
        let start = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| swm::encode(mesh, &options)))
            .unwrap_or_else(|_| panic!("{what}: the encoder panicked"));
        match result {
            Ok(encoded) => {
                let decoded = catch_unwind(AssertUnwindSafe(|| {
                    swm::decode(&encoded.bytes, &DecodeOptions::default())
                }))
                .unwrap_or_else(|_| panic!("{what}: the decoder panicked"))
                .unwrap_or_else(|e| panic!("{what}: encoded but does not decode: {e}"));
                decoded
                    .validate()
                    .unwrap_or_else(|e| panic!("{what}: decodes to an invalid mesh: {e}"));
                println!("{what}: {} bytes", encoded.bytes.len());
                ok.push(mode_name);
            }
            // The lossless mode takes whatever cleaning leaves, so it
            // must not fail on any of these; a retiling may (any error
            // will do, as long as it says something).
            Err(e) => {
                println!("{what}: {e}");
                assert!(mode_name != "lossless", "{what} failed: {e}");
                assert!(!e.to_string().is_empty(), "{what}");
            }
        }
        assert!(
            start.elapsed() < PER_CASE,
            "{what}: took {:?}",
            start.elapsed()
        );
    }
    ok
}

fn tetrahedron(offset: [f32; 3], size: f32) -> TriMesh {
    let p = |x: f32, y: f32, z: f32| {
        [
            offset[0] + x * size,
            offset[1] + y * size,
            offset[2] + z * size,
        ]
    };
    TriMesh::new(
        vec![p(0., 0., 0.), p(1., 0., 0.), p(0., 1., 0.), p(0., 0., 1.)],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

/// A clean manifold mesh (nothing for cleaning to drop) that the lossless
/// mode must keep whole: every triangle, every vertex, each position within
/// its `qp` grid's half step of the input.
fn lossless_keeps_every_triangle(name: &str, mesh: &TriMesh) {
    let options = EncodeOptions {
        mode: EncodeMode::Lossless { qp: 12 },
        ..Default::default()
    };
    let encoded = swm::encode(mesh, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
    let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
    assert_eq!(decoded.triangles.len(), mesh.triangles.len(), "{name}");
    assert_eq!(decoded.positions.len(), mesh.positions.len(), "{name}");
    // Each decoded vertex lies near an input vertex: within a grid step
    // of the bounding box's longest side at 12 bits.
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        });
    let side = (0..3).map(|i| f64::from(hi[i] - lo[i])).fold(0.0, f64::max);
    let step = side / 4095.0;
    for p in &decoded.positions {
        let nearest = mesh
            .positions
            .iter()
            .map(|q| {
                (0..3)
                    .map(|i| (f64::from(p[i]) - f64::from(q[i])).abs())
                    .fold(0.0, f64::max)
            })
            .fold(f64::MAX, f64::min);
        assert!(
            nearest <= step,
            "{name}: {p:?} is {nearest:e} from the input (step {step:e})"
        );
    }
}

fn append(a: &mut TriMesh, b: &TriMesh) {
    let base = a.positions.len() as u32;
    a.positions.extend_from_slice(&b.positions);
    a.triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + base)));
}

fn scaled(m: &TriMesh, s: f32) -> TriMesh {
    TriMesh::new(
        m.positions.iter().map(|p| p.map(|c| c * s)).collect(),
        m.triangles.clone(),
    )
}

#[test]
fn a_single_triangle() {
    let m = TriMesh::new(
        vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]],
        vec![[0, 1, 2]],
    );
    // Lossless keeps any manifold mesh; at 4 b/v the triangle is below
    // what retiling is worth, and the swing file holds it in REST.
    let ok = encode_both("one triangle", &m);
    assert!(ok.contains(&"lossless") && ok.contains(&"swing"), "{ok:?}");
}

#[test]
fn a_tetrahedron() {
    let ok = encode_both("tetrahedron", &tetrahedron([0.; 3], 1.0));
    assert!(ok.contains(&"lossless") && ok.contains(&"swing"), "{ok:?}");
}

#[test]
fn two_triangles_sharing_one_vertex() {
    let m = TriMesh::new(
        vec![
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [-1., 0., 0.],
            [0., -1., 0.],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    encode_both("bow tie", &m);
}

#[test]
fn thousands_of_tiny_components() {
    let mut m = TriMesh::default();
    for i in 0..2000 {
        let (x, y) = ((i % 50) as f32, (i / 50) as f32);
        append(&mut m, &tetrahedron([x, y, 0.], 0.3));
    }
    // Every component is far below L at 4 b/v: a swing file of REST only.
    assert!(encode_both("2000 tetrahedra", &m).contains(&"swing"));
}

#[test]
fn slivers_and_zero_area_faces() {
    // A strip whose middle row is squeezed to a line: slivers, then
    // triangles with three collinear corners.
    let mut p = Vec::new();
    for row in 0..3 {
        for col in 0..6 {
            let y = [0.0, 1e-7, 1e-7][row];
            p.push([col as f32, y, row as f32 * 1e-9]);
        }
    }
    let mut t = Vec::new();
    for row in 0..2u32 {
        for col in 0..5u32 {
            let a = row * 6 + col;
            t.push([a, a + 1, a + 7]);
            t.push([a, a + 7, a + 6]);
        }
    }
    encode_both("slivers", &TriMesh::new(p, t));
    // A closed mesh where one face has zero area: a tetrahedron with a
    // corner moved onto the opposite edge.
    let mut m = tetrahedron([0.; 3], 1.0);
    m.positions[3] = [0.5, 0.5, 0.0];
    encode_both("flat tetrahedron", &m);
}

#[test]
fn huge_and_tiny_coordinates() {
    let sphere = swm_corpus::icosphere(1.0, 2);
    encode_both("sphere at 1e30", &scaled(&sphere, 1e30));
    encode_both("sphere at 1e-30", &scaled(&sphere, 1e-30));
    lossless_keeps_every_triangle("sphere at 1e30", &scaled(&sphere, 1e30));
    lossless_keeps_every_triangle("sphere at 1e-30", &scaled(&sphere, 1e-30));
    // Far from the origin, small in extent.
    let shifted = TriMesh::new(
        sphere
            .positions
            .iter()
            .map(|p| [p[0] + 1e30, p[1], p[2]])
            .collect(),
        sphere.triangles.clone(),
    );
    encode_both("sphere shifted by 1e30", &shifted);
    // At 1e30 a float's step is far above the sphere's size: the shifted
    // sphere's vertices collapse onto few positions, which cleaning
    // merges, so only "lossless succeeds" holds for it (above).
}

#[test]
fn all_points_coplanar() {
    encode_both("plane patch", &swm_corpus::plane_patch(8, 8));
    lossless_keeps_every_triangle("plane patch", &swm_corpus::plane_patch(8, 8));
    // A closed "pillow" of zero thickness: two copies of a patch, one
    // flipped, sharing their boundary vertices is non-manifold-free only
    // if stitched; here the two sheets are separate.
    let a = swm_corpus::plane_patch(4, 4);
    let mut m = a.clone();
    let flipped = TriMesh::new(
        a.positions.clone(),
        a.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect(),
    );
    append(&mut m, &flipped);
    encode_both("two coincident sheets", &m);
}

#[test]
fn a_very_thin_torus() {
    // The tube is a thousandth of the ring: far thinner than any edge
    // length a few bits per vertex allow.
    encode_both("thin torus", &swm_corpus::torus(1.0, 0.001, 24, 6));
    lossless_keeps_every_triangle("thin torus", &swm_corpus::torus(1.0, 0.001, 24, 6));
}

#[test]
fn duplicate_faces() {
    let mut m = tetrahedron([0.; 3], 1.0);
    m.triangles.push(m.triangles[0]);
    m.triangles.push(m.triangles[1]);
    encode_both("duplicate faces", &m);
    // The same face twice, the second time reversed.
    let mut m = tetrahedron([0.; 3], 1.0);
    let t = m.triangles[0];
    m.triangles.push([t[0], t[2], t[1]]);
    encode_both("a face and its reverse", &m);
}

#[test]
fn inconsistent_orientation() {
    let mut m = swm_corpus::icosphere(1.0, 2);
    for t in m.triangles.iter_mut().step_by(3) {
        t.swap(1, 2);
    }
    encode_both("sphere with every third face flipped", &m);
    let mut m = tetrahedron([0.; 3], 1.0);
    m.triangles[0].swap(1, 2);
    encode_both("tetrahedron with one face flipped", &m);
}
