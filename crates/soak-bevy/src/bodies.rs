//! soak-driver's view of bevy_rapier's bodies ([`Gathered`]): each step
//! every body's pose from its `Transform`, its velocities from `Velocity`,
//! its gravity scale and the engine's settings from Rapier's own body, read
//! in one pass; the forces the driver hands back written as
//! `ExternalForce`, mass as `AdditionalMassProperties`, in another.

use bevy::prelude::{Entity, Quat, Query, Transform, Vec3};
use bevy_rapier3d::prelude::{GravityScale, MassProperties, Velocity};
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

/// How the driver names a body of the plugin: its entity, and its slot in
/// the plugin's dense arrays (the body's [`SoakId`](soak_driver::SoakId)),
/// so that a step reads and writes every body in one pass over the ECS.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BodyKey {
    /// The entity with the [`Floating`](crate::Floating) component.
    pub entity: Entity,
    /// Its index in the driver (its `SoakId`).
    pub(crate) slot: u32,
}

/// What the plugin reads of a registered body each step.
pub(crate) type ReadItem = (
    &'static SoakLink,
    &'static Transform,
    &'static Velocity,
    Option<&'static GravityScale>,
    Option<&'static bevy_rapier3d::prelude::RapierRigidBodyHandle>,
);

/// The bodies of one step, gathered from the ECS in one pass (by slot),
/// what the driver hands them collected the same way, then written back
/// in one pass ([`Gathered::scatter`]). Kept between steps: its arrays are
/// reused.
#[derive(Debug, Default)]
pub(crate) struct Gathered {
    pub(crate) bodies: Vec<Option<EngineBody>>,
    pub(crate) wrenches: Vec<Option<Wrench>>,
    pub(crate) masses: Vec<Option<(MassProperties, f64)>>,
}

impl Gathered {
    /// Reads every registered body of `query` (`slots` of them at most),
    /// the engine's settings from Rapier's own `set`.
    pub(crate) fn gather(&mut self, query: &Query<ReadItem>, set: &RigidBodySet, slots: usize) {
        self.bodies.clear();
        self.bodies.resize(slots, None);
        self.wrenches.clear();
        self.wrenches.resize(slots, None);
        self.masses.clear();
        self.masses.resize(slots, None);
        for (link, transform, velocity, gravity, handle) in query {
            let rapier = handle.and_then(|h| set.get(h.0));
            if let Some(slot) = self.bodies.get_mut(link.id.0) {
                *slot = Some(engine_body(transform, velocity, gravity, link, rapier));
            }
        }
    }
}

impl Bodies for Gathered {
    type Handle = BodyKey;

    fn body(&self, key: BodyKey) -> Option<EngineBody> {
        self.bodies.get(key.slot as usize).copied().flatten()
    }
}

impl BodiesMut for Gathered {
    fn set_mass_properties(&mut self, key: BodyKey, mass: &EngineMass) -> bool {
        let slot = key.slot as usize;
        let Some(Some(body)) = self.bodies.get_mut(slot) else {
            return false;
        };
        let (props, engine) = bevy_mass(mass);
        // The next reads of this step see the mass the engine will have.
        body.mass = engine;
        self.masses[slot] = Some((props, engine));
        true
    }

    fn set_wrench(&mut self, key: BodyKey, wrench: &Wrench) -> bool {
        let slot = key.slot as usize;
        if !matches!(self.bodies.get(slot), Some(Some(_))) {
            return false;
        }
        self.wrenches[slot] = Some(*wrench);
        true
    }
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
    pub(crate) key: BodyKey,
    pub(crate) body: EngineBody,
    pub(crate) mass: Option<(MassProperties, f64)>,
}

impl Registering {
    /// The body `key` names, standing at `transform` with `velocity`.
    pub(crate) fn new(
        key: BodyKey,
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
            key,
            body: engine_body(transform, velocity.unwrap_or(&zero), gravity, &link, None),
            mass: None,
        }
    }
}

impl Bodies for Registering {
    type Handle = BodyKey;

    fn body(&self, key: BodyKey) -> Option<EngineBody> {
        (key == self.key).then_some(self.body)
    }
}

impl BodiesMut for Registering {
    fn set_mass_properties(&mut self, key: BodyKey, mass: &EngineMass) -> bool {
        if key != self.key {
            return false;
        }
        let (props, engine) = bevy_mass(mass);
        self.body.mass = engine;
        self.mass = Some((props, engine));
        true
    }

    fn set_wrench(&mut self, key: BodyKey, _: &Wrench) -> bool {
        key == self.key
    }
}
