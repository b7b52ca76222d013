//! Symbols, side information and the corner layout that the encoder and
//! the decoder share. Everything here must match on both sides exactly.
//!
//! The CLERS cases, seen from the triangle X being visited through its
//! gate (the edge shared with the triangle it was reached from):
//!
//! ```text
//!         C            L            E            R            S
//!     *-------*    *-------*    *-------*    *-------*    *-------*
//!      \  X  /     |\  X  /      \  X  /      \  X  /|     |\  X  /|
//!   new tip *    done|  *         |*|          *  |done     |  *   |
//!       (unvisited) left       both sides   right side   tip on the
//!                  visited      visited      visited     loop, both
//!                                                        sides open
//! ```
//!
//! * C: the tip vertex is new; continue through the right edge.
//! * L: the left neighbour is done; continue right.
//! * R: the right neighbour is done; continue left.
//! * S: the tip is already on the boundary but both neighbours are open:
//!   remember the left edge, continue right first.
//! * E: both neighbours done; resume at the last remembered left edge.
//!
//! Decoded corner layout: the triangle of visit number t owns corners 3t,
//! 3t+1, 3t+2, with 3t at the tip. Its gate faces corner 3t, its right
//! edge faces 3t+1 and its left edge faces 3t+2:
//!
//! ```text
//!                 3t (tip)
//!                  /\
//!     left edge   /  \   right edge
//!  (faces 3t+2)  /    \  (faces 3t+1)
//!               /      \
//!        3t+1  +--------+  3t+2
//!                 gate (faces 3t)
//! ```
//!
//! The first triangle of a component has no symbol; its corners 0, 1, 2
//! are the encoder's start corner c0, n(c0), p(c0), and the traversal
//! enters the second triangle through the edge facing corner 1.
//!
//! Bit bounds: with the fixed code C=0, L=110, R=101, S=100, E=111 a
//! closed genus-0 component costs at most 2 bits per triangle; the
//! adaptive coder of the container does far better on regular meshes.

use crate::prelude::*;

/// One CLERS symbol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Symbol {
    /// New tip vertex.
    C = 0,
    /// Left neighbour already visited.
    L = 1,
    /// Both neighbours visited.
    E = 2,
    /// Right neighbour already visited.
    R = 3,
    /// Tip already visited, both neighbours open: the boundary splits.
    S = 4,
}

impl Symbol {
    /// All symbols, in code order.
    pub const ALL: [Symbol; 5] = [Symbol::C, Symbol::L, Symbol::E, Symbol::R, Symbol::S];

    /// The symbol with this code, if any.
    pub fn from_code(code: u32) -> Option<Symbol> {
        Symbol::ALL.get(code as usize).copied()
    }

    /// Its letter.
    pub fn letter(self) -> char {
        ['C', 'L', 'E', 'R', 'S'][self as usize]
    }
}

/// Which edge of a triangle, in the decoded corner layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// The edge facing corner 3t+1.
    Right,
    /// The edge facing corner 3t+2.
    Left,
}

/// A handle: the left edge of the S triangle with symbol index `split` is
/// glued to the `side` edge of the later triangle with symbol index
/// `source` (an L, R or E triangle), instead of to a branch of its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SplitEvent {
    /// Symbol index of the S* triangle.
    pub split: u32,
    /// Symbol index of the triangle it is glued to (`source > split`).
    pub source: u32,
    /// Which edge of the source triangle.
    pub side: Side,
}

/// The connectivity of a closed oriented manifold, as coded.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Connectivity {
    /// CLERS symbols of all components, one per triangle but the first
    /// of each component, in visiting order.
    pub symbols: Vec<Symbol>,
    /// Handle events, sorted by `split`.
    pub splits: Vec<SplitEvent>,
    /// Number of connected components.
    pub components: u32,
    /// Number of vertices.
    pub vertices: u32,
}

impl Connectivity {
    /// Number of triangles: one per symbol plus each component's first.
    pub fn triangles(&self) -> u64 {
        self.symbols.len() as u64 + self.components as u64
    }

    /// Symbol ranges of the components, found from the stack depth: a
    /// component starts with one open gate, an S opens one more (unless it
    /// is an S*, whose left edge is glued by its event), an E closes one.
    /// `None` if the symbols do not split into exactly `components` parts.
    pub fn component_ranges(&self) -> Option<Vec<(usize, usize)>> {
        let mut ranges = Vec::with_capacity(self.components as usize);
        let mut splits = self.splits.iter().map(|e| e.split as usize).peekable();
        let mut depth = 0u64;
        let mut start = 0;
        for (i, &s) in self.symbols.iter().enumerate() {
            if depth == 0 {
                depth = 1;
                start = i;
            }
            match s {
                Symbol::S => {
                    if splits.peek() == Some(&i) {
                        splits.next();
                    } else {
                        depth += 1;
                    }
                }
                Symbol::E => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                ranges.push((start, i + 1));
            }
        }
        (depth == 0 && splits.next().is_none() && ranges.len() == self.components as usize)
            .then_some(ranges)
    }
}
