//! Wavefront OBJ reader and writer. The format is the one of Wavefront's
//! Advanced Visualizer manual (Appendix B1, "Object Files (.obj)"); the
//! parsing is done by the `tobj` crate.
//!
//! Geometry statements: `v x y z [w]` and `f v1[/vt[/vn]] v2 ...` with
//! 1-based or negative (relative) indices; polygons are fan-triangulated.
//! Groups, objects, materials, smoothing groups, points and lines are
//! ignored. When attributes are asked for (`keep`), `vt u [v [w]]`,
//! `vn x y z` and vertex colours (`v x y z r g b`, an extension many
//! writers use) become streams, `vt` and `vn` with the face's own indices
//! (per corner, so seams stay as written); otherwise they are reported
//! as dropped. An attribute that is malformed or that not every face
//! corner names (`f 1/1 2/2 3` on a textured mesh) is dropped and
//! reported, never an error: attributes do not make a readable file
//! unreadable.
//!
//! tobj on its own would not return the raw mesh this module promises, so
//! it only gets to see a filtered copy of the statements (see [`Feed`]):
//! - tobj numbers vertices in the order faces first use them and drops the
//!   unused ones; a synthetic first face `f 1 2 ... N` that uses every
//!   vertex in file order pins vertex i to slot i, and its triangles are
//!   removed afterwards. Vertex numbering and unreferenced vertices
//!   survive, so OBJ round trips are exact;
//! - tobj starts a new model, with its own copies of the shared vertices,
//!   at every `o`, `g` and `usemtl`; those lines are withheld, so the mesh
//!   stays connected across groups;
//! - tobj computes texture and normal slots with unchecked arithmetic on
//!   file indices; `vt` and `vn` lines are withheld so those slots are
//!   never used;
//! - tobj silently drops faces with fewer than three vertices; a first
//!   pass over the file ([`scan`]) reports them, counts vertices and
//!   triangles for the [`Limits`] before tobj allocates anything, and
//!   gives errors their line numbers.

use super::builder::{limit, Builder};
use super::text::{self, Text};
use super::Attributes;
use crate::{
    AttributeKind, AttributedMesh, Error, FormatError, Limited, Limits, Location, Malformed,
    TriMesh,
};
use std::io::{self, BufRead, Read, Write};

const FORMAT: &str = "OBJ";

fn error(what: Malformed, line: u64) -> Error {
    FormatError::new(FORMAT, what)
        .at(Location::Line(line))
        .into()
}

/// A line without its `#` comment.
fn uncomment(line: &[u8]) -> &[u8] {
    match line.iter().position(|&b| b == b'#') {
        Some(hash) => &line[..hash],
        None => line,
    }
}

/// What the first pass found.
#[derive(Debug, Default)]
struct Counts {
    vertices: u64,
    faces: u64,
    triangles: u64,
    /// `vt`, `vn` and coloured `v` statements seen.
    dropped: Attributes,
    /// `vt` and `vn` statements, and whether a `vt` has a third value.
    texcoords: u64,
    normals: u64,
    texcoord_w: bool,
}

/// The first pass: counts, and the checks tobj does not make.
fn scan(bytes: &[u8]) -> Result<Counts, Error> {
    let mut counts = Counts::default();
    let mut t = Text::new(bytes, 1);
    while let Some((n, line)) = t.next_line() {
        let mut words = text::tokens(uncomment(line));
        match words.next() {
            Some(b"v") => {
                let values = words.count();
                if values < 3 {
                    let why = "a vertex needs three coordinates";
                    return Err(error(Malformed::BadSyntax(why), n));
                }
                // x y z [w] is a position; x y z r g b [a] carries a colour.
                counts.dropped.colors |= values >= 6;
                counts.vertices += 1;
            }
            Some(b"vt") => {
                counts.dropped.uv = true;
                counts.texcoords += 1;
                counts.texcoord_w |= words.count() >= 3;
            }
            Some(b"vn") => {
                counts.dropped.normals = true;
                counts.normals += 1;
            }
            Some(b"f") => {
                let corners = words.count() as u64;
                if corners < 3 {
                    return Err(error(Malformed::FaceTooSmall { count: corners }, n));
                }
                counts.faces += 1;
                counts.triangles += corners - 2;
            }
            _ => {}
        }
    }
    Ok(counts)
}

/// Reads an OBJ file, with its attributes if `keep`.
pub(super) fn read(
    bytes: &[u8],
    limits: &Limits,
    keep: bool,
) -> Result<(AttributedMesh, Attributes), Error> {
    if let Some(why) = text::not_text(bytes) {
        return Err(FormatError::new(FORMAT, why).into());
    }
    let counts = scan(bytes)?;
    if counts.vertices == 0 && counts.faces == 0 {
        return Err(FormatError::new(FORMAT, Malformed::Empty).into());
    }
    limits.check_vertices(counts.vertices)?;
    limits.check_faces(counts.triangles)?;
    // tobj's working memory, roughly: its position list, vertex map and
    // output (about 100 bytes per vertex), its list of faces (about 200
    // bytes each), and the indices (36 bytes per triangle).
    let working = counts
        .vertices
        .saturating_mul(100)
        .saturating_add(counts.faces.saturating_mul(200))
        .saturating_add(counts.triangles.saturating_mul(36));
    // With attributes: their values (at most 3 floats each) and a triple
    // per triangle for `vt` and for `vn`, all built beside tobj's output.
    let attributes = match keep {
        true => (counts.texcoords + counts.normals + counts.vertices)
            .saturating_mul(12)
            .saturating_add(counts.triangles.saturating_mul(24)),
        false => 0,
    };
    limits.check_alloc(working.saturating_add(attributes))?;
    if counts.vertices > 1 << 32 {
        return Err(limit(Limited::Vertices, counts.vertices, 1 << 32));
    }

    let mut feed = Feed::new(bytes, counts.vertices);
    // tobj's `merging` and `reordering` features add fields, so the
    // struct update is needed whenever another crate turns them on.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        // Polygons come back whole and are fanned below: tobj would look
        // every corner of every fan triangle up in its vertex map, which
        // for the synthetic face alone is three lookups per vertex.
        triangulate: false,
        single_index: false,
        // Only the synthetic first face can be a point or a line (when the
        // file has fewer than three vertices); `scan` rejects real ones.
        ignore_points: false,
        ignore_lines: false,
        ..Default::default()
    };
    // `mtllib` lines are withheld, so this is never called.
    let no_materials = |_: &std::path::Path| Err(tobj::LoadError::GenericFailure);
    let (models, _) = tobj::load_obj_buf(&mut feed, &options, no_materials)
        .map_err(|e| load_error(e, feed.line, bytes, counts.vertices))?;

    let mut out = Builder::new(limits);
    if !keep {
        out.dropped = counts.dropped;
    }
    out.reserve_vertices(counts.vertices)?;
    out.reserve_triangles(counts.triangles)?;
    // One model, whose vertices are the file's in file order (see
    // `Feed`); anything else would make the indices below wrong.
    let returned: usize = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
    if returned as u64 != counts.vertices {
        let why = "tobj returned vertices other than the file's";
        return Err(FormatError::new(FORMAT, Malformed::BadSyntax(why)).into());
    }
    // The synthetic face is the first face of the first model.
    let mut skip = usize::from(counts.vertices > 0);
    for model in &models {
        let offset = out.mesh.positions.len() as u32;
        for p in model.mesh.positions.chunks_exact(3) {
            out.mesh.positions.push([p[0], p[1], p[2]]);
        }
        let mesh = &model.mesh;
        // tobj leaves the arities empty when every face is a triangle.
        let arity = |f: usize| mesh.face_arities.get(f).map_or(3, |&n| n as usize);
        let mut corners = mesh.indices.as_slice();
        let mut f = 0;
        while let Some((face, rest)) = corners.split_at_checked(arity(f).max(1)) {
            corners = rest;
            f += 1;
            if skip > 0 {
                skip -= 1;
                continue;
            }
            if let [first, fan @ ..] = face {
                for pair in fan.windows(2) {
                    let t = [*first, pair[0], pair[1]];
                    out.mesh.triangles.push(t.map(|v| v + offset));
                }
            }
        }
    }
    if let Some(i) = out
        .mesh
        .positions
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        let mut e = FormatError::new(FORMAT, Malformed::NonFinite { vertex: i as u64 });
        if let Some(line) = vertex_line(bytes, i as u64) {
            e = e.at(Location::Line(line));
        }
        return Err(e.into());
    }
    if keep {
        read_attributes(bytes, &counts, &mut out)?;
    }
    Ok(out.finish())
}

/// The `vt`, `vn` and colour streams, in a pass of their own (tobj never
/// sees those statements): the values in file order, and per triangle of
/// each face (fanned as the positions are) the values its corners name.
fn read_attributes(bytes: &[u8], counts: &Counts, out: &mut Builder) -> Result<(), Error> {
    let vt_dims = if counts.texcoord_w { 3 } else { 2 };
    let add = |out: &mut Builder, kind, dims, n, per_vertex| -> Result<Option<usize>, Error> {
        if n == 0 {
            return Ok(None);
        }
        let s = out.add_stream(kind, dims, per_vertex);
        let triples = if per_vertex { 0 } else { counts.triangles };
        out.reserve_values(s, n, triples)?;
        Ok(Some(s))
    };
    let normals = add(out, AttributeKind::Normal, 3, counts.normals, false)?;
    let uv = add(
        out,
        AttributeKind::TexCoord(0),
        vt_dims,
        counts.texcoords,
        false,
    )?;
    let colours = match counts.dropped.colors {
        true => add(out, AttributeKind::Color(0), 3, counts.vertices, true)?,
        false => None,
    };
    // Values read so far, for relative indices.
    let (mut seen_vt, mut seen_vn) = (0i64, 0i64);
    let mut face: Vec<[Option<u32>; 2]> = Vec::new();
    let mut t = Text::new(bytes, 1);
    while let Some((_, line)) = t.next_line() {
        let mut words = text::tokens(uncomment(line));
        let (stream, dims, values) = match words.next() {
            Some(b"v") => {
                let Some(s) = colours else { continue };
                let rgb: Vec<&[u8]> = words.skip(3).take(3).collect();
                (s, 3, rgb)
            }
            Some(b"vt") => {
                seen_vt += 1;
                let Some(s) = uv else { continue };
                (s, vt_dims, words.take(3).collect())
            }
            Some(b"vn") => {
                seen_vn += 1;
                let Some(s) = normals else { continue };
                (s, 3, words.take(3).collect())
            }
            Some(b"f") => {
                face.clear();
                for word in words {
                    let mut parts = word.split(|&b| b == b'/').skip(1);
                    let mut index = |seen: i64| {
                        let i = text::parse_i64(parts.next()?)?;
                        let i = if i < 0 { seen.checked_add(i)? } else { i - 1 };
                        u32::try_from(i).ok().filter(|&i| i64::from(i) < seen)
                    };
                    let vt = index(seen_vt);
                    face.push([vt, index(seen_vn)]);
                }
                for (slot, stream) in [normals, uv].into_iter().enumerate() {
                    // Slot 0 of `face` is the texture coordinate.
                    let Some(s) = stream else { continue };
                    let k = 1 - slot;
                    let corners: Option<Vec<u32>> = face.iter().map(|c| c[k]).collect();
                    let pending = &mut out.streams[s];
                    match corners {
                        Some(c) if !pending.broken => {
                            for pair in c[1..].windows(2) {
                                pending.stream.corners.push([c[0], pair[0], pair[1]]);
                            }
                        }
                        _ => pending.broken = true,
                    }
                }
                continue;
            }
            _ => continue,
        };
        let dims = usize::from(dims);
        let pending = &mut out.streams[stream];
        let parsed: Option<Vec<f32>> = values.iter().map(|w| text::parse_f32(w)).collect();
        let is_uv = Some(stream) == uv;
        match parsed {
            // `vt u` and `vt u v` leave the rest 0 (Appendix B1).
            Some(v) if v.len() == dims || (is_uv && !v.is_empty()) => {
                let v = &v[..v.len().min(dims)];
                pending.stream.values.extend_from_slice(v);
                pending.stream.values.extend((v.len()..dims).map(|_| 0.0));
            }
            _ => pending.broken = true,
        }
    }
    Ok(())
}

/// Translates a tobj error; `line` is the line tobj was parsing.
fn load_error(e: tobj::LoadError, line: u64, bytes: &[u8], vertices: u64) -> Error {
    use tobj::LoadError as L;
    let what = match e {
        // tobj checks indices only after the whole file was parsed.
        L::FaceVertexOutOfBounds => return bad_index(bytes, vertices),
        L::PositionParseError | L::FaceParseError | L::ColorParseError => Malformed::BadNumber,
        L::ScalingByZeroError => Malformed::BadSyntax("a vertex has the weight w = 0"),
        L::ReadError => Malformed::BadSyntax("a line is not UTF-8 text"),
        _ => Malformed::BadSyntax("tobj rejected this statement"),
    };
    error(what, line)
}

/// Finds the first face index out of range, resolving indices the way
/// tobj does (relative ones against the vertices read so far).
fn bad_index(bytes: &[u8], vertices: u64) -> Error {
    let mut seen = 0i64;
    let mut t = Text::new(bytes, 1);
    while let Some((n, line)) = t.next_line() {
        let mut words = text::tokens(uncomment(line));
        match words.next() {
            Some(b"v") => seen += 1,
            Some(b"f") => {
                for word in words {
                    let first = word.split(|&b| b == b'/').next().unwrap_or_default();
                    let Some(i) = text::parse_i64(first) else {
                        continue;
                    };
                    if i == 0 {
                        let why = "vertex index 0 is invalid: OBJ indices start at 1";
                        return error(Malformed::BadSyntax(why), n);
                    }
                    let index = if i < 0 { seen.saturating_add(i) } else { i - 1 };
                    if index < 0 || index as u64 >= vertices {
                        // Quoted as written (1-based or relative), not
                        // as converted.
                        let index = i;
                        return error(Malformed::IndexOutOfRange { index, vertices }, n);
                    }
                }
            }
            _ => {}
        }
    }
    let what = Malformed::IndexOutOfRange {
        index: -1,
        vertices,
    };
    FormatError::new(FORMAT, what).into()
}

/// The line of the `i`-th (0-based) vertex statement.
fn vertex_line(bytes: &[u8], i: u64) -> Option<u64> {
    let mut seen = 0;
    let mut t = Text::new(bytes, 1);
    while let Some((n, line)) = t.next_line() {
        if text::tokens(uncomment(line)).next() == Some(b"v") {
            if seen == i {
                return Some(n);
            }
            seen += 1;
        }
    }
    None
}

/// What tobj reads: first the synthetic face `f 1 2 ... N`, then the
/// file's `v` and `f` lines, without comments, each ending in `\n`.
/// Every other line is withheld (see the module header for why).
struct Feed<'a> {
    /// File bytes not yet looked at.
    rest: &'a [u8],
    /// 1-based number of the file line being served; 0 while serving the
    /// synthetic face.
    line: u64,
    /// What is left of the served line, before its newline.
    chunk: &'a [u8],
    /// The served line still owes its `\n`.
    newline: bool,
    /// The synthetic face, generated a piece at a time.
    synthetic: Vec<u8>,
    synthetic_pos: usize,
    /// Next vertex to name in the synthetic face (1-based), and the last.
    next_vertex: u64,
    vertices: u64,
}

impl<'a> Feed<'a> {
    fn new(bytes: &'a [u8], vertices: u64) -> Self {
        Feed {
            rest: bytes,
            line: 0,
            chunk: &[],
            newline: false,
            synthetic: Vec::with_capacity(1 << 13),
            synthetic_pos: 0,
            next_vertex: 1,
            vertices,
        }
    }

    /// Makes sure unread synthetic bytes are buffered; false once the
    /// whole synthetic face was served.
    fn refill_synthetic(&mut self) -> bool {
        if self.synthetic_pos < self.synthetic.len() {
            return true;
        }
        if self.next_vertex > self.vertices {
            return false;
        }
        self.synthetic.clear();
        self.synthetic_pos = 0;
        if self.next_vertex == 1 {
            self.synthetic.push(b'f');
        }
        while self.synthetic.len() < (1 << 13) - 24 && self.next_vertex <= self.vertices {
            // Writing to a Vec cannot fail.
            let _ = write!(self.synthetic, " {}", self.next_vertex);
            self.next_vertex += 1;
        }
        if self.next_vertex > self.vertices {
            self.synthetic.push(b'\n');
        }
        true
    }

    /// Moves to the next `v` or `f` line of the file; false at the end.
    fn next_line(&mut self) -> bool {
        while !self.rest.is_empty() {
            let (line, rest) = text::split_line(self.rest);
            self.rest = rest;
            self.line += 1;
            let line = uncomment(line);
            let mut words = text::tokens(line);
            match words.next() {
                Some(b"v") => {
                    // `v x y z r g b` (colours) and longer: keep x y z only,
                    // tobj would misread the extra values. `v x y z w` is
                    // passed on, tobj divides by w.
                    let extra = words.clone().count();
                    if extra > 4 {
                        let end = words.nth(2).map_or(line.len(), |z| {
                            z.as_ptr() as usize - line.as_ptr() as usize + z.len()
                        });
                        self.chunk = line.get(..end).unwrap_or(line);
                    } else {
                        self.chunk = line;
                    }
                }
                Some(b"f") => self.chunk = line,
                _ => continue,
            }
            self.newline = true;
            return true;
        }
        false
    }
}

impl Read for Feed<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let available = self.fill_buf()?;
        let n = available.len().min(buf.len());
        buf[..n].copy_from_slice(&available[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for Feed<'_> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.refill_synthetic() {
            return Ok(&self.synthetic[self.synthetic_pos..]);
        }
        if self.chunk.is_empty() && !self.newline && !self.next_line() {
            return Ok(&[]);
        }
        Ok(if self.chunk.is_empty() {
            b"\n"
        } else {
            self.chunk
        })
    }

    fn consume(&mut self, n: usize) {
        // The same order of precedence as `fill_buf`.
        if self.synthetic_pos < self.synthetic.len() {
            self.synthetic_pos += n;
        } else if !self.chunk.is_empty() {
            self.chunk = self.chunk.get(n..).unwrap_or_default();
        } else if n > 0 {
            self.newline = false;
        }
    }
}

/// Writes OBJ: `v x y z` with shortest round-trip decimals, then 1-based
/// `f a b c`.
pub(super) fn write<W: Write>(w: &mut W, mesh: &TriMesh) -> io::Result<()> {
    writeln!(
        w,
        "# written by swm: {} vertices, {} triangles",
        mesh.positions.len(),
        mesh.triangles.len()
    )?;
    for [x, y, z] in &mesh.positions {
        writeln!(w, "v {x} {y} {z}")?;
    }
    // Faces are most of the file; format their integers by hand.
    let mut line = Vec::with_capacity(40);
    for t in &mesh.triangles {
        line.clear();
        line.push(b'f');
        for &v in t {
            line.push(b' ');
            push_decimal(&mut line, u64::from(v) + 1);
        }
        line.push(b'\n');
        w.write_all(&line)?;
    }
    Ok(())
}

/// Writes OBJ with attributes: `v x y z [r g b]`, `vt u v [w]` (texture
/// coordinate set 0), `vn x y z`, then `f v/vt/vn` with the streams' own
/// indices, so seams are written as they are. Colours are per `v` line:
/// a position with several colours is written once per colour. Returns
/// what OBJ cannot hold (other texture sets and colour sets, alpha,
/// generic streams), which is not written. Without any stream OBJ can
/// hold, the file is [`write`]'s.
pub(super) fn write_attributed<W: Write>(w: &mut W, m: &AttributedMesh) -> io::Result<Attributes> {
    let mut unwritten = Attributes::default();
    for s in &m.streams {
        let written = match s.kind {
            AttributeKind::Normal | AttributeKind::TexCoord(0) => true,
            AttributeKind::Color(0) => s.dims == 3,
            _ => false,
        };
        if !written {
            unwritten = unwritten.union(Attributes::of(s.kind));
        }
    }
    let colour = AttributeKind::Color(0);
    let split;
    let m = match m.stream(colour) {
        Some(c) if c.corners != m.mesh.triangles || c.value_count() != m.mesh.positions.len() => {
            split = m.split_vertices_by(|s| s.kind == colour);
            &split
        }
        _ => m,
    };
    let colours = m.stream(colour).filter(|c| c.dims == 3);
    let uv = m.stream(AttributeKind::TexCoord(0));
    let normals = m.stream(AttributeKind::Normal);
    if colours.is_none() && uv.is_none() && normals.is_none() {
        write(w, &m.mesh)?;
        return Ok(unwritten);
    }
    writeln!(
        w,
        "# written by swm: {} vertices, {} triangles",
        m.mesh.positions.len(),
        m.mesh.triangles.len()
    )?;
    for (v, [x, y, z]) in m.mesh.positions.iter().enumerate() {
        match colours {
            Some(c) => {
                let [r, g, b] = [0, 1, 2].map(|k| c.values[3 * v + k]);
                writeln!(w, "v {x} {y} {z} {r} {g} {b}")?;
            }
            None => writeln!(w, "v {x} {y} {z}")?,
        }
    }
    if let Some(uv) = uv {
        for t in uv.values.chunks_exact(usize::from(uv.dims)) {
            match t {
                [u, v] => writeln!(w, "vt {u} {v}")?,
                [u, v, w3] => writeln!(w, "vt {u} {v} {w3}")?,
                _ => unreachable!("validated: 2 or 3 components"),
            }
        }
    }
    if let Some(n) = normals {
        for [x, y, z] in n.values.chunks_exact(3).map(|n| [n[0], n[1], n[2]]) {
            writeln!(w, "vn {x} {y} {z}")?;
        }
    }
    let mut line = Vec::with_capacity(80);
    for (f, t) in m.mesh.triangles.iter().enumerate() {
        line.clear();
        line.push(b'f');
        for (k, &v) in t.iter().enumerate() {
            line.push(b' ');
            push_decimal(&mut line, u64::from(v) + 1);
            if uv.is_some() || normals.is_some() {
                line.push(b'/');
            }
            if let Some(uv) = uv {
                push_decimal(&mut line, u64::from(uv.corners[f][k]) + 1);
            }
            if let Some(n) = normals {
                line.push(b'/');
                push_decimal(&mut line, u64::from(n.corners[f][k]) + 1);
            }
        }
        line.push(b'\n');
        w.write_all(&line)?;
    }
    Ok(unwritten)
}

fn push_decimal(out: &mut Vec<u8>, mut n: u64) {
    let mut digits = [0u8; 20];
    let mut k = digits.len();
    loop {
        k -= 1;
        digits[k] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&digits[k..]);
}

#[cfg(test)]
mod tests {
    use super::super::tests::{malformed, read};
    use super::super::MeshFormat;
    use super::*;

    fn obj(text: &str) -> Result<TriMesh, Error> {
        read(text.as_bytes(), MeshFormat::Obj)
    }

    const SQUARE: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];

    #[test]
    fn face_syntaxes() {
        let v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n";
        for faces in [
            "f 1 2 3 4\n",
            "f 1/1 2/2 3/3 4/1\n",
            "f 1/1/1 2/2/1 3/3/1 4/1/1\n",
            "f 1//1 2//1 3//1 4//1\n",
            "f -4 -3 -2 -1\n",
            "f -4/-3/-1 -3//-1 3/-1 4\n",
            "f 1 2 3\nf 1 3 4\n",
        ] {
            let mesh = obj(&format!("{v}{faces}")).unwrap_or_else(|e| panic!("{faces}: {e}"));
            assert_eq!(mesh.positions, SQUARE, "{faces}");
            assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]], "{faces}");
        }
        let pentagon = obj("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n").unwrap();
        assert_eq!(pentagon.triangles, [[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
    }

    /// `\n`, `\r\n` and a lone `\r` end lines alike: the same mesh, and
    /// an error on the same line.
    #[test]
    fn every_line_ending_reads_alike() {
        let text = "# a square\nv 0 0 0\nv 1 0 0\n\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
        let bad = "v 0 0 0\nv 1 0 0\n# comment\nv 0 1 0\nf 1 2 3\nf 1 2 9\n";
        for eol in ["\n", "\r\n", "\r"] {
            let mesh = obj(&text.replace('\n', eol)).unwrap_or_else(|e| panic!("{eol:?}: {e}"));
            assert_eq!(mesh.positions, SQUARE, "{eol:?}");
            assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]], "{eol:?}");
            let (_, at) = malformed(obj(&bad.replace('\n', eol)));
            assert_eq!(at, Some(Location::Line(6)), "{eol:?}");
        }
    }

    #[test]
    fn raw_vertices_survive() {
        // Faces use vertices out of order, one vertex is unused, a face
        // refers forward, groups and materials split the faces, vertices
        // carry colours or a weight, and comments and CRLF are everywhere.
        let text =
            "# header\r\nmtllib scene.mtl\r\no first\r\nv 0 0 0 1 0 0\r\nv 2 0 0 # trailing\r\n\
v 9 9 9\r\nusemtl red\r\nf 5 1 2\r\ng second\r\nv 2 4 0 2\r\nv 0 1 0 0.5 0.5 0.5\r\ns 1\r\n\
f 1 2 4 # comment\r\nl 1 2\r\np 3\r\nf 2 4 5\r\n";
        let mesh = obj(text).unwrap();
        let positions = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [9.0, 9.0, 9.0],
            [1.0, 2.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        assert_eq!(mesh.positions, positions);
        assert_eq!(mesh.triangles, [[4, 0, 1], [0, 1, 3], [1, 3, 4]]);
        // Vertices without faces are a point cloud, not an error.
        let points = obj("v 1 2 3\nv 4 5 6\n").unwrap();
        assert_eq!((points.positions.len(), points.triangles.len()), (2, 0));
        // One or two vertices: the synthetic first face is a point or a line.
        assert_eq!(obj("v 1 2 3\nf 1 1 1\n").unwrap().triangles, [[0, 0, 0]]);
        assert_eq!(
            obj("v 1 2 3\nv 1 2 4\nf 1 2 2\n").unwrap().triangles,
            [[0, 1, 1]]
        );
        // Latin-1 in a comment or a group name is not a problem.
        assert!(obj("# caf\u{e9}\ng \u{e9}\nv 0 0 0\nf 1 1 1\n").is_ok());
        assert!(read(b"# caf\xe9\ng \xe9\nv 0 0 0\nf 1 1 1\n", MeshFormat::Obj).is_ok());
    }

    #[test]
    fn malformed_files() {
        let v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        let cases: [(&str, Malformed, u64); 12] = [
            (
                "f 1 2 4\n",
                Malformed::IndexOutOfRange {
                    index: 4,
                    vertices: 3,
                },
                4,
            ),
            (
                "f -1 -2 -4\n",
                Malformed::IndexOutOfRange {
                    index: -4,
                    vertices: 3,
                },
                4,
            ),
            (
                "f 1 2 3\nf 0 1 2\n",
                Malformed::BadSyntax("vertex index 0 is invalid: OBJ indices start at 1"),
                5,
            ),
            ("f 1 2\n", Malformed::FaceTooSmall { count: 2 }, 4),
            ("f 1\n", Malformed::FaceTooSmall { count: 1 }, 4),
            ("f\n", Malformed::FaceTooSmall { count: 0 }, 4),
            ("f 1 2 x\n", Malformed::BadNumber, 4),
            ("f 1 2 3/1/1/1\n", Malformed::BadNumber, 4),
            (
                "v 1 2\nf 1 2 3\n",
                Malformed::BadSyntax("a vertex needs three coordinates"),
                4,
            ),
            ("v 1 2 z\nf 1 2 3\n", Malformed::BadNumber, 4),
            (
                "v 1 2 3 0\nf 1 2 3\n",
                Malformed::BadSyntax("a vertex has the weight w = 0"),
                4,
            ),
            (
                "f 1 2 3\nf 1 2 99999999999999999999\n",
                Malformed::BadNumber,
                5,
            ),
        ];
        for (text, what, line) in cases {
            let text = format!("{v}{text}");
            assert_eq!(
                malformed(obj(&text)),
                (what, Some(Location::Line(line))),
                "{text:?}"
            );
        }
        for (text, vertex, line) in [
            ("v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 0, 1),
            ("v 0 0 0\n# comment\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", 1, 3),
            ("v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n", 2, 3),
            // Unused, but still part of the raw mesh.
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e30 0 0 1e-30\nf 1 2 3\n",
                3,
                4,
            ),
        ] {
            let expected = (Malformed::NonFinite { vertex }, Some(Location::Line(line)));
            assert_eq!(malformed(obj(text)), expected, "{text:?}");
        }
        let (what, at) = malformed(read(b"v 0 0 0\nv 1 \xff 0\n", MeshFormat::Obj));
        assert_eq!(
            (what, at),
            (
                Malformed::BadSyntax("a line is not UTF-8 text"),
                Some(Location::Line(2))
            )
        );
        assert_eq!(
            malformed(obj("# only\n# comments\ng nothing\n")).0,
            Malformed::Empty
        );
        // Not UTF-8 or ASCII text at all: said so, not "empty".
        let utf16le: Vec<u8> = [0xFF, 0xFE]
            .into_iter()
            .chain("v 0 0 0\nf 1 1 1\n".bytes().flat_map(|b| [b, 0]))
            .collect();
        let utf16be: Vec<u8> = "v 0 0 0\nf 1 1 1\n".bytes().flat_map(|b| [0, b]).collect();
        for bytes in [&utf16le, &utf16be] {
            assert_eq!(malformed(read(bytes, MeshFormat::Obj)).0, Malformed::Utf16);
        }
        let swm = b"SWM\x00\x01\x00\x00\x00\x01\x20\x00\x00\x00\x10";
        assert_eq!(malformed(read(swm, MeshFormat::Obj)).0, Malformed::Binary);
        assert_eq!(malformed(read(swm, MeshFormat::Off)).0, Malformed::Binary);
        let (what, _) = malformed(obj("f 1 2 3\n"));
        assert_eq!(
            what,
            Malformed::IndexOutOfRange {
                index: 1,
                vertices: 0
            }
        );
    }

    #[test]
    fn writes_one_based_faces_and_shortest_decimals() {
        let mesh = TriMesh::new(
            vec![[0.1, -0.0, 1e-7], [1.0, 2.5, 3e20], [0.0; 3]],
            vec![[0, 1, 2]],
        );
        let mut bytes = Vec::new();
        write(&mut bytes, &mesh).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.contains("\nv 0.1 -0 0.0000001\n"), "{text}");
        assert!(text.ends_with("\nf 1 2 3\n"), "{text}");
    }
}
