//! The force generator itself ([`ForceGenerator`]): its water, weather,
//! backend and bodies, and registering bodies and changing their mass,
//! shape, wetting and flooding between steps. Each step's work is in `driver.rs`, the
//! saved state in `state.rs`.

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use rapier3d::prelude::{ColliderSet, RigidBodyHandle, RigidBodySet};
use serde::Serialize;
use soak_bake::Atlas;
use soak_graph::{Flooding, Permeability};
use soak_hydro::{
    HydroForces, MassModel, MassProperties, SeaSampling, SeaVelocity, TiledAtlas, Water, Wrench,
};
use soak_wet::{Environment, Wetting};

use super::body::{FloodSettings, Shape, SoakBody, with_extra};
use super::config::{Backend, BodyDesc, SoakId};
use super::rapier_body::{check_not_too_light, push_mass};
use super::waves::{CoupledWaves, WaveCoupling};
use crate::error::SoakError;
use crate::firewall::Firewall;

/// Drives the effects of registered rapier3d bodies ([`Effects`](super::Effects))
/// every step: buoyancy and drag, water entering their hulls (flooding) and
/// liquid soaking into their surfaces (wetting).
///
/// Gravity stays Rapier's: the generator only adds fluid forces and keeps
/// each body's mass properties in line with its mass model (plus the
/// liquid inside it). User forces in Rapier persist across steps, so every
/// step resets the body's forces and torques before adding the new ones.
///
/// A flooding body's liquid advances each step by the world's `dt` with
/// the body's pose, and the body carries its mass ([`ForceGenerator::flood`]).
/// A wet body's liquid texture absorbs water through the submerged texels,
/// dries in the generator's [`Environment`] and diffuses over the step
/// ([`ForceGenerator::wet`]); wetting does not change the body's mass or
/// forces. A body without flooding or wetting holds no state for them and
/// costs nothing for them.
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
    pub(super) water: Water,
    pub(super) bodies: Vec<SoakBody>,
    pub(super) backend: Backend,
    pub(super) sea: SeaSampling,
    pub(super) sea_velocity: SeaVelocity,
    pub(super) time: f64,
    pub(super) steps: u64,
    pub(super) firewall: Firewall,
    pub(super) environment: Environment,
    pub(super) impacts: Vec<Impact>,
    /// Interactive waves, when the scene has them (boxed: a pointer's
    /// width when off).
    pub(super) waves: Option<Box<CoupledWaves>>,
    #[cfg(feature = "gpu")]
    pub(super) gpu: Option<crate::gpu::GpuBackend>,
}

/// A hole a hard contact opened ([`ImpactHoles`](super::ImpactHoles)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Impact {
    /// The body holed.
    pub body: SoakId,
    /// Simulated time at the end of the step the blow came in, s.
    pub time: f64,
    /// The hole's centre in the body's frame, m.
    pub centre: [f64; 3],
    /// The contact pair's impulse over the step, N·s.
    pub impulse: f64,
    /// Texels opened.
    pub texels: usize,
}

impl ForceGenerator {
    /// A generator for bodies in `water` (any fluid: water, a sea, air).
    pub fn new(water: Water) -> Self {
        Self {
            water,
            bodies: Vec::new(),
            backend: Backend::default(),
            sea: SeaSampling::default(),
            sea_velocity: SeaVelocity::default(),
            time: 0.0,
            steps: 0,
            firewall: Firewall::default(),
            environment: Environment::default(),
            impacts: Vec::new(),
            waves: None,
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
        if let Some(w) = self.waves.as_deref_mut() {
            w.on_gpu(device, queue)?;
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
        for k in 0..self.bodies.len() {
            let b = &self.bodies[k];
            let tiled = (backend != Backend::PerTexel && b.effects.needs_hydrostatics())
                .then(|| shared_tiles(&self.bodies[..k], &b.atlas));
            self.bodies[k].tiled = tiled;
        }
        self
    }

    /// The same generator reading a sea (a surface that is not a plane)
    /// as `sea` says: sampled once per step over each body's footprint
    /// (the default, 16 nodes per shortest wavelength), or exactly at
    /// every texel ([`SeaSampling::Exact`], the reference).
    pub fn with_sea_sampling(mut self, sea: SeaSampling) -> Self {
        self.sea = sea;
        self
    }

    /// How a sea is read (see [`ForceGenerator::with_sea_sampling`]).
    pub fn sea_sampling(&self) -> SeaSampling {
        self.sea
    }

    /// The same generator reading a sampled sea's velocity for the drag as
    /// `velocity` says: once per tile of each body's atlas, to first order
    /// over the tile (the default: within 2e-4 of the per-texel read at
    /// 1024², 6e-3 at 128², 1.4 to 5 times faster) or at every texel
    /// ([`SeaVelocity::PerTexel`], the reference). See [`SeaVelocity`].
    pub fn with_sea_velocity(mut self, velocity: SeaVelocity) -> Self {
        self.sea_velocity = velocity;
        self
    }

    /// Where a sea's velocity is read for the drag (see
    /// [`ForceGenerator::with_sea_velocity`]).
    pub fn sea_velocity(&self) -> SeaVelocity {
        self.sea_velocity
    }

    /// The same generator with interactive waves on its water (see
    /// [`WaveCoupling`]): every body with buoyancy presses on them and
    /// floats on them from the next step. The waves take the water's
    /// density and gravity now.
    ///
    /// # Errors
    /// [`SoakError::Waves`] for a region or sponge that is refused (see
    /// [`InteractiveWaves::new`](soak_hydro::InteractiveWaves::new)).
    pub fn with_waves(mut self, rule: WaveCoupling) -> Result<Self, SoakError> {
        let solver = soak_hydro::InteractiveWaves::new(
            rule.region(),
            self.water.gravity,
            self.water.density,
            rule.sponge,
        )
        .map_err(SoakError::Waves)?;
        #[cfg_attr(not(feature = "gpu"), allow(unused_mut))]
        let mut waves = Box::new(CoupledWaves {
            solver,
            rule,
            own: Vec::new(),
            settle_pending: rule.settle,
            follow: None,
            #[cfg(feature = "gpu")]
            gpu: None,
            moved: false,
        });
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &self.gpu {
            waves.on_gpu(&gpu.device, &gpu.queue)?;
        }
        self.waves = Some(waves);
        Ok(self)
    }

    /// The interactive waves, if the generator has them
    /// ([`ForceGenerator::with_waves`]): their surface, energy and the
    /// energy their sponge took.
    pub fn waves(&self) -> Option<&soak_hydro::InteractiveWaves> {
        self.waves.as_deref().map(|w| &w.solver)
    }

    /// The cells body `id` pressed on the interactive waves at the last
    /// step and the depth (m) in each: its depression, which
    /// [`ForceGenerator::waves`]' elevation holds. Empty without waves.
    pub fn pressed(&self, id: SoakId) -> &[(usize, f64)] {
        self.waves
            .as_deref()
            .and_then(|w| w.own.get(id.0))
            .map_or(&[], |v| v.as_slice())
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
    /// with `None`, which drops the state and everything it allocated. A
    /// body registers with wetting through [`Effects::with_wetting`](super::Effects::with_wetting).
    ///
    /// # Errors
    /// An unknown id; a state made for an atlas of another size.
    pub fn set_wetting(&mut self, id: SoakId, wetting: Option<Wetting>) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if let Some(w) = &wetting {
            check_wetting(&b.name, &b.atlas, w)?;
        }
        b.effects.wetting = wetting;
        b.wet_report = soak_wet::StepReport::default();
        Ok(())
    }

    /// A body's wetting state, if it has one.
    pub fn wetting(&self, id: SoakId) -> Option<&Wetting> {
        self.bodies.get(id.0).and_then(SoakBody::wetting)
    }

    /// A body's wetting state, to splash, paint or change its settings
    /// (with the body's atlas: [`SoakBody::atlas`]).
    pub fn wetting_mut(&mut self, id: SoakId) -> Option<&mut Wetting> {
        self.bodies.get_mut(id.0).and_then(|b| b.effects.wetting.as_mut())
    }

    /// A body's liquid texture, if it has wetting: `h_i` per texel in atlas
    /// order, m³/m² = m. [`soak_wet::liquid_texture`] lays it out as an
    /// image, [`soak_wet::write_liquid_png`] writes it in pseudo-colour.
    pub fn liquid_texture(&self, id: SoakId) -> Option<&[f64]> {
        self.bodies.get(id.0).and_then(SoakBody::liquid)
    }

    /// The liquid graph inside a body, if it has flooding.
    pub fn flooding(&self, id: SoakId) -> Option<&Flooding> {
        self.bodies.get(id.0).and_then(SoakBody::flooding)
    }

    /// The liquid graph inside a body, to punch a hole
    /// ([`Flooding::permeability_mut`], or [`ForceGenerator::punch`]) or
    /// pour water ([`Flooding::pour`]); call
    /// [`ForceGenerator::sync_liquid_mass`] after pouring if the body must
    /// feel it before the next step.
    pub fn flooding_mut(&mut self, id: SoakId) -> Option<&mut Flooding> {
        self.bodies
            .get_mut(id.0)
            .and_then(|b| b.effects.flooding.as_mut())
    }

    /// Punches a hole in a flooding body's hull: the wall's permeability
    /// becomes `kappa` (m) within `radius` (m) of `centre` (the mesh's own
    /// frame, m: `[x, y, z]` or a point). Returns the texels it covers; 0 for a sealed liquid graph, which
    /// has no wall ([`Flooding::sealed`]).
    ///
    /// # Errors
    /// An unknown id, a body without flooding, an invalid region or
    /// permeability.
    pub fn punch(
        &mut self,
        id: SoakId,
        centre: impl Into<Point3<f64>>,
        radius: f64,
        kappa: f64,
    ) -> Result<usize, SoakError> {
        let centre = centre.into();
        self.change_wall(id, |p, atlas| p.paint(atlas, centre, radius, kappa))
    }

    /// Changes a flooding body's wall with `change`; 0 for a sealed liquid
    /// graph, which has none.
    fn change_wall(
        &mut self,
        id: SoakId,
        change: impl FnOnce(&mut Permeability, &Atlas) -> Result<usize, soak_graph::PermeabilityError>,
    ) -> Result<usize, SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let flooding = b
            .effects
            .flooding
            .as_mut()
            .ok_or_else(|| SoakError::NoFlooding { name: b.name.clone() })?;
        let Some(p) = flooding.permeability_mut() else {
            return Ok(0);
        };
        change(p, &b.atlas).map_err(|source| SoakError::Permeability {
            name: b.name.clone(),
            source,
        })
    }

    /// Opens a hole in a flooding body's wall: every texel within `radius`
    /// (m) of `centre` (the mesh's own frame, m) becomes an opening, through
    /// which water flows freely (the orifice law, see
    /// [`soak_graph::Permeability`]) from the next step. Returns the texels
    /// it covers (0 when the region misses the surface, or for a sealed
    /// liquid graph, which has no wall). A hole opened during a run is part
    /// of the saved state.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, an invalid region.
    pub fn open_hole(
        &mut self,
        id: SoakId,
        centre: impl Into<Point3<f64>>,
        radius: f64,
    ) -> Result<usize, SoakError> {
        let centre = centre.into();
        self.change_wall(id, |p, atlas| p.open(atlas, centre, radius))
    }

    /// [`ForceGenerator::open_hole`] at a world point (m): where a shell
    /// struck the hull, as the body stands now in `bodies`.
    ///
    /// # Errors
    /// As [`ForceGenerator::open_hole`]; a missing Rapier body.
    pub fn open_hole_at(
        &mut self,
        id: SoakId,
        bodies: &RigidBodySet,
        point: impl Into<Point3<f64>>,
        radius: f64,
    ) -> Result<usize, SoakError> {
        let b = self.bodies.get(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let rb = bodies
            .get(b.handle)
            .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?;
        let local = crate::convert::pose(rb.position()).inverse_transform_point(&point.into());
        self.open_hole(id, local, radius)
    }

    /// The holes hard contacts opened in the last step ([`ImpactHoles`](super::ImpactHoles)).
    pub fn impacts(&self) -> &[Impact] {
        &self.impacts
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
        let b = self.flooding_body(id)?;
        if let Some(m) = &ballast
            && !m.is_finite()
        {
            return Err(SoakError::MassProperties {
                name: b.name.clone(),
                reason: format!("ballast {m:?} is not finite"),
            });
        }
        b.flood.ballast = ballast;
        self.sync_liquid_mass(id, bodies, colliders)
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
        let b = self.flooding_body(id)?;
        if !(density.is_finite() && density >= 0.0) {
            return Err(SoakError::LiquidDensity {
                name: b.name.clone(),
                density,
            });
        }
        b.flood.density = Some(density);
        self.sync_liquid_mass(id, bodies, colliders)
    }

    /// The liquid inside a flooding body: its mass properties (local frame;
    /// kg, m, kg·m²) at its density ([`SoakBody::liquid_density`]).
    pub fn liquid_mass(&self, id: SoakId) -> Option<MassProperties> {
        self.bodies.get(id.0)?.liquid_mass(&self.water)
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
        let b = self.bodies.get(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let extra = b
            .flooding_extra(&self.water)
            .ok_or_else(|| SoakError::NoFlooding { name: b.name.clone() })?;
        self.set_extra_mass(id, extra, bodies, colliders)
    }

    /// A registered body with flooding.
    fn flooding_body(&mut self, id: SoakId) -> Result<&mut SoakBody, SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if b.effects.flooding.is_none() {
            return Err(SoakError::NoFlooding { name: b.name.clone() });
        }
        Ok(b)
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

    /// The draft of body `id` at its current pose in `bodies`, m: how deep
    /// its lowest texel lies below the water's surface above it (for a
    /// flat bottom, the bottom itself; otherwise within a texel of the
    /// lowest point of the mesh). Negative when the body is clear of the
    /// water: minus its height above it. `None` for an unknown id or a
    /// body no longer in `bodies`; `Some(f64::INFINITY)` under water with
    /// no free surface ([`soak_hydro::Unbounded`]).
    ///
    /// Reads every texel (a pass over the atlas): for a report, not for
    /// every step of a large scene.
    pub fn draft(&self, id: SoakId, bodies: &RigidBodySet) -> Option<f64> {
        let b = self.bodies.get(id.0)?;
        let pose = crate::convert::pose(bodies.get(b.handle)?.position());
        // Texel positions are stored from the atlas origin.
        let (origin, positions) = (b.atlas.origin(), b.atlas.local_positions());
        let lowest = (0..b.atlas.len())
            .map(|i| {
                let x = positions.get(i);
                pose * (origin + Vector3::new(f64::from(x[0]), f64::from(x[1]), f64::from(x[2])))
            })
            .min_by(|p, q| p.y.total_cmp(&q.y))?;
        Some(self.water.surface.depth(&lowest, self.time))
    }

    /// Rejected quantities so far.
    pub fn firewall(&self) -> &Firewall {
        &self.firewall
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
        if let Some(w) = &desc.effects.wetting {
            check_wetting(&desc.name, &desc.atlas, w)?;
        }
        if let Some(rule) = &desc.effects.impact_holes {
            let reason = rule.problem().or_else(|| {
                desc.effects
                    .flooding
                    .as_ref()
                    .is_none_or(|f| f.permeability().is_none())
                    .then(|| "needs flooding with a wall (a liquid graph made for the atlas)".to_string())
            });
            if let Some(reason) = reason {
                return Err(SoakError::ImpactHoles {
                    name: desc.name.clone(),
                    reason,
                });
            }
        }
        if let Some(reason) = desc.effects.slamming.and_then(|s| s.problem()) {
            return Err(SoakError::Slamming {
                name: desc.name.clone(),
                reason,
            });
        }
        if let Some(texels) = &desc.effects.drag_texels {
            texels.check(&desc.atlas).map_err(|source| SoakError::Hydro {
                name: desc.name.clone(),
                source,
            })?;
        }
        // The atlas' volume and bounds: a pass over its texels, taken once.
        let shape = Shape::of(&desc.atlas);
        check_not_too_light(&desc.name, mass.mass, &desc.effects, &self.water, shape.volume)?;
        if let Some(added) = &desc.effects.added_mass
            && !added.is_valid()
        {
            return Err(SoakError::Hydro {
                name: desc.name.clone(),
                source: soak_hydro::HydroError::AddedMass {
                    reason: format!("{added:?} is not finite with a volume > 0"),
                },
            });
        }
        push_mass(&desc.name, body, colliders, &mass)?;
        let tiled = (self.backend != Backend::PerTexel && desc.effects.needs_hydrostatics())
            .then(|| shared_tiles(&self.bodies, &desc.atlas));
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            gpu.upload(&desc.atlas)?;
        }
        self.bodies.push(SoakBody {
            name: desc.name,
            handle,
            shape,
            atlas: desc.atlas,
            tiled,
            mass_model: desc.mass_model,
            model_mass: mass,
            extra_mass: None,
            mass,
            effects: desc.effects,
            forces: HydroForces::default(),
            applied: Wrench::default(),
            added_force: Wrench::default(),
            dry_skips: 0,
            wet_report: soak_wet::StepReport::default(),
            flood: FloodSettings::default(),
            slam: None,
        });
        let id = SoakId(self.bodies.len() - 1);
        if self.bodies[id.0].effects.slamming.is_some() {
            self.bodies[id.0].slam = Some(Box::default());
        }
        if self.bodies[id.0].effects.flooding.is_some() {
            // The liquid already inside, at once.
            self.sync_liquid_mass(id, bodies, colliders)?;
        }
        Ok(id)
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
        let total = with_extra(&mass, b.extra_mass.as_ref());
        check_not_too_light(&b.name, total.mass, &b.effects, &self.water, b.shape.volume)?;
        push_mass(&b.name, rb, colliders, &total)?;
        b.mass = with_extra(&mass, b.extra_mass.as_ref());
        b.model_mass = mass;
        b.mass_model = model;
        Ok(())
    }

    /// Sets the mass a body carries besides its mass model (local frame):
    /// liquid inside, a gas, a payload. It is combined with the model's
    /// about the common centre of mass and handed to Rapier at once. A
    /// flooding body's extra mass is its liquid and ballast, set again
    /// whenever its liquid changes: give it ballast with
    /// [`ForceGenerator::set_ballast`] instead.
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
    /// topology) refresh the atlas (and the drag texels, if any) from its
    /// barycentrics (no re-bake) and the mass properties.
    pub fn deform(
        &mut self,
        id: SoakId,
        positions: &[Point3<f64>],
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let mut atlas = soak_bake::Atlas::clone(&b.atlas);
        atlas.refresh(positions).map_err(|source| SoakError::Bake {
            name: b.name.clone(),
            source,
        })?;
        // The drag texels follow the same vertices (a copy of their own:
        // other bodies may share them).
        let drag_texels = match &b.effects.drag_texels {
            Some(texels) => {
                let mut texels = soak_hydro::DragTexels::clone(texels);
                texels.refresh(positions).map_err(|source| SoakError::Bake {
                    name: b.name.clone(),
                    source,
                })?;
                Some(Arc::new(texels))
            }
            None => None,
        };
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
        let shape = Shape::of(&atlas);
        check_not_too_light(&b.name, total.mass, &b.effects, &self.water, shape.volume)?;
        push_mass(&b.name, rb, colliders, &total)?;
        if b.tiled.is_some() {
            b.tiled = Some(Arc::new(TiledAtlas::new(&atlas)));
        }
        if let Some(w) = &mut b.effects.wetting {
            // The texels moved in object space: rebin the diffusion field.
            w.refresh_field();
        }
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            gpu.deform(id.0, positions)?;
        }
        b.shape = shape;
        b.atlas = Arc::new(atlas);
        b.effects.drag_texels = drag_texels;
        b.model_mass = mass;
        b.mass = total;
        Ok(())
    }
}

/// Refuses a wetting state made for an atlas of another size.
/// The tiles of `atlas`: those of a body in `bodies` that shares it (the
/// same `Arc`), or new ones.
fn shared_tiles(bodies: &[SoakBody], atlas: &Arc<soak_bake::Atlas>) -> Arc<TiledAtlas> {
    // Bodies of one mesh are usually registered together: look back from
    // the last.
    bodies
        .iter()
        .rev()
        .find(|b| Arc::ptr_eq(&b.atlas, atlas))
        .and_then(|b| b.tiled.clone())
        .unwrap_or_else(|| Arc::new(TiledAtlas::new(atlas)))
}

fn check_wetting(name: &str, atlas: &soak_bake::Atlas, w: &Wetting) -> Result<(), SoakError> {
    if w.texels() == atlas.len() {
        return Ok(());
    }
    Err(SoakError::Wet {
        name: name.to_string(),
        source: soak_wet::WetError::AtlasMismatch {
            state: w.texels(),
            atlas: atlas.len(),
        },
    })
}
