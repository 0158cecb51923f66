//! [`GpuWetting`] and [`GpuWetBody`]: a body's liquid texture and field
//! resident on a device, stepped by compute kernels.
//!
//! The types and the device's buffers are here; moving a body to and from
//! the device is in `upload`, the encoding of a step in `step`.

use nalgebra::Point3;
use soak_gpu::GpuError;

use super::error::GpuWetError;
use super::kernels::Kernels;
use crate::diffusion::{Diffusion, SubstepPlan};
use crate::environment::EnvironmentResponse;
use crate::grid::VoxelGrid;
use crate::material::{Liquid, Material};

mod step;
mod upload;

/// The wetting kernels compiled on a device the caller provides.
///
/// Upload a body once ([`GpuWetting::upload`]); each [`GpuWetting::step`]
/// then sends a pose, the water's parameters and a few constants (under a
/// kilobyte for calm water) and records one compute pass: the exchange
/// kernel over the texels, and when the body diffuses, the gather, the
/// substeps of the 3×3×3 kernel and the scatter. Nothing comes back until
/// [`GpuWetting::download`].
///
/// The kernels are the CPU's arithmetic in f32 (the CPU accumulates in f64):
/// the parity test holds them to 1e-4 of the saturation per texel and 1e-4
/// relative on the total after a hundred steps. They stay within the WebGPU
/// baseline (at most 7 storage buffers per stage, no atomics, no f64), so
/// Mesa's llvmpipe (GL) and lavapipe (Vulkan) run them headless.
///
/// Only a body's own field runs on the device; a [`crate::SharedField`] is
/// CPU only. The water surface must be one the GPU knows (Plane, FlowPlane,
/// Gerstner, HeightField, Unbounded).
///
/// # Example
/// ```no_run
/// use nalgebra::Isometry3;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_hydro::Water;
/// use soak_wet::gpu::{GpuWetting, headless_device};
/// use soak_wet::prelude::*;
///
/// let (device, queue, _info) = headless_device()?;
/// let gpu = GpuWetting::new(&device, &queue)?;
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(256))?;
/// let wet = Wetting::new(&atlas, Material::sand(), Liquid::water())?.with_diffusion(Diffusion::new(1e-4));
/// let mut body = gpu.upload(&atlas, &wet)?;
/// for k in 0..100 {
///     gpu.step(&mut body, &Isometry3::identity(), &Water::calm(0.0), &Environment::default(), 0.1 * k as f64, 0.1)?;
/// }
/// let h = gpu.download(&body)?;
/// assert_eq!(h.len(), atlas.len());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct GpuWetting {
    device: wgpu::Device,
    queue: wgpu::Queue,
    kernels: Kernels,
    limit: u64,
}

impl std::fmt::Debug for GpuWetting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuWetting")
            .field("limit", &self.limit)
            .finish_non_exhaustive()
    }
}

/// The device buffers of a body's own field.
struct GpuField {
    grid: VoxelGrid,
    count_max: u32,
    defined: u32,
    gather: wgpu::BindGroup,
    /// Substep reading `a` and writing `b`, and the reverse.
    substep: [wgpu::BindGroup; 2],
    /// Finish reading the result from `a` or from `b`.
    finish: [wgpu::BindGroup; 2],
    activity: wgpu::BindGroup,
    delta: wgpu::BindGroup,
    residual: wgpu::BindGroup,
    scatter: wgpu::BindGroup,
    bytes: u64,
}

/// A body on the device: its texels, liquid texture and (with diffusion)
/// its field, with a copy of the settings it was uploaded with.
pub struct GpuWetBody {
    texels: usize,
    origin: Point3<f64>,
    radius: f64,
    material: Material,
    liquid: Liquid,
    response: EnvironmentResponse,
    diffusion: Option<Diffusion>,
    texel_buf: wgpu::Buffer,
    liquid_buf: wgpu::Buffer,
    permeability_buf: wgpu::Buffer,
    body_buf: wgpu::Buffer,
    radii_buf: wgpu::Buffer,
    params_buf: wgpu::Buffer,
    staging: wgpu::Buffer,
    waves: (wgpu::Buffer, usize),
    heights: (wgpu::Buffer, usize),
    exchange: wgpu::BindGroup,
    field: Option<GpuField>,
}

impl std::fmt::Debug for GpuWetBody {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuWetBody")
            .field("texels", &self.texels)
            .field("diffusion", &self.diffusion)
            .field("voxels", &self.field.as_ref().map(|f| f.defined))
            .finish_non_exhaustive()
    }
}

impl GpuWetBody {
    /// Number of texels.
    pub fn texels(&self) -> usize {
        self.texels
    }

    /// The field's grid (object space), when the body diffuses.
    pub fn field_grid(&self) -> Option<VoxelGrid> {
        self.field.as_ref().map(|f| f.grid)
    }

    /// Device bytes the field holds; zero without diffusion.
    pub fn field_bytes(&self) -> u64 {
        self.field.as_ref().map_or(0, |f| f.bytes)
    }
}

/// What a [`GpuWetting::step`] recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GpuStep {
    /// The diffusion substeps, when the body diffuses.
    pub diffusion: Option<SubstepPlan>,
}

const STORAGE: wgpu::BufferUsages = wgpu::BufferUsages::STORAGE
    .union(wgpu::BufferUsages::COPY_DST)
    .union(wgpu::BufferUsages::COPY_SRC);

impl GpuWetting {
    /// Compiles the kernels on `device`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, GpuWetError> {
        let limits = device.limits();
        let limit = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            kernels: Kernels::new(device)?,
            limit,
        })
    }

    fn buffer(&self, label: &'static str, bytes: u64) -> Result<wgpu::Buffer, GpuError> {
        if bytes > self.limit {
            return Err(GpuError::TooLarge {
                what: label,
                needed: bytes,
                limit: self.limit,
            });
        }
        Ok(self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes.max(16).next_multiple_of(16),
            usage: STORAGE,
            mapped_at_creation: false,
        }))
    }

    fn filled<T: bytemuck::Pod>(&self, label: &'static str, data: &[T]) -> Result<wgpu::Buffer, GpuError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let b = self.buffer(label, bytes.len() as u64)?;
        self.queue.write_buffer(&b, 0, bytes);
        Ok(b)
    }

    /// Waits until the device has finished every submitted step (for
    /// timing).
    pub fn wait(&self) -> Result<(), GpuWetError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::DeviceLost {
                what: "waiting for wetting steps",
                reason: e.to_string(),
            })?;
        Ok(())
    }
}
