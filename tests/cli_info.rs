//! `swm info` against the counts the shared corpus README publishes, and
//! on the generated corpus, whose topology is known by construction.

mod common;
use common::*;

#[test]
fn manifold_corpus_matches_the_readme() {
    let Some(dir) = shared_corpus() else { return };
    for &(file, vertices, faces, components, loops, genus) in MANIFOLD_CORPUS {
        let path = dir.join(file);
        let v = json(&swm(&["info", path.to_str().unwrap(), "--json"]));
        let got = |k: &str| {
            v[k].as_i64()
                .unwrap_or_else(|| panic!("{file}: key {k} missing in {v}"))
        };
        assert_eq!(got("vertices"), vertices as i64, "{file} vertices");
        assert_eq!(got("faces"), faces as i64, "{file} faces");
        assert_eq!(got("components"), components as i64, "{file} components");
        assert_eq!(got("boundary_loops"), loops as i64, "{file} boundary loops");
        assert_eq!(got("genus"), genus, "{file} genus");
        assert_eq!(got("non_manifold_edges"), 0, "{file}");
        assert_eq!(got("non_manifold_vertices"), 0, "{file}");
        assert!(v["bbox_diagonal"].as_f64().unwrap() > 0.0);
        assert!(v["area"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn json_has_exactly_the_documented_keys() {
    let dir = scratch("keys");
    let path = dir.join("torus.obj");
    swm::io::write_mesh(&path, &swm_corpus::torus(1.0, 0.3, 24, 12)).unwrap();
    let v = json(&swm(&["info", path.to_str().unwrap(), "--json"]));
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    keys.sort_unstable();
    let mut want = vec![
        "vertices",
        "faces",
        "components",
        "boundary_loops",
        "genus",
        "non_manifold_edges",
        "non_manifold_vertices",
        "degenerate_faces",
        "bbox_diagonal",
        "area",
    ];
    want.sort_unstable();
    assert_eq!(keys, want);
    assert_eq!(v["genus"], 1);
}

#[test]
fn non_manifold_corpus_loads_and_reports_repairs() {
    let Some(dir) = shared_corpus() else { return };
    for &(file, vertices, faces) in NON_MANIFOLD_CORPUS {
        let path = dir.join(file);
        let p = path.to_str().unwrap();
        let v = json(&swm(&["info", p, "--json"]));
        assert_eq!(v["vertices"], vertices, "{file}");
        assert_eq!(v["faces"], faces, "{file}");
        let nm = v["non_manifold_edges"].as_u64().unwrap()
            + v["non_manifold_vertices"].as_u64().unwrap();
        assert!(nm > 0, "{file}: the README says it is not manifold: {v}");
        let text = swm(&["info", p]);
        assert!(text.status.success());
        let text = String::from_utf8(text.stdout).unwrap();
        assert!(
            text.contains("cleaning:") && text.contains("non-manifold"),
            "{file}: {text}"
        );
    }
    // The README's specific claims.
    let comps = |f: &str| json(&swm(&["info", dir.join(f).to_str().unwrap(), "--json"]));
    assert_eq!(comps("cow.obj")["non_manifold_vertices"], 1);
    assert_eq!(comps("cow.obj")["boundary_loops"], 0, "cow is closed");
    assert_eq!(comps("beetle.obj")["non_manifold_edges"], 47);
    assert_eq!(comps("teapot.obj")["components"], 4);
    assert_eq!(comps("suzanne.obj")["components"], 3);
    assert_eq!(comps("beetle.obj")["components"], 2);
    assert_eq!(comps("cow.obj")["components"], 1);
}

#[test]
fn generated_corpus_has_the_topology_it_was_built_with() {
    let dir = scratch("generated");
    let expected = [
        ("uv-sphere", 0, 0),
        ("icosphere", 0, 0),
        ("torus", 1, 0),
        ("double-torus", 2, 0),
        ("fandisk-like", 0, 0),
        ("cube", 0, 0),
        ("plane-patch", 0, 1),
    ];
    let all = swm_corpus::all();
    for (name, genus, loops) in expected {
        let mesh = &all
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("{name} not generated"))
            .1;
        let path = dir.join(format!("{name}.ply"));
        swm::io::write_mesh(&path, mesh).unwrap();
        let v = json(&swm(&["info", path.to_str().unwrap(), "--json"]));
        assert_eq!(v["genus"], genus, "{name}");
        assert_eq!(v["boundary_loops"], loops, "{name}");
        assert_eq!(v["components"], 1, "{name}");
        assert_eq!(v["vertices"], mesh.vertex_count(), "{name}");
        assert_eq!(v["faces"], mesh.face_count(), "{name}");
        assert_eq!(v["degenerate_faces"], 0, "{name}");
    }
}

/// `b` with its trailing CRC-32 recomputed.
fn fix_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = swm::container::crc32(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

/// Issue 18: `swm info` is as strict as `decode` about the header's
/// counts. Headers that lie about the vertex or triangle count (CRC
/// repaired, so only the counts give them away), in every sample and in
/// the lossless file nested in `REST`, are refused by both with exit 1,
/// and info names the impossible count.
#[test]
fn info_refuses_the_counts_decode_refuses() {
    let dir = scratch("info-lying-counts");
    // Offsets of the vertex count in the fixed header (the file nested in
    // REST below is rewritten in place).
    const VERTICES: usize = 9;
    let mut cases: Vec<(String, Vec<u8>, u32)> = Vec::new();
    for s in samples_in_both_framings() {
        let frame = Frame::of(&s.bytes);
        let (v, t) = (frame.counts[0] as u32, frame.counts[1] as u32);
        for (what, vertices, triangles, quoted) in [
            ("both", 268_435_455, 268_435_455, 268_435_455),
            ("triangles", v, t + 1, t + 1),
            ("vertices", v + 1, t, v + 1),
        ] {
            let mut f = frame.clone();
            f.counts[0] = vertices.into();
            f.counts[1] = triangles.into();
            let b = f.bytes();
            cases.push((format!("{} {what}", s.name), b, quoted));
        }
    }
    // The file nested in REST: its own CRC and the outer one repaired.
    let s = samples_in_both_framings()
        .iter()
        .find(|s| s.name == "swing+REST (fixed framing)")
        .unwrap();
    let s = &common::Sample {
        name: s.name,
        // The nested file in the fixed framing too, so its count sits at
        // a fixed offset.
        bytes: {
            let mut f = Frame::of(&s.bytes);
            let file = swm::container::parse_container(&s.bytes, &Default::default()).unwrap();
            let rest = file.find(swm::container::Tag::REST).unwrap();
            let fixed = common::reframed(rest.bytes, swm::Framing::Fixed);
            let mut payload = Vec::new();
            for (k, sec) in file.sections().enumerate() {
                if sec.tag == swm::container::Tag::REST {
                    payload.extend_from_slice(&fixed);
                    f.entries[k].1 = fixed.len() as u64;
                } else {
                    payload.extend_from_slice(sec.bytes);
                }
            }
            f.payload = payload;
            f.bytes()
        },
    };
    let file = swm::container::parse_container(&s.bytes, &Default::default()).unwrap();
    let rest = file.find(swm::container::Tag::REST).unwrap();
    let (start, len) = (rest.offset, rest.bytes.len());
    let at = start + VERTICES;
    let v = u32::from_le_bytes(s.bytes[at..at + 4].try_into().unwrap());
    let mut b = s.bytes.clone();
    b[at..at + 4].copy_from_slice(&(v - 1).to_le_bytes());
    fix_crc(&mut b[start..start + len]);
    fix_crc(&mut b);
    cases.push(("REST vertices".into(), b, v - 1));

    for (k, (name, bytes, quoted)) in cases.iter().enumerate() {
        assert!(
            swm::decode(bytes, &Default::default()).is_err(),
            "{name}: decode accepts it"
        );
        let path = dir.join(format!("lying-{k}.swm"));
        std::fs::write(&path, bytes).unwrap();
        let p = path.to_str().unwrap();
        for args in [vec!["info", p], vec!["info", p, "--json"]] {
            let out = swm(&args);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{name}: {args:?}\n{err}");
            assert!(out.stdout.is_empty(), "{name}: printed as valid");
            assert_eq!(err.lines().count(), 1, "{name}: {err}");
            assert!(
                err.contains(&format!("declares {quoted} ")),
                "{name}: {err}"
            );
        }
        let out = swm(&["decode", p, "-o", dir.join("out.obj").to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1), "{name}: decode");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
