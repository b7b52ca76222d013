//! Resource limits for untrusted input.

/// Caps on what a reader or decoder may allocate because a file said so.
///
/// Every count read from a file is checked against these limits, and
/// against what the remaining bytes could possibly hold, *before* any
/// allocation sized by that count. The defaults suit a viewer on a desktop
/// machine; a server that decodes files from strangers may want less.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Largest vertex count accepted. Default: 2^28 (268 million).
    pub max_vertices: u64,
    /// Largest triangle count accepted. Default: 2^29 (537 million).
    pub max_faces: u64,
    /// Largest number of bytes a single reader or decoder may allocate for
    /// its output and working buffers. Default: 16 GiB.
    pub max_alloc_bytes: u64,
    /// Largest input file, in bytes, that the file readers of `swm::io`
    /// open (`read_file`, `read_mesh`; larger files are refused before
    /// they are mapped or read). Default: 16 GiB. Decoding from bytes in
    /// memory does not use it.
    pub max_input_bytes: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_vertices: 1 << 28,
            max_faces: 1 << 29,
            max_alloc_bytes: 16 << 30,
            max_input_bytes: 16 << 30,
        }
    }
}

impl Limits {
    /// No limit beyond what the address space allows; for trusted input only.
    pub const UNLIMITED: Limits = Limits {
        max_vertices: u64::MAX,
        max_faces: u64::MAX,
        max_alloc_bytes: u64::MAX,
        max_input_bytes: u64::MAX,
    };

    /// Checks a declared vertex count.
    pub fn check_vertices(&self, n: u64) -> Result<(), crate::LimitError> {
        check(crate::Limited::Vertices, n, self.max_vertices)
    }

    /// Checks a declared face count.
    pub fn check_faces(&self, n: u64) -> Result<(), crate::LimitError> {
        check(crate::Limited::Faces, n, self.max_faces)
    }

    /// Checks the length of an input file in bytes.
    pub fn check_input(&self, bytes: u64) -> Result<(), crate::LimitError> {
        check(crate::Limited::InputBytes, bytes, self.max_input_bytes)
    }

    /// Checks a planned allocation in bytes.
    pub fn check_alloc(&self, bytes: u64) -> Result<(), crate::LimitError> {
        check(crate::Limited::AllocBytes, bytes, self.max_alloc_bytes)
    }
}

fn check(what: crate::Limited, requested: u64, limit: u64) -> Result<(), crate::LimitError> {
    if requested > limit {
        Err(crate::LimitError {
            what,
            requested,
            limit,
        })
    } else {
        Ok(())
    }
}

/// Caps on what one [`encode`](crate::encode) call may spend, for input
/// from strangers (a server compressing uploads) or batch jobs that must
/// not stall on one odd file. Reaching a cap ends the encode with a
/// [`LimitError`](crate::LimitError); it never changes the bytes of a
/// file that is written, so encoding stays deterministic.
///
/// Independently of these caps, every retiling run is bounded by its own
/// size: a run that takes far more steps than its surface and its output
/// explain fails like a run whose front does not close, and rate control
/// moves on.
#[cfg(feature = "encoder")]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EncodeLimits {
    /// Elementary steps of the retiler's searches (a turn around a vertex,
    /// a step of a walk, a node of a shortest-path or nearest-vertex
    /// search), summed over every run of rate control. Default: no cap.
    pub max_work: u64,
    /// Bytes the retiler's working surface and output may hold at once
    /// (estimated from their buffers). Default: 8 GiB.
    pub max_memory_bytes: u64,
    /// Wall-clock time of the encode in milliseconds, checked between
    /// retiling steps. Default: no cap.
    pub max_milliseconds: Option<u64>,
}

#[cfg(feature = "encoder")]
impl Default for EncodeLimits {
    fn default() -> Self {
        EncodeLimits {
            max_work: u64::MAX,
            max_memory_bytes: 8 << 30,
            max_milliseconds: None,
        }
    }
}
