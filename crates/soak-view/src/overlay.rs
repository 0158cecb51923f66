//! The overlay: lines of text in a translucent box at the top left of a
//! frame, drawn on the CPU with an 8×8 bitmap font.

use font8x8::UnicodeFonts as _;
use image::RgbaImage;

/// Margin inside the box, pixels.
const PAD: u32 = 6;

/// Draws `lines` at the top left of `image`: light text on a dark box
/// blended at 70 %, the font doubled where the lines fit so; characters
/// the font lacks are drawn as `?`. Lines that do not fit are cut at the
/// image's edge.
pub(crate) fn draw(image: &mut RgbaImage, lines: &[String]) {
    if lines.is_empty() {
        return;
    }
    let (w, h) = image.dimensions();
    let widest = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as u32;
    // Pixels per font pixel, and the glyph cell's side.
    let scale = if widest * 16 + 2 * PAD <= w { 2 } else { 1 };
    let cell = 8 * scale;
    let box_w = (widest * cell + 2 * PAD).min(w);
    let box_h = (lines.len() as u32 * (cell + 2) + 2 * PAD).min(h);
    for y in 0..box_h {
        for x in 0..box_w {
            let p = image.get_pixel_mut(x, y);
            for c in 0..3 {
                p[c] = (f32::from(p[c]) * 0.3 + 10.0 * 0.7) as u8;
            }
        }
    }
    for (row, line) in lines.iter().enumerate() {
        let y0 = PAD + row as u32 * (cell + 2);
        for (col, ch) in line.chars().enumerate() {
            let x0 = PAD + col as u32 * cell;
            let glyph = font8x8::BASIC_FONTS
                .get(ch)
                .or_else(|| font8x8::BASIC_FONTS.get('?'))
                .unwrap_or([0; 8]);
            for (gy, bits) in glyph.iter().enumerate() {
                for gx in 0..8u32 {
                    if bits & (1 << gx) == 0 {
                        continue;
                    }
                    for sy in 0..scale {
                        for sx in 0..scale {
                            let (x, y) = (x0 + gx * scale + sx, y0 + gy as u32 * scale + sy);
                            if x < box_w && y < box_h {
                                image.put_pixel(x, y, image::Rgba([235, 240, 245, 255]));
                            }
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_drawn_in_its_box_and_nowhere_else() {
        let mut image = RgbaImage::from_pixel(200, 100, image::Rgba([100, 150, 200, 255]));
        draw(&mut image, &["Ab 1".to_string(), "x".to_string()]);
        // The box darkens what it covers, text is light, the rest untouched.
        let lit = image.pixels().filter(|p| p[0] == 235).count();
        assert!(lit > 30, "{lit} text pixels");
        assert_eq!(*image.get_pixel(199, 99), image::Rgba([100, 150, 200, 255]));
        assert!(image.get_pixel(1, 1)[0] < 100);
        // A line wider than the image is cut, not drawn out of bounds.
        draw(
            &mut image,
            &["a very long line that does not fit in two hundred pixels".to_string()],
        );
    }
}
