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
//! and `inspect`).

use crate::prelude::*;

mod angle;
pub(crate) mod chain;
mod density;
mod forward;
mod front;
mod hole;
mod read;
mod rebuild;
mod residual;
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
pub(crate) use write::{write, Clers};

use crate::edgebreaker::Symbol;
#[cfg(feature = "encoder")]
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
#[cfg(feature = "encoder")]
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

/// The figures of one SwingWrapper file (what `swm info` shows).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SwingStats {
    /// Edge length L: the length of the first gate.
    pub edge_length: f64,
    /// Angle bits K.
    pub angle_bits: u8,
    /// The predicted angle code stored in `HEAD`.
    pub predicted_code: u32,
    /// Vertices of the retiled mesh as coded (holes covered, before the
    /// hole mask; without `REST`): the header's count.
    pub vertices: u64,
    /// Triangles of the retiled mesh as coded: the header's count.
    pub triangles: u64,
    /// Connected components of the retiled mesh as coded.
    pub components: u64,
    /// Handle events (two per handle).
    pub handle_events: u64,
    /// CLERS histogram, in the order C, L, E, R, S.
    pub clers: [u64; 5],
    /// Share of the CLERS labels that are C or R (0 to 1).
    pub cr_share: f64,
    /// Share of the vertices of valence 6 (0 to 1).
    pub valence6_share: f64,
    /// Bits per triangle of the connectivity (`TOPO` and `CLRS` or `CLRF`).
    pub connectivity_bits_per_triangle: f64,
    /// Bits per triangle of the angles (`GEOM`).
    pub geometry_bits_per_triangle: f64,
    /// Bits per coded angle (`GEOM` over the C tips).
    pub bits_per_angle: f64,
    /// Bytes of each section, in file order.
    pub sections: Vec<([u8; 4], usize)>,
    /// Bytes of the whole file.
    pub file_bytes: usize,
    /// Bytes of the hole mask (`HOLE`; 0 without holes).
    pub hole_bytes: u64,
    /// Triangles retiled over the patch of a hole that the hole mask
    /// drops (the fans of boundary loops are counted apart).
    pub holes_masked_triangles: u64,
    /// Components that start on a boundary loop (`LOOP`, format 1.1).
    pub loops: u64,
    /// Points of those loops: the vertices of the decoded boundary they
    /// code (each two angle codes in `LOOP`). Each loop's fan has one
    /// triangle per point: coded as connectivity only, and dropped with
    /// the dummy vertex at its centre.
    pub loop_points: u64,
    /// Bytes of `LOOP` (0 without one).
    pub loop_bytes: u64,
    /// Bytes of the lossless remainder (`REST`, a whole mode-0 file; 0
    /// without one).
    pub rest_bytes: u64,
    /// Triangles of the lossless remainder, appended to the decoded mesh.
    pub rest_triangles: u64,
    /// Connected components of the lossless remainder: the input's
    /// components not retiled (too small, or simplified by the automatic
    /// mode's choice per component), as coded.
    pub rest_components: u64,
    /// Bytes of the density (`DENS`, format 1.1; 0 without one).
    pub density_bytes: u64,
    /// The lowest and highest level of the C tips (radius r·2^(ℓ/4)), when
    /// the file has `DENS`.
    pub density_levels: Option<(i8, i8)>,
}

/// The lowest and highest of `levels` (`None` when empty).
pub(crate) fn level_range(levels: &[i8]) -> Option<(i8, i8)> {
    let lo = *levels.iter().min()?;
    let hi = *levels.iter().max()?;
    Some((lo, hi))
}

impl SwingStats {
    /// Share of the retiled triangles (the loops' fans left out) that
    /// cover a hole's patch and are dropped (0 to 1).
    pub fn masked_share(&self) -> f64 {
        // A fan has one triangle per loop point.
        let retiled = self.triangles.saturating_sub(self.loop_points);
        self.holes_masked_triangles as f64 / retiled.max(1) as f64
    }

    /// The figures of a file: its header fields, decoded corner table,
    /// symbols, sections, masked triangles and triangles of `REST`. The
    /// writer and `inspect` both build them here.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        head: &read::Head,
        table: &crate::CornerTable,
        conn: &crate::edgebreaker::Connectivity,
        sections: Vec<([u8; 4], usize)>,
        file_bytes: usize,
        masked: u64,
        (rest_triangles, rest_components): (u64, u64),
        loops: &chain::Loops,
    ) -> Self {
        let mut clers = [0u64; 5];
        for &s in &conn.symbols {
            clers[s as usize] += 1;
        }
        let labels = conn.symbols.len().max(1) as f64;
        let mut valence = vec![0u32; table.vertex_count()];
        for v in table.vertices() {
            valence[v.idx()] += 1;
        }
        let six = valence.iter().filter(|&&k| k == 6).count();
        let triangles = table.face_count() as u64;
        let bytes_of = |tags: &[&[u8; 4]]| -> usize {
            sections
                .iter()
                .filter(|(t, _)| tags.contains(&t))
                .map(|(_, n)| n)
                .sum()
        };
        let per_triangle = |bytes: usize| 8.0 * bytes as f64 / triangles.max(1) as f64;
        let geom = bytes_of(&[b"GEOM"]);
        let hole_bytes = bytes_of(&[&crate::container::Tag::HOLE.0]) as u64;
        let rest_bytes = bytes_of(&[&crate::container::Tag::REST.0]) as u64;
        let density_bytes = bytes_of(&[&crate::container::Tag::DENS.0]) as u64;
        let loop_bytes = bytes_of(&[&crate::container::Tag::LOOP.0]) as u64;
        // `masked` counts the patches' triangles only.
        SwingStats {
            edge_length: head.first.first().map_or(0.0, first_edge_length),
            angle_bits: head.bits,
            predicted_code: head.predicted,
            vertices: table.vertex_count() as u64,
            triangles,
            components: conn.components as u64,
            handle_events: conn.splits.len() as u64,
            clers,
            cr_share: (clers[Symbol::C as usize] + clers[Symbol::R as usize]) as f64 / labels,
            valence6_share: six as f64 / valence.len().max(1) as f64,
            connectivity_bits_per_triangle: per_triangle(bytes_of(&[b"TOPO", b"CLRS", b"CLRF"])),
            geometry_bits_per_triangle: per_triangle(geom),
            bits_per_angle: 8.0 * geom as f64 / (clers[Symbol::C as usize].max(1)) as f64,
            sections,
            file_bytes,
            hole_bytes,
            holes_masked_triangles: masked,
            loops: loops.entries.len() as u64,
            loop_points: loops.entries.iter().map(|e| u64::from(e.1)).sum(),
            loop_bytes,
            rest_bytes,
            rest_triangles,
            rest_components,
            density_bytes,
            density_levels: None,
        }
    }
}
