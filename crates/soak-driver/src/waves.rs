//! Waves that bodies make, coupled to the generator ([`WaveCoupling`]):
//! every body presses its hull on an [`InteractiveWaves`] surface over a
//! region that follows the bodies, and floats on the water with those
//! waves on it, less its own depression.

use serde::{Deserialize, Serialize};
use soak_hydro::{InteractiveWaves, WaveRegion, WavesState};

/// Interactive waves under the bodies
/// ([`Driver::with_waves`](crate::Driver::with_waves)): an
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
/// With a GPU backend ([`Driver::with_gpu`](crate::Driver::with_gpu),
/// before or after this) the waves step on the device
/// ([`GpuWaves`](soak_hydro::gpu::GpuWaves), f32; their cells per side must
/// then be a power of two) and the generator's copy takes their elevation
/// and potential after each step; the sponge's energy
/// ([`InteractiveWaves::absorbed`]) is then not counted.
///
/// The surface the drag reads is the base water's (the waves' orbital
/// velocity is not counted), and a body's [`Effects::added_mass`] (if
/// set) is on top of the inertia the waves already give it.
///
/// [`Effects::added_mass`]: crate::Effects::with_added_mass
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaveCoupling {
    /// Centre `(x, z)` of the region at the start, world, m.
    pub centre: [f64; 2],
    /// Side of the square region, m. Default 64.
    pub size: f64,
    /// Cells per side (even, 8 to
    /// [`MAX_WAVE_CELLS`](soak_hydro::MAX_WAVE_CELLS); a product of small
    /// primes transforms fastest, a power of two on the GPU). Default 256
    /// (0.25 m cells at the default size).
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
    /// The same surface stepped on the GPU, when the generator has a GPU
    /// backend: `solver` then mirrors it after each step.
    #[cfg(feature = "gpu")]
    pub(crate) gpu: Option<soak_hydro::gpu::GpuWaves>,
    /// The CPU's surface changed since the GPU's copy was made (a held
    /// depression, a shifted region, a restored state): the GPU takes it
    /// before its next step.
    pub(crate) moved: bool,
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
    /// Steps the surface by `dt` (s) under the pressure the bodies put on
    /// it: on the GPU when it has one there (the CPU's copy then takes the
    /// device's elevation and potential), else on the CPU.
    pub(crate) fn step(&mut self, dt: f64) -> Result<(), crate::error::SoakError> {
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            if self.moved {
                let state = self.solver.state();
                gpu.set_state(&state.h, &state.phi)?;
            }
            self.moved = false;
            gpu.set_pressure(self.solver.pressure())?;
            gpu.step(dt)?;
            let (h, phi) = gpu.state()?;
            let mut state = self.solver.state();
            state.h = h;
            state.phi = phi;
            state.time += dt;
            return self
                .solver
                .restore(&state)
                .map_err(crate::error::SoakError::Waves);
        }
        self.solver.step(dt).map_err(crate::error::SoakError::Waves)
    }

    /// Moves the region to follow the bodies (see [`WaveCoupling::follow`]),
    /// renumbering their presses, and the GPU's copy with it.
    pub(crate) fn follow(&mut self) -> Result<(), crate::error::SoakError> {
        let Some(centre) = self.follow.filter(|_| self.rule.follow) else {
            return Ok(());
        };
        let shift = self.solver.recentre(centre);
        if shift == (0, 0) {
            return Ok(());
        }
        for own in &mut self.own {
            self.solver.shift_cells(own, shift);
        }
        self.moved = true;
        Ok(())
    }

    /// The GPU's copy of the surface, on `device`, from the CPU's now.
    #[cfg(feature = "gpu")]
    pub(crate) fn on_gpu(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<(), crate::error::SoakError> {
        let mut gpu = soak_hydro::gpu::GpuWaves::new(
            device,
            queue,
            *self.solver.region(),
            self.solver.gravity(),
            self.rule.sponge,
        )?;
        let state = self.solver.state();
        gpu.set_state(&state.h, &state.phi)?;
        self.gpu = Some(gpu);
        Ok(())
    }

    pub(crate) fn state(&self) -> CoupledWavesState {
        CoupledWavesState {
            surface: self.solver.state(),
            own: self.own.clone(),
            settle_pending: self.settle_pending,
        }
    }
}
