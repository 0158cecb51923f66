//! The renderer's render targets: the size-dependent colour, depth, output
//! and read-back buffers (reallocated on a resize), and the sun's shadow map.

use super::error::RenderError;
use super::pipelines::{DEPTH_FORMAT, HDR_FORMAT, OUTPUT_FORMAT};

/// Size-dependent render targets.
pub(super) struct Targets {
    pub(super) width: u32,
    pub(super) height: u32,
    /// MSAA colour (when `sample_count > 1`).
    pub(super) msaa: Option<wgpu::TextureView>,
    /// Resolved linear radiance.
    pub(super) hdr: wgpu::TextureView,
    pub(super) depth: wgpu::TextureView,
    pub(super) output: wgpu::Texture,
    pub(super) readback: wgpu::Buffer,
    pub(super) padded_row: u32,
}

impl Targets {
    /// Targets for `width`×`height` images with `samples` MSAA samples.
    pub(super) fn new(device: &wgpu::Device, width: u32, height: u32, samples: u32) -> Self {
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        use wgpu::TextureUsages as U;
        let msaa = (samples > 1).then(|| {
            texture("msaa colour", HDR_FORMAT, samples, U::RENDER_ATTACHMENT).create_view(&Default::default())
        });
        let hdr = texture("hdr", HDR_FORMAT, 1, U::RENDER_ATTACHMENT | U::TEXTURE_BINDING)
            .create_view(&Default::default());
        let depth =
            texture("depth", DEPTH_FORMAT, samples, U::RENDER_ATTACHMENT).create_view(&Default::default());
        let output = texture("output", OUTPUT_FORMAT, 1, U::RENDER_ATTACHMENT | U::COPY_SRC);
        let padded_row =
            (4 * width).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded_row) * u64::from(height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Targets {
            width,
            height,
            msaa,
            hdr,
            depth,
            output,
            readback,
            padded_row,
        }
    }

    /// Bytes of targets for `width`×`height` images with `samples` MSAA
    /// samples, for out-of-memory reports.
    pub(super) fn bytes(width: u32, height: u32, samples: u32) -> u64 {
        u64::from(width) * u64::from(height) * (8 * u64::from(samples) + 24)
    }
}

/// The sun's shadow map: a square depth texture and its comparison sampler.
pub(super) struct ShadowMap {
    pub(super) view: wgpu::TextureView,
    pub(super) sampler: wgpu::Sampler,
    /// Side, texels.
    pub(super) size: u32,
}

impl ShadowMap {
    pub(super) fn new(device: &wgpu::Device, size: u32) -> Self {
        let view = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("shadow map"),
                size: wgpu::Extent3d {
                    width: size,
                    height: size,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: DEPTH_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default());
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        Self { view, sampler, size }
    }

    /// Bytes of a shadow map of side `size`, for out-of-memory reports.
    pub(super) fn bytes(size: u32) -> u64 {
        4 * u64::from(size) * u64::from(size)
    }
}

/// Refuses a zero-sized image or one larger than the device's `max`.
pub(super) fn check_size(what: &'static str, width: u32, height: u32, max: u32) -> Result<(), RenderError> {
    if width == 0 || height == 0 || width > max || height > max {
        return Err(RenderError::ImageSize {
            what,
            width,
            height,
            max,
        });
    }
    Ok(())
}
