//! Scenes as data: a TOML file describing the fluid, the bodies and the run.
//!
//! ```toml
//! dt = 0.0166667          # time step, s
//! duration = 30.0         # s
//! gravity = [0.0, -9.81, 0.0]
//!
//! [water]
//! kind = "gerstner"       # plane | gerstner | spectrum | height_field | air
//! level = 0.0             # m
//! density = 1000.0        # kg/m³
//! waves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]
//! sampling = { per_wavelength = 16 }  # the default; or "exact" (every texel inverts the sea), or "plane" (each body reads one plane fitted over it)
//! velocity = "per_tile"              # drag reads the sea's velocity once per tile (default); or "per_texel"
//! # Or a spectral sea (`kind = "spectrum"`, see `WaterSpec::spectral_sea`):
//! #   spectrum = "jonswap"  # or "pierson_moskowitz"
//! #   significant_height = 2.0   # m (required)
//! #   peak_period = 8.0          # s (required)
//! #   gamma = 3.3                # JONSWAP's peak enhancement
//! #   direction_deg = 0.0        # mean direction of travel
//! #   spreading = 10.0           # the cos-2s exponent s
//! #   seed = 0                   # the same seed, the same sea
//! #   tile = 800.0               # m, default eight peak wavelengths
//! #   cells = 128                # a power of two
//! #   choppiness = 1.0           # horizontal displacement, 0 to 1
//! #   band = 0.5                 # each body reads the waves ≥ 0.5 of its bounding diameter long and
//! #                              # the shorter ones dropped as a band (`SeaBand`); default: every wave
//!
//! [[bodies]]
//! name = "buoy"
//! mesh = "builtin:sphere:0.5"   # or a path to .obj / .gltf / .glb, relative to the scene
//! resolution = 256           # texels a side, or "auto" with `tolerance = 1e-3` (of its volume)
//! mass = { model = "solid", density = 500.0 }   # or { model = "shell", areal_density = 20.0 }
//! position = [0.0, 0.5, 0.0]
//! rotation_deg = [0.0, 0.0, 0.0]
//! drag = { coefficient = 0.5, linear = 5.0 }
//! drag_resolution = 64       # optional: the drag over a 64² bake of the mesh (the buoyancy stays 256²)
//! # drag_coarsening = 4      # or: the drag over the atlas' 4 × 4 texel blocks merged (64² here)
//! # sampling = "plane"       # on a sea: this body reads it as one plane, whatever `[water] sampling` says
//! # Surface wetting, opt-in per body (see `WettingSpec`):
//! wetting = { material = "wood", diffusion = 2e-5, mode = "conservative", initial = 0.0 }
//!
//! [environment]           # the weather wet bodies dry in (all keys optional)
//! temperature_c = 20.0    # air temperature, °C
//! relative_humidity = 0.5 # a fraction in [0, 1]
//! wind_speed = 2.0        # m/s
//! rain_mm_per_hour = 0.0  # rain everywhere, mm/h
//! # The weather may change: keys at times (s), linear in between, held after
//! # the last; a key's absent values are the previous key's (or the ones above).
//! keys = [{ at = 60.0, temperature_c = 30.0, relative_humidity = 0.2 }]
//!
//! [[splash]]              # liquid landing on the wet bodies near a point, once
//! at = 2.0                # s
//! center = [0.0, 1.0, 0.0]  # world position, m
//! radius = 0.3            # m
//! volume = 5e-4           # m³ shared by the texels within the radius
//!
//! [output]
//! every = 1               # record every N steps
//! liquid_png_every = 60   # `soak simulate`: liquid textures as PNG every N steps
//! ```
//!
//! Unknown keys, wrong types and out-of-range values are errors that name
//! the key and its line.
//!
//! One concept per file: [`Scene`] and [`OutputSpec`] here, the fluid in
//! `water`, the bodies in `bodies`, their wetting and the weather in
//! `wetting`, their liquid graph in `liquid_graph`, a scene read from a file
//! and checked in `loaded`, and locating a key's line in `key_path`.

mod bodies;
mod key_path;
mod liquid_graph;
mod loaded;
mod water;
mod wetting;

use serde::{Deserialize, Serialize};

use crate::Backend;

pub use self::bodies::{Auto, BodySpec, ColliderSpec, DEFAULT_TOLERANCE, MassSpec, ResolutionSpec};
pub use self::key_path::line_of;
pub use self::liquid_graph::{AutoGraphSpec, CavitySpec, GraphSpec, HoleSpec};
pub use self::loaded::LoadedScene;
pub use self::water::{SpectrumName, WaterKind, WaterSpec};
pub use self::wetting::{
    EnvironmentKeySpec, EnvironmentSpec, InitialLiquid, LiquidParams, LiquidSpec, MaterialParams,
    MaterialSpec, SplashSpec, WettingSpec,
};

fn default_dt() -> f64 {
    1.0 / 60.0
}
fn default_duration() -> f64 {
    10.0
}
/// `duration`: a number of seconds or `"forever"`.
fn duration_or_forever<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Duration {
        Seconds(f64),
        Word(String),
    }
    match Duration::deserialize(d)? {
        Duration::Seconds(s) => Ok(s),
        Duration::Word(w) if w == "forever" => Ok(f64::INFINITY),
        Duration::Word(w) => Err(serde::de::Error::custom(format!(
            "duration must be a number of seconds or \"forever\", not \"{w}\""
        ))),
    }
}

/// `duration` as [`duration_or_forever`] reads it.
fn write_duration<S: serde::Serializer>(d: &f64, s: S) -> Result<S::Ok, S::Error> {
    if d.is_infinite() && *d > 0.0 {
        s.serialize_str("forever")
    } else {
        s.serialize_f64(*d)
    }
}

fn default_gravity() -> [f64; 3] {
    [0.0, -9.81, 0.0]
}
fn default_every() -> usize {
    1
}

/// A whole scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Time step, s.
    #[serde(default = "default_dt")]
    pub dt: f64,
    /// Simulated duration, s: a positive number, or `"forever"` (read as
    /// infinity) for a run that goes on until it is stopped (the viewer,
    /// interactive use, `soak simulate` with checkpoints).
    #[serde(
        default = "default_duration",
        deserialize_with = "duration_or_forever",
        serialize_with = "write_duration"
    )]
    pub duration: f64,
    /// Gravity, m/s².
    #[serde(default = "default_gravity")]
    pub gravity: [f64; 3],
    /// CPU evaluation path.
    #[serde(default)]
    pub backend: Backend,
    /// The fluid.
    pub water: WaterSpec,
    /// The bodies.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// The weather wet bodies dry in; [`Environment::default`](soak_wet::Environment::default) when absent.
    pub environment: Option<EnvironmentSpec>,
    /// Splashes landing on the wet bodies during the run.
    #[serde(default)]
    pub splash: Vec<SplashSpec>,
    /// What to record.
    #[serde(default)]
    pub output: OutputSpec,
    /// Interactive waves the bodies make and float on (`[waves]`, keys of
    /// [`WaveCoupling`](crate::WaveCoupling); absent: none).
    #[serde(default)]
    pub waves: Option<crate::WaveCoupling>,
}

/// What a run records.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Record every N steps.
    #[serde(default = "default_every")]
    pub every: usize,
    /// `soak simulate` writes each wet body's liquid texture as a
    /// pseudo-colour PNG every N steps (dark blue dry, dark red saturated);
    /// none when absent. `--liquid-png-every` overrides it.
    pub liquid_png_every: Option<usize>,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            every: 1,
            liquid_png_every: None,
        }
    }
}
