//! Section tags and the registry of tags defined by format 1.0.
//!
//! A tag is four ASCII letters. As in PNG's chunk names (PNG specification
//! §5.4), the case of the first letter says whether a decoder may skip the
//! section: upper case (bit 5 clear) is *critical*, lower case (bit 5 set)
//! is *ancillary*. The case of the other three letters carries no meaning.

use core::fmt;

/// A four-letter section tag.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Tag(pub [u8; 4]);

impl Tag {
    /// Critical. The mode's parameters (quantization, bounding box, angle
    /// bits, edge length, first triangle...); contents defined by the
    /// mode's page.
    pub const HEAD: Tag = Tag(*b"HEAD");
    /// Critical. Entropy-coded connectivity (CLERS symbols).
    pub const CLRS: Tag = Tag(*b"CLRS");
    /// Critical. Topology events: handles, holes, component starts.
    pub const TOPO: Tag = Tag(*b"TOPO");
    /// Critical. Entropy-coded geometry (angle symbols or coordinate
    /// residuals).
    pub const GEOM: Tag = Tag(*b"GEOM");
    /// Critical. SwingWrapper hole mask: one bit per coded triangle, set
    /// for the triangles the decoder drops (format-spec/05-swing.md). It
    /// changes the decoded mesh, so a decoder may not skip it.
    pub const HOLE: Tag = Tag(*b"HOLE");
    /// Critical. SwingWrapper remainder: a complete lossless (mode 0)
    /// file whose mesh is appended to the decoded one
    /// (format-spec/05-swing.md).
    pub const REST: Tag = Tag(*b"REST");
    /// Critical (format 1.1). SwingWrapper density: one level step per C
    /// tip, scaling its circle's radius (format-spec/05-swing.md).
    pub const DENS: Tag = Tag(*b"DENS");
    /// Critical (format 1.1). SwingWrapper CLERS symbols coded in the
    /// forward pass with the front's angles as context, in place of
    /// `CLRS` (format-spec/05-swing.md).
    pub const CLRF: Tag = Tag(*b"CLRF");
    /// Critical (format 1.1). SwingWrapper boundary loops: components
    /// whose retiling starts on a loop of the input, and the residuals
    /// that place the loop's points (format-spec/05-swing.md).
    pub const LOOP: Tag = Tag(*b"LOOP");
    /// Critical (format 1.1). SwingWrapper radius codes: one per C tip,
    /// moving it along its gate's bisecting plane, off the circle, onto a
    /// crease of the input (format-spec/05-swing.md).
    pub const RADS: Tag = Tag(*b"RADS");
    /// Critical (format 1.1). Lossless positions coded with the offsets
    /// of their predictions as context, in place of `GEOM`
    /// (format-spec/04-lossless.md).
    pub const GEOF: Tag = Tag(*b"GEOF");
    /// Critical (format 1.1). Lossless CLERS symbols coded last to first
    /// with the decoder's degrees at the active gate as context, in place
    /// of `CLRS` (format-spec/04-lossless.md).
    pub const CLRD: Tag = Tag(*b"CLRD");
    /// Critical (format 1.2). Displaced subdivision's base mesh: a
    /// complete lossless (mode 0) file (format-spec/07-displaced.md).
    pub const BASE: Tag = Tag(*b"BASE");
    /// Critical (format 1.2). Displaced subdivision's scalars, one
    /// range-coded chunk per level, coarse to fine
    /// (format-spec/07-displaced.md).
    pub const DISP: Tag = Tag(*b"DISP");
    /// Critical (format 1.2). Lossless vertex attributes: per stream its
    /// kind, quantization, seams and predicted values
    /// (format-spec/08-attributes.md).
    pub const ATTR: Tag = Tag(*b"ATTR");
    /// Ancillary. Key/value metadata (see [`meta_entries`](super::meta_entries)).
    pub const META: Tag = Tag(*b"meta");
    /// Ancillary (format 1.1). The encoder's post-processing hint:
    /// whether the decoder should run EdgeSharpener and how many Bender
    /// steps (format-spec/06-post.md; [`crate::post::hint`]).
    pub const POST: Tag = Tag(*b"post");

    /// Four ASCII letters (`A-Z`, `a-z`)?
    pub const fn is_valid(self) -> bool {
        let b = self.0;
        b[0].is_ascii_alphabetic()
            && b[1].is_ascii_alphabetic()
            && b[2].is_ascii_alphabetic()
            && b[3].is_ascii_alphabetic()
    }

    /// Must a decoder understand this section to decode the file? True when
    /// bit 5 of the first byte is clear (an upper-case first letter).
    pub const fn is_critical(self) -> bool {
        self.0[0] & 0x20 == 0
    }

    /// May a decoder that does not know this section skip it?
    pub const fn is_ancillary(self) -> bool {
        !self.is_critical()
    }

    /// Is this tag defined by the format version this crate implements
    /// ([`FORMAT_MAJOR`](super::FORMAT_MAJOR).[`FORMAT_MINOR`](super::FORMAT_MINOR))?
    pub fn is_known(self) -> bool {
        KNOWN_CRITICAL.contains(&self) || KNOWN_ANCILLARY.contains(&self)
    }

    /// The four bytes.
    pub const fn as_bytes(&self) -> &[u8; 4] {
        &self.0
    }
}

/// Critical tags of format 1.0, then those 1.1 and 1.2 added. A decoder rejects
/// any other critical tag.
/// The position in this list is the bit a parser uses to spot duplicates.
/// (At most 16: the parser keeps them in a `u16`.)
pub(crate) const KNOWN_CRITICAL: [Tag; 15] = [
    Tag::HEAD,
    Tag::CLRS,
    Tag::TOPO,
    Tag::GEOM,
    Tag::HOLE,
    Tag::REST,
    Tag::DENS,
    Tag::CLRF,
    Tag::LOOP,
    Tag::RADS,
    Tag::GEOF,
    Tag::CLRD,
    Tag::BASE,
    Tag::DISP,
    Tag::ATTR,
];

/// Ancillary tags of format 1.0, then those 1.1 added. Other ancillary
/// tags are skipped.
pub(crate) const KNOWN_ANCILLARY: [Tag; 2] = [Tag::META, Tag::POST];

impl fmt::Display for Tag {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0.escape_ascii())
    }
}

impl fmt::Debug for Tag {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Tag(\"{}\")", self.0.escape_ascii())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn criticality_follows_first_letter() {
        for t in KNOWN_CRITICAL {
            assert!(t.is_valid() && t.is_critical() && t.is_known(), "{t}");
        }
        for t in KNOWN_ANCILLARY {
            assert!(t.is_valid() && t.is_ancillary() && t.is_known(), "{t}");
        }
        assert!(Tag(*b"xTRA").is_ancillary());
        assert!(Tag(*b"Xtra").is_critical());
        assert!(!Tag(*b"xtra").is_known());
    }

    #[test]
    fn validity() {
        assert!(!Tag(*b"HEA1").is_valid());
        assert!(!Tag(*b"HE D").is_valid());
        assert!(!Tag([0, b'A', b'B', b'C']).is_valid());
        assert_eq!(
            format!("{:?}", Tag([b'A', 0, b'B', b'C'])),
            "Tag(\"A\\x00BC\")"
        );
    }
}
