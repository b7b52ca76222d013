//! OFF reader and writer, after the Object File Format of Geomview
//! (Geometry Center, University of Minnesota; `OFF(5)` manual page).
//!
//! ```text
//! [ST][C][N]OFF            keyword; may be followed by the counts
//! NVertices NFaces NEdges  NEdges is optional and ignored
//! x y z [normal] [colour] [texture]      one vertex per line
//! n i0 i1 ... i(n-1) [colour]            one face per line, 0-based
//! ```
//!
//! `#` starts a comment anywhere. Extra values after a vertex's x, y, z or
//! after a face's indices (the colours, normals and texture coordinates
//! the keyword prefixes announce) are skipped, so the reader does not need
//! to trust the prefixes; the prefixes alone say which attributes are
//! reported as dropped (`ST` texture coordinates, `C` colours, `N`
//! normals). `4OFF`, `nOFF` and binary OFF are refused.
//!
//! When attributes are asked for, the announced vertex values become
//! per-vertex streams, in the order `OFF(5)` gives them: normal (3),
//! colour (3 or 4, as many as the first vertex has; integers 0..255 when
//! any value exceeds 1, then scaled to 0..1), texture coordinates (2). A
//! vertex with another number of values drops them all (reported); face
//! colours are not vertex attributes and are skipped.
//!
//! Invariants: the counts are checked against the bytes left and the
//! [`Limits`] before any allocation; each vertex and face is one line, so
//! errors carry the line number.

use super::builder::Builder;
use super::text::{self, Text};
use super::Attributes;
use crate::{
    AttributeKind, AttributedMesh, Error, FormatError, Limits, Location, Malformed, TriMesh,
};
use std::io::{self, Write};

const FORMAT: &str = "OFF";

fn error(what: Malformed, line: u64) -> Error {
    FormatError::new(FORMAT, what)
        .at(Location::Line(line))
        .into()
}

/// The next line that holds something besides whitespace and comments,
/// with its number.
fn data_line<'a>(t: &mut Text<'a>) -> Option<(u64, &'a [u8])> {
    while let Some((n, line)) = t.next_line() {
        let line = match line.iter().position(|&b| b == b'#') {
            Some(hash) => &line[..hash],
            None => line,
        };
        if !text::is_blank(line) {
            return Some((n, line));
        }
    }
    None
}

/// Checks the header keyword: optional `ST`, `C`, `N` prefixes, in that
/// order, then `OFF`. The attributes the prefixes announce, or `None`
/// when the word is not a keyword.
fn keyword(word: &[u8], line: u64) -> Result<Option<Attributes>, Error> {
    let mut rest = word;
    let mut announced = [false; 3];
    for (prefix, seen) in [&b"ST"[..], b"C", b"N"].into_iter().zip(&mut announced) {
        if let Some(r) = rest.strip_prefix(prefix) {
            rest = r;
            *seen = true;
        }
    }
    let [uv, colors, normals] = announced;
    match rest {
        b"OFF" => Ok(Some(Attributes {
            uv,
            normals,
            colors,
            generic: false,
        })),
        b"4OFF" | b"nOFF" | b"4nOFF" => Err(error(
            Malformed::Unsupported("OFF with other than 3 dimensions"),
            line,
        )),
        _ => Ok(None),
    }
}

/// The attribute streams of an OFF file being read: `(stream, dims)` for
/// the normal, colour and texture coordinates the keyword announces.
struct VertexValues {
    streams: Vec<(usize, usize)>,
    /// The colour stream, to scale at the end.
    colour: Option<usize>,
}

impl VertexValues {
    /// Adds the streams the keyword announces, the colour's width taken
    /// from the first vertex line (`extra`: its values after x, y, z).
    fn new(
        announced: Attributes,
        extra: usize,
        vertices: u64,
        out: &mut Builder,
    ) -> Result<Self, Error> {
        let normal = if announced.normals { 3 } else { 0 };
        let uv = if announced.uv { 2 } else { 0 };
        let colour = extra.saturating_sub(normal + uv);
        let mut streams = Vec::new();
        let mut colour_stream = None;
        let mut add = |out: &mut Builder, kind, dims: usize| -> Result<usize, Error> {
            let s = out.add_stream(kind, dims as u8, true);
            out.reserve_values(s, vertices, 0)?;
            streams.push((s, dims));
            Ok(s)
        };
        if announced.normals {
            add(out, AttributeKind::Normal, 3)?;
        }
        if announced.colors {
            // Neither RGB nor RGBA: the stream is dropped at the end.
            let s = add(out, AttributeKind::Color(0), colour.clamp(3, 4))?;
            out.streams[s].broken |= !matches!(colour, 3 | 4);
            colour_stream = Some(s);
        }
        if announced.uv {
            add(out, AttributeKind::TexCoord(0), 2)?;
        }
        Ok(VertexValues {
            streams,
            colour: colour_stream,
        })
    }

    /// Adds one vertex's values (the words after x, y, z).
    fn push<'a>(&self, words: impl Iterator<Item = &'a [u8]>, out: &mut Builder) {
        let parsed: Option<Vec<f32>> = words.map(text::parse_f32).collect();
        let width: usize = self.streams.iter().map(|s| s.1).sum();
        let parsed = parsed.filter(|v| v.len() == width);
        let mut at = 0;
        for &(s, dims) in &self.streams {
            let pending = &mut out.streams[s];
            match &parsed {
                Some(v) => pending.stream.values.extend_from_slice(&v[at..at + dims]),
                None => pending.broken = true,
            }
            at += dims;
        }
    }

    /// Scales 0..255 colours to 0..1.
    fn finish(&self, out: &mut Builder) {
        if let Some(s) = self.colour {
            let values = &mut out.streams[s].stream.values;
            if values.iter().any(|&c| c > 1.0) {
                values.iter_mut().for_each(|c| *c /= 255.0);
            }
        }
    }
}

/// Reads an OFF file, with its attributes if `keep`.
pub(super) fn read(
    bytes: &[u8],
    limits: &Limits,
    keep: bool,
) -> Result<(AttributedMesh, Attributes), Error> {
    if let Some(why) = text::not_text(bytes) {
        return Err(FormatError::new(FORMAT, why).into());
    }
    let mut t = Text::new(bytes, 1);
    let Some((n, line)) = data_line(&mut t) else {
        return Err(FormatError::new(FORMAT, Malformed::Empty).into());
    };
    let mut words = text::tokens(line).peekable();
    // Geomview lets the keyword be left out; the counts then come first.
    let first = words.peek().copied().unwrap_or_default();
    let mut counts_line = n;
    let announced = keyword(first, n)?;
    if announced.is_some() {
        words.next();
        if words.peek() == Some(&&b"BINARY"[..]) {
            return Err(error(Malformed::Unsupported("binary OFF"), n));
        }
    } else if text::parse_u64(first).is_none() {
        return Err(error(
            Malformed::BadHeader("the file does not start with OFF"),
            n,
        ));
    }
    let mut counts: Vec<&[u8]> = words.collect();
    if counts.is_empty() {
        let (n, line) = data_line(&mut t).ok_or_else(|| error(Malformed::Truncated, t.line()))?;
        counts_line = n;
        counts = text::tokens(line).collect();
    }
    let count = |k: usize| {
        counts
            .get(k)
            .and_then(|c| text::parse_u64(c))
            .ok_or_else(|| {
                let why = "the counts line needs the vertex and face counts";
                error(Malformed::BadHeader(why), counts_line)
            })
    };
    let (vertices, faces) = (count(0)?, count(1)?);

    // The shortest vertex line is "0 0 0\n", the shortest face "3 0 1 2\n";
    // the last line may lack its newline. As in PLY, each count is checked
    // against all that follows, so that a file cut short is reported as
    // Truncated where it ends, and CountTooLarge means the header lies.
    let left = t.remaining() as u64 + 1;
    let too_large = |element, declared, possible| {
        let what = Malformed::CountTooLarge {
            element,
            declared,
            possible,
        };
        error(what, counts_line)
    };
    if vertices > left / 6 {
        return Err(too_large("vertex", vertices, left / 6));
    }
    if faces > left / 8 {
        return Err(too_large("face", faces, left / 8));
    }
    let mut out = Builder::new(limits);
    let announced = announced.unwrap_or_default();
    if !keep {
        out.dropped = announced;
    }
    out.reserve_vertices(vertices)?;
    out.reserve_triangles(faces)?;
    let mut attributes: Option<VertexValues> = None;

    for i in 0..vertices {
        let (n, line) = data_line(&mut t).ok_or_else(|| error(Malformed::Truncated, t.line()))?;
        let mut p = [0f32; 3];
        let mut words = text::tokens(line);
        for c in &mut p {
            let word = words.next().ok_or_else(|| {
                error(Malformed::BadSyntax("a vertex needs three coordinates"), n)
            })?;
            *c = text::parse_f32(word).ok_or_else(|| error(Malformed::BadNumber, n))?;
        }
        if !p.iter().all(|c| c.is_finite()) {
            return Err(error(Malformed::NonFinite { vertex: i }, n));
        }
        out.mesh.positions.push(p);
        if keep && !announced.is_empty() {
            let values = match attributes.take() {
                Some(v) => v,
                None => VertexValues::new(announced, words.clone().count(), vertices, &mut out)?,
            };
            values.push(words, &mut out);
            attributes = Some(values);
        }
    }
    if let Some(values) = &attributes {
        values.finish(&mut out);
    }
    for _ in 0..faces {
        let (n, line) = data_line(&mut t).ok_or_else(|| error(Malformed::Truncated, t.line()))?;
        let mut words = text::tokens(line);
        let size = words
            .next()
            .and_then(text::parse_u64)
            .ok_or_else(|| error(Malformed::BadNumber, n))?;
        if size < 3 {
            return Err(error(Malformed::FaceTooSmall { count: size }, n));
        }
        let mut index = || {
            let word = words.next().ok_or_else(|| {
                error(
                    Malformed::BadSyntax("a face has fewer indices than its count"),
                    n,
                )
            })?;
            let i = text::parse_i64(word).ok_or_else(|| error(Malformed::BadNumber, n))?;
            match u32::try_from(i) {
                Ok(v) if u64::from(v) < vertices => Ok(v),
                _ => Err(error(Malformed::IndexOutOfRange { index: i, vertices }, n)),
            }
        };
        let first = index()?;
        let mut prev = index()?;
        for _ in 2..size {
            let next = index()?;
            out.mesh.triangles.push([first, prev, next]);
            prev = next;
        }
        if size > 3 {
            out.check_growth()?;
        }
    }
    // Whatever follows the faces is ignored: some writers append edges.
    Ok(out.finish())
}

/// Writes OFF with shortest round-trip decimals.
pub(super) fn write<W: Write>(w: &mut W, mesh: &TriMesh) -> io::Result<()> {
    writeln!(
        w,
        "OFF\n{} {} 0",
        mesh.positions.len(),
        mesh.triangles.len()
    )?;
    for [x, y, z] in &mesh.positions {
        writeln!(w, "{x} {y} {z}")?;
    }
    for [a, b, c] in &mesh.triangles {
        writeln!(w, "3 {a} {b} {c}")?;
    }
    Ok(())
}

/// Writes OFF with the attributes it has prefixes for, one vertex per
/// distinct position and values (see `AttributedMesh::split_vertices`):
/// `[ST][C][N]OFF`, each vertex `x y z [nx ny nz] [r g b [a]] [s t]` in
/// floats. Returns what OFF cannot hold (texture sets past 0, a third
/// texture coordinate, colour sets past 0, generic streams), which is not
/// written. Without any stream it can hold, the file is [`write`]'s.
pub(super) fn write_attributed<W: Write>(w: &mut W, m: &AttributedMesh) -> io::Result<Attributes> {
    let (split, unwritten) = super::attributes::split_kept(m, super::attributes::per_vertex);
    let Some(split) = split else {
        write(w, &m.mesh)?;
        return Ok(unwritten);
    };
    // In the order of the keyword's prefixes, reversed on the line.
    let normal = split.stream(AttributeKind::Normal);
    let colour = split.stream(AttributeKind::Color(0));
    let uv = split
        .stream(AttributeKind::TexCoord(0))
        .filter(|s| s.dims == 2);
    let keyword = [
        (uv.is_some(), "ST"),
        (colour.is_some(), "C"),
        (normal.is_some(), "N"),
    ];
    for (present, prefix) in keyword {
        if present {
            w.write_all(prefix.as_bytes())?;
        }
    }
    writeln!(
        w,
        "OFF\n{} {} 0",
        split.mesh.positions.len(),
        split.mesh.triangles.len()
    )?;
    for (v, [x, y, z]) in split.mesh.positions.iter().enumerate() {
        write!(w, "{x} {y} {z}")?;
        for s in [normal, colour, uv].into_iter().flatten() {
            for c in s.value(v as u32) {
                write!(w, " {c}")?;
            }
        }
        writeln!(w)?;
    }
    for [a, b, c] in &split.mesh.triangles {
        writeln!(w, "3 {a} {b} {c}")?;
    }
    Ok(unwritten)
}

#[cfg(test)]
mod tests {
    use super::super::tests::{malformed, read};
    use super::super::MeshFormat;
    use super::*;

    fn off(text: &str) -> Result<TriMesh, Error> {
        read(text.as_bytes(), MeshFormat::Off)
    }

    #[test]
    fn variants_and_extras() {
        let square = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let files = [
            "OFF\n4 1 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
            // Counts on the keyword line, comments, blank lines, CRLF.
            "# a square\r\nOFF 4 1 0 # counts\r\n\r\n0 0 0\r\n1 0 0\r\n# between\r\n1 1 0\r\n0 1 0\r\n4 0 1 2 3\r\n",
            // Colours per vertex and per face.
            "COFF\n4 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 9\n4 0 1 2 3 0.5 0.5 0.5\n",
            // Normals, and normals plus colours.
            "NOFF\n4 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n4 0 1 2 3\n",
            "CNOFF\n4 1 0\n0 0 0 0 0 1 1 1 1 1\n1 0 0 0 0 1 1 1 1 1\n1 1 0 0 0 1 1 1 1 1\n0 1 0 0 0 1 1 1 1 1\n4 0 1 2 3\n",
            "STOFF\n4 1 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n",
            // No keyword, no trailing newline.
            "4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3",
        ];
        for text in files {
            let mesh = off(text).unwrap_or_else(|e| panic!("{text:?}: {e}"));
            assert_eq!(mesh.positions, square, "{text:?}");
            assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]], "{text:?}");
        }
    }

    /// `\n`, `\r\n` and a lone `\r` end lines alike: the same mesh, and
    /// an error on the same line.
    #[test]
    fn every_line_ending_reads_alike() {
        let text = "OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n\n1 1 0\n0 1 0\n4 0 1 2 3\n";
        let bad = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n# end\n";
        for eol in ["\n", "\r\n", "\r"] {
            let mesh = off(&text.replace('\n', eol)).unwrap_or_else(|e| panic!("{eol:?}: {e}"));
            assert_eq!(mesh.positions.len(), 4, "{eol:?}");
            assert_eq!(mesh.positions[2], [1.0, 1.0, 0.0], "{eol:?}");
            assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]], "{eol:?}");
            let (_, at) = malformed(off(&bad.replace('\n', eol)));
            assert_eq!(at, Some(Location::Line(6)), "{eol:?}");
        }
    }

    #[test]
    fn malformed_files() {
        // Each file ends in a comment so that the counts check (a face
        // line takes at least 8 bytes) does not catch the bad face first.
        let cases: [(&str, Malformed, u64); 12] = [
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                Malformed::IndexOutOfRange {
                    index: 3,
                    vertices: 3,
                },
                6,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                Malformed::IndexOutOfRange {
                    index: -1,
                    vertices: 3,
                },
                6,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                Malformed::FaceTooSmall { count: 2 },
                6,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
                Malformed::BadSyntax("a face has fewer indices than its count"),
                6,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n",
                Malformed::NonFinite { vertex: 1 },
                4,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n",
                Malformed::NonFinite { vertex: 2 },
                5,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\n3 0 1 2\n",
                Malformed::BadSyntax("a vertex needs three coordinates"),
                5,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n",
                Malformed::BadNumber,
                4,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n",
                Malformed::BadNumber,
                6,
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
                Malformed::IndexOutOfRange {
                    index: 0,
                    vertices: 0,
                },
                0,
            ),
            (
                "OFF\n3\n",
                Malformed::BadHeader("the counts line needs the vertex and face counts"),
                2,
            ),
            (
                "OFX\n3 1 0\n",
                Malformed::BadHeader("the file does not start with OFF"),
                1,
            ),
        ];
        for (text, what, line) in cases {
            let text = &format!("{text}# padding\n");
            if line == 0 {
                // Extra faces after the declared ones are ignored.
                assert!(off(text).is_ok());
                continue;
            }
            assert_eq!(
                malformed(off(text)),
                (what, Some(Location::Line(line))),
                "{text:?}"
            );
        }
        assert_eq!(
            malformed(off("4OFF\n")).0,
            Malformed::Unsupported("OFF with other than 3 dimensions")
        );
        assert_eq!(
            malformed(off("OFF BINARY\n")).0,
            Malformed::Unsupported("binary OFF")
        );
        // Cut short: the lines run out.
        let (what, _) = malformed(off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
        assert_eq!(what, Malformed::Truncated);
        // Counts the rest of the file cannot hold.
        let (what, at) = malformed(off("OFF\n2000000000 2000000000 0\n0 0 0\n"));
        let too_large = Malformed::CountTooLarge {
            element: "vertex",
            declared: 2_000_000_000,
            possible: 1,
        };
        assert_eq!((what, at), (too_large, Some(Location::Line(2))));
        let (what, _) = malformed(off("OFF\n3 99 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
        assert!(matches!(
            what,
            Malformed::CountTooLarge {
                element: "face",
                ..
            }
        ));
    }
}
