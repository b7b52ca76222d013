//! One file from several pieces: each closed component (`fill`) is
//! retiled on its own with the edge length of the first one retiled, and
//! the results are concatenated in component order, which is the order
//! Edgebreaker visits them (each component starts at its lowest-numbered
//! face, here its first triangle). The hole mask of each piece is grown
//! on its own retiled mesh (`mask`).
//!
//! A component too small to hold a few triangloids at this L is not
//! retiled: it is kept by the lossless mode (the file's `REST`), so no
//! part of the input disappears. Every component's fate is reported.

use super::fill::Piece;
use super::{mask, retile_piece, Budget, Failure, RetileOptions};
use crate::swing::Retiled;
use crate::{CornerTable, TriMesh};

/// A component whose area is under this many equilateral triangles of
/// edge L is kept losslessly without trying to retile it.
const TINY_TRIANGLES: f64 = 8.0;
/// A component under this many triangles' area whose retiling fails is
/// kept losslessly; a larger one fails the run (a smaller L may work).
const SMALL_TRIANGLES: f64 = 64.0;
/// The lossless quantization step of kept components, in units of L.
const REST_STEP: f64 = 1.0 / 64.0;

/// What happened to one component of the input.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PieceReport {
    /// Faces of the component in the cleaned input.
    pub faces: u64,
    /// Its boundary loops.
    pub holes: u32,
    /// Its genus (holes closed).
    pub genus: i64,
    /// What the encoder did with it.
    pub outcome: PieceOutcome,
}

/// How a component was coded.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum PieceOutcome {
    /// Retiled: `triangles` retiled triangles of which `masked` cover its
    /// holes; `lost_holes` holes were too small for any triangle and are
    /// closed in the output; a retiling started on a boundary loop
    /// (`loop_points` > 0) also codes that loop's fan, one triangle per
    /// point, which the decoder drops with its dummy centre.
    Retiled {
        /// Retiled triangles, masked ones included (the fan not).
        triangles: u64,
        /// Triangles over hole patches the decoder drops (hole mask).
        masked: u64,
        /// Holes that closed.
        lost_holes: u32,
        /// Points of the boundary loop the retiling started on (0: it
        /// started inside).
        loop_points: u32,
    },
    /// Too small to retile at this L: kept by the lossless mode.
    Lossless,
    /// Coded by the simplified method (the automatic mode measured it
    /// closer than a retiling at its share of the size): simplified to
    /// `faces` triangles, kept by the lossless mode.
    Simplified {
        /// Triangles kept.
        faces: u64,
    },
}

/// The retiled file contents and the report per component.
pub struct Composed {
    pub retiled: Retiled,
    pub report: Vec<PieceReport>,
    /// Per vertex of `retiled`: a vertex of the cleaned input at the face
    /// its tip was fitted in (`NONE`: not known), see [`seed`].
    pub seeds: Vec<u32>,
}

impl Composed {
    /// [`Composed::seeds`] numbered as the decoder numbers the vertices
    /// (the hole mask and the loops' fans drop some, `hole::dropped`);
    /// `REST`'s vertices, after these, have none.
    pub fn decoded_seeds(&self) -> Vec<u32> {
        let r = &self.retiled;
        let mask = (!r.hole_mask.is_empty()).then(|| r.hole_mask.clone());
        match crate::swing::hole::dropped(mask, &r.triangles, &r.loops) {
            None => self.seeds.clone(),
            Some(mask) => {
                let kept =
                    crate::swing::hole::kept_vertices(r.positions.len(), &r.triangles, &mask);
                self.seeds
                    .iter()
                    .zip(kept)
                    .filter(|(_, k)| *k)
                    .map(|(&s, _)| s)
                    .collect()
            }
        }
    }
}

/// The seed of a tip whose sample lies in face `f` of piece `p`'s mesh,
/// its decoded position `x`: the corner of `f` nearest `x` among those
/// that are vertices of the input (a patch's or a rebuilt fan's own
/// vertices are not), as a vertex of the cleaned input; `NONE` if none
/// is. Provenance starts its descent there (`encoder::provenance`).
fn seed(p: &Piece, f: u32, x: [f64; 3]) -> u32 {
    let Some(t) = p.mesh.triangles.get(f as usize) else {
        return super::surface::NONE;
    };
    let d2 = |v: u32| {
        let q = p.mesh.positions[v as usize];
        (0..3)
            .map(|k| (f64::from(q[k]) - x[k]).powi(2))
            .sum::<f64>()
    };
    t.iter()
        .filter_map(|&v| p.cleaned.get(v as usize).map(|&c| (d2(v), v, c)))
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
        .map_or(super::surface::NONE, |(_, _, c)| c)
}

/// Retiles every piece at `opt.edge_length` (the first retiled piece
/// fixes the exact L, as in a one-piece file), charging `budget`.
pub fn retile_pieces(
    pieces: &[Piece],
    opt: &RetileOptions,
    budget: &Budget,
) -> Result<Composed, Failure> {
    let mut out = Retiled {
        angle_bits: opt.angle_bits,
        first: Vec::new(),
        triangles: Vec::new(),
        positions: Vec::new(),
        symbols: Vec::new(),
        codes: Vec::new(),
        edge_length: opt.edge_length,
        steps: Vec::new(),
        stretch: Vec::new(),
        hole_mask: Vec::new(),
        rest: None,
        loops: Default::default(),
        loop_codes: Vec::new(),
    };
    let mut fixed: Option<f64> = None;
    let mut report = Vec::with_capacity(pieces.len());
    let mut seeds = Vec::new();
    let mut rest: Vec<&TriMesh> = Vec::new();
    // The finest step each kept simplification asks for.
    let mut kept_step: Option<f64> = None;
    // Some component was too small to retile.
    let mut tiny = false;
    for p in pieces {
        let l = fixed.unwrap_or(opt.edge_length);
        let tri_area = l * l * 3f64.sqrt() / 4.0;
        let mut outcome = PieceOutcome::Lossless;
        if let Some((kept, qp)) = &p.keep {
            let step = extent(kept) / f64::from(1u32 << (*qp).min(31));
            kept_step = Some(kept_step.map_or(step, |s: f64| s.min(step)));
            rest.push(kept);
            report.push(PieceReport {
                faces: p.original.face_count() as u64,
                holes: p.holes,
                genus: p.genus,
                outcome: PieceOutcome::Simplified {
                    faces: kept.face_count() as u64,
                },
            });
            continue;
        }
        if p.area >= TINY_TRIANGLES * tri_area {
            match retile_tries(p, opt, fixed, budget) {
                Ok((r, cover, placed)) => {
                    let (mask, lost) = piece_mask(&r, &cover, p.holes)?;
                    let fan = r.loops.points(0);
                    outcome = PieceOutcome::Retiled {
                        triangles: r.triangles.len() as u64 - u64::from(fan),
                        masked: mask.iter().filter(|&&m| m).count() as u64 - u64::from(fan),
                        lost_holes: lost,
                        loop_points: fan,
                    };
                    fixed.get_or_insert(r.edge_length);
                    seeds.extend(
                        placed
                            .iter()
                            .zip(&r.positions)
                            .map(|(&f, &x)| seed(p, f, x)),
                    );
                    append(&mut out, r, mask);
                }
                Err(f) if f == Failure::Limit || p.area >= SMALL_TRIANGLES * tri_area => {
                    return Err(f)
                }
                Err(_) => {}
            }
        }
        if outcome == PieceOutcome::Lossless {
            rest.push(&p.original);
            tiny = true;
        }
        report.push(PieceReport {
            faces: p.original.face_count() as u64,
            holes: p.holes,
            genus: p.genus,
            outcome,
        });
    }
    // Nothing retiled (every piece below the size worth retiling): the
    // whole mesh goes to REST, which 05-swing.md allows; REST's
    // quantization still follows the requested L.
    let l = fixed.unwrap_or(opt.edge_length);
    out.edge_length = l;
    if out.hole_mask.iter().all(|&m| !m) {
        out.hole_mask.clear();
    }
    if !rest.is_empty() {
        let merged = merge(&rest);
        // Tiny components get a step of REST_STEP x L; kept
        // simplifications the step of their own quantization.
        let step = match (tiny, kept_step) {
            (true, Some(k)) => k.min(REST_STEP * l),
            (false, Some(k)) => k,
            (_, None) => REST_STEP * l,
        };
        let qp = rest_bits(&merged, step);
        out.rest = Some((merged, qp));
    }
    Ok(Composed {
        retiled: out,
        report,
        seeds,
    })
}

/// Start vertices tried on a piece before its failure fails the run.
const PIECE_TRIES: u32 = 3;

/// Retiles one piece, from the next start vertices when a start fails:
/// a file of several pieces fails when any of them does, so each piece
/// gets its own retries rather than the whole run.
fn retile_tries(
    p: &Piece,
    opt: &RetileOptions,
    fixed: Option<f64>,
    budget: &Budget,
) -> Result<(Retiled, Vec<mask::Cover>, Vec<u32>), Failure> {
    let mut result = Err(Failure::BadInput);
    for k in 0..PIECE_TRIES {
        // The last start may close a gate that nothing else closes with
        // a long edge or a large triangle (`gate::SLACK`): a few poor
        // triangles where earlier starts failed outright, rather than a
        // failed run that costs the next edge length its own tries.
        let o = RetileOptions {
            start_rank: opt.start_rank + k,
            last_resort: k + 1 == PIECE_TRIES,
            ..opt.clone()
        };
        result = retile_piece(
            &p.mesh,
            &p.table,
            Some(&p.patch),
            &o,
            fixed,
            p.genus > 0,
            budget,
        );
        if result.is_ok() || result == Err(Failure::Limit) || opt.start_vertex.is_some() {
            break;
        }
    }
    // The last start failed to lay the first triangle: the flattest
    // vertices are likely in a region no first triangle fits (a planar
    // face fanned into needles). One more start, chosen by ring shape.
    if matches!(
        result,
        Err(Failure::NoSecondVertex | Failure::NoThirdVertex)
    ) && opt.start_vertex.is_none()
    {
        let o = RetileOptions {
            start_by_shape: true,
            last_resort: true,
            ..opt.clone()
        };
        result = retile_piece(
            &p.mesh,
            &p.table,
            Some(&p.patch),
            &o,
            fixed,
            p.genus > 0,
            budget,
        );
    }
    result
}

/// The hole mask of one retiled piece.
fn piece_mask(r: &Retiled, cover: &[mask::Cover], holes: u32) -> Result<(Vec<bool>, u32), Failure> {
    if holes == 0 {
        return Ok((vec![false; r.triangles.len()], 0));
    }
    // The retiler closes every loop, so M′ is a closed manifold.
    let table = CornerTable::new(&r.triangles, r.positions.len()).map_err(|_| Failure::BadInput)?;
    // A retiling started on a loop begins with that loop's fan: n
    // triangles, all to be dropped with their dummy centre.
    let fan = r.loops.points(0) as usize;
    let first = (fan > 0).then(|| cover[0].0);
    let (mask, lost) = mask::grow(&table, cover, holes, first);
    if mask.iter().take(fan).any(|&m| !m) {
        return Err(Failure::NoThirdVertex);
    }
    Ok((mask, lost))
}

/// Appends a one-component retiling to the file's.
fn append(out: &mut Retiled, r: Retiled, mask: Vec<bool>) {
    let base = out.positions.len() as u32;
    let component = out.first.len() as u32;
    out.loops
        .entries
        .extend(r.loops.entries.iter().map(|&(c, n)| (c + component, n)));
    out.loop_codes.extend(r.loop_codes);
    out.first.extend(r.first);
    out.triangles
        .extend(r.triangles.iter().map(|t| t.map(|v| v + base)));
    out.positions.extend(r.positions);
    out.symbols.extend(r.symbols);
    out.codes.extend(r.codes);
    out.steps.extend(r.steps);
    out.stretch.extend(r.stretch);
    out.hole_mask.extend(mask);
}

/// The kept components as one mesh.
fn merge(parts: &[&TriMesh]) -> TriMesh {
    let mut m = TriMesh::new(Vec::new(), Vec::new());
    for p in parts {
        let base = m.positions.len() as u32;
        m.positions.extend_from_slice(&p.positions);
        m.triangles
            .extend(p.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    m
}

/// The largest side of a mesh's bounding box.
fn extent(m: &TriMesh) -> f64 {
    m.bbox().map_or(0.0, |(lo, hi)| (hi - lo).max_element())
}

/// Bits per coordinate that make the lossless step at most `step` over
/// the kept components' bounding box.
fn rest_bits(m: &TriMesh, step: f64) -> u8 {
    let extent = extent(m);
    let steps = (extent / step).max(1.0);
    let bits = steps.log2().ceil() as i64;
    bits.clamp(
        i64::from(crate::geometry::MIN_BITS),
        i64::from(crate::geometry::MAX_BITS),
    ) as u8
}
