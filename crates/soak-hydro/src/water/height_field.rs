//! A height field: heights sampled on a regular grid, bilinearly
//! interpolated.

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

use super::Surface;
use crate::error::WaterError;

/// Heights sampled on a regular grid, bilinearly interpolated; outside the
/// grid the nearest edge value holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeightField {
    /// World `(x, z)` of sample `(0, 0)`, m.
    pub origin: [f64; 2],
    /// Spacing between samples along x and z, m.
    pub spacing: [f64; 2],
    /// Samples along x.
    pub nx: usize,
    /// Samples along z.
    pub nz: usize,
    /// Heights, m, row-major with x fastest: `heights[iz * nx + ix]`.
    pub heights: Vec<f64>,
    /// Uniform current, m/s.
    #[serde(default)]
    pub current: [f64; 3],
}

impl HeightField {
    /// A validated height field.
    pub fn new(
        origin: [f64; 2],
        spacing: [f64; 2],
        nx: usize,
        nz: usize,
        heights: Vec<f64>,
    ) -> Result<Self, WaterError> {
        if nx < 2 || nz < 2 || heights.len() != nx * nz {
            return Err(WaterError::HeightFieldShape {
                nx,
                nz,
                len: heights.len(),
            });
        }
        for (name, v) in [("spacing x", spacing[0]), ("spacing z", spacing[1])] {
            if !(v.is_finite() && v > 0.0) {
                return Err(WaterError::Parameter { name, value: v });
            }
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(WaterError::HeightFieldSample {
                index: i,
                value: heights[i],
            });
        }
        Ok(Self {
            origin,
            spacing,
            nx,
            nz,
            heights,
            current: [0.0; 3],
        })
    }
}

/// The grid cell under a point: its corner heights `[h00, h10, h01, h11]`,
/// the point's fractions `(u, v)` across it, and whether the point is
/// inside the grid along x and z (outside, the edge value holds).
struct Cell {
    corners: [f64; 4],
    u: f64,
    v: f64,
    inside: [bool; 2],
}

impl HeightField {
    fn cell(&self, x: f64, z: f64) -> Cell {
        let gx = (x - self.origin[0]) / self.spacing[0];
        let gz = (z - self.origin[1]) / self.spacing[1];
        let (nx, nz) = ((self.nx - 1) as f64, (self.nz - 1) as f64);
        let (fx, fz) = (gx.clamp(0.0, nx), gz.clamp(0.0, nz));
        let (ix, iz) = ((fx as usize).min(self.nx - 2), (fz as usize).min(self.nz - 2));
        let h = |i: usize, j: usize| self.heights[j * self.nx + i];
        Cell {
            corners: [h(ix, iz), h(ix + 1, iz), h(ix, iz + 1), h(ix + 1, iz + 1)],
            u: fx - ix as f64,
            v: fz - iz as f64,
            inside: [(0.0..=nx).contains(&gx), (0.0..=nz).contains(&gz)],
        }
    }
}

impl Surface for HeightField {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        let lo = self.heights.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = self.heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Some((lo, hi))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        let c = self.cell(x, z);
        let [h00, h10, h01, h11] = c.corners;
        (1.0 - c.v) * ((1.0 - c.u) * h00 + c.u * h10) + c.v * ((1.0 - c.u) * h01 + c.u * h11)
    }
    /// The bilinear interpolant's slope; zero across an axis outside the
    /// grid, where the edge value holds.
    fn slope(&self, x: f64, z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        let c = self.cell(x, z);
        let [h00, h10, h01, h11] = c.corners;
        let sx = if c.inside[0] {
            ((1.0 - c.v) * (h10 - h00) + c.v * (h11 - h01)) / self.spacing[0]
        } else {
            0.0
        };
        let sz = if c.inside[1] {
            ((1.0 - c.u) * (h01 - h00) + c.u * (h11 - h10)) / self.spacing[1]
        } else {
            0.0
        };
        [sx, sz]
    }
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        Vector3::from(self.current)
    }
}
