//! Typed errors of the driver ([`SoakError`]).

use std::path::PathBuf;

/// Registering or driving a body failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SoakError {
    /// The engine has no rigid body for the handle (never had, or it was
    /// removed).
    #[error("body `{name}`: the engine has no rigid body for its handle")]
    MissingBody {
        /// The soak body's name.
        name: String,
    },
    /// A collider attached to the body has mass (soak owns the body's
    /// mass: the engine must add none of its own).
    #[error(
        "body `{name}`: collider {collider} has density {density} kg/m³; soak sets the body's mass properties, \
         so give its colliders density 0"
    )]
    ColliderHasMass {
        /// The soak body's name.
        name: String,
        /// The collider, as the engine numbers it (Rapier's collider index,
        /// a Bevy entity's index).
        collider: u32,
        /// Its density.
        density: f32,
    },
    /// The body's mass properties are invalid (zero mass, non-finite values).
    #[error("body `{name}`: {reason}")]
    MassProperties {
        /// The soak body's name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// The soak id is not registered.
    #[error("no soak body with id {0}")]
    UnknownId(usize),
    /// Mass or hydrostatics failed.
    #[error("body `{name}`: {source}")]
    Hydro {
        /// The soak body's name.
        name: String,
        /// The underlying error.
        source: soak_hydro::HydroError,
    },
    /// A saved state could not be written or read as JSON (damaged or
    /// truncated input, a value JSON cannot hold).
    #[error("saved state: {0}")]
    Json(#[from] serde_json::Error),
    /// The physics engine's own state could not be saved or restored (the
    /// adapter's part of a saved run: Rapier's world, say).
    #[error("saved state: the physics world: {reason}")]
    World {
        /// What went wrong.
        reason: String,
    },
    /// A file or directory could not be created or written.
    #[error("cannot write `{path}`: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A saved state holds another number of bodies than the generator.
    #[error("saved state: it has {saved} bodies, the generator {registered}")]
    StateBodies {
        /// Bodies in the saved state.
        saved: usize,
        /// Bodies registered with the generator.
        registered: usize,
    },
    /// A saved liquid texture does not cover the body's atlas.
    #[error("saved state: body `{name}`: the saved liquid texture has {saved} texels, the atlas {atlas}")]
    StateTexels {
        /// The soak body's name.
        name: String,
        /// Texels of the saved liquid texture.
        saved: usize,
        /// Texels of the body's atlas.
        atlas: usize,
    },
    /// A saved state has flooding for a body without it, or none for a
    /// body with it.
    #[error("saved state: body `{name}`: {}", flooding_mismatch(*.saved))]
    StateFlooding {
        /// The soak body's name.
        name: String,
        /// Whether the saved state has flooding (the body then has none).
        saved: bool,
    },
    /// The liquid inside a body could not advance or be restored (bad
    /// pose, depth, a channel that does not fit the body's atlas, a saved
    /// state of another graph).
    #[error("body `{name}`: liquid: {source}")]
    Flow {
        /// The soak body's name.
        name: String,
        /// The underlying error.
        source: soak_graph::FlowError,
    },
    /// A hull's permeability could not be changed (a hole punched with
    /// invalid values).
    #[error("body `{name}`: permeability: {source}")]
    Permeability {
        /// The soak body's name.
        name: String,
        /// The underlying error.
        source: soak_graph::PermeabilityError,
    },
    /// A liquid density that is not a finite number ≥ 0.
    #[error("body `{name}`: liquid density {density} kg/m³ is not a finite number ≥ 0")]
    LiquidDensity {
        /// The soak body's name.
        name: String,
        /// The density given, kg/m³.
        density: f64,
    },
    /// An impact rule that cannot hold: no flooding to take the holes, or
    /// a threshold or radius out of range.
    #[error("body `{name}`: impact holes: {reason}")]
    ImpactHoles {
        /// The soak body's name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// A body so light against the fluid it displaces (under a millionth
    /// of its mass) that its buoyancy alone would accelerate it at over a
    /// million `g`: without the water
    /// it must push aside ([`Effects::added_mass`](crate::Effects::added_mass))
    /// the step cannot follow it. Give it an added mass, or more mass.
    #[error(
        "body `{name}`: {mass:.3e} kg displacing {displaced:.3e} kg of fluid is lighter than a millionth of it: \
         its buoyancy alone would accelerate it at over a million g; give it an added mass (Effects::with_added_mass, \
         `added_mass = true` in a scene) or more mass"
    )]
    TooLight {
        /// The soak body's name.
        name: String,
        /// Its mass, kg.
        mass: f64,
        /// The mass of the fluid its enclosed volume displaces, kg.
        displaced: f64,
    },
    /// Slamming settings out of range.
    #[error("body `{name}`: slamming: {reason}")]
    Slamming {
        /// The soak body's name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// Radiation that does not fit the body or the water (a model baked
    /// for another density or gravity, or another mass), or a saved
    /// radiation memory of another model.
    #[error("body `{name}`: radiation: {reason}")]
    Radiation {
        /// The soak body's name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// The interactive waves were refused (their region or sponge) or
    /// failed to advance (a time step that is not finite and > 0).
    #[error("waves: {0}")]
    Waves(#[source] soak_hydro::WaterError),
    /// A saved state has interactive waves and the generator none, or the
    /// other way round, or its waves do not fit the generator's region.
    #[error("saved state: {reason}")]
    StateWaves {
        /// What does not match.
        reason: String,
    },
    /// A flooding setting was given for a body without flooding.
    #[error("body `{name}` has no flooding")]
    NoFlooding {
        /// The soak body's name.
        name: String,
    },
    /// The GPU backend failed (device, upload or evaluation).
    #[cfg(feature = "gpu")]
    #[error("gpu: {0}")]
    Gpu(#[from] soak_hydro::gpu::GpuHydroError),
    /// A body's wetting (or the environment) was refused or failed to advance.
    #[error("body `{name}`: wetting: {source}")]
    Wet {
        /// The soak body's name (`(environment)` for the environment).
        name: String,
        /// The underlying error.
        source: soak_wet::WetError,
    },
    /// Baking or refreshing the atlas failed.
    #[error("body `{name}`: {source}")]
    Bake {
        /// The soak body's name.
        name: String,
        /// The underlying error.
        source: soak_bake::BakeError,
    },
}

fn flooding_mismatch(saved: bool) -> &'static str {
    if saved {
        "the state has flooding, the body none"
    } else {
        "the body has flooding, the state none"
    }
}
