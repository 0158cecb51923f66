//! Scene resources on the GPU: per-object uniforms and bind groups, mesh
//! albedo and liquid uploads (cached per `Arc` across frames), and
//! the subsurface term's targets.

use std::collections::HashMap;
use std::sync::{Arc, Weak};

use soak_bake::Mesh;
use wgpu::util::DeviceExt;

use super::camera::to_gpu;
use super::geometry::{MeshLayout, areas, mesh_layout};
use super::gpu_types::{BlurUniform, ObjectUniform, rgba};
use super::pipelines::{ALBEDO_FORMAT, LIQUID_FORMAT, Pipelines, SUBSURFACE_FORMAT};
use super::scene::{Albedo, LiquidImage, RenderObject};
use super::subsurface::Subsurface;
use crate::artist_curve::ArtistCurveGpu;
use crate::gamma::Gamma;
use crate::mean_reflectance::stern_mean_reflectance;
use crate::specular::alpha_from_roughness;

/// A mesh's vertex buffer is reused while the same `Arc<Mesh>` (and segment
/// ids and crease angle) come back: keyed by the allocations' addresses,
/// checked through `Weak`s (an `Arc` mutated in place through `make_mut`
/// loses its `Weak`s, so it is uploaded again).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct MeshKey {
    mesh: usize,
    segments: usize,
    crease: u64,
}

struct CachedMesh {
    mesh: Weak<Mesh>,
    segments: Option<Weak<Vec<u32>>>,
    buffer: wgpu::Buffer,
    layout: MeshLayout,
    /// Surface area (m²) and UV area.
    areas: (f64, f64),
    used: bool,
}

struct CachedAlbedo {
    image: Weak<image::RgbaImage>,
    view: wgpu::TextureView,
    used: bool,
}

/// A liquid texture uploaded for an `Arc<LiquidImage>`, kept while frames
/// draw the same `Arc` (a viewer redrawing one state).
struct CachedLiquid {
    image: Weak<LiquidImage>,
    view: wgpu::TextureView,
    used: bool,
}

/// A mesh ready to draw.
pub(super) struct MeshBuffer {
    pub(super) buffer: wgpu::Buffer,
    pub(super) layout: MeshLayout,
    pub(super) areas: (f64, f64),
}

/// Everything uploaded for one object.
pub(super) struct GpuObject {
    pub(super) vertices: wgpu::Buffer,
    /// Vertices drawn shaded: the walls, out and (open meshes) in.
    pub(super) count: u32,
    /// Of those, the outward walls (the texture-space passes draw these).
    pub(super) front: u32,
    /// Cap vertices after them (depth only).
    pub(super) caps: u32,
    pub(super) bind: wgpu::BindGroup,
    pub(super) casts_shadow: bool,
    pub(super) subsurface: Option<ObjectSubsurface>,
}

pub(super) struct ObjectSubsurface {
    pub(super) irradiance: wgpu::TextureView,
    pub(super) scratch: wgpu::TextureView,
    pub(super) result: wgpu::TextureView,
    /// Two bind groups (u pass, v pass) per Gaussian.
    pub(super) blurs: Vec<(wgpu::BindGroup, wgpu::BindGroup)>,
}

/// Uploads a frame's objects, keeping mesh vertex buffers and albedo
/// textures across frames while the same `Arc`s come back, and the
/// stand-in textures and the sampler of objects without them.
pub(super) struct Uploader {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// Albedo of objects without a texture.
    white: wgpu::TextureView,
    /// Liquid of objects without a liquid texture.
    dry: wgpu::TextureView,
    /// Subsurface result of objects without the subsurface term.
    no_subsurface: wgpu::TextureView,
    linear_sampler: wgpu::Sampler,
    meshes: HashMap<MeshKey, CachedMesh>,
    albedos: HashMap<usize, CachedAlbedo>,
    liquids: HashMap<usize, CachedLiquid>,
}

impl Uploader {
    pub(super) fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
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
        Self {
            device: device.clone(),
            queue: queue.clone(),
            white: pixel("white albedo", ALBEDO_FORMAT, &[255; 4]),
            dry: pixel("dry liquid", LIQUID_FORMAT, &[0; 2]),
            no_subsurface: pixel("no subsurface", SUBSURFACE_FORMAT, &[0; 8]),
            linear_sampler,
            meshes: HashMap::new(),
            albedos: HashMap::new(),
            liquids: HashMap::new(),
        }
    }

    /// Starts a frame: nothing cached is used yet.
    pub(super) fn begin_frame(&mut self) {
        for c in self.meshes.values_mut() {
            c.used = false;
        }
        for c in self.albedos.values_mut() {
            c.used = false;
        }
        for c in self.liquids.values_mut() {
            c.used = false;
        }
    }

    /// Ends a frame: keeps what it used if it succeeded (`ok`), drops the
    /// rest (and everything after a failure).
    pub(super) fn end_frame(&mut self, ok: bool) {
        self.meshes.retain(|_, c| ok && c.used);
        self.albedos.retain(|_, c| ok && c.used);
        self.liquids.retain(|_, c| ok && c.used);
    }

    pub(super) fn cached_mesh(&mut self, o: &RenderObject) -> MeshBuffer {
        let key = MeshKey {
            mesh: Arc::as_ptr(&o.mesh) as usize,
            segments: o.segments.as_ref().map_or(0, |s| Arc::as_ptr(s) as usize),
            crease: o.crease_degrees.to_bits(),
        };
        if let Some(c) = self.meshes.get_mut(&key) {
            let same_mesh = c.mesh.upgrade().is_some_and(|m| Arc::ptr_eq(&m, &o.mesh));
            let same_segments = match (&c.segments, &o.segments) {
                (None, None) => true,
                (Some(w), Some(s)) => w.upgrade().is_some_and(|x| Arc::ptr_eq(&x, s)),
                _ => false,
            };
            if same_mesh && same_segments {
                c.used = true;
                return MeshBuffer {
                    buffer: c.buffer.clone(),
                    layout: c.layout,
                    areas: c.areas,
                };
            }
        }
        let (vertices, layout) = mesh_layout(
            &o.mesh,
            o.segments.as_deref().map(|s| s.as_slice()),
            o.crease_degrees,
        );
        let buffer = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("mesh"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let areas = areas(&o.mesh);
        self.meshes.insert(
            key,
            CachedMesh {
                mesh: Arc::downgrade(&o.mesh),
                segments: o.segments.as_ref().map(Arc::downgrade),
                buffer: buffer.clone(),
                layout,
                areas,
                used: true,
            },
        );
        MeshBuffer {
            buffer,
            layout,
            areas,
        }
    }

    pub(super) fn cached_albedo(&mut self, image: &Arc<image::RgbaImage>) -> wgpu::TextureView {
        let key = Arc::as_ptr(image) as usize;
        if let Some(c) = self.albedos.get_mut(&key) {
            if c.image.upgrade().is_some_and(|i| Arc::ptr_eq(&i, image)) {
                c.used = true;
                return c.view.clone();
            }
        }
        let view = self.upload_albedo(image);
        self.albedos.insert(
            key,
            CachedAlbedo {
                image: Arc::downgrade(image),
                view: view.clone(),
                used: true,
            },
        );
        view
    }

    /// The liquid texture of `image`, uploaded once per `Arc`.
    pub(super) fn cached_liquid(&mut self, image: &Arc<LiquidImage>) -> wgpu::TextureView {
        let key = Arc::as_ptr(image) as usize;
        if let Some(c) = self.liquids.get_mut(&key)
            && c.image.upgrade().is_some_and(|i| Arc::ptr_eq(&i, image))
        {
            c.used = true;
            return c.view.clone();
        }
        let view = self.upload_liquid(image);
        self.liquids.insert(
            key,
            CachedLiquid {
                image: Arc::downgrade(image),
                view: view.clone(),
                used: true,
            },
        );
        view
    }

    pub(super) fn upload_object(
        &self,
        pipelines: &Pipelines,
        o: &RenderObject,
        mesh: MeshBuffer,
        (albedo_view, liquid_view): (Option<wgpu::TextureView>, Option<wgpu::TextureView>),
        subsurface: Option<&Subsurface>,
    ) -> GpuObject {
        let device = &self.device;
        let liquid = &o.material.liquid;
        let (kind, param, curve) = match &o.material.gamma {
            Gamma::Artist { curve } => (4, 0.0, curve.to_gpu()),
            g => {
                let (k, p) = g.gpu_code().unwrap_or((0, 0.0));
                (k, p, bytemuck::Zeroable::zeroed())
            }
        };
        let curve: ArtistCurveGpu = curve;
        let tint = match &o.albedo {
            Albedo::Constant(c) => *c,
            Albedo::Texture { tint, .. } => *tint,
        };
        let sss = subsurface.filter(|_| o.mesh.uvs.is_some() && !o.mesh.triangles.is_empty());
        let (mean_texel_area, targets) = match sss {
            Some(s) => {
                let (world, uv) = mesh.areas;
                let n = f64::from(s.resolution);
                let mean = if uv > 0.0 { world / (uv * n * n) } else { 1.0 };
                (mean, Some(self.subsurface_targets(pipelines, s, mean)))
            }
            None => (1.0, None),
        };
        let uniform = ObjectUniform {
            model: to_gpu(&o.pose.to_homogeneous()),
            albedo: rgba(tint, 1.0),
            transmittance: rgba(liquid.transmittance, liquid.refractive_index),
            optics: [
                stern_mean_reflectance(liquid.refractive_index) as f32,
                liquid.internal_reflectance() as f32,
                liquid.f0() as f32,
                alpha_from_roughness(liquid.film_roughness) as f32,
            ],
            gamma: [param, mean_texel_area as f32, 0.0, 0.0],
            flags: [
                kind,
                u32::from(albedo_view.is_some()),
                u32::from(liquid_view.is_some()),
                u32::from(targets.is_some()),
            ],
            curve,
        };
        let ub = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("object"),
            contents: bytemuck::bytes_of(&uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("object"),
            layout: &pipelines.object_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: ub.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(albedo_view.as_ref().unwrap_or(&self.white)),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(liquid_view.as_ref().unwrap_or(&self.dry)),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(
                        targets.as_ref().map_or(&self.no_subsurface, |t| &t.result),
                    ),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::Sampler(&self.linear_sampler),
                },
            ],
        });
        GpuObject {
            vertices: mesh.buffer,
            count: mesh.layout.front + mesh.layout.back,
            front: mesh.layout.front,
            caps: mesh.layout.caps,
            bind,
            casts_shadow: o.casts_shadow,
            subsurface: targets,
        }
    }

    fn subsurface_targets(
        &self,
        pipelines: &Pipelines,
        s: &Subsurface,
        mean_texel_area: f64,
    ) -> ObjectSubsurface {
        let device = &self.device;
        let texture = |label| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: s.resolution,
                        height: s.resolution,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: SUBSURFACE_FORMAT,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        let irradiance = texture("subsurface irradiance");
        let scratch = texture("subsurface scratch");
        let result = texture("subsurface result");
        let k = s.profile.len() as f64;
        let bind = |source: &wgpu::TextureView, uniform: BlurUniform| {
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("subsurface blur"),
                contents: bytemuck::bytes_of(&uniform),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("subsurface blur"),
                layout: &pipelines.blur_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(source),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&irradiance),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: buffer.as_entire_binding(),
                    },
                ],
            })
        };
        let blurs = s
            .profile
            .iter()
            .map(|g| {
                let sigma = g.variance.max(0.0).sqrt() as f32;
                let weight = rgba(g.weight, 1.0 / k);
                let u = BlurUniform {
                    direction: [1.0, 0.0, sigma, mean_texel_area as f32],
                    weight,
                    mode: [0; 4],
                };
                let v = BlurUniform {
                    direction: [0.0, 1.0, sigma, mean_texel_area as f32],
                    weight,
                    mode: [1, 0, 0, 0],
                };
                (bind(&irradiance, u), bind(&scratch, v))
            })
            .collect();
        ObjectSubsurface {
            irradiance,
            scratch,
            result,
            blurs,
        }
    }

    fn upload_albedo(&self, image: &image::RgbaImage) -> wgpu::TextureView {
        let (w, h) = image.dimensions();
        let levels = 32 - w.max(h).leading_zeros();
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("albedo"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: ALBEDO_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let mut level = std::borrow::Cow::Borrowed(image);
        for mip in 0..levels {
            let (lw, lh) = level.dimensions();
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: mip,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                level.as_raw(),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * lw),
                    rows_per_image: Some(lh),
                },
                wgpu::Extent3d {
                    width: lw,
                    height: lh,
                    depth_or_array_layers: 1,
                },
            );
            if mip + 1 < levels {
                level = std::borrow::Cow::Owned(half_size(&level));
            }
        }
        texture.create_view(&Default::default())
    }

    fn upload_liquid(&self, image: &LiquidImage) -> wgpu::TextureView {
        let (w, h) = image.dimensions();
        let data: Vec<u16> = image
            .as_raw()
            .iter()
            .map(|v| half::f16::from_f32(v.clamp(0.0, 1.0)).to_bits())
            .collect();
        self.device
            .create_texture_with_data(
                &self.queue,
                &wgpu::TextureDescriptor {
                    label: Some("liquid"),
                    size: wgpu::Extent3d {
                        width: w,
                        height: h,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: LIQUID_FORMAT,
                    usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                    view_formats: &[],
                },
                wgpu::util::TextureDataOrder::LayerMajor,
                bytemuck::cast_slice(&data),
            )
            .create_view(&Default::default())
    }
}

/// The next mip level: 2×2 box filter of the linear values, re-encoded
/// to sRGB.
fn half_size(image: &image::RgbaImage) -> image::RgbaImage {
    let (w, h) = image.dimensions();
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    let lut: [f64; 256] = std::array::from_fn(|v| super::colour::srgb_to_linear(v as f64 / 255.0));
    let decode = |v: u8| lut[v as usize];
    image::RgbaImage::from_fn(nw, nh, |x, y| {
        let mut sum = [0.0f64; 4];
        let mut n = 0.0;
        for dy in 0..2 {
            for dx in 0..2 {
                let (sx, sy) = ((2 * x + dx).min(w - 1), (2 * y + dy).min(h - 1));
                let p = image.get_pixel(sx, sy).0;
                for c in 0..3 {
                    sum[c] += decode(p[c]);
                }
                sum[3] += f64::from(p[3]);
                n += 1.0;
            }
        }
        let enc = |v: f64| (super::colour::linear_to_srgb(v / n) * 255.0).round() as u8;
        image::Rgba([enc(sum[0]), enc(sum[1]), enc(sum[2]), (sum[3] / n).round() as u8])
    })
}
