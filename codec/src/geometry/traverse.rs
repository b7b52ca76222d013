//! The order in which positions are coded, and each vertex's
//! prediction, derived from connectivity alone: a greedy traversal that
//! always decodes next the vertex with the most parallelograms available.
//!
//! Source: the prediction-degree idea of Cohen-Or, Cohen & Irony,
//! "Multi-way geometry encoding" (2002), also behind Draco's
//! `MaxPredictionDegreeTraverser`. This implementation is vertex-based and
//! the project's own: priorities are exact parallelogram counts, kept up to
//! date incrementally, with one FIFO queue per count.
//!
//! ```text
//!        x-----v-----.        v has two parallelograms available:
//!       / \ P1 / \ P2/        (x, y, o1) across xy and (y, z, o2)
//!      /   \  /   \ /         across yz, where x, y, z, o1, o2 are all
//!     o1----y-----z           decoded. Decoding the vertices with the
//!            \   /            most such parallelograms first lets most
//!             \ /             vertices be predicted by two, which the
//!              o2             coder can average or choose between.
//! ```
//!
//! Why it matters: on the Stanford bunny at 11 bits, a breadth-first
//! order leaves a vertex 1 to 3 parallelograms when it is reached; this
//! order gives 95% of vertices two, and position coding drops from 8.22 to
//! 7.79 bits/vertex (see [`super::lossless`]).
//!
//! Because the order depends only on the corner table, the encoder and the
//! decoder compute it the same way once connectivity is known; the
//! connectivity codec does not need to know about it. Must match the
//! encoder exactly: both sides call [`traverse`] on identical tables.
//!
//! Rules, in order:
//! 1. A component starts at the triangle of the lowest corner whose
//!    vertex is not decoded yet; its vertices are decoded in corner order,
//!    the first one predicted by [`Prediction::None`], the next ones by
//!    [`Prediction::Delta`] from the previous one.
//! 2. A vertex becomes a candidate when a neighbour is decoded. Its
//!    *degree* is the number of its corners `c` whose three vertices
//!    `V[n(c)]`, `V[p(c)]`, `V[O[c]]` are decoded: one parallelogram each.
//! 3. The next vertex is the candidate of highest degree (counts above
//!    [`MAX_PRIORITY`] count as that), first come first served among equal
//!    degrees (a queue per degree; a vertex whose degree rose is queued
//!    again, and stale entries are skipped).
//! 4. Its prediction lists its parallelograms in the order of its corners
//!    (increasing corner index): one gives [`Prediction::Parallelogram`],
//!    several [`Prediction::Multi`]; none gives a `Delta` from its first
//!    decoded neighbour (corners in order, `n(c)` before `p(c)`).
//! 5. Vertices without corners come last, predicted by `None`.
//!
//! [`traverse_except`] leaves chosen vertices out (they are never decoded,
//! so no parallelogram or delta uses them).
//!
//! The table is not trusted: vertex indices out of range are an error,
//! opposite corners out of range count as boundaries, and every loop is
//! bounded by the table's size whatever its contents. (On a table whose
//! opposites are not mutual, degrees may be miscounted; the order is then
//! still the same on both sides, and predictions still only name decoded
//! vertices, since rule 4 recomputes them from scratch.)

use std::collections::VecDeque;

use super::predict::{Prediction, Predictions};
use crate::mesh::{CornerId, CornerTable, VertexId};
use crate::{Error, FormatError, Malformed};

/// Degrees above this share its queue (more parallelograms than this are
/// rare, and would not change which vertex goes first in practice). Part
/// of the bitstream definition, since it fixes the order.
pub const MAX_PRIORITY: usize = 6;

/// A coding order and the predictions along it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Traversal {
    /// `order[k]` is the mesh vertex decoded `k`-th.
    pub order: Vec<VertexId>,
    /// The prediction of each decoded vertex, in decoding order (indices
    /// refer to decoding order too).
    pub predictions: Predictions,
}

const UNSEEN: u32 = u32::MAX;

/// Computes the coding order and predictions of `table`'s vertices (see
/// the module docs).
///
/// Fails with [`Error::Format`] if a corner names a vertex outside the
/// table. Runs in time and memory linear in the table's size.
pub fn traverse(table: &CornerTable) -> Result<Traversal, Error> {
    traverse_except(table, &[])
}

/// [`traverse`], leaving out the vertices `v` with `excluded[v]` true
/// (e.g. the dummy vertices that close holes for Edgebreaker): they are
/// not in the order and no prediction uses them. Entries past the end of
/// `excluded` count as false.
pub fn traverse_except(table: &CornerTable, excluded: &[bool]) -> Result<Traversal, Error> {
    let vertices = table.vertex_count();
    let corners = table.corner_count() - table.corner_count() % 3;
    let v_of = table.vertices();
    if let Some(bad) = v_of[..corners].iter().find(|v| v.idx() >= vertices) {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::IndexOutOfRange {
                index: bad.0 as i64,
                vertices: vertices as u64,
            },
        )));
    }
    let mut state = State::new(table, corners, excluded);

    let mut seed_cursor = 0;
    while let Some(seed) = (seed_cursor..corners).find(|&c| state.open(v_of[c].0)) {
        seed_cursor = seed;
        // Rule 1: the seed triangle, in corner order.
        let first = seed - seed % 3;
        let mut previous = None;
        for v in &v_of[first..first + 3] {
            if state.open(v.0) {
                let p = match previous {
                    None => Prediction::None,
                    Some(from) => Prediction::Delta { from },
                };
                state.decode(v.idx(), p);
            }
            if state.decoded(v.0) {
                previous = Some(state.id[v.idx()]);
            }
        }
        // Rules 2–4 until the component is done.
        while let Some(v) = state.pop() {
            let p = state.prediction(v);
            state.decode(v, p);
        }
    }
    // Rule 5.
    for v in 0..vertices {
        if state.open(v as u32) {
            state.decode(v, Prediction::None);
        }
    }
    Ok(state.out)
}

/// What the traversal needs of one corner `c` of a vertex `v`, gathered
/// once so that visiting `v` reads one contiguous run of memory instead of
/// chasing the corner table: `[x, y, o, ox, oy]` with `x = V[n(c)]`,
/// `y = V[p(c)]`, `o = V[O[c]]` (across the edge xy), `ox = V[O[n(c)]]`
/// (across the edge yv, from x) and `oy = V[O[p(c)]]` (across vx, from
/// y); `NONE` where the opposite corner does not exist.
type Wing = [u32; 5];

const NONE: u32 = u32::MAX;

/// Working state of [`traverse`]. Memory: 20 bytes per corner and about
/// 16 per vertex, freed on return (the result aside).
struct State<'t> {
    /// `start[v] .. start[v+1]` index `wings`: the corners of vertex `v`,
    /// in increasing corner order.
    start: Vec<u32>,
    wings: Vec<Wing>,
    /// Decoding index of each vertex, or `UNSEEN`.
    id: Vec<u32>,
    /// Vertices never to decode.
    excluded: &'t [bool],
    /// Parallelograms available to each undecoded vertex.
    degree: Vec<u32>,
    /// Whether a vertex has been queued at all (it has a decoded neighbour).
    queued: Vec<bool>,
    /// One FIFO per priority `min(degree, MAX_PRIORITY)`.
    queues: [VecDeque<u32>; MAX_PRIORITY + 1],
    out: Traversal,
}

impl<'t> State<'t> {
    fn new(table: &CornerTable, corners: usize, excluded: &'t [bool]) -> Self {
        let vertices = table.vertex_count();
        let v_of = table.vertices();
        // Corners per vertex by a counting sort: no swinging, so a broken
        // table cannot make this loop.
        let mut start = vec![0u32; vertices + 1];
        for v in &v_of[..corners] {
            start[v.idx() + 1] += 1;
        }
        for v in 0..vertices {
            start[v + 1] += start[v];
        }
        // The vertex across the edge facing `c`, if the opposite corner is
        // a real corner of a whole triangle.
        let across = |c: CornerId| {
            let o = table.opposite(c);
            if o.is_some() && o.idx() < corners {
                table.vertex(o).0
            } else {
                NONE
            }
        };
        let mut fill = start.clone();
        let mut wings = vec![[NONE; 5]; corners];
        for (c, v) in v_of[..corners].iter().enumerate() {
            let c = CornerId(c as u32);
            wings[fill[v.idx()] as usize] = [
                table.vertex(c.next()).0,
                table.vertex(c.prev()).0,
                across(c),
                across(c.next()),
                across(c.prev()),
            ];
            fill[v.idx()] += 1;
        }
        State {
            start,
            wings,
            id: vec![UNSEEN; vertices],
            excluded,
            degree: vec![0; vertices],
            queued: vec![false; vertices],
            queues: Default::default(),
            out: Traversal {
                order: Vec::with_capacity(vertices),
                predictions: Predictions {
                    vertices: Vec::with_capacity(vertices),
                    parallelograms: Vec::new(),
                },
            },
        }
    }

    /// The wings of vertex `v`'s corners.
    #[inline]
    fn wings_of(&self, v: usize) -> core::ops::Range<usize> {
        self.start[v] as usize..self.start[v + 1] as usize
    }

    /// Decoded (`NONE`, a missing vertex, never is).
    #[inline]
    fn decoded(&self, v: u32) -> bool {
        self.id.get(v as usize).is_some_and(|&i| i != UNSEEN)
    }

    /// Not decoded yet, and not excluded: still to be decoded.
    #[inline]
    fn open(&self, v: u32) -> bool {
        let v = v as usize;
        v < self.id.len() && self.id[v] == UNSEEN && !self.excluded.get(v).copied().unwrap_or(false)
    }

    fn enqueue(&mut self, v: usize) {
        self.queued[v] = true;
        let priority = (self.degree[v] as usize).min(MAX_PRIORITY);
        self.queues[priority].push_back(v as u32);
    }

    /// Records that `w` gained a parallelogram (`completes`) and/or a
    /// decoded neighbour, queueing it if its priority changed or it just
    /// became a candidate.
    #[inline]
    fn touch(&mut self, w: u32, completes: bool, neighbour: bool) {
        let w = w as usize;
        if completes {
            self.degree[w] += 1;
        }
        if completes || (neighbour && !self.queued[w]) {
            self.enqueue(w);
        }
    }

    /// Gives `v` its decoding index and updates its surroundings: its
    /// neighbours become candidates, and every parallelogram `v` completes
    /// adds to its vertex's degree.
    fn decode(&mut self, v: usize, p: Prediction) {
        self.id[v] = self.out.order.len() as u32;
        self.out.order.push(VertexId(v as u32));
        self.out.predictions.vertices.push(p);
        for i in self.wings_of(v) {
            let [x, y, o, ox, oy] = self.wings[i];
            let (x_done, y_done) = (self.decoded(x), self.decoded(y));
            // x's parallelogram at corner n(c) is (y, v, ox); v is decoded
            // now, so it is complete exactly when y and ox are, and this is
            // the moment it becomes available. Likewise y's, (v, x, oy).
            if self.open(x) {
                let completes = y_done && self.decoded(ox);
                self.touch(x, completes, true);
            }
            if self.open(y) {
                let completes = x_done && self.decoded(oy);
                self.touch(y, completes, true);
            }
            // The vertex across the edge xy gets the parallelogram
            // (y, x, v) once x and y are decoded too.
            if x_done && y_done && self.open(o) {
                self.touch(o, true, false);
            }
        }
    }

    /// Rule 3: the undecoded candidate of highest priority, if any.
    fn pop(&mut self) -> Option<usize> {
        for priority in (0..=MAX_PRIORITY).rev() {
            while let Some(v) = self.queues[priority].pop_front() {
                if self.open(v) && (self.degree[v as usize] as usize).min(MAX_PRIORITY) == priority
                {
                    return Some(v as usize);
                }
            }
        }
        None
    }

    /// Rule 4: the prediction of candidate `v`.
    fn prediction(&mut self, v: usize) -> Prediction {
        let first = self.out.predictions.parallelograms.len();
        let mut from = None;
        for i in self.wings_of(v) {
            let [x, y, o, _, _] = self.wings[i];
            let (x_done, y_done) = (self.decoded(x), self.decoded(y));
            if from.is_none() {
                from = [(x, x_done), (y, y_done)]
                    .into_iter()
                    .find_map(|(w, done)| done.then_some(w));
            }
            if x_done && y_done && self.decoded(o) {
                let p = [
                    self.id[x as usize],
                    self.id[y as usize],
                    self.id[o as usize],
                ];
                self.out.predictions.parallelograms.push(p);
            }
        }
        let list = &self.out.predictions.parallelograms[first..];
        match list.len() {
            0 => match from {
                Some(w) => Prediction::Delta {
                    from: self.id[w as usize],
                },
                None => Prediction::None,
            },
            1 => {
                let [a, b, opposite] = list[0];
                self.out.predictions.parallelograms.truncate(first);
                Prediction::Parallelogram { a, b, opposite }
            }
            n => Prediction::Multi {
                first: first as u32,
                count: n as u32,
            },
        }
    }
}
