//! # swm-corpus — meshes the project owns
//!
//! Deterministic generators of the test meshes that swm's remesher,
//! codec and benchmarks run on, so that no test depends on a downloaded
//! file. Every generator returns a [`swm::TriMesh`] that is
//!
//! * manifold and consistently oriented, counter-clockwise seen from
//!   outside (for closed meshes the enclosed signed volume is positive);
//! * free of duplicate positions (seams and poles are welded by
//!   construction, not by merging afterwards);
//! * free of zero-area triangles, with a bounded smallest angle (each
//!   function's documentation says how small);
//! * deterministic: the same arguments give a bit-identical mesh (only
//!   `f64` arithmetic in a fixed order, rounded to `f32` at the end; no
//!   hash-map iteration, no threads). Across platforms, `sin`, `cos` and
//!   `atan2` come from the system's math library and may differ in the
//!   last bit.
//!
//! | name           | function            | topology                  |
//! |----------------|---------------------|---------------------------|
//! | `uv-sphere`    | [`uv_sphere`]       | closed, genus 0           |
//! | `icosphere`    | [`icosphere`]       | closed, genus 0, valence 6|
//! | `torus`        | [`torus`]           | closed, genus 1           |
//! | `double-torus` | [`double_torus`]    | closed, genus 2           |
//! | `fandisk-like` | [`fandisk_like`]    | closed, genus 0, creases  |
//! | `cube`         | [`cube`]            | closed, genus 0, creases  |
//! | `plane-patch`  | [`plane_patch`]     | genus 0, 1 boundary loop  |
//!
//! [`all`] returns the standard set at moderate sizes; the `swm-corpus`
//! binary writes it as OBJ files. [`quality`] holds the measures the tests
//! check.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod cad;
mod implicit;
mod obj;
mod parametric;
mod planar;
pub mod quality;
mod relax;
mod vec;

pub use cad::{cube, fandisk_like};
pub use implicit::double_torus;
pub use obj::{save_obj, write_obj};
pub use parametric::{icosphere, plane_patch, torus, uv_sphere};

use swm::TriMesh;

/// The names of the standard set, in the order [`all`] returns it.
pub const NAMES: [&str; 7] = [
    "uv-sphere",
    "icosphere",
    "torus",
    "double-torus",
    "fandisk-like",
    "cube",
    "plane-patch",
];

/// The standard set, by name, each between 1k and 20k triangles.
///
/// Sizes are chosen so that every mesh has a few thousand triangles: big
/// enough to exercise the remesher, small enough that the whole set builds
/// in well under a second in a debug build (about 0.25 s unoptimized,
/// 0.05 s optimized, nearly all of it the double torus and the fandisk
/// caps).
///
/// | name           | vertices | triangles | smallest angle |
/// |----------------|---------:|----------:|---------------:|
/// | `uv-sphere`    |    1,106 |     2,208 |      7.4 deg   |
/// | `icosphere`    |    2,562 |     5,120 |     54.0 deg   |
/// | `torus`        |    1,536 |     3,072 |     34.7 deg   |
/// | `double-torus` |    4,605 |     9,214 |     26.7 deg   |
/// | `fandisk-like` |    2,614 |     5,224 |     30.6 deg   |
/// | `cube`         |    1,538 |     3,072 |     45.0 deg   |
/// | `plane-patch`  |    3,185 |     6,144 |     43.7 deg   |
pub fn all() -> Vec<(&'static str, TriMesh)> {
    NAMES
        .iter()
        .map(|&name| (name, by_name(name).unwrap()))
        .collect()
}

/// One mesh of the standard set by name, or `None` for an unknown name.
pub fn by_name(name: &str) -> Option<TriMesh> {
    Some(match name {
        "uv-sphere" => uv_sphere(1.0, 24, 48),
        "icosphere" => icosphere(1.0, 4),
        "torus" => torus(1.0, 0.35, 64, 24),
        "double-torus" => double_torus(44),
        "fandisk-like" => fandisk_like(32),
        "cube" => cube(16),
        "plane-patch" => plane_patch(64, 48),
        _ => return None,
    })
}

#[cfg(test)]
mod tests;
