//! The viewer-facing decoding API (issue 9): bounds first, then decoding
//! into caller-provided buffers; normals over the same flat buffers.

mod common;

use swm::{decode_into_with, decoded_len, DecodeOptions, Error, ParameterError};

fn options(sharpen: bool, bend_steps: u32) -> DecodeOptions {
    DecodeOptions {
        sharpen: Some(sharpen),
        bend_steps: Some(bend_steps),
        ..Default::default()
    }
}

/// For every kind of file and post-processing: the buffers sized by
/// `decoded_len` receive exactly what `decode` returns, the counts stay
/// within the bound, and equal it when the bound says it is exact.
#[test]
fn decode_into_matches_decode_within_the_bound() {
    for s in common::samples() {
        for (sharpen, bend) in [(false, 0), (true, 0), (false, 1), (true, 1)] {
            let o = options(sharpen, bend);
            let what = format!("{} sharpen={sharpen} bend={bend}", s.name);
            let bound = decoded_len(&s.bytes, &o).unwrap();
            let mesh = swm::decode(&s.bytes, &o).unwrap();
            let (v, t) = (mesh.positions.len() as u64, mesh.triangles.len() as u64);
            assert!(
                v <= bound.vertices && t <= bound.triangles,
                "{what}: {v} {t} vs {bound:?}"
            );
            if bound.exact {
                assert_eq!((v, t), (bound.vertices, bound.triangles), "{what}");
            }
            // Hole masks and post-processing decide their output from the
            // decoded data; everything else is in the header.
            let plain = !sharpen && bend == 0;
            // (And the loops' fans, which the decoder drops.)
            let header_exact = !matches!(s.name, "swing+HOLE+LOOP" | "swing+ATTR");
            assert_eq!(bound.exact, plain && header_exact, "{what}");

            let mut p = vec![f32::NAN; bound.position_floats() as usize];
            let mut i = vec![u32::MAX; bound.index_count() as usize];
            let got = decode_into_with(&s.bytes, &o, &mut p, &mut i).unwrap();
            assert_eq!((got.vertices, got.triangles), (v, t), "{what}");
            assert!(got.exact);
            assert_eq!(
                &p[..3 * v as usize],
                mesh.positions.as_flattened(),
                "{what}"
            );
            assert_eq!(
                &i[..3 * t as usize],
                mesh.triangles.as_flattened(),
                "{what}"
            );
            // The rest of the buffers is untouched.
            assert!(p[3 * v as usize..].iter().all(|x| x.is_nan()), "{what}");
            assert!(i[3 * t as usize..].iter().all(|&x| x == u32::MAX), "{what}");
        }
    }
}

/// A buffer one element short of the bound is refused before decoding,
/// naming the buffer, and left as it was.
#[test]
fn short_buffers_are_refused_and_untouched() {
    let s = &common::samples()[0];
    let o = DecodeOptions::default();
    let bound = decoded_len(&s.bytes, &o).unwrap();
    let n = bound.position_floats() as usize;
    let m = bound.index_count() as usize;
    for (np, ni, which) in [(n - 1, m, "positions"), (n, m - 1, "indices")] {
        let mut p = vec![7.0; np];
        let mut i = vec![7; ni];
        match decode_into_with(&s.bytes, &o, &mut p, &mut i) {
            Err(Error::Parameter(ParameterError::BufferTooSmall {
                buffer,
                needed,
                given,
            })) => {
                assert_eq!(buffer, which);
                assert_eq!(given + 1, needed);
            }
            other => panic!("{which}: {other:?}"),
        }
        assert!(p.iter().all(|&x| x == 7.0) && i.iter().all(|&x| x == 7));
    }
}

/// Damaged bytes give the same error through every entry point.
#[test]
fn damaged_files_fail_through_every_entry_point() {
    let mut bytes = common::samples()[3].bytes.clone();
    let k = bytes.len() / 2;
    bytes[k] ^= 0x10;
    let o = DecodeOptions::default();
    let want = swm::decode(&bytes, &o).unwrap_err().to_string();
    assert_eq!(decoded_len(&bytes, &o).unwrap_err().to_string(), want);
    let (mut p, mut i) = (vec![0.0; 1 << 16], vec![0; 1 << 16]);
    let got = decode_into_with(&bytes, &o, &mut p, &mut i).unwrap_err();
    assert_eq!(got.to_string(), want);
}

/// Per vertex, whether its angle-weighted face normals add up to a
/// direction rounding cannot turn: at a fold (two faces back to back, as
/// a retiled mesh can have where a loop's fan was dropped) they cancel to
/// a millionth of their sum, and `f32` and `f64` sums point anywhere.
fn well_conditioned(mesh: &swm::TriMesh) -> Vec<bool> {
    let p = |v: u32| mesh.positions[v as usize].map(f64::from);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let norm = |a: [f64; 3]| dot(a, a).sqrt();
    let mut sum = vec![[0.0f64; 3]; mesh.positions.len()];
    let mut total = vec![0.0f64; mesh.positions.len()];
    for t in &mesh.triangles {
        let q = t.map(p);
        let [a, b, c] = q;
        let (u, v) = (sub(b, a), sub(c, a));
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let area = norm(n);
        if area == 0.0 {
            continue;
        }
        for k in 0..3 {
            let (o, e1, e2) = (q[k], q[(k + 1) % 3], q[(k + 2) % 3]);
            let (x, y) = (sub(e1, o), sub(e2, o));
            let angle = (dot(x, y) / (norm(x) * norm(y))).clamp(-1.0, 1.0).acos();
            let s = &mut sum[t[k] as usize];
            for j in 0..3 {
                s[j] += angle * n[j] / area;
            }
            total[t[k] as usize] += angle;
        }
    }
    sum.iter()
        .zip(&total)
        .map(|(s, &w)| norm(*s) > 1e-4 * w)
        .collect()
}

/// Normals over the flat buffers a viewer holds agree with the owned
/// version and are unit length (where the direction is defined beyond
/// rounding: [`well_conditioned`]).
#[test]
fn normals_over_flat_buffers() {
    for s in common::samples() {
        let mesh = swm::decode(&s.bytes, &DecodeOptions::default()).unwrap();
        let owned = swm::vertex_normals(&mesh);
        let mut flat = vec![0.0; 3 * mesh.positions.len()];
        swm::vertex_normals_into(
            mesh.positions.as_flattened(),
            mesh.triangles.as_flattened(),
            &mut flat,
        );
        let conditioned = well_conditioned(&mesh);
        for ((a, b), ok) in flat.chunks_exact(3).zip(&owned).zip(conditioned) {
            let len = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-5, "{}: |n| = {len}", s.name);
            if !ok {
                continue;
            }
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() < 1e-4, "{}: {a:?} vs {b:?}", s.name);
            }
        }
    }
}
