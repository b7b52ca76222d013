//! The boxes of the tree and the nodes of its binary form as built
//! (`build`) before `widen` lays them out for the search.

use crate::metrics::triangle::Tri;

/// An axis-aligned box in `f32`; empty when `min > max` (the
/// [`Aabb::EMPTY`] box of `+∞` and `−∞`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Aabb {
    pub min: [f32; 3],
    pub max: [f32; 3],
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    /// Plain comparisons rather than `f32::min`, whose NaN rules cost
    /// instructions (every value here is finite or an empty box's ±∞).
    #[inline(always)]
    pub fn grow(&mut self, other: &Aabb) {
        for k in 0..3 {
            let (lo, hi) = (self.min[k], self.max[k]);
            self.min[k] = if other.min[k] < lo { other.min[k] } else { lo };
            self.max[k] = if other.max[k] > hi { other.max[k] } else { hi };
        }
    }

    /// Grows the box to hold the point `p` (as [`Self::grow`]).
    #[inline(always)]
    pub fn grow_point(&mut self, p: &[f32; 3]) {
        for (k, &c) in p.iter().enumerate() {
            let (lo, hi) = (self.min[k], self.max[k]);
            self.min[k] = if c < lo { c } else { lo };
            self.max[k] = if c > hi { c } else { hi };
        }
    }

    pub fn of(t: &Tri) -> Aabb {
        Aabb {
            min: core::array::from_fn(|k| t[0][k].min(t[1][k]).min(t[2][k])),
            max: core::array::from_fn(|k| t[0][k].max(t[1][k]).max(t[2][k])),
        }
    }

    pub fn half_area(&self) -> f64 {
        if self.min[0] > self.max[0] {
            return 0.0;
        }
        let d: [f64; 3] = core::array::from_fn(|k| self.max[k] as f64 - self.min[k] as f64);
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }
}

/// A node of the binary tree as it is built (one box per node).
#[derive(Clone, Copy, Debug)]
pub(super) struct Node {
    pub bounds: Aabb,
    /// Leaf: first triangle; inner node: index of the right child.
    pub index: u32,
    /// Leaf: number of triangles (≥ 1); inner node: 0.
    pub count: u32,
}
