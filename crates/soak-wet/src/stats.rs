//! Area-weighted statistics of a liquid texture: totals and a histogram of
//! the fill fraction, for reports and snapshot tests.

use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

/// Bins of [`LiquidStats::histogram`].
pub const HISTOGRAM_BINS: usize = 10;

/// Fill from which [`LiquidStats::wet_area`] counts a texel as wet.
pub const WET_FILL: f64 = 0.01;

/// Area-weighted summary of a liquid texture.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LiquidStats {
    /// Total liquid `Σ a_i h_i`, m³.
    pub total: f64,
    /// Surface area `Σ a_i`, m².
    pub area: f64,
    /// Area at least 1 % full (`h ≥ 0.01 h_max`), m². (Diffusion leaves
    /// traces everywhere it reaches; this counts visibly wet surface.)
    pub wet_area: f64,
    /// Mean fill fraction `Σ a_i h_i / (h_max Σ a_i)`.
    pub mean_fill: f64,
    /// Largest `h_i`, m.
    pub max: f64,
    /// Fraction of the area whose fill `h / h_max` lies in each of
    /// [`HISTOGRAM_BINS`] equal bins of [0, 1] (the last includes 1; dry
    /// texels count in the first).
    pub histogram: [f64; HISTOGRAM_BINS],
}

impl LiquidStats {
    /// Statistics of `h` (m per texel) over `atlas` with saturation `h_max` (m).
    pub fn of(atlas: &Atlas, h: &[f64], saturation: f64) -> Self {
        let mut total = 0.0;
        let mut area = 0.0;
        let mut wet_area = 0.0;
        let mut max: f64 = 0.0;
        let mut histogram = [0.0; HISTOGRAM_BINS];
        for (&h, &a) in h.iter().zip(atlas.areas()) {
            let a = a as f64;
            total += a * h;
            area += a;
            if h > 0.0 && h >= WET_FILL * saturation {
                wet_area += a;
            }
            max = max.max(h);
            let fill = if saturation > 0.0 { h / saturation } else { 0.0 };
            let bin = ((fill * HISTOGRAM_BINS as f64) as usize).min(HISTOGRAM_BINS - 1);
            histogram[bin] += a;
        }
        if area > 0.0 {
            for b in &mut histogram {
                *b /= area;
            }
        }
        Self {
            total,
            area,
            wet_area,
            mean_fill: if area > 0.0 && saturation > 0.0 {
                total / (area * saturation)
            } else {
                0.0
            },
            max,
            histogram,
        }
    }

    /// The same statistics rounded to `digits` significant digits (the
    /// histogram's fractions to `digits − 1` decimals), for snapshots.
    pub fn rounded(&self, digits: i32) -> Self {
        let r = |x: f64| round_significant(x, digits);
        let scale = 10f64.powi((digits - 1).max(0));
        Self {
            total: r(self.total),
            area: r(self.area),
            wet_area: r(self.wet_area),
            mean_fill: r(self.mean_fill),
            max: r(self.max),
            histogram: self.histogram.map(|x| (x * scale).round() / scale),
        }
    }
}

/// `x` rounded to `digits` significant digits.
pub fn round_significant(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}
