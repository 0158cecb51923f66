//! What the driver needs of a rigid-body engine: [`Bodies`] reads a body's
//! pose, velocities and mass as the engine has them, [`BodiesMut`] hands
//! it the mass properties and the step's force and torque; [`StepParams`]
//! is the step the engine is about to take. Also the checks every mass
//! goes through before an engine sees it ([`push_mass`]).

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use soak_hydro::{BuoyancyMode, MassProperties, Water, Wrench};

use crate::config::Effects;
use crate::error::SoakError;

/// A rigid body as the driver reads it from its engine: world frame, y up,
/// SI units, in f64 (an engine in f32 widens its values exactly).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EngineBody {
    /// The pose of the body's own frame (the frame its atlas and mass
    /// properties are given in), world, m.
    pub pose: Isometry3<f64>,
    /// Linear velocity of its centre of mass, world, m/s.
    pub linear_velocity: Vector3<f64>,
    /// Angular velocity, world, rad/s.
    pub angular_velocity: Vector3<f64>,
    /// Its mass as the engine integrates it, kg: what the driver handed it
    /// ([`BodiesMut::set_mass_properties`]) as the engine stores it (an
    /// f32 engine's rounding included: the step the driver predicts is the
    /// one the engine takes).
    pub mass: f64,
    /// The factor on gravity for this body (1 for most; 0 floats it in
    /// no gravity at all).
    pub gravity_scale: f64,
    /// Whether the engine lets the body turn more than `π/4` in a step.
    /// Rapier caps the angular speed at `π/(4 dt)` unless told otherwise;
    /// the driver's prediction of the step caps it where the engine does.
    pub fast_rotation: bool,
    /// Whether the engine applies the gyroscopic term (`−ω × Iω`, explicit,
    /// once per substep) to the body's spin.
    pub gyroscopic: bool,
}

/// Mass properties as an engine takes them: mass, centre of mass and the
/// principal moments of inertia in their frame (every engine's form).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EngineMass {
    /// Mass, kg (finite, > 0, a normal f32).
    pub mass: f64,
    /// Centre of mass, the body's own frame, m.
    pub center_of_mass: Point3<f64>,
    /// Principal moments of inertia about the centre of mass, kg·m².
    pub principal_moments: Vector3<f64>,
    /// The principal axes: the rotation from the principal frame to the
    /// body's own frame.
    pub principal_frame: UnitQuaternion<f64>,
}

/// How an engine names a rigid body: any small copyable key (Rapier's
/// `RigidBodyHandle`, a Bevy `Entity`, an index).
pub trait Handle: Copy + Eq + std::fmt::Debug + Send + Sync {}

impl<T: Copy + Eq + std::fmt::Debug + Send + Sync> Handle for T {}

/// Reads rigid bodies from a physics engine.
///
/// The driver reads each body it drives once per step, before the engine
/// steps (and again where a user call needs the pose now: a draft, a
/// splash). An adapter implements it over the engine's own storage: a
/// Rapier `RigidBodySet` (soak-rapier) or bevy_rapier's components
/// (soak-bevy).
pub trait Bodies {
    /// How the engine names a body (Rapier's `RigidBodyHandle`, a Bevy
    /// `Entity`).
    type Handle: Handle;

    /// The body `handle` names now, or `None` when the engine has no such
    /// body (never had, or it was removed).
    fn body(&self, handle: Self::Handle) -> Option<EngineBody>;
}

/// Hands forces and mass properties to a physics engine.
pub trait BodiesMut: Bodies {
    /// Replaces the body's mass properties with `mass` (the body's own
    /// frame), taking effect for the engine's next step. The engine must
    /// add no mass of its own (colliders of density 0): soak owns the
    /// body's mass. Returns `false` when the engine has no such body.
    fn set_mass_properties(&mut self, handle: Self::Handle, mass: &EngineMass) -> bool;

    /// Replaces the force (N, world frame, through the centre of mass) and
    /// torque (N·m, world frame, about the centre of mass) the engine
    /// applies to the body over its next step, held constant over its
    /// substeps, on top of gravity. The previous step's are dropped.
    /// Returns `false` when the engine has no such body.
    fn set_wrench(&mut self, handle: Self::Handle, wrench: &Wrench) -> bool;
}

/// The step the engine is about to take.
///
/// The driver predicts the engine's step to keep stiff bodies stable and
/// to check that no step creates energy: the engine's integrator is
/// symplectic Euler over `substeps` equal substeps with the force held
/// constant (Rapier's, and bevy_rapier's, which runs Rapier). See
/// [`predict_step`](crate::predict_step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepParams {
    /// The step, s (finite, > 0).
    pub dt: f64,
    /// The number of substeps the engine divides it into (Rapier's
    /// `num_solver_iterations`; at least 1).
    pub substeps: usize,
}

impl StepParams {
    /// A step of `dt` seconds in `substeps` substeps.
    pub fn new(dt: f64, substeps: usize) -> Self {
        Self { dt, substeps }
    }

    /// The substeps as a number, at least 1.
    pub(crate) fn substeps_f64(&self) -> f64 {
        self.substeps.max(1) as f64
    }
}

/// Below this fraction of the fluid it displaces a body without an added
/// mass is refused ([`SoakError::TooLight`]): its buoyancy would
/// accelerate it at over a million `g`, and the stiff step can no longer
/// resolve it (at a trillionth, a sphere under water was handed no force
/// at all and fell through).
pub(crate) const LIGHTEST_WITHOUT_ADDED_MASS: f64 = 1e-6;

/// Refuses a body with buoyancy and no added mass whose `mass` (kg) is
/// below [`LIGHTEST_WITHOUT_ADDED_MASS`] of the `water` its `volume` (m³)
/// displaces.
pub(crate) fn check_not_too_light(
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

/// Mass properties as an engine takes them, or why they are not a body.
pub fn engine_mass(name: &str, m: &MassProperties) -> Result<EngineMass, SoakError> {
    // Engines hold the mass in f32: a mass that rounds to nothing there
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
    Ok(EngineMass {
        mass: m.mass,
        center_of_mass: m.center_of_mass,
        principal_moments: p.moments,
        principal_frame: p.frame,
    })
}

/// Hands mass properties to the engine (checked first: see
/// [`engine_mass`]).
pub(crate) fn push_mass<B: BodiesMut + ?Sized>(
    name: &str,
    bodies: &mut B,
    handle: B::Handle,
    m: &MassProperties,
) -> Result<(), SoakError> {
    let mass = engine_mass(name, m)?;
    if bodies.set_mass_properties(handle, &mass) {
        Ok(())
    } else {
        Err(SoakError::MissingBody {
            name: name.to_string(),
        })
    }
}
