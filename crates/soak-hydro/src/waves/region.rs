//! The square region interactive waves cover ([`WaveRegion`]) and a
//! snapshot of their elevation over it ([`WaveHeights`]), read bilinearly
//! between cell centres.

use serde::Serialize;

use crate::error::WaterError;

/// Most cells along a side of an [`InteractiveWaves`](super::InteractiveWaves) region (2048² cells
/// hold about 300 MB of state and plans).
pub const MAX_WAVE_CELLS: usize = 2048;

/// The square region an [`InteractiveWaves`](super::InteractiveWaves) covers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct WaveRegion {
    /// Centre `(x, z)`, world, m.
    pub centre: [f64; 2],
    /// Side, m.
    pub size: f64,
    /// Cells per side (even, 8 to [`MAX_WAVE_CELLS`]).
    pub cells: usize,
}

impl WaveRegion {
    /// Cell size, m.
    pub fn cell(&self) -> f64 {
        self.size / self.cells as f64
    }
}

/// The elevation of an [`InteractiveWaves`](super::InteractiveWaves) at one time
/// ([`InteractiveWaves::snapshot`](super::InteractiveWaves::snapshot)), e.g. for drawing the surface.
#[derive(Clone, Debug, PartialEq)]
pub struct WaveHeights {
    /// The region it covers.
    pub region: WaveRegion,
    /// Elevation per cell, m (cell `(ix, iz)` at `iz · n + ix`).
    pub heights: Vec<f64>,
}

impl WaveHeights {
    /// The elevation at `(x, z)` (world, m), bilinear between cell
    /// centres; 0 outside the region (and for heights of the wrong length).
    pub fn height(&self, x: f64, z: f64) -> f64 {
        if self.heights.len() != self.region.cells * self.region.cells {
            return 0.0;
        }
        bilinear(&self.region, &self.heights, x, z)
    }
}

/// What [`InteractiveWaves::new`] refuses (shared with the GPU solver).
pub(crate) fn check_waves(
    region: &WaveRegion,
    gravity: f64,
    density: f64,
    sponge: usize,
) -> Result<(), WaterError> {
    let bad = |name: &'static str, value: f64| Err(WaterError::Parameter { name, value });
    if !(region.size.is_finite() && region.size > 0.0) {
        return bad("waves.size", region.size);
    }
    if region.cells < 8 || region.cells % 2 == 1 || region.cells > MAX_WAVE_CELLS {
        return bad("waves.cells", region.cells as f64);
    }
    if !region.centre.iter().all(|c| c.is_finite()) {
        return bad("waves.centre", region.centre[0] + region.centre[1]);
    }
    if !(gravity.is_finite() && gravity > 0.0) {
        return bad("waves.gravity", gravity);
    }
    if !(density.is_finite() && density > 0.0) {
        return bad("waves.density", density);
    }
    if 4 * sponge > region.cells {
        return bad("waves.sponge", sponge as f64);
    }
    Ok(())
}

/// The elevation `h` (per cell of `region`) at `(x, z)` (world, m),
/// bilinear between cell centres; 0 outside the cells' centres.
pub(super) fn bilinear(region: &WaveRegion, h: &[f64], x: f64, z: f64) -> f64 {
    let n = region.cells;
    let d = region.cell();
    let half = 0.5 * region.size;
    let (x0, z0) = (region.centre[0] - half, region.centre[1] - half);
    let (u, v) = ((x - x0) / d - 0.5, (z - z0) / d - 0.5);
    if !(u >= 0.0 && v >= 0.0 && u <= (n - 1) as f64 && v <= (n - 1) as f64) {
        return 0.0;
    }
    let (i, j) = ((u as usize).min(n - 2), (v as usize).min(n - 2));
    let (fu, fv) = (u - i as f64, v - j as f64);
    let at = |i: usize, j: usize| h[j * n + i];
    (1.0 - fv) * ((1.0 - fu) * at(i, j) + fu * at(i + 1, j))
        + fv * ((1.0 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1))
}
