//! soak-driver's view of rapier3d's bodies: [`RapierBodies`] reads and
//! writes a `RigidBodySet` (with its colliders, to make the mass it is
//! handed readable at once), [`RapierBodiesRef`] only reads one.

use rapier3d::prelude::{ColliderSet, MassProperties, RigidBody, RigidBodyHandle, RigidBodySet};
use soak_driver::{Bodies, BodiesMut, EngineBody, EngineMass};
use soak_hydro::Wrench;

use crate::convert;

/// A rapier3d body as the driver reads it.
fn engine_body(rb: &RigidBody) -> EngineBody {
    EngineBody {
        pose: convert::pose(rb.position()),
        linear_velocity: convert::vector(rb.linvel()),
        angular_velocity: convert::vector(rb.angvel()),
        mass: rb.mass() as f64,
        gravity_scale: rb.gravity_scale() as f64,
        fast_rotation: rb.is_fast_rotation_allowed(),
        gyroscopic: rb.gyroscopic_forces_enabled(),
    }
}

/// A `RigidBodySet` the driver reads and writes, with the colliders its
/// bodies' mass is recomputed from (so that `mass()` reads the new mass at
/// once).
#[derive(Debug)]
pub struct RapierBodies<'a> {
    /// The bodies.
    pub bodies: &'a mut RigidBodySet,
    /// Their colliders.
    pub colliders: &'a ColliderSet,
}

impl<'a> RapierBodies<'a> {
    /// The driver's view of `bodies` and their `colliders`.
    pub fn new(bodies: &'a mut RigidBodySet, colliders: &'a ColliderSet) -> Self {
        Self { bodies, colliders }
    }
}

/// A `RigidBodySet` the driver only reads (a draft, a splash, wetting).
#[derive(Clone, Copy, Debug)]
pub struct RapierBodiesRef<'a>(pub &'a RigidBodySet);

impl Bodies for RapierBodiesRef<'_> {
    type Handle = RigidBodyHandle;

    fn body(&self, handle: RigidBodyHandle) -> Option<EngineBody> {
        self.0.get(handle).map(engine_body)
    }
}

impl Bodies for RapierBodies<'_> {
    type Handle = RigidBodyHandle;

    fn body(&self, handle: RigidBodyHandle) -> Option<EngineBody> {
        self.bodies.get(handle).map(engine_body)
    }
}

impl BodiesMut for RapierBodies<'_> {
    fn set_mass_properties(&mut self, handle: RigidBodyHandle, m: &EngineMass) -> bool {
        let Some(rb) = self.bodies.get_mut(handle) else {
            return false;
        };
        let props = MassProperties::with_principal_inertia_frame(
            convert::point_to_vector(&m.center_of_mass),
            m.mass as f32,
            convert::to_vector(&m.principal_moments),
            convert::to_rotation(&m.principal_frame),
        );
        rb.set_additional_mass_properties(props, true);
        rb.recompute_mass_properties_from_colliders(self.colliders);
        true
    }

    fn set_wrench(&mut self, handle: RigidBodyHandle, w: &Wrench) -> bool {
        let Some(rb) = self.bodies.get_mut(handle) else {
            return false;
        };
        // User forces persist across Rapier's steps: the last step's go.
        rb.reset_forces(false);
        rb.reset_torques(false);
        if w.force != nalgebra::Vector3::zeros() || w.torque != nalgebra::Vector3::zeros() {
            rb.add_force(convert::to_vector(&w.force), true);
            rb.add_torque(convert::to_vector(&w.torque), true);
        }
        true
    }
}
