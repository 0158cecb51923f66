//! Liquid textures from per-texel values: the bridge from an atlas (where
//! the wetting simulation keeps one saturation per covered texel) to the
//! W×H image the renderer samples.

use super::scene::LiquidImage;

/// A `width`×`height` liquid texture with `values[i]` at texel
/// `texels[i] = [x, y]` (as [`soak_bake::Atlas::texels`] lists them, row 0
/// at `v = 0`), then grown `gutter` texels into the uncovered texels around
/// the charts (each takes the mean of its covered neighbours), so bilinear
/// filtering at chart edges does not mix in dry gutter texels. Texels not
/// reached stay 0. Values are clamped to `[0, 1]`; texels outside the image
/// and non-finite values are skipped.
///
/// # Example
/// ```
/// use soak_shade::render::liquid_image_from_texels;
/// let img = liquid_image_from_texels(4, 4, &[[1, 1]], &[0.8], 1);
/// assert_eq!(img.get_pixel(1, 1).0[0], 0.8);
/// assert_eq!(img.get_pixel(2, 2).0[0], 0.8); // gutter
/// assert_eq!(img.get_pixel(3, 3).0[0], 0.0); // beyond it
/// ```
pub fn liquid_image_from_texels(
    width: u32,
    height: u32,
    texels: &[[u16; 2]],
    values: &[f32],
    gutter: u32,
) -> LiquidImage {
    let (w, h) = (width.max(1) as usize, height.max(1) as usize);
    let mut data = vec![0.0f32; w * h];
    let mut set = vec![false; w * h];
    for (t, v) in texels.iter().zip(values) {
        let (x, y) = (t[0] as usize, t[1] as usize);
        if x < w && y < h && v.is_finite() {
            data[y * w + x] = v.clamp(0.0, 1.0);
            set[y * w + x] = true;
        }
    }
    for _ in 0..gutter {
        let mut grown = Vec::new();
        for y in 0..h {
            for x in 0..w {
                if set[y * w + x] {
                    continue;
                }
                let (mut sum, mut n) = (0.0f32, 0u32);
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                        if nx >= 0 && ny >= 0 && (nx as usize) < w && (ny as usize) < h {
                            let k = ny as usize * w + nx as usize;
                            if set[k] {
                                sum += data[k];
                                n += 1;
                            }
                        }
                    }
                }
                if n > 0 {
                    grown.push((y * w + x, sum / n as f32));
                }
            }
        }
        if grown.is_empty() {
            break;
        }
        for (k, v) in grown {
            data[k] = v;
            set[k] = true;
        }
    }
    LiquidImage::from_raw(w as u32, h as u32, data).expect("sized by construction")
}
