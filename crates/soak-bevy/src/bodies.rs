//! soak-driver's view of bevy_rapier's bodies ([`BevyBodies`]): a body's
//! pose from its `Transform`, its velocities from `Velocity`, its gravity
//! scale, and the engine's settings from Rapier's own body; forces handed
//! back as `ExternalForce`, mass as `AdditionalMassProperties`.

use bevy::prelude::{Entity, Quat, Query, Transform, Vec3};
use bevy_rapier3d::prelude::{
    AdditionalMassProperties, ExternalForce, GravityScale, MassProperties, Velocity,
};
use bevy_rapier3d::rapier::prelude::RigidBodySet;
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use soak_driver::{Bodies, BodiesMut, EngineBody, EngineMass};
use soak_hydro::Wrench;

use crate::floating::SoakLink;

/// A Bevy vector as f64.
pub(crate) fn vector(v: Vec3) -> Vector3<f64> {
    Vector3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// An f64 vector as a Bevy vector.
pub(crate) fn to_vec3(v: &Vector3<f64>) -> Vec3 {
    Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}

/// An f64 rotation as a Bevy rotation.
pub(crate) fn to_quat(q: &UnitQuaternion<f64>) -> Quat {
    Quat::from_xyzw(q.i as f32, q.j as f32, q.k as f32, q.w as f32).normalize()
}

/// A `Transform`'s pose (its scale aside, as bevy_rapier takes it) in f64.
pub(crate) fn engine_pose(t: &Transform) -> Isometry3<f64> {
    let q = t.rotation;
    Isometry3::from_parts(
        Translation3::from(vector(t.translation)),
        UnitQuaternion::from_quaternion(Quaternion::new(q.w as f64, q.x as f64, q.y as f64, q.z as f64)),
    )
}

/// What the plugin reads and writes of a registered body.
pub(crate) type BodyItem = (
    &'static Transform,
    &'static Velocity,
    Option<&'static GravityScale>,
    &'static mut ExternalForce,
    &'static mut AdditionalMassProperties,
    &'static mut SoakLink,
    Option<&'static bevy_rapier3d::prelude::RapierRigidBodyHandle>,
);

/// bevy_rapier's bodies as the driver sees them, over one physics step.
pub(crate) struct BevyBodies<'a, 'w, 's> {
    pub(crate) query: &'a mut Query<'w, 's, BodyItem>,
    /// Rapier's own bodies (for the settings bevy_rapier has no component
    /// for), if there is a context.
    pub(crate) set: Option<&'a RigidBodySet>,
}

/// A body as the driver reads it from its components.
fn engine_body(
    transform: &Transform,
    velocity: &Velocity,
    gravity: Option<&GravityScale>,
    link: &SoakLink,
    rapier: Option<&bevy_rapier3d::rapier::prelude::RigidBody>,
) -> EngineBody {
    EngineBody {
        pose: engine_pose(transform),
        linear_velocity: vector(velocity.linear),
        angular_velocity: vector(velocity.angular),
        mass: link.engine_mass,
        gravity_scale: gravity.map_or(1.0, |g| g.0 as f64),
        // Rapier's defaults where its body is not there yet.
        fast_rotation: rapier.is_some_and(|rb| rb.is_fast_rotation_allowed()),
        gyroscopic: rapier.is_none_or(|rb| rb.gyroscopic_forces_enabled()),
    }
}

impl Bodies for BevyBodies<'_, '_, '_> {
    type Handle = Entity;

    fn body(&self, entity: Entity) -> Option<EngineBody> {
        let (transform, velocity, gravity, _, _, link, handle) = self.query.get(entity).ok()?;
        let rapier = match (self.set, handle) {
            (Some(set), Some(h)) => set.get(h.0),
            _ => None,
        };
        Some(engine_body(transform, velocity, gravity, link, rapier))
    }
}

impl BodiesMut for BevyBodies<'_, '_, '_> {
    fn set_mass_properties(&mut self, entity: Entity, mass: &EngineMass) -> bool {
        let Ok((_, _, _, _, mut additional, mut link, _)) = self.query.get_mut(entity) else {
            return false;
        };
        let (props, engine_mass) = bevy_mass(mass);
        *additional = AdditionalMassProperties::MassProperties(props);
        link.engine_mass = engine_mass;
        true
    }

    fn set_wrench(&mut self, entity: Entity, wrench: &Wrench) -> bool {
        let Ok((_, _, _, mut force, _, _, _)) = self.query.get_mut(entity) else {
            return false;
        };
        // Written every step (bevy_rapier hands a changed component to
        // Rapier, replacing the last step's force).
        *force = ExternalForce {
            force: to_vec3(&wrench.force),
            torque: to_vec3(&wrench.torque),
        };
        true
    }
}

/// Mass properties as bevy_rapier takes them, and the mass Rapier will
/// integrate with (its own f32 arithmetic: `1/(1/m)`), kg.
pub(crate) fn bevy_mass(mass: &EngineMass) -> (MassProperties, f64) {
    let props = MassProperties {
        local_center_of_mass: to_vec3(&mass.center_of_mass.coords),
        mass: mass.mass as f32,
        principal_inertia_local_frame: to_quat(&mass.principal_frame),
        principal_inertia: to_vec3(&mass.principal_moments),
    };
    let engine = props.into_rapier().mass() as f64;
    (props, engine)
}

/// One entity being registered, before its components are on it: the
/// driver reads its pose and velocity from what it was spawned with and
/// hands it its mass, which the plugin then puts on it.
pub(crate) struct Registering {
    pub(crate) entity: Entity,
    pub(crate) body: EngineBody,
    pub(crate) mass: Option<(MassProperties, f64)>,
}

impl Registering {
    /// `entity` standing at `transform` with `velocity`.
    pub(crate) fn new(
        entity: Entity,
        transform: &Transform,
        velocity: Option<&Velocity>,
        gravity: Option<&GravityScale>,
    ) -> Self {
        let zero = Velocity::zero();
        let link = SoakLink {
            id: soak_driver::SoakId(usize::MAX),
            engine_mass: 0.0,
        };
        Self {
            entity,
            body: engine_body(transform, velocity.unwrap_or(&zero), gravity, &link, None),
            mass: None,
        }
    }
}

impl Bodies for Registering {
    type Handle = Entity;

    fn body(&self, entity: Entity) -> Option<EngineBody> {
        (entity == self.entity).then_some(self.body)
    }
}

impl BodiesMut for Registering {
    fn set_mass_properties(&mut self, entity: Entity, mass: &EngineMass) -> bool {
        if entity != self.entity {
            return false;
        }
        let (props, engine) = bevy_mass(mass);
        self.body.mass = engine;
        self.mass = Some((props, engine));
        true
    }

    fn set_wrench(&mut self, entity: Entity, _: &Wrench) -> bool {
        entity == self.entity
    }
}
