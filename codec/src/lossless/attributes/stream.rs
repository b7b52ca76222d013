//! One attribute stream's coded data: its seams over the connectivity,
//! the values its corners share at each vertex, and the values,
//! predicted in the positions' decoding order. Encoder and decoder steps
//! sit side by side and must match exactly.
//!
//! Source: Draco's mesh attribute seams (`MeshAttributeCornerTable`:
//! one bit per interior edge saying whether the attribute is continuous
//! across it, corners around a vertex split into "attribute vertices" at
//! seams). Beyond Draco, so that which corners share a value is kept
//! exactly: an edge is continuous only when the values at *both* ends
//! agree, and a wedge (a run of corners around a vertex between seams)
//! may name an earlier wedge of its vertex whose value it shares (a
//! "merge": the other end of a seam edge, or OBJ corners that share an
//! index across a seam).
//!
//! ```text
//!   seams: for each corner c < O[c], both faces real:   1 bit (context: seams met
//!                                                        so far at the edge's ends)
//!   then for each vertex v in decoding order:
//!     for each wedge of v (ordered by its lowest corner):
//!       [merge bit, [index of the earlier group: raw bits]]   (not for the first)
//!       if new: [orientation bit] residual                    (texture coordinates:
//!                                                              the bit when projected)
//! ```
//!
//! Invariants: every real corner ends with a group; a group's corners
//! are all at one vertex; decoding allocates only what the corner count
//! (bounded by the header's triangles) sizes.

use crate::prelude::*;

use super::frame::{next, prev, Frame, NONE};
use super::octahedral;
use super::predict::{Known, Prediction};
use super::residual::Residuals;
use super::spec::Spec;
#[cfg(feature = "encoder")]
use crate::entropy::Encoder;
use crate::entropy::{ContextModel, Decoder};
use crate::Error;

/// The models and the decoded state of one stream, both sides.
pub(crate) struct State<'a> {
    frame: &'a Frame<'a>,
    spec: &'a Spec,
    /// Values are in `0..modulus` per component.
    modulus: u64,
    /// Per corner: the stream is continuous across the edge facing it.
    continuous: Vec<bool>,
    /// Per corner: its value (group), `NONE` until decoded.
    group: Vec<u32>,
    /// The groups' values, `dims` per group.
    values: Vec<u64>,
    seam_models: ContextModel,
    merge_model: ContextModel,
    orientation_model: ContextModel,
    last_orientation: usize,
    residuals: Residuals,
}

impl<'a> State<'a> {
    pub(crate) fn new(frame: &'a Frame<'a>, spec: &'a Spec) -> Self {
        let corners = frame.table.corner_count();
        let modulus = spec.modulus();
        State {
            frame,
            spec,
            modulus,
            continuous: vec![false; corners],
            group: vec![NONE; corners],
            values: Vec::new(),
            seam_models: ContextModel::new(9, 2),
            merge_model: ContextModel::new(1, 2),
            orientation_model: ContextModel::new(2, 2),
            last_orientation: 0,
            residuals: Residuals::new(spec.coded_dims(), spec.bits, modulus),
        }
    }

    /// The prediction of a new group with corners `corners`.
    fn predict(&self, corners: &[u32]) -> Prediction {
        Known {
            frame: self.frame,
            spec: self.spec,
            modulus: self.modulus,
            continuous: &self.continuous,
            group: &self.group,
            values: &self.values,
        }
        .predict(corners)
    }

    /// Groups decoded so far.
    fn count(&self) -> u32 {
        (self.values.len() / self.spec.coded_dims()) as u32
    }

    /// The corners `c < O[c]` whose edge joins two real faces, in
    /// increasing order: the edges that carry a seam bit.
    fn edges(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        let o = self.frame.table.opposites();
        (0..o.len() as u32).filter_map(move |c| {
            let x = o[c as usize].0;
            let real = |c: u32| {
                self.frame
                    .real
                    .get(c as usize / 3)
                    .copied()
                    .unwrap_or(false)
            };
            (x != NONE && c < x && (x as usize) < o.len() && real(c) && real(x)).then_some((c, x))
        })
    }

    /// The seam bit's context: how many seams (0, 1, 2 or more) were
    /// met so far at each end of the edge facing `c`.
    fn seam_context(seams: &[u8], v: &[crate::VertexId], c: u32) -> usize {
        let a = seams[v[next(c) as usize].idx()].min(2) as usize;
        let b = seams[v[prev(c) as usize].idx()].min(2) as usize;
        3 * a.max(b) + a.min(b)
    }

    /// The wedges of vertex `v` into `w`: its corners on real faces,
    /// joined across continuous edges, each wedge's corners increasing,
    /// the wedges ordered by their lowest corner.
    pub(crate) fn wedges(&self, v: crate::VertexId, w: &mut Wedges) {
        w.corners.clear();
        let real = &self.frame.real;
        w.corners.extend(
            self.frame
                .corners_of(v)
                .iter()
                .copied()
                .filter(|&c| real[c as usize / 3]),
        );
        let n = w.corners.len();
        w.parent.clear();
        w.parent.extend(0..n as u32);
        fn root(parent: &mut [u32], mut i: usize) -> usize {
            while parent[i] as usize != i {
                parent[i] = parent[parent[i] as usize];
                i = parent[i] as usize;
            }
            i
        }
        let o = self.frame.table.opposites();
        for i in 0..n {
            // Across the edge c → n(c) (it faces p(c)), the corner at v
            // is p(O[p(c)]).
            let e = prev(w.corners[i]);
            if !self.continuous[e as usize] {
                continue;
            }
            let other = prev(o[e as usize].0);
            if let Ok(j) = w.corners.binary_search(&other) {
                let (ri, rj) = (root(&mut w.parent, i), root(&mut w.parent, j));
                w.parent[ri.max(rj)] = ri.min(rj) as u32;
            }
        }
        // Wedge numbers in order of first corner, then the corners laid
        // out wedge by wedge (a counting sort, stable: increasing within).
        w.slot.clear();
        w.slot.resize(n, u32::MAX);
        w.starts.clear();
        w.starts.push(0);
        for i in 0..n {
            let r = root(&mut w.parent, i);
            if w.slot[r] == u32::MAX {
                w.slot[r] = (w.starts.len() - 1) as u32;
                w.starts.push(0);
            }
            let k = w.slot[r] as usize;
            w.starts[k + 1] += 1;
            w.parent[i] = r as u32;
        }
        for k in 1..w.starts.len() {
            w.starts[k] += w.starts[k - 1];
        }
        w.flat.clear();
        w.flat.resize(n, 0);
        let mut fill = w.starts.clone();
        for i in 0..n {
            let k = w.slot[w.parent[i] as usize] as usize;
            w.flat[fill[k] as usize] = w.corners[i];
            fill[k] += 1;
        }
    }

    /// Records a new group with `value` for `corners`.
    fn push(&mut self, value: &[u64], corners: &[u32]) -> u32 {
        let g = self.count();
        self.values
            .extend_from_slice(&value[..self.spec.coded_dims()]);
        self.assign(g, corners);
        g
    }

    fn assign(&mut self, g: u32, corners: &[u32]) {
        for &c in corners {
            self.group[c as usize] = g;
        }
    }

    /// Normals: the prediction and the value in the frame their residual
    /// is taken in (both mirrored through the equator when the
    /// prediction lies below it).
    fn normal_frame(&self, pred: [u64; 4], value: [u64; 4]) -> ([u64; 4], [u64; 4], bool) {
        let bits = self.spec.bits;
        let h = octahedral::half(bits);
        let un = |q: [u64; 4]| [q[0] as i64 - h, q[1] as i64 - h];
        let sh = |q: [i64; 2]| [(q[0] + h) as u64, (q[1] + h) as u64, 0, 0];
        if !octahedral::is_outer(un(pred), bits) {
            return (pred, value, false);
        }
        let p = sh(octahedral::invert(un(pred), bits));
        (p, sh(octahedral::invert(un(value), bits)), true)
    }
}

/// The wedges of one vertex, in buffers reused from vertex to vertex.
#[derive(Default)]
pub(crate) struct Wedges {
    corners: Vec<u32>,
    parent: Vec<u32>,
    slot: Vec<u32>,
    flat: Vec<u32>,
    starts: Vec<u32>,
}

impl Wedges {
    /// How many.
    fn count(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// Wedge `k`'s corners, increasing.
    fn get(&self, k: usize) -> &[u32] {
        &self.flat[self.starts[k] as usize..self.starts[k + 1] as usize]
    }
}

/// Raw bits that name one of `n` earlier groups of a vertex.
fn index_bits(n: usize) -> u32 {
    usize::BITS - (n.max(1) - 1).leading_zeros()
}

#[cfg(feature = "encoder")]
/// Codes a stream: `index[c]` is the input value of table corner `c`
/// (`NONE` on dropped faces), `values` the input values quantized
/// (`dims` per value, each in `0..modulus`).
pub(crate) fn encode(frame: &Frame<'_>, spec: &Spec, index: &[u32], values: &[u64]) -> Vec<u8> {
    let mut s = State::new(frame, spec);
    let mut enc = Encoder::new();
    let v = frame.table.vertices();
    let mut seams = vec![0u8; frame.table.vertex_count()];
    let edges: Vec<(u32, u32)> = s.edges().collect();
    for (c, o) in edges {
        let same = |x: u32, y: u32| index[x as usize] == index[y as usize];
        let cont = same(next(c), prev(o)) && same(prev(c), next(o));
        let ctx = State::seam_context(&seams, v, c);
        enc.encode(s.seam_models.get(ctx), u32::from(!cont));
        if cont {
            s.continuous[c as usize] = true;
            s.continuous[o as usize] = true;
        } else {
            for x in [next(c), prev(c)] {
                let n = &mut seams[v[x as usize].idx()];
                *n = n.saturating_add(1);
            }
        }
    }
    let d = spec.coded_dims();
    let mut wedges = Wedges::default();
    let mut local: Vec<(u32, u32)> = Vec::new(); // (input value, group)
    for &vertex in frame.order {
        local.clear();
        s.wedges(vertex, &mut wedges);
        for k in 0..wedges.count() {
            let wedge = wedges.get(k);
            let input = index[wedge[0] as usize];
            // A merge names one of at most 2^24 earlier values (the raw
            // bits' limit); past that (a vertex of more than 16 million
            // values, beyond any limit) a value is coded anew.
            if !local.is_empty() && index_bits(local.len()) <= crate::entropy::MAX_RAW_BITS {
                let earlier = local.iter().position(|&(i, _)| i == input);
                enc.encode(s.merge_model.get(0), u32::from(earlier.is_some()));
                if let Some(j) = earlier {
                    enc.encode_bits(j as u32, index_bits(local.len()));
                    s.assign(local[j].1, wedge);
                    continue;
                }
            }
            let mut value = [0u64; 4];
            value[..d].copy_from_slice(&values[input as usize * d..(input as usize + 1) * d]);
            match s.predict(wedge) {
                Prediction::Fixed { class, value: pred } => {
                    let (p, q, _) = if spec.is_normal() {
                        s.normal_frame(pred, value)
                    } else {
                        (pred, value, false)
                    };
                    s.residuals.encode(&mut enc, class, &q[..d], &p[..d]);
                }
                Prediction::Oriented { kept, mirrored } => {
                    let dist = |p: &[u64; 4]| (0..d).map(|k| p[k].abs_diff(value[k])).sum::<u64>();
                    let flip = usize::from(dist(&mirrored) < dist(&kept));
                    enc.encode(s.orientation_model.get(s.last_orientation), flip as u32);
                    s.last_orientation = flip;
                    let p = if flip == 1 { mirrored } else { kept };
                    s.residuals.encode(&mut enc, 0, &value[..d], &p[..d]);
                }
            }
            let g = s.push(&value, wedge);
            local.push((input, g));
        }
    }
    enc.finish()
}

/// Decodes a stream (must match [`encode`] exactly): the group of every
/// table corner (`NONE` on dropped faces) and the groups' values.
pub(crate) fn decode(
    frame: &Frame<'_>,
    spec: &Spec,
    bytes: &[u8],
) -> Result<(Vec<u32>, Vec<u64>), Error> {
    let mut s = State::new(frame, spec);
    let mut dec = Decoder::new(bytes)?;
    let v = frame.table.vertices();
    let mut seams = vec![0u8; frame.table.vertex_count()];
    let edges: Vec<(u32, u32)> = s.edges().collect();
    for (c, o) in edges {
        let ctx = State::seam_context(&seams, v, c);
        let cont = dec.decode(s.seam_models.get(ctx))? == 0;
        if cont {
            s.continuous[c as usize] = true;
            s.continuous[o as usize] = true;
        } else {
            for x in [next(c), prev(c)] {
                let n = &mut seams[v[x as usize].idx()];
                *n = n.saturating_add(1);
            }
        }
    }
    let d = spec.coded_dims();
    let mut wedges = Wedges::default();
    let mut local: Vec<u32> = Vec::new();
    for &vertex in frame.order {
        local.clear();
        s.wedges(vertex, &mut wedges);
        for k in 0..wedges.count() {
            let wedge = wedges.get(k);
            if !local.is_empty() && dec.decode(s.merge_model.get(0))? == 1 {
                let bits = index_bits(local.len());
                if bits > crate::entropy::MAX_RAW_BITS {
                    return Err(super::spec::bad(
                        "more values at one vertex than a merge can name",
                    ));
                }
                let j = dec.decode_bits(bits)? as usize;
                let g = *local
                    .get(j)
                    .ok_or_else(|| super::bad("merge names no earlier value"))?;
                s.assign(g, wedge);
                continue;
            }
            let mut value = [0u64; 4];
            match s.predict(wedge) {
                Prediction::Fixed { class, value: pred } => {
                    let mut p = pred;
                    let mut mirrored = false;
                    if spec.is_normal() {
                        (p, _, mirrored) = s.normal_frame(pred, pred);
                    }
                    s.residuals
                        .decode(&mut dec, class, &p[..d], &mut value[..d])?;
                    if mirrored {
                        (_, value, _) = s.normal_frame(pred, value);
                    }
                }
                Prediction::Oriented { kept, mirrored } => {
                    let flip = dec.decode(s.orientation_model.get(s.last_orientation))? as usize;
                    s.last_orientation = flip;
                    let p = if flip == 1 { mirrored } else { kept };
                    s.residuals.decode(&mut dec, 0, &p[..d], &mut value[..d])?;
                }
            }
            let g = s.push(&value, wedge);
            local.push(g);
        }
    }
    dec.finish()?;
    let values = s.values;
    Ok((s.group, values))
}
