//! Unstable sorting for the decoder's paths, one small routine on
//! WebAssembly.
//!
//! `core`'s `sort_unstable` (ipnsort, with sorting networks for short runs
//! and a heapsort fallback) is fast and large: each element type it is
//! used with adds 2-4 KB of code, a quarter of the web module's size gone
//! to nine instances. On `wasm32` these helpers sort with a heapsort of a
//! few hundred bytes per type instead; elsewhere they are `core`'s.
//!
//! Only for sorts whose result does not depend on the algorithm: whole
//! values under their `Ord` (equal elements are identical), or keys that
//! are unique. Then every build decodes to the same bits.

#[cfg(not(target_family = "wasm"))]
pub(crate) fn sort_unstable<T: Ord>(v: &mut [T]) {
    v.sort_unstable();
}

#[cfg(target_family = "wasm")]
pub(crate) fn sort_unstable<T: Ord>(v: &mut [T]) {
    heapsort(v, |a, b| a < b);
}

/// Sorts by a key that is unique to each element.
#[cfg(not(target_family = "wasm"))]
pub(crate) fn sort_by_unique_key<T, K: Ord>(v: &mut [T], key: impl Fn(&T) -> K) {
    v.sort_unstable_by_key(key);
}

/// Sorts by a key that is unique to each element.
#[cfg(target_family = "wasm")]
pub(crate) fn sort_by_unique_key<T, K: Ord>(v: &mut [T], key: impl Fn(&T) -> K) {
    heapsort(v, |a, b| key(a) < key(b));
}

/// Heapsort: O(n log n) whatever the input, in place, not stable.
#[cfg_attr(not(any(target_family = "wasm", test)), allow(dead_code))]
pub(crate) fn heapsort<T>(v: &mut [T], mut is_less: impl FnMut(&T, &T) -> bool) {
    // Moves `v[node]` down its max-heap within `v[..end]`.
    let mut sift_down = |v: &mut [T], mut node: usize, end: usize| loop {
        let mut child = 2 * node + 1;
        if child >= end {
            break;
        }
        if child + 1 < end && is_less(&v[child], &v[child + 1]) {
            child += 1;
        }
        if !is_less(&v[node], &v[child]) {
            break;
        }
        v.swap(node, child);
        node = child;
    };
    let n = v.len();
    for node in (0..n / 2).rev() {
        sift_down(v, node, n);
    }
    for end in (1..n).rev() {
        v.swap(0, end);
        sift_down(v, 0, end);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The heapsort sorts as `core` does, on short and long, random,
    /// sorted, reversed and repetitive input.
    #[test]
    fn heapsort_sorts_as_core_does() {
        let mut rng = crate::mesh::test_rng::Rng(0x2545_f491_4f6c_dd1d);
        for n in [0usize, 1, 2, 3, 7, 8, 9, 31, 100, 1000, 4097] {
            for kind in 0..4 {
                let v: alloc::vec::Vec<(u32, u32)> = (0..n)
                    .map(|i| match kind {
                        0 => (rng.below(50), rng.below(3)),
                        1 => (i as u32, 0),
                        2 => ((n - i) as u32, 1),
                        _ => (7, (i % 2) as u32),
                    })
                    .collect();
                let mut ours = v.clone();
                heapsort(&mut ours, |a, b| a < b);
                let mut theirs = v;
                theirs.sort_unstable();
                assert_eq!(ours, theirs, "n = {n}, kind {kind}");
            }
        }
    }
}
