//! What can stop the accuracy report, as values.

use std::path::PathBuf;

use soak_bake::{BakeError, LoadError};
use soak_hydro::HydroError;

use crate::GpuError;
use crate::chart::ChartError;

/// The accuracy report could not be measured or its figures written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AccuracyError {
    /// A mesh of the report could not be made.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// A mesh could not be baked.
    #[error(transparent)]
    Bake(#[from] BakeError),
    /// Mass properties or hydrostatics could not be evaluated.
    #[error(transparent)]
    Hydro(#[from] HydroError),
    /// The GPU path failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Chart(#[from] ChartError),
    /// The folder of the figures could not be made.
    #[error("creating {}: {source}", path.display())]
    Io {
        /// The folder.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A report with no sweep has nothing to plot.
    #[error("no sweep to plot")]
    NoSweep,
}
