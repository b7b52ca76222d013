//! `Retiled`: what the retiler hands to the writer, in the numbering the
//! file's connectivity decodes to. Plain data below both, so that the
//! writer and the retiler import it without importing each other.

use crate::prelude::*;

use super::chain;
use crate::edgebreaker::Symbol;
use crate::TriMesh;

/// What the retiler hands to the writer: the retiled mesh M′ in creation
/// order, with the decoded positions the file must reproduce.
///
/// Conventions (format-spec/02-connectivity.md, "Decoded numbering"):
/// components follow each other; a component's first triangle is
/// (p1, p3, p2) and takes the next three vertex numbers; every later
/// triangle t is (tip, GL, GR), so that Edgebreaker run on M′ (each
/// component from corner 0 of its first triangle) visits the triangles in
/// this order, each through corner 3t, reproduces `symbols`, and numbers
/// the vertices 0, 1, 2, … as given (each C tip takes the next number).
#[derive(Clone, Debug, PartialEq)]
pub struct Retiled {
    /// Angle bits K, [`MIN_ANGLE_BITS`]`..=`[`MAX_ANGLE_BITS`].
    pub angle_bits: u8,
    /// Per component, in order: p1, p3, p2 of its first triangle, already
    /// binary32 values. Component 0's are vertices 0, 1, 2.
    pub first: Vec<[[f64; 3]; 3]>,
    /// Triangles in creation order, as above.
    pub triangles: Vec<[u32; 3]>,
    /// The decoded position X̂ of every vertex, by vertex number: what
    /// the decoder computes, bit for bit.
    pub positions: Vec<[f64; 3]>,
    /// One CLERS symbol per triangle except each component's first.
    pub symbols: Vec<Symbol>,
    /// The angle code q of each C tip, in order.
    pub codes: Vec<u32>,
    /// The level step d (−1, 0 or 1) of each C tip, in order: its circle
    /// has radius r·2^(ℓ/4), ℓ the mean level of its gate rounded down
    /// plus d (`DENS`, format 1.1). Empty, or all zero: every radius is r
    /// and the file is format 1.0.
    pub steps: Vec<i8>,
    /// The radius code j of each C tip, in order: its radius is further
    /// scaled by 1 + j·2^(3−K) (`RADS`, format 1.1). Empty, or all zero:
    /// every tip is on its circle.
    pub stretch: Vec<i32>,
    /// L = |first[0][0] − first[0][2]| ([`first_edge_length`]); every
    /// component's tips use its radius.
    pub edge_length: f64,
    /// Per triangle: it covers a filled hole of the input and the decoder
    /// drops it. Empty when the input had no boundary.
    pub hole_mask: Vec<bool>,
    /// Components too small to retile at this L, kept exactly by the
    /// lossless mode at `qp` bits and appended after the retiled mesh.
    pub rest: Option<(TriMesh, u8)>,
    /// Components that start on a boundary loop (`chain`, `LOOP`): the
    /// first `n − 2` C tips of each are loop points, whose `codes`
    /// entries the writer sets to the predicted code.
    pub loops: chain::Loops,
    /// The two angle codes of each loop point, in order
    /// ([`chain::place`]).
    pub loop_codes: Vec<[u32; 2]>,
}
