//! What can go wrong drawing or showing a simulation.

use thiserror::Error;

/// An error of [`SceneRenderer`](crate::SceneRenderer) or the viewer.
#[derive(Debug, Error)]
pub enum ViewError {
    /// The scene file: it does not load, or a body's mesh does not.
    #[error(transparent)]
    Scene(#[from] soak_rapier::SceneError),
    /// The simulation failed a step.
    #[error(transparent)]
    Simulation(#[from] soak_rapier::SoakError),
    /// The scene's sea is not valid.
    #[error(transparent)]
    Hydro(#[from] soak_hydro::HydroError),
    /// The renderer failed.
    #[error(transparent)]
    Render(#[from] soak_shade::render::RenderError),
    /// No GPU device.
    #[error("no GPU adapter for rendering: {0}")]
    Gpu(#[from] soak_shade::render::GpuError),
    /// A world of your own was given another number of meshes than bodies.
    #[error("{meshes} meshes for {bodies} bodies: give the mesh of each body, in order")]
    Meshes {
        /// Bodies of the simulation.
        bodies: usize,
        /// Meshes given.
        meshes: usize,
    },
    /// The window could not be opened or drawn to.
    #[error("the window: {0}")]
    Window(String),
    /// The time series (`ViewOptions::csv`) could not be written.
    #[error("cannot write the CSV `{path}`: {source}")]
    Csv {
        /// The file.
        path: std::path::PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A screenshot could not be written.
    #[error("cannot write `{path}`: {message}")]
    Screenshot {
        /// The file.
        path: std::path::PathBuf,
        /// Why.
        message: String,
    },
}
