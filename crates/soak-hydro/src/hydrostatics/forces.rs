//! What the water does to a body: the wrench type and the forces of one
//! evaluation.

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

/// A force and a torque, world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Wrench {
    /// Force, N.
    pub force: Vector3<f64>,
    /// Torque about the centre of mass, N·m.
    pub torque: Vector3<f64>,
}

impl std::ops::Add for Wrench {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            force: self.force + o.force,
            torque: self.torque + o.torque,
        }
    }
}

impl Wrench {
    /// Whether force and torque are finite.
    pub fn is_finite(&self) -> bool {
        self.force.iter().chain(self.torque.iter()).all(|c| c.is_finite())
    }
}

/// Everything the fluid does to a body in one evaluation, world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct HydroForces {
    /// Submerged volume `V_s`, m³: `Σ −A_y d` over the submerged texels,
    /// but in Archimedes mode, for a body wholly under a surface that is
    /// not a plane, moved towards the enclosed volume as it goes deeper
    /// (by the weight [`HydroForces::deep`]), which takes out the sampling
    /// error of `∮ h n_y dA = 0`.
    pub submerged_volume: f64,
    /// Centre of buoyancy, world, m (the body's centre of mass when dry).
    pub center_of_buoyancy: Point3<f64>,
    /// Wetted (submerged) surface area, m².
    pub wetted_area: f64,
    /// Submerged texels.
    pub submerged_texels: usize,
    /// The water columns' potential `ρ_w g Σ (−A_{i,y}) d_i²/2` over the
    /// submerged texels, J (zero dry; summed whatever the buoyancy mode).
    /// Minus its derivative along a vertical displacement is the vertical
    /// buoyancy, and in Archimedes mode minus its derivative along a turn
    /// is the torque wherever the body is partly dry, so that on calm water
    /// `½ m v² + ½ ωᵀIω + m g y_G + potential` is conserved. (0 when read
    /// from a saved state that predates it.)
    #[serde(default)]
    pub potential: f64,
    /// How deep the body is: 0 while any texel is dry, 1 once every texel
    /// is under water; but in Archimedes mode under a surface that is not
    /// a plane, `φ = Π min(d_i/r, 1)` over the texels (`r` the bounding
    /// radius), 1 only once every texel is deeper than `r`: the weight with
    /// which the force's volume has moved from `Σ −A_y d` to the enclosed
    /// volume (see [`HydroForces::submerged_volume`]). Below 1 the body is
    /// at the surface, where its buoyancy changes with its pose. (0 when
    /// read from a saved state that predates it.)
    #[serde(default)]
    pub deep: f64,
    /// The buoyancy of the mode [`HydroOptions::buoyancy`](crate::HydroOptions::buoyancy) selects, N and
    /// N·m about the centre of mass: in Archimedes mode `ρ g V_s` up at the
    /// centre of buoyancy (its torque with the terms that make it the
    /// derivative of the sampled potential), in pressure mode the pressure
    /// force `Σ −ρ g d_i A_i` and its moment, zero when off. Only the
    /// selected mode's sums are taken: to compare the two, evaluate twice.
    pub buoyancy: Wrench,
    /// Drag as applied: the implicit integral over the step divided by `dt`.
    pub drag: Wrench,
    /// Drag at the current velocity (explicit), for reporting.
    pub drag_explicit: Wrench,
}

impl HydroForces {
    /// Buoyancy plus drag: what to apply to the body.
    pub fn total(&self) -> Wrench {
        self.buoyancy + self.drag
    }
}
