//! The offscreen renderer: a [`RenderScene`] in, an sRGB [`image::RgbaImage`]
//! out. Its render targets are in `targets`, a frame's uploads and encoding
//! in `frame` and `passes`, the read-back in `readback`.

use soak_gpu::scoped;

use super::error::RenderError;
use super::frame::{FrameGpu, encode, scene_bytes};
use super::pipelines::Pipelines;
use super::readback::{read_padded, unpad};
use super::scene::RenderScene;
use super::targets::{ShadowMap, Targets, check_size};
use super::upload::Uploader;

/// Construction-time settings of a [`Renderer`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RendererOptions {
    /// MSAA samples per pixel: 1 or 4 (default 4).
    pub sample_count: u32,
    /// Side of the sun's shadow map, texels (default 2048).
    pub shadow_map_size: u32,
}

impl Default for RendererOptions {
    fn default() -> Self {
        Self {
            sample_count: 4,
            shadow_map_size: 2048,
        }
    }
}

/// An offscreen wgpu renderer for soak scenes: wetting meshes (the
/// Lekner–Dorf dry/wet blend of [`crate::WetMaterial`]), water, sky, sun
/// shadows, force arrows and debug views, read back as an 8-bit sRGB image.
///
/// It keeps a clone of the device and queue it is given (GPU code takes a
/// device, it does not make one), its pipelines and its render targets.
/// Each [`Renderer::render`] uploads the frame's uniforms, liquid textures
/// and water; mesh vertex buffers and albedo textures are kept while the
/// same `Arc<Mesh>` / `Arc<RgbaImage>` come back in the next frame (an `Arc`
/// changed through `Arc::make_mut` is uploaded again).
///
/// # Example
/// ```no_run
/// use nalgebra::{Isometry3, Point3};
/// use soak_shade::render::{Camera, RenderObject, RenderScene, Renderer, RenderWater, headless_device};
///
/// let (device, queue, _info) = headless_device()?;
/// let mut renderer = Renderer::new(&device, &queue, 320, 180)?;
/// let mut scene = RenderScene::new(Camera::perspective(
///     Point3::new(3.0, 2.0, 4.0),
///     Point3::new(0.0, 0.3, 0.0),
///     40.0,
/// ));
/// scene.objects.push(RenderObject::new(
///     soak_bake::builtin::sphere(0.5, 48, 24),
///     Isometry3::translation(0.0, 0.3, 0.0),
/// ));
/// scene.water = Some(RenderWater::plane(0.0));
/// let image = renderer.render(&scene)?;
/// assert_eq!(image.dimensions(), (320, 180));
/// # Ok::<(), soak_shade::render::RenderError>(())
/// ```
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    options: RendererOptions,
    pipelines: Pipelines,
    targets: Targets,
    shadow_map: ShadowMap,
    uploader: Uploader,
}

impl Renderer {
    /// A renderer drawing `width`×`height` images on `device`, with 4×
    /// MSAA and a 2048² shadow map.
    ///
    /// # Errors
    /// [`RenderError::ImageSize`] for a zero or oversized image;
    /// [`GpuError::Validation`](soak_gpu::GpuError::Validation) if the device cannot compile the
    /// shaders or make the targets (it needs renderable, blendable,
    /// filterable `Rgba16Float`, as WebGPU guarantees);
    /// [`GpuError::OutOfMemory`](soak_gpu::GpuError::OutOfMemory).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        Self::with_options(device, queue, width, height, RendererOptions::default())
    }

    /// A renderer with explicit [`RendererOptions`].
    ///
    /// # Errors
    /// As [`Renderer::new`]; [`RenderError::SampleCount`] for a sample
    /// count other than 1 or 4.
    pub fn with_options(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        width: u32,
        height: u32,
        options: RendererOptions,
    ) -> Result<Self, RenderError> {
        if !matches!(options.sample_count, 1 | 4) {
            return Err(RenderError::SampleCount(options.sample_count));
        }
        let max = device.limits().max_texture_dimension_2d;
        check_size("the image", width, height, max)?;
        let s = options.shadow_map_size;
        check_size("the shadow map", s, s, max)?;
        let bytes = Targets::bytes(width, height, options.sample_count) + ShadowMap::bytes(s);
        scoped::<_, RenderError>(device, "creating the renderer", bytes, || {
            let pipelines = Pipelines::new(device, options.sample_count);
            let targets = Targets::new(device, width, height, options.sample_count);
            let shadow_map = ShadowMap::new(device, s);
            let uploader = Uploader::new(device, queue);
            Ok(Self {
                device: device.clone(),
                queue: queue.clone(),
                options,
                pipelines,
                targets,
                shadow_map,
                uploader,
            })
        })
    }

    /// Image size, pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.targets.width, self.targets.height)
    }

    /// The options the renderer was made with.
    pub fn options(&self) -> RendererOptions {
        self.options
    }

    /// Changes the image size (reallocates the targets).
    ///
    /// # Errors
    /// [`RenderError::ImageSize`], [`GpuError::OutOfMemory`](soak_gpu::GpuError::OutOfMemory).
    pub fn resize(&mut self, width: u32, height: u32) -> Result<(), RenderError> {
        if (width, height) == self.size() {
            return Ok(());
        }
        let max = self.device.limits().max_texture_dimension_2d;
        check_size("the image", width, height, max)?;
        let device = self.device.clone();
        let samples = self.options.sample_count;
        let bytes = Targets::bytes(width, height, samples);
        self.targets = scoped::<_, RenderError>(&device, "resizing the renderer", bytes, || {
            Ok(Targets::new(&device, width, height, samples))
        })?;
        Ok(())
    }

    /// Renders `scene` and reads the image back: `width`×`height`, 8-bit
    /// sRGB RGBA, alpha 255, row 0 at the top.
    ///
    /// # Errors
    /// Scene problems ([`RenderError::Material`], [`RenderError::Mesh`],
    /// [`RenderError::MissingUvs`], [`RenderError::Texture`],
    /// [`RenderError::SegmentCount`], [`RenderError::Scene`]) before any
    /// GPU work; GPU failures ([`GpuError::OutOfMemory`](soak_gpu::GpuError::OutOfMemory),
    /// [`GpuError::DeviceLost`](soak_gpu::GpuError::DeviceLost), [`GpuError::Validation`](soak_gpu::GpuError::Validation)).
    pub fn render(&mut self, scene: &RenderScene) -> Result<image::RgbaImage, RenderError> {
        let data = self.render_padded(scene)?;
        unpad(&self.targets, &data)
    }

    fn render_padded(&mut self, scene: &RenderScene) -> Result<Vec<u8>, RenderError> {
        scene.validate(self.device.limits().max_texture_dimension_2d)?;
        let bytes = scene_bytes(scene);
        self.uploader.begin_frame();
        let gpu = FrameGpu {
            device: &self.device,
            queue: &self.queue,
            pipelines: &self.pipelines,
            targets: &self.targets,
            shadow_map: &self.shadow_map,
        };
        let uploader = &mut self.uploader;
        let result = scoped::<_, RenderError>(&self.device, "rendering a frame", bytes, || {
            encode(&gpu, uploader, scene)
        });
        // Keep what this frame used, drop the rest (and everything after a
        // failure).
        uploader.end_frame(result.is_ok());
        result?;
        read_padded(&self.device, &self.targets)
    }
}
