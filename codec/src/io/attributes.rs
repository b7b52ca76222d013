//! What a mesh file carried besides positions and faces: the per-vertex
//! attributes swm does not code (texture coordinates, normals, colours),
//! so that a program can say they were dropped instead of losing them
//! in silence.
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
        ]
        .into_iter()
        .filter_map(|(present, name)| present.then_some(name))
    }

    /// Both sets together.
    pub(crate) fn union(self, other: Attributes) -> Attributes {
        Attributes {
            uv: self.uv || other.uv,
            normals: self.normals || other.normals,
            colors: self.colors || other.colors,
        }
    }
}

/// What reading a mesh file found besides the mesh
/// ([`read_mesh_with_report`](super::read_mesh_with_report)).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadReport {
    /// The vertex attributes the file carried and the mesh does not keep.
    pub dropped: Attributes,
}
