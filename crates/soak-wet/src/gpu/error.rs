//! What can go wrong on the GPU path, as values.

use soak_gpu::GpuError;
use soak_hydro::gpu::GpuHydroError;

use crate::error::WetError;

/// A GPU wetting operation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GpuWetError {
    /// The device: no adapter, lost device, out of memory, a buffer above
    /// the binding limit (soak-gpu's errors, shared by every GPU path of soak).
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The water: a surface the kernels do not know, or invalid water
    /// (soak-hydro's encoder of water surfaces for the GPU).
    #[error(transparent)]
    Surface(#[from] GpuHydroError),
    /// The input: the same checks as the CPU path.
    #[error(transparent)]
    Wet(#[from] WetError),
}
