//! `swm rd --check TABLE`: the rate-distortion ratchet.
//!
//! Every row of a committed table is run again with the same mesh, rate,
//! configuration and sample count, and compared with what the table says.
//! A row regresses when
//!
//! * its file grows by even one byte,
//! * its `l2_rel` or `hausdorff_rel` grows by more than the tolerance
//!   (relative, 1% by default: `--tolerance 0.01`) plus [`SLACK`], or
//! * it was coded and now has no file (`infeasible`, `failed` or `n/a`).
//!
//! A row without a file passes whatever it becomes; so does every
//! improvement. All measured numbers are deterministic, so on an unchanged
//! codec every row reproduces exactly on the platform that wrote the table
//! (the committed tables: x86-64 Linux); the tolerance absorbs last-bit
//! differences of other platforms' math libraries in the distances (but
//! not in sizes: `swm_corpus` meshes built with another libm's `sin` may
//! differ in the last bit, and so may their files). A legitimate
//! trade (more bytes for much less error within the same budget) also
//! fails: regenerate the table in the same commit, so the change is seen.
//! A row whose mesh changed (different vertex count or budget) is a
//! failure too: the table no longer describes that mesh.
//! A table whose `effort` cell contradicts its configuration (`auto` is
//! always `max`) is refused as it is read (`table::from_csv`): it
//! describes runs this harness does not make.
//!
//! This file holds the comparison; the run itself (read the table, run
//! its rows again, print the verdicts) is `run_check` in `rd`, beside the
//! fresh run whose steps it shares.

use crate::rd::table::{Outcome, Row};

/// Absolute slack on distances, in their unit (1e-4 of the diagonal):
/// 1e-7 of the diagonal, the resolution of `f32` coordinates. Without it
/// an exact reconstruction (distance 0) would fail on any rounding.
pub const SLACK: f64 = 1e-3;

/// One way a row got worse.
#[derive(Clone, Debug, PartialEq)]
pub enum Regression {
    /// The row was coded and now has no file.
    Status {
        /// The fresh status.
        new: &'static str,
        /// Why, when the encoder said (`failed`, `n/a`).
        why: String,
    },
    /// A count that must not change did, or a file grew: `bytes`,
    /// `vertices` or `budget_bytes`.
    Count {
        /// The column.
        metric: &'static str,
        /// The table's value.
        old: u64,
        /// The fresh value.
        new: u64,
    },
    /// A distance grew beyond the tolerance: `l2_rel` or `hausdorff_rel`.
    Distance {
        /// The column.
        metric: &'static str,
        /// The table's value.
        old: f64,
        /// The fresh value.
        new: f64,
    },
}

impl std::fmt::Display for Regression {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Regression::Status { new, why } if why.is_empty() => write!(f, "status ok -> {new}"),
            Regression::Status { new, why } => write!(f, "status ok -> {new} ({why})"),
            Regression::Count { metric, old, new } => write!(f, "{metric} {old} -> {new}"),
            Regression::Distance { metric, old, new } => write!(
                f,
                "{metric} {old:.4} -> {new:.4} ({:+.1}%)",
                100.0 * (new / old - 1.0)
            ),
        }
    }
}

/// How `new` (a fresh run of `old`'s row) compares with `old`.
pub fn compare(old: &Row, new: &Row, tolerance: f64) -> Vec<Regression> {
    let mut out = Vec::new();
    let exact = |metric, old, new| Regression::Count { metric, old, new };
    if old.vertices != new.vertices {
        out.push(exact("vertices", old.vertices, new.vertices));
    }
    if old.budget_bytes != new.budget_bytes {
        out.push(exact("budget_bytes", old.budget_bytes, new.budget_bytes));
    }
    match (old.coded(), new.coded()) {
        (Some(_), None) => out.push(Regression::Status {
            new: new.status(),
            why: match &new.outcome {
                Outcome::Failed { why } | Outcome::NotApplicable { why } => why.clone(),
                _ => String::new(),
            },
        }),
        (Some(o), Some(n)) => {
            if n.bytes > o.bytes {
                out.push(exact("bytes", o.bytes, n.bytes));
            }
            for (metric, old, new) in [
                ("l2_rel", o.l2_rel, n.l2_rel),
                ("hausdorff_rel", o.hausdorff_rel, n.hausdorff_rel),
            ] {
                if new > old * (1.0 + tolerance) + SLACK {
                    out.push(Regression::Distance { metric, old, new });
                }
            }
        }
        (None, _) => {}
    }
    out
}

/// The line printed for one row.
pub fn verdict_line(old: &Row, new: &Row, regressions: &[Regression]) -> String {
    let what = match new.coded() {
        Some(c) => format!(
            "{} B, l2_rel {:.4}, hausdorff_rel {:.3}",
            c.bytes, c.l2_rel, c.hausdorff_rel
        ),
        None => new.status().to_string(),
    };
    if regressions.is_empty() {
        let same = match (old.coded(), new.coded()) {
            (None, None) => old.status() == new.status(),
            (Some(o), Some(n)) => {
                (o.bytes, o.l2_rel, o.hausdorff_rel) == (n.bytes, n.l2_rel, n.hausdorff_rel)
            }
            _ => false,
        };
        let tag = if same { "same" } else { "ok" };
        format!("{tag:<7}{}: {what}", old.key())
    } else {
        let why: Vec<String> = regressions.iter().map(|r| r.to_string()).collect();
        format!("WORSE  {}: {}", old.key(), why.join("; "))
    }
}
