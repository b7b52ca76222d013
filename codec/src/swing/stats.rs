//! `SwingStats`: the figures of one SwingWrapper file (what `swm info`
//! shows). The reader and the writer fill them (`read::SwingStats::new`);
//! this file holds the type, below both.

use crate::prelude::*;

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
}
