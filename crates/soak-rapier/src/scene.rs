//! Scenes as data: a TOML file describing the fluid, the bodies and the run.
//!
//! ```toml
//! dt = 0.0166667          # time step, s
//! duration = 30.0         # s
//! gravity = [0.0, -9.81, 0.0]
//!
//! [water]
//! kind = "gerstner"       # plane | gerstner | height_field | air
//! level = 0.0             # m
//! density = 1000.0        # kg/m³
//! waves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]
//!
//! [[bodies]]
//! name = "buoy"
//! mesh = "builtin:sphere:0.5"   # or a path to .obj / .gltf / .glb, relative to the scene
//! resolution = 256
//! mass = { model = "solid", density = 500.0 }   # or { model = "shell", areal_density = 20.0 }
//! position = [0.0, 0.5, 0.0]
//! rotation_deg = [0.0, 0.0, 0.0]
//! drag = { coefficient = 0.5, linear = 5.0 }
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

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use soak_hydro::{BuoyancyMode, Drag, GerstnerWave};
use soak_wet::{DiffusionMode, Environment, EnvironmentTrack, Liquid, Material, Rain, Splash};

use crate::error::SceneError;
use crate::generator::Backend;

fn default_dt() -> f64 {
    1.0 / 60.0
}
fn default_duration() -> f64 {
    10.0
}
fn default_gravity() -> [f64; 3] {
    [0.0, -9.81, 0.0]
}
fn default_resolution() -> u32 {
    256
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
    /// Simulated duration, s.
    #[serde(default = "default_duration")]
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
    /// The weather wet bodies dry in; [`Environment::default`] when absent.
    pub environment: Option<EnvironmentSpec>,
    /// Splashes landing on the wet bodies during the run.
    #[serde(default)]
    pub splash: Vec<SplashSpec>,
    /// What to record.
    #[serde(default)]
    pub output: OutputSpec,
}

/// Which fluid surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WaterKind {
    /// A calm plane at `level`.
    #[default]
    Plane,
    /// A sum of Gerstner waves about `level`.
    Gerstner,
    /// Heights from a CSV file on a grid.
    HeightField,
    /// Air (or any fluid) everywhere: no free surface.
    Air,
}

/// The fluid. Keys that do not apply to `kind` are errors.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaterSpec {
    /// Surface kind.
    #[serde(default)]
    pub kind: WaterKind,
    /// Mean level, m (plane, gerstner).
    pub level: Option<f64>,
    /// Density, kg/m³ (default 1000, or 1.2 for air).
    pub density: Option<f64>,
    /// Uniform current or wind, m/s.
    pub current: Option<[f64; 3]>,
    /// Gerstner waves.
    pub waves: Option<Vec<GerstnerWave>>,
    /// Height-field CSV file (rows along z, columns along x, heights in m), relative to the scene.
    pub file: Option<String>,
    /// World (x, z) of the height field's first sample, m.
    pub origin: Option<[f64; 2]>,
    /// Height-field sample spacing (dx, dz), m.
    pub spacing: Option<[f64; 2]>,
}

/// How a body's mass is distributed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum MassSpec {
    /// Uniform solid.
    Solid {
        /// kg/m³
        density: f64,
    },
    /// Mass on the surface (a hollow body).
    Shell {
        /// kg/m²
        areal_density: f64,
    },
}

/// A collider for contacts with other bodies (massless: soak sets the mass).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ColliderSpec {
    /// No contacts.
    #[default]
    None,
    /// The convex hull of the mesh.
    ConvexHull,
    /// The triangle mesh itself (fixed bodies only in practice).
    Trimesh,
}

/// One body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Name for reports.
    pub name: String,
    /// Mesh path (relative to the scene file) or `builtin:` name.
    pub mesh: String,
    /// Atlas side, texels.
    #[serde(default = "default_resolution")]
    pub resolution: u32,
    /// Generate a physics atlas instead of using the mesh's UVs.
    #[serde(default)]
    pub unwrap: bool,
    /// Mass model.
    pub mass: MassSpec,
    /// Initial position of the mesh origin, m.
    #[serde(default)]
    pub position: [f64; 3],
    /// Initial rotation, degrees about x, then y, then z.
    #[serde(default)]
    pub rotation_deg: [f64; 3],
    /// Initial velocity, m/s.
    #[serde(default)]
    pub linear_velocity: [f64; 3],
    /// Initial angular velocity, rad/s.
    #[serde(default)]
    pub angular_velocity: [f64; 3],
    /// Buoyancy mode (`archimedes`, `pressure`, `off`).
    #[serde(default)]
    pub buoyancy: BuoyancyMode,
    /// Drag coefficients; no drag when absent.
    pub drag: Option<Drag>,
    /// Contacts.
    #[serde(default)]
    pub collider: ColliderSpec,
    /// A fixed (immovable) body, e.g. a terrain.
    #[serde(default)]
    pub fixed: bool,
    /// Liquid graph inside the body (water that enters through permeable
    /// texels): a graph file relative to the scene, or `{ auto = true }`.
    pub graph: Option<GraphSpec>,
    /// Permeable regions (holes) of the wall; needs `graph`.
    #[serde(default)]
    pub permeability: Vec<HoleSpec>,
    /// Surface wetting: the body's liquid texture soaks up the water it is
    /// dipped in, dries and diffuses. Off when absent (and then nothing is
    /// allocated for it).
    pub wetting: Option<WettingSpec>,
}

/// A body's surface wetting.
///
/// ```toml
/// wetting = { material = "wood", diffusion = 2e-5, mode = "conservative", initial = 0.0 }
/// wetting = { material = { permeability = 1e-12, thickness = 0.005, saturation = 0.001 },
///             liquid = { viscosity = 1e-3, evaporation_rate = 1e8 }, initial = "wet.png" }
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WettingSpec {
    /// The surface material: a preset name (`sand`, `wood`, `rock`,
    /// `cotton`, see [`Material`]) or its parameters.
    pub material: MaterialSpec,
    /// The liquid: `water` (the default), `ethanol`, or its parameters.
    #[serde(default)]
    pub liquid: LiquidSpec,
    /// Diffusion coefficient D, m²/s; absent for no diffusion (no voxel
    /// field at all), 0 for a field that does not spread.
    pub diffusion: Option<f64>,
    /// Diffusion scheme, `conservative` (the default: total liquid is
    /// conserved) or `thesis` (the thesis' Shepard scheme); needs `diffusion`.
    pub mode: Option<DiffusionMode>,
    /// Voxel edge of the body's diffusion field, m; automatic from the mean
    /// texel size when absent. Needs `diffusion`.
    pub voxel_size: Option<f64>,
    /// The liquid at the start: a fill fraction of saturation in [0, 1]
    /// (0, dry, by default), or an image (PNG or EXR, relative to the scene)
    /// laid over the UV square whose luminance 1 is saturation.
    #[serde(default)]
    pub initial: InitialLiquid,
}

/// A surface material: a preset or its parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum MaterialSpec {
    /// `sand`, `wood`, `rock` or `cotton`.
    Preset(String),
    /// The parameters.
    Custom(MaterialParams),
}

/// A material's parameters (thesis Table 5.1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialParams {
    /// Intrinsic permeability C_M, m² (≥ 0).
    pub permeability: f64,
    /// Thickness of the porous layer, m (> 0).
    pub thickness: f64,
    /// Saturation: the most liquid per area, m³/m² = m (> 0).
    pub saturation: f64,
}

impl MaterialSpec {
    /// The material, or `None` for an unknown preset name.
    pub fn material(&self) -> Option<Material> {
        match self {
            MaterialSpec::Preset(name) => match name.as_str() {
                "sand" => Some(Material::sand()),
                "wood" => Some(Material::wood()),
                "rock" => Some(Material::rock()),
                "cotton" => Some(Material::cotton()),
                _ => None,
            },
            MaterialSpec::Custom(p) => Some(Material {
                permeability: p.permeability,
                thickness: p.thickness,
                saturation: p.saturation,
            }),
        }
    }
}

/// A liquid: a preset or its parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum LiquidSpec {
    /// `water` or `ethanol`.
    Preset(String),
    /// The parameters.
    Custom(LiquidParams),
}

impl Default for LiquidSpec {
    fn default() -> Self {
        LiquidSpec::Preset("water".into())
    }
}

/// A liquid's parameters (thesis Table 5.1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiquidParams {
    /// Dynamic viscosity μ, Pa·s (> 0).
    pub viscosity: f64,
    /// Evaporation rate k_L, 1/(m·s) (≥ 0): the surface dries at
    /// `f_env k_L C_M` m/s. Water's is 1e4; a larger value makes a
    /// time-lapse.
    pub evaporation_rate: f64,
}

impl LiquidSpec {
    /// The liquid, or `None` for an unknown preset name.
    pub fn liquid(&self) -> Option<Liquid> {
        match self {
            LiquidSpec::Preset(name) => match name.as_str() {
                "water" => Some(Liquid::water()),
                "ethanol" => Some(Liquid::ethanol()),
                _ => None,
            },
            LiquidSpec::Custom(p) => Some(Liquid {
                viscosity: p.viscosity,
                evaporation_rate: p.evaporation_rate,
            }),
        }
    }
}

/// The liquid a wet body starts with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum InitialLiquid {
    /// Every texel at this fraction of saturation, in [0, 1].
    Fill(f64),
    /// An image file relative to the scene (luminance 1 = saturation).
    Image(String),
}

impl Default for InitialLiquid {
    fn default() -> Self {
        InitialLiquid::Fill(0.0)
    }
}

fn default_temperature_c() -> f64 {
    20.0
}
fn default_humidity() -> f64 {
    0.5
}
fn default_wind() -> f64 {
    2.0
}

/// The weather wet bodies dry in, the same for all of them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSpec {
    /// Air temperature, °C (default 20).
    #[serde(default = "default_temperature_c")]
    pub temperature_c: f64,
    /// Relative humidity, a fraction in [0, 1] (default 0.5); at 1 nothing dries.
    #[serde(default = "default_humidity")]
    pub relative_humidity: f64,
    /// Wind speed, m/s (default 2).
    #[serde(default = "default_wind")]
    pub wind_speed: f64,
    /// Rain falling everywhere on upward-facing dry texels, mm/h (default 0).
    #[serde(default)]
    pub rain_mm_per_hour: f64,
    /// Later weather: keys at increasing times after the start, linearly
    /// interpolated between them and held after the last (default none: the
    /// weather above all along).
    #[serde(default)]
    pub keys: Vec<EnvironmentKeySpec>,
}

/// The weather at a time `at` (s); absent values are the previous key's
/// (the base environment's for the first key).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentKeySpec {
    /// Time of the key, s (> 0, increasing from key to key).
    pub at: f64,
    /// Air temperature, °C.
    pub temperature_c: Option<f64>,
    /// Relative humidity, a fraction in [0, 1].
    pub relative_humidity: Option<f64>,
    /// Wind speed, m/s.
    pub wind_speed: Option<f64>,
    /// Rain, mm/h.
    pub rain_mm_per_hour: Option<f64>,
}

impl Default for EnvironmentSpec {
    fn default() -> Self {
        Self {
            temperature_c: default_temperature_c(),
            relative_humidity: default_humidity(),
            wind_speed: default_wind(),
            rain_mm_per_hour: 0.0,
            keys: Vec::new(),
        }
    }
}

impl EnvironmentSpec {
    /// The environment at the start, in soak-wet's units (temperature in K).
    pub fn environment(&self) -> Environment {
        Self::convert(
            self.temperature_c,
            self.relative_humidity,
            self.wind_speed,
            self.rain_mm_per_hour,
        )
    }

    /// Each key's time and full values (temperature °C, relative humidity,
    /// wind m/s, rain mm/h), a key's absent values taken from the key before.
    pub fn resolved_keys(&self) -> Vec<(f64, [f64; 4])> {
        let mut current = [
            self.temperature_c,
            self.relative_humidity,
            self.wind_speed,
            self.rain_mm_per_hour,
        ];
        self.keys
            .iter()
            .map(|k| {
                let given = [
                    k.temperature_c,
                    k.relative_humidity,
                    k.wind_speed,
                    k.rain_mm_per_hour,
                ];
                for (c, g) in current.iter_mut().zip(given) {
                    if let Some(g) = g {
                        *c = g;
                    }
                }
                (k.at, current)
            })
            .collect()
    }

    /// The weather over time: the base environment at t = 0, then the keys;
    /// `None` when there are no keys (the weather never changes).
    ///
    /// # Errors
    /// Keys out of order or with values out of range.
    pub fn track(&self) -> Result<Option<EnvironmentTrack>, soak_wet::WetError> {
        if self.keys.is_empty() {
            return Ok(None);
        }
        let mut keys = vec![(0.0, self.environment())];
        keys.extend(
            self.resolved_keys()
                .into_iter()
                .map(|(at, [t, h, w, r])| (at, Self::convert(t, h, w, r))),
        );
        EnvironmentTrack::new(keys).map(Some)
    }

    fn convert(
        temperature_c: f64,
        relative_humidity: f64,
        wind_speed: f64,
        rain_mm_per_hour: f64,
    ) -> Environment {
        Environment {
            temperature: temperature_c + 273.15,
            relative_humidity,
            wind_speed,
            rain: if rain_mm_per_hour > 0.0 {
                Rain::mm_per_hour(rain_mm_per_hour)
            } else {
                Rain::none()
            },
        }
    }
}

/// Liquid landing once, at time `at`, on every wet body within `radius` of
/// `center` (see [`soak_wet::Splash`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SplashSpec {
    /// When it lands, s (≥ 0).
    #[serde(default)]
    pub at: f64,
    /// World position, m.
    pub center: [f64; 3],
    /// Radius, m (> 0).
    pub radius: f64,
    /// Volume of liquid, m³ (≥ 0), shared by the texels within the radius
    /// of each wet body it reaches; what a saturated texel cannot hold runs off.
    pub volume: f64,
}

impl SplashSpec {
    /// The splash in soak-wet's form.
    pub fn splash(&self) -> Splash {
        Splash {
            center: self.center,
            radius: self.radius,
            volume: self.volume,
        }
    }
}

/// Where a body's liquid graph comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum GraphSpec {
    /// A graph file (TOML or JSON), relative to the scene.
    File(String),
    /// Automatic segmentation of the mesh (Shape Diameter Function).
    Auto(AutoGraphSpec),
}

fn default_clusters() -> usize {
    5
}
fn one() -> f64 {
    1.0
}

/// Automatic graph parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AutoGraphSpec {
    /// Must be `true`.
    pub auto: bool,
    /// Clusters of the segmentation.
    #[serde(default = "default_clusters")]
    pub clusters: usize,
    /// Fraction of each segment open to liquid, in [0, 1] (≈ 0.9 for stuffing).
    #[serde(default = "one")]
    pub porosity: f64,
}

/// A permeable region: every texel within `radius` of `centre`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HoleSpec {
    /// Centre in the body's local frame, m.
    pub centre: [f64; 3],
    /// Radius, m.
    pub radius: f64,
    /// Permeability over wall thickness κ = k/L, m.
    pub kappa: f64,
    /// Time the region opens (a hole punched during the run), s.
    #[serde(default)]
    pub at: f64,
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

/// A scene with the file it came from (for relative paths and messages).
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The file, or a label for an embedded scene.
    pub path: PathBuf,
    /// The TOML text (for locating keys in messages).
    pub text: String,
}

impl LoadedScene {
    /// Reads and validates a scene file.
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::from_str(&text, path)
    }

    /// Parses and validates scene text; `path` names it in messages and
    /// anchors relative mesh paths.
    pub fn from_str(text: &str, path: &Path) -> Result<Self, SceneError> {
        let scene: Scene = toml::from_str(text).map_err(|e| SceneError::Parse {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let loaded = Self {
            scene,
            path: path.to_path_buf(),
            text: text.to_string(),
        };
        loaded.validate()?;
        Ok(loaded)
    }

    /// The 1-based line of a dotted key path (`bodies[1].mass.density`), or of
    /// its nearest existing parent.
    pub fn line_of(&self, key: &str) -> usize {
        line_of(&self.text, key)
    }

    /// An [`SceneError::Invalid`] for `key`.
    pub fn invalid(&self, key: &str, message: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            path: self.path.clone(),
            line: self.line_of(key),
            key: key.to_string(),
            message: message.into(),
        }
    }

    /// A path relative to the scene file.
    pub fn resolve(&self, relative: &str) -> PathBuf {
        let p = Path::new(relative);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        self.path
            .parent()
            .map(|d| d.join(p))
            .unwrap_or_else(|| p.to_path_buf())
    }

    /// Checks one set of weather values; `key` names the table they are in.
    fn check_weather(
        &self,
        key: &str,
        temperature_c: f64,
        relative_humidity: f64,
        wind_speed: f64,
        rain_mm_per_hour: f64,
    ) -> Result<(), SceneError> {
        if !(temperature_c.is_finite() && temperature_c > -273.15) {
            return Err(self.invalid(
                &format!("{key}.temperature_c"),
                format!("must be a temperature above absolute zero in °C, not {temperature_c}"),
            ));
        }
        if !(0.0..=1.0).contains(&relative_humidity) {
            return Err(self.invalid(
                &format!("{key}.relative_humidity"),
                format!("must be a fraction in [0, 1], not {relative_humidity}"),
            ));
        }
        if !(wind_speed.is_finite() && wind_speed >= 0.0) {
            return Err(self.invalid(
                &format!("{key}.wind_speed"),
                format!("must be ≥ 0 m/s, not {wind_speed}"),
            ));
        }
        if !(rain_mm_per_hour.is_finite() && rain_mm_per_hour >= 0.0) {
            return Err(self.invalid(
                &format!("{key}.rain_mm_per_hour"),
                format!("must be ≥ 0 mm/h, not {rain_mm_per_hour}"),
            ));
        }
        Ok(())
    }

    fn validate(&self) -> Result<(), SceneError> {
        let s = &self.scene;
        let positive = |key: &str, v: f64| -> Result<(), SceneError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(self.invalid(key, format!("must be a positive number, not {v}")))
            }
        };
        let finite = |key: &str, v: &[f64]| -> Result<(), SceneError> {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(self.invalid(key, format!("must be finite, not {v:?}")))
            }
        };
        positive("dt", s.dt)?;
        if s.dt > 0.25 {
            return Err(self.invalid("dt", format!("{} s is too long a step (at most 0.25 s)", s.dt)));
        }
        positive("duration", s.duration)?;
        finite("gravity", &s.gravity)?;
        if s.output.every == 0 {
            return Err(self.invalid("output.every", "must be at least 1"));
        }
        if s.output.liquid_png_every == Some(0) {
            return Err(self.invalid("output.liquid_png_every", "must be at least 1"));
        }
        if let Some(e) = &s.environment {
            self.check_weather(
                "environment",
                e.temperature_c,
                e.relative_humidity,
                e.wind_speed,
                e.rain_mm_per_hour,
            )?;
            let mut last = 0.0;
            for (i, (at, [t, h, w, r])) in e.resolved_keys().into_iter().enumerate() {
                let key = format!("environment.keys[{i}]");
                if !(at.is_finite() && at > last) {
                    return Err(self.invalid(
                        &format!("{key}.at"),
                        format!(
                            "must be a time in s after the start and after the previous key ({last}), not {at}"
                        ),
                    ));
                }
                last = at;
                self.check_weather(&key, t, h, w, r)?;
            }
        }
        for (i, sp) in s.splash.iter().enumerate() {
            let key = format!("splash[{i}]");
            if !(sp.at.is_finite() && sp.at >= 0.0) {
                return Err(self.invalid(
                    &format!("{key}.at"),
                    format!("must be a time ≥ 0 s, not {}", sp.at),
                ));
            }
            if !sp.center.iter().all(|c| c.is_finite()) {
                return Err(self.invalid(&format!("{key}.center"), "must be three finite numbers, m"));
            }
            if !(sp.radius.is_finite() && sp.radius > 0.0) {
                return Err(self.invalid(
                    &format!("{key}.radius"),
                    format!("must be > 0 m, not {}", sp.radius),
                ));
            }
            if !(sp.volume.is_finite() && sp.volume >= 0.0) {
                return Err(self.invalid(
                    &format!("{key}.volume"),
                    format!("must be ≥ 0 m³, not {}", sp.volume),
                ));
            }
        }
        let w = &s.water;
        let kind = w.kind;
        let only = |key: &str, present: bool, kinds: &[WaterKind]| -> Result<(), SceneError> {
            if present && !kinds.contains(&kind) {
                Err(self.invalid(
                    &format!("water.{key}"),
                    format!("does not apply to water of kind {kind:?}"),
                ))
            } else {
                Ok(())
            }
        };
        only(
            "level",
            w.level.is_some(),
            &[WaterKind::Plane, WaterKind::Gerstner],
        )?;
        only("waves", w.waves.is_some(), &[WaterKind::Gerstner])?;
        only("file", w.file.is_some(), &[WaterKind::HeightField])?;
        only("origin", w.origin.is_some(), &[WaterKind::HeightField])?;
        only("spacing", w.spacing.is_some(), &[WaterKind::HeightField])?;
        if let Some(d) = w.density {
            positive("water.density", d)?;
        }
        if let Some(l) = w.level {
            finite("water.level", &[l])?;
        }
        if let Some(c) = w.current {
            finite("water.current", &c)?;
        }
        if kind == WaterKind::Gerstner && w.waves.as_ref().is_none_or(|v| v.is_empty()) {
            return Err(self.invalid("water", "a gerstner sea needs `waves`"));
        }
        if let Some(waves) = &w.waves
            && let Err(soak_hydro::WaterError::Wave { index, field, value }) =
                soak_hydro::Gerstner::new(0.0, waves.clone(), 9.81)
        {
            return Err(self.invalid(
                &format!("water.waves[{index}].{field}"),
                format!("{value} is out of range"),
            ));
        }
        if kind == WaterKind::HeightField {
            for (key, present) in [("file", w.file.is_some()), ("spacing", w.spacing.is_some())] {
                if !present {
                    return Err(self.invalid("water", format!("a height field needs `{key}`")));
                }
            }
            let [dx, dz] = w.spacing.unwrap_or([1.0, 1.0]);
            positive("water.spacing", dx.min(dz))?;
        }
        let mut names = std::collections::HashSet::new();
        for (i, b) in s.bodies.iter().enumerate() {
            let key = |k: &str| format!("bodies[{i}].{k}");
            if !names.insert(b.name.as_str()) {
                return Err(self.invalid(&key("name"), format!("`{}` is used by another body", b.name)));
            }
            if b.resolution == 0 || b.resolution > soak_bake::MAX_RESOLUTION {
                return Err(self.invalid(
                    &key("resolution"),
                    format!("{} is outside 1..={}", b.resolution, soak_bake::MAX_RESOLUTION),
                ));
            }
            match b.mass {
                MassSpec::Solid { density } => positive(&key("mass.density"), density)?,
                MassSpec::Shell { areal_density } => positive(&key("mass.areal_density"), areal_density)?,
            }
            finite(&key("position"), &b.position)?;
            finite(&key("rotation_deg"), &b.rotation_deg)?;
            finite(&key("linear_velocity"), &b.linear_velocity)?;
            finite(&key("angular_velocity"), &b.angular_velocity)?;
            if let Some(GraphSpec::Auto(a)) = &b.graph {
                if !a.auto {
                    return Err(self.invalid(&key("graph.auto"), "must be true (or give a graph file)"));
                }
                if a.clusters == 0 {
                    return Err(self.invalid(&key("graph.clusters"), "must be at least 1"));
                }
                if !(0.0..=1.0).contains(&a.porosity) {
                    return Err(self.invalid(
                        &key("graph.porosity"),
                        format!("{} is outside [0, 1]", a.porosity),
                    ));
                }
            }
            if !b.permeability.is_empty() && b.graph.is_none() {
                return Err(self.invalid(&key("permeability"), "needs a `graph` for the water to go into"));
            }
            for (k, h) in b.permeability.iter().enumerate() {
                let hk = |f: &str| key(&format!("permeability[{k}].{f}"));
                finite(&hk("centre"), &h.centre)?;
                positive(&hk("radius"), h.radius)?;
                if !(h.kappa.is_finite() && h.kappa >= 0.0) {
                    return Err(self.invalid(&hk("kappa"), format!("must be ≥ 0 m, not {}", h.kappa)));
                }
                if !(h.at.is_finite() && h.at >= 0.0) {
                    return Err(self.invalid(&hk("at"), format!("must be a time ≥ 0 s, not {}", h.at)));
                }
            }
            if let Some(w) = &b.wetting {
                self.validate_wetting(i, b, w)?;
            }
            if let Some(d) = b.drag {
                if !(d.coefficient.is_finite() && d.coefficient >= 0.0) {
                    return Err(self.invalid(
                        &key("drag.coefficient"),
                        format!("must be ≥ 0, not {}", d.coefficient),
                    ));
                }
                if !(d.linear.is_finite() && d.linear >= 0.0) {
                    return Err(self.invalid(&key("drag.linear"), format!("must be ≥ 0, not {}", d.linear)));
                }
            }
        }
        Ok(())
    }
}

impl LoadedScene {
    fn validate_wetting(&self, i: usize, b: &BodySpec, w: &WettingSpec) -> Result<(), SceneError> {
        let key = |k: &str| format!("bodies[{i}].wetting{k}");
        if b.fixed {
            return Err(self.invalid(
                &key(""),
                "does not apply to a fixed body (only bodies soak drives get wet)",
            ));
        }
        let check = |k: &str, v: f64, ok: bool, what: &str| -> Result<(), SceneError> {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(self.invalid(&key(k), format!("must be {what}, not {v}")))
            }
        };
        match &w.material {
            MaterialSpec::Preset(name) if w.material.material().is_none() => {
                return Err(self.invalid(
                    &key(".material"),
                    format!("`{name}` is not a material (sand, wood, rock, cotton, or a table)"),
                ));
            }
            MaterialSpec::Custom(p) => {
                check(
                    ".material.permeability",
                    p.permeability,
                    p.permeability >= 0.0,
                    "≥ 0 m²",
                )?;
                check(".material.thickness", p.thickness, p.thickness > 0.0, "> 0 m")?;
                check(".material.saturation", p.saturation, p.saturation > 0.0, "> 0 m")?;
            }
            MaterialSpec::Preset(_) => {}
        }
        match &w.liquid {
            LiquidSpec::Preset(name) if w.liquid.liquid().is_none() => {
                return Err(self.invalid(
                    &key(".liquid"),
                    format!("`{name}` is not a liquid (water, ethanol, or a table)"),
                ));
            }
            LiquidSpec::Custom(p) => {
                check(".liquid.viscosity", p.viscosity, p.viscosity > 0.0, "> 0 Pa·s")?;
                check(
                    ".liquid.evaporation_rate",
                    p.evaporation_rate,
                    p.evaporation_rate >= 0.0,
                    "≥ 0 1/(m·s)",
                )?;
            }
            LiquidSpec::Preset(_) => {}
        }
        if let Some(d) = w.diffusion {
            check(".diffusion", d, d >= 0.0, "a diffusion coefficient ≥ 0 m²/s")?;
        }
        for (k, present) in [("mode", w.mode.is_some()), ("voxel_size", w.voxel_size.is_some())] {
            if present && w.diffusion.is_none() {
                return Err(self.invalid(&key(&format!(".{k}")), "needs `diffusion`"));
            }
        }
        if let Some(v) = w.voxel_size {
            check(".voxel_size", v, v > 0.0, "> 0 m")?;
        }
        if let InitialLiquid::Fill(f) = w.initial {
            check(
                ".initial",
                f,
                (0.0..=1.0).contains(&f),
                "a fill fraction in [0, 1] or an image path",
            )?;
        }
        Ok(())
    }
}

/// One step of a dotted key path.
enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

fn parse_path(key: &str) -> Vec<Seg<'_>> {
    let mut out = Vec::new();
    for part in key.split('.') {
        let (name, rest) = part.split_once('[').map_or((part, None), |(n, r)| (n, Some(r)));
        if !name.is_empty() {
            out.push(Seg::Key(name));
        }
        if let Some(rest) = rest {
            for idx in rest.split('[') {
                if let Ok(i) = idx.trim_end_matches(']').parse() {
                    out.push(Seg::Index(i));
                }
            }
        }
    }
    out
}

/// 1-based line of `key` in TOML `text` (of its deepest existing parent if
/// the key itself is absent); 1 if nothing matches.
pub fn line_of(text: &str, key: &str) -> usize {
    use toml::de::{DeTable, DeValue};
    let line = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;
    let Ok(root) = DeTable::parse(text) else {
        return 1;
    };
    let mut best = 1;
    let mut current: Option<&DeValue<'_>> = None;
    let mut table: Option<&DeTable<'_>> = Some(root.get_ref());
    for seg in parse_path(key) {
        match seg {
            Seg::Key(k) => {
                let Some(t) = table else { break };
                let Some((kk, v)) = t.iter().find(|(kk, _)| kk.get_ref().as_ref() == k) else {
                    break;
                };
                best = line(kk.span().start);
                current = Some(v.get_ref());
            }
            Seg::Index(i) => {
                let Some(DeValue::Array(a)) = current else { break };
                let Some(v) = a.get(i) else { break };
                best = line(v.span().start);
                current = Some(v.get_ref());
            }
        }
        table = match current {
            Some(DeValue::Table(t)) => Some(t),
            _ => None,
        };
    }
    best
}
