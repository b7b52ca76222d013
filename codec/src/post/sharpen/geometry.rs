//! The per-face geometry the passes of EdgeSharpener share: face normals
//! and the longest edge (one pass over the input), the sliver test, and
//! the angle at a corner, accurate for small and flat angles alike.
//!
//! Below `cleanup` and `split`, which use it, and below `mod.rs`, which
//! calls them: none of these helpers calls back into a pass.

use crate::math;
use crate::prelude::*;

use glam::{DVec3, Vec3};

/// Whether a triangle has an angle with `sin² ≤ sin2` (or no area).
/// The smallest angle (at most 60°) faces the shortest edge, and its sine
/// is twice the area over the product of the two other edges' lengths.
#[inline]
pub(super) fn is_sliver(p: [DVec3; 3], sin2: f64) -> bool {
    let (e0, e1, e2) = (p[2] - p[1], p[0] - p[2], p[1] - p[0]);
    let l = [
        e0.length_squared(),
        e1.length_squared(),
        e2.length_squared(),
    ];
    let cross2 = e2.cross(-e1).length_squared();
    let k = if l[0] <= l[1] && l[0] <= l[2] {
        0
    } else if l[1] <= l[2] {
        1
    } else {
        2
    };
    cross2 <= sin2 * l[(k + 1) % 3] * l[(k + 2) % 3]
}

/// The `sin²` of the angle below which a triangle is a sliver.
pub(super) fn sliver_sin2(min_angle_degrees: f64) -> f64 {
    let s = math::sin(min_angle_degrees.to_radians());
    s * s
}

/// Per-face unit normals and the longest edge, computed in one pass.
pub(super) struct FaceGeometry {
    /// Unit normal of each face; zero for a face without area. Single
    /// precision (1e-7 is far below any angle the filters compare) halves
    /// the memory that the per-edge sweep reads out of order.
    pub normals: Vec<Vec3>,
    /// Length of the longest edge of the mesh.
    pub longest_edge: f64,
    /// Faces that are slivers already ([`is_sliver`] with `sin2`).
    pub slivers: Vec<u32>,
}

impl FaceGeometry {
    pub(super) fn new(positions: &[[f32; 3]], triangles: &[[u32; 3]], sin2: f64) -> Self {
        let mut longest2 = 0.0f64;
        let mut slivers = Vec::new();
        let normals = triangles
            .iter()
            .enumerate()
            .map(|(f, t)| {
                let p = t.map(|v| point(positions, v));
                let (ab, bc, ca) = (p[1] - p[0], p[2] - p[1], p[0] - p[2]);
                longest2 = longest2
                    .max(ab.length_squared())
                    .max(bc.length_squared())
                    .max(ca.length_squared());
                if is_sliver(p, sin2) {
                    slivers.push(f as u32);
                }
                unit_normal(ab, -ca).as_vec3()
            })
            .collect();
        FaceGeometry {
            normals,
            longest_edge: math::sqrt(longest2),
            slivers,
        }
    }
}

/// The unit normal of a triangle with edge vectors `u`, `v` from one
/// corner, or zero when the triangle has no area to speak of (its cross
/// product is lost in the rounding of its edges' lengths).
#[inline]
pub(super) fn unit_normal(u: DVec3, v: DVec3) -> DVec3 {
    let n = u.cross(v);
    let len2 = n.length_squared();
    let scale = u.length_squared() * v.length_squared();
    if len2 > 1e-24 * scale && len2 > 0.0 {
        n / math::sqrt(len2)
    } else {
        DVec3::ZERO
    }
}

/// A position in double precision.
#[inline(always)]
pub(super) fn point(positions: &[[f32; 3]], v: u32) -> DVec3 {
    let p = positions[v as usize];
    DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
}

/// The angle at `p` between the directions to `q` and `r`, accurate for
/// small and flat angles alike (0 or π when `q` or `r` is `p` itself).
#[inline]
pub(super) fn angle_at(p: DVec3, q: DVec3, r: DVec3) -> f64 {
    let (u, v) = (q - p, r - p);
    math::atan2(u.cross(v).length(), u.dot(v))
}
