//! The water every floating body is in ([`SoakWater`]): a Bevy resource
//! holding soak-driver's [`Driver`] with Bevy entities as handles.

use std::collections::HashMap;
use std::sync::Arc;

use bevy::asset::AssetId;
use bevy::prelude::{Entity, Mesh, Resource, Transform};
use soak_bake::Atlas;
use soak_driver::{Bodies, Driver, EngineBody, SoakBody, SoakError, SoakId, WaveCoupling};
use soak_hydro::Water;

use crate::bodies::{BodyKey, Gathered, engine_pose};

/// The fluid the floating bodies are in and the driver that drives them:
/// insert it as a resource before the first physics step (a plane, a
/// Gerstner sea, a height field, with interactive waves or not).
///
/// ```
/// use soak_bevy::SoakWater;
/// use soak_hydro::{Gerstner, GerstnerWave, Water};
///
/// let calm = SoakWater::new(Water::calm(0.0));
/// let wave = GerstnerWave { amplitude: 0.25, wavelength: 9.0, direction_deg: 0.0, steepness: 0.6, phase: 0.0 };
/// let sea = SoakWater::new(Water::new(Gerstner::new(0.0, vec![wave], 9.81)?));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Resource, Debug)]
pub struct SoakWater {
    pub(crate) driver: Driver<BodyKey>,
    /// The registered entities and their ids.
    pub(crate) entities: HashMap<Entity, SoakId>,
    /// The atlases baked from mesh assets, by asset and resolution.
    pub(crate) atlases: HashMap<(AssetId<Mesh>, u32), Arc<Atlas>>,
    /// The bodies of a step, gathered and written back in one pass each.
    pub(crate) gathered: Gathered,
    /// The mesh assets whose atlas is being baked now.
    pub(crate) baking: Vec<(AssetId<Mesh>, u32)>,
    /// bevy_rapier's time step mode was found wanting (said once).
    pub(crate) schedule_refused: bool,
    /// How long the last physics step's work took.
    pub(crate) last_step: std::time::Duration,
}

impl SoakWater {
    /// Bodies float in `water` (any fluid: water, a sea, air).
    pub fn new(water: Water) -> Self {
        Self::from_driver(Driver::new(water))
    }

    /// Bodies are driven by `driver` (set up as soak-driver's builders
    /// allow: another CPU backend, a sea read exactly, interactive waves).
    /// Bodies registered with it beforehand are not bevy entities the
    /// plugin knows of: give it none.
    pub fn from_driver(driver: Driver<BodyKey>) -> Self {
        Self {
            driver,
            entities: HashMap::new(),
            atlases: HashMap::new(),
            baking: Vec::new(),
            gathered: Gathered::default(),
            schedule_refused: false,
            last_step: std::time::Duration::ZERO,
        }
    }

    /// The same water with interactive waves on it (see
    /// [`WaveCoupling`]): the bodies press on them and float on them.
    ///
    /// # Errors
    /// [`SoakError::Waves`] for a region or sponge that is refused.
    pub fn with_waves(self, rule: WaveCoupling) -> Result<Self, SoakError> {
        Ok(Self {
            driver: self.driver.with_waves(rule)?,
            ..self
        })
    }

    /// The fluid.
    pub fn water(&self) -> &Water {
        self.driver.water()
    }

    /// The water's surface height at `(x, z)` (m) now, with the
    /// interactive waves on it if there are any, m: what a renderer draws
    /// (the bodies' own depressions included).
    pub fn height(&self, x: f64, z: f64) -> f64 {
        let t = self.driver.time();
        let base = self.driver.water().surface.height(x, z, t);
        base + self.driver.waves().map_or(0.0, |w| w.height(x, z))
    }

    /// The driver underneath: every body, its effects and their state,
    /// the firewall, the saved state.
    pub fn driver(&self) -> &Driver<BodyKey> {
        &self.driver
    }

    /// The driver, to change the water, the weather or a body's wetting
    /// and flooding between steps. Registering bodies through it directly
    /// bypasses the plugin: use [`Floating`](crate::Floating).
    pub fn driver_mut(&mut self) -> &mut Driver<BodyKey> {
        &mut self.driver
    }

    /// The wall time the plugin's last physics step took: reading the
    /// bodies, the driver's work and writing their forces and reports
    /// (bevy_rapier's own step aside).
    pub fn last_step_time(&self) -> std::time::Duration {
        self.last_step
    }

    /// The driver's time, s.
    pub fn time(&self) -> f64 {
        self.driver.time()
    }

    /// The id of the body `entity` floats as, once registered.
    pub fn id(&self, entity: Entity) -> Option<SoakId> {
        self.entities.get(&entity).copied()
    }

    /// The body `entity` floats as, once registered.
    pub fn body(&self, entity: Entity) -> Option<&SoakBody<BodyKey>> {
        self.driver.body(self.id(entity)?)
    }

    /// The draft of `entity`'s body standing at `transform` (its
    /// `Transform`), m: how deep its lowest texel lies below the water's
    /// surface above it (see [`Driver::draft`]); a pass over its texels,
    /// for a report. `None` before it is registered.
    pub fn draft(&self, entity: Entity, transform: &Transform) -> Option<f64> {
        struct One(Entity, EngineBody);
        impl Bodies for One {
            type Handle = BodyKey;
            fn body(&self, h: BodyKey) -> Option<EngineBody> {
                (h.entity == self.0).then_some(self.1)
            }
        }
        let body = EngineBody {
            pose: engine_pose(transform),
            linear_velocity: nalgebra::Vector3::zeros(),
            angular_velocity: nalgebra::Vector3::zeros(),
            mass: 0.0,
            gravity_scale: 1.0,
            fast_rotation: false,
            gyroscopic: true,
        };
        self.driver.draft(self.id(entity)?, &One(entity, body))
    }
}
