//! One frame, encoded: the sun's view of the shadow casters, the frame
//! uniform and its bind groups, the objects, water, arrows and tone-map
//! settings uploaded, then the render passes (`passes`) and the copy
//! into the read-back buffer, submitted as one command buffer.

use nalgebra::{Matrix4, Point3, Vector3};
use wgpu::util::DeviceExt;

use super::camera::{light_view_projection, to_gpu};
use super::error::RenderError;
use super::geometry::{arrow_vertices, cull_to_view, inner_water, water_grid};
use super::gpu_types::{FrameUniform, PostUniform, WaterUniform, rgba, vec4};
use super::passes::{
    ArrowDraw, WaterDraw, arrow_pass, scene_pass, shadow_pass, subsurface_passes, tone_map_pass,
};
use super::pipelines::Pipelines;
use super::readback::copy_out;
use super::scene::{Albedo, DebugView, RenderObject, RenderScene, ToneMap, WaterShape};
use super::targets::{ShadowMap, Targets};
use super::upload::{GpuObject, MeshBuffer, Uploader};
use crate::fresnel::fresnel_f0;
use crate::specular::alpha_from_roughness;

/// What encoding a frame draws with: the renderer's device, pipelines and
/// targets.
pub(super) struct FrameGpu<'a> {
    pub(super) device: &'a wgpu::Device,
    pub(super) queue: &'a wgpu::Queue,
    pub(super) pipelines: &'a Pipelines,
    pub(super) targets: &'a Targets,
    pub(super) shadow_map: &'a ShadowMap,
}

/// The frame's bind groups of the frame uniform: with the shadow map (for
/// shading) and the matrices alone (for the shadow pass).
struct FrameBinds {
    frame: wgpu::BindGroup,
    matrices: wgpu::BindGroup,
}

/// Uploads `scene`, records its passes and the read-back copy, and submits
/// them. Mesh and albedo uploads go through `uploader`'s caches.
pub(super) fn encode(
    gpu: &FrameGpu<'_>,
    uploader: &mut Uploader,
    scene: &RenderScene,
) -> Result<(), RenderError> {
    let device = gpu.device;
    let shaded = scene.view == DebugView::Shaded;
    let shadow = sun_view(scene, shaded);
    let frame = frame_uniform(gpu, scene, shadow.map(|s| s.0), shadow.map_or(1.0, |s| s.1));
    let binds = frame_binds(gpu, &frame);

    let subsurface = if shaded { scene.subsurface.as_ref() } else { None };
    let objects = upload_objects(gpu.pipelines, uploader, scene, subsurface);
    let water = upload_water(gpu, scene);
    let arrows = upload_arrows(device, scene);
    let post_bind = tone_map_bind(gpu, scene, shaded);

    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("soak render"),
    });
    let (p, t) = (gpu.pipelines, gpu.targets);
    if shadow.is_some() {
        shadow_pass(&mut encoder, p, gpu.shadow_map, &binds.matrices, &objects);
    }
    subsurface_passes(&mut encoder, p, &binds.frame, &objects);
    scene_pass(&mut encoder, p, t, &binds.frame, &objects, water.as_ref());
    arrow_pass(&mut encoder, p, t, &binds.frame, arrows.as_ref());
    tone_map_pass(&mut encoder, p, t, &post_bind);
    copy_out(&mut encoder, t);
    gpu.queue.submit([encoder.finish()]);
    Ok(())
}

/// The sun's view of the shadow casters (light view-projection and the
/// radius of their bounding sphere), when the frame draws shadows.
fn sun_view(scene: &RenderScene, shaded: bool) -> Option<(Matrix4<f64>, f64)> {
    let casters: Vec<&RenderObject> = scene
        .objects
        .iter()
        .filter(|o| o.casts_shadow && !o.mesh.triangles.is_empty())
        .collect();
    if scene.shadows && shaded && !casters.is_empty() {
        let (lo, hi) = world_bounds(&casters);
        let centre = nalgebra::center(&lo, &hi);
        let radius = (0.5 * (hi - lo).norm()).max(1e-3);
        Some((
            light_view_projection(&scene.light.direction, &centre, radius),
            radius,
        ))
    } else {
        None
    }
}

fn view_code(view: DebugView) -> u32 {
    match view {
        DebugView::Shaded => 0,
        DebugView::Liquid => 1,
        DebugView::Segments => 2,
        DebugView::Normals => 3,
    }
}

/// The frame uniform: camera, sun, sky, water colour, shadow settings and
/// debug view.
fn frame_uniform(
    gpu: &FrameGpu<'_>,
    scene: &RenderScene,
    shadow: Option<Matrix4<f64>>,
    radius: f64,
) -> FrameUniform {
    let (w, h) = (gpu.targets.width, gpu.targets.height);
    let aspect = f64::from(w) / f64::from(h);
    let vp = scene.camera.view_projection(aspect);
    let inv = vp.try_inverse().unwrap_or_else(Matrix4::identity);
    let env = &scene.environment;
    let sun = scene
        .light
        .direction
        .try_normalize(1e-12)
        .unwrap_or_else(Vector3::y);
    let size = f64::from(gpu.shadow_map.size);
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

fn frame_binds(gpu: &FrameGpu<'_>, frame: &FrameUniform) -> FrameBinds {
    let device = gpu.device;
    let frame_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("frame"),
        contents: bytemuck::bytes_of(frame),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let frame = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("frame"),
        layout: &gpu.pipelines.frame_layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&gpu.shadow_map.view),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::Sampler(&gpu.shadow_map.sampler),
            },
        ],
    });
    let matrices = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("frame matrices"),
        layout: &gpu.pipelines.matrices_layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: frame_buffer.as_entire_binding(),
        }],
    });
    FrameBinds { frame, matrices }
}

/// Every object's mesh, albedo, liquid texture, uniform and subsurface
/// targets.
fn upload_objects(
    pipelines: &Pipelines,
    uploader: &mut Uploader,
    scene: &RenderScene,
    subsurface: Option<&super::subsurface::Subsurface>,
) -> Vec<GpuObject> {
    type Views = (Option<wgpu::TextureView>, Option<wgpu::TextureView>);
    let prepared: Vec<(MeshBuffer, Views)> = scene
        .objects
        .iter()
        .map(|o| {
            let albedo = match &o.albedo {
                Albedo::Texture { image, .. } => Some(uploader.cached_albedo(image)),
                Albedo::Constant(_) => None,
            };
            let liquid = o.liquid.as_ref().map(|image| uploader.cached_liquid(image));
            (uploader.cached_mesh(o), (albedo, liquid))
        })
        .collect();
    scene
        .objects
        .iter()
        .zip(prepared)
        .map(|(o, (mesh, views))| uploader.upload_object(pipelines, o, mesh, views, subsurface))
        .collect()
}

/// Where the surface point resting over `(x, z)` (m) is: a plane's, a
/// Gerstner or spectral sea's particle, raised by interactive waves where
/// it has gone.
fn surface_point(shape: &WaterShape, x: f64, z: f64) -> Point3<f64> {
    match shape {
        WaterShape::Plane { level } => Point3::new(x, *level, z),
        WaterShape::Gerstner { sea, time } => sea.particle(x, z, *time),
        WaterShape::Spectral { fields } => Point3::from(fields.particle_at(x, z).0),
        WaterShape::Interactive { base, waves } => {
            let p = surface_point(base, x, z);
            Point3::new(p.x, p.y + waves.height(p.x, p.z), p.z)
        }
    }
}

/// The water grid around the camera's target, culled to the view, and its
/// uniform.
fn upload_water(gpu: &FrameGpu<'_>, scene: &RenderScene) -> Option<WaterDraw> {
    let device = gpu.device;
    scene.water.as_ref().map(|w| {
        let (cx, cz) = (scene.camera.target.x, scene.camera.target.z);
        let (vertices, all) = match &w.shape {
            WaterShape::Plane { level } => water_grid(cx, cz, w.extent, 2, |x, z| Point3::new(x, *level, z)),
            shape => water_grid(cx, cz, w.extent, w.resolution, |x, z| surface_point(shape, x, z)),
        };
        let (width, height) = (gpu.targets.width, gpu.targets.height);
        let view_proj = scene.camera.view_projection(f64::from(width) / f64::from(height));
        let sea = cull_to_view(&vertices, &all, &view_proj);
        // The liquid inside open containers goes first (see `scene_pass`).
        let mut vertices = vertices;
        let mut indices = Vec::new();
        for o in scene.objects.iter().filter(|o| !o.mesh.openings.is_empty()) {
            let Some(level) = o.inner_water else { continue };
            let (v, i) = inner_water(&o.mesh, &o.pose, level);
            let base = vertices.len() as u32;
            vertices.extend(v);
            indices.extend(i.into_iter().map(|k| k + base));
        }
        let inner = indices.len() as u32;
        indices.extend(sea);
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
            layout: &gpu.pipelines.water_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: ub.as_entire_binding(),
            }],
        });
        WaterDraw {
            vertices: vb,
            indices: ib,
            count: indices.len() as u32,
            inner,
            bind,
        }
    })
}

/// The arrows' solids, if the scene has any.
fn upload_arrows(device: &wgpu::Device, scene: &RenderScene) -> Option<ArrowDraw> {
    let mut arrow_data = Vec::new();
    for a in &scene.arrows {
        arrow_vertices(a.origin, a.vector, a.radius, a.colour, &mut arrow_data);
    }
    (!arrow_data.is_empty()).then(|| ArrowDraw {
        vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("arrows"),
            contents: bytemuck::cast_slice(&arrow_data),
            usage: wgpu::BufferUsages::VERTEX,
        }),
        count: arrow_data.len() as u32,
    })
}

/// The tone map's settings (exposure, tone map, dither) and input. Debug
/// views are shown linear, at exposure 1.
fn tone_map_bind(gpu: &FrameGpu<'_>, scene: &RenderScene, shaded: bool) -> wgpu::BindGroup {
    let linear = matches!(scene.tone_map, ToneMap::Linear) || !shaded;
    let post = PostUniform {
        exposure: [if shaded { scene.exposure as f32 } else { 1.0 }, 0.0, 0.0, 0.0],
        mode: [u32::from(linear), u32::from(scene.dither), 0, 0],
    };
    let post_buffer = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("tone map"),
        contents: bytemuck::bytes_of(&post),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("tone map"),
        layout: &gpu.pipelines.post_layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&gpu.targets.hdr),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: post_buffer.as_entire_binding(),
            },
        ],
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
pub(super) fn scene_bytes(scene: &RenderScene) -> u64 {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Interactive waves raise the base water by their elevation where
    /// they are (a plane's point, or a Gerstner particle's), and nothing
    /// outside their region.
    #[test]
    fn interactive_waves_raise_the_base_surface() {
        let region = soak_hydro::WaveRegion {
            centre: [0.0, 0.0],
            size: 8.0,
            cells: 8,
        };
        // A ramp along x: cell (ix, iz) at 0.1 ix m.
        let heights = (0..64).map(|i| 0.1 * (i % 8) as f64).collect();
        let waves = soak_hydro::WaveHeights { region, heights };
        let shape = WaterShape::Interactive {
            base: Box::new(WaterShape::Plane { level: 2.0 }),
            waves,
        };
        // Cell centres at −3.5, −2.5, …: x = 0 is half-way between cells 3 and 4.
        let p = surface_point(&shape, 0.0, 0.0);
        assert!((p.y - 2.35).abs() < 1e-12, "{p}");
        assert_eq!(surface_point(&shape, 50.0, 0.0).y, 2.0);
        let sea = soak_hydro::Gerstner::new(
            0.0,
            vec![soak_hydro::GerstnerWave {
                amplitude: 0.2,
                wavelength: 10.0,
                direction_deg: 0.0,
                steepness: 0.5,
                phase: 0.0,
            }],
            9.81,
        )
        .unwrap();
        let particle = sea.particle(1.0, 0.5, 3.0);
        let on_sea = WaterShape::Interactive {
            base: Box::new(WaterShape::Gerstner { sea, time: 3.0 }),
            waves: soak_hydro::WaveHeights {
                region,
                heights: vec![0.25; 64],
            },
        };
        let q = surface_point(&on_sea, 1.0, 0.5);
        assert_eq!((q.x, q.z), (particle.x, particle.z));
        assert!((q.y - particle.y - 0.25).abs() < 1e-12);
    }

    /// A spectral sea is drawn through its particles: one mode's tile
    /// drawn anywhere, repeated, is the Gerstner wave of that mode (the
    /// same amplitude, length and phase; steepness `k a`), within the
    /// tile's interpolation error.
    #[test]
    fn a_spectral_sea_is_drawn_through_its_particles() {
        let (size, g) = (40.0, 9.81);
        let sea = soak_hydro::SpectralSea::from_modes(
            1.5,
            size,
            64,
            &[soak_hydro::SeaMode {
                n: 2,
                l: 0,
                amplitude: 0.3,
                phase: 0.4,
            }],
            g,
        )
        .unwrap();
        let wave = soak_hydro::Gerstner::new(
            1.5,
            vec![soak_hydro::GerstnerWave {
                amplitude: 0.3,
                wavelength: size / 2.0,
                direction_deg: 0.0,
                steepness: 0.3 * std::f64::consts::TAU / (size / 2.0),
                phase: 0.4,
            }],
            g,
        )
        .unwrap();
        let shape = WaterShape::Spectral {
            fields: std::sync::Arc::new(sea.fields(2.5)),
        };
        for (x, z) in [(0.0, 0.0), (3.3, -7.1), (-123.4, 56.7)] {
            let (p, q) = (surface_point(&shape, x, z), wave.particle(x, z, 2.5));
            assert!((p - q).norm() < 1e-3, "at ({x}, {z}): {p} against {q}");
        }
    }
}
