//! The GPU path for the commands that time or run it (`gpu` feature).

use soak_bake::Atlas;
use soak_hydro::{BodyState, HydroForces, HydroOptions, MassProperties, Water};

/// A headless device with the hydrostatics kernels, or nothing.
pub struct Gpu {
    #[cfg(feature = "gpu")]
    hydro: soak_hydro::gpu::GpuHydro,
    /// Adapter name and backend, flagged when it is a software adapter.
    pub label: String,
}

impl Gpu {
    /// A device if the build has the `gpu` feature and an adapter exists;
    /// otherwise `Err` with the reason.
    pub fn new() -> Result<Self, String> {
        #[cfg(feature = "gpu")]
        {
            let (device, queue, info) = soak_hydro::gpu::headless_device().map_err(|e| e.to_string())?;
            let hydro = soak_hydro::gpu::GpuHydro::new(&device, &queue).map_err(|e| e.to_string())?;
            let mut label = soak_hydro::gpu::adapter_label(&info);
            if soak_hydro::gpu::is_software(&info) {
                label.push_str(" — a software adapter: its times are CPU times, not GPU times");
            }
            Ok(Self { hydro, label })
        }
        #[cfg(not(feature = "gpu"))]
        Err("this soak was built without its `gpu` feature".into())
    }

    /// Mass properties of `atlas` under `model`, computed on the device.
    pub fn mass_properties(
        &mut self,
        atlas: &Atlas,
        model: &soak_hydro::MassModel,
    ) -> anyhow::Result<MassProperties> {
        #[cfg(feature = "gpu")]
        {
            let id = self.hydro.upload(atlas)?;
            Ok(self.hydro.mass_properties(id, model)?)
        }
        #[cfg(not(feature = "gpu"))]
        {
            let _ = (atlas, model);
            anyhow::bail!("this soak was built without its `gpu` feature")
        }
    }

    /// Uploads `atlas`, evaluates it once and times `runs` more evaluations
    /// (median, ms, upload excluded).
    pub fn evaluate_timed(
        &mut self,
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        options: &HydroOptions,
        runs: usize,
    ) -> anyhow::Result<(HydroForces, f64)> {
        #[cfg(feature = "gpu")]
        {
            let id = self.hydro.upload(atlas)?;
            let forces = self.hydro.evaluate(id, water, state, mass, 0.0, options)?;
            let ms =
                crate::common::time_ms(runs, || self.hydro.evaluate(id, water, state, mass, 0.0, options));
            Ok((forces, ms))
        }
        #[cfg(not(feature = "gpu"))]
        {
            let _ = (atlas, water, state, mass, options, runs);
            anyhow::bail!("this soak was built without its `gpu` feature")
        }
    }
}
