//! Bounded valence: no vertex of a piece handed to the retiler has more
//! than [`MAX_VALENCE`] faces around it.
//!
//! The retiler's searches (`walk`, `path`, `snap`, `region`) turn around
//! vertices of M, so every visit of a vertex costs its valence. A
//! fan-triangulated polygon (a CAD export's 100,000-gon, a patch closing a
//! long loop) or a double cone has one vertex in every face, and a
//! retiling run over it becomes quadratic in the input. This step, new in
//! swm (the thesis assumes reasonable input), rebuilds the fan of every
//! such vertex in two ways:
//!
//! 1. **Smooth runs** (at least `MIN_RUN` consecutive fan faces with one
//!    patch label whose normals turn slowly, as a fanned polygon's or a
//!    fine cone's do) are rebuilt as
//!    a mesh graded from the rim inwards (`rebuild_open`): levels that
//!    halve the number of spokes, each about as deep as its spacing. The
//!    fan's n spokes each spanned the polygon, so every path of the
//!    retiler across it crossed all of them; the graded mesh has edges of
//!    total length O(perimeter · log n) and valence O(log n). (Ear
//!    clipping without new vertices was tried first: `earcut` fanned a
//!    2,000-gon from one vertex again, and ears of nearly collinear rim
//!    vertices have meaningless normals, which the retiler inherits.)
//! 2. **Rings**: what is still above the cap (a cone's apex) gets rings
//!    near v that halve the number of vertices at each level:
//!
//! ```text
//!   u_i ──────── u_{i+1}         the fan's ring (kept)
//!    │ ╲            │            level 1: r_i at `OUTER` of the shortest
//!   r_i ──────── r_{i+1}         (v u_i u_{i+1}) → (r_i u_i u_{i+1}),
//!    │    ╲  ╲     │                              (r_i u_{i+1} r_{i+1})
//!   p_j ─────────  p_{j+1}       level k+1 keeps every other edge of
//!    …                           level k: (p a b) (p b c) (p c q)
//!    v                           innermost level: a fan around v
//! ```
//!
//! An open fan (a vertex on a boundary, one chain of faces between two
//! boundary edges) gets its smooth runs rebuilt but no rings; the
//! retiler only sees closed pieces, but the simplifier of the automatic
//! mode (`simplify::Simplifier`) meets a fanned polygon's first vertex
//! open.
//!
//! Invariants:
//! * a mesh without a vertex above the cap passes through unchanged (so
//!   files of ordinary meshes do not change);
//! * the result is a closed oriented manifold when the input was (and
//!   keeps its boundary loops when it was open); every
//!   new face is oriented as the fan it replaces, the input's faces keep
//!   their numbers (a flat run is rewritten in place, face for face, and
//!   each ring-rebuilt fan face becomes its outer strip triangle) and
//!   every new face inherits the patch label of the fan face at its angle;
//! * geometry: a smooth run's new vertices lie on its spokes (in its
//!   plane if it is flat) and its chords stay within about 1e-4 of the
//!   spoke length of the fan (`TURN_SINE`); rings lie exactly in the fan's faces on
//!   the outer strip, and inner levels lie within `OUTER` of the shortest
//!   fan edge around v, where they cut chords across neighbouring
//!   fan faces;
//! * work and memory are linear in the number of corners: each fan is
//!   rebuilt once from a vertex-to-face incidence list.

use crate::TriMesh;
use glam::DVec3;

/// Largest valence left as it is. Ordinary meshes, scans and CAD parts
/// stay far below it, and so do the centres of the patches closing holes
/// of up to 256 boundary edges (the generated plane patch's is 224), so
/// their files do not change; a rebuilt fan ends with at most
/// `INNER_SPOKES` spokes at its vertex and valence about 40 around it.
pub const MAX_VALENCE: usize = 256;
/// Spokes left at a rebuilt vertex: levels halve until this many remain.
const INNER_SPOKES: usize = 32;
/// Share of the shortest fan edge, from the centre, where the first ring
/// sits. Below 1/2, so two neighbouring capped vertices never meet on an
/// edge.
const OUTER: f64 = 0.25;

/// Caps every vertex's valence at [`MAX_VALENCE`]; `label` holds one value
/// per face (the patch numbers) and is extended for new faces. Returns the
/// number of vertices whose fans were rebuilt.
pub fn cap(mesh: &mut TriMesh, label: &mut Vec<u32>) -> usize {
    let valence = valences(mesh);
    let high: Vec<u32> = (0..valence.len() as u32)
        .filter(|&x| valence[x as usize] as usize > MAX_VALENCE)
        .collect();
    if high.is_empty() {
        return 0;
    }
    let mut faces_at: Vec<Vec<u32>> = valence
        .iter()
        .map(|&n| Vec::with_capacity(n as usize))
        .collect();
    for (f, t) in mesh.triangles.iter().enumerate() {
        for &x in t {
            faces_at[x as usize].push(f as u32);
        }
    }
    let mut done = 0;
    for v in high {
        let Some((mut fan, closed)) = ordered_fan(mesh, v, &faces_at[v as usize]) else {
            continue; // not one fan: leave it to the retiler
        };
        if !closed {
            // One open fan (v on a boundary, as a fanned polygon's first
            // vertex before its hole is closed): its smooth runs only,
            // no rings (they need a closed fan).
            if flatten_runs(mesh, label, &mut faces_at, v, &fan, false) {
                done += 1;
            }
            continue;
        }
        if flatten_runs(mesh, label, &mut faces_at, v, &fan, true) {
            match ordered_fan(mesh, v, &faces_at[v as usize]) {
                Some((f, true)) => fan = f,
                _ => continue,
            }
        }
        // Once rebuilt, a vertex ends with few spokes: what the smooth runs
        // left gets rings too.
        if fan.len() > 2 * INNER_SPOKES {
            rebuild(mesh, label, &mut faces_at, v, &fan);
        }
        done += 1;
    }
    done
}

/// The faces around `v` in counterclockwise order, as (face, u_i, u_{i+1})
/// with face = (v, u_i, u_{i+1}) up to rotation, and whether they close
/// around `v`; `None` unless they form exactly one fan: a cycle (started
/// at its lowest face), or one chain between two boundary edges (started
/// at the face whose first spoke no other face ends on). `faces` may list
/// faces that no longer hold `v`.
#[allow(clippy::type_complexity)]
fn ordered_fan(mesh: &TriMesh, v: u32, faces: &[u32]) -> Option<(Vec<(u32, u32, u32)>, bool)> {
    let mut by_first = std::collections::HashMap::with_capacity(faces.len());
    let mut seconds = std::collections::HashSet::with_capacity(faces.len());
    for &f in faces {
        let t = mesh.triangles[f as usize];
        let Some(k) = t.iter().position(|&x| x == v) else {
            continue;
        };
        let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
        if by_first.insert(a, (f, a, b)).is_some() {
            return None;
        }
        seconds.insert(b);
    }
    let count = by_first.len();
    let mut starts = by_first.keys().filter(|a| !seconds.contains(a));
    let (first, closed) = match starts.next() {
        // Some spoke starts a face and ends none: an open chain, which
        // has exactly one such spoke and no spoke ending two faces.
        Some(a) if starts.next().is_none() && seconds.len() == count => (by_first[a], false),
        Some(_) => return None,
        None => (*by_first.values().min_by_key(|e| e.0)?, true),
    };
    let mut fan = Vec::with_capacity(count);
    let mut at = first;
    loop {
        fan.push(at);
        match by_first.get(&at.2) {
            Some(&next) if closed && next == first => break,
            Some(&next) => at = next,
            None if !closed => break,
            None => return None,
        }
        if fan.len() > count {
            return None;
        }
    }
    (fan.len() == count).then_some((fan, closed))
}

/// Faces around each vertex.
fn valences(mesh: &TriMesh) -> Vec<u32> {
    let mut valence = vec![0u32; mesh.vertex_count()];
    for t in &mesh.triangles {
        for &x in t {
            valence[x as usize] += 1;
        }
    }
    valence
}

/// The largest number of faces around one vertex of `mesh`.
pub fn max_valence(mesh: &TriMesh) -> usize {
    valences(mesh).into_iter().max().unwrap_or(0) as usize
}

/// Neighbouring faces of a smooth run turn by less than this sine (about
/// 1.1 degrees): a fanned polygon's faces do not turn at all, a cone of
/// 20,000 faces by 0.02 degrees, a coarse shape's edge by much more.
const STEP_SINE: f64 = 0.02;
/// No face of a smooth run turns from the run's mean normal by more than
/// this sine (about 14 degrees). The graded rebuild cuts chords across
/// fan faces; with the innermost level's 32 chords spanning at most 1/32
/// of this turn each, they stay within about 1e-4 of the spoke length of
/// the surface.
const TURN_SINE: f64 = 0.25;
/// Fewest faces in a smooth run worth rebuilding.
const MIN_RUN: usize = 64;

/// Rebuilds the long smooth runs of the fan of `v` as graded meshes
/// (`closed`: the fan goes all around `v`; otherwise it is one chain
/// between two boundary edges, and runs do not wrap); returns whether any
/// run changed.
fn flatten_runs(
    mesh: &mut TriMesh,
    label: &mut Vec<u32>,
    faces_at: &mut [Vec<u32>],
    v: u32,
    fan: &[(u32, u32, u32)],
    closed: bool,
) -> bool {
    let d = fan.len();
    let cross: Vec<DVec3> = fan
        .iter()
        .map(|&(f, _, _)| mesh.face_cross(crate::FaceId(f)))
        .collect();
    let lab = |i: usize| label[fan[i].0 as usize];
    let breaks = |i: usize, j: usize| {
        let (a, b) = (cross[i].normalize_or_zero(), cross[j].normalize_or_zero());
        a == DVec3::ZERO || a.dot(b) <= 0.0 || a.cross(b).length() >= STEP_SINE || lab(i) != lab(j)
    };
    // Start after a break, so that no run is cut by the fan's seam; a fan
    // flat all around keeps its last face out.
    let start = if closed {
        (0..d).find(|&i| breaks((i + d - 1) % d, i)).unwrap_or(0)
    } else {
        0
    };
    let mut runs = Vec::new();
    let mut i = 0;
    while i < d {
        let first = (start + i) % d;
        let mut sum = cross[first].normalize_or_zero();
        let mut k = 1;
        while i + k < d && (k + 1 < d || !closed) {
            let j = (first + k) % d;
            let n = sum.normalize_or_zero();
            let c = cross[j].normalize_or_zero();
            let turned = n.dot(c) <= 0.0 || n.cross(c).length() >= TURN_SINE;
            if c == DVec3::ZERO || turned || breaks((j + d - 1) % d, j) {
                break;
            }
            sum += c;
            k += 1;
        }
        if k >= MIN_RUN {
            runs.push((0..k).map(|j| fan[(first + j) % d]).collect::<Vec<_>>());
        }
        i += k;
    }
    for run in &runs {
        rebuild_open(mesh, label, faces_at, v, run);
    }
    !runs.is_empty()
}

/// Replaces one smooth run of fan faces (v u_i u_{i+1}), i = 0..k, by a mesh
/// graded from the rim u_0 … u_k inwards: level 1 sits just inside the rim
/// on the interior spokes u_1 … u_{k−1}, each next level keeps every other
/// spoke (always the first and the last), and the radial step follows the
/// level's spacing, so its triangles are about as deep as they are wide.
/// The two boundary spokes v u_0 and v u_k stay edges (the faces beyond
/// them are not touched); the strips along them are fans at u_0 and u_k.
///
/// ```text
///   u_0 ── u_1 ── u_2 ── … ── u_k     rim (kept)
///    │ ╲   P_1 ── r ── … ── Q_1 ╱ │   level 1 on interior spokes
///    │   ╲ P_2 ──────── Q_2   ╱   │   level 2: every other spoke
///    │     ╲  …          … ╱      │
///    v ─────────────────────────  v   innermost level: a fan at v
/// ```
fn rebuild_open(
    mesh: &mut TriMesh,
    label: &mut Vec<u32>,
    faces_at: &mut [Vec<u32>],
    v: u32,
    run: &[(u32, u32, u32)],
) {
    let k = run.len();
    let lab = label[run[0].0 as usize];
    let centre = mesh.point(crate::VertexId(v));
    let rim: Vec<u32> = run
        .iter()
        .map(|&(_, a, _)| a)
        .chain([run[k - 1].2])
        .collect();
    let dir: Vec<DVec3> = rim
        .iter()
        .map(|&u| mesh.point(crate::VertexId(u)) - centre)
        .collect();
    let turn: f64 = (0..k).map(|i| dir[i].angle_between(dir[i + 1])).sum();
    let add = |mesh: &mut TriMesh, p: DVec3| {
        mesh.positions.push(p.as_vec3().to_array());
        mesh.positions.len() as u32 - 1
    };
    let mut faces: Vec<[u32; 3]> = Vec::new();
    // Spoke index (into `rim`) of each vertex of the current level.
    let mut spoke: Vec<usize> = (1..k).collect();
    let mut fraction = 1.0 - (turn / (2.0 * k as f64)).min(0.5);
    let mut ring: Vec<u32> = spoke
        .iter()
        .map(|&i| add(mesh, centre + dir[i] * fraction))
        .collect();
    let (mut first_chain, mut last_chain) = (vec![ring[0]], vec![ring[ring.len() - 1]]);
    // The outer strip.
    faces.push([ring[0], rim[0], rim[1]]);
    for i in 1..k - 1 {
        faces.push([ring[i - 1], rim[i], rim[i + 1]]);
        faces.push([ring[i - 1], rim[i + 1], ring[i]]);
    }
    faces.push([ring[k - 2], rim[k - 1], rim[k]]);
    while ring.len() > INNER_SPOKES {
        let n = ring.len();
        let mut kept: Vec<usize> = (0..n).step_by(2).collect();
        if kept[kept.len() - 1] != n - 1 {
            kept.push(n - 1);
        }
        let m = kept.len();
        fraction *= 1.0 - (turn / (2.0 * m as f64)).min(0.5);
        let inner: Vec<u32> = kept
            .iter()
            .map(|&j| add(mesh, centre + dir[spoke[j]] * fraction))
            .collect();
        for g in 0..m - 1 {
            let (s, e) = (kept[g], kept[g + 1]);
            let (p, q) = (inner[g], inner[g + 1]);
            for t in s..e {
                faces.push([p, ring[t], ring[t + 1]]);
            }
            faces.push([p, ring[e], q]);
        }
        first_chain.push(inner[0]);
        last_chain.push(inner[m - 1]);
        spoke = kept.iter().map(|&j| spoke[j]).collect();
        ring = inner;
    }
    for j in 0..ring.len() - 1 {
        faces.push([v, ring[j], ring[j + 1]]);
    }
    // The strips along the boundary spokes: fans at u_0 and u_k.
    for w in first_chain.windows(2) {
        faces.push([rim[0], w[0], w[1]]);
    }
    faces.push([rim[0], first_chain[first_chain.len() - 1], v]);
    for w in last_chain.windows(2) {
        faces.push([rim[k], w[1], w[0]]);
    }
    faces.push([rim[k], v, last_chain[last_chain.len() - 1]]);
    // Run faces are rewritten in place, the rest appended.
    let old: Vec<u32> = run.iter().map(|&(f, _, _)| f).collect();
    let mut ids = Vec::with_capacity(faces.len());
    for (j, t) in faces.into_iter().enumerate() {
        let f = if j < k {
            mesh.triangles[old[j] as usize] = t;
            old[j]
        } else {
            mesh.triangles.push(t);
            label.push(lab);
            mesh.triangles.len() as u32 - 1
        };
        ids.push(f);
    }
    let old: std::collections::HashSet<u32> = old.into_iter().collect();
    // Vertices made by an earlier rebuild (they can be on this fan's rim)
    // have no list: they are never capped.
    for &x in rim.iter().chain([&v]) {
        if let Some(list) = faces_at.get_mut(x as usize) {
            list.retain(|f| !old.contains(f));
        }
    }
    for &f in &ids {
        for x in mesh.triangles[f as usize] {
            if (x as usize) < faces_at.len() {
                faces_at[x as usize].push(f);
            }
        }
    }
}

/// Replaces the fan of `v` (valence d = fan.len()) by halving rings.
fn rebuild(
    mesh: &mut TriMesh,
    label: &mut Vec<u32>,
    faces_at: &mut [Vec<u32>],
    v: u32,
    fan: &[(u32, u32, u32)],
) {
    let d = fan.len();
    let centre = mesh.point(crate::VertexId(v));
    let point = |mesh: &TriMesh, u: u32| mesh.point(crate::VertexId(u));
    // The direction and length of each fan edge v → u_i.
    let spokes: Vec<DVec3> = fan
        .iter()
        .map(|&(_, a, _)| point(mesh, a) - centre)
        .collect();
    let add_vertex = |mesh: &mut TriMesh, p: DVec3| {
        mesh.positions.push(p.as_vec3().to_array());
        mesh.positions.len() as u32 - 1
    };
    let push = |mesh: &mut TriMesh, label: &mut Vec<u32>, t: [u32; 3], lab: u32| {
        mesh.triangles.push(t);
        label.push(lab);
    };
    // Level 1 on every edge; each fan face keeps its number as the outer
    // strip triangle (r_i u_i u_{i+1}).
    // Rings at one distance from v along every spoke (a share of the
    // shortest): spokes of different lengths in nearly one direction
    // (after a smooth run was rebuilt) would otherwise zigzag.
    let shortest = spokes
        .iter()
        .map(|s| s.length())
        .fold(f64::INFINITY, f64::min);
    let unit: Vec<DVec3> = spokes.iter().map(|s| s.normalize_or_zero()).collect();
    let mut radius = OUTER * shortest;
    let mut ring: Vec<u32> = unit
        .iter()
        .map(|&s| add_vertex(mesh, centre + s * radius))
        .collect();
    // Edge index (into the fan) of each vertex of the current ring.
    let mut edge: Vec<usize> = (0..d).collect();
    let labels: Vec<u32> = fan.iter().map(|&(f, _, _)| label[f as usize]).collect();
    for (i, &(f, a, b)) in fan.iter().enumerate() {
        let (r, rn) = (ring[i], ring[(i + 1) % d]);
        mesh.triangles[f as usize] = [r, a, b];
        push(mesh, label, [r, b, rn], labels[i]);
        let g = mesh.face_count() as u32 - 1;
        // Vertices made by a graded run have no list: never capped.
        if let Some(list) = faces_at.get_mut(b as usize) {
            list.push(g);
        }
    }
    // Inner levels, each keeping every other edge of the one outside it;
    // the radial step follows the ring's spacing, so triangles stay
    // roughly as wide as they are deep.
    while ring.len() > INNER_SPOKES {
        let n = ring.len();
        let m = n / 2;
        radius *= 1.0 - (std::f64::consts::PI / m as f64).min(0.5);
        let inner: Vec<u32> = (0..m)
            .map(|j| add_vertex(mesh, centre + unit[edge[2 * j]] * radius))
            .collect();
        for j in 0..m {
            let p = inner[j];
            let q = inner[(j + 1) % m];
            // The last group takes three outer edges when n is odd.
            let end = if j + 1 == m { n } else { 2 * j + 2 };
            for k in 2 * j..end {
                push(
                    mesh,
                    label,
                    [p, ring[k], ring[(k + 1) % n]],
                    labels[edge[k]],
                );
            }
            push(mesh, label, [p, ring[end % n], q], labels[edge[2 * j]]);
        }
        edge = (0..m).map(|j| edge[2 * j]).collect();
        ring = inner;
    }
    let n = ring.len();
    for k in 0..n {
        push(
            mesh,
            label,
            [v, ring[k], ring[(k + 1) % n]],
            labels[edge[k]],
        );
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::CornerTable;

    /// `n` points on the unit circle, at height `wave`·sin 7a.
    pub(in crate::swing::retile) fn circle(n: u32, wave: f32) -> Vec<[f32; 3]> {
        (0..n)
            .map(|i| {
                let a = std::f32::consts::TAU * i as f32 / n as f32;
                [a.cos(), a.sin(), wave * (7.0 * a).sin()]
            })
            .collect()
    }

    /// The n-gon on [`circle`], fanned from its vertex 0 as the mesh
    /// readers triangulate a polygon face.
    pub(in crate::swing::retile) fn fanned_polygon(n: u32, wave: f32) -> TriMesh {
        let triangles = (1..n - 1).map(|i| [0, i, i + 1]).collect();
        TriMesh::new(circle(n, wave), triangles)
    }

    /// A closed double cone: apexes 0 and 1 over a ring of `n` vertices.
    fn double_fan(n: u32) -> TriMesh {
        let mut positions = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
        positions.extend(circle(n, 0.0));
        let mut triangles = Vec::new();
        for i in 0..n {
            let (p, q) = (2 + i, 2 + (i + 1) % n);
            triangles.push([0, p, q]);
            triangles.push([1, q, p]);
        }
        TriMesh::new(positions, triangles)
    }

    #[test]
    fn an_ordinary_mesh_is_unchanged() {
        let mut m = double_fan(256);
        let before = m.clone();
        let mut label = vec![7; m.face_count()];
        assert_eq!(cap(&mut m, &mut label), 0);
        assert_eq!(m, before);
    }

    #[test]
    fn a_double_fan_becomes_a_closed_manifold_of_bounded_valence() {
        for n in [257, 333, 1000, 20_000] {
            let mut m = double_fan(n);
            let area = m.area();
            let mut label: Vec<u32> = (0..m.face_count() as u32).map(|f| f % 2).collect();
            assert_eq!(cap(&mut m, &mut label), 2, "n = {n}");
            assert_eq!(label.len(), m.face_count());
            assert!(max_valence(&m) <= 64, "n = {n}: {}", max_valence(&m));
            let table = CornerTable::new(&m.triangles, m.vertex_count()).unwrap();
            assert!(
                table.opposites().iter().all(|o| o.is_some()),
                "n = {n}: open"
            );
            let (v, f) = (m.vertex_count() as i64, m.face_count() as i64);
            assert_eq!(v - 3 * f / 2 + f, 2, "n = {n}: not a sphere");
            // Orientation kept: every face's normal points away from the axis.
            for t in &m.triangles {
                let [a, b, c] = t.map(|x| DVec3::from(m.positions[x as usize].map(f64::from)));
                let mid = (a + b + c) / 3.0;
                let out = DVec3::new(mid.x, mid.y, 0.0) + DVec3::Z * mid.z.signum() * 1e-9;
                assert!(
                    (b - a).cross(c - a).dot(out) >= 0.0,
                    "n = {n}: a face turned inside out: {t:?} {a} {b} {c}"
                );
            }
            // Chords across a smooth cone barely change its area.
            assert!((m.area() - area).abs() < 1e-3 * area, "n = {n}");
        }
    }

    #[test]
    fn an_open_fan_is_rebuilt_in_place_with_its_boundary_kept() {
        // A fanned polygon as the reader gives it, before any hole patch:
        // vertex 0 is on the boundary, its fan one open chain.
        let mut m = fanned_polygon(5000, 0.0);
        let area = m.area();
        let mut label = vec![0u32; m.face_count()];
        assert_eq!(cap(&mut m, &mut label), 1);
        assert!(max_valence(&m) <= 64, "{}", max_valence(&m));
        assert!((m.area() - area).abs() < 1e-9 * area);
        let table = CornerTable::new(&m.triangles, m.vertex_count()).unwrap();
        let loops = table.boundary_loops();
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 5000, "the boundary is the polygon's");
        // Flat and facing +z, as the fan did (up to the f32 rounding of
        // needles along the boundary spokes, which were needles before).
        for t in &m.triangles {
            let [a, b, c] = t.map(|x| DVec3::from(m.positions[x as usize].map(f64::from)));
            assert!(a.z == 0.0 && b.z == 0.0 && c.z == 0.0);
            assert!((b - a).cross(c - a).z > -1e-9, "{t:?} {a} {b} {c}");
        }
    }

    #[test]
    fn a_flat_fan_keeps_its_shape_and_labels() {
        // A polygon fanned from its centre (vertex n) and closed by a cone
        // under it (apex n + 1); top faces labelled 0, the cone 1.
        let n = 500u32;
        let mut positions = circle(n, 0.0);
        positions.push([0.0, 0.0, 0.0]);
        positions.push([0.0, 0.0, -0.5]);
        let mut triangles = Vec::new();
        for i in 0..n {
            triangles.push([n, i, (i + 1) % n]);
        }
        for i in 0..n {
            triangles.push([n + 1, (i + 1) % n, i]);
        }
        let mut m = TriMesh::new(positions, triangles);
        let top_area: f64 = (0..n)
            .map(|f| m.face_cross(crate::FaceId(f)).length() / 2.0)
            .sum();
        let mut label: Vec<u32> = (0..m.face_count() as u32)
            .map(|f| u32::from(f >= n))
            .collect();
        assert_eq!(cap(&mut m, &mut label), 2);
        assert!(max_valence(&m) <= 64);
        let mut area = 0.0;
        for (f, t) in m.triangles.iter().enumerate() {
            let flat = t.iter().all(|&x| m.positions[x as usize][2] == 0.0);
            assert_eq!(label[f] == 0, flat, "face {f}");
            if flat {
                area += m.face_cross(crate::FaceId(f as u32)).length() / 2.0;
            }
        }
        assert!(
            (area - top_area).abs() < 1e-5 * top_area,
            "{area} vs {top_area}"
        );
    }

    #[test]
    fn a_fanned_polygon_is_rebuilt_with_short_edges() {
        // An n-gon fanned from its vertex 0 (a reader's triangulation),
        // closed by a cone under it.
        let n = 2000u32;
        let mut m = fanned_polygon(n, 0.0);
        m.positions.push([0.0, 0.0, -0.5]);
        for i in 0..n {
            m.triangles.push([n, (i + 1) % n, i]);
        }
        let polygon = n as usize - 2;
        let area = |m: &TriMesh, f: usize| m.face_cross(crate::FaceId(f as u32)).length() / 2.0;
        let before: f64 = (0..polygon).map(|f| area(&m, f)).sum();
        let mut label: Vec<u32> = (0..m.face_count())
            .map(|f| u32::from(f >= polygon))
            .collect();
        assert_eq!(cap(&mut m, &mut label), 2);
        assert!(max_valence(&m) <= 64, "{}", max_valence(&m));
        let table = CornerTable::new(&m.triangles, m.vertex_count()).unwrap();
        assert!(table.opposites().iter().all(|o| o.is_some()));
        let (v, f) = (m.vertex_count() as i64, m.face_count() as i64);
        assert_eq!(v - 3 * f / 2 + f, 2, "not a sphere");
        // The polygon's faces: in its plane, facing up, same area, and
        // edges of total length a few perimeters, where the fan's spokes
        // alone were about n·(4/π) long.
        let (mut after, mut length, mut signed) = (0.0, 0.0, 0.0);
        for (f, t) in m.triangles.iter().enumerate() {
            if label[f] != 0 {
                continue;
            }
            assert!(
                t.iter().all(|&x| m.positions[x as usize][2] == 0.0),
                "face {f} left the plane"
            );
            // Needles next to v (its neighbours' spokes are nearly
            // parallel, as in the input's own fan) may round either way
            // in f32; any larger face must face up.
            let z = m.face_cross(crate::FaceId(f as u32)).z;
            assert!(z > -1e-9, "face {f} turned over: {z}");
            signed += z / 2.0;
            after += area(&m, f);
            for k in 0..3 {
                let [a, b] = [t[k], t[(k + 1) % 3]].map(|x| m.point(crate::VertexId(x)));
                length += a.distance(b) / 2.0;
            }
        }
        assert!(
            (after - before).abs() < 1e-5 * before,
            "{after} vs {before}"
        );
        assert!(
            (signed - before).abs() < 1e-5 * before,
            "folded: {signed} vs {before}"
        );
        let perimeter = std::f64::consts::TAU;
        assert!(length < 40.0 * perimeter, "{length}");
        assert!(length < (n as f64) / 10.0, "{length}");
    }
}
