//! Decoder post-processing: Sharpen&Bend (M. Attene, *Surface Remeshing
//! and Applications*, 2004, chapter 8; design notes, ALGORITHMS.md §7-8).
//!
//! Feature-insensitive retiling cuts sharp edges and corners into chamfers.
//! [`sharpen`] (EdgeSharpener) finds the chamfers from the geometry alone,
//! splits them and snaps the new vertices onto the intersection of the
//! planes extrapolated from the smooth regions beside them; it tags the
//! edges it made sharp. [`bend`] (Bender) then refines the mesh by a
//! modified butterfly subdivision whose crease rules keep those tagged
//! edges sharp. Neither costs a bit in the file.
//!
//! The tags are the only thing the two steps share: [`SharpEdges`].
//!
//! Whether to run them is the caller's choice or, by default, the file's
//! [`hint`]: the encoder measures both on its own file and records the
//! better (format 1.1's ancillary `post` section).

use crate::prelude::*;

pub mod bend;
pub mod hint;
pub mod sharpen;

/// Undirected edges tagged sharp, as vertex pairs `[lo, hi]` (`lo < hi`),
/// sorted and without repeats, so that lookups are a binary search and two
/// tag sets compare equal exactly when they tag the same edges.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SharpEdges {
    pairs: Vec<[u32; 2]>,
}

impl SharpEdges {
    /// Tags the given edges; the order of each pair and of the list, and
    /// repeats, do not matter. Pairs joining a vertex to itself are dropped.
    pub fn new(pairs: impl IntoIterator<Item = [u32; 2]>) -> Self {
        let mut pairs: Vec<[u32; 2]> = pairs
            .into_iter()
            .filter(|[a, b]| a != b)
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        crate::sort::sort_unstable(&mut pairs);
        pairs.dedup();
        SharpEdges { pairs }
    }

    /// Whether the edge between `a` and `b` (either order) is tagged.
    pub fn contains(&self, a: u32, b: u32) -> bool {
        self.pairs.binary_search(&[a.min(b), a.max(b)]).is_ok()
    }

    /// The tagged edges, `[lo, hi]`, sorted.
    pub fn pairs(&self) -> &[[u32; 2]] {
        &self.pairs
    }

    /// Number of tagged edges.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// Whether no edge is tagged.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::SharpEdges;

    /// Fuzz finding (issue 8): a valid swing file with L ≈ 1e38 decodes
    /// to finite positions, but Bender's stencils overflow them to
    /// infinity; decoding with Sharpen&Bend must refuse, not return them.
    #[test]
    fn overflowing_post_processing_is_an_error() {
        let bytes = include_bytes!("testdata/fuzz-bend-overflow.swm");
        let plain = crate::decode(bytes, &Default::default()).unwrap();
        plain.validate().unwrap();
        let options = crate::DecodeOptions {
            sharpen: Some(true),
            bend_steps: Some(1),
            ..Default::default()
        };
        match crate::decode(bytes, &options) {
            Ok(mesh) => mesh.validate().unwrap(),
            Err(e) => assert!(matches!(e, crate::Error::Format(_)), "{e:?}"),
        }
    }

    #[test]
    fn sharp_edges_normalize_order_and_repeats() {
        let s = SharpEdges::new([[3, 1], [1, 3], [2, 2], [0, 5]]);
        assert_eq!(s.pairs(), &[[0, 5], [1, 3]]);
        assert!(s.contains(3, 1) && s.contains(5, 0));
        assert!(!s.contains(0, 1) && !s.contains(2, 2));
    }
}
