//! The post-processing hint: the encoder's measured recommendation of
//! Sharpen&Bend for one file, in the ancillary section `post` (format
//! 1.1; format-spec/06-post.md, "The hint"; issue 21 item 3; beyond the
//! thesis, whose decoder runs EdgeSharpener and Bender on every mesh).
//!
//! Why a hint: whether EdgeSharpener helps depends on the mesh. On CAD
//! parts it restores the creases a uniform retiling chamfers; on smooth
//! scans it finds "creases" in the sampling noise and moves vertices off
//! the surface (up to 24% more L2 on the bunny, corpus/rd). Only the
//! encoder has the input to tell, so it decodes its own file each way and
//! writes the choice; a decoder follows it unless its caller decides.
//!
//! ```text
//!  payload:  u8 sharpen   0 = off, 1 = EdgeSharpener
//!            u8 bend      Bender steps after it, 0..=MAX_BEND
//!            ...          (later minor versions may append bytes:
//!                          a reader ignores them)
//! ```
//!
//! A payload shorter than two bytes, or a value outside those sets (a
//! later version's choice), makes a reader ignore the whole hint: the
//! hint is advice, so a file never fails to decode because of it, and a
//! file without one decodes plain, as every file before it did.
//!
//! Encoder and decoder sides sit together here: [`payload`] writes what
//! [`read`] reads.

use crate::container::{Container, Tag};

/// The most Bender steps a hint may ask for (each multiplies the
/// triangles by four; more than two makes a viewer's mesh 16x larger for
/// changes below the sampling of any measure the encoder has).
pub const MAX_HINT_BEND: u32 = 2;

/// Sharpen&Bend as a file's hint or a caller asks for it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PostProcessing {
    /// Run EdgeSharpener.
    pub sharpen: bool,
    /// Bender steps after it.
    pub bend_steps: u32,
}

impl PostProcessing {
    /// Plain decoding: neither step.
    pub const PLAIN: PostProcessing = PostProcessing {
        sharpen: false,
        bend_steps: 0,
    };

    /// Neither step runs.
    pub fn is_plain(&self) -> bool {
        !self.sharpen && self.bend_steps == 0
    }
}

/// The hint's two bytes (the writer's side of [`read`]).
///
/// # Panics
/// If `hint.bend_steps` exceeds [`MAX_HINT_BEND`]: the encoder only
/// recommends steps it measured.
#[cfg(feature = "encoder")]
pub(crate) fn payload(hint: PostProcessing) -> [u8; 2] {
    assert!(
        hint.bend_steps <= MAX_HINT_BEND,
        "hint beyond MAX_HINT_BEND"
    );
    [u8::from(hint.sharpen), hint.bend_steps as u8]
}

/// The file's hint, if it has one this version understands (see the
/// module docs: anything else is ignored, never an error).
pub fn read(file: &Container<'_>) -> Option<PostProcessing> {
    let bytes = file.section(Tag::POST)?;
    let (&s, &b) = (bytes.first()?, bytes.get(1)?);
    let sharpen = match s {
        0 => false,
        1 => true,
        _ => return None,
    };
    let bend_steps = u32::from(b);
    (bend_steps <= MAX_HINT_BEND).then_some(PostProcessing {
        sharpen,
        bend_steps,
    })
}

/// What the decoder runs: each field the caller set, the file's hint for
/// the others (plain where the file has no hint).
pub(crate) fn resolve(
    file: &Container<'_>,
    sharpen: Option<bool>,
    bend_steps: Option<u32>,
) -> PostProcessing {
    let hint = if sharpen.is_some() && bend_steps.is_some() {
        PostProcessing::PLAIN
    } else {
        read(file).unwrap_or(PostProcessing::PLAIN)
    };
    PostProcessing {
        sharpen: sharpen.unwrap_or(hint.sharpen),
        bend_steps: bend_steps.unwrap_or(hint.bend_steps),
    }
}
