//! Writing a SwingWrapper file from the retiler's output.
//!
//! The writer decides nothing about the mesh: it checks that the retiled
//! mesh is what Edgebreaker and the decoder will make of it (same
//! symbols, same vertex numbering, same positions bit for bit), picks the
//! predicted angle, and serializes. A failed check is a bug in the
//! retiler, reported as an error rather than a panic.

use super::read::{write_head, Head};
use super::{angle, residual, Retiled, SwingStats, MAX_ANGLE_BITS, MIN_ANGLE_BITS};
use crate::container::{write_container, Header, Mode, Tag};
use crate::edgebreaker;
use crate::lossless::{write_clers, write_topo};
use crate::{CornerTable, Error, FormatError, Malformed, ParameterError};

/// A retiled mesh that is not what it claims: the retiler has a bug.
fn internal(why: &'static str) -> Error {
    Error::Format(FormatError::new("retiled mesh", Malformed::BadSyntax(why)))
}

fn same_bits(a: &[[f64; 3]], b: &[[f64; 3]]) -> bool {
    a.len() == b.len()
        && a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| x.to_bits() == y.to_bits())
}

/// Encodes a retiled mesh as a SwingWrapper (mode 1) file.
///
/// Fails with [`Error::Parameter`] for angle bits out of range, and with
/// a format error naming the "retiled mesh" when `retiled` is
/// inconsistent: triangles that are not one closed manifold in
/// Edgebreaker creation order with the given symbols and numbering,
/// first vertices that are not binary32 values or not `positions[0..3]`,
/// an edge length other than [`first_edge_length`](super::first_edge_length),
/// or positions other than those the decoder rebuilds from the codes.
pub(crate) fn write(retiled: &Retiled) -> Result<(Vec<u8>, SwingStats), Error> {
    let bits = retiled.angle_bits;
    if !(MIN_ANGLE_BITS..=MAX_ANGLE_BITS).contains(&bits) {
        return Err(ParameterError::OutOfRange {
            name: "angle bits",
            value: f64::from(bits),
            min: f64::from(MIN_ANGLE_BITS),
            max: f64::from(MAX_ANGLE_BITS),
        }
        .into());
    }
    let (triangles, positions) = (&retiled.triangles, &retiled.positions);
    let nv = positions.len();
    if nv > u32::MAX as usize || triangles.len() > u32::MAX as usize {
        return Err(internal("too many vertices or triangles"));
    }
    if triangles.len() != retiled.symbols.len() + 1 {
        return Err(internal("not one symbol per triangle after the first"));
    }
    if triangles.iter().flatten().any(|&v| v as usize >= nv) {
        return Err(internal("a triangle names a vertex without a position"));
    }
    let first = retiled.first;
    let exact = first
        .iter()
        .flatten()
        .all(|&x| f64::from(x as f32).to_bits() == x.to_bits());
    if !exact || !same_bits(&first, positions.get(..3).unwrap_or(&[])) {
        return Err(internal(
            "first vertices are not binary32 values or not vertices 0, 1, 2",
        ));
    }
    if angle::first_edge_length(&first).to_bits() != retiled.edge_length.to_bits() {
        return Err(internal("edge length is not |first[0] - first[2]|"));
    }

    // Edgebreaker on M' must retrace the retiler's steps exactly.
    let table = CornerTable::new(triangles, nv)?;
    let eb = edgebreaker::encode(&table)?;
    let conn = eb.connectivity;
    if conn.symbols != retiled.symbols || conn.components != 1 {
        return Err(internal(
            "the symbols differ from Edgebreaker's on the retiled mesh",
        ));
    }
    let in_order = eb
        .vertex_order
        .iter()
        .enumerate()
        .all(|(k, v)| v.idx() == k)
        && eb
            .tip_corners
            .iter()
            .enumerate()
            .all(|(t, c)| c.idx() == 3 * t);
    if !in_order {
        return Err(internal(
            "triangles or vertices are not in Edgebreaker order",
        ));
    }
    // The decoder's table, built the decoder's way; positions from it.
    let decoded = edgebreaker::decode(&conn)?;
    if decoded.triangles() != *triangles {
        return Err(internal(
            "the decoded triangles differ from the retiled ones",
        ));
    }
    let rebuilt = super::rebuild_positions(&decoded, &[first], bits, &retiled.codes)
        .map_err(|_| internal("the angle codes do not rebuild the vertices"))?;
    if !same_bits(&rebuilt, positions) {
        return Err(internal("positions differ from the decoder's"));
    }

    let angles = angle::AngleTable::new(bits);
    let head = Head {
        bits,
        predicted: residual::predict(&retiled.codes, &angles),
        first: vec![first],
    };
    let head_bytes = write_head(&head);
    let topo = write_topo(&conn, &[]);
    let clrs = write_clers(&conn.symbols);
    let geom = residual::encode(&decoded, &retiled.codes, bits, head.predicted)?;
    let header = Header::new(Mode::Swing, nv as u32, triangles.len() as u32, 1);
    let sections: [(Tag, &[u8]); 4] = [
        (Tag::HEAD, &head_bytes),
        (Tag::TOPO, &topo),
        (Tag::CLRS, &clrs),
        (Tag::GEOM, &geom),
    ];
    let bytes = write_container(&header, &sections)?;
    let tags = sections.iter().map(|(t, b)| (t.0, b.len())).collect();
    let stats = SwingStats::new(&head, &decoded, &conn, tags, bytes.len());
    Ok((bytes, stats))
}
