//! Quality triangulation of a convex polygon with interior points, for the
//! flat caps of the CAD-like parts.
//!
//! 1. Ear clipping of the boundary, always taking the ear with the largest
//!    smallest angle (Meisters' two-ears theorem guarantees progress; in a
//!    convex polygon every strictly convex vertex is an ear). Collinear
//!    boundary vertices are allowed: they are never clipped as ears, and no
//!    ear is taken that would leave only collinear vertices, so no
//!    zero-area triangle is ever made.
//! 2. Incremental insertion of the interior points (1-to-3 split, or 2-to-4
//!    split when a point falls on an edge).
//! 3. Lawson flips to the constrained Delaunay triangulation (boundary
//!    edges are the constraints: they have one triangle and are never
//!    flipped), then rounds of Laplacian smoothing of the interior points
//!    (a move that would invert or flatten a triangle is undone) and flips.
//!
//! Point location is brute force: caps have hundreds of points, not
//! millions, and the simple version is easy to trust.

use std::collections::HashMap;

/// A point in the plane.
pub(crate) type P2 = [f64; 2];

/// Twice the signed area of `abc` (positive when counter-clockwise).
#[inline]
fn orient(a: P2, b: P2, c: P2) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Positive when `d` lies strictly inside the circumcircle of the
/// counter-clockwise triangle `abc`.
fn incircle(a: P2, b: P2, c: P2, d: P2) -> f64 {
    let (adx, ady) = (a[0] - d[0], a[1] - d[1]);
    let (bdx, bdy) = (b[0] - d[0], b[1] - d[1]);
    let (cdx, cdy) = (c[0] - d[0], c[1] - d[1]);
    (adx * adx + ady * ady) * (bdx * cdy - bdy * cdx)
        + (bdx * bdx + bdy * bdy) * (cdx * ady - cdy * adx)
        + (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx)
}

/// Smallest angle of triangle `abc`, in radians.
fn min_angle(a: P2, b: P2, c: P2) -> f64 {
    let ang = |p: P2, q: P2, r: P2| {
        let (u, v) = ([q[0] - p[0], q[1] - p[1]], [r[0] - p[0], r[1] - p[1]]);
        (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1])
    };
    ang(a, b, c).min(ang(b, c, a)).min(ang(c, a, b))
}

/// Triangulates the convex polygon `boundary` (counter-clockwise, collinear
/// vertices allowed) together with `interior` points that lie strictly
/// inside it. Returns the points (the boundary first and unchanged, then
/// the interior points after smoothing) and counter-clockwise triangles.
pub(crate) fn triangulate_convex(boundary: &[P2], interior: &[P2]) -> (Vec<P2>, Vec<[u32; 3]>) {
    let nb = boundary.len();
    assert!(nb >= 3, "a polygon needs three vertices");
    let mut pts: Vec<P2> = boundary.iter().chain(interior).copied().collect();
    // Length scale for the tolerances.
    let (mut lo, mut hi) = (boundary[0], boundary[0]);
    for p in boundary {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let eps_area = 1e-12 * size * size;

    let mut tris = ear_clip(&pts[..nb], eps_area);
    for i in nb..pts.len() {
        insert_point(&pts, &mut tris, i as u32, eps_area);
    }
    lawson(&pts, &mut tris, size);
    for _ in 0..4 {
        smooth_interior(&mut pts, &tris, nb, eps_area);
        lawson(&pts, &mut tris, size);
    }
    (pts, tris)
}

fn ear_clip(poly: &[P2], eps_area: f64) -> Vec<[u32; 3]> {
    let strictly_convex = |a: u32, b: u32, c: u32| {
        orient(poly[a as usize], poly[b as usize], poly[c as usize]) > eps_area
    };
    let mut ring: Vec<u32> = (0..poly.len() as u32).collect();
    let mut tris = Vec::with_capacity(poly.len());
    while ring.len() > 3 {
        let n = ring.len();
        let at = |i: usize| ring[i % n];
        let convex: Vec<bool> = (0..n)
            .map(|i| strictly_convex(at(i + n - 1), at(i), at(i + 1)))
            .collect();
        let total = convex.iter().filter(|&&c| c).count();
        let mut best: Option<(f64, usize)> = None;
        for i in 0..n {
            if !convex[i] {
                continue;
            }
            // Clipping i changes the corners at its two neighbours. Keep at
            // least three strictly convex corners, or what is left is a
            // flat chain that could only be triangulated with slivers.
            let (ip, inx) = ((i + n - 1) % n, (i + 1) % n);
            let after = total - 1 - convex[ip] as usize - convex[inx] as usize
                + strictly_convex(at(i + n - 2), at(ip), at(inx)) as usize
                + strictly_convex(at(ip), at(inx), at(i + 2)) as usize;
            if after < 3 {
                continue;
            }
            let q = min_angle(
                poly[at(ip) as usize],
                poly[at(i) as usize],
                poly[at(inx) as usize],
            );
            if best.is_none_or(|(bq, _)| q > bq) {
                best = Some((q, i));
            }
        }
        let (_, i) = best.expect("a convex polygon always has an ear");
        tris.push([at(i + n - 1), at(i), at(i + 1)]);
        ring.remove(i);
    }
    tris.push([ring[0], ring[1], ring[2]]);
    tris
}

/// Inserts point `p` into the triangulation by splitting the triangle
/// (or the edge) it falls in.
fn insert_point(pts: &[P2], tris: &mut Vec<[u32; 3]>, p: u32, eps_area: f64) {
    let q = pts[p as usize];
    // Newest triangles first: consecutive lattice points are neighbours,
    // so the search usually ends within a few triangles.
    for t in (0..tris.len()).rev() {
        let [a, b, c] = tris[t];
        let w = [
            orient(pts[b as usize], pts[c as usize], q),
            orient(pts[c as usize], pts[a as usize], q),
            orient(pts[a as usize], pts[b as usize], q),
        ];
        if w.iter().any(|&x| x < -eps_area) {
            continue;
        }
        let on_edge = (0..3).find(|&k| w[k] <= eps_area);
        match on_edge {
            None => {
                tris[t] = [a, b, p];
                tris.push([b, c, p]);
                tris.push([c, a, p]);
            }
            Some(k) => {
                // q lies on the edge opposite corner k: split both triangles.
                let tri = tris[t];
                let (u, v, x) = (tri[(k + 1) % 3], tri[(k + 2) % 3], tri[k]);
                let other = (0..tris.len())
                    .find(|&s| {
                        s != t && (0..3).any(|j| tris[s][j] == v && tris[s][(j + 1) % 3] == u)
                    })
                    .expect("interior points never lie on the boundary");
                let ot = tris[other];
                let y = *ot.iter().find(|&&z| z != u && z != v).unwrap();
                tris[t] = [x, u, p];
                tris.push([v, x, p]);
                tris[other] = [y, v, p];
                tris.push([u, y, p]);
            }
        }
        return;
    }
    panic!("interior point outside the polygon");
}

/// Flips interior edges until every one is locally Delaunay (Lawson's
/// algorithm with a stack of edges to recheck: after a flip only the four
/// outer edges of the flipped quad can have become illegal).
fn lawson(pts: &[P2], tris: &mut [[u32; 3]], size: f64) {
    let eps_in = 1e-12 * size.powi(4);
    let eps_area = 1e-12 * size * size;
    // Directed edge -> the triangle that runs along it.
    let mut owner: HashMap<(u32, u32), usize> = HashMap::with_capacity(tris.len() * 3);
    let mut stack = Vec::with_capacity(tris.len() * 3);
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            owner.insert((tri[k], tri[(k + 1) % 3]), t);
            stack.push((tri[k], tri[(k + 1) % 3]));
        }
    }
    let p = |i: u32| pts[i as usize];
    while let Some((a, b)) = stack.pop() {
        // A boundary edge (a constraint) has no triangle on its other side.
        let (Some(&t), Some(&s)) = (owner.get(&(a, b)), owner.get(&(b, a))) else {
            continue;
        };
        let c = *tris[t].iter().find(|&&z| z != a && z != b).unwrap();
        let d = *tris[s].iter().find(|&&z| z != a && z != b).unwrap();
        if incircle(p(a), p(b), p(c), p(d)) <= eps_in
            || orient(p(a), p(d), p(c)) <= eps_area
            || orient(p(d), p(b), p(c)) <= eps_area
        {
            continue; // locally Delaunay, or the quad is not strictly convex
        }
        // (a, b, c) + (b, a, d) -> (a, d, c) + (d, b, c).
        tris[t] = [a, d, c];
        tris[s] = [d, b, c];
        owner.remove(&(a, b));
        owner.remove(&(b, a));
        owner.insert((a, d), t);
        owner.insert((d, c), t);
        owner.insert((b, c), s);
        owner.insert((c, d), s);
        stack.extend([(a, d), (d, b), (b, c), (c, a)]);
    }
}

/// One round of Laplacian smoothing of the points after the first `nb`.
fn smooth_interior(pts: &mut [P2], tris: &[[u32; 3]], nb: usize, eps_area: f64) {
    let n = pts.len();
    let mut sum = vec![[0.0; 2]; n];
    let mut cnt = vec![0u32; n];
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            for (x, y) in [(a, b), (b, a)] {
                sum[x][0] += pts[y][0];
                sum[x][1] += pts[y][1];
                cnt[x] += 1;
            }
        }
    }
    let old = pts.to_vec();
    for v in nb..n {
        if cnt[v] > 0 {
            pts[v] = [sum[v][0] / cnt[v] as f64, sum[v][1] / cnt[v] as f64];
        }
    }
    // Undo moves that flatten or invert a triangle (rare near the rim).
    loop {
        let mut undone = false;
        for t in tris {
            let [a, b, c] = t.map(|i| pts[i as usize]);
            if orient(a, b, c) > eps_area.max(1e-3 * orient_old(&old, t)) {
                continue;
            }
            for &i in t {
                if pts[i as usize] != old[i as usize] {
                    pts[i as usize] = old[i as usize];
                    undone = true;
                }
            }
        }
        if !undone {
            return;
        }
    }
}

fn orient_old(old: &[P2], t: &[u32; 3]) -> f64 {
    let [a, b, c] = t.map(|i| old[i as usize]);
    orient(a, b, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_collinear_rim_and_interior() {
        // A 4x4 square with 4 vertices per side and a 3x3 interior lattice.
        let mut b = Vec::new();
        for i in 0..4 {
            b.push([i as f64, 0.0]);
        }
        for i in 0..4 {
            b.push([4.0, i as f64]);
        }
        for i in 0..4 {
            b.push([4.0 - i as f64, 4.0]);
        }
        for i in 0..4 {
            b.push([0.0, 4.0 - i as f64]);
        }
        let inner: Vec<P2> = (1..4)
            .flat_map(|j| (1..4).map(move |i| [i as f64 + 0.01 * j as f64, j as f64]))
            .collect();
        let (pts, tris) = triangulate_convex(&b, &inner);
        // Euler: a disc with V points has 2V - nb - 2 triangles.
        assert_eq!(tris.len(), 2 * pts.len() - b.len() - 2);
        let area: f64 = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| pts[i as usize]);
                assert!(orient(a, b, c) > 0.0);
                0.5 * orient(a, b, c)
            })
            .sum();
        assert!((area - 16.0).abs() < 1e-9);
    }
}
