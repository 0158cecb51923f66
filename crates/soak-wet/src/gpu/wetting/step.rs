//! The step on the device: the parameters of one step written, and the
//! exchange, gather, substep, finish and scatter passes encoded.

use nalgebra::{Isometry3, Vector3};
use soak_gpu::{GpuError, scoped};
use soak_hydro::gpu::wgsl::{Body, HeightFields, Wave, encode_surface};
use soak_hydro::{SurfaceKind, Water};

use super::{GpuStep, GpuWetBody, GpuWetting};
use crate::diffusion::DiffusionMode;
use crate::environment::Environment;
use crate::exchange::Rates;
use crate::gpu::error::GpuWetError;
use crate::gpu::layout::{
    FLAG_RAINING, FLAG_WET_POSSIBLE, MODE_CONSERVATIVE, MODE_THESIS, Params, REGION_BOX, REGION_DISC,
    REGION_EVERYWHERE, groups,
};
use crate::source::Region;
use crate::wetting::check_pose;

impl GpuWetting {
    /// Advances the body's liquid by `dt` (s) at time `time` (s), at `pose`
    /// (object → world) in `water` under `env`:
    /// [`Wetting::step`](crate::Wetting::step) on the device. Records and
    /// submits the work without waiting for it.
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
