//! Decoding a SwingWrapper file: `HEAD`, then the connectivity (`TOPO`,
//! `CLRS`, shared with the lossless mode), then the angle codes (`GEOM`)
//! and the one pass that rebuilds the vertices; then the hole mask
//! (`HOLE`) drops triangles and the lossless remainder (`REST`) adds
//! some. A file with `CLRF` instead decodes in the forward pass alone
//! ([`super::forward`]): symbols, vertices, triangles and mask bits
//! together. Every count is checked before anything sized by it is
//! allocated.

use crate::prelude::*;

use super::chain::{self, Loops};

use super::{angle, density, hole, residual, stretch, SwingStats, MAX_ANGLE_BITS, MIN_ANGLE_BITS};
use crate::container::{
    check_count_fits, in_section, parse_container, Container, Mode, Section, Tag,
};
use crate::edgebreaker::{self, Connectivity, Symbol};
use crate::varint::Reader;
use crate::{CornerTable, Error, FormatError, Limits, Malformed, TriMesh};

/// Bytes of `HEAD` before the first triangles: `K` and `q_pred`.
const HEAD_FIXED_LEN: usize = 3;
/// Bytes of one component's first triangle in `HEAD`: nine f32.
const FIRST_LEN: usize = 36;

/// The parameters in `HEAD`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Head {
    /// Angle bits K.
    pub bits: u8,
    /// The predicted code q_pred.
    pub predicted: u32,
    /// Each component's first triangle (corners 3t, 3t+1, 3t+2), read
    /// from f32.
    pub first: Vec<[[f64; 3]; 3]>,
}

fn bad_header(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadHeader(why)))
}

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// Writes `HEAD`; [`read_head`] must match it exactly.
#[cfg(feature = "encoder")]
pub(crate) fn write_head(head: &Head) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEAD_FIXED_LEN + FIRST_LEN * head.first.len());
    out.push(head.bits);
    out.extend_from_slice(&(head.predicted as u16).to_le_bytes());
    for p in head.first.iter().flatten().flatten() {
        out.extend_from_slice(&(*p as f32).to_le_bytes());
    }
    out
}

/// Reads and checks `HEAD` for a file of `components` components.
pub(crate) fn read_head(bytes: &[u8], components: u32) -> Result<Head, Error> {
    let mut r = Reader::new(bytes);
    let bits = r.u8()?;
    let predicted = u32::from(r.u8()?) | u32::from(r.u8()?) << 8;
    if !(MIN_ANGLE_BITS..=MAX_ANGLE_BITS).contains(&bits) {
        return Err(bad_header("angle bits out of range"));
    }
    if predicted >> bits != 0 {
        return Err(bad_header("predicted angle code out of range"));
    }
    // The length first, so that the allocation is bounded by the file.
    let expected = HEAD_FIXED_LEN as u64 + FIRST_LEN as u64 * u64::from(components);
    match (bytes.len() as u64).cmp(&expected) {
        core::cmp::Ordering::Less => {
            return Err(FormatError::new("SWM", Malformed::Truncated).into())
        }
        core::cmp::Ordering::Greater => {
            return Err(FormatError::new("SWM", Malformed::TrailingData).into())
        }
        core::cmp::Ordering::Equal => {}
    }
    let mut first = Vec::with_capacity(components as usize);
    for _ in 0..components {
        let mut f = [[0.0; 3]; 3];
        for p in &mut f {
            for x in p.iter_mut() {
                let v = r.f32()?;
                if !v.is_finite() {
                    return Err(bad_header("first vertex is not finite"));
                }
                *x = f64::from(v);
            }
        }
        first.push(f);
    }
    r.end()?;
    if let Some(f) = first.first() {
        // sqrt of a sum of squares of differences of f32 values: finite.
        if angle::first_edge_length(f) == 0.0 {
            return Err(bad_header("the first gate has length zero"));
        }
    }
    Ok(Head {
        bits,
        predicted,
        first,
    })
}

/// What the forward pass of `CLRF` read on its way that [`inspect`]
/// reports (a `CLRS` file decodes it from the corner table instead).
pub(super) struct Tips {
    pub levels: Option<Vec<i8>>,
}

/// Reads `HEAD`, `TOPO` and `CLRS` or `CLRF` and decodes the
/// connectivity; with `CLRF`, also the tips' codes and levels.
pub(super) fn read_connectivity(
    file: &Container<'_>,
    limits: &Limits,
) -> Result<(Head, Connectivity, CornerTable, Option<Tips>), Error> {
    let h = &file.header;
    let head = read_checked_head(file)?;
    // (A file with both CLRS and CLRF was refused with its head.)
    let (conn, dummies, tips) = match file.find(Tag::CLRF) {
        None => {
            let (conn, dummies) = crate::lossless::read_topology(file, limits)?;
            (conn, dummies, None)
        }
        Some(_) => {
            let (conn, d, _) = read_forward(file, limits, &head, false, true)?;
            let tips = Tips { levels: d.levels };
            (conn, Vec::new(), Some(tips))
        }
    };
    if !dummies.is_empty() {
        return Err(bad("a SwingWrapper file has no dummy vertices"));
    }
    if conn.triangles() != u64::from(h.triangle_count) {
        let declared = h.triangle_count.into();
        return Err(crate::lossless::mismatch(
            "triangles",
            declared,
            conn.triangles(),
        ));
    }
    let table = edgebreaker::decode(&conn)?;
    Ok((head, conn, table, tips))
}

/// `HEAD`, once the file is known to hold no section of mode 0.
fn read_checked_head(file: &Container<'_>) -> Result<Head, Error> {
    if file.find(Tag::GEOF).is_some() || file.find(Tag::CLRD).is_some() {
        // Mode 0's positions mean nothing here (05-swing.md, check 1).
        return Err(bad("a SwingWrapper file has a critical section of mode 0"));
    }
    if file.find(Tag::CLRS).is_some() && file.find(Tag::CLRF).is_some() {
        return Err(bad("a file with both CLRS and CLRF"));
    }
    read_head(file.require(Tag::HEAD)?.bytes, file.header.component_count)
}

/// Reads `TOPO` for `CLRF` and runs the forward pass over `CLRF`, `GEOM`,
/// `DENS`, `RADS` and `LOOP` (and `HOLE` when `hole`): what the pass
/// decoded on its way, the mesh's triangles among them (and the symbols,
/// codes and levels when `record`); also `LOOP`'s list. Every count is
/// checked before the pass allocates.
pub(super) fn read_forward<'a>(
    file: &Container<'a>,
    limits: &Limits,
    head: &Head,
    hole: bool,
    record: bool,
) -> Result<(Connectivity, super::forward::Decoded, Loops), Error> {
    let h = &file.header;
    let clrf = file.require(Tag::CLRF)?;
    let (mut conn, dummies, count) = crate::lossless::read_topo(file, limits, clrf.bytes.len())?;
    if !dummies.is_empty() {
        return Err(bad("a SwingWrapper file has no dummy vertices"));
    }
    // The counts the header declares, checked against TOPO's before
    // anything is sized by them: T = S + C, and every vertex is a first
    // vertex or a C tip, so V ≤ 3C + S.
    let components = u64::from(h.component_count);
    let triangles = count as u64 + components;
    if triangles != u64::from(h.triangle_count) {
        let declared = h.triangle_count.into();
        return Err(crate::lossless::mismatch("triangles", declared, triangles));
    }
    if u64::from(h.vertex_count) > 3 * components + count as u64 {
        return Err(bad("more vertices than the symbols can place"));
    }
    let vertices = h.vertex_count as usize;
    // Per vertex: a position, a residual length, a level and two flags
    // (step, radius code); per symbol: up to two nodes of 21 bytes, the
    // symbol, a code, a level, a radius code, a triangle and a mask bit.
    let (v, s) = (vertices as u64, count as u64);
    limits.check_alloc(v.saturating_mul(29).saturating_add(s.saturating_mul(65)))?;
    let geom = file.require(Tag::GEOM)?;
    let dens = file.find(Tag::DENS).map(|s| s.bytes);
    let rads = file.find(Tag::RADS).map(|s| s.bytes);
    let hole = if hole { file.find(Tag::HOLE) } else { None };
    let (list, reader) = read_loops(file, head.bits)?;
    let points = reader.map(|r| points(&list, r, head));
    let mut d = super::forward::decode(
        clrf.bytes,
        geom.bytes,
        dens,
        rads,
        hole.map(|s| s.bytes),
        record,
        &head.first,
        head.bits,
        head.predicted,
        vertices,
        count,
        points,
    )
    .map_err(in_section(clrf.offset))?;
    conn.symbols = core::mem::take(&mut d.symbols);
    Ok((conn, d, list))
}

/// `LOOP`'s entries and code stream in a file of `bits` angle bits; no
/// entries and no stream without the section.
fn read_loops<'a>(
    file: &Container<'a>,
    bits: u8,
) -> Result<(Loops, Option<chain::Reader<'a>>), Error> {
    let Some(s) = file.find(Tag::LOOP) else {
        return Ok((Loops::default(), None));
    };
    let h = &file.header;
    let (list, reader) = chain::read(
        s.bytes,
        u64::from(h.component_count),
        u64::from(h.vertex_count),
        bits,
    )
    .map_err(in_section(s.offset))?;
    Ok((list, Some(reader)))
}

/// The loop points of a file with `LOOP`, at its angle bits.
fn points<'a>(list: &'a Loops, reader: chain::Reader<'a>, head: &Head) -> chain::Points<'a> {
    chain::Points::new(
        list,
        chain::Residuals::Stream(Box::new(reader)),
        head.bits,
        head.predicted,
    )
}

/// Parses `REST`: a complete lossless (mode 0) file, checked down to its
/// section table (no recursion: a nested SwingWrapper file, or a nested
/// file with its own `HOLE` or `REST`, is malformed). Allocates nothing.
fn read_rest<'a>(section: Section<'a>, limits: &Limits) -> Result<Container<'a>, Error> {
    let check = |rest: Container<'a>| {
        if rest.header.mode != Mode::Lossless {
            return Err(bad("REST does not hold a lossless (mode 0) file"));
        }
        if rest.find(Tag::HOLE).is_some() || rest.find(Tag::REST).is_some() {
            return Err(bad("the file in REST has a HOLE or REST section"));
        }
        Ok(rest)
    };
    parse_container(section.bytes, limits)
        .and_then(check)
        .map_err(in_section(section.offset))
}

/// Vertices and triangles of `REST` (0, 0 without one), from its header:
/// what `decode` appends to the retiled mesh.
pub(crate) fn rest_counts(file: &Container<'_>, limits: &Limits) -> Result<(u64, u64), Error> {
    Ok(match file.find(Tag::REST) {
        Some(s) => {
            let h = read_rest(s, limits)?.header;
            (u64::from(h.vertex_count), u64::from(h.triangle_count))
        }
        None => (0, 0),
    })
}

/// `REST`'s container and offset, if there is one, after checking that
/// the retiled mesh and REST's together fit the limits.
fn rest_frame<'a>(
    file: &Container<'a>,
    limits: &Limits,
) -> Result<Option<(Container<'a>, usize)>, Error> {
    let Some(s) = file.find(Tag::REST) else {
        return Ok(None);
    };
    let rest = read_rest(s, limits)?;
    let (h, r) = (&file.header, &rest.header);
    let vertices = u64::from(h.vertex_count) + u64::from(r.vertex_count);
    limits.check_vertices(vertices)?;
    limits.check_faces(u64::from(h.triangle_count) + u64::from(r.triangle_count))?;
    if vertices > u64::from(u32::MAX) {
        return Err(bad("more than 2^32 - 1 vertices with REST's"));
    }
    Ok(Some((rest, s.offset)))
}

/// Decodes a SwingWrapper file whose container was parsed.
pub(crate) fn decode(file: &Container<'_>, limits: &Limits) -> Result<TriMesh, Error> {
    if file.find(Tag::CLRF).is_some() {
        return decode_forward(file, limits);
    }
    let (head, conn, table, _) = read_connectivity(file, limits)?;
    // REST's frame first: the whole output must fit the limits before
    // anything is decoded.
    let rest = rest_frame(file, limits)?;
    let geom = file.require(Tag::GEOM)?.bytes;
    let count = conn.symbols.iter().filter(|&&s| s == Symbol::C).count();
    // A length costs more than K/2^16 bits: its model has K + 1 symbols.
    check_count_fits(
        "angle",
        count as u64,
        geom.len(),
        u64::from(head.bits),
        1 << crate::entropy::PRECISION,
    )?;
    // f64 and f32 positions, a length and a radius flag per vertex, a
    // code, a level and a radius code per C tip; a mask bit per triangle
    // and a new number per vertex.
    let (v, t) = (table.vertex_count() as u64, table.face_count() as u64);
    limits.check_alloc(v.saturating_mul(46).saturating_add(t.saturating_mul(18)))?;
    let codes = residual::decode(&table, geom, count, head.bits, head.predicted)?;
    let levels = read_levels(file, &table, count)?;
    let radii = read_stretch(file, &table, count, head.bits)?;
    let (list, reader) = read_loops(file, head.bits)?;
    let mut points = reader.map(|r| points(&list, r, &head));
    let x = super::rebuild::rebuild_positions(
        &table,
        &head.first,
        head.bits,
        &codes,
        levels.as_deref(),
        radii.as_deref(),
        points.as_mut(),
    )?;
    if let Some(p) = points {
        p.finish()?;
    }
    let positions = x.iter().map(|p| p.map(|c| c as f32)).collect();
    let triangles = table.triangles();
    if triangles.len() != file.header.triangle_count as usize {
        let declared = file.header.triangle_count.into();
        return Err(crate::lossless::mismatch(
            "triangles",
            declared,
            triangles.len() as u64,
        ));
    }
    let mut mesh = TriMesh {
        positions,
        triangles,
    };
    // Dropped: the triangles HOLE masks, and the fans of the loops.
    let mask = match file.find(Tag::HOLE) {
        Some(s) => Some(hole::decode(&table, s.bytes).map_err(in_section(s.offset))?),
        None => None,
    };
    if let Some(mask) = hole::dropped(mask, &mesh.triangles, &list) {
        mesh = hole::drop_masked(mesh, &mask)?;
    }
    append_rest(mesh, rest, limits)
}

/// Decodes a file with `CLRF` in one pass (format-spec/05-swing.md,
/// "CLRF"): the forward pass reads the symbols, places every vertex,
/// builds every triangle and reads `HOLE`'s bits as it goes, so there is
/// no corner table to build and no second walk over the triangles.
fn decode_forward(file: &Container<'_>, limits: &Limits) -> Result<TriMesh, Error> {
    let head = read_checked_head(file)?;
    let (_, d, loops) = read_forward(file, limits, &head, true, false)?;
    // REST's frame first: the whole output must fit the limits before
    // it is decoded.
    let rest = rest_frame(file, limits)?;
    let geom = file.require(Tag::GEOM)?.bytes;
    check_count_fits(
        "angle",
        d.c_tips as u64,
        geom.len(),
        u64::from(head.bits),
        1 << crate::entropy::PRECISION,
    )?;
    // f32 positions, and a new number per vertex when some are dropped.
    limits.check_alloc((d.positions.len() as u64).saturating_mul(16))?;
    // Dropped: the triangles HOLE masks, and the fans of the loops.
    let mesh = match hole::dropped(d.mask, &d.triangles, &loops) {
        Some(mask) => hole::drop_masked_from(&d.positions, d.triangles, &mask)?,
        None => TriMesh {
            positions: d.positions.iter().map(|p| p.map(|c| c as f32)).collect(),
            triangles: d.triangles,
        },
    };
    append_rest(mesh, rest, limits)
}

/// Appends `REST`'s mesh (if any) to the retiled one, its vertex numbers
/// moved past the retiled mesh's.
fn append_rest(
    mut mesh: TriMesh,
    rest: Option<(Container<'_>, usize)>,
    limits: &Limits,
) -> Result<TriMesh, Error> {
    if let Some((rest, offset)) = &rest {
        let kept = crate::lossless::decode(rest, limits).map_err(in_section(*offset))?;
        // Checked against the limits (`rest_frame`): both counts are
        // below 2^32.
        let first = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&kept.positions);
        mesh.triangles
            .extend(kept.triangles.iter().map(|t| t.map(|v| v + first)));
    }
    Ok(mesh)
}

/// One value per C tip from the section `tag` (`None` without one),
/// decoded by `decode` from its payload once `count` values of at least
/// 1/2^16 bit each (a binary or ternary adaptive symbol per tip keeps
/// every frequency at least 1) are known to fit its length.
fn read_per_tip<T>(
    file: &Container<'_>,
    tag: Tag,
    what: &'static str,
    count: usize,
    decode: impl FnOnce(&[u8]) -> Result<Vec<T>, Error>,
) -> Result<Option<Vec<T>>, Error> {
    let Some(s) = file.find(tag) else {
        return Ok(None);
    };
    check_count_fits(
        what,
        count as u64,
        s.bytes.len(),
        1,
        1 << crate::entropy::PRECISION,
    )
    .map_err(|e| in_section(s.offset)(e.into()))?;
    decode(s.bytes).map(Some).map_err(in_section(s.offset))
}

/// The level of each of the `count` C tips, from `DENS` (`None` without
/// one); the count is checked against the section's length first.
pub(super) fn read_levels(
    file: &Container<'_>,
    table: &CornerTable,
    count: usize,
) -> Result<Option<Vec<i8>>, Error> {
    read_per_tip(file, Tag::DENS, "level step", count, |b| {
        density::decode(table, b, count)
    })
}

/// The radius code of each of the `count` C tips, from `RADS` (`None`
/// without one); the count is checked against the section's length
/// first.
pub(super) fn read_stretch(
    file: &Container<'_>,
    table: &CornerTable,
    count: usize,
    bits: u8,
) -> Result<Option<Vec<i32>>, Error> {
    read_per_tip(file, Tag::RADS, "radius code", count, |b| {
        stretch::decode(table, bits, b, count)
    })
}

/// The figures of a SwingWrapper file, read without decoding geometry:
/// the hole mask is decoded (it needs only the corner table), `REST` is
/// parsed down to its section table. A `CLRF` file is the exception: its
/// symbols come out of the forward pass, which decodes `GEOM` and places
/// every tip on its way.
pub(crate) fn inspect(
    file: &Container<'_>,
    limits: &Limits,
    file_bytes: usize,
) -> Result<(Connectivity, SwingStats), Error> {
    let (head, conn, table, tips) = read_connectivity(file, limits)?;
    let (loops, _) = read_loops(file, head.bits)?;
    let fans = chain::fans(&table, &loops);
    // Masked over patches: HOLE's bits outside the loops' fans.
    let masked = match file.find(Tag::HOLE) {
        Some(s) => hole::decode(&table, s.bytes)
            .map_err(in_section(s.offset))?
            .iter()
            .zip(&fans)
            .filter(|(&m, &f)| m && !f)
            .count() as u64,
        None => 0,
    };
    // As strict as `decode` about REST's counts too: its frame against
    // the limits, its connectivity against its header.
    let rest_counts = match rest_frame(file, limits)? {
        Some((rest, offset)) => {
            let check = || {
                let (_, conn, dummies, table) = crate::lossless::read_connectivity(&rest, limits)?;
                crate::lossless::decode_topology(&rest, &conn, &dummies, table)?;
                Ok::<_, Error>(conn.components)
            };
            let components = check().map_err(in_section(offset))?;
            (u64::from(rest.header.triangle_count), u64::from(components))
        }
        None => (0, 0),
    };
    let sections = file.sections().map(|s| (s.tag.0, s.bytes.len())).collect();
    // The density needs only the corner table, like the mask.
    let count = conn.symbols.iter().filter(|&&s| s == Symbol::C).count();
    let levels = match tips {
        Some(t) => t.levels,
        None => read_levels(file, &table, count)?,
    };
    let mut stats = SwingStats::new(
        &head,
        &table,
        &conn,
        sections,
        file_bytes,
        masked,
        rest_counts,
        &loops,
    );
    stats.density_levels = levels.as_deref().and_then(super::level_range);
    Ok((conn, stats))
}

impl SwingStats {
    /// The figures of a file: its header fields, decoded corner table,
    /// symbols, sections, masked triangles and triangles of `REST`. The
    /// writer and `inspect` both build them here.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        head: &Head,
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
            edge_length: head.first.first().map_or(0.0, super::first_edge_length),
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
