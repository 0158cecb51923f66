//! The offscreen renderer: a [`RenderScene`] in, an sRGB [`image::RgbaImage`]
//! out.

use std::collections::HashMap;

use nalgebra::{Matrix4, Point3, Vector3};
use wgpu::util::DeviceExt;

use super::camera::{light_view_projection, to_gpu};
use super::error::RenderError;
use super::geometry::{arrow_vertices, cull_to_view, water_grid};
use super::gpu_types::{FrameUniform, PostUniform, WaterUniform};
use super::pipelines::{
    ALBEDO_FORMAT, DEPTH_FORMAT, HDR_FORMAT, LIQUID_FORMAT, OUTPUT_FORMAT, Pipelines, SUBSURFACE_FORMAT,
};
use super::scene::{Albedo, DebugView, RenderObject, RenderScene, ToneMap, WaterShape};
use super::upload::{CachedAlbedo, CachedMesh, GpuObject, MeshBuffer, MeshKey};
use crate::fresnel::fresnel_f0;
use crate::specular::alpha_from_roughness;
use soak_gpu::{GpuError, read_back, scoped};

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
    pub(super) device: wgpu::Device,
    pub(super) queue: wgpu::Queue,
    pub(super) options: RendererOptions,
    pub(super) pipelines: Pipelines,
    pub(super) targets: Targets,
    pub(super) shadow_map: wgpu::TextureView,
    pub(super) linear_sampler: wgpu::Sampler,
    pub(super) shadow_sampler: wgpu::Sampler,
    pub(super) white: wgpu::TextureView,
    pub(super) dry: wgpu::TextureView,
    pub(super) no_subsurface: wgpu::TextureView,
    pub(super) meshes: HashMap<MeshKey, CachedMesh>,
    pub(super) albedos: HashMap<usize, CachedAlbedo>,
}

fn check_size(what: &'static str, width: u32, height: u32, max: u32) -> Result<(), RenderError> {
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

pub(super) fn rgba(v: [f64; 3], w: f64) -> [f32; 4] {
    [v[0] as f32, v[1] as f32, v[2] as f32, w as f32]
}

fn vec4(v: &Vector3<f64>, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

fn view_code(view: DebugView) -> u32 {
    match view {
        DebugView::Shaded => 0,
        DebugView::Liquid => 1,
        DebugView::Segments => 2,
        DebugView::Normals => 3,
    }
}

impl Renderer {
    /// A renderer drawing `width`×`height` images on `device`, with 4×
    /// MSAA and a 2048² shadow map.
    ///
    /// # Errors
    /// [`RenderError::ImageSize`] for a zero or oversized image;
    /// [`GpuError::Validation`] if the device cannot compile the
    /// shaders or make the targets (it needs renderable, blendable,
    /// filterable `Rgba16Float`, as WebGPU guarantees);
    /// [`GpuError::OutOfMemory`].
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
        let bytes = u64::from(width) * u64::from(height) * (8 * u64::from(options.sample_count) + 24)
            + 4 * u64::from(s) * u64::from(s);
        scoped::<_, RenderError>(device, "creating the renderer", bytes, || {
            let pipelines = Pipelines::new(device, options.sample_count);
            let targets = Self::make_targets(device, width, height, options.sample_count);
            let shadow_map = device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some("shadow map"),
                    size: wgpu::Extent3d {
                        width: s,
                        height: s,
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
            let linear_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("linear"),
                address_mode_u: wgpu::AddressMode::ClampToEdge,
                address_mode_v: wgpu::AddressMode::ClampToEdge,
                address_mode_w: wgpu::AddressMode::ClampToEdge,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                anisotropy_clamp: 1,
                ..Default::default()
            });
            let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("shadow"),
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                compare: Some(wgpu::CompareFunction::LessEqual),
                ..Default::default()
            });
            let pixel = |label, format, bytes: &[u8]| {
                device
                    .create_texture_with_data(
                        queue,
                        &wgpu::TextureDescriptor {
                            label: Some(label),
                            size: wgpu::Extent3d {
                                width: 1,
                                height: 1,
                                depth_or_array_layers: 1,
                            },
                            mip_level_count: 1,
                            sample_count: 1,
                            dimension: wgpu::TextureDimension::D2,
                            format,
                            usage: wgpu::TextureUsages::TEXTURE_BINDING,
                            view_formats: &[],
                        },
                        wgpu::util::TextureDataOrder::LayerMajor,
                        bytes,
                    )
                    .create_view(&Default::default())
            };
            let white = pixel("white albedo", ALBEDO_FORMAT, &[255; 4]);
            let dry = pixel("dry liquid", LIQUID_FORMAT, &[0; 2]);
            let no_subsurface = pixel("no subsurface", SUBSURFACE_FORMAT, &[0; 8]);
            Ok(Self {
                device: device.clone(),
                queue: queue.clone(),
                options,
                pipelines,
                targets,
                shadow_map,
                linear_sampler,
                shadow_sampler,
                white,
                dry,
                no_subsurface,
                meshes: HashMap::new(),
                albedos: HashMap::new(),
            })
        })
    }

    fn make_targets(device: &wgpu::Device, width: u32, height: u32, samples: u32) -> Targets {
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
    /// [`RenderError::ImageSize`], [`GpuError::OutOfMemory`].
    pub fn resize(&mut self, width: u32, height: u32) -> Result<(), RenderError> {
        if (width, height) == self.size() {
            return Ok(());
        }
        let max = self.device.limits().max_texture_dimension_2d;
        check_size("the image", width, height, max)?;
        let device = self.device.clone();
        let samples = self.options.sample_count;
        let bytes = u64::from(width) * u64::from(height) * (8 * u64::from(samples) + 24);
        self.targets = scoped::<_, RenderError>(&device, "resizing the renderer", bytes, || {
            Ok(Self::make_targets(&device, width, height, samples))
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
    /// GPU work; GPU failures ([`GpuError::OutOfMemory`],
    /// [`GpuError::DeviceLost`], [`GpuError::Validation`]).
    pub fn render(&mut self, scene: &RenderScene) -> Result<image::RgbaImage, RenderError> {
        let data = self.render_padded(scene)?;
        let (w, h) = self.size();
        let row = self.targets.padded_row as usize;
        let mut pixels = Vec::with_capacity((4 * w * h) as usize);
        for y in 0..h as usize {
            pixels.extend_from_slice(&data[y * row..y * row + 4 * w as usize]);
        }
        image::RgbaImage::from_raw(w, h, pixels).ok_or(
            GpuError::Validation {
                what: "reading the image back",
                message: "the readback has the wrong size".into(),
            }
            .into(),
        )
    }

    fn render_padded(&mut self, scene: &RenderScene) -> Result<Vec<u8>, RenderError> {
        scene.validate(self.device.limits().max_texture_dimension_2d)?;
        let device = self.device.clone();
        let bytes = scene_bytes(scene);
        for c in self.meshes.values_mut() {
            c.used = false;
        }
        for c in self.albedos.values_mut() {
            c.used = false;
        }
        let result = scoped::<_, RenderError>(&device, "rendering a frame", bytes, || self.encode(scene));
        // Keep what this frame used, drop the rest (and everything after a
        // failure).
        let ok = result.is_ok();
        self.meshes.retain(|_, c| ok && c.used);
        self.albedos.retain(|_, c| ok && c.used);
        result?;
        let t = &self.targets;
        Ok(read_back(
            &self.device,
            &t.readback,
            u64::from(t.padded_row) * u64::from(t.height),
            "reading the image back",
        )?)
    }

    fn frame_uniform(&self, scene: &RenderScene, shadow: Option<Matrix4<f64>>, radius: f64) -> FrameUniform {
        let (w, h) = self.size();
        let aspect = f64::from(w) / f64::from(h);
        let vp = scene.camera.view_projection(aspect);
        let inv = vp.try_inverse().unwrap_or_else(Matrix4::identity);
        let env = &scene.environment;
        let sun = scene
            .light
            .direction
            .try_normalize(1e-12)
            .unwrap_or_else(Vector3::y);
        let size = f64::from(self.options.shadow_map_size);
        let water = scene.water.as_ref().map_or([0.0; 4], |w| {
            rgba(w.colour, fresnel_f0(w.refractive_index).max(1e-6))
        });
        FrameUniform {
            view_proj: to_gpu(&vp),
            inv_view_proj: to_gpu(&inv),
            light_view_proj: to_gpu(&shadow.unwrap_or_else(Matrix4::identity)),
            eye: vec4(
                &scene.camera.eye.coords,
                if scene.camera.is_orthographic() { 1.0 } else { 0.0 },
            ),
            forward: vec4(&scene.camera.forward(), 0.0),
            sun_direction: vec4(&sun, 0.0),
            sun_irradiance: rgba(scene.light.irradiance, 0.0),
            zenith: rgba(env.zenith, 0.0),
            horizon: rgba(env.horizon, 0.0),
            ground: rgba(env.ground, 0.0),
            sky_mean: rgba(env.sky_mean(), 0.0),
            water,
            shadow: [
                if shadow.is_some() { 1.0 } else { 0.0 },
                (1.0 / size) as f32,
                // One shadow texel of normal offset; half a texel of depth
                // bias (the light's depth range is 4 radii).
                (2.0 * radius / size) as f32,
                (0.5 / size) as f32,
            ],
            view: [view_code(scene.view), 0, 0, 0],
        }
    }

    fn encode(&mut self, scene: &RenderScene) -> Result<(), RenderError> {
        let device = &self.device.clone();
        let shaded = scene.view == DebugView::Shaded;
        // The sun's view of the shadow casters.
        let casters: Vec<&RenderObject> = scene
            .objects
            .iter()
            .filter(|o| o.casts_shadow && !o.mesh.triangles.is_empty())
            .collect();
        let shadow = if scene.shadows && shaded && !casters.is_empty() {
            let (lo, hi) = world_bounds(&casters);
            let centre = nalgebra::center(&lo, &hi);
            let radius = (0.5 * (hi - lo).norm()).max(1e-3);
            Some((
                light_view_projection(&scene.light.direction, &centre, radius),
                radius,
            ))
        } else {
            None
        };
        let frame = self.frame_uniform(scene, shadow.map(|s| s.0), shadow.map_or(1.0, |s| s.1));
        let frame_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame"),
            contents: bytemuck::bytes_of(&frame),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let frame_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &self.pipelines.frame_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: frame_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&self.shadow_map),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&self.shadow_sampler),
                },
            ],
        });
        let matrices_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame matrices"),
            layout: &self.pipelines.matrices_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
            }],
        });

        let subsurface = if shaded { scene.subsurface.as_ref() } else { None };
        let prepared: Vec<(MeshBuffer, Option<wgpu::TextureView>)> = scene
            .objects
            .iter()
            .map(|o| {
                let albedo = match &o.albedo {
                    Albedo::Texture { image, .. } => Some(self.cached_albedo(image)),
                    Albedo::Constant(_) => None,
                };
                (self.cached_mesh(o), albedo)
            })
            .collect();
        let device = &self.device;
        let objects: Vec<GpuObject> = scene
            .objects
            .iter()
            .zip(prepared)
            .map(|(o, (mesh, albedo))| self.upload_object(o, mesh, albedo, subsurface))
            .collect();

        let water = scene.water.as_ref().map(|w| {
            let (cx, cz) = (scene.camera.target.x, scene.camera.target.z);
            let (vertices, all) = match &w.shape {
                WaterShape::Plane { level } => {
                    water_grid(cx, cz, w.extent, 2, |x, z| Point3::new(x, *level, z))
                }
                WaterShape::Gerstner { sea, time } => {
                    water_grid(cx, cz, w.extent, w.resolution, |x, z| sea.particle(x, z, *time))
                }
            };
            let (width, height) = self.size();
            let view_proj = scene.camera.view_projection(f64::from(width) / f64::from(height));
            let indices = cull_to_view(&vertices, &all, &view_proj);
            let uniform = WaterUniform {
                colour: rgba(w.colour, w.opacity.clamp(0.0, 1.0)),
                params: [
                    fresnel_f0(w.refractive_index) as f32,
                    alpha_from_roughness(w.roughness) as f32,
                    (0.6 * w.extent) as f32,
                    (0.95 * w.extent) as f32,
                ],
                centre: [cx as f32, 0.0, cz as f32, 0.0],
            };
            let vb = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("water vertices"),
                contents: bytemuck::cast_slice(&vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
            let ib = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("water indices"),
                contents: bytemuck::cast_slice(&indices),
                usage: wgpu::BufferUsages::INDEX,
            });
            let ub = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("water"),
                contents: bytemuck::bytes_of(&uniform),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("water"),
                layout: &self.pipelines.water_layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: ub.as_entire_binding(),
                }],
            });
            (vb, ib, indices.len() as u32, bind)
        });

        let mut arrow_data = Vec::new();
        for a in &scene.arrows {
            arrow_vertices(a.origin, a.vector, a.radius, a.colour, &mut arrow_data);
        }
        let arrows = (!arrow_data.is_empty()).then(|| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("arrows"),
                contents: bytemuck::cast_slice(&arrow_data),
                usage: wgpu::BufferUsages::VERTEX,
            })
        });

        let linear = matches!(scene.tone_map, ToneMap::Linear) || !shaded;
        let post = PostUniform {
            exposure: [if shaded { scene.exposure as f32 } else { 1.0 }, 0.0, 0.0, 0.0],
            mode: [u32::from(linear), u32::from(scene.dither), 0, 0],
        };
        let post_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("tone map"),
            contents: bytemuck::bytes_of(&post),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let post_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tone map"),
            layout: &self.pipelines.post_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&self.targets.hdr),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: post_buffer.as_entire_binding(),
                },
            ],
        });

        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("soak render"),
        });
        let p = &self.pipelines;

        // 1. Shadow map.
        if shadow.is_some() {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.shadow_map,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&p.shadow);
            pass.set_bind_group(0, &matrices_bind, &[]);
            for o in objects.iter().filter(|o| o.casts_shadow && o.count > 0) {
                pass.set_bind_group(1, &o.bind, &[]);
                pass.set_vertex_buffer(0, o.vertices.slice(..));
                pass.draw(0..o.count, 0..1);
            }
        }

        // 2. Subsurface: irradiance in texture space, then the blurs.
        for o in &objects {
            let Some(sss) = &o.subsurface else { continue };
            {
                let mut pass = color_pass(&mut encoder, "subsurface irradiance", &sss.irradiance, true);
                pass.set_pipeline(&p.irradiance);
                pass.set_bind_group(0, &frame_bind, &[]);
                pass.set_bind_group(1, &o.bind, &[]);
                pass.set_vertex_buffer(0, o.vertices.slice(..));
                pass.draw(0..o.count, 0..1);
            }
            for (k, (u, v)) in sss.blurs.iter().enumerate() {
                {
                    let mut pass = color_pass(&mut encoder, "subsurface blur u", &sss.scratch, true);
                    pass.set_pipeline(&p.blur_sum);
                    pass.set_bind_group(0, u, &[]);
                    pass.draw(0..3, 0..1);
                }
                let mut pass = color_pass(&mut encoder, "subsurface blur v", &sss.result, k == 0);
                pass.set_pipeline(&p.blur_accumulate);
                pass.set_bind_group(0, v, &[]);
                pass.draw(0..3, 0..1);
            }
        }

        // 3. Sky, objects, water.
        let t = &self.targets;
        let (colour, resolve) = match &t.msaa {
            Some(msaa) => (msaa, Some(&t.hdr)),
            None => (&t.hdr, None),
        };
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("scene"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: colour,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &t.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &frame_bind, &[]);
            pass.set_pipeline(&p.sky);
            pass.draw(0..3, 0..1);
            pass.set_pipeline(&p.surface);
            for o in objects.iter().filter(|o| o.count > 0) {
                pass.set_bind_group(1, &o.bind, &[]);
                pass.set_vertex_buffer(0, o.vertices.slice(..));
                pass.draw(0..o.count, 0..1);
            }
            // Nothing of the water may be in view (a camera under it, looking down).
            if let Some((vb, ib, n, bind)) = water.as_ref().filter(|w| w.2 > 0) {
                pass.set_pipeline(&p.water);
                pass.set_bind_group(1, bind, &[]);
                pass.set_vertex_buffer(0, vb.slice(..));
                pass.set_index_buffer(ib.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..*n, 0, 0..1);
            }
        }

        // 4. Arrows over everything (depth cleared), and the MSAA resolve.
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("arrows"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: colour,
                    depth_slice: None,
                    resolve_target: resolve,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &t.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if let Some(buffer) = &arrows {
                pass.set_pipeline(&p.arrow);
                pass.set_bind_group(0, &frame_bind, &[]);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(0..arrow_data.len() as u32, 0..1);
            }
        }

        // 5. Tone map into the output.
        {
            let view = t.output.create_view(&Default::default());
            let mut pass = color_pass(&mut encoder, "tone map", &view, true);
            pass.set_pipeline(&p.post);
            pass.set_bind_group(0, &post_bind, &[]);
            pass.draw(0..3, 0..1);
        }

        // 6. Copy out, rows padded to COPY_BYTES_PER_ROW_ALIGNMENT.
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &t.output,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &t.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(t.padded_row),
                    rows_per_image: Some(t.height),
                },
            },
            wgpu::Extent3d {
                width: t.width,
                height: t.height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        Ok(())
    }
}

fn color_pass<'a>(
    encoder: &'a mut wgpu::CommandEncoder,
    label: &'static str,
    view: &'a wgpu::TextureView,
    clear: bool,
) -> wgpu::RenderPass<'a> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: if clear {
                    wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                } else {
                    wgpu::LoadOp::Load
                },
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// World-space bounding box of the objects' meshes.
fn world_bounds(objects: &[&RenderObject]) -> (Point3<f64>, Point3<f64>) {
    let mut lo = Point3::from([f64::INFINITY; 3]);
    let mut hi = Point3::from([f64::NEG_INFINITY; 3]);
    for o in objects {
        let (a, b) = o.mesh.bounds();
        for i in 0..8 {
            let corner = Point3::new(
                if i & 1 == 0 { a.x } else { b.x },
                if i & 2 == 0 { a.y } else { b.y },
                if i & 4 == 0 { a.z } else { b.z },
            );
            let p = o.pose * corner;
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        }
    }
    (lo, hi)
}

/// A rough count of the bytes a scene uploads, for out-of-memory reports.
fn scene_bytes(scene: &RenderScene) -> u64 {
    let mut bytes = 0u64;
    for o in &scene.objects {
        bytes += 108 * o.mesh.triangles.len() as u64 + 512;
        if let Albedo::Texture { image, .. } = &o.albedo {
            bytes += 6 * u64::from(image.width()) * u64::from(image.height());
        }
        if let Some(l) = &o.liquid {
            bytes += 2 * u64::from(l.width()) * u64::from(l.height());
        }
        if let Some(s) = &scene.subsurface {
            bytes += 24 * u64::from(s.resolution) * u64::from(s.resolution);
        }
    }
    if let Some(w) = &scene.water {
        bytes += 40 * u64::from(w.resolution) * u64::from(w.resolution);
    }
    bytes
}
