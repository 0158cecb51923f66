#![doc = include_str!("../README.md")]

pub mod convert;
pub mod error;
pub mod firewall;
pub mod generator;
#[cfg(feature = "gpu")]
mod gpu;
pub mod hull;
pub mod scene;
pub mod simulation;

pub use error::{SceneError, SoakError};
pub use firewall::{Firewall, FirewallEvent};
pub use generator::{
    Backend, BodyDesc, BodyRunState, Effects, ForceGenerator, GeneratorState, SoakBody, SoakId,
};
pub use scene::{LoadedScene, Scene};
pub use simulation::{BodyReport, Sample, SavedSimulation, Simulation};
/// Water entering hulls (the liquid graph of [`Effects::flooding`]).
pub use soak_graph;
/// Surface wetting (the liquid texture of [`Effects::wetting`]).
pub use soak_wet;

/// The types most users need.
pub mod prelude {
    pub use crate::{BodyDesc, Effects, ForceGenerator, SoakId};
    pub use soak_hydro::{BuoyancyMode, Drag, MassModel, Water};
}
