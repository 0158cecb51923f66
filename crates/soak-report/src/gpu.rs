//! The GPU path for the reports that time or run it (`gpu` feature).

use soak_bake::Atlas;
use soak_hydro::{BodyState, HydroForces, HydroOptions, MassProperties, Water};

/// The GPU path could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GpuError {
    /// The crate was built without its `gpu` feature.
    #[error("this soak was built without its `gpu` feature")]
    NotBuilt,
    /// No device could be opened.
    #[cfg(feature = "gpu")]
    #[error(transparent)]
    Device(#[from] soak_hydro::gpu::GpuError),
    /// The hydrostatics kernels failed.
    #[cfg(feature = "gpu")]
    #[error(transparent)]
    Hydro(#[from] soak_hydro::gpu::GpuHydroError),
}

/// A headless device with the hydrostatics kernels, or nothing.
pub struct Gpu {
    #[cfg(feature = "gpu")]
    hydro: soak_hydro::gpu::GpuHydro,
    /// Adapter name and backend, flagged when it is a software adapter.
    pub label: String,
}

impl Gpu {
    /// A device if the build has the `gpu` feature and an adapter exists.
    ///
    /// # Errors
    /// [`GpuError::NotBuilt`] without the `gpu` feature; otherwise the
    /// reason no device or kernels could be made.
    pub fn new() -> Result<Self, GpuError> {
        #[cfg(feature = "gpu")]
        {
            let (device, queue, info) = soak_hydro::gpu::headless_device()?;
            let hydro = soak_hydro::gpu::GpuHydro::new(&device, &queue)?;
            let mut label = soak_hydro::gpu::adapter_label(&info);
            if soak_hydro::gpu::is_software(&info) {
                label.push_str(" — a software adapter: its times are CPU times, not GPU times");
            }
            Ok(Self { hydro, label })
        }
        #[cfg(not(feature = "gpu"))]
        Err(GpuError::NotBuilt)
    }

    /// Mass properties of `atlas` under `model`, computed on the device.
    ///
    /// # Errors
    /// The device's error uploading or evaluating.
    pub fn mass_properties(
        &mut self,
        atlas: &Atlas,
        model: &soak_hydro::MassModel,
    ) -> Result<MassProperties, GpuError> {
        #[cfg(feature = "gpu")]
        {
            let id = self.hydro.upload(atlas)?;
            Ok(self.hydro.mass_properties(id, model)?)
        }
        #[cfg(not(feature = "gpu"))]
        {
            let _ = (atlas, model);
            Err(GpuError::NotBuilt)
        }
    }

    /// Uploads `atlas`, evaluates it once and times `runs` more evaluations
    /// (median, ms, upload excluded).
    ///
    /// # Errors
    /// The device's error uploading or evaluating.
    pub fn evaluate_timed(
        &mut self,
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        options: &HydroOptions,
        runs: usize,
    ) -> Result<(HydroForces, f64), GpuError> {
        #[cfg(feature = "gpu")]
        {
            let id = self.hydro.upload(atlas)?;
            let forces = self.hydro.evaluate(id, water, state, mass, 0.0, options)?;
            let ms = median_ms(runs, || self.hydro.evaluate(id, water, state, mass, 0.0, options));
            Ok((forces, ms))
        }
        #[cfg(not(feature = "gpu"))]
        {
            let _ = (atlas, water, state, mass, options, runs);
            Err(GpuError::NotBuilt)
        }
    }
}

/// Median time of `runs` calls of `f`, ms.
#[cfg(feature = "gpu")]
fn median_ms<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut t: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let s = std::time::Instant::now();
            std::hint::black_box(f());
            s.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}
