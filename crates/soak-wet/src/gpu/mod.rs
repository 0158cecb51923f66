//! Wetting with wgpu compute kernels (feature `gpu`), in agreement with the
//! CPU by test.
//!
//! [`GpuWetting`] compiles nine kernels on a device the caller provides;
//! [`GpuWetBody`] keeps one body's texels, liquid texture and (with
//! diffusion) its voxel field on that device:
//!
//! - `exchange.wgsl`: absorption, rain and evaporation per texel, with the
//!   water depth from soak-hydro's water surfaces ([`soak_hydro::gpu::wgsl`]; plane,
//!   a plane whose current changes over space, Gerstner sea, height field);
//! - `gather.wgsl`: texels → voxels (liquid volume or Shepard average), one
//!   invocation per defined voxel summing its texels in a fixed order (no
//!   atomics, so results are deterministic);
//! - `substep.wgsl`: the 3×3×3 kernel, ping-ponging between two buffers,
//!   as many substeps as the CPU plans;
//! - `finish.wgsl`, `activity.wgsl`: per voxel, its change and whether
//!   its neighbourhood changed;
//! - `delta.wgsl`, `residual.wgsl` (conservative): per texel its smooth
//!   share of the change, per voxel what those shares leave over;
//! - `scatter.wgsl`: voxels → texels.
//!
//! The binning (which texel lies in which voxel, neighbour lists) is built
//! on the CPU at upload with the same code as [`crate::Wetting`] and never
//! changes (a body's field lives in object space). Device helpers come from
//! soak-gpu ([`headless_device`], [`adapter_label`], [`is_software`]).

mod error;
mod kernels;
mod layout;
mod wetting;

pub use error::GpuWetError;
pub use kernels::kernel_sources;
pub use soak_gpu::{GpuError, adapter_label, headless_device, is_software, test_device};
pub use wetting::{GpuStep, GpuWetBody, GpuWetting};
