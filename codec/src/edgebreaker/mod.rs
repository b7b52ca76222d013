//! Edgebreaker connectivity coding (Rossignac, "Edgebreaker: connectivity
//! compression for triangle meshes", IEEE TVCG 1999; the corner-table form
//! of Rossignac, Safonova and Szymczak, SMI 2001).
//!
//! The encoder ([`encode`]) walks each connected component of a closed,
//! oriented manifold from a first triangle, right branch first, and writes
//! one CLERS symbol per further triangle; handles (genus > 0) add one
//! [`SplitEvent`] each S* triangle, as Draco's topology-split events do.
//! The decoder ([`decode`]) rebuilds the corner table in linear time by
//! Spirale Reversi (Isenburg and Snoeyink, "Spirale Reversi: reverse
//! decoding of the Edgebreaker encoding", CGTA 2001): symbols are read
//! from last to first, so every S finds its left branch already built.
//!
//! Open meshes are closed first by [`fill_holes`]: a dummy vertex per
//! boundary loop, coned to the loop (Rossignac's TPATCH scheme); the
//! decoder drops the dummies and their fans again. [`close_holes`] builds
//! the closed mesh's corner table directly from the open one's.
//!
//! Invariants (tested): decode(encode(M)) has exactly M's triangles with
//! M's orientation, with vertices renumbered in the encoder's order of
//! first visit and faces in the encoder's visiting order; recompressing
//! the decoded mesh gives the same symbols.

mod decode;
mod encode;
mod holes;
mod shared;

#[cfg(test)]
mod reference;
#[cfg(test)]
mod tests;
#[cfg(test)]
pub(crate) use tests::swm_corpus_like as tests_support;

pub use decode::{decode, decode_from, decode_recording, ranges_of, SymbolSource, CONTEXTS};
pub use encode::{encode, Encoded};
pub use holes::{close_holes, fill_holes, Closed, Filled};
pub use shared::{Connectivity, Side, SplitEvent, Symbol};
