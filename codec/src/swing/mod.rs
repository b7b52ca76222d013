//! The SwingWrapper mode (mode 1): the retiled mesh's connectivity, coded
//! by Edgebreaker exactly as the lossless mode codes it, and one quantized
//! dihedral angle per C tip (M. Attene, *Surface Remeshing and
//! Applications*, 2004, §7; `../shared/design/ALGORITHMS.md` §5).
//!
//! Sections (format-spec/05-swing.md):
//! * `HEAD`: `u8 K`, `u16 q_pred`, then per component the three vertices
//!   of its first triangle as `f32 ×9`;
//! * `TOPO`, `CLRS`: as in the lossless mode (no dummy vertices); or,
//!   format 1.1, `TOPO` and `CLRF`: the symbols coded in a forward pass
//!   with the front's shape at each gate as context ([`forward`]);
//! * `GEOM`: the angle residuals `(q − q_pred) mod 2^K`, range coded
//!   ([`residual`]);
//! * `HOLE` (only when some triangle is masked): one bit per triangle,
//!   set for those that cover a hole of the input ([`hole`]);
//! * `REST` (only when some component was too small to retile): a whole
//!   lossless (mode 0) file, whose mesh follows the retiled one.
//!
//! The decoder rebuilds the corner table, then every vertex in one pass
//! over the triangles ([`rebuild::rebuild_positions`]); the encoder runs the same
//! pass on the retiler's output before writing, so the file decodes to
//! exactly the retiler's positions. Then masked triangles and the
//! vertices only they used are dropped, and `REST`'s mesh appended.
//!
//! One concern per file: `angle` (the exact arithmetic of a tip),
//! `front` and `forward` (the `CLRF` pass and its loops),
//! `residual` (the GEOM stream), `hole` (the HOLE stream and the
//! dropping rule), `write` (the encoder side), `read` (the decoder side
//! and `inspect`); `retile/`, encoder only, the retiler that makes the
//! mesh and its angles, with rate control (`retile::rate`). The method
//! that runs them for the encoder's chooser is `encoder/swing/`.

mod angle;
pub(crate) mod chain;
mod density;
mod forward;
mod front;
mod hole;
mod read;
mod rebuild;
mod residual;
#[cfg(feature = "encoder")]
pub(crate) mod retile;
#[cfg(feature = "encoder")]
mod retiled;
mod stats;
mod stretch;
#[cfg(feature = "encoder")]
mod write;

#[cfg(all(test, feature = "encoder"))]
mod measure;
#[cfg(test)]
mod tests;

pub use angle::{first_edge_length, MAX_ANGLE_BITS, MIN_ANGLE_BITS};
#[cfg(feature = "encoder")]
pub(crate) use density::{gate_level, ratio as level_ratio, LEVEL_MAX};
#[cfg(feature = "encoder")]
pub(crate) use stretch::{apply as stretch_apply, nearest as stretch_code};
// What the retiler builds its tips with: the decoder's own arithmetic.
#[cfg(feature = "encoder")]
pub use angle::{quantize, tip_radius, AngleTable, Frame};
pub(crate) use read::{decode, inspect, rest_counts};
#[cfg(feature = "encoder")]
pub use retiled::Retiled;
pub(crate) use stats::level_range;
pub use stats::SwingStats;
#[cfg(feature = "encoder")]
pub(crate) use write::{write, Clers};
