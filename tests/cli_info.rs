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
