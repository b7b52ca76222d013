//! The lossless method: the cleaned input's own triangles, positions
//! quantized to `qp` bits (mode 0, `crate::lossless`). It answers no
//! size: the automatic mode weighs it through the simplified method,
//! which ends at the whole mesh.

use super::method::{Ask, CodingMethod, Job, Made};
use super::stats::{Method, MethodStats};
use crate::{Error, ParameterError};

/// The lossless method at `qp` bits per coordinate.
pub(crate) struct Lossless {
    /// Bits per coordinate, `geometry::MIN_BITS..=MAX_BITS`.
    pub qp: u8,
}

impl Lossless {
    /// `qp` checked against the format's range.
    pub fn new(qp: u8) -> Result<Lossless, Error> {
        use crate::geometry::{MAX_BITS, MIN_BITS};
        if !(MIN_BITS..=MAX_BITS).contains(&qp) {
            return Err(ParameterError::OutOfRange {
                name: "qp",
                value: qp as f64,
                min: MIN_BITS as f64,
                max: MAX_BITS as f64,
            }
            .into());
        }
        Ok(Lossless { qp })
    }
}

impl CodingMethod for Lossless {
    fn method(&self) -> Method {
        Method::Lossless
    }

    fn runs_when_whole_fits(&self) -> bool {
        true
    }

    fn carries_attributes(&self, _streams: &[crate::AttributeStream]) -> bool {
        true
    }

    fn encode(&self, job: &Job<'_, '_>, _ask: Ask) -> Result<Option<Made>, Error> {
        let c = job.cleaned;
        let (bytes, stats, _) =
            crate::lossless::encode(&c.table, &c.mesh, self.qp, job.options.framing)?;
        Ok(Some(Made {
            bytes,
            stats: MethodStats::Lossless(stats),
            l2_relative: None,
            whole: true,
            seeds: None,
        }))
    }
}

/// [`crate::encode_attributed`]: the lossless method with the input's
/// attribute streams kept (`ATTR`, format 1.2). Cleaning follows the
/// streams' triples face by face (`clean_attributed`).
pub(crate) fn encode_attributed(
    mesh: &crate::AttributedMesh,
    options: &crate::EncodeOptions,
) -> Result<super::stats::Encoded, Error> {
    use crate::options::EncodeMode;
    let EncodeMode::Lossless { qp } = options.mode else {
        return Err(ParameterError::NotApplicable {
            name: "attributes",
            mode: "a lossy mode (only the lossless mode keeps them)",
        }
        .into());
    };
    let method = Lossless::new(qp)?;
    let (cleaned, streams) = crate::clean_attributed(mesh, &options.clean)?;
    let (bytes, stats, _) = crate::lossless::encode_attributed(
        &cleaned.table,
        &cleaned.mesh,
        &streams,
        &options.attributes,
        method.qp,
        options.framing,
    )?;
    Ok(super::stats::Encoded {
        bytes,
        stats: super::stats::EncodeStats {
            clean: cleaned.report,
            method: MethodStats::Lossless(stats),
            candidates: Vec::new(),
            check: None,
            origins: Vec::new(),
            attributes: Default::default(),
            smallest_instead: None,
        },
    })
}
