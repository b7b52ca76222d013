use super::*;
use crate::mesh::test_shapes::{coloured_sphere, seamed_cube};
use crate::{AttributeError, Error};

/// Every corner's position and values, face by face: what two meshes
/// must agree on to be the same surface with the same attributes,
/// whatever their indexing.
pub(crate) fn corner_values(m: &AttributedMesh) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    for (f, t) in m.mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let mut c: Vec<u32> = m.mesh.positions[t[k] as usize]
                .iter()
                .map(|x| x.to_bits())
                .collect();
            for s in &m.streams {
                c.extend(
                    s.corner_value(FaceId(f as u32), k)
                        .iter()
                        .map(|x| x.to_bits()),
                );
            }
            out.push(c);
        }
    }
    out
}

#[test]
fn validate_accepts_the_shapes() {
    seamed_cube().validate().unwrap();
    coloured_sphere().validate().unwrap();
    AttributedMesh::from(crate::mesh::test_shapes::unit_cube())
        .validate()
        .unwrap();
}

#[test]
fn validate_names_each_broken_rule() {
    let attribute = |m: AttributedMesh| match m.validate() {
        Err(Error::Attribute(e)) => e,
        other => panic!("{other:?}"),
    };
    let mut m = seamed_cube();
    m.streams[0].dims = 2;
    assert_eq!(attribute(m), AttributeError::Dims { stream: 0, dims: 2 });
    let mut m = seamed_cube();
    m.streams[1].values.pop();
    assert_eq!(
        attribute(m),
        AttributeError::ValueCount {
            stream: 1,
            floats: 47,
            dims: 2
        }
    );
    let mut m = seamed_cube();
    m.streams[1].values[5] = f32::NAN;
    assert_eq!(
        attribute(m),
        AttributeError::NonFinite {
            stream: 1,
            value: 2
        }
    );
    let mut m = seamed_cube();
    m.streams[0].corners.pop();
    assert_eq!(
        attribute(m),
        AttributeError::CornerCount {
            stream: 0,
            triples: 11,
            faces: 12
        }
    );
    let mut m = seamed_cube();
    m.streams[0].corners[3][1] = 6;
    assert_eq!(
        attribute(m),
        AttributeError::IndexOutOfRange {
            stream: 0,
            index: 6,
            values: 6
        }
    );
    let mut m = seamed_cube();
    m.streams[1].kind = AttributeKind::Normal;
    m.streams[1].dims = 3;
    m.streams[1].values.truncate(27);
    assert_eq!(attribute(m), AttributeError::DuplicateKind { stream: 1 });
    let mut m = seamed_cube();
    m.streams[1].kind = AttributeKind::Normal;
    m.streams[1].dims = 1;
    assert_eq!(attribute(m), AttributeError::Dims { stream: 1, dims: 1 });
    let mut m = seamed_cube();
    m.streams.push(m.streams[1].clone());
    assert_eq!(attribute(m), AttributeError::DuplicateKind { stream: 2 });
    // Position errors are the mesh's own.
    let mut m = seamed_cube();
    m.mesh.positions[0][0] = f32::INFINITY;
    assert!(matches!(m.validate(), Err(Error::Format(_))));
}

#[test]
fn split_cube_has_one_vertex_per_distinct_corner() {
    let cube = seamed_cube();
    let split = cube.split_vertices();
    split.validate().unwrap();
    assert!(split.is_split());
    assert!(!cube.is_split());
    // Each of the 6 sides has its own 4 corners (its normal differs from
    // its neighbours'), as a glTF cube does.
    assert_eq!(split.mesh.positions.len(), 24);
    assert_eq!(corner_values(&split), corner_values(&cube));
    // Position order: vertices of position 0 first, and so on.
    let welded = split.weld();
    welded.validate().unwrap();
    assert_eq!(welded.mesh.positions, cube.mesh.positions);
    assert_eq!(welded.mesh.triangles, cube.mesh.triangles);
    assert_eq!(welded.streams[0].value_count(), 6);
    // The cross shares corners between neighbouring squares.
    assert_eq!(welded.streams[1].value_count(), 14);
    assert_eq!(corner_values(&welded), corner_values(&cube));
    // Deterministic.
    assert_eq!(cube.split_vertices(), split);
}

#[test]
fn split_keeps_vertex_order_without_seams_and_unused_positions() {
    let mut sphere = coloured_sphere();
    // An unused position, last: kept, with zero attributes.
    sphere.mesh.positions.push([9.0, 9.0, 9.0]);
    sphere.streams[0].values.extend([0.1, 0.2, 0.3, 0.4]);
    let split = sphere.split_vertices();
    assert_eq!(split.mesh, sphere.mesh);
    let n = sphere.mesh.positions.len();
    assert_eq!(
        &split.streams[0].values[..4 * (n - 1)],
        &sphere.streams[0].values[..4 * (n - 1)]
    );
    assert_eq!(&split.streams[0].values[4 * (n - 1)..], &[0.0; 4]);
}

#[test]
fn split_by_some_streams_leaves_the_others() {
    let cube = seamed_cube();
    let split = cube.split_vertices_by(|s| s.kind == AttributeKind::Normal);
    split.validate().unwrap();
    assert_eq!(split.mesh.positions.len(), 24);
    assert_eq!(split.streams[1], cube.streams[1]);
    assert_eq!(split.streams[0].corners, split.mesh.triangles);
    assert_eq!(corner_values(&split), corner_values(&cube));
    let none = cube.split_vertices_by(|_| false);
    assert_eq!(none, cube);
}

#[test]
fn weld_keeps_signed_zeros_apart_and_drops_nothing() {
    let m = AttributedMesh::new(
        TriMesh::new(
            vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [-0.0, 0.0, 0.0],
                [0.0; 3],
            ],
            vec![[0, 1, 2], [4, 1, 2]],
        ),
        vec![AttributeStream::new(
            AttributeKind::Generic(7),
            1,
            vec![1.0, 1.0, 2.0],
            vec![[0, 1, 2], [1, 1, 2]],
        )],
    );
    let w = m.weld();
    assert_eq!(w.mesh.positions.len(), 4);
    assert_eq!(w.mesh.triangles, [[0, 1, 2], [0, 1, 2]]);
    assert_eq!(w.streams[0].values, [1.0, 2.0]);
    assert_eq!(w.streams[0].corners, [[0, 0, 1], [0, 0, 1]]);
    assert_eq!(corner_values(&w), corner_values(&m));
}

/// Cleaning flips a face back and drops a degenerate and a duplicate one:
/// every kept corner keeps its values, the triples following the face.
#[cfg(feature = "encoder")]
#[test]
fn cleaning_keeps_triples_with_their_faces() {
    use crate::mesh::clean::{clean, clean_attributed, CleanOptions, FaceOrigin};
    let cube = seamed_cube();
    let mut m = cube.clone();
    // Face 3 written the other way round, corners and values alike.
    m.mesh.triangles[3].swap(0, 2);
    for s in &mut m.streams {
        s.corners[3].swap(0, 2);
    }
    // A degenerate face, and a duplicate of face 0, both to be dropped.
    m.mesh.triangles.insert(1, [0, 0, 1]);
    m.mesh.triangles.push([0, 2, 6]);
    for s in &mut m.streams {
        s.corners.insert(1, [0, 0, 0]);
        s.corners.push([0, 0, 0]);
    }
    m.validate().unwrap();
    let (cleaned, streams) = clean_attributed(&m, &CleanOptions::default()).unwrap();
    assert_eq!(cleaned.report.flipped_faces, 1);
    assert_eq!(cleaned.report.degenerate_faces(), 1);
    assert_eq!(cleaned.report.duplicate_faces, 1);
    assert_eq!(
        cleaned.mesh,
        clean(&m.mesh, &CleanOptions::default()).unwrap().mesh
    );
    let out = AttributedMesh::new(cleaned.mesh, streams);
    out.validate().unwrap();
    // The flipped face comes back as (0, 2, 1) of what was written, which
    // is a rotation of the cube's own face: compare corner sets per face.
    let per_face = |m: &AttributedMesh| {
        let c = corner_values(m);
        let mut faces: Vec<Vec<Vec<u32>>> = c
            .chunks(3)
            .map(|f| {
                // Rotate so the smallest corner comes first, keeping the cycle.
                let k = (0..3).min_by_key(|&k| f[k].clone()).unwrap();
                (0..3).map(|j| f[(k + j) % 3].clone()).collect()
            })
            .collect();
        faces.sort();
        faces
    };
    assert_eq!(per_face(&out), per_face(&cube));
    let origin = FaceOrigin {
        face: crate::FaceId(4),
        flipped: true,
    };
    assert_eq!(origin.corners([1, 2, 3]), [1, 3, 2]);
}
