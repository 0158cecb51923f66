//! Water surfaces in the kernels' terms: parameters relative to the body's
//! world reference point `o_w`, computed in f64 and rounded once to f32.

use nalgebra::Vector3;

use super::error::GpuHydroError;
use super::layout::{
    Body, PATCH_CELL_FLOATS, PATCH_VELOCITY_CELL_FLOATS, SURFACE_GERSTNER, SURFACE_HEIGHT_FIELD,
    SURFACE_PATCH, SURFACE_PLANE, SURFACE_UNBOUNDED, Wave, u32_indexed,
};
use crate::error::WaterError;
use crate::water::{FlowPlane, Gerstner, HeightField, Plane, SurfacePatch, Unbounded, Water};

/// The height samples of the height fields of one batch and the cell
/// coefficients of its sampled surfaces ([`SurfacePatch`]), each field or
/// patch stored once however many bodies share it (the WGSL binding
/// `heights`).
#[derive(Debug, Default)]
pub struct HeightFields {
    /// Heights minus each field's reference (m), all fields end to end; then
    /// per patch its bicubic coefficients, the constant one minus the
    /// patch's reference (m), and its velocity coefficients (m/s).
    pub samples: Vec<f32>,
    /// (field address, first sample, reference height).
    seen: Vec<(usize, u32, f64)>,
    /// (patch address, where it went).
    patches: Vec<(usize, PatchSlots)>,
}

/// Where a patch's coefficients went in [`HeightFields::samples`].
#[derive(Clone, Copy, Debug)]
struct PatchSlots {
    /// First float of the bicubic coefficients.
    first: u32,
    /// Height the constant coefficients are relative to, m.
    reference: f64,
    /// First float of the velocity coefficients and the velocity grid's
    /// nodes along y, when velocities were sampled.
    velocity: Option<(u32, u32)>,
}

impl HeightFields {
    fn add(&mut self, h: &HeightField) -> Result<(u32, f64), WaterError> {
        let key = h as *const HeightField as usize;
        if let Some(&(_, first, reference)) = self.seen.iter().find(|s| s.0 == key) {
            return Ok((first, reference));
        }
        if h.nx < 2 || h.nz < 2 || h.heights.len() != h.nx * h.nz || h.nx * h.nz > u32::MAX as usize / 2 {
            return Err(WaterError::HeightFieldShape {
                nx: h.nx,
                nz: h.nz,
                len: h.heights.len(),
            });
        }
        for (name, v) in [("spacing x", h.spacing[0]), ("spacing z", h.spacing[1])] {
            if !(v.is_finite() && v > 0.0) {
                return Err(WaterError::Parameter { name, value: v });
            }
        }
        if let Some(i) = h.heights.iter().position(|v| !v.is_finite()) {
            return Err(WaterError::HeightFieldSample {
                index: i,
                value: h.heights[i],
            });
        }
        // Heights relative to their mean keep f32 precision at any sea level.
        let reference = h.heights.iter().sum::<f64>() / h.heights.len() as f64;
        let first = self.samples.len() as u32;
        self.samples
            .extend(h.heights.iter().map(|v| (v - reference) as f32));
        self.seen.push((key, first, reference));
        Ok((first, reference))
    }
}

impl HeightFields {
    /// Appends `p`'s bicubic coefficients (16 floats per cell, `a[p][q]` at
    /// `4 p + q`, cells x fastest) and, when it has them, its velocity
    /// coefficients (24 floats per cell, `c[k]` lane `m` at `3 k + m`, cells
    /// x fastest, then z, then y), once per patch.
    fn add_patch(&mut self, index: usize, p: &SurfacePatch) -> Result<PatchSlots, GpuHydroError> {
        let key = p as *const SurfacePatch as usize;
        if let Some(&(_, slots)) = self.patches.iter().find(|s| s.0 == key) {
            return Ok(slots);
        }
        let grid = p.grid();
        let velocity = p.velocity_grid();
        // The kernel takes the velocity grid's x and z from the patch's.
        let matches = |v: &crate::water::PatchVelocityGrid<'_>| {
            v.nodes[0] == grid.cells[0] + 1
                && v.nodes[2] == grid.cells[1] + 1
                && v.cells[0] == grid.cells[0]
                && v.cells[2] == grid.cells[1]
        };
        if !velocity.as_ref().is_none_or(matches) {
            return Err(GpuHydroError::UnsupportedSurface { body: index });
        }
        let needed = grid.coefficients.len() * PATCH_CELL_FLOATS
            + velocity
                .as_ref()
                .map_or(0, |v| v.coefficients.len() * PATCH_VELOCITY_CELL_FLOATS);
        u32_indexed(
            "the height fields and sampled surfaces of this batch",
            self.samples.len() as u64 + needed as u64,
        )?;
        let bad = |name: &'static str, value: f64| GpuHydroError::Water {
            body: index,
            source: WaterError::Parameter { name, value },
        };
        // Constant terms relative to their mean keep f32 precision at any
        // sea level; the others are differences already.
        let cells = grid.coefficients.len().max(1) as f64;
        let reference = grid.coefficients.iter().map(|a| a[0][0]).sum::<f64>() / cells;
        let start = self.samples.len();
        let first = start as u32;
        for a in grid.coefficients {
            for (p, row) in a.iter().enumerate() {
                for (q, &c) in row.iter().enumerate() {
                    let c = if p == 0 && q == 0 { c - reference } else { c };
                    self.samples.push(c as f32);
                }
            }
        }
        let mut velocity_slots = None;
        if let Some(v) = &velocity {
            let at = self.samples.len() as u32;
            for c in v.coefficients {
                for lanes in c {
                    self.samples.extend(lanes[..3].iter().map(|&x| x as f32));
                }
            }
            velocity_slots = Some((at, v.nodes[1] as u32));
        }
        if let Some(x) = self.samples[start..].iter().copied().find(|x| !x.is_finite()) {
            self.samples.truncate(start);
            return Err(bad("patch coefficient", x as f64));
        }
        if !reference.is_finite() {
            self.samples.truncate(start);
            return Err(bad("patch height", reference));
        }
        let slots = PatchSlots {
            first,
            reference,
            velocity: velocity_slots,
        };
        self.patches.push((key, slots));
        Ok(slots)
    }
}

fn v4(v: &Vector3<f64>, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// Fills the surface fields of `body` (`surface`, `surface2`, `current`,
/// `info`, and `slot.y`, `slot.z` for a [`SurfacePatch`]) for `water` seen
/// from the body's atlas origin at world position `ow` (m), at time `t`
/// (s), appending its waves to `waves` and its height samples or patch
/// coefficients to `heights`. The rest of `body` is the caller's.
///
/// A Gerstner sea is encoded as its waves, which the kernels invert at
/// every texel; a sea sampled once ([`crate::sampled_water`]) is a
/// [`SurfacePatch`], which they read as its polynomials.
///
/// # Errors
/// [`GpuHydroError::UnsupportedSurface`] for a surface the kernels do not know
/// (a custom [`crate::Surface`]), [`GpuHydroError::Water`] for invalid water,
/// [`GpuHydroError::Gpu`] for more patch coefficients than a `u32` indexes;
/// the first two name the body as `index`.
pub fn encode_surface(
    index: usize,
    water: &Water,
    ow: &Vector3<f64>,
    t: f64,
    body: &mut Body,
    waves: &mut Vec<Wave>,
    heights: &mut HeightFields,
) -> Result<(), GpuHydroError> {
    let any = water
        .surface
        .as_any()
        .ok_or(GpuHydroError::UnsupportedSurface { body: index })?;
    let flow = any.downcast_ref::<FlowPlane>();
    if let Some(p) = any.downcast_ref::<Plane>().or(flow.map(|f| &f.plane)) {
        let n = p.normal;
        if !(n.iter().all(|c| c.is_finite()) && n.y > 0.0 && p.offset.is_finite()) {
            return Err(GpuHydroError::Water {
                body: index,
                source: WaterError::PlaneNormal { normal: n.into() },
            });
        }
        body.info[0] = SURFACE_PLANE;
        body.surface = v4(&n, p.offset - n.dot(ow));
        body.current = v4(&p.current, 0.0);
        // A current changing linearly: its velocity at o_w and its rows.
        if let Some(f) = flow {
            let g = &f.gradient;
            body.current = v4(&(p.current + g * (ow - f.about.coords)), 0.0);
            body.flow0 = v4(&g.row(0).transpose(), 0.0);
            body.flow1 = v4(&g.row(1).transpose(), 0.0);
            body.flow2 = v4(&g.row(2).transpose(), 0.0);
        }
    } else if let Some(g) = any.downcast_ref::<Gerstner>() {
        body.info[0] = SURFACE_GERSTNER;
        body.info[1] = waves.len() as u32;
        body.info[2] = g.waves.len() as u32;
        body.surface = [(g.level - ow.y) as f32, 0.0, 0.0, 0.0];
        body.surface2 = [ow.x as f32, ow.z as f32, 0.0, 0.0];
        // Gerstner::new's per-wave constants, from the public fields.
        let n = g.waves.len().max(1) as f64;
        for w in &g.waves {
            let k = w.wavenumber();
            let q = if w.amplitude > 0.0 {
                w.steepness / (k * w.amplitude * n)
            } else {
                0.0
            };
            let omega = (g.gravity * k).sqrt();
            let a = w.direction_deg.to_radians();
            let dir = (a.cos(), a.sin());
            // The phase at o_w and time t, in f64, wrapped into [0, 2π).
            let phase =
                (k * (dir.0 * ow.x + dir.1 * ow.z) - omega * t + w.phase).rem_euclid(std::f64::consts::TAU);
            waves.push(Wave {
                a: [dir.0 as f32, dir.1 as f32, k as f32, omega as f32],
                b: [(q * w.amplitude) as f32, w.amplitude as f32, phase as f32, 0.0],
            });
        }
    } else if let Some(h) = any.downcast_ref::<HeightField>() {
        let (first, reference) = heights
            .add(h)
            .map_err(|source| GpuHydroError::Water { body: index, source })?;
        body.info = [SURFACE_HEIGHT_FIELD, first, h.nx as u32, h.nz as u32];
        body.surface = [
            ((ow.x - h.origin[0]) / h.spacing[0]) as f32,
            ((ow.z - h.origin[1]) / h.spacing[1]) as f32,
            (1.0 / h.spacing[0]) as f32,
            (1.0 / h.spacing[1]) as f32,
        ];
        body.surface2 = [(reference - ow.y) as f32, 0.0, 0.0, 0.0];
        body.current = v4(&Vector3::from(h.current), 0.0);
    } else if let Some(p) = any.downcast_ref::<SurfacePatch>() {
        let slots = heights.add_patch(index, p)?;
        let grid = p.grid();
        let inv = 1.0 / grid.spacing;
        body.info = [
            SURFACE_PATCH,
            slots.first,
            grid.cells[0] as u32,
            grid.cells[1] as u32,
        ];
        body.surface = [
            ((ow.x - grid.origin[0]) * inv) as f32,
            ((ow.z - grid.origin[1]) * inv) as f32,
            inv as f32,
            inv as f32,
        ];
        let (velocity_first, velocity_ny, y) = match (slots.velocity, p.velocity_grid()) {
            (Some((first, ny)), Some(v)) => (first, ny, (ow.y - v.y0) * inv),
            _ => (0, 0, 0.0),
        };
        body.surface2 = [(slots.reference - ow.y) as f32, y as f32, 0.0, 0.0];
        body.current = [0.0; 4];
        body.slot[1] = velocity_first;
        body.slot[2] = velocity_ny;
    } else if let Some(u) = any.downcast_ref::<Unbounded>() {
        body.info[0] = SURFACE_UNBOUNDED;
        body.current = v4(&Vector3::from(u.current), 0.0);
    } else {
        return Err(GpuHydroError::UnsupportedSurface { body: index });
    }
    Ok(())
}
