//! Measures of a floating hull in its Rapier pose: trim ([`pitch_degrees`]),
//! heel ([`heel_degrees`]) and how high its highest point stands above the
//! water ([`highest_above_water`]), for bodies whose bow points along their
//! local +x and whose starboard is their local +z.
//!
//! They take the pose as Rapier hands it back
//! (`world.bodies[handle].position()`), so a sinking boat's trim is one
//! call:
//!
//! ```
//! use rapier3d::prelude::*;
//! use soak_rapier::hull::pitch_degrees;
//!
//! // Bow 10° up (a rotation about the starboard axis, +z).
//! let pose = Pose::from_parts(Vector::ZERO, Rotation::from_rotation_z(10f32.to_radians()));
//! assert!((pitch_degrees(&pose) - 10.0).abs() < 1e-4);
//! ```

use rapier3d::math::{Pose, Vector};
use soak_bake::Atlas;
use soak_hydro::Water;

use crate::convert;

/// Pitch of a body whose bow points along its local +x, degrees: the angle
/// of that axis above the horizontal, positive bow-up (stern-down),
/// negative bow-down.
pub fn pitch_degrees(pose: &Pose) -> f64 {
    let bow = pose.rotation * Vector::X;
    f64::from(bow.y).clamp(-1.0, 1.0).asin().to_degrees()
}

/// Heel of a body whose starboard is its local +z, degrees: the angle of
/// that axis below the horizontal, positive listing to starboard.
pub fn heel_degrees(pose: &Pose) -> f64 {
    let starboard = pose.rotation * Vector::Z;
    f64::from(-starboard.y).clamp(-1.0, 1.0).asin().to_degrees()
}

/// Height of the body's highest texel above the water's surface at time
/// `t` (s), m: negative once the whole body is under water (sunk). `+∞` for
/// an empty atlas, `−∞` in an unbounded fluid.
///
/// Not a naval architect's freeboard (the height of the deck's edge at its
/// lowest): a boat that floods and trims bow-down lifts its stern, and this
/// height rises while the deck's edge at the bow goes under.
pub fn highest_above_water(atlas: &Atlas, pose: &Pose, water: &Water, t: f64) -> f64 {
    let pose = convert::pose(pose);
    (0..atlas.len())
        .map(|i| -water.surface.depth(&(pose * atlas.position(i)), t))
        .filter(|d| !d.is_nan())
        .fold(f64::NEG_INFINITY, f64::max)
        .max(if atlas.is_empty() {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        })
}
