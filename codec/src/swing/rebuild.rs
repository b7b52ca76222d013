//! Rebuilding a SwingWrapper mesh's vertices from its corner table, its
//! first triangles and its angle codes (format-spec/05-swing.md, "The
//! angle of a C tip"): the one pass the decoder and the encoder's own
//! check both run, so a file decodes to exactly what its encoder wrote.
//!
//! Above `angle` (the arithmetic of one tip) and the per-tip side streams
//! it validates (`density` levels, `stretch` radius codes, `chain`
//! points); none of them imports this.

use crate::prelude::*;

use super::angle::{
    first_edge_length, push_point, tip_radius, AngleTable, Frame, MAX_ANGLE_BITS, MIN_ANGLE_BITS,
};
use crate::{CornerId, CornerTable, Error, FormatError, Malformed};

fn bad(why: &'static str) -> Error {
    Error::Format(FormatError::new("SWM", Malformed::BadSyntax(why)))
}

/// Rebuilds every vertex of a SwingWrapper mesh from its decoded corner
/// table (vertices numbered in Edgebreaker order, triangle t's corner 3t
/// its tip), the explicit first triangle of each component, and the angle
/// code of each C tip in order.
///
/// One pass over the triangles in order: a triangle whose corners 3t+1
/// and 3t+2 hold vertices not yet placed starts a component and takes the
/// next entry of `first` (corners 3t, 3t+1, 3t+2); a triangle whose tip
/// is the next vertex is a C, whose tip is
/// `Frame::new(X[V[3t+1]], X[V[3t+2]], X[V[O[3t]]], r).point(q)`; every
/// other triangle places nothing. r = [`tip_radius`] of
/// [`first_edge_length`] of `first[0]`, for the whole mesh, times
/// 2^(ℓ/4) for the k-th C tip of level ℓ = `levels[k]` when the file
/// carries levels (`DENS`, format 1.1; `None`: every level is 0), times
/// `stretch::factor(K, j)` for its radius code j = `stretch[k]` when the
/// file carries them (`RADS`, format 1.1; `None`: every code is 0), in
/// that order: `(r · 2^(ℓ/4)) · (1 + j·2^(3−K))`.
///
/// Fails (format error, never a panic) when the table is not numbered
/// that way, the number of codes or first triangles is wrong, a code is
/// not below 2^K, or a coordinate is not finite or does not round to a
/// finite binary32. The encoder runs this same function on its own
/// output, so a file it writes decodes to exactly its positions.
pub fn rebuild_positions(
    table: &CornerTable,
    first: &[[[f64; 3]; 3]],
    bits: u8,
    codes: &[u32],
    levels: Option<&[i8]>,
    stretch: Option<&[i32]>,
    mut points: Option<&mut super::chain::Points<'_>>,
) -> Result<Vec<[f64; 3]>, Error> {
    if let Some(l) = levels {
        if l.len() != codes.len() || l.iter().any(|l| l.abs() > super::density::LEVEL_MAX) {
            return Err(bad("levels are not one per angle code, or out of range"));
        }
    }
    if let Some(j) = stretch {
        let limit = super::stretch::max_code(bits);
        if j.len() != codes.len() || j.iter().any(|j| j.abs() > limit) {
            return Err(bad(
                "radius codes are not one per angle code, or out of range",
            ));
        }
    }
    let mut k = 0usize;
    if !(MIN_ANGLE_BITS..=MAX_ANGLE_BITS).contains(&bits) {
        return Err(bad("angle bits out of range"));
    }
    let angles = AngleTable::new(bits);
    let r = first
        .first()
        .map_or(0.0, |f| tip_radius(first_edge_length(f)));
    let mut x: Vec<[f64; 3]> = Vec::with_capacity(table.vertex_count());
    let (mut firsts, mut codes) = (first.iter(), codes.iter());
    let mut component = 0u32;
    walk(table, |triangle| match triangle {
        // A component's first triangle: three new vertices in order.
        Coded::First => {
            let f = firsts
                .next()
                .ok_or(bad("more components than first triangles"))?;
            if let Some(p) = points.as_deref_mut() {
                p.start(component, f)?;
            }
            component += 1;
            f.iter().try_for_each(|p| push_point(&mut x, *p))
        }
        // A C triangle: its tip is new, the gate and previous tip are not.
        Coded::C([b, c, prev]) => {
            let &q = codes.next().ok_or(bad("fewer angle codes than C tips"))?;
            if q >= angles.codes() {
                return Err(bad("angle code out of range"));
            }
            let rk = match levels {
                Some(l) => r * super::density::ratio(l[k]),
                None => r,
            };
            let rk = match stretch {
                Some(j) => super::stretch::apply(bits, rk, j[k]),
                None => rk,
            };
            k += 1;
            let [b, c, prev] = [b, c, prev].map(|v| v as usize);
            // A boundary loop's point (`chain`), else a swing tip.
            if let Some(p) = points.as_deref_mut() {
                if let Some(tip) = p.tip(q, x[b], x[c], x[prev])? {
                    return push_point(&mut x, tip);
                }
            }
            let frame = Frame::new(x[b], x[c], x[prev], rk);
            push_point(&mut x, frame.point(&angles, q))
        }
    })?;
    if firsts.next().is_some() {
        return Err(bad("more first triangles than components"));
    }
    if codes.next().is_some() {
        return Err(bad("more angle codes than C tips"));
    }
    if x.len() != table.vertex_count() {
        return Err(bad("a vertex is neither a first vertex nor a C tip"));
    }
    Ok(x)
}

/// A triangle of the rebuilding pass that places vertices.
enum Coded {
    /// A component's first triangle (three new vertices).
    First,
    /// A C triangle: its gate GL = V[3t+1], GR = V[3t+2] and previous
    /// tip P = V[O[3t]], all placed before its tip.
    C([u32; 3]),
}

/// The walk of [`rebuild_positions`]: the triangles in order, the
/// numbering checked as the coding order makes it, `f` called for each
/// that places vertices. Returns how many vertices the walk placed.
fn walk(table: &CornerTable, mut f: impl FnMut(Coded) -> Result<(), Error>) -> Result<u64, Error> {
    let v = table.vertices();
    let mut next = 0u64;
    for t in 0..table.face_count() {
        let [a, b, c] = [v[3 * t].0, v[3 * t + 1].0, v[3 * t + 2].0].map(u64::from);
        if b >= next {
            if (a, b, c) != (next, next + 1, next + 2) {
                return Err(bad("vertices are not numbered in coding order"));
            }
            f(Coded::First)?;
            next += 3;
        } else if a == next {
            let tip = table.opposite(CornerId(3 * t as u32));
            let prev = if tip.is_some() && tip.idx() < v.len() {
                u64::from(v[tip.idx()].0)
            } else {
                u64::MAX
            };
            if c >= next || prev >= next {
                return Err(bad("a C tip is built on vertices not yet placed"));
            }
            // All below `next`, a vertex count: they fit in u32.
            f(Coded::C([b, c, prev].map(|x| x as u32)))?;
            next += 1;
        } else if a > next || c >= next {
            return Err(bad("vertices are not numbered in coding order"));
        }
    }
    Ok(next)
}
