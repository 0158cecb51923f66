//! Buoyancy and drag of a body from its texel atlas, per texel.
//!
//! For texel `i` at world position `p_i` with world area vector `A_i`,
//! depth `d_i = f(p_i) − p_i.y` and submerged set `S = {i : d_i > 0}`:
//! `V_s = Σ_S −A_{i,y} d_i` (signed columns, exact for non-convex bodies and
//! any surface `y = f(x, z)`), `C_B = (1/V_s) Σ_S −A_{i,y} d_i (p_x, p_y + d_i/2, p_z)`;
//! Archimedes mode applies `ρ g V_s` up at `C_B`; pressure mode sums
//! `−ρ g d_i A_i` and its torque (equal on a plane, and it also feels the
//! sideways push of a wave's slope). Drag is quadratic per submerged texel
//! facing its relative velocity, plus optional linear skin friction, and is
//! integrated implicitly over the step so it never reverses a velocity.
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
//! - `slope_torque`: Archimedes' torque as the derivative of the potential.
//! - `deep_volume`: the volume of a body wholly under a surface that is not
//!   a plane.
//! - `implicit_drag`: drag integrated implicitly over the step.
//! - `finish`: the sums turned into forces.
//! - `evaluation`: the per-texel pass, [`evaluate`](crate::evaluate) and
//!   [`streaming_read`](crate::streaming_read).

pub(crate) mod body_state;
pub(crate) mod deep_volume;
pub(crate) mod evaluation;
pub(crate) mod finish;
pub(crate) mod forces;
pub(crate) mod frame;
pub(crate) mod implicit_drag;
pub(crate) mod options;
pub(crate) mod planar_kernel;
pub(crate) mod slope_torque;
pub(crate) mod sums;
