//! The driver itself ([`Driver`]): its water, weather, backend and
//! bodies, how it is set up and what it reports. Registering bodies and
//! changing their mass is in `registry.rs`, their liquid (wetting,
//! flooding, holes) in `liquid.rs`, each step's work in `step.rs`, the
//! saved state in `state.rs`.

use nalgebra::Vector3;
use serde::Serialize;
use soak_hydro::{SeaBand, SeaSampling, SeaVelocity, Water};
use soak_wet::Environment;

use crate::body::{SoakBody, shared_tiles};
use crate::config::{Backend, SoakId};
use crate::engine::{Bodies, Handle};
use crate::error::SoakError;
use crate::firewall::Firewall;
use crate::waves::{CoupledWaves, WaveCoupling};

/// Drives the effects of the rigid bodies of any physics engine
/// ([`Effects`](crate::Effects)) every step: buoyancy and drag, added
/// mass and slamming, water entering their hulls (flooding), liquid
/// soaking into their surfaces (wetting) and the waves they make.
///
/// The engine is seen through [`Bodies`] and
/// [`BodiesMut`](crate::BodiesMut): `H` is how it names a body (Rapier's
/// `RigidBodyHandle`, a Bevy `Entity`). soak-rapier and soak-bevy are the
/// adapters most users want; this type is what they drive.
///
/// Gravity stays the engine's: the driver only adds fluid forces and keeps
/// each body's mass properties in line with its mass model (plus the
/// liquid inside it). Each step, per body, it hands the engine the force
/// and torque of that step, replacing the last.
///
/// A flooding body's liquid advances each step by the step's `dt` with
/// the body's pose, and the body carries its mass ([`Driver::flood`]).
/// A wet body's liquid texture absorbs water through the submerged texels,
/// dries in the driver's [`Environment`] and diffuses over the step
/// ([`Driver::wet`]); wetting does not change the body's mass or
/// forces. A body without flooding or wetting holds no state for them and
/// costs nothing for them.
///
/// # Example
///
/// A boat of solid pine on calm water, in [`FreeBodies`](crate::FreeBodies),
/// the minimal engine soak ships for examples (soak-rapier and soak-bevy
/// drive Rapier's bodies the same way):
/// ```
/// use nalgebra::Isometry3;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, StepParams};
/// use soak_hydro::{Drag, MassModel, Water};
///
/// let mut engine = FreeBodies::new(9.81);
/// let hull = engine.insert(Isometry3::translation(0.0, 1.0, 0.0));
/// let atlas = Atlas::bake(&builtin::boat(4.0, 1.6, 0.8), BakeOptions::square(128))?;
/// let mut soak = Driver::new(Water::calm(0.0));
/// let boat = soak.register(&mut engine, hull, BodyDesc {
///     name: "boat".into(),
///     atlas: atlas.into(),
///     mass_model: MassModel::Solid { density: 400.0 },
///     effects: Effects::buoyancy().with_drag(Drag::default()),
/// })?;
/// let step = StepParams::new(1.0 / 60.0, 4);
/// for _ in 0..600 {
///     soak.before_step(&mut engine, &step)?; // the water's forces, handed to the engine
///     engine.step(&step); // the engine's own step
///     soak.after_step(step.dt);
/// }
/// let draft = soak.draft(boat, &engine).ok_or("no such body")?;
/// assert!(draft > 0.0 && draft < 1.0, "draft {draft} m");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Driver<H> {
    pub(crate) water: Water,
    pub(crate) bodies: Vec<SoakBody<H>>,
    pub(crate) backend: Backend,
    pub(crate) sea: SeaSampling,
    pub(crate) sea_velocity: SeaVelocity,
    pub(crate) sea_band: SeaBand,
    pub(crate) time: f64,
    pub(crate) steps: u64,
    pub(crate) firewall: Firewall,
    pub(crate) environment: Environment,
    pub(crate) impacts: Vec<Impact>,
    /// Interactive waves, when the scene has them (boxed: a pointer's
    /// width when off).
    pub(crate) waves: Option<Box<CoupledWaves>>,
    /// The step's lists, kept across steps ([`Driver::apply`]).
    pub(crate) scratch: crate::scratch::StepScratch<H>,
    /// How long the last [`Driver::apply`]'s phases took.
    pub(crate) phases: crate::StepPhases,
    #[cfg(feature = "gpu")]
    pub(crate) gpu: Option<crate::gpu::GpuBackend>,
}

/// A hole a hard contact opened ([`ImpactHoles`](crate::ImpactHoles)).
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

impl<H: Handle> Driver<H> {
    /// A driver for bodies in `water` (any fluid: water, a sea, air).
    pub fn new(water: Water) -> Self {
        Self {
            water,
            bodies: Vec::new(),
            backend: Backend::default(),
            sea: SeaSampling::default(),
            sea_velocity: SeaVelocity::default(),
            sea_band: SeaBand::default(),
            time: 0.0,
            steps: 0,
            firewall: Firewall::default(),
            environment: Environment::default(),
            impacts: Vec::new(),
            waves: None,
            scratch: crate::scratch::StepScratch::default(),
            phases: crate::StepPhases::default(),
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

    /// The same driver with another CPU backend.
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

    /// The same driver reading a sea (a surface that is not a plane)
    /// as `sea` says: each body as it is against the waves (the default,
    /// [`SeaSampling::Auto`]: one plane over a body at most an eighth of
    /// the shortest wave across, the sea sampled over any other), sampled
    /// once per step over each body's footprint
    /// ([`SeaSampling::PerWavelength`], nodes per shortest wavelength),
    /// read as one plane fitted over each body ([`SeaSampling::Plane`]: a
    /// calm-water evaluation's cost, for bodies small against the waves),
    /// or exactly at every texel ([`SeaSampling::Exact`], the reference). A body
    /// may read it otherwise ([`Effects::sea`](crate::Effects::sea)).
    /// Nodes per wavelength that are not finite and positive are refused
    /// when a body that would read them is registered
    /// ([`Driver::register`]'s [`SoakError::Hydro`](crate::SoakError::Hydro)).
    pub fn with_sea_sampling(mut self, sea: SeaSampling) -> Self {
        self.sea = sea;
        self
    }

    /// How a sea is read (see [`Driver::with_sea_sampling`]).
    pub fn sea_sampling(&self) -> SeaSampling {
        self.sea
    }

    /// Whether the bodies' water is read on the device alone: the GPU
    /// backend reading the sea exactly for every body (no patch sampled
    /// and no plane read on the CPU), and no interactive waves (whose
    /// bodies read the sea under them on the CPU).
    pub(crate) fn reads_on_device(&self) -> bool {
        #[cfg(feature = "gpu")]
        return self.gpu.is_some()
            && self.sea == SeaSampling::Exact
            && self.waves.is_none()
            && self
                .bodies
                .iter()
                .all(|b| b.effects.sea.is_none_or(|s| s == SeaSampling::Exact));
        #[cfg(not(feature = "gpu"))]
        false
    }

    /// The same driver reading a sampled sea's velocity for the drag as
    /// `velocity` says: once per tile of each body's atlas, to first order
    /// over the tile (the default: within 2e-4 of the per-texel read at
    /// 1024², 6e-3 at 128², 1.4 to 5 times faster) or at every texel
    /// ([`SeaVelocity::PerTexel`], the reference). See [`SeaVelocity`].
    pub fn with_sea_velocity(mut self, velocity: SeaVelocity) -> Self {
        self.sea_velocity = velocity;
        self
    }

    /// Where a sea's velocity is read for the drag (see
    /// [`Driver::with_sea_velocity`]).
    pub fn sea_velocity(&self) -> SeaVelocity {
        self.sea_velocity
    }

    /// The same driver with each body reading the waves of a sampled sea
    /// that `band` keeps: all of them (the default), or with
    /// [`SeaBand::BodyLengths`] only those long against the body (the
    /// shorter ones average out over its hull; a spectral sea then reads
    /// a coarser tile). See [`SeaBand`] for the cut-off.
    pub fn with_sea_band(mut self, band: SeaBand) -> Self {
        self.sea_band = band;
        self
    }

    /// Which of a sea's waves the bodies read (see
    /// [`Driver::with_sea_band`]).
    pub fn sea_band(&self) -> SeaBand {
        self.sea_band
    }

    /// The same driver with interactive waves on its water (see
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
    /// ([`Driver::with_waves`]): their surface, energy and the
    /// energy their sponge took.
    pub fn waves(&self) -> Option<&soak_hydro::InteractiveWaves> {
        self.waves.as_deref().map(|w| &w.solver)
    }

    /// The cells body `id` pressed on the interactive waves at the last
    /// step and the depth (m) in each: its depression, which
    /// [`Driver::waves`]' elevation holds. Empty without waves.
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

    /// Simulated time, s (advanced by [`Driver::after_step`] and [`Driver::advance`]).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// How long each phase of the last [`Driver::apply`] took, wall time
    /// (all zero before the first): where a step's time goes, the bodies'
    /// evaluations against the driver's own work around them.
    pub fn last_step_phases(&self) -> crate::StepPhases {
        self.phases
    }

    /// The registered bodies, in registration order.
    pub fn bodies(&self) -> &[SoakBody<H>] {
        &self.bodies
    }

    /// One body.
    pub fn body(&self, id: SoakId) -> Option<&SoakBody<H>> {
        self.bodies.get(id.0)
    }

    /// The draft of body `id` at its current pose in `bodies`, m: how deep
    /// its lowest texel lies below the water's surface above it (for a
    /// flat bottom, the bottom itself; otherwise within a texel of the
    /// lowest point of the mesh). Negative when the body is clear of the
    /// water: minus its height above it. `None` for an unknown id or a
    /// body the engine no longer has; `Some(f64::INFINITY)` under water with
    /// no free surface ([`soak_hydro::Unbounded`]).
    ///
    /// Reads every texel (a pass over the atlas): for a report, not for
    /// every step of a large scene.
    pub fn draft<B: Bodies<Handle = H> + ?Sized>(&self, id: SoakId, bodies: &B) -> Option<f64> {
        let b = self.bodies.get(id.0)?;
        let pose = bodies.body(b.handle)?.pose;
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
}
