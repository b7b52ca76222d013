//! PLY reader and writer, after Greg Turk, "The PLY Polygon File Format"
//! (Stanford, 1994) as implemented by `ply.c` and by the files Stanford's
//! scanning repository and VCG/MeshLab write.
//!
//! A PLY file is a text header (`ply`, `format`, then `element` lines each
//! followed by its `property` lines, then `end_header`) and the elements'
//! records in header order, either as whitespace-separated ASCII or as
//! packed little- or big-endian binary.
//!
//! What this reader keeps and how:
//! - the `vertex` element's `x`, `y`, `z` properties, of any numeric type,
//!   converted to `f32`; when attributes are asked for, also `nx ny nz`
//!   (a normal), the first of the pairs `u v`, `s t`, `texture_u
//!   texture_v` (texture coordinate set 0) and `red green blue [alpha]`
//!   (a colour; integer types scaled to 0..1: 8-bit by 1/255, 16-bit by
//!   1/65535), each a per-vertex stream (see [`attribute_layout`]); every
//!   other property is skipped, and normals, texture coordinates and
//!   colours that are not kept are reported as dropped (see [`dropped`]);
//! - the `face` element's `texcoord` list (2 floats per corner, as
//!   MeshLab writes), when attributes are asked for: a per-corner texture
//!   coordinate set after the vertex one, fanned as the face is; a face
//!   whose list does not hold two values per corner drops the stream;
//! - the `face` element's `vertex_indices` (or `vertex_index`) list, fan
//!   triangulated as (v0, vi, vi+1);
//! - the `tristrips` element's `vertex_indices` list: strips separated by
//!   -1, triangle i of a strip is (a, b, c) for even i and (b, a, c) for
//!   odd i so that all have the strip's orientation; degenerate triangles
//!   are kept for the cleaner to judge;
//! - any other element, and any element order; bytes after the last
//!   element are ignored, as most readers do.
//!
//! Invariants: every count in the header is checked against the bytes that
//! follow the header and against the [`Limits`] before anything is
//! allocated for it; every read is bounds-checked (a short file gives
//! [`Malformed::Truncated`]); vertex indices are checked against the
//! declared vertex count as they are read, so faces may precede vertices.

use super::builder::Builder;
use super::text::{self, Text};
use super::Attributes;
use crate::{
    AttributeKind, AttributedMesh, Error, FormatError, Limits, Location, Malformed, TriMesh,
};
use std::io::{self, Write};

const FORMAT: &str = "PLY";

fn error(what: Malformed, at: Location) -> Error {
    FormatError::new(FORMAT, what).at(at).into()
}

/// A property's numeric type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// Both the original names and the sized ones `ply.c` added later.
    fn from_name(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property<'a> {
    name: &'a [u8],
    kind: Kind,
}

/// What the reader does with an element's records.
#[derive(Clone, Copy, Debug)]
enum Role {
    /// Positions; the indices of the x, y and z properties.
    Vertex([usize; 3]),
    /// Polygons; the index of the vertex list property.
    Face(usize),
    /// Triangle strips; the index of the vertex list property.
    Strips(usize),
    /// Skipped.
    Other,
}

#[derive(Debug)]
struct Element<'a> {
    name: &'a [u8],
    count: u64,
    props: Vec<Property<'a>>,
    role: Role,
    /// Header line of the `element` statement.
    line: u64,
    /// Per property of a vertex element, where its value goes when
    /// attributes are read (see [`attribute_layout`]).
    attrs: Vec<Option<Slot>>,
    /// A face element's `texcoord` list: its property and its stream.
    texcoord: Option<(usize, usize)>,
}

/// Where a vertex property's value goes: component `comp` of stream
/// `stream` (an index of the builder's streams), divided by `divisor`
/// (255 or 65535 for integer colours, else 1).
#[derive(Clone, Copy, Debug)]
struct Slot {
    stream: usize,
    comp: usize,
    divisor: f64,
}

impl Element<'_> {
    /// Name for error messages.
    fn label(&self) -> &'static str {
        match self.role {
            Role::Vertex(_) => "vertex",
            Role::Face(_) => "face",
            Role::Strips(_) => "tristrips",
            Role::Other => "extra",
        }
    }

    /// The fewest bytes one record can take, so that a count can be
    /// checked against the bytes left before anything is allocated.
    fn min_record_size(&self, encoding: Encoding) -> u64 {
        let ascii = encoding == Encoding::Ascii;
        let mut size = 0u64;
        for (k, p) in self.props.iter().enumerate() {
            // One character and a separator per ASCII value.
            size += match p.kind {
                Kind::Scalar(_) if ascii => 2,
                Kind::Scalar(s) => s.size() as u64,
                Kind::List { count, item } => {
                    let face_list = matches!(self.role, Role::Face(f) if f == k);
                    // A face has at least three indices; other lists may be empty.
                    let items = if face_list { 3 } else { 0 };
                    if ascii {
                        2 + 2 * items
                    } else {
                        count.size() as u64 + items * item.size() as u64
                    }
                }
            };
        }
        size
    }

    /// The record size when every property is a scalar.
    fn fixed_record_size(&self) -> Option<usize> {
        self.props.iter().try_fold(0, |n, p| match p.kind {
            Kind::Scalar(s) => Some(n + s.size()),
            Kind::List { .. } => None,
        })
    }
}

struct Header<'a> {
    encoding: Encoding,
    elements: Vec<Element<'a>>,
    /// Offset of the first data byte.
    data: usize,
    /// Line of the first data byte (for ASCII files).
    data_line: u64,
}

fn bad_header(why: &'static str, line: u64) -> Error {
    error(Malformed::BadHeader(why), Location::Line(line))
}

fn parse_header(bytes: &[u8]) -> Result<Header<'_>, Error> {
    let mut t = Text::new(bytes, 1);
    match t.next_line() {
        Some((_, line)) if line.trim_ascii_end() == b"ply" => {}
        _ => return Err(bad_header("the file does not start with \"ply\"", 1)),
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        let Some((n, line)) = t.next_line() else {
            return Err(error(Malformed::Truncated, Location::Line(t.line())));
        };
        let mut words = text::tokens(line);
        match words.next() {
            None | Some(b"comment") | Some(b"obj_info") => {}
            Some(b"format") => {
                if encoding.is_some() {
                    return Err(bad_header("more than one format line", n));
                }
                encoding = Some(match words.next() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::Little,
                    Some(b"binary_big_endian") => Encoding::Big,
                    _ => return Err(bad_header("unknown format", n)),
                });
                if !matches!(words.next(), Some(b"1.0") | Some(b"1")) {
                    let what = Malformed::Unsupported("PLY versions other than 1.0");
                    return Err(error(what, Location::Line(n)));
                }
            }
            Some(b"element") => {
                let (Some(name), Some(count)) = (words.next(), words.next()) else {
                    return Err(bad_header("an element needs a name and a count", n));
                };
                let count = text::parse_u64(count)
                    .ok_or_else(|| bad_header("an element count is not a number", n))?;
                elements.push(Element {
                    name,
                    count,
                    props: Vec::new(),
                    role: Role::Other,
                    line: n,
                    attrs: Vec::new(),
                    texcoord: None,
                });
            }
            Some(b"property") => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| bad_header("a property precedes every element", n))?;
                let ty = |w: Option<&[u8]>| {
                    w.and_then(Scalar::from_name)
                        .ok_or_else(|| bad_header("unknown property type", n))
                };
                let mut first = words.next();
                let kind = if first == Some(b"list") {
                    let count = ty(words.next())?;
                    let item = ty(words.next())?;
                    if !count.is_integer() {
                        return Err(bad_header("a list count type is not an integer type", n));
                    }
                    first = None;
                    Kind::List { count, item }
                } else {
                    Kind::Scalar(ty(first.take())?)
                };
                let name = words
                    .next()
                    .ok_or_else(|| bad_header("a property has no name", n))?;
                element.props.push(Property { name, kind });
            }
            Some(b"end_header") => break,
            Some(_) => return Err(bad_header("unknown header keyword", n)),
        }
    }
    let encoding = encoding.ok_or_else(|| bad_header("no format line", 2))?;
    assign_roles(&mut elements)?;
    // The header's lines all end alike, as its first does. When that is a
    // lone `\r` (old Mac exporters), a `\n` after `end_header\r` is the
    // first byte of binary data, not part of a `\r\n`.
    let mut data = t.pos();
    let lone_cr = bytes.get(3) == Some(&b'\r') && bytes.get(4) != Some(&b'\n');
    if lone_cr && encoding != Encoding::Ascii && bytes[..data].ends_with(b"\r\n") {
        data -= 1;
    }
    Ok(Header {
        encoding,
        elements,
        data,
        data_line: t.line(),
    })
}

/// Finds the vertex, face and tristrips elements and the properties the
/// reader needs in them.
fn assign_roles(elements: &mut [Element]) -> Result<(), Error> {
    let (mut vertex, mut face, mut strips) = (false, false, false);
    for e in elements.iter_mut() {
        let find = |names: &[&[u8]]| e.props.iter().position(|p| names.contains(&p.name));
        let seen = match e.name {
            b"vertex" => {
                let mut xyz = [0; 3];
                for (slot, name) in xyz.iter_mut().zip([b"x", b"y", b"z"]) {
                    *slot = find(&[name])
                        .filter(|&k| matches!(e.props[k].kind, Kind::Scalar(_)))
                        .ok_or_else(|| {
                            bad_header("the vertex element lacks scalar x, y and z", e.line)
                        })?;
                }
                e.role = Role::Vertex(xyz);
                &mut vertex
            }
            b"face" | b"tristrips" => {
                let k = find(&[b"vertex_indices", b"vertex_index"]).ok_or_else(|| {
                    bad_header("a face or tristrips element has no vertex_indices", e.line)
                })?;
                match e.props[k].kind {
                    Kind::List { item, .. } if item.is_integer() => {}
                    _ => {
                        let why = "vertex_indices is not a list of integers";
                        return Err(bad_header(why, e.line));
                    }
                }
                if e.name == b"face" {
                    e.role = Role::Face(k);
                    &mut face
                } else {
                    e.role = Role::Strips(k);
                    &mut strips
                }
            }
            _ => continue,
        };
        if std::mem::replace(seen, true) {
            return Err(bad_header("an element appears twice", e.line));
        }
    }
    Ok(())
}

/// The attributes the header declares that the reader skips: by the
/// property names of `ply.c`, VCG/MeshLab and Blender. A face `texcoord`
/// list (per-corner texture coordinates, as MeshLab writes) counts too.
fn dropped(elements: &[Element]) -> Attributes {
    let mut dropped = Attributes::default();
    for e in elements.iter().filter(|e| e.count > 0) {
        let has = |names: &[&[u8]]| e.props.iter().any(|p| names.contains(&p.name));
        match e.role {
            Role::Vertex(_) => {
                dropped.normals |= has(&[b"nx", b"ny", b"nz"]);
                dropped.uv |= has(&[b"u", b"v", b"s", b"t", b"texture_u", b"texture_v"]);
                dropped.colors |= has(&[b"red", b"green", b"blue", b"alpha"]);
            }
            Role::Face(_) => dropped.uv |= has(&[b"texcoord"]),
            _ => {}
        }
    }
    dropped
}

/// The attribute streams of the vertex and face elements: adds them to
/// `out` and records in each element where its properties go. A group is
/// read only whole (all of `nx ny nz`, both of a pair, all of `red green
/// blue`) and of scalar properties; what is left is reported as dropped.
fn attribute_layout(elements: &mut [Element], out: &mut Builder) -> Attributes {
    let mut dropped = Attributes::default();
    for e in elements.iter_mut().filter(|e| e.count > 0) {
        let find = |name: &[u8]| {
            e.props
                .iter()
                .position(|p| p.name == name && matches!(p.kind, Kind::Scalar(_)))
        };
        match e.role {
            Role::Vertex(_) => {
                let mut attrs = vec![None; e.props.len()];
                let mut group = |kind, names: &[&[u8]], out: &mut Builder| {
                    let found: Option<Vec<usize>> = names.iter().map(|n| find(n)).collect();
                    let found = found?;
                    let s = out.add_stream(kind, found.len() as u8, true);
                    for (comp, &k) in found.iter().enumerate() {
                        let colour = matches!(kind, AttributeKind::Color(_));
                        let divisor = match e.props[k].kind {
                            Kind::Scalar(Scalar::U16 | Scalar::I16) if colour => 65535.0,
                            Kind::Scalar(ty) if ty.is_integer() && colour => 255.0,
                            _ => 1.0,
                        };
                        attrs[k] = Some(Slot {
                            stream: s,
                            comp,
                            divisor,
                        });
                    }
                    Some(())
                };
                group(AttributeKind::Normal, &[b"nx", b"ny", b"nz"], out);
                let pairs: [[&[u8]; 2]; 3] =
                    [[b"u", b"v"], [b"s", b"t"], [b"texture_u", b"texture_v"]];
                let _ = pairs
                    .iter()
                    .find_map(|pair| group(AttributeKind::TexCoord(0), pair, out));
                if find(b"alpha").is_some() {
                    group(
                        AttributeKind::Color(0),
                        &[b"red", b"green", b"blue", b"alpha"],
                        out,
                    );
                } else {
                    group(AttributeKind::Color(0), &[b"red", b"green", b"blue"], out);
                }
                e.attrs = attrs;
            }
            Role::Face(_) => {
                let list = e.props.iter().position(|p| {
                    p.name == b"texcoord"
                        && matches!(p.kind, Kind::List { item, .. } if !item.is_integer())
                });
                if let Some(k) = list {
                    let set = out
                        .streams
                        .iter()
                        .filter(|p| matches!(p.stream.kind, AttributeKind::TexCoord(_)))
                        .count();
                    let s = out.add_stream(AttributeKind::TexCoord(set as u8), 2, false);
                    e.texcoord = Some((k, s));
                }
            }
            _ => {}
        }
        // What the element declares and nothing reads.
        let read = |k: usize| {
            e.attrs.get(k).is_some_and(|a| a.is_some()) || e.texcoord.is_some_and(|t| t.0 == k)
        };
        let unread: Vec<Property> = e
            .props
            .iter()
            .enumerate()
            .filter(|&(k, _)| !read(k))
            .map(|(_, p)| Property {
                name: p.name,
                kind: p.kind,
            })
            .collect();
        let rest = Element {
            name: e.name,
            count: e.count,
            props: unread,
            role: e.role,
            line: e.line,
            attrs: Vec::new(),
            texcoord: None,
        };
        dropped = dropped.union(self::dropped(core::slice::from_ref(&rest)));
    }
    dropped
}

/// Reads a PLY file, with its attributes if `keep`.
pub(super) fn read(
    bytes: &[u8],
    limits: &Limits,
    keep: bool,
) -> Result<(AttributedMesh, Attributes), Error> {
    let mut header = parse_header(bytes)?;
    let data = bytes.get(header.data..).unwrap_or_default();
    let ascii = header.encoding == Encoding::Ascii;

    // Each count must fit in the data section on its own before anything
    // is allocated. Checking every element against the whole section (not
    // against what precedes it) keeps "the header lies" apart from "the
    // file was cut short", which is reported as Truncated where it ends.
    for e in &header.elements {
        let min = e.min_record_size(header.encoding);
        // Records of no bytes (no properties) fit any number of times.
        if let Some(possible) = (data.len() as u64 + u64::from(ascii)).checked_div(min) {
            if e.count > possible {
                let what = Malformed::CountTooLarge {
                    element: e.label(),
                    declared: e.count,
                    possible,
                };
                return Err(error(what, Location::Line(e.line)));
            }
        }
    }
    let role_count = |f: fn(&Role) -> bool| {
        header
            .elements
            .iter()
            .find(|e| f(&e.role))
            .map_or(0, |e| e.count)
    };
    let vertices = role_count(|r| matches!(r, Role::Vertex(_)));
    let faces = role_count(|r| matches!(r, Role::Face(_)));
    let mut out = Builder::new(limits);
    out.dropped = match keep {
        true => attribute_layout(&mut header.elements, &mut out),
        false => dropped(&header.elements),
    };
    out.reserve_vertices(vertices)?;
    out.reserve_triangles(faces)?;
    for s in 0..out.streams.len() {
        match out.streams[s].per_vertex {
            true => out.reserve_values(s, vertices, 0)?,
            false => out.reserve_values(s, faces.saturating_mul(3), faces)?,
        }
    }

    let base = header.data as u64;
    if ascii {
        let mut values = Ascii {
            text: Text::new(data, header.data_line),
        };
        // Records without properties take no bytes; a huge count of them
        // must not become a huge loop.
        for e in header.elements.iter().filter(|e| !e.props.is_empty()) {
            for i in 0..e.count {
                read_record(&mut values, e, i, vertices, &mut out)?;
            }
        }
    } else {
        let mut values = Binary {
            data,
            pos: 0,
            big: header.encoding == Encoding::Big,
            base,
        };
        for e in header.elements.iter().filter(|e| !e.props.is_empty()) {
            read_binary_element(&mut values, e, vertices, &mut out)?;
        }
    }
    Ok(out.finish())
}

/// The values of the data section, read one at a time.
trait Values {
    /// A coordinate.
    fn real(&mut self, ty: Scalar) -> Result<f64, Error>;
    /// A list count or a vertex index (`ty` is an integer type).
    fn int(&mut self, ty: Scalar) -> Result<i64, Error>;
    /// Skips `n` values.
    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Error>;
    /// Where the next record starts, for errors about the whole record.
    fn mark(&mut self) -> Location;
}

struct Ascii<'a> {
    text: Text<'a>,
}

impl<'a> Ascii<'a> {
    fn token(&mut self) -> Result<&'a [u8], Error> {
        let line = self.text.line();
        self.text
            .token()
            .ok_or_else(|| error(Malformed::Truncated, Location::Line(line)))
    }

    fn bad_number(&self) -> Error {
        error(Malformed::BadNumber, Location::Line(self.text.line()))
    }
}

impl Values for Ascii<'_> {
    fn real(&mut self, ty: Scalar) -> Result<f64, Error> {
        let token = self.token()?;
        let value = match ty {
            // Parsed as f32 so that the decimal is rounded once, to f32.
            Scalar::F32 => text::parse_f32(token).map(f64::from),
            Scalar::F64 => text::parse_f64(token),
            _ => text::parse_i64(token).map(|i| i as f64),
        };
        value.ok_or_else(|| self.bad_number())
    }

    fn int(&mut self, _ty: Scalar) -> Result<i64, Error> {
        let token = self.token()?;
        text::parse_i64(token).ok_or_else(|| self.bad_number())
    }

    fn skip(&mut self, _ty: Scalar, n: u64) -> Result<(), Error> {
        // Each token is at least one byte, so a lying count ends at the
        // end of the text rather than looping on.
        for _ in 0..n {
            self.token()?;
        }
        Ok(())
    }

    fn mark(&mut self) -> Location {
        // Move to the record's first token so the line is the record's.
        self.text.skip_space();
        Location::Line(self.text.line())
    }
}

struct Binary<'a> {
    data: &'a [u8],
    pos: usize,
    big: bool,
    /// File offset of `data[0]`.
    base: u64,
}

impl Binary<'_> {
    fn truncated(&self) -> Error {
        error(
            Malformed::Truncated,
            Location::Byte(self.base + self.data.len() as u64),
        )
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], Error> {
        let bytes = self
            .data
            .get(self.pos..)
            .and_then(|rest| rest.first_chunk::<N>())
            .ok_or_else(|| self.truncated())?;
        self.pos += N;
        Ok(*bytes)
    }
}

/// Reads one binary number of type `$t` with the file's byte order.
macro_rules! number {
    ($values:expr, $t:ty) => {{
        let bytes = $values.take::<{ core::mem::size_of::<$t>() }>()?;
        if $values.big {
            <$t>::from_be_bytes(bytes)
        } else {
            <$t>::from_le_bytes(bytes)
        }
    }};
}

impl Values for Binary<'_> {
    fn real(&mut self, ty: Scalar) -> Result<f64, Error> {
        Ok(match ty {
            Scalar::F32 => f64::from(number!(self, f32)),
            Scalar::F64 => number!(self, f64),
            _ => self.int(ty)? as f64,
        })
    }

    fn int(&mut self, ty: Scalar) -> Result<i64, Error> {
        Ok(match ty {
            Scalar::I8 => i64::from(number!(self, i8)),
            Scalar::U8 => i64::from(number!(self, u8)),
            Scalar::I16 => i64::from(number!(self, i16)),
            Scalar::U16 => i64::from(number!(self, u16)),
            Scalar::I32 => i64::from(number!(self, i32)),
            Scalar::U32 => i64::from(number!(self, u32)),
            // The header only lets integer types through for counts and
            // indices; a float reaching here is truncated like C would.
            Scalar::F32 => number!(self, f32) as i64,
            Scalar::F64 => number!(self, f64) as i64,
        })
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Error> {
        let bytes = n
            .checked_mul(ty.size() as u64)
            .filter(|&b| b <= (self.data.len() - self.pos) as u64)
            .ok_or_else(|| self.truncated())?;
        self.pos += bytes as usize;
        Ok(())
    }

    fn mark(&mut self) -> Location {
        Location::Byte(self.base + self.pos as u64)
    }
}

/// Checks a vertex index read from the file.
fn vertex_index(index: i64, vertices: u64, at: Location) -> Result<u32, Error> {
    if index < 0 || index as u64 >= vertices {
        return Err(error(Malformed::IndexOutOfRange { index, vertices }, at));
    }
    // vertices <= 2^32 was checked before reading.
    Ok(index as u32)
}

/// A list count read from the file.
fn list_count<V: Values>(values: &mut V, ty: Scalar, at: Location) -> Result<u64, Error> {
    let n = values.int(ty)?;
    u64::try_from(n).map_err(|_| error(Malformed::BadSyntax("a list count is negative"), at))
}

/// Reads record `i` of element `e`, whatever its role; the general path
/// that the binary fast paths fall back to.
fn read_record<V: Values>(
    values: &mut V,
    e: &Element,
    i: u64,
    vertices: u64,
    out: &mut Builder,
) -> Result<(), Error> {
    let at = values.mark();
    let mut p = [0f32; 3];
    if let Role::Vertex(_) = e.role {
        start_vertex(out);
    }
    // A face's corner count and `texcoord` values, which may come in
    // either order.
    let mut corners = None;
    let mut texcoords: Option<Vec<f32>> = None;
    for (k, prop) in e.props.iter().enumerate() {
        match (prop.kind, e.role) {
            (Kind::Scalar(ty), Role::Vertex(xyz)) => match xyz.iter().position(|&c| c == k) {
                Some(c) => p[c] = values.real(ty)? as f32,
                None => match e.attrs.get(k).copied().flatten() {
                    Some(slot) => set_attribute(out, slot, values.real(ty)?),
                    None => values.skip(ty, 1)?,
                },
            },
            (Kind::Scalar(ty), _) => values.skip(ty, 1)?,
            (Kind::List { count, item }, Role::Face(list)) if list == k => {
                let n = list_count(values, count, at)?;
                if n < 3 {
                    return Err(error(Malformed::FaceTooSmall { count: n }, at));
                }
                corners = Some(n);
                let first = vertex_index(values.int(item)?, vertices, at)?;
                let mut prev = vertex_index(values.int(item)?, vertices, at)?;
                for _ in 2..n {
                    let next = vertex_index(values.int(item)?, vertices, at)?;
                    out.mesh.triangles.push([first, prev, next]);
                    prev = next;
                }
                if n > 3 {
                    out.check_growth()?;
                }
            }
            (Kind::List { count, item }, Role::Face(_)) if e.texcoord.is_some_and(|t| t.0 == k) => {
                let n = list_count(values, count, at)?;
                // Each value takes a byte at least: a lying count ends at
                // the end of the data, not in a huge allocation.
                let mut v = Vec::new();
                for _ in 0..n {
                    v.push(values.real(item)? as f32);
                }
                texcoords = Some(v);
            }
            (Kind::List { count, item }, Role::Strips(list)) if list == k => {
                let n = list_count(values, count, at)?;
                let mut strip = Strip::default();
                for _ in 0..n {
                    match values.int(item)? {
                        -1 => strip = Strip::default(),
                        index => {
                            let v = vertex_index(index, vertices, at)?;
                            if let Some(t) = strip.push(v) {
                                out.mesh.triangles.push(t);
                            }
                        }
                    }
                }
                out.check_growth()?;
            }
            (Kind::List { count, item }, _) => {
                let n = list_count(values, count, at)?;
                values.skip(item, n)?;
            }
        }
    }
    if let Some((_, s)) = e.texcoord {
        add_corner_texcoords(out, s, corners, texcoords);
    }
    if let Role::Vertex(_) = e.role {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(error(Malformed::NonFinite { vertex: i }, at));
        }
        out.mesh.positions.push(p);
    }
    Ok(())
}

/// Makes room for one vertex's values in every per-vertex stream (zeros,
/// which [`set_attribute`] then overwrites).
fn start_vertex(out: &mut Builder) {
    for p in out.streams.iter_mut().filter(|p| p.per_vertex) {
        let s = &mut p.stream;
        s.values.extend((0..s.dims).map(|_| 0.0));
    }
}

/// Sets a component of the vertex [`start_vertex`] made room for.
fn set_attribute(out: &mut Builder, slot: Slot, value: f64) {
    let s = &mut out.streams[slot.stream].stream;
    let at = s.values.len() - usize::from(s.dims) + slot.comp;
    s.values[at] = (value / slot.divisor) as f32;
}

/// Adds a face's `texcoord` list to stream `s`, fanned as the face is: the
/// stream is dropped (broken) if the list does not hold two values per
/// corner.
fn add_corner_texcoords(out: &mut Builder, s: usize, corners: Option<u64>, uv: Option<Vec<f32>>) {
    let pending = &mut out.streams[s];
    match (corners, uv) {
        (Some(n), Some(uv)) if uv.len() as u64 == 2 * n && !pending.broken => {
            let stream = &mut pending.stream;
            let base = stream.value_count() as u32;
            stream.values.extend_from_slice(&uv);
            for k in 1..n as u32 - 1 {
                stream.corners.push([base, base + k, base + k + 1]);
            }
        }
        _ => pending.broken = true,
    }
}

/// The last two vertices of a triangle strip and the parity of the next
/// triangle.
#[derive(Default)]
struct Strip {
    a: Option<u32>,
    b: Option<u32>,
    odd: bool,
}

impl Strip {
    /// Adds a vertex; returns the triangle it completes, if any.
    fn push(&mut self, c: u32) -> Option<[u32; 3]> {
        let triangle = match (self.a, self.b) {
            // Every other triangle of a strip is wound the other way round;
            // swapping its first two corners restores the strip's orientation.
            (Some(a), Some(b)) if self.odd => Some([b, a, c]),
            (Some(a), Some(b)) => Some([a, b, c]),
            _ => None,
        };
        if triangle.is_some() {
            self.odd = !self.odd;
        }
        self.a = self.b;
        self.b = Some(c);
        triangle
    }
}

/// Reads a whole binary element, with fast paths for the layouts nearly
/// every file uses: fixed-size vertex records, and faces that are
/// triangles with a one-byte count and 32-bit indices.
fn read_binary_element(
    values: &mut Binary,
    e: &Element,
    vertices: u64,
    out: &mut Builder,
) -> Result<(), Error> {
    match e.role {
        Role::Vertex(xyz) => {
            if let Some(size) = e.fixed_record_size() {
                return read_fixed_vertices(values, e, xyz, size, out);
            }
        }
        Role::Face(_) => {
            if let [Property {
                kind:
                    Kind::List {
                        count: Scalar::U8,
                        item: item @ (Scalar::I32 | Scalar::U32),
                    },
                ..
            }] = e.props[..]
            {
                // Read as u32, a negative i32 is >= 2^31 and fails the range
                // check, and then goes the general way that reports it.
                if item == Scalar::U32 || vertices <= 1 << 31 {
                    return read_triangle_faces(values, e, vertices, out);
                }
            }
        }
        Role::Other => {
            if let Some(size) = e.fixed_record_size() {
                // Nothing to look at: skip all records at once.
                return values.skip(Scalar::U8, e.count.saturating_mul(size as u64));
            }
        }
        Role::Strips(_) => {}
    }
    for i in 0..e.count {
        read_record(values, e, i, vertices, out)?;
    }
    Ok(())
}

fn read_fixed_vertices(
    values: &mut Binary,
    e: &Element,
    xyz: [usize; 3],
    size: usize,
    out: &mut Builder,
) -> Result<(), Error> {
    let bytes = usize::try_from(e.count)
        .ok()
        .and_then(|n| n.checked_mul(size))
        .filter(|&b| b <= values.data.len() - values.pos)
        .ok_or_else(|| values.truncated())?;
    let start = values.pos;
    let records = values.data.get(start..start + bytes).unwrap_or_default();
    // Offsets and types of x, y, z inside a record, and of the attributes.
    let mut offset = 0;
    let mut layout = [(0usize, Scalar::F32); 3];
    let mut attributes = Vec::new();
    for (k, p) in e.props.iter().enumerate() {
        if let Kind::Scalar(ty) = p.kind {
            if let Some(c) = xyz.iter().position(|&x| x == k) {
                layout[c] = (offset, ty);
            }
            if let Some(slot) = e.attrs.get(k).copied().flatten() {
                attributes.push((offset, ty, slot));
            }
            offset += ty.size();
        }
    }
    let big = values.big;
    if size == 0 {
        return Ok(());
    }
    for (i, record) in records.chunks_exact(size).enumerate() {
        if !attributes.is_empty() {
            start_vertex(out);
            for &(off, ty, slot) in &attributes {
                set_attribute(out, slot, scalar_at(record, off, ty, big));
            }
        }
        let positions = &mut out.mesh.positions;
        let mut p = [0f32; 3];
        for (c, &(off, ty)) in p.iter_mut().zip(&layout) {
            *c = scalar_at(record, off, ty, big) as f32;
        }
        if !p.iter().all(|c| c.is_finite()) {
            let at = Location::Byte(values.base + (start + i * size) as u64);
            return Err(error(Malformed::NonFinite { vertex: i as u64 }, at));
        }
        positions.push(p);
    }
    values.pos += bytes;
    Ok(())
}

/// The number of type `ty` at `off` in `record`; the caller guarantees
/// that it fits (0 otherwise, never a panic).
#[inline(always)]
fn scalar_at(record: &[u8], off: usize, ty: Scalar, big: bool) -> f64 {
    macro_rules! at {
        ($t:ty) => {{
            const N: usize = core::mem::size_of::<$t>();
            match record.get(off..).and_then(|r| r.first_chunk::<N>()) {
                Some(&b) if big => <$t>::from_be_bytes(b),
                Some(&b) => <$t>::from_le_bytes(b),
                None => <$t>::default(),
            }
        }};
    }
    match ty {
        Scalar::I8 => f64::from(at!(i8)),
        Scalar::U8 => f64::from(at!(u8)),
        Scalar::I16 => f64::from(at!(i16)),
        Scalar::U16 => f64::from(at!(u16)),
        Scalar::I32 => f64::from(at!(i32)),
        Scalar::U32 => f64::from(at!(u32)),
        Scalar::F32 => f64::from(at!(f32)),
        Scalar::F64 => at!(f64),
    }
}

/// Faces with a `uchar` count and 32-bit indices: triangles in one tight
/// loop, anything else (polygons, bad indices, the end of the data)
/// through [`read_record`].
fn read_triangle_faces(
    values: &mut Binary,
    e: &Element,
    vertices: u64,
    out: &mut Builder,
) -> Result<(), Error> {
    let data = values.data;
    let big = values.big;
    let word = |b: [u8; 4]| {
        if big {
            u32::from_be_bytes(b)
        } else {
            u32::from_le_bytes(b)
        }
    };
    for i in 0..e.count {
        if let Some(r) = data.get(values.pos..).and_then(|r| r.first_chunk::<13>()) {
            if r[0] == 3 {
                let a = word([r[1], r[2], r[3], r[4]]);
                let b = word([r[5], r[6], r[7], r[8]]);
                let c = word([r[9], r[10], r[11], r[12]]);
                if u64::from(a.max(b).max(c)) < vertices {
                    out.mesh.triangles.push([a, b, c]);
                    values.pos += 13;
                    continue;
                }
            }
        }
        read_record(values, e, i, vertices, out)?;
    }
    Ok(())
}

/// Writes binary little-endian PLY: float x, y, z and a `uchar` count
/// with `int` indices (`uint` when indices do not fit an `int`), the
/// layout the fast path of the reader takes.
pub(super) fn write<W: Write>(w: &mut W, mesh: &TriMesh) -> io::Result<()> {
    let index_type = if mesh.positions.len() <= 1 << 31 {
        "int"
    } else {
        "uint"
    };
    write!(
        w,
        "ply\nformat binary_little_endian 1.0\ncomment written by swm\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {}\nproperty list uchar {index_type} vertex_indices\nend_header\n",
        mesh.positions.len(),
        mesh.triangles.len()
    )?;
    for p in &mesh.positions {
        let mut record = [0u8; 12];
        for (chunk, c) in record.chunks_exact_mut(4).zip(p) {
            chunk.copy_from_slice(&c.to_le_bytes());
        }
        w.write_all(&record)?;
    }
    for t in &mesh.triangles {
        let mut record = [3u8; 13];
        for (chunk, v) in record[1..].chunks_exact_mut(4).zip(t) {
            chunk.copy_from_slice(&v.to_le_bytes());
        }
        w.write_all(&record)?;
    }
    Ok(())
}

/// Writes binary little-endian PLY with the attributes it has property
/// names for, one vertex per distinct position and values (see
/// `AttributedMesh::split_vertices`): float `nx ny nz`, float `u v`
/// (texture set 0), and `red green blue [alpha]`, as `uchar` when every
/// component is exactly `k / 255` (what an 8-bit file read back gives),
/// as `float` otherwise. Returns what PLY cannot hold (other texture and
/// colour sets, a third texture coordinate, generic streams), which is
/// not written. Without any stream it can hold, the file is [`write`]'s.
pub(super) fn write_attributed<W: Write>(w: &mut W, m: &AttributedMesh) -> io::Result<Attributes> {
    let (split, unwritten) = super::attributes::split_kept(m, super::attributes::per_vertex);
    let Some(split) = split else {
        write(w, &m.mesh)?;
        return Ok(unwritten);
    };
    let normal = split.stream(AttributeKind::Normal);
    let uv = split
        .stream(AttributeKind::TexCoord(0))
        .filter(|s| s.dims == 2);
    let colour = split.stream(AttributeKind::Color(0));
    // Exactly as the reader decodes a `uchar` colour.
    let byte = |c: f32| {
        let k = (f64::from(c) * 255.0).round();
        (0.0..=255.0).contains(&k) && (k / 255.0) as f32 == c
    };
    let colour_bytes = colour.is_some_and(|c| c.values.iter().all(|&c| byte(c)));
    let index_type = if split.mesh.positions.len() <= 1 << 31 {
        "int"
    } else {
        "uint"
    };
    let mut header = String::from("ply\nformat binary_little_endian 1.0\ncomment written by swm\n");
    header += &format!(
        "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
        split.mesh.positions.len()
    );
    let mut names: Vec<&str> = Vec::new();
    if normal.is_some() {
        names.extend(["nx", "ny", "nz"]);
    }
    if uv.is_some() {
        names.extend(["u", "v"]);
    }
    for name in names {
        header += &format!("property float {name}\n");
    }
    if let Some(c) = colour {
        let ty = if colour_bytes { "uchar" } else { "float" };
        for name in ["red", "green", "blue", "alpha"]
            .iter()
            .take(usize::from(c.dims))
        {
            header += &format!("property {ty} {name}\n");
        }
    }
    header += &format!(
        "element face {}\nproperty list uchar {index_type} vertex_indices\nend_header\n",
        split.mesh.triangles.len()
    );
    w.write_all(header.as_bytes())?;
    let mut record = Vec::with_capacity(64);
    for (v, p) in split.mesh.positions.iter().enumerate() {
        record.clear();
        let floats = [normal, uv]
            .into_iter()
            .flatten()
            .flat_map(|s| s.value(v as u32));
        for c in p.iter().chain(floats) {
            record.extend_from_slice(&c.to_le_bytes());
        }
        if let Some(c) = colour {
            for &c in c.value(v as u32) {
                match colour_bytes {
                    true => record.push((f64::from(c) * 255.0).round() as u8),
                    false => record.extend_from_slice(&c.to_le_bytes()),
                }
            }
        }
        w.write_all(&record)?;
    }
    for t in &split.mesh.triangles {
        let mut record = [3u8; 13];
        for (chunk, v) in record[1..].chunks_exact_mut(4).zip(t) {
            chunk.copy_from_slice(&v.to_le_bytes());
        }
        w.write_all(&record)?;
    }
    Ok(unwritten)
}

#[cfg(test)]
mod tests {
    use super::super::tests::{garbage, malformed, read};
    use super::super::MeshFormat;
    use super::*;

    const TYPES: [&str; 16] = [
        "char", "int8", "uchar", "uint8", "short", "int16", "ushort", "uint16", "int", "int32",
        "uint", "uint32", "float", "float32", "double", "float64",
    ];

    /// `v` in the binary encoding of PLY type `ty`.
    fn encode(ty: &str, v: f64, big: bool) -> Vec<u8> {
        macro_rules! e {
            ($t:ty) => {
                if big {
                    (v as $t).to_be_bytes().to_vec()
                } else {
                    (v as $t).to_le_bytes().to_vec()
                }
            };
        }
        match ty {
            "char" | "int8" => e!(i8),
            "uchar" | "uint8" => e!(u8),
            "short" | "int16" => e!(i16),
            "ushort" | "uint16" => e!(u16),
            "int" | "int32" => e!(i32),
            "uint" | "uint32" => e!(u32),
            "float" | "float32" => e!(f32),
            "double" | "float64" => e!(f64),
            _ => unreachable!("{ty}"),
        }
    }

    /// A PLY value in `encoding` ("ascii", "binary_little_endian", ...).
    fn value(encoding: &str, ty: &str, v: f64) -> Vec<u8> {
        match encoding {
            "ascii" => format!("{v} ").into_bytes(),
            e => encode(ty, v, e == "binary_big_endian"),
        }
    }

    fn ply(encoding: &str, header: &str, body: &[u8]) -> Vec<u8> {
        let mut bytes = format!("ply\nformat {encoding} 1.0\n{header}end_header\n").into_bytes();
        bytes.extend_from_slice(body);
        bytes
    }

    const ENCODINGS: [&str; 3] = ["ascii", "binary_little_endian", "binary_big_endian"];

    /// A square (two triangles), with its coordinates of type `xyz`, the
    /// face list of types `count` and `item`, and extra properties and
    /// elements around them that must be skipped.
    fn square(encoding: &str, xyz: &str, count: &str, item: &str, extras: bool) -> Vec<u8> {
        let mut header = String::new();
        let mut body = Vec::new();
        let v = |ty: &str, x: f64| value(encoding, ty, x);
        let newline = |body: &mut Vec<u8>| {
            if encoding == "ascii" {
                body.push(b'\n');
            }
        };
        if extras {
            header.push_str("comment leading element with lists\nobj_info made by hand\n");
            header.push_str("element material 2\nproperty list uchar float rgb\nproperty int id\n");
            for m in 0..2 {
                body.extend(v("uchar", 3.0));
                for c in [0.25, 0.5, 0.75] {
                    body.extend(v("float", c));
                }
                body.extend(v("int", m as f64));
                newline(&mut body);
            }
        }
        header.push_str("element vertex 4\n");
        if extras {
            header.push_str("property uchar red\n");
        }
        header.push_str(&format!("property {xyz} x\nproperty {xyz} y\n"));
        if extras {
            header.push_str("property list ushort double weights\n");
        }
        header.push_str(&format!("property {xyz} z\n"));
        if extras {
            header.push_str("property double nx\n");
        }
        let corners = [
            [0.0, 0.0, 1.0],
            [2.0, 0.0, 1.0],
            [2.0, 3.0, 1.0],
            [0.0, 3.0, -1.0],
        ];
        for (i, p) in corners.iter().enumerate() {
            // Unsigned types cannot hold -1.
            let z = if xyz.starts_with('u') { 1.0 } else { p[2] };
            if extras {
                body.extend(v("uchar", 200.0));
            }
            body.extend(v(xyz, p[0]));
            body.extend(v(xyz, p[1]));
            if extras {
                body.extend(v("ushort", i as f64));
                for _ in 0..i {
                    body.extend(v("double", 0.5));
                }
            }
            body.extend(v(xyz, z));
            if extras {
                body.extend(v("double", -0.5));
            }
            newline(&mut body);
        }
        header.push_str("element face 1\n");
        if extras {
            header.push_str("property uchar flags\n");
        }
        header.push_str(&format!("property list {count} {item} vertex_indices\n"));
        if extras {
            header.push_str("property list uchar float texcoord\n");
        }
        if extras {
            body.extend(v("uchar", 7.0));
        }
        body.extend(v(count, 4.0));
        for i in [0.0, 1.0, 2.0, 3.0] {
            body.extend(v(item, i));
        }
        if extras {
            body.extend(v("uchar", 2.0));
            body.extend(v("float", 0.5));
            body.extend(v("float", 0.5));
        }
        newline(&mut body);
        if extras {
            header.push_str("element trailer 1\nproperty list int uchar bytes\n");
            body.extend(v("int", 3.0));
            for b in [1.0, 2.0, 3.0] {
                body.extend(v("uchar", b));
            }
            newline(&mut body);
        }
        ply(encoding, &header, &body)
    }

    fn check_square(mesh: &TriMesh, xyz: &str) {
        let z = if xyz.starts_with('u') { 1.0 } else { -1.0 };
        let expected = [
            [0.0, 0.0, 1.0],
            [2.0, 0.0, 1.0],
            [2.0, 3.0, 1.0],
            [0.0, 3.0, z],
        ];
        assert_eq!(mesh.positions, expected, "{xyz}");
        assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]], "{xyz}");
    }

    #[test]
    fn every_coordinate_type_in_every_encoding() {
        for encoding in ENCODINGS {
            for xyz in TYPES {
                for extras in [false, true] {
                    let bytes = square(encoding, xyz, "uchar", "int", extras);
                    let mesh = read(&bytes, MeshFormat::Ply)
                        .unwrap_or_else(|e| panic!("{encoding} {xyz} {extras}: {e}"));
                    check_square(&mesh, xyz);
                }
            }
        }
    }

    /// `\n`, `\r\n` and a lone `\r` end header lines (and ASCII data
    /// lines) alike, as old Mac exporters write them; after a lone `\r`,
    /// binary data that starts with a `\n` byte keeps it.
    #[test]
    fn every_line_ending_reads_alike() {
        for eol in ["\n", "\r\n", "\r"] {
            for encoding in ENCODINGS {
                let bytes = square(encoding, "float", "uchar", "int", true);
                let end = bytes
                    .windows(11)
                    .position(|w| w == b"end_header\n")
                    .unwrap()
                    + 11;
                let mut text = String::from_utf8_lossy(&bytes[..end]).replace('\n', eol);
                let mut file = if encoding == "ascii" {
                    text.push_str(&String::from_utf8_lossy(&bytes[end..]).replace('\n', eol));
                    text.into_bytes()
                } else {
                    [text.as_bytes(), &bytes[end..]].concat()
                };
                let mesh = read(&file, MeshFormat::Ply)
                    .unwrap_or_else(|e| panic!("{eol:?} {encoding}: {e}"));
                check_square(&mesh, "float");
                // A header error names the line it is on.
                let at = file
                    .windows(16)
                    .position(|w| w == b"element material")
                    .unwrap();
                file[at..at + 7].copy_from_slice(b"elemenX");
                let (_, at) = malformed(read(&file, MeshFormat::Ply));
                assert_eq!(at, Some(Location::Line(5)), "{eol:?} {encoding}");
            }
            // Binary data whose first byte is 10, `\n`.
            let mut file = [
                "ply",
                "format binary_little_endian 1.0",
                "element vertex 3",
                "property uchar red",
                "property float x",
                "property float y",
                "property float z",
                "element face 1",
                "property list uchar int vertex_indices",
                "end_header",
                "",
            ]
            .join(eol)
            .into_bytes();
            for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
                file.push(10);
                file.extend(p.iter().flat_map(|c| c.to_le_bytes()));
            }
            file.push(3);
            file.extend([0i32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
            let mesh = read(&file, MeshFormat::Ply).unwrap_or_else(|e| panic!("{eol:?}: {e}"));
            assert_eq!(
                mesh.positions,
                [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
            );
            assert_eq!(mesh.triangles, [[0, 1, 2]], "{eol:?}");
        }
    }

    #[test]
    fn every_count_and_index_type() {
        let integers = TYPES
            .iter()
            .filter(|t| !t.contains("float") && **t != "double");
        for encoding in ENCODINGS {
            for count in integers.clone() {
                for item in integers.clone() {
                    let bytes = square(encoding, "float", count, item, false);
                    let mesh = read(&bytes, MeshFormat::Ply)
                        .unwrap_or_else(|e| panic!("{encoding} {count} {item}: {e}"));
                    check_square(&mesh, "float");
                }
            }
        }
    }

    const TRIANGLE_HEADER: &str = "element vertex 3\nproperty float x\nproperty float y\n\
property float z\nelement face 1\nproperty list uchar int vertex_indices\n";

    /// One triangle in binary: vertices (0,0,0), (1,0,0), (0,1,0).
    fn binary_triangle(big: bool, indices: [i32; 3]) -> Vec<u8> {
        let mut body = Vec::new();
        for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for c in p {
                body.extend(encode("float", c.into(), big));
            }
        }
        body.push(3);
        for i in indices {
            body.extend(encode("int", i.into(), big));
        }
        let encoding = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        ply(encoding, TRIANGLE_HEADER, &body)
    }

    #[test]
    fn binary_fast_paths_in_both_byte_orders() {
        for big in [false, true] {
            let mesh = read(&binary_triangle(big, [0, 1, 2]), MeshFormat::Ply).unwrap();
            assert_eq!(
                mesh.positions,
                [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
            );
            assert_eq!(mesh.triangles, [[0, 1, 2]]);
            let header_end = binary_triangle(big, [0, 1, 2]).len() - 36 - 13;
            for (indices, index) in [
                ([0, 1, 3], 3),
                ([0, -1, 2], -1),
                ([i32::MIN, 1, 2], -(1 << 31)),
            ] {
                let (what, at) = malformed(read(&binary_triangle(big, indices), MeshFormat::Ply));
                assert_eq!(what, Malformed::IndexOutOfRange { index, vertices: 3 });
                assert_eq!(at, Some(Location::Byte(header_end as u64 + 36)));
            }
        }
    }

    #[test]
    fn crlf_header_and_faces_before_vertices() {
        let text = "ply\r\nformat ascii 1.0\r\ncomment CRLF\r\nelement face 2\r\n\
property list uchar uint vertex_index\r\nelement vertex 4\r\nproperty double x\r\n\
property double y\r\nproperty double z\r\nend_header\r\n3 0 1 2\r\n3 0 2 3\r\n\
0 0 1\r\n2 0 1\r\n2 3 1\r\n0 3 -1\r\n";
        let mesh = read(text.as_bytes(), MeshFormat::Ply).unwrap();
        check_square(&mesh, "double");
    }

    #[test]
    fn tristrips_alternate_and_restart() {
        let header = "element vertex 7\nproperty float x\nproperty float y\nproperty float z\n\
element tristrips 1\nproperty list int int vertex_indices\n";
        let body = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n5 5 5\n6 5 5\n5 6 5\n9 0 1 2 3 -1 4 5 6 4\n";
        let mesh = read(&ply("ascii", header, body.as_bytes()), MeshFormat::Ply).unwrap();
        // Strip 0 1 2 3: (0 1 2) then (2 1 3); strip 4 5 6 4: (4 5 6), (6 5 4)
        // which is degenerate in position but kept.
        assert_eq!(mesh.triangles, [[0, 1, 2], [2, 1, 3], [4, 5, 6], [6, 5, 4]]);
        let bad = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n5 5 5\n6 5 5\n5 6 5\n4 0 1 2 -2\n";
        let (what, _) = malformed(read(&ply("ascii", header, bad.as_bytes()), MeshFormat::Ply));
        assert_eq!(
            what,
            Malformed::IndexOutOfRange {
                index: -2,
                vertices: 7
            }
        );
    }

    #[test]
    fn polygons_are_fanned() {
        let header = "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
element face 2\nproperty list uchar int vertex_indices\n";
        let body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 2 0\n5 0 1 2 3 4\n3 4 3 2\n";
        let mesh = read(&ply("ascii", header, body.as_bytes()), MeshFormat::Ply).unwrap();
        assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3], [0, 3, 4], [4, 3, 2]]);
    }

    #[test]
    fn lying_counts_fail_fast_without_allocating() {
        let header = "element vertex 2000000000\nproperty float x\nproperty float y\n\
property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
        for encoding in ENCODINGS {
            let bytes = ply(encoding, header, &[b'0'; 120]);
            let (result, largest) =
                crate::test_alloc::largest_allocation(|| read(&bytes, MeshFormat::Ply));
            let (what, at) = malformed(result);
            // Refused before reserving anything for 2e9 vertices (the
            // measure is the allocation, not the time: a loaded machine
            // passes).
            assert!(
                largest < 1 << 20,
                "{encoding}: {largest} bytes allocated at once"
            );
            let possible = if encoding == "ascii" { 20 } else { 10 };
            assert_eq!(
                what,
                Malformed::CountTooLarge {
                    element: "vertex",
                    declared: 2_000_000_000,
                    possible
                },
                "{encoding}"
            );
            assert_eq!(at, Some(Location::Line(3)));
        }
        // A face count that cannot fit, and a huge unknown element.
        let faces = "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n\
element face 4000000000\nproperty list uchar int vertex_indices\n";
        let (what, _) = malformed(read(
            &ply("binary_little_endian", faces, &[0; 100]),
            MeshFormat::Ply,
        ));
        assert!(matches!(
            what,
            Malformed::CountTooLarge {
                element: "face",
                ..
            }
        ));
        let other = "element junk 18446744073709551615\nproperty uchar a\n";
        let (what, _) = malformed(read(
            &ply("binary_big_endian", other, &[0; 10]),
            MeshFormat::Ply,
        ));
        assert!(matches!(
            what,
            Malformed::CountTooLarge {
                element: "extra",
                ..
            }
        ));
        // A list count that lies inside a record.
        let lists = "element vertex 1\nproperty list uint float junk\nproperty float x\n\
property float y\nproperty float z\n";
        let mut body = u32::MAX.to_le_bytes().to_vec();
        body.extend([0; 12]);
        let (what, at) = malformed(read(
            &ply("binary_little_endian", lists, &body),
            MeshFormat::Ply,
        ));
        assert_eq!(what, Malformed::Truncated);
        assert!(matches!(at, Some(Location::Byte(_))));
        // Elements without properties take no bytes, whatever their count.
        let empty = format!("element nothing 18446744073709551615\n{TRIANGLE_HEADER}");
        let body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert!(read(&ply("ascii", &empty, body.as_bytes()), MeshFormat::Ply).is_ok());
        // Limits apply once the bytes could hold the count.
        let limits = Limits {
            max_vertices: 2,
            ..Limits::default()
        };
        let result = super::super::read_mesh_bytes(
            &binary_triangle(false, [0, 1, 2]),
            MeshFormat::Ply,
            &limits,
        );
        assert!(matches!(result, Err(Error::LimitExceeded(_))));
    }

    #[test]
    fn truncated_binary_reports_the_byte() {
        let whole = binary_triangle(false, [0, 1, 2]);
        // Cuts in the face record, which the count check cannot see.
        for cut in [whole.len() - 1, whole.len() - 5, whole.len() - 13] {
            let (what, at) = malformed(read(&whole[..cut], MeshFormat::Ply));
            assert_eq!(what, Malformed::Truncated, "cut at {cut}");
            assert_eq!(at, Some(Location::Byte(cut as u64)));
        }
        // Cuts so deep that the vertices cannot fit in what is left.
        for cut in [whole.len() - 20, whole.len() - 49] {
            let (what, at) = malformed(read(&whole[..cut], MeshFormat::Ply));
            assert!(matches!(
                what,
                Malformed::CountTooLarge {
                    element: "vertex",
                    ..
                }
            ));
            assert_eq!(at, Some(Location::Line(3)));
        }
    }

    #[test]
    fn bad_values() {
        let ascii = |body: &str| {
            read(
                &ply("ascii", TRIANGLE_HEADER, body.as_bytes()),
                MeshFormat::Ply,
            )
        };
        // Lines 1 to 9 are the header; vertices are on lines 10 to 12.
        let cases: [(&str, Malformed, u64); 8] = [
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                Malformed::IndexOutOfRange {
                    index: 3,
                    vertices: 3,
                },
                13,
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                Malformed::IndexOutOfRange {
                    index: -1,
                    vertices: 3,
                },
                13,
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                Malformed::FaceTooSmall { count: 2 },
                13,
            ),
            (
                "0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n",
                Malformed::BadSyntax("a list count is negative"),
                13,
            ),
            (
                "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
                Malformed::NonFinite { vertex: 1 },
                11,
            ),
            (
                "0 0 0\n1 0 0\n0 1e39 0\n3 0 1 2\n",
                Malformed::NonFinite { vertex: 2 },
                12,
            ),
            ("0 0 0\n1 0x1 0\n0 1 0\n3 0 1 2\n", Malformed::BadNumber, 11),
            ("0 0 0\n1 0 0\n0 1 0\n3 0 1.0 2\n", Malformed::BadNumber, 13),
        ];
        for (body, what, line) in cases {
            assert_eq!(
                malformed(ascii(body)),
                (what, Some(Location::Line(line))),
                "{body:?}"
            );
        }
        let (what, at) = malformed(ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1"));
        assert_eq!((what, at), (Malformed::Truncated, Some(Location::Line(13))));
        // Doubles beyond the f32 range, in binary.
        let header = "element vertex 1\nproperty double x\nproperty double y\nproperty double z\n";
        let mut body = Vec::new();
        for v in [0.0, 1e300, 0.0] {
            body.extend(encode("double", v, false));
        }
        let (what, _) = malformed(read(
            &ply("binary_little_endian", header, &body),
            MeshFormat::Ply,
        ));
        assert_eq!(what, Malformed::NonFinite { vertex: 0 });
    }

    #[test]
    fn bad_headers() {
        let header = |h: &str| malformed(read(h.as_bytes(), MeshFormat::Ply)).0;
        let bad = |why| Malformed::BadHeader(why);
        assert_eq!(header("plx\n"), bad("the file does not start with \"ply\""));
        assert_eq!(
            header("ply\nformat utf8 1.0\nend_header\n"),
            bad("unknown format")
        );
        assert_eq!(
            header("ply\nformat ascii 2.0\nend_header\n"),
            Malformed::Unsupported("PLY versions other than 1.0")
        );
        assert_eq!(
            header("ply\nelement vertex 0\nend_header\n"),
            bad("no format line")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nproperty float x\n"),
            bad("a property precedes every element")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement vertex -1\n"),
            bad("an element count is not a number")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement v 1\nproperty float16 x\n"),
            bad("unknown property type")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement v 1\nproperty list float int x\n"),
            bad("a list count type is not an integer type")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n"),
            bad("the vertex element lacks scalar x, y and z")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n"),
            bad("vertex_indices is not a list of integers")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int indices\nend_header\n"),
            bad("a face or tristrips element has no vertex_indices")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement vertex 1\nfoo\n"),
            bad("unknown header keyword")
        );
        assert_eq!(
            header("ply\nformat ascii 1.0\nelement vertex 1\n"),
            Malformed::Truncated
        );
        let mut bytes = b"ply\nformat binary_little_endian 1.0\n".to_vec();
        bytes.extend(garbage(4096, 7));
        assert!(matches!(
            malformed(read(&bytes, MeshFormat::Ply)).0,
            Malformed::BadHeader(_) | Malformed::Truncated
        ));
    }
}
