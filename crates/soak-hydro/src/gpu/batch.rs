//! Hydrostatics and drag of many bodies in one submission and one readback.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

use super::error::{GpuAtlasId, GpuHydroError};
use super::hydro::{GpuHydro, Scratch};
use super::layout::{Body, Dispatch, HYDRO_SLOTS, ITEM_TEXELS, Item, dispatch_bytes};
use super::sea::DeviceSeas;
use super::surface::{HeightFields, encode_surface};
use crate::error::HydroError;
use crate::hydrostatics::body_state::BodyState;
use crate::hydrostatics::evaluation::{Tiles, read_water_around};
use crate::hydrostatics::finish::finish;
use crate::hydrostatics::forces::HydroForces;
use crate::hydrostatics::frame::Frame;
use crate::hydrostatics::frame::deep_thickness;
use crate::hydrostatics::options::{BuoyancyMode, HydroOptions};
use crate::hydrostatics::sums::{BuoyancySums, DragSums, SlopeSums};
use crate::mass::MassProperties;
use crate::water::Water;
use soak_gpu::{GpuError, read_back, scoped};

/// One body of a batch: its atlas on the device, its water, state, mass
/// properties and options (as for [`crate::evaluate`]).
#[derive(Clone, Copy, Debug)]
pub struct GpuBody<'a> {
    /// The body's atlas, from [`GpuHydro::upload`].
    pub atlas: GpuAtlasId,
    /// The fluid around it.
    pub water: &'a Water,
    /// Pose and velocities.
    pub state: BodyState,
    /// Mass properties, object frame.
    pub mass: MassProperties,
    /// What to compute.
    pub options: HydroOptions,
}

impl<'a> From<(GpuAtlasId, &'a Water, BodyState, MassProperties, HydroOptions)> for GpuBody<'a> {
    fn from(
        (atlas, water, state, mass, options): (
            GpuAtlasId,
            &'a Water,
            BodyState,
            MassProperties,
            HydroOptions,
        ),
    ) -> Self {
        Self {
            atlas,
            water,
            state,
            mass,
            options,
        }
    }
}

const PARTIAL_BYTES: u64 = HYDRO_SLOTS as u64 * 16;

fn v4(v: &Vector3<f64>, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

fn check(index: usize, b: &GpuBody<'_>) -> Result<(), GpuHydroError> {
    b.water
        .validate()
        .map_err(|source| GpuHydroError::Water { body: index, source })?;
    b.state.check().map_err(|e| match e {
        HydroError::NonFiniteState { field } => GpuHydroError::NonFiniteState { body: index, field },
        other => GpuHydroError::Mass(other),
    })?;
    if !b.mass.is_finite() {
        return Err(GpuHydroError::NonFiniteState {
            body: index,
            field: "mass",
        });
    }
    if b.options
        .drag
        .is_some_and(|d| !(d.coefficient.is_finite() && d.linear.is_finite()))
    {
        return Err(GpuHydroError::NonFiniteState {
            body: index,
            field: "drag",
        });
    }
    Ok(())
}

/// The body's water with its surface sampled once over the body's
/// footprint, or read as one plane over it, when its options and its
/// surface ask for it (a sea with [`crate::SeaSampling::PerWavelength`]
/// or [`crate::SeaSampling::Plane`]), as [`crate::evaluate`] does; `None`
/// to read the water as it is.
fn sampled(
    index: usize,
    b: &GpuBody<'_>,
    origin: nalgebra::Point3<f64>,
    radius: f64,
    tiles: Option<Tiles<'_>>,
    t: f64,
) -> Result<Option<Water>, GpuHydroError> {
    read_water_around(origin, radius, tiles, b.water, &b.state, t, &b.options).map_err(|e| match e {
        HydroError::Water(source) => GpuHydroError::Water { body: index, source },
        other => GpuHydroError::Mass(other),
    })
}

impl GpuHydro {
    /// Buoyancy and drag on one body: [`crate::evaluate`] on the device.
    pub fn evaluate(
        &self,
        atlas: GpuAtlasId,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
        options: &HydroOptions,
    ) -> Result<HydroForces, GpuHydroError> {
        let body = GpuBody {
            atlas,
            water,
            state: *state,
            mass: *mass,
            options: *options,
        };
        Ok(self.evaluate_batch(&[body], t)?.remove(0))
    }

    /// Buoyancy and drag on many bodies at time `t` (s), each with its own
    /// atlas, water, pose and options: one submission (one dispatch per page
    /// of texels, one for the reduction) and one readback of 192 bytes per
    /// body. Results are in the order of `bodies`.
    ///
    /// A sea is read as [`HydroOptions::sea`] asks, as on the CPU: sampled
    /// once per body over its footprint (on the CPU, the bodies in
    /// parallel) and read by the kernels as that [`crate::SurfacePatch`], or
    /// with [`crate::SeaSampling::Exact`] inverted at every texel on the
    /// device: a spectral sea's tile is then evaluated on the device too,
    /// in the same submission, once however many bodies read it. A water
    /// whose surface is a [`crate::SurfacePatch`] already is read as it is.
    pub fn evaluate_batch(&self, bodies: &[GpuBody<'_>], t: f64) -> Result<Vec<HydroForces>, GpuHydroError> {
        use rayon::prelude::*;
        if bodies.is_empty() {
            return Ok(Vec::new());
        }
        if !t.is_finite() {
            return Err(GpuHydroError::NonFiniteState { body: 0, field: "t" });
        }
        let n = bodies.len();
        let mut footprints = Vec::with_capacity(n);
        for (i, b) in bodies.iter().enumerate() {
            let entry = self.entry(b.atlas)?;
            check(i, b)?;
            let tiles = entry
                .tiles
                .as_ref()
                .map(|(centres, sums)| Tiles { centres, sums });
            footprints.push((entry.origin, entry.radius, tiles));
        }
        // Kept until the encoding is done: the encoder stores a patch once
        // per address.
        let sampled_waters: Vec<Option<Water>> = bodies
            .par_iter()
            .zip(&footprints)
            .enumerate()
            .map(|(i, (b, &(origin, radius, tiles)))| sampled(i, b, origin, radius, tiles, t))
            .collect::<Vec<_>>()
            .into_iter()
            .collect::<Result<_, _>>()?;
        let mut gpu_bodies = Vec::with_capacity(n);
        let mut frames = Vec::with_capacity(n);
        let mut waves = Vec::new();
        let mut heights = HeightFields::default();
        let mut seas = DeviceSeas::default();
        let mut per_page: Vec<Vec<Item>> = vec![Vec::new(); self.pages.len()];
        let mut ranges: Vec<[u32; 2]> = Vec::with_capacity(n);
        let mut partials = 0u64;
        for (i, b) in bodies.iter().enumerate() {
            let entry = self.entry(b.atlas)?;
            let rot = b.state.pose.rotation.to_rotation_matrix().into_inner();
            let ow = (b.state.pose * entry.origin).coords;
            let com = (b.state.pose * b.mass.center_of_mass).coords;
            let drag = b.options.drag;
            let water = sampled_waters[i].as_ref().unwrap_or(b.water);
            let plane = Frame::surface_plane(water, t, &ow, 0.0);
            // Archimedes' slope sum per texel only under a surface that is
            // not a plane: a plane's follows from the other sums in `finish`.
            let slope_sums = b.options.buoyancy == BuoyancyMode::Archimedes && plane.is_none();
            let mut body = Body {
                rot0: v4(&rot.row(0).transpose(), 0.0),
                rot1: v4(&rot.row(1).transpose(), 0.0),
                rot2: v4(&rot.row(2).transpose(), 0.0),
                com: v4(&(com - ow), 0.0),
                linear_velocity: v4(&b.state.linear_velocity, b.water.density),
                angular_velocity: v4(&b.state.angular_velocity, drag.map_or(0.0, |d| d.coefficient)),
                drag: [
                    drag.map_or(0.0, |d| d.linear) as f32,
                    if drag.is_some() { 1.0 } else { 0.0 },
                    if slope_sums { 1.0 } else { 0.0 },
                    // The depth past which a texel is deep, before the
                    // kernel bounds it by the radius (zero: the radius).
                    if entry.thickness > 0.0 {
                        deep_thickness(entry.thickness, b.water.gravity, b.options.dt) as f32
                    } else {
                        0.0
                    },
                ],
                slot: [b.atlas.0, 0, 0, 0],
                ..Body::default()
            };
            // A spectral sea read as it is: its tile evaluated and read on
            // the device.
            match water
                .surface
                .as_any()
                .and_then(|a| a.downcast_ref::<crate::water::SpectralSurface>())
            {
                Some(sea) => seas.encode(i, sea, &ow, t, &mut body)?,
                None => encode_surface(i, water, &ow, t, &mut body, &mut waves, &mut heights)?,
            }
            gpu_bodies.push(body);
            // `finish` reads the reference point, the centre of mass, the
            // plane (for Archimedes' slope terms) and the texel count.
            frames.push(Frame {
                local_plane: None,
                rot,
                ow,
                com,
                plane,
                texels: entry.len,
                // The kernel takes the bounding radius and the thickness
                // itself (`shallow`).
                depth_scale: 0.0,
                deep_scale: 0.0,
            });
            let first = partials;
            for s in &entry.segments {
                let end = s.start + s.len;
                let mut start = s.start;
                while start < end {
                    let stop = end.min(start + ITEM_TEXELS);
                    per_page[s.page].push(Item {
                        body: i as u32,
                        start,
                        end: stop,
                        partial: partials as u32,
                    });
                    partials += 1;
                    start = stop;
                }
            }
            ranges.push([first as u32, (partials - first) as u32]);
        }
        // The seas' fields after the samples: the device writes them.
        seas.place(heights.samples.len(), &mut gpu_bodies)?;
        let height_bytes = ((heights.samples.len() + seas.fields) * 4) as u64;

        let limit = self.limit;
        let too_large = |what, needed: u64| -> Result<(), GpuHydroError> {
            if needed > limit {
                Err(GpuError::TooLarge { what, needed, limit }.into())
            } else {
                Ok(())
            }
        };
        let partial_bytes = partials * PARTIAL_BYTES;
        too_large("the partial sums of this batch", partial_bytes)?;
        too_large("the bodies of this batch", (n * size_of::<Body>()) as u64)?;
        too_large(
            "the work items of this batch",
            partials * size_of::<Item>() as u64,
        )?;
        too_large("the Gerstner waves of this batch", (waves.len() * 32) as u64)?;
        too_large(
            "the height fields, sampled surfaces and spectral seas of this batch",
            height_bytes,
        )?;
        too_large("the spectral seas' transforms of this batch", seas.layer_bytes())?;
        too_large(
            "the spectral seas' modes of this batch",
            (seas.modes.len() * 8) as u64,
        )?;

        let items: Vec<Item> = per_page.concat();
        let mut dispatches = Vec::new();
        let mut groups = Vec::new();
        let mut base = 0u32;
        for (page, list) in per_page.iter().enumerate() {
            if !list.is_empty() {
                let (d, g) = Dispatch::new(base, list.len() as u32, 0, [0.0; 4]);
                dispatches.push(d);
                groups.push((page, g));
                base += list.len() as u32;
            }
        }
        let (reduce, reduce_groups) = Dispatch::new(0, n as u32, 0, [0.0; 4]);
        dispatches.push(reduce);
        let result_bytes = n as u64 * PARTIAL_BYTES;

        let mut scratch = self.scratch.lock().unwrap_or_else(|p| p.into_inner());
        let s = &mut *scratch;
        let device = &self.device;
        let queue = &self.queue;
        scoped::<_, GpuHydroError>(device, "evaluating a batch", partial_bytes, || {
            let cap = limit;
            let body_buf = s.bodies.ensure(device, (n * size_of::<Body>()) as u64, cap);
            queue.write_buffer(body_buf, 0, bytemuck::cast_slice(&gpu_bodies));
            let wave_buf = s.waves.ensure(device, (waves.len() * 32) as u64, cap);
            queue.write_buffer(wave_buf, 0, bytemuck::cast_slice(&waves));
            let height_buf = s.heights.ensure(device, height_bytes, cap);
            queue.write_buffer(height_buf, 0, bytemuck::cast_slice(&heights.samples));
            let item_buf = s
                .items
                .ensure(device, (items.len() * size_of::<Item>()) as u64, cap);
            queue.write_buffer(item_buf, 0, bytemuck::cast_slice(&items));
            let range_buf = s.ranges.ensure(device, (n * 8) as u64, cap);
            queue.write_buffer(range_buf, 0, bytemuck::cast_slice(&ranges));
            let dispatch_data = dispatch_bytes(&dispatches);
            let dispatch_buf = s.dispatch.ensure(device, dispatch_data.len() as u64, u64::MAX);
            queue.write_buffer(dispatch_buf, 0, &dispatch_data);
            s.partials.ensure(device, partial_bytes, cap);
            s.results.ensure(device, result_bytes, cap);
            s.staging.ensure(device, result_bytes, u64::MAX);

            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("soak hydrostatics"),
            });
            if !seas.is_empty() {
                self.encode_seas(&mut encoder, s, &seas, cap);
            }
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("soak hydrostatics"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(self.kernels.buoyancy.pipeline());
                for (k, (page, g)) in groups.iter().enumerate() {
                    let bind = self.kernels.buoyancy.bind(
                        device,
                        &[
                            &self.pages[*page].texels,
                            s.bodies.get(),
                            s.items.get(),
                            s.waves.get(),
                            s.heights.get(),
                            &self.radii,
                            s.partials.get(),
                            s.dispatch.get(),
                        ],
                    );
                    pass.set_bind_group(0, &bind, &[(k as u64 * super::layout::DISPATCH_STRIDE) as u32]);
                    pass.dispatch_workgroups(g[0], g[1], 1);
                }
                pass.set_pipeline(self.kernels.reduce_hydro.pipeline());
                let bind = self.kernels.reduce_hydro.bind(
                    device,
                    &[
                        s.partials.get(),
                        s.ranges.get(),
                        s.results.get(),
                        s.dispatch.get(),
                    ],
                );
                let offset = (dispatches.len() as u64 - 1) * super::layout::DISPATCH_STRIDE;
                pass.set_bind_group(0, &bind, &[offset as u32]);
                pass.dispatch_workgroups(reduce_groups[0], reduce_groups[1], 1);
            }
            encoder.copy_buffer_to_buffer(s.results.get(), 0, s.staging.get(), 0, result_bytes);
            queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let data = read_back(device, s.staging.get(), result_bytes, "reading back a batch")?;
        drop(scratch);

        let floats: Vec<f32> = data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        Ok(bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let q = &floats[i * 4 * HYDRO_SLOTS as usize..(i + 1) * 4 * HYDRO_SLOTS as usize];
                let (sums, drag) = decode(q);
                let drag = b.options.drag.map(|_| drag);
                finish(
                    &frames[i],
                    b.water,
                    &b.state,
                    &b.mass,
                    &sums,
                    drag.as_ref(),
                    &b.options,
                )
            })
            .collect())
    }
}

impl GpuHydro {
    /// Records the evaluation of every spectral sea of a batch (turned
    /// amplitudes and uniforms written, then per sea its layers, their
    /// inverse FFT and its fields into `heights`, which must hold the
    /// batch's samples already). Call inside an error scope.
    fn encode_seas(&self, encoder: &mut wgpu::CommandEncoder, s: &mut Scratch, seas: &DeviceSeas, cap: u64) {
        let (device, queue) = (&self.device, &self.queue);
        let modes = s.sea_modes.ensure(device, (seas.modes.len() * 8) as u64, cap);
        queue.write_buffer(modes, 0, bytemuck::cast_slice(&seas.modes));
        let (uniforms, firsts) = seas.uniforms();
        let uniform_buf = s.sea_uniforms.ensure(device, uniforms.len() as u64, u64::MAX);
        queue.write_buffer(uniform_buf, 0, &uniforms);
        let layers = seas.layer_bytes();
        s.sea_spec.ensure(device, layers, cap);
        s.sea_scratch.ensure(device, layers, cap);
        let k = &self.kernels;
        let (modes, spec, scratch, uniforms) = (
            s.sea_modes.get(),
            s.sea_spec.get(),
            s.sea_scratch.get(),
            s.sea_uniforms.get(),
        );
        let pair = k.sea_modes.bind(device, &[modes, spec, uniforms]);
        let forth = k.sea_fft.bind(device, &[spec, scratch, uniforms]);
        let back = k.sea_fft.bind(device, &[scratch, spec, uniforms]);
        let unpack = k.sea_unpack.bind(device, &[spec, s.heights.get(), uniforms]);
        let groups = super::layout::thread_groups;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("soak spectral sea"),
            timestamp_writes: None,
        });
        for (sea, &first) in seas.seas.iter().zip(&firsts) {
            let nn = sea.n * sea.n;
            let first = first as u32;
            let g = groups(nn);
            pass.set_pipeline(k.sea_modes.pipeline());
            pass.set_bind_group(0, &pair, &[first]);
            pass.dispatch_workgroups(g[0], g[1], 1);
            // The inverse transforms, rows then columns: an even number of
            // stages, so the result is back in `spec`.
            pass.set_pipeline(k.sea_fft.pipeline());
            let stages = 2 * sea.n.trailing_zeros();
            let g = groups(super::sea::SEA_LAYERS * nn / 2);
            for stage in 0..stages {
                let group = if stage % 2 == 0 { &forth } else { &back };
                pass.set_bind_group(
                    0,
                    group,
                    &[first + (1 + stage) * super::waves::STAGE_STRIDE as u32],
                );
                pass.dispatch_workgroups(g[0], g[1], 1);
            }
            pass.set_pipeline(k.sea_unpack.pipeline());
            pass.set_bind_group(0, &unpack, &[first]);
            let g = groups(nn);
            pass.dispatch_workgroups(g[0], g[1], 1);
        }
    }
}

/// Unpacks one body's reduced sums (layout in buoyancy.wgsl).
fn decode(q: &[f32]) -> (BuoyancySums, DragSums) {
    let f = |i: usize| q[i] as f64;
    let v = |i: usize| Vector3::new(f(i), f(i + 1), f(i + 2));
    let sums = BuoyancySums {
        vol: f(0),
        wr: v(1),
        wd2: f(4),
        f: v(5),
        rxf: v(8),
        area: f(11),
        count: q[12].to_bits() as usize,
        d2a: v(40),
        slope: SlopeSums {
            wrs: v(44),
            ayr: f(43),
            shallow: f(47),
        },
    };
    let kvv = Matrix3::new(f(13), f(14), f(15), f(14), f(16), f(17), f(15), f(17), f(18));
    let kvw = Matrix3::new(f(25), f(26), f(27), f(28), f(29), f(30), f(31), f(32), f(33));
    let kww = Matrix3::new(f(34), f(35), f(36), f(35), f(37), f(38), f(36), f(38), f(39));
    let mut k = Matrix6::zeros();
    k.fixed_view_mut::<3, 3>(0, 0).copy_from(&kvv);
    k.fixed_view_mut::<3, 3>(0, 3).copy_from(&kvw);
    k.fixed_view_mut::<3, 3>(3, 0).copy_from(&kvw.transpose());
    k.fixed_view_mut::<3, 3>(3, 3).copy_from(&kww);
    let b = Vector6::new(f(19), f(20), f(21), f(22), f(23), f(24));
    (sums, DragSums { k, b })
}
