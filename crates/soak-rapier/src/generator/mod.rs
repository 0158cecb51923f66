//! The force generator: buoyancy and drag for rapier3d bodies, every step,
//! and (opt-in, per body) surface wetting: the liquid texture of
//! [`soak_wet::Wetting`], absorbing through the submerged texels,
//! evaporating and diffusing with each step.
//!
//! Split by concept, each file depending only on those listed before it:
//! `config` (what a body registers with), `body` ([`SoakBody`]),
//! `rapier_body` (what is written into a Rapier body), `predicted_step`
//! (the energy guard's prediction of Rapier's step), `implicit` (the
//! implicit heave, pitch and roll integrator), `waves` (the interactive
//! waves bodies make, [`WaveCoupling`]), `force_generator`
//! ([`ForceGenerator`] and its set-up), `state` (saving and restoring) and
//! `driver` (each step's work). The GPU backend (`crate::gpu`) depends on
//! `body` alone. This file only re-exports their public items.

pub(crate) mod body;
mod config;
mod driver;
mod force_generator;
mod implicit;
mod inertial;
mod predicted_step;
mod rapier_body;
mod state;
mod waves;

pub use body::{SlamReport, SoakBody};
pub use config::{Backend, BodyDesc, Effects, ImpactHoles, Slamming, SoakId};
pub use force_generator::{ForceGenerator, Impact};
pub use state::{BodyRunState, GeneratorState};
pub use waves::{CoupledWavesState, WaveCoupling};
