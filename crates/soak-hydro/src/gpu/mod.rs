//! Hydrostatics, drag and mass properties with wgpu compute kernels
//! (feature `gpu`), in agreement with the CPU by test.
//!
//! [`GpuHydro`] keeps atlases on a device the caller provides and evaluates
//! the per-texel sums of [`crate::evaluate`] there: one kernel transforms
//! each texel, finds its depth under the water surface (plane, Gerstner sea,
//! height field, sampled surface or unbounded medium, in
//! [`wgsl::WATER_SURFACE`]) and
//! sums buoyancy and drag terms per workgroup; a second reduces the partials
//! per body. The sums come back (192 bytes per body) and the CPU turns them
//! into [`crate::HydroForces`] with the code [`crate::evaluate`] uses, the
//! implicit drag solve included. Many bodies, each with its own atlas, pose
//! and water, go in one submission and one readback
//! ([`GpuHydro::evaluate_batch`]).
//!
//! A Gerstner sea is read as [`crate::HydroOptions::sea`] asks, as on the
//! CPU: sampled once per body and evaluation on the CPU
//! ([`crate::SurfacePatch`], heights and slopes at a few dozen nodes, with
//! drag the fluid's velocity too) and read by the kernel as per-cell
//! polynomials, or for a body small against the waves (by default, see
//! [`crate::SeaSampling::Auto`]) fitted as one plane on the CPU and summed
//! under it as under any tilted plane with a current; with
//! [`crate::SeaSampling::Exact`] the kernel inverts the
//! Gerstner map at every texel in f32. A spectral sea
//! ([`crate::SpectralSurface`]) is read the same two ways: sampled per body
//! from its tile's fields on the CPU, or, read exactly, its tile evaluated
//! on the device in the batch's own submission (each mode turned to the
//! time on the CPU in f64; its seven layers of coefficients, their inverse
//! FFTs and its fields per node on the device, once per batch however many
//! bodies read it) and its choppy map inverted at every texel.
//!
//! Precision: texel positions are relative to the atlas origin and water
//! parameters relative to the body's world position, computed in f64 and
//! rounded once, so f32 holds its precision anywhere in the world; sums are
//! f32 trees (64 texels per invocation, 64 invocations per workgroup, then the
//! partials). The tests hold GPU and CPU to 1e-4 relative on volumes,
//! forces and masses, and to 1e-4 of the body's diameter on centres.
//!
//! Kernels stay within the WebGPU baseline (no float atomics, subgroups or
//! f64; at most 7 storage buffers per stage), so Mesa's llvmpipe (GL) and
//! lavapipe (Vulkan) run them headless.

mod batch;
mod deform;
mod error;
mod hydro;
mod kernels;
mod layout;
mod mass_properties;
mod sea;
mod surface;
mod waves;
pub mod wgsl;

pub use batch::GpuBody;
pub use deform::GpuTexels;
pub use error::{GpuAtlasId, GpuHydroError};
pub use hydro::{GpuHydro, GpuOptions};
pub use kernels::kernel_sources;
/// The device helpers every GPU path of soak shares, re-exported from soak-gpu.
pub use soak_gpu::{GpuError, adapter_label, headless_device, is_software, test_device};
pub use waves::GpuWaves;
