//! A body driven by the generator ([`SoakBody`]): its atlas and what the
//! per-step work needs of it ([`Shape`]), its mass, its last forces and its
//! wetting.

use rapier3d::prelude::RigidBodyHandle;
use soak_bake::Atlas;
use soak_hydro::{HydroForces, MassModel, MassProperties, TiledAtlas, Wrench};
use soak_wet::{StepReport, Wetting};

use super::config::Effects;

/// A body driven by the generator.
#[derive(Debug)]
pub struct SoakBody {
    pub(super) name: String,
    pub(super) handle: RigidBodyHandle,
    pub(super) atlas: Atlas,
    /// The atlas' volume and the bounds the stiff-step treatment uses,
    /// computed when the atlas is set (each is a pass over the texels).
    pub(super) shape: Shape,
    pub(super) tiled: Option<TiledAtlas>,
    pub(super) mass_model: MassModel,
    /// Mass from the model alone.
    pub(super) model_mass: MassProperties,
    /// Mass carried besides the model (liquid inside, a gas, a payload), local frame.
    pub(super) extra_mass: Option<MassProperties>,
    /// `model_mass` combined with `extra_mass`: what Rapier has.
    pub(super) mass: MassProperties,
    pub(super) effects: Effects,
    pub(super) forces: HydroForces,
    pub(super) applied: Wrench,
    pub(super) dry_skips: u64,
    /// `None` unless wetting was asked for: a dry body holds no liquid
    /// texture, no field and no report.
    pub(super) wet: Option<Wet>,
}

/// A body's wetting and what its last step did.
#[derive(Clone, Debug)]
pub(super) struct Wet {
    pub(super) wetting: Wetting,
    pub(super) last: StepReport,
}

impl SoakBody {
    /// The name given at registration.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The Rapier body.
    pub fn handle(&self) -> RigidBodyHandle {
        self.handle
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
    /// Its current mass properties, local frame, as handed to Rapier.
    pub fn mass_properties(&self) -> &MassProperties {
        &self.mass
    }
    /// Its effects.
    pub fn effects(&self) -> &Effects {
        &self.effects
    }
    /// The hydrostatics of the last step (zero when skipped or dry).
    pub fn forces(&self) -> &HydroForces {
        &self.forces
    }
    /// The force and torque handed to Rapier at the last step, world frame.
    pub fn applied(&self) -> &Wrench {
        &self.applied
    }
    /// Steps at which the body was above the highest crest and skipped.
    pub fn dry_skips(&self) -> u64 {
        self.dry_skips
    }
    /// Its wetting state, if wetting is on (see
    /// [`ForceGenerator::set_wetting`](super::ForceGenerator::set_wetting)).
    pub fn wetting(&self) -> Option<&Wetting> {
        self.wet.as_ref().map(|w| &w.wetting)
    }
    /// Its liquid texture, if wetting is on: `h_i` per texel in atlas
    /// order, volume per area, m³/m² = m, in `[0, saturation]`.
    pub fn liquid(&self) -> Option<&[f64]> {
        self.wet.as_ref().map(|w| w.wetting.liquid())
    }
    /// What the last wetting step did (absorbed, evaporated, m³;
    /// submerged texels; diffusion substeps), if wetting is on.
    pub fn wet_report(&self) -> Option<&StepReport> {
        self.wet.as_ref().map(|w| &w.last)
    }
}

/// What the per-step work needs of a body's atlas, computed once per atlas.
#[derive(Clone, Copy, Debug)]
pub(super) struct Shape {
    /// Enclosed volume, m³ (absolute value).
    pub(super) volume: f64,
    /// An upper bound on the water-plane area in any pose, m²: the smaller
    /// of `π r²` (`r` the bounding radius) and half the surface area (a
    /// closed surface's projection on any plane, counted once from above
    /// and once from below, is at most its area). The second is the tight
    /// one for long thin bodies: a 200:1 rod's is 1/80 of its `π r²`.
    pub(super) water_plane: f64,
    /// Thickness `3V/A`, m: the radius of a sphere, about the width of a rod.
    pub(super) thickness: f64,
}

impl Shape {
    pub(super) fn of(atlas: &Atlas) -> Self {
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

pub(super) fn with_extra(model: &MassProperties, extra: Option<&MassProperties>) -> MassProperties {
    match extra {
        Some(e) => model.combine(e),
        None => *model,
    }
}
