#![doc = include_str!("../README.md")]

mod bodies;
mod error;
mod force_generator;
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

pub use self::bodies::{RapierBodies, RapierBodiesRef};
pub use self::error::{SceneError, SoakError};
pub use self::force_generator::{ForceGenerator, SoakBody, step_params};
pub use self::scene::{LoadedScene, Scene};
pub use self::simulation::{
    BodyReport, CHECKPOINT_MAGIC, CHECKPOINT_VERSION, CSV_HEADER, CheckpointError, Sample, SampleCsv,
    SavedSimulation, SimBody, Simulation, decode_checkpoint, radiation_settings, read_checkpoint, water_of,
    write_atomically, write_checkpoint,
};
/// The engine-neutral driver [`ForceGenerator`] adapts to Rapier.
pub use soak_driver;
pub use soak_driver::{
    Backend, BodyDesc, BodyRunState, CoupledWavesState, Effects, FIREWALL_MEMORY, Firewall, FirewallEvent,
    GeneratorState, Impact, ImpactHoles, SlamReport, Slamming, SoakId, WaveCoupling,
};
/// Water entering hulls (the liquid graph of [`Effects::flooding`]).
pub use soak_graph;
pub use soak_seakeeping;
/// Surface wetting (the liquid texture of [`Effects::wetting`]).
pub use soak_wet;

/// A [`SoakBody`]'s last forces in Rapier's vector type (f32, as handed to
/// Rapier; [`SoakBody::applied`] and [`SoakBody::forces`] have them in f64).
pub trait RapierSoakBody {
    /// The force handed to Rapier at the last step, world frame, N.
    fn applied_force(&self) -> rapier3d::math::Vector;
    /// The torque about the centre of mass handed to Rapier at the last
    /// step, world frame, N·m.
    fn applied_torque(&self) -> rapier3d::math::Vector;
    /// Its centre of buoyancy at the last step, world, m (its centre of
    /// mass when dry); in f64 as soak computed it:
    /// [`forces()`](SoakBody::forces)`.center_of_buoyancy`.
    fn center_of_buoyancy(&self) -> rapier3d::math::Vector;
}

impl RapierSoakBody for SoakBody {
    fn applied_force(&self) -> rapier3d::math::Vector {
        convert::to_vector(&self.applied().force)
    }
    fn applied_torque(&self) -> rapier3d::math::Vector {
        convert::to_vector(&self.applied().torque)
    }
    fn center_of_buoyancy(&self) -> rapier3d::math::Vector {
        convert::point_to_vector(&self.forces().center_of_buoyancy)
    }
}

/// The types most users need.
pub mod prelude {
    pub use crate::{BodyDesc, Effects, ForceGenerator, RapierSoakBody, SoakId};
    pub use soak_hydro::{BuoyancyMode, Drag, MassModel, Water};
}
