//! Tips on creases (issue 21, "retiling that respects creases"; beyond
//! the thesis): where a gate's bisecting plane crosses a sharp edge of M
//! near the circle, the C tip sits on the crossing, off the circle by a
//! radius code (`swing::stretch`, `RADS`).
//!
//! Uniform retiling puts every tip at distance r from its gate's
//! midpoint, so a crease of M is crossed by retiled edges at a slant and
//! comes out chamfered: the error EdgeSharpener can only partly undo.
//! The crease crosses the tip's plane at one point P; with P as the tip,
//!
//! ```text
//!      crease  ──P1──────P2──────P3──     tips on the crease: edges
//!               / \     / \     /         P1-P2, P2-P3 lie along it
//!              /   \   /   \   /
//!            GR1───GR2────GR3             the front arriving at it
//! ```
//!
//! the next gate (P1, GR) has its own plane crossing the crease about
//! one edge further on, so once the front reaches a crease the growth
//! lays a row of tips along it by itself, and the triangles on either
//! side stay each on their own face of the crease.
//!
//! The search walks the plane's intersection with M from the gate's own
//! crossing, both ways, as `circle` does, and takes the crease crossing
//! on the tip's side (within [`MAX_TURN`] of the circle's tip, seen from
//! the midpoint) whose distance from the midpoint is nearest r, within
//! [`NEAR`]·r … [`FAR`]·r (inside the format's 0 … 2r, so the radius code
//! rounds to a representable one). A crease is an edge of M whose two
//! faces' normals are more than [`CREASE_ANGLE`] apart (faces made by
//! splits keep their parent's normal, so splits add none).
//!
//! Measured (BENCHMARKS.md, "Tips on creases"): fandisk at L = 0.1, K = 8,
//! tips on the surface, L2 after the hint 2.55 → 1.38 (× 1e-4 of the
//! diagonal) for 19% more bytes, 57% of the crease length then covered by
//! retiled edges. What it cannot do: a gate that runs along a crease a
//! little beside it, or straddles it, has no crease point in its plane
//! near the circle, and its triangle still crosses the crease (the
//! zigzags that remain). Tried and dropped: a second code shifting such a
//! tip along its gate, onto the crease followed ahead of the gate; on
//! fandisk no such tip was usable (the crease ahead ran into claimed
//! faces or lay a whole r along the gate), and the code cost bytes.
//! Landing as near as 0.05·r (slivers between a row and the crease), or
//! only within 0.6-1.4·r and 45° of the circle's tip, measured worse.
//!
//! Invariants: the crossing lies on an edge of M that is not a path, with
//! an unclaimed face beside it (the tip must anchor a new triangloid);
//! the walk is bounded like `circle`'s; the tip's code and radius come
//! from the decoder's own frame arithmetic (`swing::Frame`), so the
//! retiled positions are what the decoder rebuilds.

use super::state::Retiler;
use super::surface::{face, NONE};
use super::walk::{Plane, Walker};
use glam::DVec3;

/// Dihedral turn (degrees) above which an edge of M is a crease.
pub(super) const CREASE_ANGLE: f64 = 45.0;
/// Nearest a crease tip may be to its gate's midpoint, in r.
pub(super) const NEAR: f64 = 0.3;
/// Farthest a crease tip may be from its gate's midpoint, in r.
pub(super) const FAR: f64 = 1.7;
/// Largest angle (degrees) between the crease tip and the circle's tip
/// as seen from the midpoint: a crossing far around the circle would
/// turn the triangle.
const MAX_TURN: f64 = 90.0;

impl Retiler<'_> {
    /// Whether the edge facing corner `c` of M is a crease.
    fn is_crease(&self, c: u32) -> bool {
        let s = &self.s;
        let o = s.opp[c as usize];
        let cos = s.normal(face(c)).dot(s.normal(face(o)));
        cos < CREASE_ANGLE.to_radians().cos()
    }

    /// The crease crossing of `plane` nearest the circle of the gate with
    /// midpoint `centre`, on the side of the circle's tip `v`: the point
    /// and an unclaimed face holding it. `crossing` is the corner facing
    /// the edge where the gate's path crosses the plane, and that point.
    pub(super) fn crease_tip(
        &self,
        plane: Plane,
        centre: DVec3,
        crossing: (u32, DVec3),
        v: DVec3,
    ) -> Option<(DVec3, u32)> {
        let s = &self.s;
        let r = self.radius;
        let (near, far) = (NEAR * r, FAR * r);
        let toward = (v - centre).normalize_or_zero();
        let min_cos = MAX_TURN.to_radians().cos();
        let (c, start) = crossing;
        let mut best: Option<(f64, DVec3, u32)> = None;
        for side in [c, s.opp[c as usize]] {
            let mut walker = Walker::across(s, plane, side, s.face_count());
            let mut length = 0.0;
            let mut from = start;
            while let Some(step) = walker.step() {
                let p = step.point;
                length += from.distance(p);
                from = p;
                let d = p.distance(centre);
                if d > far || length > 2.0 * far {
                    break;
                }
                if d < near || !self.is_crease(step.corner) || s.path[step.corner as usize] {
                    continue;
                }
                if (p - centre).dot(toward) < min_cos * d {
                    continue;
                }
                let o = s.opp[step.corner as usize];
                let f = [face(step.corner), face(o)]
                    .into_iter()
                    .find(|&f| s.owner[f as usize] == NONE);
                let Some(f) = f else { continue };
                let miss = (d - r).abs();
                if best.is_none_or(|(m, _, _)| miss < m) {
                    best = Some((miss, p, f));
                }
            }
        }
        best.map(|(_, p, f)| (p, f))
    }
}

/// Total length of the creases of the input's components `pieces`
/// (edges between two of its own faces, not a hole's patch, whose normals
/// turn by more than [`CREASE_ANGLE`]), read off the pieces' corner
/// tables; the encoder tries tips on creases only where this reaches the
/// bounding-box diagonal (`crate::hinted`: with fewer, the tips cannot
/// change the error measurably and the trial would only cost time).
pub(crate) fn crease_length(pieces: &[super::fill::Piece]) -> f64 {
    let cos = CREASE_ANGLE.to_radians().cos();
    let mut total = 0.0;
    for piece in pieces {
        let (mesh, table) = (&piece.mesh, &piece.table);
        let p = |v: crate::VertexId| DVec3::from_array(mesh.positions[v.idx()].map(f64::from));
        let normals: Vec<DVec3> = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] =
                    t.map(|v| DVec3::from_array(mesh.positions[v as usize].map(f64::from)));
                (b - a).cross(c - a).normalize_or_zero()
            })
            .collect();
        let own = |f: crate::FaceId| piece.patch[f.idx()] == NONE;
        for c in (0..table.corner_count() as u32).map(crate::CornerId) {
            let o = table.opposite(c);
            // Each edge once, from its lower corner.
            if o.is_none() || o.0 < c.0 {
                continue;
            }
            let (f, g) = (c.face(), o.face());
            if own(f) && own(g) && normals[f.idx()].dot(normals[g.idx()]) < cos {
                total += p(table.vertex(c.next())).distance(p(table.vertex(c.prev())));
            }
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::bend::tests::cube;
    use crate::swing::retile::{RetileOptions, Retiled};
    use crate::{CornerTable, TriMesh};

    fn retiled_box(creases: bool) -> Retiled {
        let mesh = cube(8).0;
        let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
        let opt = RetileOptions {
            edge_length: 0.3,
            angle_bits: 8,
            start_vertex: None,
            start_rank: 0,
            start_by_shape: false,
            approximate_tips: false,
            fit_tips: false,
            adaptive_density: false,
            last_resort: false,
            loop_start: false,
            crease_tips: creases,
        };
        crate::swing::retile::tests::retile(&mesh, &table, &opt).unwrap()
    }

    /// Vertices within 1% of L of an edge of the box (two coordinates at
    /// ±1), and the mean distance of the vertices' positions to the box.
    fn on_edges(r: &Retiled) -> (usize, f64) {
        let off = |c: f64| (c.abs() - 1.0).abs();
        let on = r
            .positions
            .iter()
            .filter(|p| p.iter().filter(|&&c| off(c) < 0.003).count() >= 2)
            .count();
        // Distance of the triangle centroids to the box surface.
        let mut sum = 0.0;
        for t in &r.triangles {
            let c: [f64; 3] = std::array::from_fn(|a| {
                t.iter().map(|&v| r.positions[v as usize][a]).sum::<f64>() / 3.0
            });
            sum += c
                .iter()
                .map(|x| 1.0 - x.abs())
                .fold(f64::INFINITY, f64::min)
                .abs();
        }
        (on, sum / r.triangles.len() as f64)
    }

    #[test]
    fn crease_tips_put_vertices_on_the_edges_and_the_triangles_nearer_the_box() {
        let plain = retiled_box(false);
        let creased = retiled_box(true);
        assert!(plain.stretch.iter().all(|&j| j == 0));
        assert!(creased.stretch.iter().any(|&j| j != 0));
        let ((a, da), (b, db)) = (on_edges(&plain), on_edges(&creased));
        // A retiling that ignores the creases puts a vertex on an edge of
        // the box only by chance; the 12 edges of length 2 hold about 80
        // at L = 0.3.
        assert!(b >= 3 * a.max(10), "on the edges: {a} without, {b} with");
        assert!(
            db < 0.8 * da,
            "mean centroid distance {da} without, {db} with"
        );
    }

    fn pieces(mesh: &TriMesh) -> Vec<crate::swing::retile::fill::Piece> {
        let table = CornerTable::new(&mesh.triangles, mesh.vertex_count()).unwrap();
        crate::swing::retile::fill::pieces(mesh, &table).unwrap()
    }

    #[test]
    fn crease_length_counts_the_sharp_edges_only() {
        let length = crease_length(&pieces(&cube(8).0));
        assert!((length - 24.0).abs() < 1e-9, "{length}");
        assert_eq!(
            crease_length(&pieces(&crate::swing::retile::tests::sphere(3))),
            0.0
        );
        // A box without its top face: the rim turns by 90° but borders a
        // hole's patch, so only the 8 other edges count.
        let mut open = cube(8).0;
        let top = |v: u32| open.positions[v as usize][2] == 1.0;
        let kept = open
            .triangles
            .iter()
            .copied()
            .filter(|t| !t.iter().all(|&v| top(v)))
            .collect();
        open.triangles = kept;
        let length = crease_length(&pieces(&open));
        assert!((length - 16.0).abs() < 1e-9, "{length}");
    }
}
