//! A body driven by the generator ([`SoakBody`]): its atlas and what the
//! per-step work needs of it ([`Shape`]), its mass, its last forces and its
//! effects (with the liquid inside it and in its surface).

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use serde::Serialize;
use soak_bake::Atlas;
use soak_graph::Flooding;
use soak_hydro::{HydroForces, MassModel, MassProperties, TiledAtlas, Water, Wrench};
use soak_wet::Wetting;

use crate::config::Effects;

/// A body the driver drives: the engine's body `handle` names (`H`: a
/// Rapier `RigidBodyHandle`, a Bevy `Entity`), its atlas, mass, effects
/// and what the last step gave it. Its centre of buoyancy at the last
/// step is [`forces()`](SoakBody::forces)`.center_of_buoyancy`; the
/// adapters add readers in their engine's vector types.
#[derive(Debug)]
pub struct SoakBody<H> {
    pub(crate) name: String,
    pub(crate) handle: H,
    pub(crate) atlas: Arc<Atlas>,
    /// The atlas' volume and the bounds the stiff-step treatment uses,
    /// computed when the atlas is set (each is a pass over the texels).
    pub(crate) shape: Shape,
    /// The atlas' tiles, shared by the bodies that share the atlas.
    pub(crate) tiled: Option<Arc<TiledAtlas>>,
    pub(crate) mass_model: MassModel,
    /// Mass from the model alone.
    pub(crate) model_mass: MassProperties,
    /// Mass carried besides the model (liquid inside, a gas, a payload), local frame.
    pub(crate) extra_mass: Option<MassProperties>,
    /// `model_mass` combined with `extra_mass`: what the engine has.
    pub(crate) mass: MassProperties,
    /// Its effects, with the flooding and wetting states: a body without
    /// them holds no liquid graph, no liquid texture and no field.
    pub(crate) effects: Effects,
    pub(crate) forces: HydroForces,
    pub(crate) applied: Wrench,
    /// The water's inertial reaction at the last step (zero without an
    /// added mass).
    pub(crate) added_force: Wrench,
    pub(crate) dry_skips: u64,
    /// What the last wetting step did (meaningful with wetting only).
    pub(crate) wet_report: soak_wet::StepReport,
    /// The flooding's settings and last report (meaningful with flooding only).
    pub(crate) flood: FloodSettings,
    /// Slamming's state, with slamming only.
    pub(crate) slam: Option<Box<SlamState>>,
    /// Radiation's memory and last force, with radiation only.
    pub(crate) radiation: Option<Box<RadiationRun>>,
    /// No longer driven ([`Driver::retire`](crate::Driver::retire)).
    pub(crate) retired: bool,
}

/// What radiation keeps between steps: the memory of the body's motion
/// and the last step's memory force.
#[derive(Clone, Debug)]
pub(crate) struct RadiationRun {
    pub(crate) state: soak_seakeeping::RadiationState,
    /// The memory force of the last step, world (N, N·m about the centre
    /// of mass), scaled by the share under water.
    pub(crate) force: Wrench,
}

/// What slamming keeps between steps: plain values, no allocation.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SlamState {
    /// The water-plane's added mass at the last evaluation, kg (`None`
    /// before the first).
    pub(crate) last_added: Option<f64>,
    /// The last step's slamming.
    pub(crate) report: SlamReport,
}

/// One step's slamming ([`Slamming`](crate::Slamming)) and the largest
/// force so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SlamReport {
    /// The slamming force of the step, world frame, N (upwards; zero
    /// while the water-plane does not grow or the body does not enter).
    pub force: Vector3<f64>,
    /// Where it acts: the water-plane's centroid at the surface, world, m.
    pub point: Point3<f64>,
    /// The water-plane's added mass, kg.
    pub added_mass: f64,
    /// Its growth over the step, kg/s.
    pub rate: f64,
    /// The downward speed of the water-plane's centroid, m/s.
    pub speed: f64,
    /// Whether the cap ([`Slamming::cap`](crate::Slamming::cap)) held the
    /// force back.
    pub capped: bool,
    /// The largest slamming force of the run so far, N, and the
    /// generator's time at the end of its step, s.
    pub peak: f64,
    /// When the peak came, s.
    pub peak_time: f64,
}

/// What a flooding body carries besides its liquid graph; plain values, no
/// allocation.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FloodSettings {
    /// Fixed mass carried with the liquid (ballast, cargo), local frame.
    pub(crate) ballast: Option<MassProperties>,
    /// Density of the liquid inside, kg/m³; the fluid's when `None`.
    pub(crate) density: Option<f64>,
    /// What the last flooding step did.
    pub(crate) last: soak_graph::StepReport,
}

impl<H: Copy> SoakBody<H> {
    /// The engine's body.
    pub fn handle(&self) -> H {
        self.handle
    }
}

impl<H> SoakBody<H> {
    /// The name given at registration.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Whether the driver no longer drives it
    /// ([`Driver::retire`](crate::Driver::retire)).
    pub fn is_retired(&self) -> bool {
        self.retired
    }
    /// Its atlas (object frame = the rigid body's local frame).
    pub fn atlas(&self) -> &Atlas {
        &self.atlas
    }
    /// Its mass model.
    pub fn mass_model(&self) -> &MassModel {
        &self.mass_model
    }
    /// Mass carried besides the mass model, if any.
    pub fn extra_mass(&self) -> Option<&MassProperties> {
        self.extra_mass.as_ref()
    }
    /// Its current mass properties, local frame, as handed to the engine.
    pub fn mass_properties(&self) -> &MassProperties {
        &self.mass
    }
    /// Its effects: buoyancy and drag, and the flooding and wetting states.
    pub fn effects(&self) -> &Effects {
        &self.effects
    }
    /// The hydrostatics of the last step (zero when skipped or dry).
    pub fn forces(&self) -> &HydroForces {
        &self.forces
    }
    /// The force and torque handed to the engine at the last step, world frame
    /// (N and N·m about the centre of mass; f64, as soak summed them).
    pub fn applied(&self) -> &Wrench {
        &self.applied
    }
    /// The reaction of the water the body sets moving at the last step,
    /// world frame (N and N·m about the centre of mass): `−M_a a` with the
    /// accelerations the step ends with, zero without an added mass
    /// ([`Effects::added_mass`](crate::Effects::added_mass)) or dry. It is
    /// already part of [`SoakBody::applied`]: the buoyancy and drag the
    /// water exerts, plus this, are what the engine was handed.
    pub fn added_mass_force(&self) -> &Wrench {
        &self.added_force
    }
    /// The last step's slamming and the peak so far, if slamming is on
    /// ([`Effects::slamming`](crate::Effects::slamming)).
    pub fn slamming(&self) -> Option<&SlamReport> {
        self.slam.as_ref().map(|s| &s.report)
    }
    /// The radiation memory's force of the last step, world frame (N and
    /// N·m about the centre of mass): `−∫ K(t − τ) ẋ(τ) dτ`, faded out as
    /// the body leaves the water (with linear theory's excitation on a
    /// Gerstner sea, and as the body enters the water the momentum the
    /// growing share of A∞ takes, `−w ΔA v / dt` with `w` the cube of
    /// the water's part of the inertia, whole for a light body); the A∞
    /// part is in
    /// [`SoakBody::added_mass_force`]. Both are already part of
    /// [`SoakBody::applied`]. `None` without radiation
    /// ([`Effects::radiation`](crate::Effects::radiation)).
    pub fn radiation_force(&self) -> Option<&Wrench> {
        self.radiation.as_ref().map(|r| &r.force)
    }
    /// Its volume under water at the last step, m³ (0 when dry or skipped
    /// above the crests).
    pub fn submerged_volume(&self) -> f64 {
        self.forces.submerged_volume
    }
    /// The fraction of its enclosed volume under water at the last step,
    /// from 0 (dry) to 1 (wholly submerged).
    pub fn submerged_fraction(&self) -> f64 {
        if self.shape.volume > 0.0 {
            (self.forces.submerged_volume / self.shape.volume).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
    /// Its enclosed volume, m³.
    pub fn volume(&self) -> f64 {
        self.shape.volume
    }
    /// Steps at which the body was above the highest crest and skipped.
    pub fn dry_skips(&self) -> u64 {
        self.dry_skips
    }
    /// Its wetting state, if wetting is on ([`Effects::wetting`]; see also
    /// [`Driver::set_wetting`](crate::Driver::set_wetting)).
    pub fn wetting(&self) -> Option<&Wetting> {
        self.effects.wetting.as_deref()
    }
    /// Its liquid texture, if wetting is on: `h_i` per texel in atlas
    /// order, volume per area, m³/m² = m, in `[0, saturation]`.
    pub fn liquid(&self) -> Option<&[f64]> {
        self.effects.wetting.as_deref().map(Wetting::liquid)
    }
    /// What the last wetting step did (absorbed, evaporated, m³;
    /// submerged texels; diffusion substeps), if wetting is on.
    pub fn wet_report(&self) -> Option<&soak_wet::StepReport> {
        self.effects.wetting.as_deref().map(|_| &self.wet_report)
    }
    /// The liquid graph inside it, if flooding is on ([`Effects::flooding`]).
    pub fn flooding(&self) -> Option<&Flooding> {
        self.effects.flooding.as_deref()
    }
    /// What the last flooding step did (volumes entered and left, m³), if
    /// flooding is on.
    pub fn flood_report(&self) -> Option<&soak_graph::StepReport> {
        self.effects.flooding.as_deref().map(|_| &self.flood.last)
    }
    /// The fixed mass carried with the liquid inside (ballast, cargo; local
    /// frame), if flooding is on and it has any.
    pub fn ballast(&self) -> Option<&MassProperties> {
        self.effects.flooding.as_deref().and(self.flood.ballast.as_ref())
    }
    /// Density of the liquid inside in `water`, kg/m³: the one set
    /// ([`Driver::set_liquid_density`](crate::Driver::set_liquid_density)),
    /// else `water`'s. `None` without flooding.
    pub fn liquid_density(&self, water: &Water) -> Option<f64> {
        self.effects
            .flooding
            .as_ref()
            .map(|_| self.flood.density.unwrap_or(water.density))
    }
    /// The liquid inside's mass properties (local frame; kg, m, kg·m²) in
    /// `water` ([`SoakBody::liquid_density`]), if flooding is on.
    pub fn liquid_mass(&self, water: &Water) -> Option<MassProperties> {
        let density = self.liquid_density(water)?;
        self.effects
            .flooding
            .as_deref()
            .map(|f| f.mass_properties(density))
    }
    /// Drops its effects and what they hold, and marks it retired
    /// ([`Driver::retire`](crate::Driver::retire)).
    pub(crate) fn retire(&mut self) {
        self.effects = Effects::default();
        self.tiled = None;
        self.slam = None;
        self.radiation = None;
        self.retired = true;
    }

    /// What the body carries besides its mass model when flooding is on:
    /// ballast combined with the liquid inside (if it has any), or `None`.
    pub(crate) fn flooding_extra(&self, water: &Water) -> Option<Option<MassProperties>> {
        let liquid = self.liquid_mass(water)?;
        Some(match (self.flood.ballast, liquid.mass > 0.0) {
            (Some(b), true) => Some(b.combine(&liquid)),
            (Some(b), false) => Some(b),
            (None, true) => Some(liquid),
            (None, false) => None,
        })
    }
}

/// What the per-step work needs of a body's atlas, computed once per atlas.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shape {
    /// Enclosed volume, m³ (absolute value).
    pub(crate) volume: f64,
    /// An upper bound on the water-plane area in any pose, m²: the smaller
    /// of `π r²` (`r` the bounding radius) and half the surface area (a
    /// closed surface's projection on any plane, counted once from above
    /// and once from below, is at most its area). The second is the tight
    /// one for long thin bodies: a 200:1 rod's is 1/80 of its `π r²`.
    pub(crate) water_plane: f64,
    /// Thickness `3V/A`, m: the radius of a sphere, about the width of a rod.
    pub(crate) thickness: f64,
}

impl Shape {
    pub(crate) fn of(atlas: &Atlas) -> Self {
        let r = atlas.bounding_radius();
        let area = atlas.area();
        let volume = atlas.volume().abs();
        Self {
            volume,
            water_plane: (std::f64::consts::PI * r * r).min(0.5 * area),
            thickness: 3.0 * volume / area.max(f64::MIN_POSITIVE),
        }
    }
}

pub(crate) fn with_extra(model: &MassProperties, extra: Option<&MassProperties>) -> MassProperties {
    match extra {
        Some(e) => model.combine(e),
        None => *model,
    }
}

/// The latest body in `bodies` that shares `atlas` (the same `Arc`): what
/// was worked out from the atlas for it (its shape, its tiles, its mass
/// properties under a mass model) holds for the atlas' next body too.
pub(crate) fn atlas_twin<'a, H>(
    bodies: &'a [SoakBody<H>],
    atlas: &Arc<soak_bake::Atlas>,
) -> Option<&'a SoakBody<H>> {
    // Bodies of one mesh are usually registered together: look back from
    // the last.
    bodies.iter().rev().find(|b| Arc::ptr_eq(&b.atlas, atlas))
}

/// The tiles of `atlas`: those of a body in `bodies` that shares it (the
/// same `Arc`), or new ones.
pub(crate) fn shared_tiles<H>(bodies: &[SoakBody<H>], atlas: &Arc<soak_bake::Atlas>) -> Arc<TiledAtlas> {
    atlas_twin(bodies, atlas)
        .and_then(|b| b.tiled.clone())
        .unwrap_or_else(|| Arc::new(TiledAtlas::new(atlas)))
}
