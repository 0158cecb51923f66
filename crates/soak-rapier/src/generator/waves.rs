//! Waves that bodies make, coupled to the generator ([`WaveCoupling`]):
//! every body presses its hull on an [`InteractiveWaves`] surface over a
//! region that follows the bodies, and floats on the water with those
//! waves on it, less its own depression.

use serde::{Deserialize, Serialize};
use soak_hydro::{InteractiveWaves, WaveRegion, WavesState};

/// Interactive waves under the bodies
/// ([`ForceGenerator::with_waves`](super::ForceGenerator::with_waves)): an
/// [`InteractiveWaves`] surface over a square region (linear deep water,
/// every mode turning at `ω = √(g k)`, exact whatever the step) laid over
/// the generator's water (a plane or a sea).
///
/// Each step every body with buoyancy presses its hull on the surface (its
/// submerged column depth per cell, times `ρ g`), and floats on the water
/// with the waves on it less the depression it pressed the step before: it
/// feels the waves the others made and what its own motion stirred, not
/// the hollow it holds. A heaving hull radiates waves and loses the energy
/// they carry off; a moving hull leaves a Kelvin wake; a buoy rocks in a
/// passing boat's waves. The surface holds its own static depressions: a
/// body's buoyancy is the pressure it puts on the waves, Newton's third law
/// cell by cell.
///
/// The surface the drag reads is the base water's (the waves' orbital
/// velocity is not counted), and a body's [`Effects::added_mass`] (if
/// set) is on top of the inertia the waves already give it.
///
/// [`Effects::added_mass`]: super::Effects::with_added_mass
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaveCoupling {
    /// Centre `(x, z)` of the region at the start, world, m.
    pub centre: [f64; 2],
    /// Side of the square region, m. Default 64.
    pub size: f64,
    /// Cells per side (even, ≥ 8; a product of small primes transforms
    /// fastest). Default 256 (0.25 m cells at the default size).
    pub cells: usize,
    /// Cells along the border that absorb the waves reaching it (at most a
    /// quarter of `cells`). Default 16.
    pub sponge: usize,
    /// Whether the region follows the bodies (it re-centres by whole cells
    /// on the middle of the bodies that press on it; waves leaving it are
    /// counted as absorbed). Default true.
    pub follow: bool,
    /// Whether the bodies' first press lowers the surface under them at
    /// rest (each body's static depression), so that bodies set at their
    /// floating level start no waves. Default true.
    pub settle: bool,
}

impl Default for WaveCoupling {
    fn default() -> Self {
        Self {
            centre: [0.0, 0.0],
            size: 64.0,
            cells: 256,
            sponge: 16,
            follow: true,
            settle: true,
        }
    }
}

impl WaveCoupling {
    /// The region it starts over.
    pub fn region(&self) -> WaveRegion {
        WaveRegion {
            centre: self.centre,
            size: self.size,
            cells: self.cells,
        }
    }
}

/// A body's press on the waves: the cells it covers and the depth of its
/// columns in each, m (increasing cell order).
pub(crate) type Pressed = Vec<(usize, f64)>;

/// The generator's waves: the surface, the rule, and what each body
/// pressed the last step.
#[derive(Debug)]
pub(crate) struct CoupledWaves {
    pub(crate) solver: InteractiveWaves,
    pub(crate) rule: WaveCoupling,
    /// Per body (registration order): the cells it pressed at the last
    /// step and the depth in each, m (increasing cell order).
    pub(crate) own: Vec<Pressed>,
    /// The first press is still to be held at rest ([`WaveCoupling::settle`]).
    pub(crate) settle_pending: bool,
    /// Where the region follows to at the next step: the middle of the
    /// bodies that pressed, `(x, z)`, m.
    pub(crate) follow: Option<[f64; 2]>,
}

/// What the generator's waves have become, for saving.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CoupledWavesState {
    /// The surface.
    pub surface: WavesState,
    /// Per body: the cells it pressed at the last step and the depth in
    /// each, m.
    pub own: Vec<Vec<(usize, f64)>>,
    /// Whether the first press is still to be held at rest.
    pub settle_pending: bool,
}

impl CoupledWaves {
    pub(crate) fn state(&self) -> CoupledWavesState {
        CoupledWavesState {
            surface: self.solver.state(),
            own: self.own.clone(),
            settle_pending: self.settle_pending,
        }
    }
}
