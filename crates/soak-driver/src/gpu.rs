//! The GPU backend of the driver: every body's atlas on the device,
//! all bodies evaluated in one batch per step.

use nalgebra::Point3;
use soak_bake::Atlas;
use soak_hydro::gpu::{GpuAtlasId, GpuBody, GpuHydro};
use soak_hydro::{BodyState, HydroForces, Water};

use crate::body::SoakBody;
use crate::error::SoakError;

/// Device-side atlases in registration order.
pub(crate) struct GpuBackend {
    hydro: GpuHydro,
    atlases: Vec<GpuAtlasId>,
    /// The caller's device and queue, for the interactive waves.
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
}

impl std::fmt::Debug for GpuBackend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuBackend")
            .field("atlases", &self.atlases.len())
            .finish_non_exhaustive()
    }
}

impl GpuBackend {
    pub(crate) fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, SoakError> {
        Ok(Self {
            hydro: GpuHydro::new(device, queue)?,
            atlases: Vec::new(),
            device: device.clone(),
            queue: queue.clone(),
        })
    }

    /// Uploads the next registered body's atlas (deformable).
    pub(crate) fn upload(&mut self, atlas: &Atlas) -> Result<(), SoakError> {
        let id = self.hydro.upload_deformable(atlas, atlas.triangles())?;
        self.atlases.push(id);
        Ok(())
    }

    /// Moves body `k`'s texels on the device.
    pub(crate) fn deform(&mut self, k: usize, positions: &[Point3<f64>]) -> Result<(), SoakError> {
        let id = self.atlases[k];
        Ok(self.hydro.deform(id, positions)?)
    }

    /// One batch for the bodies in `work` (index, state), each with what
    /// `prepared` holds for it in the same order: its options, and its
    /// sampled sea where it has one (else `water`).
    pub(crate) fn evaluate<H>(
        &self,
        bodies: &[SoakBody<H>],
        water: &Water,
        work: &[(usize, BodyState)],
        prepared: &[crate::scratch::Prepared],
        t: f64,
    ) -> Result<Vec<HydroForces>, soak_hydro::gpu::GpuHydroError> {
        let batch: Vec<GpuBody<'_>> = work
            .iter()
            .zip(prepared)
            .map(|((k, state), p)| GpuBody {
                atlas: self.atlases[*k],
                water: p.sea.as_ref().unwrap_or(water),
                state: *state,
                mass: *bodies[*k].mass_properties(),
                options: p.options,
            })
            .collect();
        self.hydro.evaluate_batch(&batch, t)
    }
}
