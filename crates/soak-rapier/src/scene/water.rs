//! The fluid a scene floats its bodies in: [`WaterSpec`] and its [`WaterKind`].

use serde::{Deserialize, Serialize};
use soak_hydro::{
    GerstnerWave, SeaSampling, SeaSpectrum, SeaVelocity, SpectralSea, SpectrumShape, WaterError,
};

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
    /// A spectral sea (JONSWAP or Pierson–Moskowitz by significant height
    /// and peak period) realised on a periodic FFT tile.
    Spectrum,
    /// Air (or any fluid) everywhere: no free surface.
    Air,
}

/// A spectrum by name, in a scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpectrumName {
    /// JONSWAP (peak enhancement `gamma`).
    #[default]
    Jonswap,
    /// Pierson–Moskowitz.
    PiersonMoskowitz,
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
    /// How the texels read a sea: `"auto"` (the default: each body as it is
    /// against the waves, one plane over a body at most an eighth of the
    /// shortest wave across and the sea sampled over any other, see
    /// [`SeaSampling::Auto`]), `{ per_wavelength = 16 }` (the sea sampled
    /// once per step over each body, 16 nodes per shortest wavelength),
    /// `"exact"` (every texel inverts the sea's map: the reference, far
    /// slower) or `"plane"` (each body reads one plane fitted over its
    /// footprint and the sea's velocity at its centre: a calm-water
    /// evaluation's cost, see [`SeaSampling::Plane`]).
    pub sampling: Option<SeaSampling>,
    /// The spectral sea's spectrum: `"jonswap"` (the default) or
    /// `"pierson_moskowitz"`.
    pub spectrum: Option<SpectrumName>,
    /// The spectral sea's significant height, m (required).
    pub significant_height: Option<f64>,
    /// The spectral sea's peak period, s (required).
    pub peak_period: Option<f64>,
    /// JONSWAP's peak enhancement `γ` (default 3.3).
    pub gamma: Option<f64>,
    /// The spectral sea's mean direction of travel, degrees from +x
    /// towards +z (default 0).
    pub direction_deg: Option<f64>,
    /// The cos-2s spreading exponent `s` (default 10: a wind sea; 75 a
    /// swell).
    pub spreading: Option<f64>,
    /// The seed of the spectral sea's realisation (default 0).
    pub seed: Option<u64>,
    /// The spectral sea's tile, m (default eight peak wavelengths).
    pub tile: Option<f64>,
    /// The spectral sea's cells along each side of its tile, a power of two
    /// (default 128).
    pub cells: Option<usize>,
    /// The spectral sea's choppiness, 0 to 1 (default 1: linear theory's
    /// horizontal particle orbits).
    pub choppiness: Option<f64>,
    /// Where the drag reads a sampled sea's velocity: `"per_tile"` (the
    /// default: once per tile of each body's atlas) or `"per_texel"` (at
    /// every texel: the reference).
    pub velocity: Option<SeaVelocity>,
    /// The waves of the spectral sea each body reads: only those at least
    /// this many times its bounding diameter long are sure to be read, the
    /// shorter ones dropped as a band (see
    /// [`SeaBand`](soak_hydro::SeaBand)); a positive number. Default: every
    /// wave.
    pub band: Option<f64>,
}

impl WaterSpec {
    /// The target spectrum of `kind = "spectrum"`: its shape, significant
    /// height, peak period, direction and spreading with their defaults
    /// filled in (`gamma` 3.3, direction 0°, spreading 10).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] naming the key (`significant_height`,
    /// `peak_period`, `gamma`, `spreading`, …) that is missing or out of
    /// range.
    pub fn sea_spectrum(&self) -> Result<SeaSpectrum, WaterError> {
        let missing = |name| WaterError::Parameter {
            name,
            value: f64::NAN,
        };
        let shape = match self.spectrum.unwrap_or_default() {
            SpectrumName::Jonswap => SpectrumShape::Jonswap {
                gamma: self.gamma.unwrap_or(3.3),
            },
            SpectrumName::PiersonMoskowitz => SpectrumShape::PiersonMoskowitz,
        };
        let spectrum = SeaSpectrum {
            shape,
            significant_height: self.significant_height.ok_or(missing("significant_height"))?,
            peak_period: self.peak_period.ok_or(missing("peak_period"))?,
            direction_deg: self.direction_deg.unwrap_or(0.0),
            spreading: self.spreading.unwrap_or(10.0),
        };
        spectrum.validate()?;
        Ok(spectrum)
    }

    /// The spectral sea of `kind = "spectrum"` under `gravity` (m/s²),
    /// realised: its spectrum ([`WaterSpec::sea_spectrum`]), tile and seed
    /// with their defaults filled in.
    ///
    /// # Errors
    /// [`WaterError::Parameter`] naming the key (`significant_height`,
    /// `peak_period`, `gamma`, `spreading`, `tile`, `cells`, `choppiness`,
    /// …) that is missing or out of range.
    pub fn spectral_sea(&self, gravity: f64) -> Result<SpectralSea, WaterError> {
        let spectrum = self.sea_spectrum()?;
        let tile = self.tile.unwrap_or_else(|| spectrum.default_tile(gravity));
        SpectralSea::realize(
            &spectrum,
            self.level.unwrap_or(0.0),
            tile,
            self.cells.unwrap_or(soak_hydro::DEFAULT_SEA_CELLS),
            self.seed.unwrap_or(0),
            gravity,
        )?
        .with_choppiness(self.choppiness.unwrap_or(1.0))
    }
}
