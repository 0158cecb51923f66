//! [`ForceGenerator`]: soak-driver's [`Driver`] over rapier3d's bodies.
//! Every method that meets the engine takes Rapier's sets (or its
//! `PhysicsWorld`); the rest are the driver's own, reached through
//! `Deref`.

use std::ops::{Deref, DerefMut};

use nalgebra::Point3;
use rapier3d::prelude::{ColliderSet, IntegrationParameters, PhysicsWorld, RigidBodyHandle, RigidBodySet};
use soak_driver::{Backend, BodyDesc, Driver, SoakId, StepParams, WaveCoupling};
use soak_hydro::{MassModel, MassProperties, SeaBand, SeaSampling, SeaVelocity, Water};

use crate::bodies::{RapierBodies, RapierBodiesRef};
use crate::convert;
use crate::error::SoakError;

/// A body driven by the generator, named by its Rapier handle.
pub type SoakBody = soak_driver::SoakBody<RigidBodyHandle>;

/// Drives the effects of registered rapier3d bodies ([`Effects`](crate::Effects))
/// every step: buoyancy and drag, added mass and slamming, water entering
/// their hulls (flooding), liquid soaking into their surfaces (wetting)
/// and the waves they make.
///
/// It is soak-driver's engine-neutral [`Driver`] with Rapier's types:
/// the methods that read or write bodies take Rapier's `RigidBodySet` (and
/// `ColliderSet`) or its `PhysicsWorld`, and every other method of
/// [`Driver`] (the water, the bodies and their reports, wetting and
/// flooding settings, the saved state) is reached through `Deref`.
///
/// Gravity stays Rapier's: the generator only adds fluid forces and keeps
/// each body's mass properties in line with its mass model (plus the
/// liquid inside it). User forces in Rapier persist across steps, so every
/// step resets the body's forces and torques before adding the new ones.
///
/// A flooding body's liquid advances each step by the world's `dt` with
/// the body's pose, and the body carries its mass ([`ForceGenerator::flood`]).
/// A wet body's liquid texture absorbs water through the submerged texels,
/// dries in the generator's [`Environment`](soak_wet::Environment) and
/// diffuses over the step ([`ForceGenerator::wet`]); wetting does not
/// change the body's mass or forces. A body without flooding or wetting
/// holds no state for them and costs nothing for them.
///
/// # Example
/// ```
/// use rapier3d::prelude::*;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_hydro::{Drag, MassModel, Water};
/// use soak_rapier::{BodyDesc, Effects, ForceGenerator};
///
/// let mut world = PhysicsWorld::new();
/// let handle = world.bodies.insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64))?;
/// let mut soak = ForceGenerator::new(Water::calm(0.0));
/// soak.register(&mut world.bodies, &world.colliders, handle, BodyDesc {
///     name: "crate".into(),
///     atlas: atlas.into(),
///     mass_model: MassModel::Solid { density: 500.0 },
///     effects: Effects::buoyancy().with_drag(Drag::default()),
/// })?;
/// for _ in 0..1200 {
///     soak.step(&mut world)?;
/// }
/// // Half as dense as water: it floats half submerged (its centre near y = 0).
/// assert!(world.bodies[handle].translation().y.abs() < 0.1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct ForceGenerator {
    driver: Driver<RigidBodyHandle>,
}

impl Deref for ForceGenerator {
    type Target = Driver<RigidBodyHandle>;

    fn deref(&self) -> &Self::Target {
        &self.driver
    }
}

impl DerefMut for ForceGenerator {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.driver
    }
}

impl ForceGenerator {
    /// A generator for bodies in `water` (any fluid: water, a sea, air).
    pub fn new(water: Water) -> Self {
        Self {
            driver: Driver::new(water),
        }
    }

    /// The engine-neutral driver underneath.
    pub fn driver(&self) -> &Driver<RigidBodyHandle> {
        &self.driver
    }

    /// Evaluates every body on the GPU, all in one batch per step (one
    /// submission, one readback), with the caller's device. Results are
    /// interchangeable with the CPU backends; should the GPU fail in a step,
    /// that step is evaluated on the CPU and the firewall records it.
    #[cfg(feature = "gpu")]
    pub fn with_gpu(self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, SoakError> {
        Ok(Self {
            driver: self.driver.with_gpu(device, queue)?,
        })
    }

    /// The same generator with another CPU backend.
    pub fn with_backend(self, backend: Backend) -> Self {
        Self {
            driver: self.driver.with_backend(backend),
        }
    }

    /// The same generator reading a sea (a surface that is not a plane)
    /// as `sea` says: each body as it is against the waves (the default,
    /// [`SeaSampling::Auto`]: one plane over a body at most an eighth of
    /// the shortest wave across, the sea sampled over any other), sampled
    /// once per step over each body's footprint
    /// ([`SeaSampling::PerWavelength`], nodes per shortest wavelength),
    /// read as one plane fitted over each body ([`SeaSampling::Plane`]: a
    /// calm-water evaluation's cost, for bodies small against the waves),
    /// or exactly at every texel ([`SeaSampling::Exact`], the reference).
    pub fn with_sea_sampling(self, sea: SeaSampling) -> Self {
        Self {
            driver: self.driver.with_sea_sampling(sea),
        }
    }

    /// The same generator reading a sampled sea's velocity for the drag as
    /// `velocity` says (see [`Driver::with_sea_velocity`]).
    pub fn with_sea_velocity(self, velocity: SeaVelocity) -> Self {
        Self {
            driver: self.driver.with_sea_velocity(velocity),
        }
    }

    /// The same generator with each body reading the waves of a sampled
    /// sea that `band` keeps (see [`Driver::with_sea_band`]).
    pub fn with_sea_band(self, band: SeaBand) -> Self {
        Self {
            driver: self.driver.with_sea_band(band),
        }
    }

    /// The same generator with interactive waves on its water (see
    /// [`WaveCoupling`] and [`Driver::with_waves`]).
    ///
    /// # Errors
    /// [`SoakError::Waves`] for a region or sponge that is refused.
    pub fn with_waves(self, rule: WaveCoupling) -> Result<Self, SoakError> {
        Ok(Self {
            driver: self.driver.with_waves(rule)?,
        })
    }

    /// Registers a rigid body with its effects: computes its mass
    /// properties from the mass model (plus the liquid already inside a
    /// flooding body) and hands them to Rapier (readable at once through
    /// `mass()`). Its colliders must have density 0: soak owns the body's
    /// mass.
    ///
    /// # Errors
    /// A missing Rapier body, a collider with mass, invalid mass
    /// properties, a wetting state made for an atlas of another size.
    pub fn register(
        &mut self,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
        handle: RigidBodyHandle,
        desc: BodyDesc,
    ) -> Result<SoakId, SoakError> {
        let body = bodies.get(handle).ok_or_else(|| SoakError::MissingBody {
            name: desc.name.clone(),
        })?;
        for &ch in body.colliders() {
            if let Some(c) = colliders.get(ch)
                && c.density() != 0.0
            {
                return Err(SoakError::ColliderHasMass {
                    name: desc.name.clone(),
                    collider: ch.into_raw_parts().0,
                    density: c.density(),
                });
            }
        }
        self.driver
            .register(&mut RapierBodies::new(bodies, colliders), handle, desc)
    }

    /// Changes a body's mass model (e.g. a shell density texture that
    /// changes every frame) and updates Rapier's mass properties at once.
    ///
    /// # Errors
    /// An unknown id, a missing Rapier body, invalid mass properties.
    pub fn set_mass_model(
        &mut self,
        id: SoakId,
        model: MassModel,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        self.driver
            .set_mass_model(id, model, &mut RapierBodies::new(bodies, colliders))
    }

    /// Sets the mass a body carries besides its mass model (local frame):
    /// liquid inside, a gas, a payload (see [`Driver::set_extra_mass`]),
    /// handed to Rapier at once.
    ///
    /// # Errors
    /// An unknown id, a missing Rapier body, invalid mass properties.
    pub fn set_extra_mass(
        &mut self,
        id: SoakId,
        extra: Option<MassProperties>,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        self.driver
            .set_extra_mass(id, extra, &mut RapierBodies::new(bodies, colliders))
    }

    /// Follows a deforming mesh: new vertex positions (local frame, m, same
    /// topology) refresh the atlas (and the drag texels, if any) from its
    /// barycentrics (no re-bake) and the mass properties.
    ///
    /// # Errors
    /// As [`Driver::deform`].
    pub fn deform(
        &mut self,
        id: SoakId,
        positions: &[Point3<f64>],
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        self.driver
            .deform(id, positions, &mut RapierBodies::new(bodies, colliders))
    }

    /// Sets the fixed mass a flooding body carries with its liquid (ballast,
    /// cargo; local frame), or none, and hands the total to Rapier at once.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, a missing Rapier body,
    /// non-finite ballast.
    pub fn set_ballast(
        &mut self,
        id: SoakId,
        ballast: Option<MassProperties>,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        self.driver
            .set_ballast(id, ballast, &mut RapierBodies::new(bodies, colliders))
    }

    /// Sets the density of the liquid inside a flooding body, kg/m³
    /// (default: the surrounding fluid's, [`Water::density`]), and hands
    /// its mass to Rapier at once.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, a missing Rapier body, a
    /// density that is not a finite number ≥ 0.
    pub fn set_liquid_density(
        &mut self,
        id: SoakId,
        density: f64,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        self.driver
            .set_liquid_density(id, density, &mut RapierBodies::new(bodies, colliders))
    }

    /// Hands a flooding body's liquid plus ballast to Rapier now, as the
    /// mass it carries besides its model ([`ForceGenerator::set_extra_mass`]).
    /// [`ForceGenerator::flood`] does it whenever the liquid changed.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, a missing Rapier body,
    /// invalid mass properties.
    pub fn sync_liquid_mass(
        &mut self,
        id: SoakId,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        self.driver
            .sync_liquid_mass(id, &mut RapierBodies::new(bodies, colliders))
    }

    /// The draft of body `id` at its current pose in `bodies`, m (see
    /// [`Driver::draft`]). `None` for an unknown id or a body no longer in
    /// `bodies`.
    pub fn draft(&self, id: SoakId, bodies: &RigidBodySet) -> Option<f64> {
        self.driver.draft(id, &RapierBodiesRef(bodies))
    }

    /// [`Driver::open_hole`] at a world point (m): where a shell struck the
    /// hull, as the body stands now in `bodies`.
    ///
    /// # Errors
    /// As [`Driver::open_hole`]; a missing Rapier body.
    pub fn open_hole_at(
        &mut self,
        id: SoakId,
        bodies: &RigidBodySet,
        point: impl Into<Point3<f64>>,
        radius: f64,
    ) -> Result<usize, SoakError> {
        self.driver
            .open_hole_at(id, &RapierBodiesRef(bodies), point, radius)
    }

    /// Advances the liquid inside every flooding body by `dt` (s) with the
    /// body's pose as Rapier has it now (see [`Driver::flood`]).
    /// [`ForceGenerator::step`] calls it first; call it yourself (once per
    /// step, after [`ForceGenerator::sync_gravity`] and before
    /// [`ForceGenerator::apply`]) when driving Rapier yourself.
    ///
    /// # Errors
    /// A flooding body Rapier no longer has, a liquid step that failed (the
    /// body's liquid is then unchanged), invalid mass properties.
    pub fn flood(
        &mut self,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
        dt: f64,
    ) -> Result<(), SoakError> {
        self.driver.flood(&mut RapierBodies::new(bodies, colliders), dt)
    }

    /// Evaluates every body's buoyancy and drag and applies them as forces
    /// and torques (resetting the previous step's), for the Rapier step
    /// that `params` describe (see [`Driver::apply`]). Does not advance
    /// time, flood nor wet bodies; [`ForceGenerator::step`] does all four.
    pub fn apply(&mut self, bodies: &mut RigidBodySet, params: &IntegrationParameters) {
        // `apply` writes no mass: no colliders are needed to recompute it.
        let colliders = ColliderSet::new();
        self.driver
            .apply(&mut RapierBodies::new(bodies, &colliders), &step_params(params));
    }

    /// Advances the liquid texture of every wet body by `dt` (s) with the
    /// body's pose as Rapier has it now (see [`Driver::wet`]).
    /// [`ForceGenerator::step`] calls it before stepping the world; call it
    /// yourself (once per step, before [`Driver::advance`]) when
    /// driving Rapier yourself.
    ///
    /// # Errors
    /// Invalid wetting settings.
    pub fn wet(&mut self, bodies: &RigidBodySet, dt: f64) -> Result<(), SoakError> {
        self.driver.wet(&RapierBodiesRef(bodies), dt)
    }

    /// Drops `splash` on every wet body, each at its pose as Rapier has it
    /// now; returns the volume that stuck, m³ (see [`Driver::splash`]).
    ///
    /// # Errors
    /// An invalid splash, or a wet body whose pose is not finite.
    pub fn splash(&mut self, bodies: &RigidBodySet, splash: &soak_wet::Splash) -> Result<f64, SoakError> {
        self.driver.splash(&RapierBodiesRef(bodies), splash)
    }

    /// Makes the fluid's hydrostatic gravity the world's (m/s²). [`ForceGenerator::step`]
    /// does this every step; call it when driving Rapier yourself.
    pub fn sync_gravity(&mut self, world: &PhysicsWorld) {
        self.driver.set_gravity(convert::vector(world.gravity).norm());
    }

    /// One step of every body's effects and of the world: advances the
    /// liquid inside flooding bodies ([`ForceGenerator::flood`]), applies
    /// the fluid forces ([`ForceGenerator::apply`]), wets the wet bodies
    /// over the step ([`ForceGenerator::wet`]), steps the interactive
    /// waves, steps the world once, advances time and opens the holes hard
    /// contacts tore ([`ForceGenerator::tear`]). The fluid's gravity
    /// follows the world's.
    ///
    /// # Errors
    /// A flooding or wetting step that failed (see [`ForceGenerator::flood`]
    /// and [`ForceGenerator::wet`]); the world is then not stepped.
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<(), SoakError> {
        self.sync_gravity(world);
        let params = step_params(&world.integration_parameters);
        self.driver.before_step(
            &mut RapierBodies::new(&mut world.bodies, &world.colliders),
            &params,
        )?;
        world.step();
        self.driver.after_step(params.dt);
        self.tear(world)
    }

    /// Opens the holes the last Rapier step's hard contacts call for
    /// ([`ImpactHoles`](crate::ImpactHoles)), recording them in
    /// [`Driver::impacts`]: every contact pair of the body's colliders
    /// whose impulse over the step exceeds the rule's, at its deepest
    /// contact. [`ForceGenerator::step`] calls it after the world's step;
    /// call it yourself after stepping the world when driving the parts one
    /// by one.
    ///
    /// # Errors
    /// A missing Rapier body.
    pub fn tear(&mut self, world: &PhysicsWorld) -> Result<(), SoakError> {
        let contacts = |handle: RigidBodyHandle| {
            let mut blows = Vec::new();
            let Some(rb) = world.bodies.get(handle) else {
                return blows;
            };
            // Each pair at its deepest contact, in the order Rapier keeps
            // the body's colliders and their pairs.
            for &ch in rb.colliders() {
                let Some(collider) = world.colliders.get(ch) else {
                    continue;
                };
                let collider_pose = convert::pose(collider.position());
                for pair in world.narrow_phase.contact_pairs_with(ch) {
                    let Some((_, contact)) = pair.find_deepest_contact() else {
                        continue;
                    };
                    let local = if pair.collider1 == ch {
                        contact.local_p1
                    } else {
                        contact.local_p2
                    };
                    let point = collider_pose * Point3::new(local.x as f64, local.y as f64, local.z as f64);
                    blows.push((pair.total_impulse_magnitude() as f64, point));
                }
            }
            blows
        };
        self.driver.tear(&RapierBodiesRef(&world.bodies), contacts)
    }
}

/// The step Rapier's integration parameters describe.
pub fn step_params(params: &IntegrationParameters) -> StepParams {
    StepParams::new(params.dt as f64, params.num_solver_iterations)
}
