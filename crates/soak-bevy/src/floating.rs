//! The components a user puts on a bevy_rapier body ([`Floating`]) and
//! reads back from it ([`FloatReport`]).

use std::sync::Arc;

use bevy::prelude::{Component, Handle, Mesh, Vec3};
use soak_bake::Atlas;
use soak_driver::Effects;
use soak_hydro::MassModel;

/// The shape a body floats with: where its texel atlas comes from.
#[derive(Clone, Debug)]
pub enum FloatingMesh {
    /// A soak mesh (a `soak_bake::builtin` shape, a file loaded with
    /// `soak_bake::load_mesh`), in the body's own frame, m. Baked off the
    /// main thread; its own UVs are used if they make a valid atlas,
    /// otherwise it is unwrapped.
    Mesh(Arc<soak_bake::Mesh>),
    /// A Bevy mesh asset (its positions, triangles and first UV channel),
    /// in the body's own frame, m: the mesh the entity is drawn with,
    /// say. Read once it is loaded, then baked as [`FloatingMesh::Mesh`]
    /// is. Bodies of one asset and resolution share one atlas.
    Asset(Handle<Mesh>),
    /// An atlas baked already (shared by every body given a clone).
    Atlas(Arc<Atlas>),
}

/// Makes a bevy_rapier rigid body float: the body's shape, mass model and
/// effects. Put it on an entity with `RigidBody::Dynamic` (and a
/// `Collider` for contacts); the plugin bakes the atlas on another thread
/// and, once it is ready, registers the body: it gives it the mass of its
/// model (as `AdditionalMassProperties`; colliders must add none: the
/// plugin sets `ColliderMassProperties::Density(0.0)` on colliders that
/// have no mass properties of their own), then hands it the water's
/// force and torque every physics step (as `ExternalForce`).
///
/// What goes wrong (no rigid body, a bad mesh, a collider with mass) is a
/// [`FloatingError`](crate::FloatingError) message; the entity then stays
/// as it is.
///
/// soak owns a floating body's `ExternalForce` (it writes it every step):
/// push the body yourself with `ExternalImpulse`. Removing `Floating` (or
/// despawning the entity) stops the water's forces and drops the body's
/// state in [`SoakWater`](crate::SoakWater).
#[derive(Component, Clone)]
pub struct Floating {
    /// A name for reports and messages.
    pub name: String,
    /// Its shape.
    pub mesh: FloatingMesh,
    /// The atlas' side in texels when it is baked here (ignored for
    /// [`FloatingMesh::Atlas`]). Default 128.
    pub resolution: u32,
    /// How its mass is distributed (kg/m³ for a solid).
    pub mass_model: MassModel,
    /// The effects it starts with (buoyancy, drag, added mass, slamming,
    /// flooding, wetting, its own read of a sea:
    /// [`Effects::with_sea_sampling`]). At registration they move into
    /// [`SoakWater`](crate::SoakWater), which keeps their state from then
    /// on (its liquid texture, the liquid inside).
    pub effects: Effects,
    /// The effects that must be made for the atlas (wetting, flooding),
    /// made once it is baked, from it and [`Floating::effects`]: see
    /// [`Floating::with_atlas_effects`].
    pub atlas_effects: Option<AtlasEffects>,
}

/// Makes a body's effects for its atlas once it is baked (a liquid texture
/// or a liquid graph is made for one atlas): from the atlas and the effects
/// given, the effects to register with, or why not.
pub type AtlasEffects = Arc<dyn Fn(&Atlas, Effects) -> Result<Effects, String> + Send + Sync>;

impl std::fmt::Debug for Floating {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Floating")
            .field("name", &self.name)
            .field("mesh", &self.mesh)
            .field("resolution", &self.resolution)
            .field("mass_model", &self.mass_model)
            .field("effects", &self.effects)
            .field("atlas_effects", &self.atlas_effects.is_some())
            .finish()
    }
}

impl Floating {
    /// A body of `mesh`, of solid wood (500 kg/m³), with buoyancy and the
    /// default drag, baked at 128².
    pub fn new(name: impl Into<String>, mesh: FloatingMesh) -> Self {
        Self {
            name: name.into(),
            mesh,
            resolution: 128,
            mass_model: MassModel::Solid { density: 500.0 },
            effects: Effects::buoyancy().with_drag(soak_hydro::Drag::default()),
            atlas_effects: None,
        }
    }

    /// The same body with another mass model.
    pub fn with_mass_model(mut self, mass_model: MassModel) -> Self {
        self.mass_model = mass_model;
        self
    }

    /// The same body with other effects.
    pub fn with_effects(mut self, effects: Effects) -> Self {
        self.effects = effects;
        self
    }

    /// The same body with effects made for its atlas once it is baked
    /// (`make(atlas, effects)` returns the effects to register with).
    ///
    /// ```
    /// use soak_bevy::{Floating, FloatingMesh};
    /// use soak_wet::{Liquid, Material, Wetting};
    ///
    /// let mesh = soak_bake::builtin::cuboid(0.8, 0.8, 0.8);
    /// let wet = Floating::new("crate", FloatingMesh::Mesh(mesh.into())).with_atlas_effects(|atlas, effects| {
    ///     let wetting = Wetting::new(atlas, Material::wood(), Liquid::water()).map_err(|e| e.to_string())?;
    ///     Ok(effects.with_wetting(wetting))
    /// });
    /// ```
    pub fn with_atlas_effects(
        mut self,
        make: impl Fn(&Atlas, Effects) -> Result<Effects, String> + Send + Sync + 'static,
    ) -> Self {
        self.atlas_effects = Some(Arc::new(make));
        self
    }

    /// The same body baked at `resolution`² texels.
    pub fn with_resolution(mut self, resolution: u32) -> Self {
        self.resolution = resolution;
        self
    }
}

/// What the water did to a floating body at the last physics step, world
/// frame, SI units; updated every step once the body is registered.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct FloatReport {
    /// The driver's time at the end of the step, s.
    pub time: f64,
    /// Its volume under water, m³.
    pub submerged_volume: f64,
    /// The fraction of its enclosed volume under water, 0 (dry) to 1.
    pub submerged_fraction: f64,
    /// Its centre of buoyancy, m (its centre of mass when dry).
    pub center_of_buoyancy: Vec3,
    /// The buoyancy force, N.
    pub buoyancy: Vec3,
    /// The drag force, N.
    pub drag: Vec3,
    /// The force handed to bevy_rapier (`ExternalForce::force`), N.
    pub force: Vec3,
    /// The torque about the centre of mass handed to bevy_rapier, N·m.
    pub torque: Vec3,
    /// Its mass, kg (with the liquid inside a flooding body).
    pub mass: f64,
    /// The liquid inside a flooding body, m³ (0 without flooding).
    pub liquid_inside: f64,
    /// The liquid soaked into its surface, m³ (0 without wetting).
    pub surface_liquid: f64,
    /// How wet its surface is on average, from 0 (dry) to 1 (saturated
    /// everywhere; 0 without wetting).
    pub wetness: f64,
}

/// The link between an entity and its body in the driver, put on the
/// entity at registration.
#[derive(Component, Clone, Copy, Debug)]
pub struct SoakLink {
    /// Its id in [`SoakWater`](crate::SoakWater)'s driver.
    pub id: soak_driver::SoakId,
    /// Its mass as bevy_rapier holds it (f32, through Rapier's mass
    /// properties), kg.
    pub(crate) engine_mass: f64,
}
