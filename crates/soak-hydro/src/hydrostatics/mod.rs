//! Buoyancy and drag of a body from its texel atlas, per texel (the model
//! is described on [`evaluate`](crate::evaluate)).
//!
//! One file per part of the design, each depending only on those above it:
//!
//! - `options`: [`BuoyancyMode`](crate::BuoyancyMode), [`Drag`](crate::Drag),
//!   [`HydroOptions`](crate::HydroOptions).
//! - `body_state`: [`BodyState`](crate::BodyState).
//! - `forces`: [`Wrench`](crate::Wrench), [`HydroForces`](crate::HydroForces).
//! - `sums`: the per-texel sums (buoyancy, Archimedes' slope terms, drag).
//! - `frame`: the frame of one evaluation, depths and texel reads.
//! - `planar_kernel`: the buoyancy sums under planar water, portable and AVX2.
//! - `drag_kernel`: the drag sums under planar water with a uniform
//!   current, per texel and as per-tile moments.
//! - `sea_kernel`: the buoyancy sums under a sampled sea, AVX2.
//! - `sea_drag`: the drag sums under a sampled sea, where the fluid's
//!   velocity differs from texel to texel.
//! - `slope_torque`: Archimedes' torque as the derivative of the potential.
//! - `deep_volume`: the volume of a body wholly under a surface that is not
//!   a plane.
//! - `implicit_drag`: drag integrated implicitly over the step.
//! - `finish`: the sums turned into forces.
//! - `evaluation`: the per-texel pass, [`evaluate`](crate::evaluate) and
//!   [`streaming_read`](crate::streaming_read).

#[cfg(target_arch = "x86_64")]
mod avx;
pub(crate) mod body_state;
pub(crate) mod deep_volume;
pub(crate) mod drag_kernel;
#[cfg(test)]
mod drag_tests;
pub(crate) mod evaluation;
pub(crate) mod finish;
pub(crate) mod forces;
pub(crate) mod frame;
pub(crate) mod implicit_drag;
pub(crate) mod options;
pub(crate) mod planar_kernel;
pub(crate) mod sea_drag;
pub(crate) mod sea_kernel;
pub(crate) mod slope_torque;
pub(crate) mod sums;
