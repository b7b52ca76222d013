//! What a mesh file carried besides positions and faces that was not
//! kept (texture coordinates, normals, colours): all of them when a
//! `TriMesh` is read, those the streams of an `AttributedMesh` could not
//! take otherwise; and what a writer could not write. So that a program
//! can say so instead of losing them in silence.
//!
//! Each reader sets the flags from what the file *declares* where the
//! format declares it (a PLY property, an OFF keyword prefix, a glTF
//! primitive attribute) and from what it holds otherwise (OBJ `vt` and
//! `vn` statements, `v` lines with colours). STL's facet normals are not
//! vertex attributes (they follow from the triangles), so STL reports
//! none.

/// Which vertex attributes an input file carried that a [`TriMesh`](crate::TriMesh)
/// cannot hold, and so were dropped by the reader.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Attributes {
    /// Texture coordinates (OBJ `vt`, PLY `u`/`v`, `s`/`t`,
    /// `texture_u`/`texture_v` or a face `texcoord` list, OFF `ST`, glTF
    /// `TEXCOORD_n`).
    pub uv: bool,
    /// Vertex normals (OBJ `vn`, PLY `nx`/`ny`/`nz`, OFF `N`, glTF `NORMAL`).
    pub normals: bool,
    /// Vertex colours (OBJ `v x y z r g b`, PLY `red`/`green`/`blue`/`alpha`,
    /// OFF `C`, glTF `COLOR_n`).
    pub colors: bool,
    /// Generic attribute streams ([`AttributeKind::Generic`](crate::AttributeKind::Generic)),
    /// which no reader makes and no writer writes.
    pub generic: bool,
}

impl Attributes {
    /// Whether the file carried none of them.
    pub fn is_empty(&self) -> bool {
        *self == Attributes::default()
    }

    /// The attributes present, named in words ("texture coordinates",
    /// "normals", "colours"), in that order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> {
        [
            (self.uv, "texture coordinates"),
            (self.normals, "normals"),
            (self.colors, "colours"),
            (self.generic, "generic attributes"),
        ]
        .into_iter()
        .filter_map(|(present, name)| present.then_some(name))
    }

    /// The flag of an attribute kind.
    pub(crate) fn of(kind: crate::AttributeKind) -> Attributes {
        use crate::AttributeKind as K;
        let mut a = Attributes::default();
        match kind {
            K::Normal => a.normals = true,
            K::TexCoord(_) => a.uv = true,
            K::Color(_) => a.colors = true,
            K::Generic(_) => a.generic = true,
        }
        a
    }

    /// Both sets together.
    pub(crate) fn union(self, other: Attributes) -> Attributes {
        Attributes {
            uv: self.uv || other.uv,
            normals: self.normals || other.normals,
            colors: self.colors || other.colors,
            generic: self.generic || other.generic,
        }
    }
}

/// What writing an [`AttributedMesh`](crate::AttributedMesh) left out
/// because the format cannot hold it
/// ([`write_attributed_mesh`](super::write_attributed_mesh)).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct WriteReport {
    /// The attribute kinds some stream of which was not written.
    pub unwritten: Attributes,
}

/// What reading a mesh file found besides the mesh
/// ([`read_mesh_with_report`](super::read_mesh_with_report)).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadReport {
    /// The vertex attributes the file carried and the mesh does not keep.
    pub dropped: Attributes,
}

/// The streams a vertex-list format (OFF, PLY) holds: normals, colour set
/// 0 and a two-dimensional texture set 0.
pub(super) fn per_vertex(s: &crate::AttributeStream) -> bool {
    use crate::AttributeKind as K;
    match s.kind {
        K::Normal | K::Color(0) => true,
        K::TexCoord(0) => s.dims == 2,
        _ => false,
    }
}

/// `m` split into one vertex per distinct position and values of the
/// streams `kept` accepts (`None` when it accepts none), and the kinds of
/// the streams it does not, which a writer leaves out.
pub(super) fn split_kept(
    m: &crate::AttributedMesh,
    kept: impl Fn(&crate::AttributeStream) -> bool + Copy,
) -> (Option<crate::AttributedMesh>, Attributes) {
    let mut unwritten = Attributes::default();
    for s in m.streams.iter().filter(|s| !kept(s)) {
        unwritten = unwritten.union(Attributes::of(s.kind));
    }
    let split = m
        .streams
        .iter()
        .any(kept)
        .then(|| m.split_vertices_by(kept));
    (split, unwritten)
}
