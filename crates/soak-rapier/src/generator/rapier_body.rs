//! What the generator writes into a Rapier rigid body: its mass properties
//! ([`push_mass`]) and the step's force and torque ([`apply_wrench`]).

use nalgebra::Vector3;
use rapier3d::prelude::{ColliderSet, RigidBody};
use soak_hydro::{MassProperties, Wrench};

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

/// Hands mass properties to Rapier and makes them readable at once.
pub(super) fn push_mass(
    name: &str,
    rb: &mut RigidBody,
    colliders: &ColliderSet,
    m: &MassProperties,
) -> Result<(), SoakError> {
    if !m.is_finite() || m.mass <= 0.0 {
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
