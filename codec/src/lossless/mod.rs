//! The lossless-connectivity mode: the input's own triangles, coded by
//! Edgebreaker, and its positions quantized to `qp` bits on the bounding
//! box and predicted by (multi-)parallelograms in decoding order.
//!
//! Sections (format-spec/04-lossless.md):
//! * `HEAD`: `u8 qp`, `f32 origin[3]`, `f32 range`;
//! * `TOPO`: varus: symbol count, dummy count and dummy vertices
//!   (delta-coded), event count and events;
//! * `CLRS`: the CLERS symbols, range coded with the previous symbol as
//!   context; or in a 1.1 file `CLRD`: the same symbols in Spirale
//!   Reversi's order, each in the context of the decoder's state (the
//!   triangles built around the active gate's two vertices), when that is
//!   smaller — a rule beyond the sources: read backwards a C completes
//!   its tip's fan, so on meshes of regular valence the count all but
//!   names the symbol (bunny-1m at 11 bits: 51,096 → 8,788 bytes; bunny
//!   7,924 → 5,012; the valence-driven coders of Touma–Gotsman and
//!   Draco exploit the same regularity forwards);
//! * `GEOM`: the position residuals (see `geometry::lossless`), or in a
//!   1.1 file `GEOF`: the same with the predictions' offsets as context,
//!   when that is smaller.
//!
//! Encoder and decoder steps that mirror each other sit side by side
//! below, and the small sections' writers beside their readers in
//! `sections` (`HEAD`, `TOPO`, `CLRS`, `CLRD`); each pair must match
//! exactly. The SwingWrapper mode writes and reads its `TOPO` and `CLRS`
//! with the same functions.

use crate::prelude::*;

pub(crate) mod attributes;
mod sections;
use sections::*;
#[cfg(feature = "encoder")]
pub(crate) use sections::{write_clers, write_topo};

#[cfg(test)]
use crate::container::parse_container;
use crate::container::{check_count_fits, Container, Tag, KNOWN_CRITICAL};
#[cfg(feature = "encoder")]
use crate::container::{write_container, Framing, Header, Mode};
use crate::edgebreaker::{self, Connectivity, Side, SplitEvent};
use crate::entropy::Decoder;
#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::geometry::{lossless as geo, Quantizer};
use crate::varint::Reader;
use crate::CornerTable;
use crate::{Error, FormatError, Limits, Malformed, TriMesh};

/// Section sizes and counts of one lossless file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LosslessStats {
    /// Decoded vertices.
    pub vertices: u64,
    /// Decoded triangles.
    pub triangles: u64,
    /// Connected components.
    pub components: u64,
    /// Boundary loops (closed by dummy vertices for coding).
    pub holes: u64,
    /// Handle events (two per handle).
    pub handle_events: u64,
    /// CLERS histogram, in the order C, L, E, R, S.
    pub clers: [u64; 5],
    /// Bytes of each section, in file order.
    pub sections: Vec<([u8; 4], usize)>,
    /// Bytes of the whole file.
    pub file_bytes: usize,
    /// The attribute streams of `ATTR` (format 1.2), in file order;
    /// empty without one.
    pub attributes: Vec<attributes::AttributeInfo>,
}

impl LosslessStats {
    /// The figures of a file with this header, connectivity, number of
    /// holes, sections (tag, bytes) and total size. The encoder and
    /// `inspect` both build their statistics here.
    pub(crate) fn new(
        header: &crate::container::Header,
        conn: &Connectivity,
        holes: usize,
        sections: impl Iterator<Item = ([u8; 4], usize)>,
        file_bytes: usize,
    ) -> Self {
        let mut clers = [0u64; 5];
        for &s in &conn.symbols {
            clers[s as usize] += 1;
        }
        LosslessStats {
            vertices: header.vertex_count as u64,
            triangles: header.triangle_count as u64,
            components: header.component_count as u64,
            holes: holes as u64,
            handle_events: conn.splits.len() as u64,
            clers,
            sections: sections.collect(),
            file_bytes,
            attributes: Vec::new(),
        }
    }
}

#[cfg(feature = "encoder")]
/// Encodes an oriented manifold mesh (a `clean` result) losslessly.
/// Also returns, for each decoded vertex, the input vertex it came from.
pub(crate) fn encode(
    table: &CornerTable,
    mesh: &TriMesh,
    qp: u8,
    framing: Framing,
) -> Result<(Vec<u8>, LosslessStats, Vec<u32>), Error> {
    let prepared = Prepared::new(table, mesh, framing)?;
    let (bytes, stats) = prepared.file(&mesh.positions, qp)?;
    Ok((bytes, stats, prepared.source))
}

#[cfg(feature = "encoder")]
/// [`encode`] of a mesh with attribute streams (one triple per face of
/// `mesh`, as `clean_attributed` gives them): the file also holds them,
/// in `ATTR` (format 1.2), when there is at least one.
pub(crate) fn encode_attributed(
    table: &CornerTable,
    mesh: &TriMesh,
    streams: &[crate::AttributeStream],
    quantization: &crate::options::AttributeQuantization,
    qp: u8,
    framing: Framing,
) -> Result<(Vec<u8>, LosslessStats, Vec<u32>), Error> {
    let prepared = Prepared::build(table, mesh, framing, !streams.is_empty())?;
    let (bytes, stats) = prepared.file_with(&mesh.positions, qp, Some((streams, quantization)))?;
    Ok((bytes, stats, prepared.source))
}

#[cfg(feature = "encoder")]
/// What coding attributes needs of a prepared mesh beyond its
/// positions: the decoder's table, its dummies, the traversal, and
/// which input corner each table corner is.
struct ForAttributes {
    decoded: CornerTable,
    excluded: Vec<bool>,
    order: Vec<crate::VertexId>,
    /// Decoded vertex `k` is input vertex `vertex_order[k]`.
    vertex_order: Vec<u32>,
    /// Per table corner: the input (cleaned) face and its corner 0..3,
    /// or `None` on a dummy's face.
    input_corner: Vec<Option<(u32, u8)>>,
}

#[cfg(feature = "encoder")]
/// Everything of a mesh's lossless file that does not depend on the
/// quantization: its connectivity coded, the decoder's traversal and
/// predictions. A search over quantizations of one mesh (the simplified
/// method's climb over the whole input) makes it once and each file
/// from it ([`Prepared::file`]): on a million triangles the part kept
/// here is about three quarters of an encode. `encode` is `new` then
/// `file`, so the bytes are the same either way.
pub(crate) struct Prepared {
    /// The connectivity (symbols, handle events, components).
    conn: Connectivity,
    /// Dummy vertices in decoding order.
    dummies: Vec<u32>,
    /// The input vertex of each decoded vertex, dummies left out.
    pub source: Vec<u32>,
    /// The input vertex of each vertex in traversal order (`None`: a
    /// dummy's place, which the traversal never visits).
    ordered: Vec<Option<u32>>,
    /// The traversal's predictions, in traversal order.
    predictions: crate::geometry::Predictions,
    /// `TOPO` and the symbols' section.
    topo: Vec<u8>,
    clers: (Tag, Vec<u8>),
    framing: Framing,
    vertices: u32,
    triangles: u32,
    /// Kept only for a file with attributes.
    attributes: Option<Box<ForAttributes>>,
}

#[cfg(feature = "encoder")]
impl Prepared {
    /// Codes `mesh`'s connectivity (`table` is its corner table).
    pub(crate) fn new(
        table: &CornerTable,
        mesh: &TriMesh,
        framing: Framing,
    ) -> Result<Self, Error> {
        Self::build(table, mesh, framing, false)
    }

    /// [`Self::new`] for a mesh whose files carry attribute streams
    /// ([`Self::file_with`]): the simplified method's whole-mesh files
    /// of an attributed input, one per quantization.
    pub(crate) fn with_attributes(
        table: &CornerTable,
        mesh: &TriMesh,
        framing: Framing,
    ) -> Result<Self, Error> {
        Self::build(table, mesh, framing, true)
    }

    /// [`Self::new`], keeping for [`Self::file_with`] what coding
    /// attributes needs when `for_attributes` ([`ForAttributes`]: the
    /// decoder's table, the traversal and which input corner each table
    /// corner is, from Edgebreaker's `tip_corners`: decoded triangle `t`
    /// is the closed input's triangle of `tips[t]`, that corner first).
    fn build(
        table: &CornerTable,
        mesh: &TriMesh,
        framing: Framing,
        for_attributes: bool,
    ) -> Result<Self, Error> {
        let closed = edgebreaker::close_holes(table).table;
        let eb = edgebreaker::encode(&closed)?;
        let conn = eb.connectivity;
        // The decoder's table, built the decoder's way, so predictions
        // match; and the symbols' contexts in `CLRD`.
        let (decoded, contexts) = edgebreaker::decode_recording(&conn)?;
        let real = mesh.vertex_count() as u32;
        // Decoded vertex k is input vertex vertex_order[k]; dummies (ids
        // past the real vertices) carry no position.
        let excluded: Vec<bool> = eb.vertex_order.iter().map(|v| v.0 >= real).collect();
        let source: Vec<u32> = eb
            .vertex_order
            .iter()
            .map(|v| v.0)
            .filter(|&v| v < real)
            .collect();
        let dummies: Vec<u32> = (0..excluded.len() as u32)
            .filter(|&k| excluded[k as usize])
            .collect();
        let topo = write_topo(&conn, &dummies);
        let clers = code_symbols(&conn, &contexts, framing)?;
        // What `geo::encode_mesh_positions` does, with each point taken
        // straight from the input in coding order (decoded vertex k is
        // input vertex vertex_order[k]; the traversal never visits a
        // dummy).
        let traversal = crate::geometry::traverse_except(&decoded, &excluded)?;
        let ordered = traversal
            .order
            .iter()
            .map(|k| Some(eb.vertex_order[k.idx()].0).filter(|&v| v < real))
            .collect();
        let attributes = for_attributes.then(|| {
            let faces = mesh.face_count() as u32;
            let input_corner = eb
                .tip_corners
                .iter()
                .flat_map(|&tip| [tip, tip.next(), tip.prev()])
                .map(|c| (c.0 / 3 < faces).then_some((c.0 / 3, (c.0 % 3) as u8)))
                .collect();
            Box::new(ForAttributes {
                decoded,
                excluded,
                order: traversal.order,
                vertex_order: eb.vertex_order.iter().map(|v| v.0).collect(),
                input_corner,
            })
        });
        Ok(Prepared {
            conn,
            dummies,
            source,
            ordered,
            predictions: traversal.predictions,
            topo,
            clers,
            framing,
            vertices: real,
            triangles: mesh.face_count() as u32,
            attributes,
        })
    }

    /// The file with `positions` (the prepared mesh's, or any of the same
    /// length) quantized to `qp` bits on their bounding box.
    pub(crate) fn file(
        &self,
        positions: &[[f32; 3]],
        qp: u8,
    ) -> Result<(Vec<u8>, LosslessStats), Error> {
        self.file_with(positions, qp, None)
    }

    /// [`Self::file`], with `ATTR` for `attrs` when given (the streams
    /// of the prepared mesh, built with `for_attributes`; none, or a
    /// `Prepared` without them, writes the file without `ATTR`).
    pub(crate) fn file_with(
        &self,
        positions: &[[f32; 3]],
        qp: u8,
        attrs: Option<(
            &[crate::AttributeStream],
            &crate::options::AttributeQuantization,
        )>,
    ) -> Result<(Vec<u8>, LosslessStats), Error> {
        let quantizer = Quantizer::from_positions(positions, qp)?;
        let grid_top = quantizer
            .origin
            .iter()
            .map(|&o| o as f64 + quantizer.range as f64)
            .fold(0.0, f64::max);
        if !quantizer.range.is_finite() || !(grid_top as f32).is_finite() {
            // The cubic grid over the bounding box would not fit in f32.
            return Err(crate::ParameterError::OutOfRange {
                name: "bounding box side",
                value: quantizer.range as f64,
                min: 0.0,
                max: f32::MAX as f64,
            }
            .into());
        }
        let head = write_head(&quantizer);
        let ordered: Vec<[u32; 3]> = self
            .ordered
            .iter()
            .map(|v| {
                v.and_then(|v| positions.get(v as usize))
                    .map_or([0; 3], |&p| quantizer.quantize(p))
            })
            .collect();
        let (geom_tag, geom) = code_positions(&ordered, &self.predictions, qp, self.framing);
        let mut header = Header::new(
            Mode::Lossless,
            self.vertices,
            self.triangles,
            self.conn.components,
        )
        .with_framing(self.framing);
        let mut sections: Vec<(Tag, &[u8])> = vec![
            (Tag::HEAD, &head),
            (Tag::TOPO, &self.topo),
            (self.clers.0, &self.clers.1),
            (geom_tag, &geom),
        ];
        let (attr, infos) = match (attrs, &self.attributes) {
            (Some((streams, q)), Some(kept)) => {
                let grid = kept
                    .vertex_order
                    .iter()
                    .map(|&v| match positions.get(v as usize) {
                        Some(&p) => quantizer.quantize(p).map(i64::from),
                        None => [0; 3],
                    })
                    .collect();
                let frame =
                    attributes::Frame::new(&kept.decoded, &kept.excluded, grid, &kept.order);
                let index: Vec<Vec<u32>> = streams
                    .iter()
                    .map(|s| {
                        kept.input_corner
                            .iter()
                            .map(|ic| match ic {
                                Some((f, k)) => s.corners[*f as usize][*k as usize],
                                None => attributes::NONE,
                            })
                            .collect()
                    })
                    .collect();
                attributes::encode(&frame, streams, &index, q)?
            }
            _ => (Vec::new(), Vec::new()),
        };
        if !infos.is_empty() {
            // ATTR is a 1.2 section; a file without it keeps its version.
            header.minor = header.minor.max(2);
            sections.push((Tag::ATTR, &attr));
        }
        let bytes = write_container(&header, &sections)?;
        let tags = sections.iter().map(|(t, b)| (t.0, b.len()));
        let mut stats =
            LosslessStats::new(&header, &self.conn, self.dummies.len(), tags, bytes.len());
        stats.attributes = infos;
        Ok((bytes, stats))
    }
}

#[cfg(feature = "encoder")]
/// The symbols' section: `CLRS`, or with the compact framing whichever of
/// `CLRS` and `CLRD` is smaller (`CLRS` on a tie).
fn code_symbols(
    conn: &Connectivity,
    contexts: &[u8],
    framing: Framing,
) -> Result<(Tag, Vec<u8>), Error> {
    let clrs = write_clers(&conn.symbols);
    if framing == Framing::Fixed {
        return Ok((Tag::CLRS, clrs));
    }
    let clrd = write_clrd(conn, contexts)?;
    Ok(if clrd.len() < clrs.len() {
        (Tag::CLRD, clrd)
    } else {
        (Tag::CLRS, clrs)
    })
}

#[cfg(feature = "encoder")]
/// The positions' section: `GEOM`, or with the compact framing (a 1.1
/// file anyway) whichever of `GEOM` and `GEOF` is smaller (`GEOM` on a
/// tie). `GEOF`'s offset contexts win on dense scans, where residuals are
/// a grid step or less (bunny-1m at 11 bits: 281,288 → 227,212 bytes),
/// and can lose a few percent on coarse meshes, whose residuals a
/// fraction of a step does not move (fandisk at 8 bits: 3,752 → 4,040);
/// coding both costs a second pass over the residuals, which runs beside
/// the first when there is a second core.
fn code_positions(
    ordered: &[[u32; 3]],
    predictions: &crate::geometry::Predictions,
    qp: u8,
    framing: Framing,
) -> (Tag, Vec<u8>) {
    let code = |coding| {
        let mut enc = Encoder::new();
        geo::encode_positions_as(ordered, predictions, qp, coding, &mut enc);
        enc.finish()
    };
    if framing == Framing::Fixed {
        return (Tag::GEOM, code(geo::Coding::Plain));
    }
    let (plain, offsets) = rayon::join(|| code(geo::Coding::Plain), || code(geo::Coding::Offsets));
    if offsets.len() < plain.len() {
        (Tag::GEOF, offsets)
    } else {
        (Tag::GEOM, plain)
    }
}

/// The positions' section of a mode-0 file: exactly one of `GEOM` (1.0)
/// and `GEOF` (1.1), and the coding it says.
fn positions_section<'a>(file: &Container<'a>) -> Result<(geo::Coding, &'a [u8]), Error> {
    match (file.find(Tag::GEOM), file.find(Tag::GEOF)) {
        (Some(s), None) => Ok((geo::Coding::Plain, s.bytes)),
        (None, Some(s)) => Ok((geo::Coding::Offsets, s.bytes)),
        (Some(_), Some(_)) => Err(bad("both GEOM and GEOF")),
        (None, None) => file
            .require(Tag::GEOM)
            .map(|s| (geo::Coding::Plain, s.bytes)),
    }
}

/// Decodes a lossless-mode file whose container was parsed: the mesh
/// only (an `ATTR` section, which holds nothing the mesh depends on, is
/// not read; [`decode_attributed`] reads it).
pub(crate) fn decode(file: &Container<'_>, limits: &Limits) -> Result<TriMesh, Error> {
    decode_parts(file, limits).map(|(mesh, _)| mesh)
}

/// Decodes a lossless-mode file with its attribute streams (none
/// without `ATTR`).
pub(crate) fn decode_attributed(
    file: &Container<'_>,
    limits: &Limits,
) -> Result<crate::AttributedMesh, Error> {
    let (mesh, parts) = decode_parts(file, limits)?;
    let Some(attr) = file.find(Tag::ATTR) else {
        return Ok(mesh.into());
    };
    let frame = attributes::Frame::new(
        &parts.topo.table,
        &parts.topo.excluded,
        parts.grid,
        &parts.order,
    );
    let streams = attributes::decode(attr.bytes, &frame, limits)?;
    Ok(crate::AttributedMesh::new(mesh, streams))
}

/// What attribute decoding needs beyond the mesh: the connectivity, the
/// traversal order and each table vertex's grid point.
struct Parts {
    topo: Topology,
    order: Vec<crate::VertexId>,
    grid: Vec<[i64; 3]>,
}

/// The mesh of a lossless file, and the parts its attributes are coded
/// over.
fn decode_parts(file: &Container<'_>, limits: &Limits) -> Result<(TriMesh, Parts), Error> {
    let (quantizer, conn, dummies, table) = read_connectivity(file, limits)?;
    let topo = decode_topology(file, &conn, &dummies, table)?;
    // What `geo::decode_mesh_positions` does, with each point dequantized
    // straight into its place instead of through a table by vertex, and
    // in one pass: each vertex's position is decoded as soon as the
    // traversal has its prediction.
    let (coding, geom) = positions_section(file)?;
    let mut dec = Decoder::new(geom)?;
    let mut pd =
        geo::PositionDecoder::new(quantizer.bits, coding, &mut dec, topo.table.vertex_count())?;
    let order =
        crate::geometry::traverse_visiting(&topo.table, &topo.excluded, &mut |p, paras| {
            pd.next(p, paras)
        })?;
    let quantized = pd.into_points();
    dec.finish()?;
    let mut positions = vec![[0f32; 3]; file.header.vertex_count as usize];
    let mut grid = Vec::new();
    if file.find(Tag::ATTR).is_some() {
        grid = vec![[0i64; 3]; topo.table.vertex_count()];
    }
    for (v, q) in order.iter().zip(&quantized) {
        // The traversal decodes exactly the vertices not excluded, so
        // every real vertex gets its point (and the error cannot happen).
        let slot = topo
            .rank
            .get(v.idx())
            .and_then(|&r| positions.get_mut(r as usize))
            .ok_or(bad("a dummy vertex has a position"))?;
        *slot = quantizer.dequantize(*q);
        if let Some(g) = grid.get_mut(v.idx()) {
            *g = q.map(i64::from);
        }
    }
    let mut topo = topo;
    let mesh = TriMesh {
        positions,
        triangles: core::mem::take(&mut topo.triangles),
    };
    Ok((mesh, Parts { topo, order, grid }))
}

/// The decoded connectivity of a lossless file, its dummy vertices
/// dropped.
pub(crate) struct Topology {
    /// The corner table, dummies included.
    table: crate::mesh::CornerTable,
    /// Per table vertex: a dummy.
    excluded: Vec<bool>,
    /// Per table vertex: its number in the output, `u32::MAX` for a dummy.
    rank: Vec<u32>,
    /// The output's triangles (those without a dummy).
    triangles: Vec<[u32; 3]>,
}

/// Decodes the connectivity and checks it against the header's counts:
/// as many vertices and triangles as declared, and every vertex used by
/// a triangle. Both [`decode`] and `inspect` go through here, so that
/// `swm info` refuses what decoding refuses.
pub(crate) fn decode_topology(
    file: &Container<'_>,
    conn: &Connectivity,
    dummies: &[u32],
    table: Option<CornerTable>,
) -> Result<Topology, Error> {
    let table = match table {
        Some(t) => t,
        None => {
            edgebreaker::decode(conn).map_err(|e| vertices_without_dummies(e, dummies.len()))?
        }
    };
    let mut excluded = vec![false; conn.vertices as usize];
    for &d in dummies {
        excluded[d as usize] = true;
    }
    // Real vertices keep their decoded order; dummies are dropped.
    let mut rank = vec![u32::MAX; conn.vertices as usize];
    let mut next = 0u32;
    for (r, &dummy) in rank.iter_mut().zip(&excluded) {
        if !dummy {
            *r = next;
            next += 1;
        }
    }
    let declared = u64::from(file.header.vertex_count);
    if u64::from(next) != declared {
        return Err(mismatch("vertices", declared, next.into()));
    }
    // Sized by the decoded table, not the header: a header that declares
    // more triangles than the sections code is refused below, after
    // allocating only for what was decoded.
    let mut triangles =
        Vec::with_capacity(table.face_count().min(file.header.triangle_count as usize));
    for t in table.vertices().chunks_exact(3) {
        let r = [rank[t[0].idx()], rank[t[1].idx()], rank[t[2].idx()]];
        if !r.contains(&u32::MAX) {
            triangles.push(r);
        }
    }
    let declared = u64::from(file.header.triangle_count);
    if triangles.len() as u64 != declared {
        return Err(mismatch("triangles", declared, triangles.len() as u64));
    }
    // A listed "dummy" that did not close a hole would leave real vertices
    // without triangles; the encoder never writes such a file.
    let mut used = vec![false; next as usize];
    for t in &triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    if used.contains(&false) {
        return Err(bad("a vertex is used by no triangle"));
    }
    Ok(Topology {
        table,
        excluded,
        rank,
        triangles,
    })
}

/// A header count that the data contradicts.
pub(crate) fn mismatch(element: &'static str, declared: u64, found: u64) -> Error {
    FormatError::new(
        "SWM",
        Malformed::CountMismatch {
            element,
            declared,
            found,
        },
    )
    .into()
}

/// The connectivity of a lossless file as read: its symbols, the dummy
/// vertices, and the corner table when reading the symbols (from `CLRD`)
/// already built it.
pub(crate) type Read = (Quantizer, Connectivity, Vec<u32>, Option<CornerTable>);

/// Reads HEAD, TOPO and CLRS or CLRD; also used by `inspect`.
pub(crate) fn read_connectivity(file: &Container<'_>, limits: &Limits) -> Result<Read, Error> {
    // Critical sections of the SwingWrapper mode mean nothing here: every
    // known critical section but mode 0's own.
    const OWN: [Tag; 7] = [
        Tag::HEAD,
        Tag::CLRS,
        Tag::TOPO,
        Tag::GEOM,
        Tag::GEOF,
        Tag::CLRD,
        Tag::ATTR,
    ];
    if KNOWN_CRITICAL
        .iter()
        .any(|t| !OWN.contains(t) && file.find(*t).is_some())
    {
        return Err(crate::FormatError::new(
            "SWM",
            crate::Malformed::BadSyntax("a lossless file has a critical section of mode 1"),
        )
        .into());
    }
    let quantizer = read_head(file.require(Tag::HEAD)?.bytes)?;
    let Some(clrd) = file.find(Tag::CLRD) else {
        let (conn, dummies) = read_topology(file, limits)?;
        return Ok((quantizer, conn, dummies, None));
    };
    if file.find(Tag::CLRS).is_some() {
        return Err(bad("both CLRS and CLRD"));
    }
    let (mut conn, dummies, count) = read_topo(file, limits, clrd.bytes.len())?;
    let table = read_clrd(clrd.bytes, &mut conn, count)
        .map_err(|e| vertices_without_dummies(e, dummies.len()))?;
    Ok((quantizer, conn, dummies, Some(table)))
}

/// A vertex-count error of the closed mesh restated for the file's
/// vertices: the table's count includes the dummies, the header's does
/// not, and the message quotes the header.
fn vertices_without_dummies(mut e: FormatError, dummies: usize) -> Error {
    if let Malformed::CountMismatch {
        declared, found, ..
    } = &mut e.what
    {
        *declared = declared.saturating_sub(dummies as u64);
        *found = found.saturating_sub(dummies as u64);
    }
    Error::from(e)
}

/// Reads TOPO and CLRS (the connectivity and the dummy vertices), with
/// every count checked before allocating. Shared with the SwingWrapper
/// mode, whose TOPO and CLRS are these.
pub(crate) fn read_topology(
    file: &Container<'_>,
    limits: &Limits,
) -> Result<(Connectivity, Vec<u32>), Error> {
    let clrs = file.require(Tag::CLRS)?.bytes;
    let (mut conn, dummies, count) = read_topo(file, limits, clrs.len())?;
    conn.symbols = read_clers(clrs, count)?;
    Ok((conn, dummies))
}

/// Reads `TOPO`, checking its symbol count against the limits and
/// against `clers_len`, the length of the section that codes the
/// symbols. Returns the connectivity without its symbols, the dummy
/// vertices and the symbol count.
pub(crate) fn read_topo(
    file: &Container<'_>,
    limits: &Limits,
    clers_len: usize,
) -> Result<(Connectivity, Vec<u32>, usize), Error> {
    let h = &file.header;
    let mut r = Reader::new(file.require(Tag::TOPO)?.bytes);
    // Counts first, checked before anything sized by them is allocated.
    let symbols = r.varu()?;
    limits.check_faces(symbols)?;
    // The closed mesh has S + C triangles: the header's T plus one per
    // boundary edge, of which there are at most 3T; so S <= 4T. Checked
    // before the symbols are read, so that a lying count allocates no
    // more than the header's counts (which the limits bound) allow.
    if symbols > 4 * u64::from(h.triangle_count) {
        return Err(bad("more CLERS symbols than the header's triangles allow"));
    }
    // Each symbol costs at least -log2(1 - 4/2^16) > 4/2^16 bits: every
    // symbol keeps a frequency of at least 1 in the 2^16 of a model.
    check_count_fits(
        "CLERS symbol",
        symbols,
        clers_len,
        4,
        1 << crate::entropy::PRECISION,
    )?;
    limits.check_alloc(symbols.saturating_mul(40))?;
    let dummy_count = r.varu()?;
    if dummy_count > symbols || dummy_count as usize > r.remaining() {
        return Err(bad("more dummy vertices than the file can hold"));
    }
    let mut dummies = Vec::with_capacity(dummy_count as usize);
    let mut prev = 0u64;
    let overflow = || bad("topology value out of range");
    for i in 0..dummy_count {
        let d = prev
            .checked_add(r.varu()?)
            .and_then(|d| d.checked_add(u64::from(i > 0)))
            .ok_or_else(overflow)?;
        dummies.push(u32::try_from(d).map_err(|_| bad("dummy vertex out of range"))?);
        prev = d;
    }
    let split_count = r.varu()?;
    if split_count > symbols || split_count as usize > r.remaining() / 3 {
        return Err(bad("more handle events than the file can hold"));
    }
    let mut splits = Vec::with_capacity(split_count as usize);
    let mut prev = 0u64;
    for i in 0..split_count {
        let (gap, offset) = (r.varu()?, r.varu()?);
        let split = prev
            .checked_add(gap)
            .and_then(|x| x.checked_add(u64::from(i > 0)))
            .ok_or_else(overflow)?;
        let source = split
            .checked_add(1)
            .and_then(|x| x.checked_add(offset))
            .ok_or_else(overflow)?;
        let side = match r.u8()? {
            0 => Side::Right,
            1 => Side::Left,
            _ => return Err(bad("handle event side is neither 0 nor 1")),
        };
        let (split, source) = (u32::try_from(split), u32::try_from(source));
        let (Ok(split), Ok(source)) = (split, source) else {
            return Err(bad("handle event out of range"));
        };
        splits.push(SplitEvent {
            split,
            source,
            side,
        });
        prev = split as u64;
    }
    r.end()?;
    let total_vertices = h.vertex_count as u64 + dummy_count;
    if total_vertices > u32::MAX as u64 || dummies.iter().any(|&d| d as u64 >= total_vertices) {
        return Err(bad("dummy vertex out of range"));
    }
    let conn = Connectivity {
        symbols: Vec::new(),
        splits,
        components: h.component_count,
        vertices: total_vertices as u32,
    };
    Ok((conn, dummies, symbols as usize))
}

/// Parses and decodes a whole lossless file (for tests).
#[cfg(test)]
pub(crate) fn decode_bytes(bytes: &[u8]) -> Result<TriMesh, Error> {
    let limits = Limits::default();
    decode(&parse_container(bytes, &limits)?, &limits)
}

#[cfg(test)]
mod tests;
