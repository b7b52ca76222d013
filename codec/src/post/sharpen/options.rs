//! What a caller of [`sharpen`](super::sharpen) asks
//! ([`SharpenOptions`]) and why the report's unmoved vertices stayed where
//! they were inserted ([`Unmoved`]): plain data, below the passes that
//! read and fill it.

use crate::ParameterError;

/// Options of [`sharpen`]. The defaults are the thesis's and the design
/// notes' values, but for `max_snap_ratio` (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SharpenOptions {
    /// An interior edge is smooth when the angle between its two face
    /// normals is below this multiple of ε, the mean of that angle over
    /// the mesh's interior edges. Default 2.0 (the thesis's "2ε": ε alone
    /// makes the filters too sensitive to noise).
    pub smooth_factor: f64,
    /// Triangles with an angle below this many degrees are removed by
    /// collapsing the edge opposite the angle. Default 1.0. Zero-area
    /// triangles are removed whatever the value.
    pub min_angle_degrees: f64,
    /// A chamfer-edge vertex stays at the edge's midpoint when the two
    /// plane normals N, M are this close to parallel: `1 − (N·M)² <` this.
    /// Default 1e-4.
    pub parallel_tolerance: f64,
    /// A corner vertex stays at the triangle's centroid when its three
    /// plane normals are this close to coplanar: `|det[N; M; S]| <` this.
    /// Default 1e-3.
    pub coplanar_tolerance: f64,
    /// A new vertex stays unmoved when snapping it would make an edge
    /// longer than this multiple of the longest edge of the input mesh.
    /// Default 1.0 (the thesis: the algorithm is tailored for nearly
    /// uniform triangulations).
    pub max_edge_factor: f64,
    /// A new vertex stays unmoved when snapping would move it farther
    /// than this multiple of its chamfer edge's length (for a corner: of
    /// its triangle's longest edge). Default 0.7; `f64::INFINITY` (or any
    /// large value) gives the thesis's rules alone.
    pub max_snap_ratio: f64,
}

impl Default for SharpenOptions {
    fn default() -> Self {
        SharpenOptions {
            smooth_factor: 2.0,
            min_angle_degrees: 1.0,
            parallel_tolerance: 1e-4,
            coplanar_tolerance: 1e-3,
            max_edge_factor: 1.0,
            max_snap_ratio: 0.7,
        }
    }
}

impl SharpenOptions {
    pub(super) fn check(&self) -> Result<(), ParameterError> {
        let ranges: [(&'static str, f64, f64, f64); 6] = [
            ("smooth_factor", self.smooth_factor, 0.0, 1e6),
            ("min_angle_degrees", self.min_angle_degrees, 0.0, 30.0),
            ("parallel_tolerance", self.parallel_tolerance, 0.0, 1.0),
            ("coplanar_tolerance", self.coplanar_tolerance, 0.0, 1.0),
            ("max_edge_factor", self.max_edge_factor, 0.0, 1e6),
            ("max_snap_ratio", self.max_snap_ratio, 0.0, f64::INFINITY),
        ];
        for (name, value, min, max) in ranges {
            // Written so that NaN fails too.
            if !(value >= min && value <= max) {
                return Err(ParameterError::OutOfRange {
                    name,
                    value,
                    min,
                    max,
                });
            }
        }
        Ok(())
    }
}

/// Why new vertices were left where they were inserted (the middle of
/// their chamfer edge or corner triangle) instead of being snapped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Unmoved {
    /// The two planes are nearly parallel (`1 − c² <` the tolerance).
    pub parallel: u64,
    /// The three planes of a corner have nearly coplanar normals.
    pub coplanar: u64,
    /// The snapped position would make an edge longer than allowed.
    pub too_long: u64,
    /// The snapped position is too far from the inserted one.
    pub too_far: u64,
    /// The chamfer mixes a concave and a convex side (`a·b ≥ 0`).
    pub mixed: u64,
    /// An endpoint's red triangles give no normal (they cancel out or
    /// have no area).
    pub no_normal: u64,
}

impl Unmoved {
    /// All unmoved vertices, whatever the reason.
    pub fn total(&self) -> u64 {
        self.parallel + self.coplanar + self.too_long + self.too_far + self.mixed + self.no_normal
    }
}
