//! STL reader and writer, after 3D Systems' StereoLithography Interface
//! Specification (1989; "SLA-1 ... STL format").
//!
//! ```text
//! binary: 80-byte header, u32 triangle count, then per triangle
//!         normal (3 x f32), 3 corners (3 x 3 x f32), u16 attribute: 50 bytes
//! ASCII:  solid name
//!           facet normal nx ny nz
//!             outer loop
//!               vertex x y z      (three times)
//!             endloop
//!           endfacet ...
//!         endsolid name
//! ```
//!
//! STL has no shared vertices: each triangle gets its own three vertices
//! here, in file order, and merging them is left to the cleaner. Normals
//! are ignored (many writers leave them zero or wrong); being facet
//! normals, which the triangles determine, they are not reported as a
//! dropped vertex attribute.
//!
//! Binary files may also begin with "solid", so the choice is by size: a
//! file whose length is exactly 84 + 50 × count is binary; otherwise one
//! that begins with "solid" is read as ASCII, falling back to binary if
//! the text does not parse but the binary count fits.
//!
//! Invariants: the binary count is checked against the file size and the
//! [`Limits`] before allocation; ASCII growth is checked facet by facet.

use super::builder::Builder;
use super::text::{self, Text};
use super::Attributes;
use crate::{Error, FormatError, Limits, Location, Malformed, TriMesh};
use std::io::{self, Write};

const FORMAT: &str = "STL";

fn error(what: Malformed, at: Location) -> Error {
    FormatError::new(FORMAT, what).at(at).into()
}

/// Bytes before the first binary triangle.
const HEADER: usize = 84;
/// Bytes per binary triangle.
const RECORD: usize = 50;

/// Reads an STL file, ASCII or binary.
pub(super) fn read(
    bytes: &[u8],
    limits: &Limits,
) -> Result<(crate::AttributedMesh, Attributes), Error> {
    read_either(bytes, limits).map(|mesh| (mesh.into(), Attributes::default()))
}

/// Binary or ASCII, as the size and first word say.
fn read_either(bytes: &[u8], limits: &Limits) -> Result<TriMesh, Error> {
    let count = bytes
        .get(80..HEADER)
        .and_then(|b| b.first_chunk::<4>())
        .map(|&b| u32::from_le_bytes(b) as u64);
    let body = bytes.len().saturating_sub(HEADER) as u64;
    let exact = count.is_some_and(|n| n * RECORD as u64 == body);
    let solid = bytes
        .trim_ascii_start()
        .get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case(b"solid"));
    if exact || !solid {
        return read_binary(bytes, limits);
    }
    // A binary file whose header starts with "solid" and that has bytes
    // after its triangles does not parse as text, or parses as a solid
    // without facets (when its name line swallows everything).
    let binary_fits = count.is_some_and(|n| n * (RECORD as u64) < body);
    match read_ascii(bytes, limits) {
        Ok(mesh) if !mesh.triangles.is_empty() || !binary_fits => Ok(mesh),
        Err(e) if !binary_fits => Err(e),
        _ => read_binary(bytes, limits),
    }
}

fn read_binary(bytes: &[u8], limits: &Limits) -> Result<TriMesh, Error> {
    let truncated = || error(Malformed::Truncated, Location::Byte(bytes.len() as u64));
    let Some(&count) = bytes.get(80..HEADER).and_then(|b| b.first_chunk::<4>()) else {
        return Err(truncated());
    };
    let count = u32::from_le_bytes(count) as usize;
    let body = bytes.get(HEADER..).unwrap_or_default();
    // Fixed-size records: a count the file cannot hold means the file was
    // cut short (or the count is a lie), either way there is nothing to
    // allocate for.
    let records = count
        .checked_mul(RECORD)
        .and_then(|n| body.get(..n))
        .ok_or_else(truncated)?;
    let mut out = Builder::new(limits);
    out.reserve_vertices(3 * count as u64)?;
    out.reserve_triangles(count as u64)?;
    for (i, r) in records.chunks_exact(RECORD).enumerate() {
        let base = out.mesh.positions.len() as u32;
        // Skip the normal (12 bytes) and read the three corners.
        for corner in r[12..48].chunks_exact(12) {
            let mut p = [0f32; 3];
            for (c, b) in p.iter_mut().zip(corner.chunks_exact(4)) {
                *c = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            }
            if !p.iter().all(|c| c.is_finite()) {
                let at = Location::Byte((HEADER + i * RECORD) as u64);
                let vertex = out.mesh.positions.len() as u64;
                return Err(error(Malformed::NonFinite { vertex }, at));
            }
            out.mesh.positions.push(p);
        }
        out.mesh.triangles.push([base, base + 1, base + 2]);
    }
    Ok(out.finish().0.mesh)
}

fn read_ascii(bytes: &[u8], limits: &Limits) -> Result<TriMesh, Error> {
    let mut t = Text::new(bytes, 1);
    let mut out = Builder::new(limits);
    let syntax = |why, t: &Text| error(Malformed::BadSyntax(why), Location::Line(t.line()));
    // Keywords are matched ignoring case: some exporters shout.
    let is = |word: Option<&[u8]>, keyword: &str| {
        word.is_some_and(|w| w.eq_ignore_ascii_case(keyword.as_bytes()))
    };
    let mut solids = 0u64;
    loop {
        let word = t.token();
        if word.is_none() {
            break;
        }
        if is(word, "solid") || is(word, "endsolid") {
            // The name runs to the end of the line and may contain spaces.
            solids += u64::from(is(word, "solid"));
            t.skip_line();
            continue;
        }
        if solids == 0 {
            return Err(syntax("expected solid", &t));
        }
        if !is(word, "facet") {
            return Err(syntax("expected facet or endsolid", &t));
        }
        let at = Location::Line(t.line());
        if !is(t.token(), "normal") {
            return Err(syntax("expected normal after facet", &t));
        }
        for _ in 0..3 {
            // Normals are recomputed downstream; they need not even parse.
            t.token()
                .ok_or_else(|| error(Malformed::Truncated, Location::Line(t.line())))?;
        }
        if !is(t.token(), "outer") || !is(t.token(), "loop") {
            return Err(syntax("expected outer loop", &t));
        }
        let base = out.mesh.positions.len();
        loop {
            let word = t.token();
            if is(word, "endloop") {
                break;
            }
            if word.is_none() {
                return Err(error(Malformed::Truncated, Location::Line(t.line())));
            }
            if !is(word, "vertex") {
                return Err(syntax("expected vertex or endloop", &t));
            }
            let mut p = [0f32; 3];
            for c in &mut p {
                let line = t.line();
                *c = t
                    .token()
                    .and_then(text::parse_f32)
                    .ok_or_else(|| error(Malformed::BadNumber, Location::Line(line)))?;
            }
            if !p.iter().all(|c| c.is_finite()) {
                let vertex = out.mesh.positions.len() as u64;
                return Err(error(
                    Malformed::NonFinite { vertex },
                    Location::Line(t.line()),
                ));
            }
            out.mesh.positions.push(p);
        }
        let corners = out.mesh.positions.len() - base;
        if corners < 3 {
            let what = Malformed::FaceTooSmall {
                count: corners as u64,
            };
            return Err(error(what, at));
        }
        // Before the indices are made: they must fit in u32.
        out.check_growth()?;
        // Not in the specification, but polygons are fanned like elsewhere.
        let v = |k: usize| (base + k) as u32;
        for k in 1..corners - 1 {
            out.mesh.triangles.push([v(0), v(k), v(k + 1)]);
        }
        if !is(t.token(), "endfacet") {
            return Err(syntax("expected endfacet", &t));
        }
    }
    Ok(out.finish().0.mesh)
}

/// Writes binary STL with computed unit normals. The 80-byte header
/// deliberately does not start with "solid".
pub(super) fn write<W: Write>(w: &mut W, mesh: &TriMesh) -> io::Result<()> {
    let count = u32::try_from(mesh.triangles.len())
        .map_err(|_| io::Error::from(io::ErrorKind::InvalidInput))?;
    let mut header = [b' '; HEADER];
    let title = b"binary STL written by swm";
    header[..title.len()].copy_from_slice(title);
    header[80..].copy_from_slice(&count.to_le_bytes());
    w.write_all(&header)?;
    for t in &mesh.triangles {
        let p = t.map(|v| mesh.positions[v as usize]);
        let normal = unit_normal(&p);
        let mut record = [0u8; RECORD];
        let floats = normal.iter().chain(p.iter().flatten());
        for (chunk, f) in record.chunks_exact_mut(4).zip(floats) {
            chunk.copy_from_slice(&f.to_le_bytes());
        }
        w.write_all(&record)?;
    }
    Ok(())
}

/// The unit normal of a triangle, zero when it is degenerate.
fn unit_normal(p: &[[f32; 3]; 3]) -> [f32; 3] {
    let d = |a: [f32; 3], b: [f32; 3]| [0, 1, 2].map(|k| f64::from(b[k]) - f64::from(a[k]));
    let (u, v) = (d(p[0], p[1]), d(p[0], p[2]));
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|c| (c / len) as f32)
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{malformed, read};
    use super::super::MeshFormat;
    use super::*;

    const ASCII: &str = "solid two triangles\n\
  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n    endloop\n  endfacet\n\
  FACET NORMAL 0 0 0\n    OUTER LOOP\n      VERTEX 1 0 0\n      VERTEX 1 1 0\n      VERTEX 0 1 0\n    ENDLOOP\n  ENDFACET\n\
endsolid two triangles\n";

    fn binary(header: &[u8], triangles: &[[[f32; 3]; 3]], count: u32) -> Vec<u8> {
        let mut bytes = header.to_vec();
        bytes.resize(80, b' ');
        bytes.extend(count.to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            for c in t.iter().flatten() {
                bytes.extend(c.to_le_bytes());
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    const TRIANGLES: [[[f32; 3]; 3]; 2] = [
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ];

    fn check(mesh: &TriMesh) {
        let corners: Vec<_> = TRIANGLES.iter().flatten().copied().collect();
        assert_eq!(mesh.positions, corners);
        assert_eq!(mesh.triangles, [[0, 1, 2], [3, 4, 5]]);
    }

    /// `\n`, `\r\n` and a lone `\r` end lines alike: the same mesh, and
    /// an error on the same line.
    #[test]
    fn every_line_ending_reads_alike() {
        let bad = ASCII.replacen("vertex 1 0 0", "vertex 1 zero 0", 1);
        for eol in ["\n", "\r\n", "\r"] {
            let text = ASCII.replace('\n', eol);
            check(
                &read(text.as_bytes(), MeshFormat::Stl).unwrap_or_else(|e| panic!("{eol:?}: {e}")),
            );
            let bad = bad.replace('\n', eol);
            let (_, at) = malformed(read(bad.as_bytes(), MeshFormat::Stl));
            assert_eq!(at, Some(Location::Line(5)), "{eol:?}");
        }
    }

    #[test]
    fn ascii_and_binary() {
        check(&read(ASCII.as_bytes(), MeshFormat::Stl).unwrap());
        check(&read(&binary(b"made by hand", &TRIANGLES, 2), MeshFormat::Stl).unwrap());
        // A binary header that starts with "solid", as many exporters write.
        let solid = binary(b"solid but binary", &TRIANGLES, 2);
        check(&read(&solid, MeshFormat::Stl).unwrap());
        // ... even with bytes after the triangles.
        let mut trailing = solid.clone();
        trailing.extend(b"\0\0junk");
        check(&read(&trailing, MeshFormat::Stl).unwrap());
        // Two solids in one file, and no final endsolid.
        let twice = format!("{ASCII}{}", ASCII.replace("endsolid two triangles\n", ""));
        assert_eq!(
            read(twice.as_bytes(), MeshFormat::Stl)
                .unwrap()
                .triangles
                .len(),
            4
        );
    }

    #[test]
    fn malformed_files() {
        let stl = |text: &str| malformed(read(text.as_bytes(), MeshFormat::Stl));
        let nan = ASCII.replacen("vertex 1 0 0", "vertex 1 nan 0", 1);
        assert_eq!(
            stl(&nan),
            (Malformed::NonFinite { vertex: 1 }, Some(Location::Line(5)))
        );
        let bad = ASCII.replacen("vertex 1 0 0", "vertex 1 O 0", 1);
        assert_eq!(stl(&bad), (Malformed::BadNumber, Some(Location::Line(5))));
        let small = ASCII.replacen("      vertex 0 1 0\n", "", 1);
        assert_eq!(
            stl(&small),
            (
                Malformed::FaceTooSmall { count: 2 },
                Some(Location::Line(2))
            )
        );
        let cut = &ASCII[..ASCII.find("endloop").unwrap()];
        assert_eq!(stl(cut).0, Malformed::Truncated);
        let why = Malformed::BadSyntax("expected facet or endsolid");
        assert_eq!(
            stl(&ASCII.replacen("facet", "facets", 1)),
            (why, Some(Location::Line(2)))
        );

        let whole = binary(b"", &TRIANGLES, 2);
        let (what, at) = malformed(read(&whole[..whole.len() - 1], MeshFormat::Stl));
        assert_eq!(
            (what, at),
            (Malformed::Truncated, Some(Location::Byte(183)))
        );
        let (what, _) = malformed(read(&binary(b"", &TRIANGLES, u32::MAX), MeshFormat::Stl));
        assert_eq!(what, Malformed::Truncated);
        let mut nan = TRIANGLES;
        nan[1][2][1] = f32::INFINITY;
        let (what, at) = malformed(read(&binary(b"", &nan, 2), MeshFormat::Stl));
        assert_eq!(
            (what, at),
            (
                Malformed::NonFinite { vertex: 5 },
                Some(Location::Byte(134))
            )
        );
    }

    #[test]
    fn written_header_is_not_mistaken_for_text() {
        let mesh = TriMesh::new(TRIANGLES[0].to_vec(), vec![[0, 1, 2]]);
        let mut bytes = Vec::new();
        write(&mut bytes, &mesh).unwrap();
        assert_eq!(bytes.len(), 84 + 50);
        assert!(!bytes.starts_with(b"solid"));
        // The normal of a counter-clockwise triangle in the xy plane is +z.
        assert_eq!(
            &bytes[84..96],
            [0f32, 0.0, 1.0].map(f32::to_le_bytes).concat()
        );
    }
}
