//! A set of small indices that empties in O(1), for the searches and
//! floods that run once per gate over a few elements of a large surface.
//!
//! Invariant: an index is in the set exactly when its stamp equals the
//! current epoch; `clear` moves to the next epoch, and wipes the stamps
//! only when the epoch counter wraps (every 2^32 − 1 clears).

/// The set; see the module docs.
#[derive(Default)]
pub struct Marks {
    stamp: Vec<u32>,
    epoch: u32,
}

impl Marks {
    /// Empties the set and makes room for the indices below `n`.
    pub fn clear(&mut self, n: usize) {
        if self.stamp.len() < n {
            self.stamp.resize(n, 0);
        }
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.fill(0);
            self.epoch = 1;
        }
    }

    /// Whether `i` is in the set.
    #[inline]
    pub fn contains(&self, i: u32) -> bool {
        self.stamp[i as usize] == self.epoch
    }

    /// Adds `i`; returns whether it was not in the set before.
    #[inline]
    pub fn insert(&mut self, i: u32) -> bool {
        let fresh = !self.contains(i);
        self.stamp[i as usize] = self.epoch;
        fresh
    }
}

#[cfg(test)]
mod tests {
    use super::Marks;

    #[test]
    fn clearing_empties_the_set_even_when_the_epoch_wraps() {
        let mut m = Marks::default();
        m.clear(4);
        assert!(m.insert(2) && !m.insert(2) && m.contains(2) && !m.contains(3));
        m.clear(8);
        assert!(!m.contains(2) && m.insert(7));
        m.epoch = u32::MAX;
        m.stamp[1] = u32::MAX;
        assert!(m.contains(1));
        m.clear(8);
        assert!((0..8).all(|i| !m.contains(i)));
    }
}
