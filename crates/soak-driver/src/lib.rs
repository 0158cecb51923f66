//! The per-step driver of soak's effects, for any rigid-body engine.
//!
//! [`Driver`] keeps the bodies registered with it (their atlas, mass model
//! and effects: buoyancy, drag, added mass, slamming, flooding, wetting,
//! the waves they make), and every step reads each body from the engine,
//! evaluates the water's forces at the pose the engine's step is predicted
//! to pass through, keeps stiff bodies stable and the step free of
//! created energy, and hands the engine the force, torque and mass
//! properties that result. It sees the engine through two small traits:
//! [`Bodies`] (read a body's pose, velocities and mass) and [`BodiesMut`]
//! (hand it mass properties and a wrench).
//!
//! It depends on no engine. soak-rapier adapts it to rapier3d
//! (`ForceGenerator`), soak-bevy to Bevy with bevy_rapier3d
//! (`SoakPlugin`); [`FreeBodies`] is a minimal engine of its own for
//! examples and tests.
//!
//! Each step, around the engine's own:
//! 1. [`Driver::set_gravity`] with the engine's gravity (m/s²),
//! 2. [`Driver::before_step`]: the liquid inside flooding hulls, the
//!    fluid forces handed to the engine, wet surfaces, the waves,
//! 3. the engine steps by `dt`,
//! 4. [`Driver::after_step`] (and [`Driver::tear`] where contacts tear
//!    holes).
//!
//! The engine is expected to integrate as Rapier does (symplectic Euler
//! over substeps with the force held constant): [`predict_step`] says how,
//! and an adapter's tests compare its engine's step with it.

mod body;
mod config;
mod driver;
mod engine;
mod error;
mod firewall;
mod free_bodies;
#[cfg(feature = "gpu")]
mod gpu;
mod implicit;
mod inertial;
mod liquid;
mod phases;
mod predicted_step;
mod radiation;
mod registry;
mod scratch;
mod state;
mod step;
mod waves;

pub use self::body::{SlamReport, SoakBody};
pub use self::config::{Backend, BodyDesc, Effects, ImpactHoles, Slamming, SoakId};
pub use self::driver::{Driver, Impact};
pub use self::engine::{Bodies, BodiesMut, EngineBody, EngineMass, Handle, StepParams, engine_mass};
pub use self::error::SoakError;
pub use self::firewall::{FIREWALL_MEMORY, Firewall, FirewallEvent};
pub use self::free_bodies::{FreeBodies, FreeHandle};
pub use self::phases::StepPhases;
pub use self::predicted_step::{PredictedStep, predict_step};
pub use self::state::{BodyRunState, GeneratorState};
pub use self::waves::{CoupledWavesState, WaveCoupling};
/// Water entering hulls (the liquid graph of [`Effects::flooding`]).
pub use soak_graph;
/// Surface wetting (the liquid texture of [`Effects::wetting`]).
pub use soak_wet;
