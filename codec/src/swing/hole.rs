//! The `HOLE` section of the SwingWrapper mode: which triangles of the
//! coded (closed) mesh the decoder drops (format-spec/05-swing.md,
//! "HOLE").
//!
//! The retiler covers the holes of an open input too, so that Edgebreaker
//! codes one closed surface; the triangles that cover a hole are then
//! marked here, one bit per triangle in decoded order, range coded with an
//! adaptive binary model per context. The context of triangle t looks only
//! at triangles decoded before it:
//!
//! ```text
//!                  V[3t]  (tip)
//!                  /    \
//!    across 3t+2  /  t   \  across 3t+1      sideways neighbours: used
//!                /        \                  when decoded before t
//!        V[3t+1] ---------- V[3t+2]
//!          = GL      |        = GR
//!            parent: the triangle of O[3t], across the gate, through
//!            which t was reached (earlier, except for a first triangle)
//! ```
//!
//! context = 4 for a component's first triangle (no parent), else
//! 2·mask[parent] + (1 if an earlier neighbour across 3t+1 or 3t+2 is
//! masked). Masked regions are contiguous, so away from a region's rim a
//! triangle's bit is its parent's and costs almost nothing; at the rim,
//! the sideways neighbours tell the traversal that it runs along the
//! region. Measured on masked disks of emulated sphere retilings (swing
//! tests, `measure_hole_contexts`), this costs 0–30% (typically 25%)
//! less than the parent's bit alone and the same as counting the masked
//! sideways neighbours (7 contexts); telling decoded from undecoded
//! sideways neighbours won 5–15% on the longest rims and lost as much on
//! medium ones. A disk costs 4.1–8.7 bits per rim edge, coder
//! termination (32–64 bits) and model learning included, the most for
//! the smallest rims; the triangles away from it cost under 0.001 bit
//! each (`a_small_hole_costs_little_and_nothing_away_from_its_rim`).
//!
//! [`encode`] and [`decode`] mirror each other: both take each context
//! from [`context`], with the same models, in the same triangle order.

use crate::prelude::*;

#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{ContextModel, Decoder};
use crate::{CornerId, CornerTable, Error, FormatError, Malformed, TriMesh};

/// Contexts of the mask bits: four for (parent bit, masked sideways
/// neighbour), one for first triangles.
pub(crate) const CONTEXTS: usize = 5;

/// The context of triangle `t`'s bit, from the bits of triangles `0..t`
/// (`earlier`, at least `t` long). Must be the same for encoder and
/// decoder, which is why both call this one function.
fn context(table: &CornerTable, t: usize, earlier: &[bool]) -> usize {
    // The triangle across the edge facing corner 3t + k, if decoded
    // before t. A decoded table is closed, so every corner has an
    // opposite; `get` keeps a hostile table panic-free anyway.
    let across = |k: usize| -> Option<usize> {
        let o = table.opposites().get(3 * t + k).copied()?;
        if o == CornerId::NONE {
            return None;
        }
        let f = o.idx() / 3;
        (f < t).then_some(f)
    };
    let masked = |f: Option<usize>| f.is_some_and(|f| earlier.get(f) == Some(&true));
    match across(0) {
        None => 4,
        Some(parent) => {
            let sideways = masked(across(1)) || masked(across(2));
            2 * usize::from(earlier[parent]) + usize::from(sideways)
        }
    }
}

/// [`context`] as the `CLRF` pass finds it, without a corner table: the
/// pass knows, for each triangle it builds, the triangle across its gate
/// (`parent`) and those across the front edges its tip closes (`sides`),
/// all decoded before it; a component's first triangle has none (`first`).
/// On a mesh the pass builds from a file swm writes, this is [`context`]
/// of the decoded table for every triangle: the parent is `f(O[3t])`,
/// and the earlier neighbours across `3t+1` and `3t+2` are exactly the
/// triangles behind the front edges an L, R or E closes (a C or an S
/// makes both edges new, so their neighbours come later).
pub(super) fn context_in_pass(
    mask: &[bool],
    parent: u32,
    sides: [Option<u32>; 2],
    first: bool,
) -> usize {
    if first {
        return 4;
    }
    let masked = |f: Option<u32>| f.is_some_and(|f| mask.get(f as usize) == Some(&true));
    let sideways = masked(sides[0]) || masked(sides[1]);
    2 * usize::from(masked(Some(parent))) + usize::from(sideways)
}

/// A `HOLE` stream being read, one bit per triangle in order, each with
/// the context its caller found: [`context`] on a corner table
/// ([`decode`]) or [`context_in_pass`] inside the `CLRF` pass.
pub(super) struct Reader<'a> {
    dec: Decoder<'a>,
    models: ContextModel,
    /// The bits read so far.
    pub mask: Vec<bool>,
}

impl<'a> Reader<'a> {
    /// The stream `bytes` of a mesh of `count` triangles. The count was
    /// checked against the limits; this checks it against the stream's
    /// own length as well.
    pub(super) fn new(bytes: &'a [u8], count: usize) -> Result<Self, Error> {
        // A bit costs at least −log2(1 − 2^−16) > 2^−16 bits: each of the
        // two symbols keeps a frequency of at least 1 in 2^16.
        crate::container::check_count_fits(
            "hole mask bit",
            count as u64,
            bytes.len(),
            1,
            1 << crate::entropy::PRECISION,
        )?;
        Ok(Reader {
            dec: Decoder::new(bytes)?,
            models: ContextModel::new(CONTEXTS, 2),
            mask: Vec::with_capacity(count),
        })
    }

    /// Reads the next triangle's bit in context `ctx`.
    pub(super) fn read(&mut self, ctx: usize) -> Result<(), Error> {
        let bit = self.dec.decode(self.models.get(ctx))? == 1;
        self.mask.push(bit);
        Ok(())
    }

    /// Reads the bit of the triangle the `CLRF` pass just built.
    pub(super) fn read_in_pass(
        &mut self,
        parent: u32,
        sides: [Option<u32>; 2],
        first: bool,
    ) -> Result<(), Error> {
        self.read(context_in_pass(&self.mask, parent, sides, first))
    }

    /// Checks that the stream ends exactly after the last bit; returns
    /// the mask.
    pub(super) fn finish(self) -> Result<Vec<bool>, Error> {
        self.dec.finish()?;
        Ok(self.mask)
    }
}

/// Codes `mask` (one bit per triangle of the decoded `table`, in order).
/// Mirrors [`decode`].
#[cfg(feature = "encoder")]
pub(crate) fn encode(table: &CornerTable, mask: &[bool]) -> Vec<u8> {
    debug_assert_eq!(mask.len(), table.face_count());
    let mut models = ContextModel::new(CONTEXTS, 2);
    let mut enc = Encoder::new();
    for (t, &bit) in mask.iter().enumerate() {
        let ctx = context(table, t, &mask[..t]);
        enc.encode(models.get(ctx), u32::from(bit));
    }
    enc.finish()
}

/// Decodes one bit per triangle of the decoded `table`. Mirrors
/// [`encode`]. The triangle count was checked against the limits and
/// `CLRS`; this checks it against the section's own length as well,
/// then that the stream ends exactly after the last bit.
pub(crate) fn decode(table: &CornerTable, bytes: &[u8]) -> Result<Vec<bool>, Error> {
    let mut r = Reader::new(bytes, table.face_count())?;
    for t in 0..table.face_count() {
        r.read(context(table, t, &r.mask))?;
    }
    r.finish()
}

/// The triangles the decoder drops: `mask` (`HOLE`'s bits, if any) with
/// every triangle of a loop's fan added, which `HOLE` need not mark
/// (`None`: nothing is dropped). The decoder drops them; the encoder asks
/// which vertices stay ([`kept_vertices`]) to number its records as the
/// decoder numbers the vertices.
pub(crate) fn dropped(
    mut mask: Option<Vec<bool>>,
    triangles: &[[u32; 3]],
    loops: &super::chain::Loops,
) -> Option<Vec<bool>> {
    if !loops.entries.is_empty() {
        let fans = super::chain::fans_of(triangles, loops);
        let m = mask.get_or_insert_with(|| vec![false; fans.len()]);
        for (m, f) in m.iter_mut().zip(fans) {
            *m |= f;
        }
    }
    mask
}

/// Which of `vertices` vertices survive [`drop_masked`] with `mask`: those
/// a kept triangle uses. The survivors keep their order, so the decoded
/// vertex k is the k-th `true` here.
#[cfg(feature = "encoder")]
pub(crate) fn kept_vertices(vertices: usize, triangles: &[[u32; 3]], mask: &[bool]) -> Vec<bool> {
    let mut kept = vec![false; vertices];
    for (t, _) in triangles.iter().zip(mask).filter(|(_, &m)| !m) {
        for &v in t {
            if let Some(k) = kept.get_mut(v as usize) {
                *k = true;
            }
        }
    }
    kept
}

/// [`drop_masked`] of the `CLRF` pass's output: binary64 positions, each
/// kept one rounded to binary32 on the way (one pass over the vertices
/// instead of a conversion, then a copy).
pub(crate) fn drop_masked_from(
    positions: &[[f64; 3]],
    mut triangles: Vec<[u32; 3]>,
    mask: &[bool],
) -> Result<TriMesh, Error> {
    if mask.len() != triangles.len() {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadSyntax("the hole mask does not have one bit per triangle"),
        )));
    }
    let mut masked = mask.iter();
    triangles.retain(|_| masked.next() == Some(&false));
    let positions =
        crate::mesh::compact_vertices_as(positions, &mut triangles, |p| p.map(|c| c as f32));
    Ok(TriMesh {
        positions,
        triangles,
    })
}

/// The decoded mesh rule: drops the masked triangles, then the vertices
/// no kept triangle uses, renumbering the others in increasing order and
/// keeping the triangles' order. `mask` has one entry per triangle.
pub(crate) fn drop_masked(mesh: TriMesh, mask: &[bool]) -> Result<TriMesh, Error> {
    if mask.len() != mesh.triangles.len() {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadSyntax("the hole mask does not have one bit per triangle"),
        )));
    }
    let mut triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .zip(mask)
        .filter(|(_, &m)| !m)
        .map(|(t, _)| *t)
        .collect();
    let positions = crate::mesh::compact_vertices(&mesh.positions, &mut triangles);
    Ok(TriMesh {
        positions,
        triangles,
    })
}
