//! What can stop the scaling bench, as values.

use std::path::PathBuf;

use soak_bake::BakeError;
use soak_rapier::SoakError;

use crate::chart::ChartError;

/// The bench could not run or write its figure.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ScalingError {
    /// A mesh could not be baked.
    #[error("baking the {mesh}: {source}")]
    Bake {
        /// The mesh.
        mesh: &'static str,
        /// What went wrong.
        source: BakeError,
    },
    /// A mesh's radiation could not be baked.
    #[error("baking the {mesh}'s radiation: {source}")]
    Radiation {
        /// The mesh.
        mesh: &'static str,
        /// What went wrong.
        source: soak_rapier::soak_seakeeping::SeakeepingError,
    },
    /// The swell could not be made.
    #[error(transparent)]
    Accuracy(#[from] crate::accuracy::AccuracyError),
    /// The spectral sea could not be realised.
    #[error(transparent)]
    Sea(#[from] soak_hydro::WaterError),
    /// Registering or stepping a body.
    #[error(transparent)]
    Soak(#[from] SoakError),
    /// No body counts, or a count of zero.
    #[error("body counts must be positive, got {0:?}")]
    Sizes(Vec<usize>),
    /// The figure could not be drawn or written.
    #[error(transparent)]
    Chart(#[from] ChartError),
    /// The output folder could not be made.
    #[error("creating {}: {source}", path.display())]
    Io {
        /// The folder.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
}
