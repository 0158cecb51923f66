//! The WGSL optics on the GPU: one compute pass over a table of
//! [`OpticsInput`] rows, the GPU side of the parity check whose CPU side is
//! [`evaluate_table`](crate::evaluate_table).

use std::borrow::Cow;

use wgpu::util::DeviceExt;

use super::error::RenderError;
use crate::artist_curve::ArtistCurveGpu;
use crate::optics_table::{OpticsInput, OpticsOutput, WET_OPTICS_WGSL};
use soak_gpu::{GpuError, read_back, scoped};

const KERNEL: &str = include_str!("../../shaders/optics_kernel.wgsl");

/// The parity kernel's full WGSL: [`WET_OPTICS_WGSL`] followed by an entry
/// point `main` that writes `evaluate_optics(inputs[i])` and
/// `gamma_artist(inputs[i].saturation, curve)`.
pub fn optics_kernel_source() -> String {
    format!("{WET_OPTICS_WGSL}\n{KERNEL}")
}

/// What [`evaluate_table_gpu`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuOpticsTable {
    /// `evaluate_optics` of each input row, in order.
    pub outputs: Vec<OpticsOutput>,
    /// `gamma_artist(saturation, curve)` of each input row, in order.
    pub artist: Vec<f32>,
}

/// Evaluates the WGSL `evaluate_optics` (and `gamma_artist` with `curve`)
/// on `device` for every row of `inputs`: one upload, one dispatch, one
/// readback. Compare with [`evaluate_table`](crate::evaluate_table) and
/// [`ArtistCurveGpu::eval`].
///
/// # Errors
/// [`GpuError::OutOfMemory`], [`GpuError::Validation`] (e.g. a table
/// above the device's storage binding limit) or
/// [`GpuError::DeviceLost`].
pub fn evaluate_table_gpu(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    inputs: &[OpticsInput],
    curve: &ArtistCurveGpu,
) -> Result<GpuOpticsTable, RenderError> {
    if inputs.is_empty() {
        return Ok(GpuOpticsTable {
            outputs: Vec::new(),
            artist: Vec::new(),
        });
    }
    let n = inputs.len() as u64;
    let out_bytes = n * size_of::<OpticsOutput>() as u64;
    let artist_bytes = n * 4;
    let total = n * size_of::<OpticsInput>() as u64 + 2 * (out_bytes + artist_bytes);
    let (staging, staging_artist) =
        scoped::<_, RenderError>(device, "evaluating the optics table", total, || {
            let source = optics_kernel_source();
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("soak-shade optics parity"),
                source: wgpu::ShaderSource::Wgsl(Cow::Owned(source)),
            });
            let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("soak-shade optics parity"),
                layout: None,
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            });
            let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("optics inputs"),
                contents: bytemuck::cast_slice(inputs),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let output = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("optics outputs"),
                size: out_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("artist curve"),
                contents: bytemuck::bytes_of(curve),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let artist = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("artist outputs"),
                size: artist_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let staging = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("optics readback"),
                size: out_bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let staging_artist = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("artist readback"),
                size: artist_bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let layout = pipeline.get_bind_group_layout(0);
            let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("optics parity"),
                layout: &layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: input.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: output.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: uniform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: artist.as_entire_binding(),
                    },
                ],
            });
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("optics parity"),
            });
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("optics parity"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &bind, &[]);
                let groups = inputs.len().div_ceil(64) as u32;
                // Stay within 65,535 workgroups per dimension.
                let x = groups.min(65_535);
                let y = groups.div_ceil(x);
                if y > 1 {
                    return Err(GpuError::Validation {
                        what: "evaluating the optics table",
                        message: format!("{} rows exceed one dispatch of 65,535 × 64", inputs.len()),
                    }
                    .into());
                }
                pass.dispatch_workgroups(x, 1, 1);
            }
            encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, out_bytes);
            encoder.copy_buffer_to_buffer(&artist, 0, &staging_artist, 0, artist_bytes);
            queue.submit([encoder.finish()]);
            Ok((staging, staging_artist))
        })?;
    let bytes = read_back(device, &staging, out_bytes, "reading the optics table")?;
    let artist = read_back(device, &staging_artist, artist_bytes, "reading the optics table")?;
    Ok(GpuOpticsTable {
        outputs: bytemuck::pod_collect_to_vec(&bytes),
        artist: bytemuck::pod_collect_to_vec(&artist),
    })
}
