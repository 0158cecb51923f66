//! Colour helpers for reading rendered images: sRGB decoding, luminance,
//! hue. Linear RGB in, linear RGB out, unless a name says sRGB.

/// The sRGB transfer function's inverse: an encoded value in `[0, 1]` to
/// linear.
pub fn srgb_to_linear(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB transfer function: linear `[0, 1]` to encoded.
pub fn linear_to_srgb(v: f64) -> f64 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.0031308 {
        v * 12.92
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// Linear RGB of an 8-bit sRGB pixel.
pub fn pixel_to_linear(p: image::Rgba<u8>) -> [f64; 3] {
    std::array::from_fn(|c| srgb_to_linear(f64::from(p.0[c]) / 255.0))
}

/// An 8-bit sRGB pixel (alpha 255) of a linear RGB colour.
pub fn linear_to_pixel(c: [f64; 3]) -> image::Rgba<u8> {
    let e = |v: f64| (linear_to_srgb(v) * 255.0).round() as u8;
    image::Rgba([e(c[0]), e(c[1]), e(c[2]), 255])
}

/// Relative luminance `Y` of linear Rec. 709 / sRGB primaries.
pub fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// Hue angle in degrees `[0, 360)` of an RGB colour (the HSV hexagon's,
/// 0 red, 120 green, 240 blue); `None` for a grey.
pub fn hue_degrees(c: [f64; 3]) -> Option<f64> {
    let max = c[0].max(c[1]).max(c[2]);
    let min = c[0].min(c[1]).min(c[2]);
    let d = max - min;
    if d.is_nan() || d <= 1e-12 {
        return None;
    }
    let h = if max == c[0] {
        ((c[1] - c[2]) / d).rem_euclid(6.0)
    } else if max == c[1] {
        (c[2] - c[0]) / d + 2.0
    } else {
        (c[0] - c[1]) / d + 4.0
    };
    Some((60.0 * h).rem_euclid(360.0))
}

/// Smallest angle between two hues, degrees in `[0, 180]`.
pub fn hue_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

/// Mean linear RGB of the pixels of `image` in the rectangle
/// `x0..x1` × `y0..y1` (clamped to the image).
pub fn mean_linear(image: &image::RgbaImage, x0: u32, y0: u32, x1: u32, y1: u32) -> [f64; 3] {
    let (x1, y1) = (x1.min(image.width()), y1.min(image.height()));
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for y in y0..y1 {
        for x in x0..x1 {
            let c = pixel_to_linear(*image.get_pixel(x, y));
            for k in 0..3 {
                sum[k] += c[k];
            }
            n += 1.0;
        }
    }
    if n > 0.0 { sum.map(|s| s / n) } else { sum }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips() {
        for i in 0..=255 {
            let v = f64::from(i) / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(v)) - v).abs() < 1e-12);
        }
    }

    #[test]
    fn hues() {
        assert_eq!(hue_degrees([1.0, 0.0, 0.0]), Some(0.0));
        assert_eq!(hue_degrees([0.0, 1.0, 0.0]), Some(120.0));
        assert_eq!(hue_degrees([0.0, 0.0, 1.0]), Some(240.0));
        assert_eq!(hue_degrees([0.5; 3]), None);
        assert_eq!(hue_distance(350.0, 10.0), 20.0);
    }
}
