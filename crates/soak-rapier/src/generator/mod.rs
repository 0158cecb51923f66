//! The force generator: buoyancy and drag for rapier3d bodies, every step,
//! and (opt-in, per body) surface wetting: the liquid texture of
//! [`soak_wet::Wetting`], absorbing through the submerged texels,
//! evaporating and diffusing with each step.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};
use rapier3d::prelude::{ColliderSet, IntegrationParameters, PhysicsWorld, RigidBodyHandle, RigidBodySet};
use soak_hydro::{
    BodyState, BuoyancyMode, HydroForces, HydroOptions, MassModel, MassProperties, TiledAtlas, Water, Wrench,
};
use soak_wet::{Environment, StepReport, Wetting};

use crate::convert;
use crate::error::SoakError;
use crate::firewall::Firewall;

pub(crate) mod body;
mod config;
mod implicit;
mod predicted_step;
mod rapier_body;
mod state;

pub use body::SoakBody;
use body::{Shape, Wet, with_extra};
pub use config::{Backend, BodyDesc, Effects, SoakId};
use implicit::{IMPLICIT_NEGLIGIBLE, implicit_heave, implicit_weight};
use rapier_body::{apply_wrench, push_mass};
pub use state::{BodyRunState, GeneratorState};

/// Applies buoyancy and drag to registered rapier3d bodies before each step.
///
/// Gravity stays Rapier's: the generator only adds fluid forces and keeps
/// each body's mass properties in line with its mass model. User forces in
/// Rapier persist across steps, so every step resets the body's forces and
/// torques before adding the new ones.
///
/// Bodies may also get wet ([`ForceGenerator::set_wetting`]): each step
/// their liquid texture absorbs water through the submerged texels, dries
/// in the generator's [`Environment`] and diffuses, all over the step's
/// `dt`. Wetting does not change the body's mass or forces. A body without
/// wetting holds no wetting state at all and costs nothing for it.
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
///     atlas,
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
    water: Water,
    bodies: Vec<SoakBody>,
    backend: Backend,
    time: f64,
    steps: u64,
    firewall: Firewall,
    environment: Environment,
    #[cfg(feature = "gpu")]
    gpu: Option<crate::gpu::GpuBackend>,
}

impl ForceGenerator {
    /// A generator for bodies in `water` (any fluid: water, a sea, air).
    pub fn new(water: Water) -> Self {
        Self {
            water,
            bodies: Vec::new(),
            backend: Backend::default(),
            time: 0.0,
            steps: 0,
            firewall: Firewall::default(),
            environment: Environment::default(),
            #[cfg(feature = "gpu")]
            gpu: None,
        }
    }

    /// Evaluates every body on the GPU, all in one batch per step (one
    /// submission, one readback), with the caller's device. Results are
    /// interchangeable with the CPU backends; should the GPU fail in a step,
    /// that step is evaluated on the CPU and the firewall records it.
    #[cfg(feature = "gpu")]
    pub fn with_gpu(mut self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, SoakError> {
        let mut gpu = crate::gpu::GpuBackend::new(device, queue)?;
        for b in &self.bodies {
            gpu.upload(&b.atlas)?;
        }
        self.gpu = Some(gpu);
        Ok(self)
    }

    /// Whether bodies are evaluated on the GPU.
    pub fn uses_gpu(&self) -> bool {
        #[cfg(feature = "gpu")]
        return self.gpu.is_some();
        #[cfg(not(feature = "gpu"))]
        false
    }

    /// The same generator with another CPU backend.
    pub fn with_backend(mut self, backend: Backend) -> Self {
        self.backend = backend;
        for b in &mut self.bodies {
            b.tiled = (backend != Backend::PerTexel && b.effects.any()).then(|| TiledAtlas::new(&b.atlas));
        }
        self
    }

    /// The fluid.
    pub fn water(&self) -> &Water {
        &self.water
    }

    /// Replaces the fluid (a new sea state, a rising tide).
    pub fn set_water(&mut self, water: Water) {
        self.water = water;
    }

    /// The weather wet bodies dry in (temperature in K, relative humidity
    /// as a fraction, wind in m/s, rain); [`Environment::default`] (20 °C,
    /// 50 %, 2 m/s, no rain) until set.
    pub fn environment(&self) -> &Environment {
        &self.environment
    }

    /// Replaces the weather (validated); it applies from the next step.
    pub fn set_environment(&mut self, environment: Environment) -> Result<(), SoakError> {
        environment.validate().map_err(|source| SoakError::Wet {
            name: "(environment)".into(),
            source,
        })?;
        self.environment = environment;
        Ok(())
    }

    /// Turns wetting on for a body with `Some(state)` (made for the body's
    /// atlas, e.g. `Wetting::new(body.atlas(), Material::wood(),
    /// Liquid::water())`, and keeping the liquid it already holds), or off
    /// with `None`, which drops the state and everything it allocated.
    pub fn set_wetting(&mut self, id: SoakId, wetting: Option<Wetting>) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if let Some(w) = &wetting
            && w.texels() != b.atlas.len()
        {
            return Err(SoakError::Wet {
                name: b.name.clone(),
                source: soak_wet::WetError::AtlasMismatch {
                    state: w.texels(),
                    atlas: b.atlas.len(),
                },
            });
        }
        b.wet = wetting.map(|wetting| Wet {
            wetting,
            last: StepReport::default(),
        });
        Ok(())
    }

    /// A body's wetting state, if it has one.
    pub fn wetting(&self, id: SoakId) -> Option<&Wetting> {
        self.bodies.get(id.0).and_then(SoakBody::wetting)
    }

    /// A body's wetting state, to splash, paint or change its settings
    /// (with the body's atlas: [`SoakBody::atlas`]).
    pub fn wetting_mut(&mut self, id: SoakId) -> Option<&mut Wetting> {
        self.bodies
            .get_mut(id.0)
            .and_then(|b| b.wet.as_mut().map(|w| &mut w.wetting))
    }

    /// A body's liquid texture, if it has wetting: `h_i` per texel in atlas
    /// order, m³/m² = m. [`soak_wet::liquid_texture`] lays it out as an
    /// image, [`soak_wet::write_liquid_png`] writes it in pseudo-colour.
    pub fn liquid_texture(&self, id: SoakId) -> Option<&[f64]> {
        self.bodies.get(id.0).and_then(SoakBody::liquid)
    }

    /// Simulated time, s (advanced by [`ForceGenerator::step`] and [`ForceGenerator::advance`]).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The registered bodies, in registration order.
    pub fn bodies(&self) -> &[SoakBody] {
        &self.bodies
    }

    /// One body.
    pub fn body(&self, id: SoakId) -> Option<&SoakBody> {
        self.bodies.get(id.0)
    }

    /// Rejected quantities so far.
    pub fn firewall(&self) -> &Firewall {
        &self.firewall
    }

    /// Registers a rigid body: computes its mass properties from the mass
    /// model and hands them to Rapier (readable at once through `mass()`).
    /// Its colliders must have density 0: soak owns the body's mass.
    pub fn register(
        &mut self,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
        handle: RigidBodyHandle,
        desc: BodyDesc,
    ) -> Result<SoakId, SoakError> {
        let body = bodies.get_mut(handle).ok_or_else(|| SoakError::MissingBody {
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
        let mass = desc
            .mass_model
            .mass_properties(&desc.atlas)
            .map_err(|source| SoakError::Hydro {
                name: desc.name.clone(),
                source,
            })?;
        push_mass(&desc.name, body, colliders, &mass)?;
        let tiled =
            (self.backend != Backend::PerTexel && desc.effects.any()).then(|| TiledAtlas::new(&desc.atlas));
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            gpu.upload(&desc.atlas)?;
        }
        self.bodies.push(SoakBody {
            name: desc.name,
            handle,
            shape: Shape::of(&desc.atlas),
            atlas: desc.atlas,
            tiled,
            mass_model: desc.mass_model,
            model_mass: mass,
            extra_mass: None,
            mass,
            effects: desc.effects,
            forces: HydroForces::default(),
            applied: Wrench::default(),
            dry_skips: 0,
            wet: None,
        });
        Ok(SoakId(self.bodies.len() - 1))
    }

    /// Changes a body's mass model (e.g. a shell density texture that
    /// changes every frame) and updates Rapier's mass properties at once.
    pub fn set_mass_model(
        &mut self,
        id: SoakId,
        model: MassModel,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let mass = model
            .mass_properties(&b.atlas)
            .map_err(|source| SoakError::Hydro {
                name: b.name.clone(),
                source,
            })?;
        let rb = bodies
            .get_mut(b.handle)
            .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?;
        push_mass(&b.name, rb, colliders, &with_extra(&mass, b.extra_mass.as_ref()))?;
        b.mass = with_extra(&mass, b.extra_mass.as_ref());
        b.model_mass = mass;
        b.mass_model = model;
        Ok(())
    }

    /// Sets the mass a body carries besides its mass model (local frame):
    /// liquid inside, a gas, a payload. It is combined with the model's
    /// about the common centre of mass and handed to Rapier at once.
    pub fn set_extra_mass(
        &mut self,
        id: SoakId,
        extra: Option<MassProperties>,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if let Some(e) = &extra
            && !e.is_finite()
        {
            return Err(SoakError::MassProperties {
                name: b.name.clone(),
                reason: format!("extra mass {e:?} is not finite"),
            });
        }
        let total = with_extra(&b.model_mass, extra.as_ref());
        let rb = bodies
            .get_mut(b.handle)
            .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?;
        push_mass(&b.name, rb, colliders, &total)?;
        b.extra_mass = extra;
        b.mass = total;
        Ok(())
    }

    /// Follows a deforming mesh: new vertex positions (local frame, m, same
    /// topology) refresh the atlas from its barycentrics (no re-bake) and the
    /// mass properties.
    pub fn deform(
        &mut self,
        id: SoakId,
        positions: &[Point3<f64>],
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let mut atlas = b.atlas.clone();
        atlas.refresh(positions).map_err(|source| SoakError::Bake {
            name: b.name.clone(),
            source,
        })?;
        let mass = b
            .mass_model
            .mass_properties(&atlas)
            .map_err(|source| SoakError::Hydro {
                name: b.name.clone(),
                source,
            })?;
        let rb = bodies
            .get_mut(b.handle)
            .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?;
        let total = with_extra(&mass, b.extra_mass.as_ref());
        push_mass(&b.name, rb, colliders, &total)?;
        if b.tiled.is_some() {
            b.tiled = Some(TiledAtlas::new(&atlas));
        }
        if let Some(w) = &mut b.wet {
            // The texels moved in object space: rebin the diffusion field.
            w.wetting.refresh_field();
        }
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            gpu.deform(id.0, positions)?;
        }
        b.shape = Shape::of(&atlas);
        b.atlas = atlas;
        b.model_mass = mass;
        b.mass = total;
        Ok(())
    }

    /// Evaluates every body's effects and applies them as forces and torques
    /// (resetting the previous step's), for the Rapier step that `params`
    /// describe. Does not advance time nor wet bodies ([`ForceGenerator::wet`]);
    /// [`ForceGenerator::step`] does all three.
    ///
    /// Rapier holds an external force constant over its `s` solver substeps,
    /// which makes any position-dependent force (a spring, buoyancy) gain
    /// energy every step. Evaluating the force at the pose predicted
    /// `β = (s − 1)/(2s)` of a step ahead makes the step area-preserving
    /// again (exactly so for a linear restoring force), so a floating body
    /// bobs for minutes without its amplitude growing or decaying.
    pub fn apply(&mut self, bodies: &mut RigidBodySet, params: &IntegrationParameters) {
        let dt = params.dt as f64;
        let substeps = params.num_solver_iterations.max(1) as f64;
        let lookahead = (substeps - 1.0) / (2.0 * substeps) * dt;
        let t = self.time;
        let step = self.steps;
        let bounds = self.water.surface.height_bounds(t);

        // 1. Which bodies need texel work, at which predicted state.
        let mut work: Vec<(usize, BodyState, HydroOptions)> = Vec::new();
        for (k, b) in self.bodies.iter_mut().enumerate() {
            if !b.effects.any() {
                continue;
            }
            let Some(rb) = bodies.get_mut(b.handle) else {
                continue;
            };
            let (v, w) = (convert::vector(rb.linvel()), convert::vector(rb.angvel()));
            let now = convert::pose(rb.position());
            // Predicted pose: the centre of mass moves with v, the body turns with ω.
            let com = now * b.mass.center_of_mass;
            let rotation = UnitQuaternion::from_scaled_axis(w * lookahead) * now.rotation;
            let translation = (com + v * lookahead).coords - rotation * b.mass.center_of_mass.coords;
            let state = BodyState {
                pose: Isometry3::from_parts(Translation3::from(translation), rotation),
                linear_velocity: v,
                angular_velocity: w,
            };
            // Above the highest crest: no texel work at all. A body stiff
            // for the step (see `implicit_heave`) is skipped only if it
            // cannot reach the water within the step, falling at g.
            let centre = state.pose * b.atlas.origin();
            let radius = b.atlas.bounding_radius();
            let reach = if implicit_weight(&self.water, &b.shape, rb.mass() as f64, dt, substeps)
                >= IMPLICIT_NEGLIGIBLE
            {
                let c = (substeps + 1.0) / (2.0 * substeps);
                (1.0 - lookahead / dt) * dt * (-v.y).max(0.0)
                    + c * dt * dt * self.water.gravity * rb.gravity_scale().abs() as f64
            } else {
                0.0
            };
            if let Some((_, highest)) = bounds
                && centre.y - radius - reach > highest
            {
                b.dry_skips += 1;
                b.forces = HydroForces {
                    center_of_buoyancy: state.pose * b.mass.center_of_mass,
                    ..HydroForces::default()
                };
                apply_wrench(rb, &Wrench::default());
                b.applied = Wrench::default();
                continue;
            }
            let options = HydroOptions {
                buoyancy: b.effects.buoyancy.unwrap_or(BuoyancyMode::Off),
                drag: b.effects.drag,
                dt,
            };
            work.push((k, state, options));
        }

        // 2. Evaluate: one GPU batch, or body by body on the CPU.
        let mut results: Vec<Result<HydroForces, String>> = Vec::with_capacity(work.len());
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &self.gpu {
            match gpu.evaluate(&self.bodies, &self.water, &work, t) {
                Ok(forces) => results.extend(forces.into_iter().map(Ok)),
                Err(e) => {
                    // Keep going on the CPU for this step; say so once per failure.
                    self.firewall.reject(
                        step,
                        "(all)",
                        "gpu evaluation",
                        format!("{e}; evaluated on the CPU"),
                    );
                }
            }
        }
        if results.is_empty() {
            for (k, state, options) in &work {
                let b = &self.bodies[*k];
                let r = match &b.tiled {
                    Some(tiled) => tiled.evaluate(&b.atlas, &self.water, state, &b.mass, t, options),
                    None => soak_hydro::evaluate(&b.atlas, &self.water, state, &b.mass, t, options),
                };
                results.push(r.map_err(|e| e.to_string()));
            }
        }

        // 3. The firewall, then Rapier.
        for ((k, state, options), result) in work.iter().zip(results) {
            let b = &mut self.bodies[*k];
            let Some(rb) = bodies.get_mut(b.handle) else {
                continue;
            };
            let forces = match result {
                Ok(f) => f,
                Err(e) => {
                    self.firewall.reject(step, &b.name, "body state", e);
                    let keep = b.applied;
                    apply_wrench(rb, &keep);
                    continue;
                }
            };
            let mut wrench = Wrench::default();
            // Buoyancy can never exceed the weight of fluid the whole body displaces.
            let limit = 1.5 * self.water.density * self.water.gravity * b.shape.volume + 1e-9;
            let bw = forces.buoyancy;
            if !bw.is_finite() {
                self.firewall
                    .reject(step, &b.name, "buoyancy", format!("non-finite {bw:?}"));
                wrench = wrench + last_part(&b.forces.buoyancy);
            } else if bw.force.norm() > limit {
                self.firewall.reject(
                    step,
                    &b.name,
                    "buoyancy",
                    format!("|F| = {:.3e} N exceeds {:.3e} N", bw.force.norm(), limit),
                );
                wrench = wrench + last_part(&b.forces.buoyancy);
            } else {
                // The drag is applied with the buoyancy: the implicit solve counts it.
                let drag = last_part(&forces.drag);
                wrench =
                    wrench + implicit_heave(b, rb, &self.water, state, options, t, substeps, limit, bw, drag);
            }
            if forces.drag.is_finite() {
                wrench = wrench + forces.drag;
            } else {
                self.firewall
                    .reject(step, &b.name, "drag", format!("non-finite {:?}", forces.drag));
            }
            apply_wrench(rb, &wrench);
            b.applied = wrench;
            b.forces = forces;
        }
    }

    /// Advances the liquid texture of every wet body by `dt` (s) at the
    /// generator's time, with the body's pose as Rapier has it now and the
    /// generator's water and environment: absorption through the submerged
    /// texels, evaporation from the others, then the body's own diffusion
    /// (see [`Wetting::step`]). Bodies without wetting are not visited
    /// beyond a check. [`ForceGenerator::step`] calls it before stepping
    /// the world; call it yourself (once per step, before
    /// [`ForceGenerator::advance`]) when driving Rapier yourself.
    ///
    /// A body whose pose is not finite is skipped and the firewall records
    /// it; invalid wetting settings are an error.
    pub fn wet(&mut self, bodies: &RigidBodySet, dt: f64) -> Result<(), SoakError> {
        let (t, step) = (self.time, self.steps);
        for b in &mut self.bodies {
            let Some(wet) = &mut b.wet else {
                continue;
            };
            let Some(rb) = bodies.get(b.handle) else {
                continue;
            };
            let pose = convert::pose(rb.position());
            let finite = pose.translation.vector.iter().all(|c| c.is_finite())
                && pose.rotation.coords.iter().all(|c| c.is_finite());
            if !finite {
                self.firewall
                    .reject(step, &b.name, "wetting pose", format!("non-finite {pose:?}"));
                continue;
            }
            wet.last = wet
                .wetting
                .step(&b.atlas, &pose, &self.water, &self.environment, t, dt)
                .map_err(|source| SoakError::Wet {
                    name: b.name.clone(),
                    source,
                })?;
        }
        Ok(())
    }

    /// Drops `splash` on every wet body, each at its pose as Rapier has it
    /// now; returns the volume that stuck (m³, summed over the bodies; the
    /// rest ran off saturated texels or landed on no body). Bodies without
    /// wetting are not touched.
    ///
    /// # Errors
    /// An invalid splash, or a wet body whose pose is not finite.
    pub fn splash(&mut self, bodies: &RigidBodySet, splash: &soak_wet::Splash) -> Result<f64, SoakError> {
        let mut stuck = 0.0;
        for b in &mut self.bodies {
            let (Some(wet), Some(rb)) = (&mut b.wet, bodies.get(b.handle)) else {
                continue;
            };
            let pose = convert::pose(rb.position());
            stuck += wet
                .wetting
                .splash(&b.atlas, &pose, splash)
                .map_err(|source| SoakError::Wet {
                    name: b.name.clone(),
                    source,
                })?;
        }
        Ok(stuck)
    }

    /// Advances the generator's clock (for moving waves) by `dt` seconds.
    pub fn advance(&mut self, dt: f64) {
        self.time += dt;
        self.steps += 1;
    }

    /// Makes the fluid's hydrostatic gravity the world's (m/s²). [`ForceGenerator::step`]
    /// does this every step; call it when driving Rapier yourself.
    pub fn sync_gravity(&mut self, world: &PhysicsWorld) {
        self.water.gravity = convert::vector(world.gravity).norm();
    }

    /// Applies the fluid forces, wets the wet bodies over the step
    /// ([`ForceGenerator::wet`]), steps the world once and advances time.
    /// The fluid's gravity follows the world's.
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<(), SoakError> {
        self.sync_gravity(world);
        let dt = world.integration_parameters.dt as f64;
        let params = world.integration_parameters;
        self.apply(&mut world.bodies, &params);
        self.wet(&world.bodies, dt)?;
        world.step();
        self.advance(dt);
        Ok(())
    }
}

fn last_part(w: &Wrench) -> Wrench {
    if w.is_finite() { *w } else { Wrench::default() }
}
