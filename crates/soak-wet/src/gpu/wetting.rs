//! [`GpuWetting`] and [`GpuWetBody`]: a body's liquid texture and field
//! resident on a device, stepped by compute kernels.

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::Atlas;
use soak_gpu::{GpuError, read_back, scoped};
use soak_hydro::gpu::wgsl::{Body, HeightFields, Wave, encode_surface};
use soak_hydro::{SurfaceKind, Water};

use super::error::GpuWetError;
use super::kernels::Kernels;
use super::layout::{
    FLAG_RAINING, FLAG_WET_POSSIBLE, MODE_CONSERVATIVE, MODE_THESIS, Params, REGION_BOX, REGION_DISC,
    REGION_EVERYWHERE, groups,
};
use crate::diffusion::{Diffusion, DiffusionMode, SubstepPlan};
use crate::environment::{Environment, EnvironmentResponse};
use crate::exchange::Rates;
use crate::grid::VoxelGrid;
use crate::material::{Liquid, Material};
use crate::source::Region;
use crate::wetting::{BodyField, Wetting, check_pose};

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
/// CPU only. The water surface must be one the GPU knows (Plane, Gerstner,
/// HeightField, Unbounded).
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

    /// Uploads `atlas` with the liquid, settings and permeability map of
    /// `wetting`; with diffusion, bins the texels into the body's field (as
    /// the CPU does) and uploads the field.
    pub fn upload(&self, atlas: &Atlas, wetting: &Wetting) -> Result<GpuWetBody, GpuWetError> {
        let n = atlas.len();
        if n != wetting.texels() {
            return Err(crate::WetError::AtlasMismatch {
                state: wetting.texels(),
                atlas: n,
            }
            .into());
        }
        if n == 0 {
            return Err(crate::WetError::EmptyAtlas.into());
        }
        if n >= (u32::MAX / 4) as usize {
            return Err(GpuError::TooLarge {
                what: "an atlas",
                needed: n as u64 * 32,
                limit: self.limit,
            }
            .into());
        }
        let diffusion = wetting.diffusion().copied();
        if let Some(d) = &diffusion {
            d.validate()?;
        }
        let field = match diffusion {
            Some(d) => Some(BodyField::build(atlas, &d, wetting.material().saturation)?),
            None => None,
        };
        let mut texels = Vec::with_capacity(2 * n);
        for ((x, a), &area) in atlas
            .local_positions()
            .iter()
            .zip(atlas.area_vectors().iter())
            .zip(atlas.areas())
        {
            texels.push([x[0], x[1], x[2], area]);
            texels.push([a[0], a[1], a[2], 0.0]);
        }
        let h: Vec<f32> = wetting.liquid().iter().map(|&h| h as f32).collect();
        let perm: Vec<f32> = match wetting.permeability_map() {
            Some(m) => m.to_vec(),
            None => vec![1.0; n],
        };
        let device = &self.device;
        let bytes = n as u64 * 40;
        let body = scoped::<_, GpuError>(device, "uploading a wet body", bytes, || {
            let texel_buf = self.filled("soak-wet texels", &texels)?;
            let liquid_buf = self.filled("soak-wet liquid", &h)?;
            let permeability_buf = self.filled("soak-wet permeability", &perm)?;
            let body_buf = self.buffer("soak-wet body", size_of::<Body>() as u64)?;
            let r = atlas.bounding_radius() as f32;
            let radii_buf = self.filled("soak-wet radii", &[(r * r).to_bits(), 0, 0, 0])?;
            let params_buf = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("soak-wet params"),
                size: size_of::<Params>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let staging = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("soak-wet readback"),
                size: (n as u64 * 4).next_multiple_of(16),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let waves = (self.buffer("soak-wet waves", 16 * 32)?, 16);
            let heights = (self.buffer("soak-wet heights", 16 * 4)?, 16);
            let exchange = self.kernels.exchange.bind(
                device,
                &[
                    &texel_buf,
                    &liquid_buf,
                    &permeability_buf,
                    &body_buf,
                    &waves.0,
                    &heights.0,
                    &radii_buf,
                    &params_buf,
                ],
            );
            let field = match &field {
                Some(f) => Some(self.upload_field(f, n, &texel_buf, &liquid_buf, &params_buf)?),
                None => None,
            };
            Ok(GpuWetBody {
                texels: n,
                origin: atlas.origin(),
                radius: atlas.bounding_radius(),
                material: *wetting.material(),
                liquid: *wetting.liquid_params(),
                response: *wetting.response(),
                diffusion,
                texel_buf,
                liquid_buf,
                permeability_buf,
                body_buf,
                radii_buf,
                params_buf,
                staging,
                waves,
                heights,
                exchange,
                field,
            })
        })?;
        Ok(body)
    }

    fn upload_field(
        &self,
        field: &BodyField,
        texels: usize,
        texel_buf: &wgpu::Buffer,
        liquid_buf: &wgpu::Buffer,
        params_buf: &wgpu::Buffer,
    ) -> Result<GpuField, GpuError> {
        let l = &field.layout;
        let grid = l.grid.expect("a built layout has a grid");
        let cells: Vec<[u32; 4]> = l.cells.iter().map(|c| [c[0], c[1], c[2], 0]).collect();
        let capacity: Vec<f32> = l.capacity.iter().map(|&c| c as f32).collect();
        let nv = l.defined() as u64;
        let start = self.filled("soak-wet voxel starts", &l.start)?;
        let members = self.filled("soak-wet voxel members", &l.members)?;
        let cells = self.filled("soak-wet voxel cells", &cells)?;
        let capacity = self.filled("soak-wet voxel capacities", &capacity)?;
        let nstart = self.filled("soak-wet neighbour starts", &l.nstart)?;
        let neighbours = self.filled("soak-wet neighbours", &l.neighbours)?;
        let voxel_of = self.filled("soak-wet texel voxels", &l.voxel_of)?;
        let dense = self.filled("soak-wet dense voxel map", &l.dense)?;
        let initial = self.buffer("soak-wet voxel start values", nv * 4)?;
        let a = self.buffer("soak-wet voxel values a", nv * 4)?;
        let b = self.buffer("soak-wet voxel values b", nv * 4)?;
        let cellinfo = self.buffer("soak-wet voxel changes", nv * 16)?;
        let factor = self.buffer("soak-wet voxel factors", nv * 8)?;
        let deltas = self.buffer("soak-wet texel deltas", texels as u64 * 4)?;
        let device = &self.device;
        let k = &self.kernels;
        let gather = k.gather.bind(
            device,
            &[
                texel_buf, liquid_buf, &start, &members, &cells, &initial, &a, params_buf,
            ],
        );
        let substep = [
            k.substep
                .bind(device, &[&a, &b, &capacity, &nstart, &neighbours, params_buf]),
            k.substep
                .bind(device, &[&b, &a, &capacity, &nstart, &neighbours, params_buf]),
        ];
        let finish = [&a, &b].map(|cur| {
            k.finish
                .bind(device, &[&initial, cur, &capacity, &cellinfo, params_buf])
        });
        let activity = k
            .activity
            .bind(device, &[&cellinfo, &nstart, &neighbours, &factor, params_buf]);
        let delta = k.delta.bind(
            device,
            &[
                texel_buf, liquid_buf, &voxel_of, &dense, &cellinfo, &factor, &deltas, params_buf,
            ],
        );
        let residual = k.residual.bind(
            device,
            &[
                texel_buf, &start, &members, &deltas, &cellinfo, &factor, params_buf,
            ],
        );
        let scatter = k.scatter.bind(
            device,
            &[
                texel_buf, liquid_buf, &voxel_of, &dense, &cellinfo, &factor, &deltas, params_buf,
            ],
        );
        let bytes = [
            &start,
            &members,
            &cells,
            &capacity,
            &nstart,
            &neighbours,
            &voxel_of,
            &dense,
            &initial,
            &a,
            &b,
            &cellinfo,
            &factor,
            &deltas,
        ]
        .iter()
        .map(|b| b.size())
        .sum();
        Ok(GpuField {
            grid,
            count_max: l.count_max,
            defined: l.defined() as u32,
            gather,
            substep,
            finish,
            activity,
            delta,
            residual,
            scatter,
            bytes,
        })
    }

    /// Replaces the body's liquid texture on the device (m per texel, in
    /// `[0, h_max]`).
    pub fn upload_liquid(&self, body: &GpuWetBody, h: &[f64]) -> Result<(), GpuWetError> {
        if h.len() != body.texels {
            return Err(crate::WetError::ChannelLength {
                what: "liquid",
                len: h.len(),
                texels: body.texels,
            }
            .into());
        }
        let hmax = body.material.saturation;
        if let Some(i) = h.iter().position(|v| !(v.is_finite() && *v >= 0.0 && *v <= hmax)) {
            return Err(crate::WetError::ChannelValue {
                what: "liquid",
                texel: i,
                value: h[i],
                expected: "[0, saturation] m",
            }
            .into());
        }
        let data: Vec<f32> = h.iter().map(|&v| v as f32).collect();
        self.queue
            .write_buffer(&body.liquid_buf, 0, bytemuck::cast_slice(&data));
        Ok(())
    }

    /// Reads the body's liquid texture back (m per texel, atlas order).
    pub fn download(&self, body: &GpuWetBody) -> Result<Vec<f64>, GpuWetError> {
        let bytes = body.texels as u64 * 4;
        scoped::<_, GpuError>(&self.device, "reading back a liquid texture", bytes, || {
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("soak-wet readback"),
                });
            encoder.copy_buffer_to_buffer(&body.liquid_buf, 0, &body.staging, 0, bytes);
            self.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let data = read_back(
            &self.device,
            &body.staging,
            bytes,
            "reading back a liquid texture",
        )?;
        Ok(data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64)
            .collect())
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

    /// Advances the body's liquid by `dt` (s) at time `time` (s), at `pose`
    /// (object → world) in `water` under `env`: [`Wetting::step`] on the
    /// device. Records and submits the work without waiting for it.
    pub fn step(
        &self,
        body: &mut GpuWetBody,
        pose: &Isometry3<f64>,
        water: &Water,
        env: &Environment,
        time: f64,
        dt: f64,
    ) -> Result<GpuStep, GpuWetError> {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(crate::WetError::TimeStep { dt }.into());
        }
        if !time.is_finite() {
            return Err(crate::WetError::Time { t: time }.into());
        }
        check_pose(pose, "the body")?;
        water.validate().map_err(crate::WetError::from)?;
        env.validate()?;
        body.response.validate()?;
        let rates = Rates::new(
            &body.material,
            &body.liquid,
            &body.response,
            env,
            water.density,
            water.gravity,
        );
        let rot = pose.rotation.to_rotation_matrix().into_inner();
        let ow = (pose * body.origin).coords;
        let surface = &*water.surface;
        let lowest = ow.y - body.radius;
        let wet_possible = rates.absorb > 0.0
            && match surface.kind(time) {
                SurfaceKind::Unbounded => false,
                _ => surface.height_bounds(time).is_none_or(|(_, hi)| lowest <= hi),
            };
        let (trough, crest) = surface
            .height_bounds(time)
            .filter(|(lo, hi)| lo.is_finite() && hi.is_finite())
            .map_or((-f32::MAX, f32::MAX), |(lo, hi)| {
                ((lo - ow.y) as f32, (hi - ow.y) as f32)
            });
        let row = |k: usize| {
            let r = rot.row(k);
            [r[0] as f32, r[1] as f32, r[2] as f32, 0.0]
        };
        let mut gpu_body = Body {
            rot0: row(0),
            rot1: row(1),
            rot2: row(2),
            ..Body::default()
        };
        let mut waves: Vec<Wave> = Vec::new();
        let mut heights = HeightFields::default();
        if wet_possible {
            encode_surface(0, water, &ow, time, &mut gpu_body, &mut waves, &mut heights)?;
        }
        let heights = heights.samples;
        let (region_kind, region, region2) = encode_region(&rates.region, &ow);
        let plan = match (&body.field, body.diffusion) {
            (Some(f), Some(d)) if d.coefficient > 0.0 && dt > 0.0 => {
                Some(d.plan(dt, f.grid.voxel_size, f.count_max))
            }
            _ => None,
        };
        let mode = match body.diffusion.map(|d| d.mode) {
            Some(DiffusionMode::Thesis) => MODE_THESIS,
            _ => MODE_CONSERVATIVE,
        };
        let texel_groups = groups(body.texels);
        let voxel_groups = groups(body.field.as_ref().map_or(0, |f| f.defined as usize));
        let (grid, dims, defined) = match &body.field {
            Some(f) => {
                let s = 1.0 / f.grid.voxel_size;
                let o = (body.origin.coords - Vector3::from(f.grid.origin)) * s;
                (
                    [o.x as f32, o.y as f32, o.z as f32, s as f32],
                    [f.grid.dims[0], f.grid.dims[1], f.grid.dims[2], texel_groups[0]],
                    f.defined,
                )
            }
            None => ([0.0; 4], [0, 0, 0, texel_groups[0]], 0),
        };
        let mut flags = 0;
        if wet_possible {
            flags |= FLAG_WET_POSSIBLE;
        }
        if rates.rain > 0.0 {
            flags |= FLAG_RAINING;
        }
        let params = Params {
            rates: [
                rates.absorb as f32,
                rates.evaporate as f32,
                rates.rain as f32,
                rates.saturation as f32,
            ],
            step: [dt as f32, trough, crest, plan.map_or(0.0, |p| p.weight as f32)],
            region,
            region2,
            grid,
            info: [body.texels as u32, flags, region_kind, defined],
            dims,
            info2: [voxel_groups[0], mode, 0, 0],
        };
        let device = &self.device;
        let queue = &self.queue;
        let bytes = (waves.len() * 32 + heights.len() * 4) as u64;
        scoped::<_, GpuError>(device, "stepping a wet body", bytes, || {
            let mut rebind = false;
            if waves.len() > body.waves.1 {
                let cap = waves.len().next_power_of_two();
                body.waves = (self.buffer("soak-wet waves", cap as u64 * 32)?, cap);
                rebind = true;
            }
            if heights.len() > body.heights.1 {
                let cap = heights.len().next_power_of_two();
                body.heights = (self.buffer("soak-wet heights", cap as u64 * 4)?, cap);
                rebind = true;
            }
            if rebind {
                body.exchange = self.kernels.exchange.bind(
                    device,
                    &[
                        &body.texel_buf,
                        &body.liquid_buf,
                        &body.permeability_buf,
                        &body.body_buf,
                        &body.waves.0,
                        &body.heights.0,
                        &body.radii_buf,
                        &body.params_buf,
                    ],
                );
            }
            queue.write_buffer(&body.params_buf, 0, bytemuck::bytes_of(&params));
            queue.write_buffer(&body.body_buf, 0, bytemuck::bytes_of(&gpu_body));
            if !waves.is_empty() {
                queue.write_buffer(&body.waves.0, 0, bytemuck::cast_slice(&waves));
            }
            if !heights.is_empty() {
                queue.write_buffer(&body.heights.0, 0, bytemuck::cast_slice(&heights));
            }
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("soak-wet step"),
            });
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("soak-wet step"),
                    timestamp_writes: None,
                });
                if dt > 0.0 {
                    pass.set_pipeline(self.kernels.exchange.pipeline());
                    pass.set_bind_group(0, &body.exchange, &[]);
                    pass.dispatch_workgroups(texel_groups[0], texel_groups[1], 1);
                }
                if let (Some(p), Some(f)) = (plan.filter(|p| p.substeps > 0), &body.field) {
                    pass.set_pipeline(self.kernels.gather.pipeline());
                    pass.set_bind_group(0, &f.gather, &[]);
                    pass.dispatch_workgroups(voxel_groups[0], voxel_groups[1], 1);
                    pass.set_pipeline(self.kernels.substep.pipeline());
                    for k in 0..p.substeps {
                        pass.set_bind_group(0, &f.substep[(k % 2) as usize], &[]);
                        pass.dispatch_workgroups(voxel_groups[0], voxel_groups[1], 1);
                    }
                    pass.set_pipeline(self.kernels.finish.pipeline());
                    pass.set_bind_group(0, &f.finish[(p.substeps % 2) as usize], &[]);
                    pass.dispatch_workgroups(voxel_groups[0], voxel_groups[1], 1);
                    if mode == MODE_CONSERVATIVE {
                        pass.set_pipeline(self.kernels.activity.pipeline());
                        pass.set_bind_group(0, &f.activity, &[]);
                        pass.dispatch_workgroups(voxel_groups[0], voxel_groups[1], 1);
                        pass.set_pipeline(self.kernels.delta.pipeline());
                        pass.set_bind_group(0, &f.delta, &[]);
                        pass.dispatch_workgroups(texel_groups[0], texel_groups[1], 1);
                        pass.set_pipeline(self.kernels.residual.pipeline());
                        pass.set_bind_group(0, &f.residual, &[]);
                        pass.dispatch_workgroups(voxel_groups[0], voxel_groups[1], 1);
                    }
                    pass.set_pipeline(self.kernels.scatter.pipeline());
                    pass.set_bind_group(0, &f.scatter, &[]);
                    pass.dispatch_workgroups(texel_groups[0], texel_groups[1], 1);
                }
            }
            queue.submit([encoder.finish()]);
            Ok(())
        })?;
        Ok(GpuStep { diffusion: plan })
    }
}

/// The rain region relative to `ow`, for the kernel.
fn encode_region(region: &Region, ow: &Vector3<f64>) -> (u32, [f32; 4], [f32; 4]) {
    match *region {
        Region::Everywhere => (REGION_EVERYWHERE, [0.0; 4], [0.0; 4]),
        Region::Disc { center, radius } => (
            REGION_DISC,
            [
                (center[0] - ow.x) as f32,
                (center[1] - ow.z) as f32,
                (radius * radius) as f32,
                0.0,
            ],
            [0.0; 4],
        ),
        Region::Box { min, max } => (
            REGION_BOX,
            [
                (min[0] - ow.x) as f32,
                (min[1] - ow.y) as f32,
                (min[2] - ow.z) as f32,
                0.0,
            ],
            [
                (max[0] - ow.x) as f32,
                (max[1] - ow.y) as f32,
                (max[2] - ow.z) as f32,
                0.0,
            ],
        ),
    }
}
