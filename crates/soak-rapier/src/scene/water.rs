//! The fluid a scene floats its bodies in: [`WaterSpec`] and its [`WaterKind`].

use serde::{Deserialize, Serialize};
use soak_hydro::{GerstnerWave, SeaSampling, SeaVelocity};

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
    /// How the texels read a Gerstner sea: `{ per_wavelength = 16 }` (the
    /// default: the sea sampled once per step over each body, 16 nodes per
    /// shortest wavelength) or `"exact"` (every texel inverts the Gerstner
    /// map: the reference, far slower).
    pub sampling: Option<SeaSampling>,
    /// Where the drag reads a sampled sea's velocity: `"per_tile"` (the
    /// default: once per tile of each body's atlas) or `"per_texel"` (at
    /// every texel: the reference).
    pub velocity: Option<SeaVelocity>,
}
