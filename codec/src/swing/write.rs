//! Writing a SwingWrapper file from the retiler's output.
//!
//! The writer decides nothing about the mesh: it checks that the retiled
//! mesh is what Edgebreaker and the decoder will make of it (same
//! symbols, same vertex numbering, same positions bit for bit), picks the
//! predicted angle, and serializes. A failed check is a bug in the
//! retiler, reported as an error rather than a panic.

use super::read::{write_head, Head};
use super::{
    angle, chain, density, forward, hole, residual, stretch, Retiled, SwingStats, MAX_ANGLE_BITS,
    MIN_ANGLE_BITS,
};
use crate::container::{write_container, Framing, Header, Mode, Tag};
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

/// The triangles that start a component: those whose corners 3t+1 and
/// 3t+2 take new vertex numbers (format-spec/02-connectivity.md,
/// "Decoded numbering").
fn component_starts(triangles: &[[u32; 3]]) -> Vec<usize> {
    let (mut next, mut starts) = (0u64, Vec::new());
    for (t, tri) in triangles.iter().enumerate() {
        if u64::from(tri[1]) >= next {
            starts.push(t);
            next += 3;
        } else if u64::from(tri[0]) == next {
            next += 1;
        }
    }
    starts
}

/// Where the writer puts the CLERS symbols.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Clers {
    /// `CLRS`, each symbol in the context of the previous one (1.0).
    Plain,
    /// `CLRF`, with the front's shape as context (1.1), whenever its pass
    /// follows the mesh.
    Front,
    /// The smaller of the two (`CLRS` on ties): what the encoder writes.
    /// `CLRF` wins on retiled meshes (a quarter of a file); on meshes
    /// whose labels the front's angles do not decide, such as the
    /// emulated retilings of subdivided icosahedra, `CLRS` can win.
    Smaller,
}

/// `CLRF` for `retiled`, if the forward pass follows it and its bytes
/// decode back to the same symbols, codes, levels, positions, triangles
/// and (`hole`, `HOLE`'s bytes) mask bits: a `CLRF` file decodes in that
/// one pass, with no corner table.
#[allow(clippy::too_many_arguments)]
fn front_coded(
    retiled: &Retiled,
    codes: &[u32],
    head: &Head,
    levels: Option<&[i8]>,
    radii: Option<(&[i32], &[u8])>,
    geom: &[u8],
    dens: Option<&[u8]>,
    loop_bytes: Option<&[u8]>,
    hole: Option<&[u8]>,
    bits: u8,
) -> Option<Vec<u8>> {
    let nv = retiled.positions.len();
    let list = &retiled.loops;
    let points = |res| chain::Points::new(list, res, bits, head.predicted);
    let bytes = forward::encode(
        &retiled.symbols,
        &retiled.triangles,
        codes,
        levels,
        radii.map(|r| r.0),
        &retiled.first,
        retiled.angle_bits,
        nv,
        loop_bytes.map(|_| points(chain::Residuals::List(retiled.loop_codes.iter()))),
    )
    .ok()?;
    let stream = match loop_bytes {
        Some(b) => Some(chain::read(b, retiled.first.len() as u64, nv as u64, bits).ok()?),
        None => None,
    };
    let back = forward::decode(
        &bytes,
        geom,
        dens,
        radii.map(|r| r.1),
        hole,
        true,
        &head.first,
        head.bits,
        head.predicted,
        nv,
        retiled.symbols.len(),
        stream.map(|(_, r)| points(chain::Residuals::Stream(Box::new(r)))),
    )
    .ok()?;
    let same = back.symbols == retiled.symbols
        && back.codes == codes
        && back.levels.as_deref() == levels
        && back.stretch.as_deref() == radii.map(|r| r.0)
        && same_bits(&back.positions, &retiled.positions)
        && back.triangles == retiled.triangles
        && (hole.is_none() || back.mask.as_deref() == Some(&retiled.hole_mask[..]));
    same.then_some(bytes)
}

/// Encodes a retiled mesh as a SwingWrapper (mode 1) file.
///
/// Fails with [`Error::Parameter`] for angle bits out of range, and with
/// a format error naming the "retiled mesh" when `retiled` is
/// inconsistent: triangles that are not closed manifold components in
/// Edgebreaker creation order with the given symbols and numbering, a
/// component count other than `first.len()`, first vertices that are not
/// binary32 values or not the positions of their component's first
/// triangle, an edge length other than
/// [`first_edge_length`](super::first_edge_length)`(&first[0])` (any edge
/// length passes when there is no component), positions other than those
/// the decoder rebuilds from the codes, or a hole mask that is neither
/// empty nor one entry per triangle. Errors of the lossless encoder on
/// the `rest` mesh are passed on.
///
/// `HOLE` is written only when some mask entry is set, `REST` only when
/// the rest mesh has a triangle: without them the file is what this
/// writer made before either existed, byte for byte. `clers` says
/// where the symbols go; `CLRF` is kept only if its pass follows the
/// mesh and its bytes decode back to the same symbols, codes and levels.
pub(crate) fn write(
    retiled: &Retiled,
    clers: Clers,
    framing: Framing,
) -> Result<(Vec<u8>, SwingStats), Error> {
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
    let (triangles, positions, first) = (&retiled.triangles, &retiled.positions, &retiled.first);
    let nv = positions.len();
    if nv > u32::MAX as usize || triangles.len() > u32::MAX as usize {
        return Err(internal("too many vertices or triangles"));
    }
    if triangles.len() != retiled.symbols.len() + first.len() {
        return Err(internal(
            "not one symbol per triangle but each component's first",
        ));
    }
    if triangles.iter().flatten().any(|&v| v as usize >= nv) {
        return Err(internal("a triangle names a vertex without a position"));
    }
    let exact = first
        .iter()
        .flatten()
        .flatten()
        .all(|&x| f64::from(x as f32).to_bits() == x.to_bits());
    let starts = component_starts(triangles);
    let placed = starts.len() == first.len()
        && starts.iter().zip(first).all(|(&t, f)| {
            let corners = triangles[t].map(|v| positions[v as usize]);
            same_bits(f, &corners)
        });
    if !exact || !placed {
        return Err(internal(
            "first vertices are not binary32 values or not their components' first vertices",
        ));
    }
    if let Some(f) = first.first() {
        if angle::first_edge_length(f).to_bits() != retiled.edge_length.to_bits() {
            return Err(internal("edge length is not |first[0][0] - first[0][2]|"));
        }
    }
    let mask = &retiled.hole_mask;
    if !mask.is_empty() && mask.len() != triangles.len() {
        return Err(internal("the hole mask is not one entry per triangle"));
    }

    // Edgebreaker on M' must retrace the retiler's steps exactly.
    let table = CornerTable::new(triangles, nv)?;
    let eb = edgebreaker::encode(&table)?;
    let conn = eb.connectivity;
    if conn.symbols != retiled.symbols || conn.components as usize != first.len() {
        return Err(internal(
            "the symbols or components differ from Edgebreaker's on the retiled mesh",
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
    // DENS only when some step is not 0: a file without is format 1.0.
    let graded = retiled.steps.iter().any(|&d| d != 0);
    let dens = if graded {
        Some(density::encode(&decoded, &retiled.steps)?)
    } else {
        None
    };
    let levels = match &dens {
        Some(b) => Some(
            density::decode(&decoded, b, retiled.codes.len())
                .map_err(|_| internal("the level steps do not decode"))?,
        ),
        None => None,
    };
    // RADS likewise only when some radius code is not 0.
    let stretched = retiled.stretch.iter().any(|&j| j != 0);
    let rads = if stretched {
        Some(stretch::encode(&decoded, bits, &retiled.stretch)?)
    } else {
        None
    };
    let radii = match &rads {
        Some(b) => Some(
            stretch::decode(&decoded, bits, b, retiled.codes.len())
                .map_err(|_| internal("the radius codes do not decode"))?,
        ),
        None => None,
    };
    // Loop points carry the predicted code, which only the other tips
    // decide.
    let angles = angle::AngleTable::new(bits);
    let on_loop = chain::loop_tips(&decoded, &retiled.loops);
    if on_loop.len() != retiled.codes.len()
        || on_loop.iter().filter(|&&b| b).count() != retiled.loop_codes.len()
    {
        return Err(internal("loop points are not C tips of their components"));
    }
    let swung: Vec<u32> = (retiled.codes.iter().zip(&on_loop))
        .filter(|(_, &l)| !l)
        .map(|(&q, _)| q)
        .collect();
    let head = Head {
        bits,
        predicted: residual::predict(&swung, &angles),
        first: first.clone(),
    };
    let codes: Vec<u32> = (retiled.codes.iter().zip(&on_loop))
        .map(|(&q, &l)| if l { head.predicted } else { q })
        .collect();
    let loop_bytes = if retiled.loops.entries.is_empty() {
        None
    } else {
        Some(chain::encode(&retiled.loops, &retiled.loop_codes, bits)?)
    };
    let mut points = loop_bytes.as_ref().map(|_| {
        chain::Points::new(
            &retiled.loops,
            chain::Residuals::List(retiled.loop_codes.iter()),
            bits,
            head.predicted,
        )
    });
    let rebuilt = super::rebuild::rebuild_positions(
        &decoded,
        first,
        bits,
        &codes,
        levels.as_deref(),
        radii.as_deref(),
        points.as_mut(),
    )
    .and_then(|x| points.map_or(Ok(()), |p| p.finish()).map(|_| x))
    .map_err(|_| internal("the angle codes do not rebuild the vertices"))?;
    if !same_bits(&rebuilt, positions) {
        return Err(internal("positions differ from the decoder's"));
    }

    let head_bytes = write_head(&head);
    let topo = write_topo(&conn, &[]);
    let geom = residual::encode(&decoded, &codes, bits, head.predicted)?;
    // The loops' fans are dropped without a bit (`chain::fans`); HOLE
    // only when some patch triangle is masked too.
    let fans = chain::fans(&decoded, &retiled.loops);
    let masked_at = |t: usize| mask.get(t).copied().unwrap_or(false);
    if fans.iter().enumerate().any(|(t, &f)| f && !masked_at(t)) {
        return Err(internal("a loop's fan is not masked"));
    }
    let masked = (0..fans.len())
        .filter(|&t| masked_at(t) && !fans[t])
        .count() as u64;
    let hole_bytes = (masked > 0).then(|| hole::encode(&decoded, mask));
    let clrf = match clers {
        Clers::Plain => None,
        Clers::Front | Clers::Smaller => front_coded(
            retiled,
            &codes,
            &head,
            levels.as_deref(),
            radii.as_deref().zip(rads.as_deref()),
            &geom,
            dens.as_deref(),
            loop_bytes.as_deref(),
            hole_bytes.as_deref(),
            bits,
        ),
    };
    let clrs = (clers != Clers::Front || clrf.is_none()).then(|| write_clers(&conn.symbols));
    let (clers_tag, clers) = match (clrf, clrs) {
        (Some(f), Some(s)) if s.len() <= f.len() => (Tag::CLRS, s),
        (Some(f), _) => (Tag::CLRF, f),
        (None, s) => (Tag::CLRS, s.unwrap_or_default()),
    };
    let (rest_bytes, rest_counts) = match &retiled.rest {
        Some((mesh, qp)) if mesh.face_count() > 0 => {
            let table = CornerTable::new(&mesh.triangles, mesh.vertex_count())?;
            let (bytes, stats, _) = crate::lossless::encode(&table, mesh, *qp, framing)?;
            (Some(bytes), (mesh.face_count() as u64, stats.components))
        }
        _ => (None, (0, 0)),
    };
    let mut header = Header::new(
        Mode::Swing,
        nv as u32,
        triangles.len() as u32,
        first.len() as u32,
    );
    if dens.is_some() || clers_tag == Tag::CLRF || loop_bytes.is_some() || rads.is_some() {
        // DENS, CLRF, LOOP and RADS are format 1.1 sections.
        header.minor = 1;
    }
    let header = header.with_framing(framing);
    let mut sections: Vec<(Tag, &[u8])> = vec![
        (Tag::HEAD, &head_bytes),
        (Tag::TOPO, &topo),
        (clers_tag, &clers),
        (Tag::GEOM, &geom),
    ];
    if let Some(b) = &dens {
        sections.push((Tag::DENS, b));
    }
    if let Some(b) = &rads {
        sections.push((Tag::RADS, b));
    }
    if let Some(b) = &loop_bytes {
        sections.push((Tag::LOOP, b));
    }
    if let Some(b) = &hole_bytes {
        sections.push((Tag::HOLE, b));
    }
    if let Some(b) = &rest_bytes {
        sections.push((Tag::REST, b));
    }
    let bytes = write_container(&header, &sections)?;
    let tags = sections.iter().map(|(t, b)| (t.0, b.len())).collect();
    let mut stats = SwingStats::new(
        &head,
        &decoded,
        &conn,
        tags,
        bytes.len(),
        masked,
        rest_counts,
        &retiled.loops,
    );
    stats.density_levels = levels.as_deref().and_then(super::level_range);
    Ok((bytes, stats))
}
