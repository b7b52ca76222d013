//! Which decoded neighbours predict each vertex, read off the decoded
//! corner table. Encoder and decoder both call [`predictions`] on the same
//! table (the encoder decodes its own connectivity first), so the lists
//! match exactly.
//!
//! Vertex k is predicted by every parallelogram (a, b, opposite) around it
//! whose three vertices were decoded before k and are not dummies (Isenburg
//! and Alliez's multi-parallelogram; the geometry coder averages them).
//! Without one, the most recently decoded real neighbour predicts it; the
//! first vertex of a component has no prediction.

use crate::geometry::Prediction;
use crate::{CornerTable, VertexId};

/// Predictions per real vertex and the parallelogram list they index, in
/// geometry numbering (real vertices only, in decoded order).
pub(crate) struct Predictions {
    pub list: Vec<Prediction>,
    pub parallelograms: Vec<[u32; 3]>,
}

/// `rank[v]` is v's geometry number, `u32::MAX` for a dummy.
pub(crate) fn predictions(table: &CornerTable, rank: &[u32]) -> Predictions {
    let mut list = Vec::with_capacity(rank.len());
    let mut parallelograms = Vec::new();
    for v in 0..table.vertex_count() as u32 {
        let k = rank[v as usize];
        if k == u32::MAX {
            continue;
        }
        let first = parallelograms.len() as u32;
        let mut nearest = u32::MAX; // highest-ranked real neighbour below k
        for c in table.ring(VertexId(v)) {
            let a = rank[table.vertex(c.next()).idx()];
            let b = rank[table.vertex(c.prev()).idx()];
            for x in [a, b] {
                if x < k && (nearest == u32::MAX || x > nearest) {
                    nearest = x;
                }
            }
            let o = rank[table.vertex(table.opposite(c)).idx()];
            if a < k && b < k && o < k {
                parallelograms.push([a, b, o]);
            }
        }
        let count = parallelograms.len() as u32 - first;
        list.push(match count {
            0 if nearest == u32::MAX => Prediction::None,
            0 => Prediction::Delta { from: nearest },
            1 => {
                let [a, b, opposite] = parallelograms.pop().expect("one entry");
                Prediction::Parallelogram { a, b, opposite }
            }
            _ => Prediction::Multi { first, count },
        });
    }
    Predictions {
        list,
        parallelograms,
    }
}
