//! The state of a body the water acts on: its pose and velocities.

use nalgebra::{Isometry3, Vector3};
use serde::{Deserialize, Serialize};

use crate::error::HydroError;

/// Pose and velocity of a body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyState {
    /// Object-to-world transform (m).
    pub pose: Isometry3<f64>,
    /// Velocity of the centre of mass, world frame, m/s.
    pub linear_velocity: Vector3<f64>,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: Vector3<f64>,
}

impl BodyState {
    /// A body at rest at `pose`.
    pub fn at_rest(pose: Isometry3<f64>) -> Self {
        Self {
            pose,
            linear_velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
        }
    }

    pub(crate) fn check(&self) -> Result<(), HydroError> {
        let fin = |v: &[f64]| v.iter().all(|c| c.is_finite());
        if !fin(self.pose.translation.vector.as_slice()) || !fin(self.pose.rotation.coords.as_slice()) {
            return Err(HydroError::NonFiniteState { field: "pose" });
        }
        if !fin(self.linear_velocity.as_slice()) {
            return Err(HydroError::NonFiniteState {
                field: "linear_velocity",
            });
        }
        if !fin(self.angular_velocity.as_slice()) {
            return Err(HydroError::NonFiniteState {
                field: "angular_velocity",
            });
        }
        Ok(())
    }
}
