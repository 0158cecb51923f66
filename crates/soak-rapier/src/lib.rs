#![doc = include_str!("../README.md")]

mod error;
mod firewall;
mod generator;
#[cfg(feature = "gpu")]
mod gpu;
mod simulation;

// Public: free functions between nalgebra and Rapier's types, named as `convert::pose(..)`:
// for code that reads soak's f64 core types; the generator's own API speaks Rapier's types.
pub mod convert;
// Public: a run as an animated glTF binary, named as `export::Recording`.
pub mod export;
// Public: free functions measuring a hull, named as `hull::pitch_degrees(..)`.
pub mod hull;
// Public: the many spec types of a scene file, named as `scene::BodySpec`.
pub mod scene;

pub use self::error::{SceneError, SoakError};
pub use self::firewall::{FIREWALL_MEMORY, Firewall, FirewallEvent};
pub use self::generator::{
    Backend, BodyDesc, BodyRunState, CoupledWavesState, Effects, ForceGenerator, GeneratorState, Impact,
    ImpactHoles, SlamReport, Slamming, SoakBody, SoakId, WaveCoupling,
};
pub use self::scene::{LoadedScene, Scene};
pub use self::simulation::{BodyReport, Sample, SavedSimulation, SimBody, Simulation, water_of};
/// Water entering hulls (the liquid graph of [`Effects::flooding`]).
pub use soak_graph;
/// Surface wetting (the liquid texture of [`Effects::wetting`]).
pub use soak_wet;

/// The types most users need.
pub mod prelude {
    pub use crate::{BodyDesc, Effects, ForceGenerator, SoakId};
    pub use soak_hydro::{BuoyancyMode, Drag, MassModel, Water};
}
