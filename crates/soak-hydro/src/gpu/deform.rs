//! Deformation on the device (`Atlas::refresh` in a kernel), and reading
//! texels back.

use nalgebra::Point3;

use super::error::{GpuAtlasId, GpuHydroError};
use super::hydro::GpuHydro;
use super::layout::{DISPATCH_STRIDE, Dispatch, ITEM_TEXELS, Item, TEXEL_BYTES, dispatch_bytes};
use soak_gpu::{read_back, scoped};

/// An atlas's texels as the device holds them.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuTexels {
    /// Positions relative to the atlas origin, m.
    pub positions: Vec<[f32; 3]>,
    /// Area vectors, m².
    pub area_vectors: Vec<[f32; 3]>,
    /// Radius of the sphere about the origin that holds every texel, m.
    pub bounding_radius: f64,
}

impl GpuHydro {
    /// Moves the texels of a deformable atlas ([`GpuHydro::upload_deformable`])
    /// with its mesh: new vertex positions (object space, m) go up, and a
    /// kernel recomputes every texel's position from its barycentrics and its
    /// area vector from its triangle's new area, like `Atlas::refresh` on the
    /// CPU. Nothing comes back.
    pub fn deform(&mut self, id: GpuAtlasId, positions: &[Point3<f64>]) -> Result<(), GpuHydroError> {
        let entry = self.entry(id)?;
        let deformable = entry
            .deformable
            .as_ref()
            .ok_or(GpuHydroError::NotDeformable(id))?;
        if positions.len() != deformable.vertex_count {
            return Err(GpuHydroError::VertexCount {
                given: positions.len(),
                expected: deformable.vertex_count,
            });
        }
        if let Some(vertex) = positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(GpuHydroError::NonFiniteVertex { vertex });
        }
        let o = entry.origin;
        // Texels lie on the triangles, so a sphere that holds every vertex
        // holds them: the footprint a sampled sea is read over.
        let radius = positions.iter().map(|p| (p - o).norm()).fold(0.0, f64::max);
        let vertices: Vec<[f32; 4]> = positions
            .iter()
            .map(|p| {
                let r = p - o;
                [r.x as f32, r.y as f32, r.z as f32, 0.0]
            })
            .collect();
        let mut per_page: Vec<Vec<Item>> = vec![Vec::new(); self.pages.len()];
        for s in &entry.segments {
            let end = s.start + s.len;
            let mut start = s.start;
            while start < end {
                let stop = end.min(start + ITEM_TEXELS);
                per_page[s.page].push(Item {
                    body: 0,
                    start,
                    end: stop,
                    partial: 0,
                });
                start = stop;
            }
        }
        let items: Vec<Item> = per_page.concat();
        let mut dispatches = Vec::new();
        let mut groups = Vec::new();
        let mut base = 0u32;
        for (page, list) in per_page.iter().enumerate() {
            if !list.is_empty() {
                let (d, g) = Dispatch::new(base, list.len() as u32, id.0, [0.0; 4]);
                dispatches.push(d);
                groups.push((page, g));
                base += list.len() as u32;
            }
        }
        let limit = self.limit;
        let device = &self.device;
        let queue = &self.queue;
        let mut scratch = self.scratch.lock().unwrap_or_else(|p| p.into_inner());
        let s = &mut *scratch;
        scoped::<_, GpuHydroError>(device, "deforming an atlas", (vertices.len() * 16) as u64, || {
            queue.write_buffer(&deformable.vertices, 0, bytemuck::cast_slice(&vertices));
            queue.write_buffer(&self.radii, id.0 as u64 * 4, bytemuck::bytes_of(&0u32));
            let item_buf = s
                .items
                .ensure(device, (items.len() * size_of::<Item>()) as u64, limit);
            queue.write_buffer(item_buf, 0, bytemuck::cast_slice(&items));
            let dispatch_data = dispatch_bytes(&dispatches);
            let dispatch_buf = s.dispatch.ensure(device, dispatch_data.len() as u64, u64::MAX);
            queue.write_buffer(dispatch_buf, 0, &dispatch_data);
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("soak deformation"),
            });
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("soak deformation"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(self.kernels.deform.pipeline());
                for (k, (page, g)) in groups.iter().enumerate() {
                    let page = &self.pages[*page];
                    let bind = self.kernels.deform.bind(
                        device,
                        &[
                            &page.texels,
                            &page.tribary,
                            &deformable.triangles,
                            &deformable.vertices,
                            &self.radii,
                            s.items.get(),
                            s.dispatch.get(),
                        ],
                    );
                    pass.set_bind_group(0, &bind, &[(k as u64 * DISPATCH_STRIDE) as u32]);
                    pass.dispatch_workgroups(g[0], g[1], 1);
                }
            }
            queue.submit([encoder.finish()]);
            Ok(())
        })?;
        drop(scratch);
        if let Some(entry) = self.atlases.get_mut(id.0 as usize) {
            entry.radius = radius;
            entry.tiles = None;
        }
        Ok(())
    }

    /// Reads an atlas's texels back from the device (for tests and tools:
    /// this waits for the queue and copies the whole atlas).
    pub fn download(&self, id: GpuAtlasId) -> Result<GpuTexels, GpuHydroError> {
        let entry = self.entry(id)?;
        let bytes = entry.len as u64 * TEXEL_BYTES + 16;
        let mut scratch = self.scratch.lock().unwrap_or_else(|p| p.into_inner());
        let s = &mut *scratch;
        let device = &self.device;
        scoped::<_, GpuHydroError>(device, "reading texels back", bytes, || {
            let staging = s.staging.ensure(device, bytes, u64::MAX);
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
            for seg in &entry.segments {
                encoder.copy_buffer_to_buffer(
                    &self.pages[seg.page].texels,
                    seg.start as u64 * TEXEL_BYTES,
                    staging,
                    seg.offset as u64 * TEXEL_BYTES,
                    seg.len as u64 * TEXEL_BYTES,
                );
            }
            encoder.copy_buffer_to_buffer(
                &self.radii,
                id.0 as u64 * 4,
                staging,
                entry.len as u64 * TEXEL_BYTES,
                4,
            );
            self.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let data = read_back(device, s.staging.get(), bytes, "reading texels back")?;
        let f: Vec<f32> = data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        let n = entry.len;
        Ok(GpuTexels {
            positions: (0..n).map(|i| [f[8 * i], f[8 * i + 1], f[8 * i + 2]]).collect(),
            area_vectors: (0..n)
                .map(|i| [f[8 * i + 4], f[8 * i + 5], f[8 * i + 6]])
                .collect(),
            bounding_radius: (f[8 * n] as f64).sqrt(),
        })
    }
}
