//! What the encoder measures of the file it returns (issue 45, item 7:
//! the error it reports is the error `swm distance` measures between the
//! input and the decoded file, within 2%; issue 23: a file that lost most
//! of the mesh never passes in silence).
//!
//! The file is decoded as a viewer would (default options: the
//! post-processing hint applied) and measured against the job's reference
//! surface, which the chooser built already: the cleaned input, or the
//! same surface with its widest fans rebuilt (`Simplifier::reference`,
//! within about 1e-4 of a spoke). Metro's samples are thinned to
//! [`check_samples`] a side (`metrics::metro_estimate`): 60,000 (a
//! third of that at effort `fast`, about 0.5% standard error instead of
//! 0.3%), keeping each kind's share, so the L2 estimates what
//! `swm distance` reports rather than the chooser's area-uniform figure,
//! which on simplified scans runs
//! 5-10% lower. One reference tree serves the chooser and this check;
//! callers need not build their own (the CLI's check once did, on a
//! million-triangle scan a second of its time).

use super::method::Job;
use super::stats::Check;
use crate::metrics::estimate::metro_estimate;
use crate::metrics::{Build, Surface};
use crate::Error;

use super::stats::check_samples;

/// Decodes `bytes` and measures the result against the job's reference.
pub(crate) fn check(job: &Job<'_, '_>, bytes: &[u8]) -> Result<Check, Error> {
    let decoded = crate::decoder::decode(bytes, &Default::default())?;
    let (decoded_vertices, decoded_triangles) = (decoded.vertex_count(), decoded.face_count());
    if decoded_triangles == 0 {
        return Ok(Check {
            decoded_vertices,
            decoded_triangles,
            area_ratio: 0.0,
            l2_relative: None,
            hausdorff_relative: None,
            samples: 0,
        });
    }
    let reference = job.reference()?;
    let samples = check_samples(job.options.effort);
    // The decoded surface answers this check's queries only.
    let how = Build::for_queries(decoded.face_count(), samples);
    let other = Surface::with_build(&decoded, how)?;
    let d = metro_estimate(reference, &other, samples)?;
    Ok(Check {
        decoded_vertices,
        decoded_triangles,
        area_ratio: other.area() / reference.area().max(f64::MIN_POSITIVE),
        l2_relative: Some(d.l2_relative()),
        hausdorff_relative: Some(d.hausdorff_relative()),
        samples: d.forward.samples.min(d.backward.samples),
    })
}
