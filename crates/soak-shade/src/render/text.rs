//! Minimal text drawing for figure labels (ab_glyph coverage, alpha-blended
//! in sRGB space).

use ab_glyph::{Font, FontArc, PxScale, ScaleFont};

/// Advance width of `text` at `px` pixels.
pub(crate) fn width(font: &FontArc, px: f32, text: &str) -> f32 {
    let f = font.as_scaled(PxScale::from(px));
    let mut w = 0.0;
    let mut last = None;
    for ch in text.chars() {
        let id = f.glyph_id(ch);
        if let Some(prev) = last {
            w += f.kern(prev, id);
        }
        w += f.h_advance(id);
        last = Some(id);
    }
    w
}

/// Draws `text` with its top-left at `(x, y)`, `px` pixels high.
pub(crate) fn draw(
    image: &mut image::RgbaImage,
    font: &FontArc,
    px: f32,
    x: f32,
    y: f32,
    ink: [u8; 3],
    text: &str,
) {
    let f = font.as_scaled(PxScale::from(px));
    let baseline = y + f.ascent();
    let mut pen = x;
    let mut last = None;
    for ch in text.chars() {
        let id = f.glyph_id(ch);
        if let Some(prev) = last {
            pen += f.kern(prev, id);
        }
        let glyph = id.with_scale_and_position(PxScale::from(px), ab_glyph::point(pen, baseline));
        pen += f.h_advance(id);
        last = Some(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (px_x, px_y) = (
                bounds.min.x as i64 + i64::from(gx),
                bounds.min.y as i64 + i64::from(gy),
            );
            if px_x < 0 || px_y < 0 || px_x >= i64::from(image.width()) || px_y >= i64::from(image.height()) {
                return;
            }
            let p = image.get_pixel_mut(px_x as u32, px_y as u32);
            let a = coverage.clamp(0.0, 1.0);
            for (channel, ink) in p.0.iter_mut().zip(ink) {
                *channel = (f32::from(*channel) * (1.0 - a) + f32::from(ink) * a).round() as u8;
            }
        });
    }
}
