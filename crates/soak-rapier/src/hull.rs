//! Measures of a floating hull in its pose: trim ([`pitch_degrees`]), heel
//! ([`heel_degrees`]) and [`freeboard`], for bodies whose bow points along
//! their local +x and whose starboard is their local +z.

use nalgebra::{Isometry3, Vector3};
use soak_bake::Atlas;
use soak_hydro::Water;

/// Pitch of a body whose bow points along its local +x, degrees: the angle
/// of that axis above the horizontal, positive bow-up (stern-down),
/// negative bow-down.
pub fn pitch_degrees(pose: &Isometry3<f64>) -> f64 {
    let bow = pose.rotation * Vector3::x();
    bow.y.clamp(-1.0, 1.0).asin().to_degrees()
}

/// Heel of a body whose starboard is its local +z, degrees: the angle of
/// that axis below the horizontal, positive listing to starboard.
pub fn heel_degrees(pose: &Isometry3<f64>) -> f64 {
    let starboard = pose.rotation * Vector3::z();
    (-starboard.y).clamp(-1.0, 1.0).asin().to_degrees()
}

/// Height of the body's highest texel above the water surface at time `t`
/// (s), m: negative once the whole body is under water (sunk). `+∞` for an
/// empty atlas, `−∞` in an unbounded fluid.
pub fn freeboard(atlas: &Atlas, pose: &Isometry3<f64>, water: &Water, t: f64) -> f64 {
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
