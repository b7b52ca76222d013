//! Corner-table invariants on every corpus mesh (after cleaning) and every
//! generated mesh: O[O[c]] = c, opposite corners see their edge reversed,
//! one fan per vertex, and a consistent Euler characteristic per component.

mod common;
use common::*;
use swm::{CleanOptions, CornerId, CornerTable, TriMesh};

fn check_table(name: &str, mesh: &TriMesh, table: &CornerTable) {
    table.check().unwrap_or_else(|e| panic!("{name}: {e}"));
    // Spell the two core identities out here too, independently of check().
    for c in 0..table.corner_count() as u32 {
        let c = CornerId(c);
        let o = table.opposite(c);
        if o.is_some() {
            assert_eq!(table.opposite(o), c, "{name}: O[O[c]] != c");
            assert_eq!(table.vertex(o.next()), table.vertex(c.prev()), "{name}");
            assert_eq!(table.vertex(o.prev()), table.vertex(c.next()), "{name}");
        }
    }
    let comps = table.components();
    let mut faces = 0;
    for (i, k) in comps.iter().enumerate() {
        let chi = k.vertices as i64 - k.edges as i64 + k.faces as i64;
        assert_eq!(chi, k.euler, "{name} component {i}");
        assert_eq!(
            chi,
            2 - 2 * k.genus - k.boundary_loops as i64,
            "{name} component {i}"
        );
        assert!(k.genus >= 0, "{name} component {i}: negative genus {k:?}");
        faces += k.faces;
    }
    assert_eq!(faces as usize, mesh.face_count(), "{name}");
    // Every vertex ring closes up (interior) or runs boundary to boundary.
    for v in 0..table.vertex_count() as u32 {
        let v = swm::VertexId(v);
        let ring: Vec<_> = table.ring(v).collect();
        assert!(
            ring.iter().all(|&c| table.vertex(c) == v),
            "{name}: ring of {v} leaves the vertex"
        );
    }
}

#[test]
fn shared_corpus() {
    let Some(dir) = common::shared_corpus() else {
        return;
    };
    let mut names: Vec<&str> = MANIFOLD_CORPUS.iter().map(|m| m.0).collect();
    names.extend(NON_MANIFOLD_CORPUS.iter().map(|m| m.0));
    for name in names {
        let mesh = swm::io::read_mesh(&dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let cleaned =
            swm::clean(&mesh, &CleanOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_table(name, &cleaned.mesh, &cleaned.table);
        // Cleaning is idempotent. (A split vertex shares its position with
        // the original, so the second pass merges and splits it again, but
        // the mesh comes out the same.)
        let again = swm::clean(&cleaned.mesh, &CleanOptions::default()).unwrap();
        assert_eq!(
            again.mesh, cleaned.mesh,
            "{name}: second cleaning changed the mesh"
        );
        assert_eq!(
            again.report.merged_vertices, again.report.split_vertices_added,
            "{name}"
        );
        assert_eq!(
            again.report.flipped_faces + again.report.degenerate_faces(),
            0,
            "{name}"
        );
    }
}

#[test]
fn generated_corpus() {
    for (name, mesh) in swm_corpus::all() {
        let table = CornerTable::new(&mesh.triangles, mesh.vertex_count())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        check_table(name, &mesh, &table);
        let cleaned = swm::clean(&mesh, &CleanOptions::default()).unwrap();
        assert!(cleaned.report.is_clean(), "{name}: {:?}", cleaned.report);
    }
}

#[test]
fn boundary_loops_follow_the_border() {
    let mesh = swm_corpus::plane_patch(8, 5);
    let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
    let loops = table.boundary_loops();
    assert_eq!(loops.len(), 1);
    // A grid of nx by ny quads has 2(nx + ny) border edges, chained end to start.
    assert_eq!(loops[0].len(), 2 * (8 + 5));
    for w in loops[0].windows(2) {
        assert_eq!(table.vertex(w[0].prev()), table.vertex(w[1].next()));
    }
}
