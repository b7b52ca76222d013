//! The lossless-connectivity mode: the input's own triangles, coded by
//! Edgebreaker, and its positions quantized to `qp` bits on the bounding
//! box and predicted by (multi-)parallelograms in decoding order.
//!
//! Sections (format-spec/04-lossless.md):
//! * `HEAD`: `u8 qp`, `f32 origin[3]`, `f32 range`;
//! * `TOPO`: varus: symbol count, dummy count and dummy vertices
//!   (delta-coded), event count and events;
//! * `CLRS`: the CLERS symbols, range coded with the previous symbol as
//!   context;
//! * `GEOM`: the position residuals (see `geometry::lossless`).
//!
//! Encoder and decoder steps that mirror each other sit side by side
//! below; each pair must match exactly. The SwingWrapper mode writes and
//! reads its `TOPO` and `CLRS` with the same functions.

use crate::prelude::*;

#[cfg(test)]
use crate::container::parse_container;
use crate::container::{check_count_fits, Container, Tag, KNOWN_CRITICAL};
#[cfg(feature = "encoder")]
use crate::container::{write_container, Framing, Header, Mode};
use crate::edgebreaker::{self, Connectivity, Side, SplitEvent, Symbol};
#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{ContextModel, Decoder};
use crate::geometry::{lossless as geo, Quantizer};
#[cfg(feature = "encoder")]
use crate::varint;
use crate::varint::Reader;
#[cfg(feature = "encoder")]
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
        }
    }
}

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
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
    let closed = edgebreaker::close_holes(table).table;
    let eb = edgebreaker::encode(&closed)?;
    let conn = &eb.connectivity;
    // The decoder's table, built the decoder's way, so predictions match.
    let decoded = edgebreaker::decode(conn)?;
    let real = mesh.vertex_count() as u32;
    // Decoded vertex k is input vertex vertex_order[k]; dummies (ids past
    // the real vertices) carry no position.
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
    let quantizer = Quantizer::from_positions(&mesh.positions, qp)?;
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
    let topo = write_topo(conn, &dummies);
    let clrs = write_clers(&conn.symbols);
    // What `geo::encode_mesh_positions` does, with each point quantized
    // straight from the input in coding order (decoded vertex k is input
    // vertex vertex_order[k]; the traversal never visits a dummy).
    let traversal = crate::geometry::traverse_except(&decoded, &excluded)?;
    let ordered: Vec<[u32; 3]> = traversal
        .order
        .iter()
        .map(|k| {
            let v = eb.vertex_order[k.idx()];
            mesh.positions
                .get(v.idx())
                .map_or([0; 3], |&p| quantizer.quantize(p))
        })
        .collect();
    let mut enc = Encoder::new();
    geo::encode_positions(&ordered, &traversal.predictions, qp, &mut enc);
    let geom = enc.finish();

    let triangles = mesh.face_count() as u32;
    let header =
        Header::new(Mode::Lossless, real, triangles, conn.components).with_framing(framing);
    let sections: [(Tag, &[u8]); 4] = [
        (Tag::HEAD, &head),
        (Tag::TOPO, &topo),
        (Tag::CLRS, &clrs),
        (Tag::GEOM, &geom),
    ];
    let bytes = write_container(&header, &sections)?;
    let tags = sections.iter().map(|(t, b)| (t.0, b.len()));
    let stats = LosslessStats::new(&header, conn, dummies.len(), tags, bytes.len());
    Ok((bytes, stats, source))
}

/// Decodes a lossless-mode file whose container was parsed.
pub(crate) fn decode(file: &Container<'_>, limits: &Limits) -> Result<TriMesh, Error> {
    let (quantizer, conn, dummies) = read_connectivity(file, limits)?;
    let topo = decode_topology(file, &conn, &dummies)?;
    // What `geo::decode_mesh_positions` does, with each point dequantized
    // straight into its place instead of through a table by vertex.
    let traversal = crate::geometry::traverse_except(&topo.table, &topo.excluded)?;
    let geom = file.require(Tag::GEOM)?.bytes;
    let mut dec = Decoder::new(geom)?;
    let mut quantized = Vec::new();
    geo::decode_positions(
        &traversal.predictions,
        quantizer.bits,
        &mut dec,
        &mut quantized,
    )?;
    dec.finish()?;
    let mut positions = vec![[0f32; 3]; file.header.vertex_count as usize];
    for (v, q) in traversal.order.iter().zip(&quantized) {
        // The traversal decodes exactly the vertices not excluded, so
        // every real vertex gets its point (and the error cannot happen).
        let slot = topo
            .rank
            .get(v.idx())
            .and_then(|&r| positions.get_mut(r as usize))
            .ok_or(bad("a dummy vertex has a position"))?;
        *slot = quantizer.dequantize(*q);
    }
    Ok(TriMesh {
        positions,
        triangles: topo.triangles,
    })
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
) -> Result<Topology, Error> {
    // The table's vertex count includes the dummies; the header's does
    // not, and the message quotes the header.
    let table = edgebreaker::decode(conn).map_err(|mut e| {
        if let Malformed::CountMismatch {
            declared, found, ..
        } = &mut e.what
        {
            *declared = declared.saturating_sub(dummies.len() as u64);
            *found = found.saturating_sub(dummies.len() as u64);
        }
        Error::from(e)
    })?;
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

/// Reads HEAD, TOPO and CLRS; also used by `inspect`.
pub(crate) fn read_connectivity(
    file: &Container<'_>,
    limits: &Limits,
) -> Result<(Quantizer, Connectivity, Vec<u32>), Error> {
    // Critical sections of the SwingWrapper mode mean nothing here: every
    // known critical section but mode 0's own four.
    const OWN: [Tag; 4] = [Tag::HEAD, Tag::CLRS, Tag::TOPO, Tag::GEOM];
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
    let (conn, dummies) = read_topology(file, limits)?;
    Ok((quantizer, conn, dummies))
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

// --- HEAD: written and read side by side; must match exactly. ---

#[cfg(feature = "encoder")]
fn write_head(q: &Quantizer) -> Vec<u8> {
    let mut out = vec![q.bits];
    for x in q.origin.iter().chain([&q.range]) {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out
}

fn read_head(bytes: &[u8]) -> Result<Quantizer, Error> {
    let mut r = Reader::new(bytes);
    let bits = r.u8()?;
    let origin = [r.f32()?, r.f32()?, r.f32()?];
    let range = r.f32()?;
    r.end()?;
    if !(crate::geometry::MIN_BITS..=crate::geometry::MAX_BITS).contains(&bits) {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadHeader("quantization bits out of range"),
        )));
    }
    // Every dequantized point lies between origin and origin + range,
    // which must stay finite in f32.
    let inside = origin
        .iter()
        .all(|&o| o.is_finite() && ((o as f64 + range as f64) as f32).is_finite());
    if !inside || !range.is_finite() || range < 0.0 {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadHeader("quantization grid is not finite"),
        )));
    }
    Ok(Quantizer {
        origin,
        range,
        bits,
    })
}

// --- TOPO writer (reader above, in read_topology). ---

#[cfg(feature = "encoder")]
pub(crate) fn write_topo(conn: &Connectivity, dummies: &[u32]) -> Vec<u8> {
    let mut out = Vec::new();
    varint::put(&mut out, conn.symbols.len() as u64);
    varint::put(&mut out, dummies.len() as u64);
    for (i, &d) in dummies.iter().enumerate() {
        let gap = if i == 0 {
            d as u64
        } else {
            (d - dummies[i - 1] - 1) as u64
        };
        varint::put(&mut out, gap);
    }
    varint::put(&mut out, conn.splits.len() as u64);
    for (i, e) in conn.splits.iter().enumerate() {
        let gap = if i == 0 {
            e.split as u64
        } else {
            (e.split - conn.splits[i - 1].split - 1) as u64
        };
        varint::put(&mut out, gap);
        varint::put(&mut out, (e.source - e.split - 1) as u64);
        out.push(match e.side {
            Side::Right => 0,
            Side::Left => 1,
        });
    }
    out
}

// --- CLRS: the previous symbol is the context; must match exactly. ---

#[cfg(feature = "encoder")]
pub(crate) fn write_clers(symbols: &[Symbol]) -> Vec<u8> {
    let mut enc = Encoder::new();
    let mut model = ContextModel::new(5, 5);
    let mut prev = Symbol::C;
    for &s in symbols {
        enc.encode(model.get(prev as usize), s as u32);
        prev = s;
    }
    enc.finish()
}

fn read_clers(bytes: &[u8], count: usize) -> Result<Vec<Symbol>, Error> {
    let mut dec = Decoder::new(bytes)?;
    let mut model = ContextModel::new(5, 5);
    let mut prev = Symbol::C;
    let mut out = Vec::with_capacity(count);
    for _ in 0..count {
        let code = dec.decode(model.get(prev as usize))?;
        prev = Symbol::from_code(code).ok_or(bad("CLERS code out of range"))?;
        out.push(prev);
    }
    // The stream must end exactly where the encoder finished it.
    dec.finish()?;
    Ok(out)
}

/// Parses and decodes a whole lossless file (for tests).
#[cfg(test)]
pub(crate) fn decode_bytes(bytes: &[u8]) -> Result<TriMesh, Error> {
    let limits = Limits::default();
    decode(&parse_container(bytes, &limits)?, &limits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CleanOptions;

    fn corpus(name: &str) -> Option<TriMesh> {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../shared/corpus")
            .join(name);
        if !path.is_file() {
            println!("skipped: ../shared/corpus not found");
            return None;
        }
        Some(crate::io::read_mesh(&path).unwrap())
    }

    /// Triangles as rotations starting at their smallest vertex, sorted:
    /// equal lists mean the same triangles with the same orientations.
    fn canonical(tris: impl Iterator<Item = [u32; 3]>) -> Vec<[u32; 3]> {
        let mut v: Vec<[u32; 3]> = tris
            .map(|t| {
                let k = (0..3).min_by_key(|&k| t[k]).unwrap();
                [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
            })
            .collect();
        v.sort_unstable();
        v
    }

    /// decode(encode(M)) has exactly M's triangles (through the decoder's
    /// vertex order), positions within half a step, and the connectivity
    /// of the decoded mesh recompresses to the same symbols.
    pub(crate) fn check_roundtrip(name: &str, mesh: &TriMesh, qp: u8) -> usize {
        let c = crate::clean(mesh, &CleanOptions::default()).unwrap();
        let (bytes, stats, source) = encode(&c.table, &c.mesh, qp, Framing::default()).unwrap();
        let again = encode(&c.table, &c.mesh, qp, Framing::default()).unwrap().0;
        assert_eq!(bytes, again, "{name}: encoding is not deterministic");
        let out = decode_bytes(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mapped = out.triangles.iter().map(|t| t.map(|v| source[v as usize]));
        assert_eq!(
            canonical(mapped),
            canonical(c.mesh.triangles.iter().copied()),
            "{name}: triangles differ"
        );
        let q = Quantizer::from_positions(&c.mesh.positions, qp).unwrap();
        let tol = q.step() / 2.0 * (1.0 + 1e-6) + f32::EPSILON as f64 * q.range as f64;
        for (k, p) in out.positions.iter().enumerate() {
            let o = c.mesh.positions[source[k] as usize];
            for a in 0..3 {
                let d = (p[a] as f64 - o[a] as f64).abs();
                assert!(d <= tol, "{name}: vertex {k} axis {a} off by {d} > {tol}");
            }
        }
        let table = CornerTable::new(&out.triangles, out.vertex_count()).unwrap();
        let filled = edgebreaker::fill_holes(&table);
        let closed = CornerTable::new(&filled.triangles, filled.vertex_count).unwrap();
        let recoded = edgebreaker::encode(&closed).unwrap().connectivity;
        let file = parse_container(&bytes, &Limits::default()).unwrap();
        let (_, coded, _) = read_connectivity(&file, &Limits::default()).unwrap();
        assert_eq!(
            recoded.symbols, coded.symbols,
            "{name}: recompression gives other symbols"
        );
        assert_eq!(stats.file_bytes, bytes.len());
        bytes.len()
    }

    #[test]
    fn small_meshes_roundtrip() {
        use crate::edgebreaker::tests_support::*;
        check_roundtrip("tetra", &tetra(), 12);
        check_roundtrip("icosphere", &icosphere(), 8);
        check_roundtrip("torus", &torus(12, 7), 16);
        check_roundtrip("grid", &grid(9, 6), 24);
        check_roundtrip("grid-qp6", &grid(9, 6), 6);
    }

    #[test]
    fn corpus_roundtrips() {
        for name in [
            "fandisk.obj",
            "stanford-bunny.obj",
            "horse.ply",
            "spot.obj",
            "homer.obj",
            "cheburashka.obj",
            "alligator.obj",
            "woody.obj",
            "bunny-1m.ply",
            "cow.obj",
            "teapot.obj",
            "beetle.obj",
            "suzanne.obj",
        ] {
            let Some(mesh) = corpus(name) else { return };
            let bytes = check_roundtrip(name, &mesh, 12);
            println!("{name}: {bytes} bytes at qp 12");
        }
    }

    #[test]
    fn corrupt_files_are_errors() {
        use crate::edgebreaker::tests_support::*;
        let c = crate::clean(&torus(8, 5), &CleanOptions::default()).unwrap();
        let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
        for cut in 0..bytes.len() {
            assert!(decode_bytes(&bytes[..cut]).is_err());
        }
        for bit in 0..bytes.len() * 8 {
            let mut b = bytes.clone();
            b[bit / 8] ^= 1 << (bit % 8);
            assert!(
                decode_bytes(&b).is_err(),
                "bit {bit} flipped and still decoded"
            );
        }
    }

    #[test]
    fn random_overwrites_with_valid_crc_never_panic() {
        use crate::edgebreaker::tests_support::*;
        let c = crate::clean(&torus(10, 6), &CleanOptions::default()).unwrap();
        let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
        let mut rng = crate::mesh::test_rng::Rng(0x9e37_79b9_7f4a_7c15);
        for _ in 0..4000 {
            let b = crate::container::overwrite_randomly(&bytes, &mut rng);
            if let Ok(mesh) = decode_bytes(&b) {
                mesh.validate().unwrap();
            }
        }
    }

    #[test]
    fn absurd_counts_are_refused_before_allocating() {
        use crate::edgebreaker::tests_support::*;
        let c = crate::clean(&torus(10, 6), &CleanOptions::default()).unwrap();
        let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
        // Header counts at offsets 9 (vertices), 13 (triangles), 17 (components).
        for (at, value) in [
            (9, u32::MAX),
            (13, u32::MAX),
            (13, 1 << 28),
            (17, 1 << 27),
            (9, 3),
        ] {
            let mut b = bytes.clone();
            b[at..at + 4].copy_from_slice(&value.to_le_bytes());
            crate::container::fix_crc(&mut b);
            assert!(decode_bytes(&b).is_err(), "count {value} at {at} accepted");
        }
        // A TOPO section claiming 2^40 symbols: its first varu.
        let file = parse_container(&bytes, &Limits::default()).unwrap();
        let topo = file.find(Tag::TOPO).unwrap().offset;
        let mut b = bytes.clone();
        b[topo..topo + 6].copy_from_slice(&[0x80, 0x80, 0x80, 0x80, 0x80, 0x20]);
        crate::container::fix_crc(&mut b);
        assert!(decode_bytes(&b).is_err());
    }

    #[test]
    fn hostile_sections_with_valid_frames_are_errors() {
        use crate::edgebreaker::tests_support::*;
        let c = crate::clean(&grid(6, 4), &CleanOptions::default()).unwrap();
        let bytes = encode(&c.table, &c.mesh, 12, Framing::default()).unwrap().0;
        let file = parse_container(&bytes, &Limits::default()).unwrap();
        let (clrs, topo) = (
            file.section(Tag::CLRS).unwrap().to_vec(),
            file.section(Tag::TOPO).unwrap().to_vec(),
        );
        // CLRS with a word the encoder never wrote.
        let mut longer = clrs.clone();
        longer.extend_from_slice(&[0, 0, 0, 0]);
        assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::CLRS, &longer)).is_err());
        // TOPO whose dummy gaps overflow 64 bits.
        let mut t = Vec::new();
        varint::put(&mut t, topo[0] as u64); // symbol count (one byte for this mesh)
        varint::put(&mut t, 2);
        varint::put(&mut t, u64::MAX);
        varint::put(&mut t, u64::MAX);
        varint::put(&mut t, 0);
        assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::TOPO, &t)).is_err());
        // A grid that does not fit in f32: origin 3e38, range 1e38.
        let mut head = vec![12u8];
        for x in [3e38f32, 0.0, 0.0, 1e38] {
            head.extend_from_slice(&x.to_le_bytes());
        }
        assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::HEAD, &head)).is_err());
        // The unmodified frame still decodes (the helper itself is sound).
        assert!(decode_bytes(&crate::container::with_section(&bytes, Tag::CLRS, &clrs)).is_ok());
    }
}
