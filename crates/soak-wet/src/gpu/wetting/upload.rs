//! Moving a body between host and device: the upload of its texels,
//! settings and field, and its liquid texture in and out.

use soak_bake::Atlas;
use soak_gpu::{GpuError, read_back, scoped};
use soak_hydro::gpu::wgsl::{Body, texel_vec4s};

use super::{GpuField, GpuWetBody, GpuWetting};
use crate::body_field::BodyField;
use crate::gpu::error::GpuWetError;
use crate::gpu::layout::Params;
use crate::wetting::Wetting;

impl GpuWetting {
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
        let texels = texel_vec4s(atlas);
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
}
