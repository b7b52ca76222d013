//! One mesh of an rd run, prepared once and shared by every job on it:
//! the mesh as read, its reference surface (the BVH every distance is
//! measured against), and the encode results that several rates reuse.
//!
//! Caches only hold pure functions of their keys, so whichever job fills
//! an entry first, every job reads the same value: results do not depend
//! on scheduling.

use crate::error::CliError;
use crate::rd::source::Source;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;
use swm::metrics::{DistanceOptions, Surface};
use swm::TriMesh;

/// A mesh prepared for the harness.
pub struct Case {
    /// Where it came from.
    pub source: Source,
    /// How the table names it.
    pub table_name: String,
    /// The mesh as read: the reference of every distance.
    pub mesh: TriMesh,
    /// `mesh`, prepared for nearest-point queries.
    pub reference: Surface,
    /// Lossless file sizes of `mesh` by qp.
    lossless_sizes: Mutex<HashMap<u8, u64>>,
    /// SwingWrapper files by (byte budget, angle bits): the swing
    /// configurations differ only in how they decode the same file.
    swing_files: Mutex<HashMap<(u64, swm::SwingTuning), SwingCell>>,
}

impl Case {
    /// Prepares a mesh already read from `source`.
    pub fn new(source: Source, table_name: String, mesh: TriMesh) -> Result<Case, CliError> {
        let err = |e| CliError::new(source.label(), e);
        let reference = Surface::new(&mesh).map_err(err)?;
        Ok(Case {
            source,
            table_name,
            mesh,
            reference,
            lossless_sizes: Mutex::new(HashMap::new()),
            swing_files: Mutex::new(HashMap::new()),
        })
    }

    /// Vertices of the mesh as read: the unit of every rate.
    pub fn vertices(&self) -> u64 {
        self.mesh.positions.len() as u64
    }

    /// What error messages call this mesh.
    pub fn label(&self) -> PathBuf {
        self.source.label()
    }

    /// Wraps a library error with this mesh's name.
    pub fn err(&self, e: impl Into<swm::Error>) -> CliError {
        CliError::new(self.label(), e)
    }

    /// Size of the lossless file of the whole mesh at `qp`.
    pub fn lossless_size(&self, qp: u8) -> Result<u64, CliError> {
        if let Some(&n) = self.lossless_sizes.lock().expect("cache lock").get(&qp) {
            return Ok(n);
        }
        let n = encode(&self.mesh, qp).map_err(|e| self.err(e))?.len() as u64;
        self.lossless_sizes
            .lock()
            .expect("cache lock")
            .insert(qp, n);
        Ok(n)
    }

    /// The SwingWrapper file of the whole mesh asked for `budget` bytes
    /// (also its cap) with `tuning`, encoded once per key: a job that asks
    /// while another encodes waits for that result.
    pub fn swing_file(&self, budget: u64, tuning: swm::SwingTuning) -> SwingCell {
        let cell = Arc::clone(
            self.swing_files
                .lock()
                .expect("cache lock")
                .entry((budget, tuning))
                .or_default(),
        );
        cell.get_or_init(|| {
            let start = Instant::now();
            swm::encode(&self.mesh, &swing_options(budget, tuning))
                .map(|e| (e.bytes, start.elapsed().as_secs_f64()))
        });
        cell
    }

    /// L2 and Hausdorff distances from the reference to `other`, in units
    /// of 1e-4 of the reference's diagonal, from `samples` area-uniform
    /// face samples on each surface (the thesis's L2 and the shared
    /// corpus's peer figures are measured this way).
    pub fn distance(&self, other: &TriMesh, samples: u64) -> Result<(f64, f64), CliError> {
        let other = Surface::new(other).map_err(|e| self.err(e))?;
        let d = swm::metrics::distance_between(
            &self.reference,
            &other,
            &DistanceOptions::area_uniform(samples),
        )
        .map_err(|e| self.err(e))?;
        Ok((1e4 * d.l2_relative(), 1e4 * d.hausdorff_relative()))
    }
}

/// A SwingWrapper encode's outcome: the file and the seconds it took.
pub type SwingFile = Result<(Vec<u8>, f64), swm::Error>;

/// One entry of the swing cache, filled by the first job that asks.
pub type SwingCell = Arc<OnceLock<SwingFile>>;

/// What the rd harness asks the SwingWrapper encoder for: `budget` bytes,
/// never more, with `swm encode`'s defaults otherwise (angle bits chosen
/// by rate control) and the encoder-side choices `tuning`.
pub fn swing_options(budget: u64, tuning: swm::SwingTuning) -> swm::EncodeOptions {
    swm::EncodeOptions {
        mode: swm::EncodeMode::Swing {
            target: swm::SwingTarget::Bytes(budget),
            angle_bits: None,
            max_bytes: Some(budget),
        },
        swing: tuning,
        ..Default::default()
    }
}

/// The lossless-mode file of `mesh` at `qp`.
pub fn encode(mesh: &TriMesh, qp: u8) -> Result<Vec<u8>, swm::Error> {
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp },
        ..Default::default()
    };
    Ok(swm::encode(mesh, &options)?.bytes)
}
