//! What the generator writes into a Rapier rigid body: its mass properties
//! ([`push_mass`]) and the step's force and torque ([`apply_wrench`]).

use nalgebra::Vector3;
use rapier3d::prelude::{ColliderSet, RigidBody};
use soak_hydro::{BuoyancyMode, MassProperties, Water, Wrench};

use super::config::Effects;

use crate::convert;
use crate::error::SoakError;

pub(super) fn apply_wrench(rb: &mut RigidBody, w: &Wrench) {
    rb.reset_forces(false);
    rb.reset_torques(false);
    if w.force != Vector3::zeros() || w.torque != Vector3::zeros() {
        rb.add_force(convert::to_vector(&w.force), true);
        rb.add_torque(convert::to_vector(&w.torque), true);
    }
}

/// Below this fraction of the fluid it displaces a body without an added
/// mass is refused ([`SoakError::TooLight`]): its buoyancy would
/// accelerate it at over a million `g`, and the stiff step can no longer
/// resolve it (at a trillionth, a sphere under water was handed no force
/// at all and fell through).
pub(super) const LIGHTEST_WITHOUT_ADDED_MASS: f64 = 1e-6;

/// Refuses a body with buoyancy and no added mass whose `mass` (kg) is
/// below [`LIGHTEST_WITHOUT_ADDED_MASS`] of the `water` its `volume` (m³)
/// displaces.
pub(super) fn check_not_too_light(
    name: &str,
    mass: f64,
    effects: &Effects,
    water: &Water,
    volume: f64,
) -> Result<(), SoakError> {
    let buoyant = effects.buoyancy.is_some_and(|m| m != BuoyancyMode::Off);
    let displaced = water.density * volume.abs();
    if buoyant && effects.added_mass.is_none() && mass < LIGHTEST_WITHOUT_ADDED_MASS * displaced {
        return Err(SoakError::TooLight {
            name: name.to_string(),
            mass,
            displaced,
        });
    }
    Ok(())
}

/// Hands mass properties to Rapier and makes them readable at once.
pub(super) fn push_mass(
    name: &str,
    rb: &mut RigidBody,
    colliders: &ColliderSet,
    m: &MassProperties,
) -> Result<(), SoakError> {
    // Rapier holds the mass in f32: a mass that rounds to nothing there
    // (or to a subnormal) would leave the body unmoved by any force.
    if !m.is_finite() || m.mass <= 0.0 || !(m.mass as f32).is_normal() {
        return Err(SoakError::MassProperties {
            name: name.to_string(),
            reason: format!(
                "mass {} kg and inertia {:?} are not a valid body",
                m.mass, m.inertia
            ),
        });
    }
    let p = m.principal();
    let props = rapier3d::prelude::MassProperties::with_principal_inertia_frame(
        convert::point_to_vector(&m.center_of_mass),
        m.mass as f32,
        convert::to_vector(&p.moments),
        convert::to_rotation(&p.frame),
    );
    rb.set_additional_mass_properties(props, true);
    rb.recompute_mass_properties_from_colliders(colliders);
    Ok(())
}
