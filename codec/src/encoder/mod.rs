//! The encoder: one seam for every coding method ([`method`]), the
//! methods each in their own module ([`lossless`], [`simplified`],
//! [`swing`], [`mixed`]), the per-file chooser above them ([`choose`]),
//! the effort levels that give it its list ([`effort`]) and the error
//! target that searches over its sizes ([`target`]).
//!
//! A mode that names a method runs that method alone; the automatic mode
//! runs the chooser. Either way the input is cleaned once and every
//! method shares the job's services (the simplifier's collapse sequence,
//! the reference surface).

pub(crate) mod check;
pub(crate) mod choose;
pub(crate) mod displaced;
#[cfg(test)]
mod displaced_tests;
pub(crate) mod effort;
pub(crate) mod lossless;
pub(crate) mod method;
pub(crate) mod mixed;
pub(crate) mod provenance;
pub(crate) mod request;
pub(crate) mod resample;
pub(crate) mod simplified;
pub(crate) mod smooth;
pub(crate) mod stats;
pub(crate) mod swing;
pub(crate) mod target;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_attributed;
#[cfg(test)]
mod tests_resampled;

use crate::options::{EncodeMode, EncodeOptions, SwingTarget};
use crate::{Error, TriMesh};
use method::{Ask, CodingMethod, Job, Services};
use stats::{AttributeReport, AttributesDropped, EncodeStats, Encoded};

/// Cleans and encodes `mesh` (see [`crate::encode`]).
pub(crate) fn encode(mesh: &TriMesh, options: &EncodeOptions) -> Result<Encoded, Error> {
    encode_with(mesh, None, options)
}

/// Cleans and encodes `mesh` with its attribute streams (see
/// [`crate::encode_attributed`]). The lossless mode keeps them; the
/// automatic and simplified modes keep them too, running only methods
/// whose files carry them (`CodingMethod::carries_attributes`); a mode
/// that names a method that cannot (SwingWrapper and displaced
/// subdivision, for texture coordinates) drops them and says so
/// ([`AttributeReport`]).
/// No streams: [`encode`]'s bytes.
pub(crate) fn encode_attributed(
    mesh: &crate::AttributedMesh,
    options: &EncodeOptions,
) -> Result<Encoded, Error> {
    mesh.validate()?;
    if mesh.streams.is_empty() {
        return encode(&mesh.mesh, options);
    }
    let kinds: Vec<crate::AttributeKind> = mesh.streams.iter().map(|s| s.kind).collect();
    let dropped_by = match options.mode {
        EncodeMode::Lossless { .. } => {
            let mut encoded = lossless::encode_attributed(mesh, options)?;
            encoded.stats.attributes.kept = kinds;
            return Ok(encoded);
        }
        // Normals, colours and generic streams resampled at their
        // vertices; texture coordinates they cannot keep (`resample`).
        EncodeMode::Swing { .. } if !resample::carries(&mesh.streams) => Some(stats::Method::Swing),
        EncodeMode::Displaced { .. } if !resample::carries(&mesh.streams) => {
            Some(stats::Method::Displaced)
        }
        EncodeMode::Auto { .. }
        | EncodeMode::Simplified { .. }
        | EncodeMode::Swing { .. }
        | EncodeMode::Displaced { .. } => None,
    };
    if let Some(method) = dropped_by {
        let mut encoded = encode(&mesh.mesh, options)?;
        encoded.stats.attributes = AttributeReport {
            dropped: kinds,
            dropped_because: Some(AttributesDropped::Method(method)),
            ..Default::default()
        };
        return Ok(encoded);
    }
    // Normals the geometry gives back are left to the decoder (`smooth`);
    // the others' distance from the geometry is what dropping them costs.
    let off = match options.keep_smooth_normals {
        true => None,
        false => smooth::normals_off(mesh),
    };
    let smooth = off.filter(|&rms| rms <= smooth::SMOOTH_NORMAL_DEGREES);
    let rest;
    let coded = match smooth {
        Some(_) => {
            rest = smooth::without_normals(mesh);
            &rest
        }
        None => mesh,
    };
    // The streams' attempt and the surface's answer the request or fail
    // (`or_smallest` is applied below, once both have failed).
    let strict = EncodeOptions {
        or_smallest: false,
        ..options.clone()
    };
    let mut encoded = match coded.streams.is_empty() {
        true => encode(&mesh.mesh, options)?,
        false => match encode_with(&mesh.mesh, Some(coded), &strict) {
            // A size below the smallest file that keeps the streams: the
            // surface alone, and the report says why (a request is for
            // bytes; `--strict` makes the loss an error).
            // When the surface alone does not fit either, the error is the
            // streams' (its smallest file keeps them).
            Err(Error::Size(e)) => {
                let mut encoded = match encode(&mesh.mesh, &strict) {
                    // Below both smallest files, with `or_smallest`: the
                    // request made again at the streams' smallest size,
                    // once (what a user who did not ask for a size, or
                    // asked for too few bytes, expects: the streams kept
                    // where they can be, else the surface at that size).
                    Err(Error::Size(_)) if options.or_smallest => {
                        let Some(mode) = at_size(options.mode, e.smallest) else {
                            return Err(e.into());
                        };
                        let again = EncodeOptions { mode, ..strict };
                        let mut encoded = encode_attributed(mesh, &again)?;
                        encoded.stats.smallest_instead = Some(e);
                        return Ok(encoded);
                    }
                    Err(Error::Size(_)) => return Err(e.into()),
                    other => other?,
                };
                encoded.stats.attributes = AttributeReport {
                    dropped: coded.streams.iter().map(|s| s.kind).collect(),
                    dropped_because: Some(AttributesDropped::NoRoom {
                        smallest: e.smallest,
                    }),
                    ..Default::default()
                };
                encoded
            }
            other => other?,
        },
    };
    if let (Some(off), None) = (off, smooth) {
        encoded = without_costly_normals(coded, encoded, off, &strict);
    }
    if let Some(rms_degrees) = smooth {
        let report = &mut encoded.stats.attributes;
        report.dropped.push(crate::AttributeKind::Normal);
        if report.dropped_because.is_none() {
            report.dropped_because = Some(AttributesDropped::SmoothNormals {
                rms_degrees: rms_degrees as f32,
            });
        }
    }
    Ok(encoded)
}

/// `kept`, or the file without the normals at the same size when those
/// cost the surface more than they give (`smooth`): a lossy file at a
/// size that kept normals `off` degrees RMS from the geometry's own.
fn without_costly_normals(
    coded: &crate::AttributedMesh,
    kept: Encoded,
    off: f64,
    options: &EncodeOptions,
) -> Encoded {
    let sized = match options.mode {
        EncodeMode::Auto { target, .. }
        | EncodeMode::Simplified { target, .. }
        | EncodeMode::Displaced { target, .. } => is_size(target),
        _ => false,
    };
    let normals = kept
        .stats
        .attributes
        .kept
        .contains(&crate::AttributeKind::Normal);
    let Some(l2_kept) = kept.stats.check.and_then(|c| c.l2_relative) else {
        return kept;
    };
    if !sized || !normals || !smooth::may_cost_more_than_they_give(l2_kept, off) {
        return kept;
    }
    // The second file within the level's time bar: at `default` it is
    // searched at `fast` (a second `default` encode doubled fandisk's
    // with crease normals at 0.5 b/v, 237 -> 518 ms against a 500 ms
    // bar); `max` spends what it takes.
    let effort = match options.effort {
        crate::Effort::Max => crate::Effort::Max,
        _ => crate::Effort::Fast,
    };
    let options = &EncodeOptions {
        effort,
        ..options.clone()
    };
    let rest = smooth::without_normals(coded);
    let other = match rest.streams.is_empty() {
        true => encode(&rest.mesh, options),
        false => encode_with(&rest.mesh, Some(&rest), options),
    };
    // The second file only ever replaces the first: where it cannot be
    // made (too small a size for its own smallest file, a limit), the
    // first stands.
    let Ok(mut other) = other else {
        return kept;
    };
    let l2_without = other.stats.check.and_then(|c| c.l2_relative);
    if !l2_without.is_some_and(|l2| smooth::cost_more_than_they_give(l2_kept, l2, off)) {
        return kept;
    }
    let report = &mut other.stats.attributes;
    report.dropped.push(crate::AttributeKind::Normal);
    report.dropped_because = Some(AttributesDropped::CostlyNormals {
        rms_degrees: off as f32,
        l2_kept: l2_kept as f32,
    });
    other
}

/// [`encode`], with `attributed` (the same mesh with its streams) when
/// the file is to carry them.
fn encode_with(
    mesh: &TriMesh,
    attributed: Option<&crate::AttributedMesh>,
    options: &EncodeOptions,
) -> Result<Encoded, Error> {
    // A parameter error comes before any work.
    let lossless = match options.mode {
        EncodeMode::Lossless { qp } => Some(lossless::Lossless::new(qp)?),
        _ => None,
    };
    let (cleaned, streams) = match attributed {
        Some(a) => crate::clean_attributed(a, &options.clean)?,
        None => (crate::clean(mesh, &options.clean)?, Vec::new()),
    };
    let services = Services::new(
        mesh,
        &cleaned,
        options.framing,
        options.effort == crate::Effort::Fast,
    )
    .with_attributes(&streams, options.attributes);
    let job = Job {
        cleaned: &cleaned,
        input_vertices: mesh.distinct_positions(),
        options,
        services: &services,
    };
    // The file, and the seeds of its origins when its method gave them.
    let forced = |m: &dyn CodingMethod, ask: Ask| -> Result<(Encoded, Seeds), Error> {
        let made = m
            .encode(&job, ask)?
            .expect("a method run alone always has something to add");
        let encoded = Encoded {
            bytes: made.bytes,
            stats: EncodeStats {
                clean: cleaned.report.clone(),
                method: made.stats,
                candidates: Vec::new(),
                check: None,
                origins: Vec::new(),
                attributes: AttributeReport::default(),
                smallest_instead: None,
            },
        };
        Ok((encoded, made.seeds))
    };
    let (mut encoded, seeds) = match options.mode {
        EncodeMode::Lossless { .. } => {
            let m = lossless.expect("checked above");
            // Its file needs no size: any ask will do.
            let ask = Ask {
                target: SwingTarget::Bytes(1),
                max_bytes: None,
            };
            return forced(&m, ask).map(|(encoded, _)| encoded);
        }
        EncodeMode::Swing {
            target,
            angle_bits,
            max_bytes,
        } => sized(options, Ask { target, max_bytes }, |ask| {
            forced(&swing::Swing { angle_bits }, ask)
        })?,
        EncodeMode::Simplified { target, max_bytes } => {
            let ask = Ask { target, max_bytes };
            let search = match options.effort {
                crate::Effort::Fast => simplified::Search::Quick,
                _ => simplified::Search::Full,
            };
            if let SwingTarget::MaxError(bound) = target {
                let list = [effort::Entry {
                    method: if search == simplified::Search::Quick {
                        &simplified::Simplified::QUICK
                    } else {
                        &simplified::Simplified::FULL
                    },
                    work: None,
                }];
                finish(
                    &cleaned,
                    target::smallest_within(&job, bound, max_bytes, &list)?,
                )?
            } else {
                sized(options, ask, |ask| {
                    forced(&simplified::Simplified { search }, ask)
                })?
            }
        }
        EncodeMode::Displaced { target, max_bytes } => {
            sized(options, Ask { target, max_bytes }, |ask| {
                forced(&displaced::Displaced::DEFAULT, ask)
            })?
        }
        EncodeMode::Auto { target, max_bytes } => {
            let list = effort::methods(options.effort, cleaned.mesh.triangles.len());
            match target {
                SwingTarget::MaxError(bound) => finish(
                    &cleaned,
                    target::smallest_within(&job, bound, max_bytes, &list)?,
                )?,
                _ => sized(options, Ask { target, max_bytes }, |ask| {
                    finish(&cleaned, choose::choose(&job, ask, &list)?)
                })?,
            }
        }
    };
    // Every lossy file is decoded and measured once more, as
    // `swm distance` would measure it (`check`).
    encoded.stats.check = Some(check::check(&job, &encoded.bytes)?);
    if options.origins {
        encoded.stats.origins = provenance::of_file(&job, &encoded.bytes, seeds.as_deref())?;
    }
    if !streams.is_empty() {
        encoded.stats.attributes = AttributeReport {
            kept: streams.iter().map(|s| s.kind).collect(),
            texcoord_error: job.simplifier().texcoord_error(&encoded.bytes)?,
            ..Default::default()
        };
    }
    Ok(encoded)
}

/// The seeds of a file's origins (`method::Made::seeds`).
type Seeds = Option<Vec<u32>>;

/// `mode` with its size or rate replaced by `bytes`, if it has one and
/// no cap below `bytes`.
fn at_size(mode: EncodeMode, bytes: u64) -> Option<EncodeMode> {
    let target = SwingTarget::Bytes(bytes);
    let fits = |cap: Option<u64>| cap.is_none_or(|c| bytes <= c);
    match mode {
        EncodeMode::Auto { max_bytes, .. } if fits(max_bytes) => {
            Some(EncodeMode::Auto { target, max_bytes })
        }
        EncodeMode::Simplified { max_bytes, .. } if fits(max_bytes) => {
            Some(EncodeMode::Simplified { target, max_bytes })
        }
        EncodeMode::Displaced { max_bytes, .. } if fits(max_bytes) => {
            Some(EncodeMode::Displaced { target, max_bytes })
        }
        EncodeMode::Swing {
            angle_bits,
            max_bytes,
            ..
        } if fits(max_bytes) => Some(EncodeMode::Swing {
            target,
            angle_bits,
            max_bytes,
        }),
        _ => None,
    }
}

/// `run` at `ask`; with [`EncodeOptions::or_smallest`], a size request
/// below the smallest file is run again at that smallest size (any cap
/// allowing), in the same job, and the file says so
/// (`EncodeStats::smallest_instead`).
fn sized(
    options: &EncodeOptions,
    ask: Ask,
    run: impl Fn(Ask) -> Result<(Encoded, Seeds), Error>,
) -> Result<(Encoded, Seeds), Error> {
    match run(ask) {
        Err(Error::Size(e))
            if options.or_smallest
                && is_size(ask.target)
                && ask.max_bytes.is_none_or(|cap| e.smallest <= cap) =>
        {
            let again = Ask {
                target: SwingTarget::Bytes(e.smallest),
                ..ask
            };
            let (mut encoded, seeds) = run(again)?;
            encoded.stats.smallest_instead = Some(e);
            Ok((encoded, seeds))
        }
        other => other,
    }
}

/// Whether `target` asks for a size (bytes or bits per vertex), not an
/// edge length or an error bound.
fn is_size(target: SwingTarget) -> bool {
    matches!(
        target,
        SwingTarget::Bytes(_) | SwingTarget::BitsPerVertex(_)
    )
}

/// The chooser's file as the encoder's result, and its seeds.
fn finish(cleaned: &crate::Cleaned, chosen: choose::Chosen) -> Result<(Encoded, Seeds), Error> {
    let encoded = Encoded {
        bytes: chosen.bytes,
        stats: EncodeStats {
            clean: cleaned.report.clone(),
            method: chosen.stats,
            candidates: chosen.candidates,
            check: None,
            origins: Vec::new(),
            attributes: AttributeReport::default(),
            smallest_instead: None,
        },
    };
    Ok((encoded, chosen.seeds))
}
