//! A body's surface wetting ([`WettingSpec`]: material, liquid, initial
//! liquid) and what it meets: the weather ([`EnvironmentSpec`]) and splashes
//! ([`SplashSpec`]).

use serde::{Deserialize, Serialize};
use soak_wet::{DiffusionMode, Environment, EnvironmentTrack, Liquid, Material, Rain, Splash};

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
