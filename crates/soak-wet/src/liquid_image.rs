//! The liquid texture as an image: raw values for renderers, and the
//! pseudo-colour view of the thesis' Fig. 7.14 (right column).

use std::path::Path;

use image::{Rgb, RgbImage};
use soak_bake::Atlas;

use crate::error::WetError;

/// Colour of texels no sample covers in [`liquid_rgb`].
pub const UNCOVERED: [u8; 3] = [28, 28, 28];

/// The liquid texture as a `width × height` image of the atlas (row `y`
/// holds texels with `v·H` in `[y, y+1)`), m per pixel: the area-weighted
/// mean `h` of the samples in each texel, `NaN` where no sample lies.
pub fn liquid_texture(atlas: &Atlas, h: &[f64]) -> Result<Vec<f32>, WetError> {
    if h.len() != atlas.len() {
        return Err(WetError::ChannelLength {
            what: "liquid",
            len: h.len(),
            texels: atlas.len(),
        });
    }
    let (w, hh) = (atlas.width() as usize, atlas.height() as usize);
    let mut num = vec![0.0f64; w * hh];
    let mut den = vec![0.0f64; w * hh];
    let mut hit = vec![false; w * hh];
    for ((t, &a), &v) in atlas.texels().iter().zip(atlas.areas()).zip(h) {
        let (x, y) = (t[0] as usize, t[1] as usize);
        if x < w && y < hh {
            let k = y * w + x;
            num[k] += a as f64 * v;
            den[k] += a as f64;
            hit[k] = true;
        }
    }
    Ok((0..w * hh)
        .map(|k| {
            if !hit[k] {
                f32::NAN
            } else if den[k] > 0.0 {
                (num[k] / den[k]) as f32
            } else {
                0.0
            }
        })
        .collect())
}

/// Pseudo-colour of a fill fraction `x` ∈ [0, 1] (clamped; NaN is 0): the
/// classic "jet" ramp of the thesis' figures, dark blue (dry) through
/// blue, cyan, yellow and red to dark red (saturated).
pub fn pseudo_colour(x: f64) -> [u8; 3] {
    const STOPS: [(f64, [f64; 3]); 6] = [
        (0.0, [0.0, 0.0, 0.5]),
        (0.125, [0.0, 0.0, 1.0]),
        (0.375, [0.0, 1.0, 1.0]),
        (0.625, [1.0, 1.0, 0.0]),
        (0.875, [1.0, 0.0, 0.0]),
        (1.0, [0.5, 0.0, 0.0]),
    ];
    let x = if x.is_finite() { x.clamp(0.0, 1.0) } else { 0.0 };
    let k = STOPS
        .iter()
        .rposition(|s| s.0 <= x)
        .unwrap_or(0)
        .min(STOPS.len() - 2);
    let (x0, a) = STOPS[k];
    let (x1, b) = STOPS[k + 1];
    let s = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    [0, 1, 2].map(|c| ((a[c] + (b[c] - a[c]) * s) * 255.0).round() as u8)
}

/// The liquid texture in pseudo-colour: `h / scale` through
/// [`pseudo_colour`] (pass the saturation as `scale` to show the fill),
/// [`UNCOVERED`] where no texel lies.
pub fn liquid_rgb(atlas: &Atlas, h: &[f64], scale: f64) -> Result<RgbImage, WetError> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(WetError::parameter("image.scale", scale, "finite and > 0 m"));
    }
    let tex = liquid_texture(atlas, h)?;
    let (w, hh) = (atlas.width(), atlas.height());
    Ok(RgbImage::from_fn(w, hh, |x, y| {
        let v = tex[(y * w + x) as usize];
        Rgb(if v.is_nan() {
            UNCOVERED
        } else {
            pseudo_colour(v as f64 / scale)
        })
    }))
}

/// Writes [`liquid_rgb`] as a PNG at `path` (its directory must exist).
pub fn write_liquid_png(atlas: &Atlas, h: &[f64], scale: f64, path: &Path) -> Result<(), WetError> {
    liquid_rgb(atlas, h, scale)?
        .save_with_format(path, image::ImageFormat::Png)
        .map_err(|e| WetError::Image {
            path: Some(path.to_path_buf()),
            reason: e.to_string(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jet_runs_from_blue_to_red() {
        let dry = pseudo_colour(0.0);
        let wet = pseudo_colour(1.0);
        assert_eq!(dry, [0, 0, 128]);
        assert_eq!(wet, [128, 0, 0]);
        assert_eq!(pseudo_colour(0.5), [128, 255, 128]);
        assert_eq!(pseudo_colour(f64::NAN), dry);
        assert_eq!(pseudo_colour(7.0), wet);
    }
}
