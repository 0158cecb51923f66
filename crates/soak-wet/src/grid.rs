//! The regular voxel grid of a liquid density field (the thesis' CDL,
//! Eq. 5.1–5.2), with cubic voxels.

use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use crate::error::WetError;

/// The largest field, in voxels (2^24: 256³, or 64 MiB of f32 per channel).
pub const MAX_VOXELS: u64 = 1 << 24;

/// Voxels along the longest side of a body's box at most, when the size is
/// chosen automatically.
pub const AUTO_MAX_CELLS: u32 = 128;

/// Voxel edge in mean texel edges when the size is chosen automatically.
pub const AUTO_TEXEL_SPAN: f64 = 8.0;

/// How fine a field's voxels are.
///
/// The thesis sizes its grid from the mean texel size: voxels large enough
/// to hold a good sample of texels for the Shepard average, small enough to
/// resolve the wet patterns. The mean texel edge is `√(Σ a_i / N)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "value", rename_all = "snake_case")]
pub enum FieldResolution {
    /// [`AUTO_TEXEL_SPAN`] (8) mean texel edges per voxel edge (about 64
    /// texels per voxel on a flat surface), but at most
    /// [`AUTO_MAX_CELLS`] (128) voxels along the longest side of the box.
    #[default]
    Auto,
    /// This many mean texel edges per voxel edge.
    TexelSpan(f64),
    /// Voxel edge, m.
    VoxelSize(f64),
    /// This many voxels along the longest side of the box.
    Cells(u32),
}

impl FieldResolution {
    /// The variant's name, for messages.
    pub fn name(&self) -> &'static str {
        match self {
            FieldResolution::Auto => "Auto",
            FieldResolution::TexelSpan(_) => "TexelSpan",
            FieldResolution::VoxelSize(_) => "VoxelSize",
            FieldResolution::Cells(_) => "Cells",
        }
    }

    /// The voxel edge (m) for a box whose longest side is `longest` (m)
    /// holding texels of mean edge `texel` (m; `None` when unknown).
    pub fn voxel_size(&self, longest: f64, texel: Option<f64>) -> Result<f64, WetError> {
        let size = match *self {
            FieldResolution::Auto => {
                let t = texel.ok_or(WetError::Resolution {
                    resolution: self.name(),
                })?;
                (AUTO_TEXEL_SPAN * t).max(longest / AUTO_MAX_CELLS as f64)
            }
            FieldResolution::TexelSpan(span) => {
                if !(span.is_finite() && span > 0.0) {
                    return Err(WetError::parameter(
                        "diffusion.resolution.texel_span",
                        span,
                        "finite and > 0",
                    ));
                }
                span * texel.ok_or(WetError::Resolution {
                    resolution: self.name(),
                })?
            }
            FieldResolution::VoxelSize(size) => size,
            FieldResolution::Cells(n) => {
                if n == 0 {
                    return Err(WetError::parameter("diffusion.resolution.cells", 0.0, ">= 1"));
                }
                longest / n as f64
            }
        };
        if !(size.is_finite() && size > 0.0) {
            return Err(WetError::parameter(
                "diffusion.resolution.voxel_size",
                size,
                "finite and > 0 m",
            ));
        }
        Ok(size)
    }
}

/// A regular grid of cubic voxels: voxel `(i, j, k)` spans
/// `origin + voxel_size · [(i, j, k), (i+1, j+1, k+1)]`.
///
/// It carries a liquid density field (the thesis' CDL, Eq. 5.1–5.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VoxelGrid {
    /// Lower corner of voxel (0, 0, 0), m, in the field's frame (object
    /// space for a body's own field, world space for a shared one).
    pub origin: [f64; 3],
    /// Voxel edge Δx, m.
    pub voxel_size: f64,
    /// Voxels along x, y and z.
    pub dims: [u32; 3],
}

impl VoxelGrid {
    /// The grid of cubic voxels of edge `voxel_size` (m) covering the box
    /// `[min, max]` (m), centred on it: `max(1, ⌈extent/Δx⌉)` voxels per
    /// axis. A flat surface in a plane of the box so sits in the middle of
    /// one layer of voxels.
    pub fn covering(min: Point3<f64>, max: Point3<f64>, voxel_size: f64) -> Result<Self, WetError> {
        let bad_box = || WetError::FieldBox {
            min: min.into(),
            max: max.into(),
        };
        if !(0..3).all(|k| min[k].is_finite() && max[k].is_finite() && min[k] <= max[k]) {
            return Err(bad_box());
        }
        if !(voxel_size.is_finite() && voxel_size > 0.0) {
            return Err(WetError::parameter(
                "diffusion.resolution.voxel_size",
                voxel_size,
                "finite and > 0 m",
            ));
        }
        let mut dims = [0u64; 3];
        let mut origin = [0.0; 3];
        for k in 0..3 {
            let extent = max[k] - min[k];
            let n = ((extent / voxel_size) * (1.0 - 1e-12)).ceil().max(1.0);
            if n.is_nan() || n >= 1e9 {
                return Err(WetError::FieldTooLarge {
                    dims: [u64::MAX; 3],
                    voxels: u64::MAX,
                    limit: MAX_VOXELS,
                });
            }
            dims[k] = n as u64;
            origin[k] = 0.5 * (min[k] + max[k]) - 0.5 * n * voxel_size;
        }
        let voxels = dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]);
        if voxels > MAX_VOXELS {
            return Err(WetError::FieldTooLarge {
                dims,
                voxels,
                limit: MAX_VOXELS,
            });
        }
        Ok(Self {
            origin,
            voxel_size,
            dims: dims.map(|d| d as u32),
        })
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.dims.iter().map(|&d| d as usize).product()
    }

    /// Position of `p` in voxel units: voxel `(i, j, k)` spans
    /// `[i, i+1) × [j, j+1) × [k, k+1)` and has its centre at `+0.5`.
    #[inline]
    pub fn grid_coords(&self, p: &Point3<f64>) -> [f64; 3] {
        let s = 1.0 / self.voxel_size;
        [
            (p.x - self.origin[0]) * s,
            (p.y - self.origin[1]) * s,
            (p.z - self.origin[2]) * s,
        ]
    }

    /// The voxel holding grid coordinates `g`, with points up to `slack`
    /// voxels outside the grid clamped onto its border; `None` farther out
    /// (or for non-finite coordinates).
    #[inline]
    pub fn cell(&self, g: [f64; 3], slack: f64) -> Option<[u32; 3]> {
        let mut c = [0u32; 3];
        for k in 0..3 {
            let n = self.dims[k] as f64;
            if !(g[k] >= -slack && g[k] < n + slack) {
                return None;
            }
            c[k] = (g[k].floor().clamp(0.0, n - 1.0)) as u32;
        }
        Some(c)
    }

    /// Linear index of voxel `c` (x fastest).
    #[inline]
    pub fn index(&self, c: [u32; 3]) -> usize {
        c[0] as usize + self.dims[0] as usize * (c[1] as usize + self.dims[1] as usize * c[2] as usize)
    }

    /// Centre of voxel `c` in the field's frame, m.
    pub fn center(&self, c: [u32; 3]) -> Point3<f64> {
        Point3::new(
            self.origin[0] + (c[0] as f64 + 0.5) * self.voxel_size,
            self.origin[1] + (c[1] as f64 + 0.5) * self.voxel_size,
            self.origin[2] + (c[2] as f64 + 0.5) * self.voxel_size,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_cover_a_cube_exactly() {
        let g = VoxelGrid::covering(
            Point3::new(-0.5, -0.5, -0.5),
            Point3::new(0.5, 0.5, 0.5),
            1.0 / 64.0,
        )
        .unwrap();
        assert_eq!(g.dims, [64, 64, 64]);
        assert_eq!(
            g.cell(g.grid_coords(&Point3::new(0.5, 0.5, 0.5)), 1e-3),
            Some([63, 63, 63])
        );
        assert_eq!(
            g.cell(g.grid_coords(&Point3::new(-0.5, 0.0, 0.5)), 1e-3),
            Some([0, 32, 63])
        );
        assert_eq!(g.cell(g.grid_coords(&Point3::new(0.6, 0.0, 0.0)), 1e-3), None);
    }

    #[test]
    fn a_flat_plate_sits_in_the_middle_of_one_layer() {
        let g = VoxelGrid::covering(
            Point3::new(-1.0, -0.001, -1.0),
            Point3::new(1.0, 0.001, 1.0),
            0.05,
        )
        .unwrap();
        assert_eq!(g.dims, [40, 1, 40]);
        assert!((g.center([0, 0, 0]).y).abs() < 1e-12);
    }

    #[test]
    fn huge_fields_are_refused() {
        let e = VoxelGrid::covering(Point3::origin(), Point3::new(1.0, 1.0, 1.0), 1e-3).unwrap_err();
        assert!(matches!(e, WetError::FieldTooLarge { .. }), "{e}");
        assert!(VoxelGrid::covering(Point3::origin(), Point3::new(f64::NAN, 1.0, 1.0), 0.1).is_err());
        assert!(FieldResolution::Cells(0).voxel_size(1.0, None).is_err());
        assert!(FieldResolution::Auto.voxel_size(1.0, None).is_err());
        assert_eq!(
            FieldResolution::Cells(64).voxel_size(2.0, None).unwrap(),
            2.0 / 64.0
        );
    }
}
