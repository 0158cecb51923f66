//! Water surfaces in the kernels' terms: parameters relative to the body's
//! world reference point `o_w`, computed in f64 and rounded once to f32.

use nalgebra::Vector3;

use super::error::GpuHydroError;
use super::layout::{Body, SURFACE_GERSTNER, SURFACE_HEIGHT_FIELD, SURFACE_PLANE, SURFACE_UNBOUNDED, Wave};
use crate::error::WaterError;
use crate::water::{Gerstner, HeightField, Plane, Unbounded, Water};

/// The height samples of the height fields of one batch, each field stored
/// once however many bodies share it (the WGSL binding `heights`).
#[derive(Debug, Default)]
pub struct HeightFields {
    /// Heights minus each field's reference, m, all fields end to end.
    pub samples: Vec<f32>,
    /// (field address, first sample, reference height).
    seen: Vec<(usize, u32, f64)>,
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

fn v4(v: &Vector3<f64>, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// Fills the surface fields of `body` (`surface`, `surface2`, `current`,
/// `info`) for `water` seen from the body's atlas origin at world position
/// `ow` (m), at time `t` (s), appending its waves to `waves` and its height
/// samples to `heights`. The rest of `body` is the caller's.
///
/// # Errors
/// [`GpuHydroError::UnsupportedSurface`] for a surface the kernels do not know
/// (a custom [`crate::Surface`]), [`GpuHydroError::Water`] for invalid water;
/// both name the body as `index`.
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
    if let Some(p) = any.downcast_ref::<Plane>() {
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
    } else if let Some(u) = any.downcast_ref::<Unbounded>() {
        body.info[0] = SURFACE_UNBOUNDED;
        body.current = v4(&Vector3::from(u.current), 0.0);
    } else {
        return Err(GpuHydroError::UnsupportedSurface { body: index });
    }
    Ok(())
}
