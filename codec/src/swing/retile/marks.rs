//! A set of small indices that empties in O(1), for the searches and
//! floods that run once per gate over a few elements of a large surface.
//!
//! Invariant: an index is in the set exactly when its stamp equals the
//! current epoch; `clear` moves to the next epoch, and wipes the stamps
//! only when the epoch counter wraps (every 2^32 − 1 clears).
//!
//! The stamps, and the per-element arrays of the searches that use a
//! set ([`grow_zeroed`]), grow into fresh zeroed allocations rather than
//! by writing zeros: the system hands a large zeroed block over as pages
//! that take no memory until written, so an array indexed by the whole
//! (growing) surface costs memory only where a search wrote (issue 22:
//! Dijkstra's arrays, 16 bytes per face, are written near the few paths
//! that fall back to it).

/// The set; see the module docs.
#[derive(Default)]
pub struct Marks {
    stamp: Vec<u32>,
    epoch: u32,
}

impl Marks {
    /// Empties the set and makes room for the indices below `n`.
    pub fn clear(&mut self, n: usize) {
        grow_zeroed(&mut self.stamp, n);
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

/// Makes `v` at least `n` long, new entries zero (`T::default()` must
/// be all zero bits: integers, floats), growing at least twofold into a
/// fresh zeroed allocation (see the module docs).
pub fn grow_zeroed<T: Copy + Default>(v: &mut Vec<T>, n: usize) {
    if v.len() >= n {
        return;
    }
    let mut fresh = vec![T::default(); n.max(2 * v.len())];
    fresh[..v.len()].copy_from_slice(v);
    *v = fresh;
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

    #[test]
    fn growing_keeps_the_entries_and_zeroes_the_rest() {
        let mut v = vec![7u32, 8, 9];
        super::grow_zeroed(&mut v, 5);
        assert_eq!(v, [7, 8, 9, 0, 0, 0]);
        super::grow_zeroed(&mut v, 4);
        assert_eq!(v.len(), 6, "long enough: unchanged");
    }
}
