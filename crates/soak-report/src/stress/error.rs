//! What can stop the stability matrix, as values.

use soak_bake::{BakeError, LoadError};
use soak_graph::{FlowError, GraphError, PermeabilityError};
use soak_hydro::WaterError;
use soak_rapier::SoakError;
use soak_wet::WetError;

/// A cell of the stability matrix could not be set up or run.
///
/// A cell that runs and fails its checks is not an error: it is an
/// [`super::Outcome`] with `pass == false`. These are the failures to run it
/// at all; [`StressError::Cell`] names the cell.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StressError {
    /// No cell of the matrix matches the filter.
    #[error("no cell of the matrix matches {0:?}")]
    NoCell(String),
    /// A matrix mesh could not be made.
    #[error("making the {mesh} at scale {scale}: {source}")]
    Load {
        /// The mesh's label.
        mesh: &'static str,
        /// The scale, m per unit.
        scale: f64,
        /// What went wrong.
        source: LoadError,
    },
    /// A matrix mesh could not be baked.
    #[error("baking the {mesh} at scale {scale}: {source}")]
    Bake {
        /// The mesh's label.
        mesh: &'static str,
        /// The scale, m per unit.
        scale: f64,
        /// What went wrong.
        source: BakeError,
    },
    /// A baked mesh encloses no positive finite volume.
    #[error("the {mesh} at scale {scale} encloses a volume of {volume} m³")]
    Volume {
        /// The mesh's label.
        mesh: &'static str,
        /// The scale, m per unit.
        scale: f64,
        /// Its volume, m³.
        volume: f64,
    },
    /// The cell's water.
    #[error(transparent)]
    Water(#[from] WaterError),
    /// Registering or stepping the body.
    #[error(transparent)]
    Soak(#[from] SoakError),
    /// The ingress cells' liquid graph.
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// The ingress cells' hull permeability.
    #[error(transparent)]
    Permeability(#[from] PermeabilityError),
    /// The ingress cells' flooding.
    #[error(transparent)]
    Flow(#[from] FlowError),
    /// The wetting cells' surface liquid.
    #[error(transparent)]
    Wet(#[from] WetError),
    /// The wetting field of a cell has no voxel with neighbours, so its
    /// diffusion cannot be set at a multiple of its explicit limit.
    #[error("the wetting field has no voxel with neighbours")]
    NoNeighbours,
    /// A cell failed to run.
    #[error("cell {cell}: {source}")]
    Cell {
        /// The cell's name.
        cell: String,
        /// What went wrong.
        source: Box<StressError>,
    },
    /// A worker thread running cells panicked.
    #[error("a worker running cells panicked")]
    Worker,
}
