//! Mass properties on the device: the solid's volume moments and the shell
//! sums of [`crate::mass`], per texel, reduced like the hydrostatics.

use nalgebra::{Matrix3, Vector3};

use super::error::{GpuAtlasId, GpuHydroError};
use super::hydro::GpuHydro;
use super::layout::{Dispatch, ITEM_TEXELS, Item, MASS_SLOTS, dispatch_bytes};
use crate::error::HydroError;
use crate::mass::{MassModel, MassProperties, VolumeMoments, inertia_from_second_moment, parallel_axis};
use soak_gpu::{GpuError, read_back, scoped};

const SOLID: u32 = 0;
const SHELL_UNIFORM: u32 = 1;
const SHELL_TEXTURE: u32 = 2;

fn check_density(what: &'static str, value: f64) -> Result<(), GpuHydroError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(HydroError::Density { what, value }.into())
    }
}

fn check_thickness(value: f64) -> Result<(), GpuHydroError> {
    crate::mass::check_thickness(value).map_err(Into::into)
}

impl GpuHydro {
    /// Volume moments of the solid bounded by the atlas, about its origin:
    /// [`crate::volume_moments`] on the device.
    pub fn volume_moments(&self, id: GpuAtlasId) -> Result<VolumeMoments, GpuHydroError> {
        let s = self.mass_sums(id, SOLID, 0.0, None)?;
        let (sxx, syy, szz) = (s[4] / 3.0, s[5] / 3.0, s[6] / 3.0);
        let (sxy, syz, szx) = (s[7], s[8], s[9]);
        Ok(VolumeMoments {
            origin: self.entry(id)?.origin,
            volume: s[0] / 3.0,
            first: Vector3::new(s[1], s[2], s[3]),
            second: Matrix3::new(sxx, sxy, szx, sxy, syy, syz, szx, syz, szz),
        })
    }

    /// Mass properties of the atlas under `model`, object frame:
    /// [`MassModel::mass_properties`] on the device. A per-texel areal
    /// density ([`MassModel::ShellTexture`]) is uploaded with each call, so
    /// it may change every frame.
    pub fn mass_properties(
        &self,
        id: GpuAtlasId,
        model: &MassModel,
    ) -> Result<MassProperties, GpuHydroError> {
        let walls = self.entry(id)?.walls.clone();
        let uniform = |sigma: f64| -> Result<MassProperties, GpuHydroError> {
            match &walls {
                None => {
                    let s = self.mass_sums(id, SHELL_UNIFORM, sigma as f32, None)?;
                    self.shell(id, &s)
                }
                Some(w) => {
                    let texture: Vec<f32> = w.iter().map(|&m| m * sigma as f32).collect();
                    let s = self.mass_sums(id, SHELL_TEXTURE, 0.0, Some(&texture))?;
                    self.shell(id, &s)
                }
            }
        };
        match model {
            MassModel::Solid { density } => {
                check_density("solid", *density)?;
                if walls.is_some() {
                    return Err(HydroError::OpenSolid.into());
                }
                Ok(self.volume_moments(id)?.solid(*density))
            }
            MassModel::Shell { areal_density } => {
                check_density("areal", *areal_density)?;
                uniform(*areal_density)
            }
            MassModel::Given { properties } => crate::mass::check_given(properties).map_err(Into::into),
            MassModel::Walls { density, thickness } => {
                check_density("wall", *density)?;
                check_thickness(*thickness)?;
                uniform(density * thickness)
            }
            MassModel::ShellTexture { areal_density } => {
                let texels = self.entry(id)?.len;
                if areal_density.len() != texels {
                    return Err(HydroError::ChannelLength {
                        what: "areal density texture",
                        len: areal_density.len(),
                        texels,
                    }
                    .into());
                }
                if let Some(texel) = areal_density.iter().position(|d| !(d.is_finite() && *d >= 0.0)) {
                    return Err(HydroError::ChannelValue {
                        what: "areal density",
                        texel,
                        value: areal_density[texel],
                    }
                    .into());
                }
                let masked: Vec<f32>;
                let texture = match &walls {
                    None => areal_density.as_slice(),
                    Some(w) => {
                        masked = areal_density.iter().zip(w).map(|(d, m)| d * m).collect();
                        masked.as_slice()
                    }
                };
                let s = self.mass_sums(id, SHELL_TEXTURE, 0.0, Some(texture))?;
                self.shell(id, &s)
            }
        }
    }

    /// The tail of [`crate::shell`]: sums about the origin to mass properties.
    fn shell(&self, id: GpuAtlasId, s: &[f64; 10]) -> Result<MassProperties, GpuHydroError> {
        let mass = s[0];
        let o = self.entry(id)?.origin;
        if mass <= 0.0 {
            return Ok(MassProperties::point(0.0, o));
        }
        let c = Vector3::new(s[1], s[2], s[3]) / mass;
        let second = Matrix3::new(s[4], s[7], s[9], s[7], s[5], s[8], s[9], s[8], s[6]);
        Ok(MassProperties {
            mass,
            center_of_mass: o + c,
            inertia: inertia_from_second_moment(&second) - parallel_axis(mass, &c),
        })
    }

    /// The ten sums of mass.wgsl for one atlas (one submission, one readback).
    fn mass_sums(
        &self,
        id: GpuAtlasId,
        mode: u32,
        sigma: f32,
        densities: Option<&[f32]>,
    ) -> Result<[f64; 10], GpuHydroError> {
        let entry = self.entry(id)?;
        let mut per_page: Vec<Vec<Item>> = vec![Vec::new(); self.pages.len()];
        let mut partials = 0u32;
        for s in &entry.segments {
            let end = s.start + s.len;
            let mut start = s.start;
            while start < end {
                let stop = end.min(start + ITEM_TEXELS);
                per_page[s.page].push(Item {
                    body: s.offset + (start - s.start),
                    start,
                    end: stop,
                    partial: partials,
                });
                partials += 1;
                start = stop;
            }
        }
        let limit = self.limit;
        let slot_bytes = MASS_SLOTS as u64 * 16;
        let partial_bytes = partials as u64 * slot_bytes;
        let density_bytes = densities.map_or(0, |d| d.len() as u64 * 4);
        for (what, needed) in [
            ("the mass partial sums", partial_bytes),
            ("the areal density texture", density_bytes),
        ] {
            if needed > limit {
                return Err(GpuError::TooLarge { what, needed, limit }.into());
            }
        }
        let items: Vec<Item> = per_page.concat();
        let mut dispatches = Vec::new();
        let mut groups = Vec::new();
        let mut base = 0u32;
        for (page, list) in per_page.iter().enumerate() {
            if !list.is_empty() {
                let (d, g) = Dispatch::new(base, list.len() as u32, mode, [sigma, 0.0, 0.0, 0.0]);
                dispatches.push(d);
                groups.push((page, g));
                base += list.len() as u32;
            }
        }
        let (reduce, reduce_groups) = Dispatch::new(0, 1, 0, [0.0; 4]);
        dispatches.push(reduce);

        let mut scratch = self.scratch.lock().unwrap_or_else(|p| p.into_inner());
        let s = &mut *scratch;
        let device = &self.device;
        let queue = &self.queue;
        scoped::<_, GpuHydroError>(
            device,
            "computing mass properties",
            partial_bytes + density_bytes,
            || {
                let item_buf = s
                    .items
                    .ensure(device, (items.len() * size_of::<Item>()) as u64, limit);
                queue.write_buffer(item_buf, 0, bytemuck::cast_slice(&items));
                let density_buf = s.densities.ensure(device, density_bytes, limit);
                if let Some(d) = densities {
                    queue.write_buffer(density_buf, 0, bytemuck::cast_slice(d));
                }
                let range_buf = s.ranges.ensure(device, 8, limit);
                queue.write_buffer(range_buf, 0, bytemuck::cast_slice(&[0u32, partials]));
                let dispatch_data = dispatch_bytes(&dispatches);
                let dispatch_buf = s.dispatch.ensure(device, dispatch_data.len() as u64, u64::MAX);
                queue.write_buffer(dispatch_buf, 0, &dispatch_data);
                s.partials.ensure(device, partial_bytes, limit);
                s.results.ensure(device, slot_bytes, limit);
                s.staging.ensure(device, slot_bytes, u64::MAX);

                let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("soak mass properties"),
                });
                {
                    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: Some("soak mass properties"),
                        timestamp_writes: None,
                    });
                    pass.set_pipeline(self.kernels.mass.pipeline());
                    for (k, (page, g)) in groups.iter().enumerate() {
                        let bind = self.kernels.mass.bind(
                            device,
                            &[
                                &self.pages[*page].texels,
                                s.items.get(),
                                s.densities.get(),
                                s.partials.get(),
                                s.dispatch.get(),
                            ],
                        );
                        pass.set_bind_group(0, &bind, &[(k as u64 * super::layout::DISPATCH_STRIDE) as u32]);
                        pass.dispatch_workgroups(g[0], g[1], 1);
                    }
                    pass.set_pipeline(self.kernels.reduce_mass.pipeline());
                    let bind = self.kernels.reduce_mass.bind(
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
                encoder.copy_buffer_to_buffer(s.results.get(), 0, s.staging.get(), 0, slot_bytes);
                queue.submit([encoder.finish()]);
                Ok(())
            },
        )?;
        let data = read_back(
            device,
            s.staging.get(),
            slot_bytes,
            "reading back mass properties",
        )?;
        let mut out = [0.0f64; 10];
        for (o, c) in out.iter_mut().zip(data.chunks_exact(4)) {
            *o = f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64;
        }
        Ok(out)
    }
}
