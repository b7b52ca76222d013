//! A four-ary min-heap: the collapse queue of `qem`.
//!
//! Why not `alloc::collections::BinaryHeap`: on a million-triangle scan
//! the quadric collapse pops about five million entries from a queue of
//! two million (most of them stale, skipped on the way), and a binary
//! heap's pop then walks 21 levels, nearly each a cache miss: a third of
//! the whole encode's time (BENCHMARKS.md, "Quadric collapse, the
//! queue"). Four children per node halve the levels, and the four sit
//! side by side in memory, so a level costs about one miss. Any correct
//! min-heap pops the same sequence of distinct values, so the collapse
//! order (and every file) is the one the binary heap gave.
//!
//! Invariant: every entry is no smaller than its parent (`slots[i] >=
//! slots[(i - 1) / 4]`); the smallest is at the root.

use alloc::vec::Vec;

/// Children per node.
const D: usize = 4;

/// A min-heap of `T`.
pub(super) struct Heap<T: Ord + Copy> {
    slots: Vec<T>,
}

impl<T: Ord + Copy> Heap<T> {
    pub fn with_capacity(n: usize) -> Heap<T> {
        Heap {
            slots: Vec::with_capacity(n),
        }
    }

    pub fn len(&self) -> usize {
        self.slots.len()
    }

    /// Adds `x`: it rises from a new leaf while smaller than its parent.
    pub fn push(&mut self, x: T) {
        let mut i = self.slots.len();
        self.slots.push(x);
        while i > 0 {
            let parent = (i - 1) / D;
            if self.slots[parent] <= x {
                break;
            }
            self.slots[i] = self.slots[parent];
            i = parent;
        }
        self.slots[i] = x;
    }

    /// Removes and returns the smallest entry: the last leaf takes the
    /// root's place and sinks while a child is smaller.
    pub fn pop(&mut self) -> Option<T> {
        let last = self.slots.pop()?;
        let Some(&top) = self.slots.first() else {
            return Some(last);
        };
        self.sink(0, last);
        Some(top)
    }

    /// Keeps the entries `keep` accepts, then restores the order
    /// bottom-up (linear in the length).
    pub fn retain(&mut self, keep: impl FnMut(&T) -> bool) {
        self.slots.retain(keep);
        let n = self.slots.len();
        if n > 1 {
            for i in (0..=(n - 2) / D).rev() {
                let x = self.slots[i];
                self.sink(i, x);
            }
        }
    }

    /// Places `x` at `i` or below, moving smaller children up.
    fn sink(&mut self, mut i: usize, x: T) {
        let n = self.slots.len();
        loop {
            let first = D * i + 1;
            if first >= n {
                break;
            }
            let end = (first + D).min(n);
            let mut least = first;
            for c in first + 1..end {
                if self.slots[c] < self.slots[least] {
                    least = c;
                }
            }
            if self.slots[least] >= x {
                break;
            }
            self.slots[i] = self.slots[least];
            i = least;
        }
        self.slots[i] = x;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pops come out sorted, duplicates included, through interleaved
    /// pushes, pops and a retain; the same as `BinaryHeap` gives.
    #[test]
    fn pops_in_order_as_a_binary_heap() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % 1000
        };
        let mut ours = Heap::with_capacity(0);
        let mut std = alloc::collections::BinaryHeap::new();
        for round in 0..2000 {
            for _ in 0..3 {
                let v = next();
                ours.push(v);
                std.push(core::cmp::Reverse(v));
            }
            if round % 3 != 0 {
                assert_eq!(ours.pop(), std.pop().map(|r| r.0));
            }
            if round == 1000 {
                ours.retain(|v| v % 7 != 0);
                std.retain(|r| r.0 % 7 != 0);
            }
            assert_eq!(ours.len(), std.len());
        }
        while let Some(v) = ours.pop() {
            assert_eq!(Some(v), std.pop().map(|r| r.0));
        }
        assert!(std.is_empty());
    }
}
