//! What can go wrong on the GPU path, as values.

use soak_hydro::gpu::GpuError;

use crate::error::WetError;

/// A GPU wetting operation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GpuWetError {
    /// The device: no adapter, lost device, out of memory, a buffer above
    /// the binding limit, a water surface the kernels do not know
    /// (soak-hydro's GPU errors, shared by every GPU path of soak).
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The input: the same checks as the CPU path.
    #[error(transparent)]
    Wet(#[from] WetError),
}
