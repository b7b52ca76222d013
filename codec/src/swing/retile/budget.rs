//! The encoder's work and memory accounting ([`EncodeLimits`]).
//!
//! The retiler's searches count their elementary steps on the surface
//! (`Surface::work`: turns around a vertex, walk steps, search pops and
//! floods); after every gate the retiler hands the count to the
//! [`Budget`] with an estimate of its memory. Two bounds apply:
//! * the caller's [`EncodeLimits`], over the whole encode: passing one
//!   ends the encode with a [`LimitError`];
//! * a per-run bound, `RUN_STEPS_PER_ELEMENT` steps and
//!   `RUN_BYTES_PER_ELEMENT` bytes per corner of the surface and per
//!   corner of the largest output the run may make: a run beyond it is
//!   running away (ordinary runs stay one to two orders of magnitude
//!   below), and fails like a front that does not close.
//!
//! Counting never influences a decision of the retiler, so the bytes of
//! a file do not depend on the limits, only whether it is written.

use crate::{EncodeLimits, LimitError, Limited};
use std::cell::Cell;
use std::time::Instant;

/// Steps per element (surface corner, or corner of the most triangles
/// the run may make) allowed to one retiling run. Measured: about 10 on
/// horse, bunny and fandisk at 0.5-8 b/v, about 50 on a fanned
/// 10,000-gon (BENCHMARKS.md, "Encoder work bounds"); the bound leaves
/// two orders of magnitude.
pub const RUN_STEPS_PER_ELEMENT: u64 = 2_000;
/// Bytes per element a run's surface and output may hold. Measured: 70
/// (horse at 8 b/v) to 180 (woody at 4 b/v) on the corpus, 340-500 on a
/// fanned 10,000-gon and a double fan of valence 2,000, and 5,000 on a
/// double fan of valence 20,000 at 2 b/v, whose fine rim every path
/// splits again and again (BENCHMARKS.md, "Encoder work bounds").
pub const RUN_BYTES_PER_ELEMENT: u64 = 1_000;

/// The running account of one encode.
#[derive(Debug)]
pub struct Budget {
    limits: EncodeLimits,
    used: Cell<u64>,
    peak: Cell<u64>,
    start: Instant,
    exceeded: Cell<Option<(Limited, u64, u64)>>,
}

impl Budget {
    pub fn new(limits: EncodeLimits) -> Budget {
        Budget {
            limits,
            used: Cell::new(0),
            peak: Cell::new(0),
            start: Instant::now(),
            exceeded: Cell::new(None),
        }
    }

    /// No cap (tests and trusted callers).
    #[cfg(test)]
    pub fn unlimited() -> Budget {
        Budget::new(EncodeLimits {
            max_work: u64::MAX,
            max_memory_bytes: u64::MAX,
            max_milliseconds: None,
        })
    }

    /// Adds `steps` of work and checks `memory` bytes in use against the
    /// limits; `false` once any limit is passed (the first one is kept).
    pub fn charge(&self, steps: u64, memory: u64) -> bool {
        if self.exceeded.get().is_some() {
            return false;
        }
        let used = self.used.get().saturating_add(steps);
        self.used.set(used);
        self.peak.set(self.peak.get().max(memory));
        let over = if used > self.limits.max_work {
            Some((Limited::Work, used, self.limits.max_work))
        } else if memory > self.limits.max_memory_bytes {
            Some((Limited::AllocBytes, memory, self.limits.max_memory_bytes))
        } else if let Some(ms) = self.limits.max_milliseconds {
            let elapsed = self.start.elapsed().as_millis() as u64;
            (elapsed > ms).then_some((Limited::Milliseconds, elapsed, ms))
        } else {
            None
        };
        self.exceeded.set(over);
        over.is_none()
    }

    /// Work charged so far.
    pub fn used(&self) -> u64 {
        self.used.get()
    }

    /// The most memory any charge reported.
    pub fn peak_memory(&self) -> u64 {
        self.peak.get()
    }

    /// The limit that was passed, if any.
    pub fn error(&self) -> Option<LimitError> {
        self.exceeded
            .get()
            .map(|(what, requested, limit)| LimitError {
                what,
                requested,
                limit,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_limit_passed_is_reported_and_stays() {
        let b = Budget::new(EncodeLimits {
            max_work: 100,
            ..EncodeLimits::default()
        });
        assert!(b.charge(60, 0));
        assert!(!b.charge(60, 0));
        assert!(!b.charge(0, 0), "a budget once exceeded stays exceeded");
        let e = b.error().unwrap();
        assert_eq!((e.what, e.requested, e.limit), (Limited::Work, 120, 100));
        let m = Budget::new(EncodeLimits {
            max_memory_bytes: 10,
            ..EncodeLimits::default()
        });
        assert!(m.charge(1, 10));
        assert!(!m.charge(1, 11));
        assert_eq!(m.error().unwrap().what, Limited::AllocBytes);
        let t = Budget::new(EncodeLimits {
            max_milliseconds: Some(0),
            ..EncodeLimits::default()
        });
        std::thread::sleep(std::time::Duration::from_millis(2));
        assert!(!t.charge(0, 0));
        assert_eq!(t.error().unwrap().what, Limited::Milliseconds);
    }
}
