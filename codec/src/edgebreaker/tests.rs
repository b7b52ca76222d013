//! Round trips of the Edgebreaker codec against the input and against the
//! Wrap&Zip reference decoder.

use super::reference::wrap_and_zip;
use super::*;
use crate::{CornerTable, TriMesh};

/// The triangles of `table`, renumbered and reordered as the decoder will
/// produce them.
fn expected(table: &CornerTable, enc: &Encoded) -> Vec<[u32; 3]> {
    let mut new_id = vec![u32::MAX; table.vertex_count()];
    for (k, v) in enc.vertex_order.iter().enumerate() {
        new_id[v.idx()] = k as u32;
    }
    enc.tip_corners
        .iter()
        .map(|&c| [c, c.next(), c.prev()].map(|x| new_id[table.vertex(x).idx()]))
        .collect()
}

fn roundtrip(name: &str, triangles: &[[u32; 3]], vertex_count: usize) -> Encoded {
    let table = CornerTable::new(triangles, vertex_count).unwrap_or_else(|e| panic!("{name}: {e}"));
    let enc = encode(&table).unwrap_or_else(|e| panic!("{name}: {e}"));
    let conn = &enc.connectivity;
    assert_eq!(conn.triangles() as usize, triangles.len(), "{name}");
    let dec = decode(conn).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        dec.triangles(),
        expected(&table, &enc),
        "{name}: decoded triangles differ"
    );
    // Recording the contexts builds the same table, one context per
    // symbol, each in range.
    let (recorded, contexts) = decode_recording(conn).unwrap();
    assert_eq!(recorded.triangles(), dec.triangles(), "{name}");
    assert_eq!(contexts.len(), conn.symbols.len(), "{name}");
    assert!(contexts.iter().all(|&c| (c as usize) < CONTEXTS), "{name}");
    // Recompressing the decoded mesh gives the same symbols, in the
    // decoder's own numbering (identity orders).
    let again = encode(&dec).unwrap();
    assert_eq!(again.connectivity, *conn, "{name}: recompression differs");
    assert!(
        again
            .vertex_order
            .iter()
            .enumerate()
            .all(|(k, v)| v.0 == k as u32),
        "{name}"
    );
    enc
}

fn closed(mesh: &TriMesh) -> (Vec<[u32; 3]>, usize) {
    let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
    let f = fill_holes(&table);
    (f.triangles, f.vertex_count)
}

#[test]
fn genus_zero_matches_the_reference_decoder() {
    for (name, mesh) in [
        ("icosphere", swm_corpus_like::icosphere()),
        ("tetra", swm_corpus_like::tetra()),
    ] {
        let enc = roundtrip(name, &mesh.triangles, mesh.vertex_count());
        let conn = &enc.connectivity;
        assert!(conn.splits.is_empty());
        assert_eq!(conn.components, 1);
        let reference = wrap_and_zip(&conn.symbols);
        assert_eq!(reference, decode(conn).unwrap().triangles(), "{name}");
        // #C = V - 3, #E = #S + 1 for a closed genus-0 component.
        let count = |s| conn.symbols.iter().filter(|&&x| x == s).count();
        assert_eq!(count(Symbol::C), mesh.vertex_count() - 3, "{name}");
        assert_eq!(count(Symbol::E), count(Symbol::S) + 1, "{name}");
    }
}

#[test]
fn handles_holes_and_components() {
    // A torus (one handle), an open grid (one hole, closed by a dummy
    // vertex), and both as two components of one mesh.
    let torus = swm_corpus_like::torus(12, 7);
    let enc = roundtrip("torus", &torus.triangles, torus.vertex_count());
    assert_eq!(
        enc.connectivity.splits.len(),
        2,
        "a handle costs two events"
    );
    let grid = swm_corpus_like::grid(9, 6);
    let (t, n) = closed(&grid);
    roundtrip("grid", &t, n);
    let mut both = torus.clone();
    let off = both.positions.len() as u32;
    both.positions.extend(&grid.positions);
    both.triangles
        .extend(grid.triangles.iter().map(|t| t.map(|v| v + off)));
    let (t, n) = closed(&both);
    let enc = roundtrip("torus+grid", &t, n);
    assert_eq!(enc.connectivity.components, 2);
}

#[test]
fn corrupt_streams_are_errors() {
    let mesh = swm_corpus_like::icosphere();
    let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
    let conn = encode(&table).unwrap().connectivity;
    // Every single-symbol substitution either decodes to a valid closed
    // manifold or is an error; none panics.
    for i in 0..conn.symbols.len() {
        for s in Symbol::ALL {
            let mut bad = conn.clone();
            bad.symbols[i] = s;
            if let Ok(t) = decode(&bad) {
                t.check().unwrap();
            }
        }
    }
    let mut short = conn.clone();
    short.symbols.pop();
    assert!(decode(&short).is_err());
    let mut wrong = conn.clone();
    wrong.vertices += 1;
    assert!(decode(&wrong).is_err());
    let mut comps = conn;
    comps.components = 2;
    assert!(decode(&comps).is_err());
}

/// The decoder skips the fan walk of [`CornerTable::check`], because its
/// gluing makes every vertex one fan by construction (see `finish` in
/// `decode.rs`). Mutated streams with handles, holes and two components
/// test that: each decodes to a table that passes the full check, or is
/// an error. (Debug builds also assert it inside the decoder.)
#[test]
fn mutated_streams_decode_to_valid_tables() {
    let mut bases = Vec::new();
    for m in [
        swm_corpus_like::torus(6, 4),
        swm_corpus_like::torus(9, 5),
        swm_corpus_like::grid(5, 4),
        swm_corpus_like::icosphere(),
    ] {
        let (t, n) = closed(&m);
        let table = CornerTable::new(&t, n).unwrap();
        bases.push(encode(&table).unwrap().connectivity);
    }
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut below = move |n: usize| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x % n as u64) as usize
    };
    let mut decoded = 0;
    for round in 0..20_000 {
        let mut conn = bases[round % bases.len()].clone();
        for _ in 0..1 + below(3) {
            let i = below(conn.symbols.len());
            conn.symbols[i] = Symbol::ALL[below(5)];
        }
        if below(3) == 0 && !conn.splits.is_empty() {
            let j = below(conn.splits.len());
            conn.splits[j].source = conn.splits[j].split + 1 + below(8) as u32;
        }
        if let Ok(table) = decode(&conn) {
            table.check().unwrap();
            decoded += 1;
        }
    }
    assert!(decoded > 500, "only {decoded} mutated streams decoded");
}

/// Small meshes built here, so the codec's unit tests need no other crate.
pub(crate) mod swm_corpus_like {
    use crate::TriMesh;

    pub fn tetra() -> TriMesh {
        TriMesh::new(
            vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        )
    }

    /// An icosahedron subdivided twice (connectivity only matters here):
    /// midpoints in `f32`, not pushed out onto a sphere.
    pub fn icosphere() -> TriMesh {
        let t = (1.0 + 5f32.sqrt()) / 2.0;
        let (p, f) = subdivided(icosahedron(t as f64), 2, |a, b| {
            core::array::from_fn(|k| (a[k] as f32 + b[k] as f32) as f64 / 2.0)
        });
        TriMesh::new(p.iter().map(|q| q.map(|c| c as f32)).collect(), f)
    }

    /// The twelve vertices `(±1, ±t, 0)` and their cyclic permutations,
    /// and the twenty faces, of an icosahedron (a regular one for
    /// `t` the golden ratio).
    pub fn icosahedron(t: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let p = vec![
            [-1., t, 0.],
            [1., t, 0.],
            [-1., -t, 0.],
            [1., -t, 0.],
            [0., -1., t],
            [0., 1., t],
            [0., -1., -t],
            [0., 1., -t],
            [t, 0., -1.],
            [t, 0., 1.],
            [-t, 0., -1.],
            [-t, 0., 1.],
        ];
        let f = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        (p, f)
    }

    /// The six vertices `(±1, 0, 0)`, `(0, ±1, 0)`, `(0, 0, ±1)` and the
    /// eight outward faces of a regular octahedron.
    pub fn octahedron() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let p = vec![
            [1., 0., 0.],
            [-1., 0., 0.],
            [0., 1., 0.],
            [0., -1., 0.],
            [0., 0., 1.],
            [0., 0., -1.],
        ];
        let f = vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        (p, f)
    }

    /// Splits every triangle into four, `levels` times; the vertex on edge
    /// `ab` is `mid(a, b)`, made once per edge.
    pub fn subdivided(
        (mut p, mut f): (Vec<[f64; 3]>, Vec<[u32; 3]>),
        levels: u32,
        mid: impl Fn([f64; 3], [f64; 3]) -> [f64; 3],
    ) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        for _ in 0..levels {
            let mut made = std::collections::HashMap::new();
            let mut next = Vec::with_capacity(4 * f.len());
            for tri in &f {
                let m: [u32; 3] = core::array::from_fn(|k| {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    *made.entry((a.min(b), a.max(b))).or_insert_with(|| {
                        p.push(mid(p[a as usize], p[b as usize]));
                        p.len() as u32 - 1
                    })
                });
                next.extend([
                    [tri[0], m[0], m[2]],
                    [tri[1], m[1], m[0]],
                    [tri[2], m[2], m[1]],
                    m,
                ]);
            }
            f = next;
        }
        (p, f)
    }

    /// A torus grid of n by m quads.
    pub fn torus(n: u32, m: u32) -> TriMesh {
        let mut p = Vec::new();
        for i in 0..n {
            for j in 0..m {
                let tau = std::f32::consts::TAU;
                let (a, b) = (i as f32 / n as f32 * tau, j as f32 / m as f32 * tau);
                let r = 2.0 + 0.5 * b.cos();
                p.push([r * a.cos(), r * a.sin(), 0.5 * b.sin()]);
            }
        }
        let id = |i: u32, j: u32| (i % n) * m + (j % m);
        let mut f = Vec::new();
        for i in 0..n {
            for j in 0..m {
                f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        TriMesh::new(p, f)
    }

    /// An open grid of n by m quads (one boundary loop).
    pub fn grid(n: u32, m: u32) -> TriMesh {
        let mut p = Vec::new();
        for j in 0..=m {
            for i in 0..=n {
                p.push([i as f32, j as f32, 0.0]);
            }
        }
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let mut f = Vec::new();
        for j in 0..m {
            for i in 0..n {
                f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        TriMesh::new(p, f)
    }
}
