//! Text for figure labels: one line laid out with ab_glyph (kerning and
//! advances), and drawn by glyph coverage, alpha-blended in sRGB space.

use ab_glyph::{Font as _, FontArc, Glyph, PxScale, ScaleFont, point};

/// One line of text laid out by [`layout_text`].
#[derive(Debug, Clone)]
pub struct TextLayout {
    /// The glyphs, kerned and advanced along the baseline, which lies the
    /// font's ascent below the line's top.
    pub glyphs: Vec<Glyph>,
    /// Advance width of the line, px.
    pub width: f32,
    /// Line height (ascent − descent), px.
    pub height: f32,
}

/// Lays out `text` as one line `px` pixels high with its top-left at
/// `(x, y)`, in ab_glyph's pixel coordinates (y down). The glyphs are
/// ready for [`ab_glyph::Font::outline_glyph`]; the material sweep's labels
/// and the `soak` command's charts are both set with it.
pub fn layout_text(font: &FontArc, px: f32, x: f32, y: f32, text: &str) -> TextLayout {
    let scale = PxScale::from(px);
    let f = font.as_scaled(scale);
    let baseline = y + f.ascent();
    let mut pen = x;
    let mut last = None;
    let mut glyphs = Vec::with_capacity(text.len());
    for ch in text.chars() {
        let id = f.glyph_id(ch);
        if let Some(prev) = last {
            pen += f.kern(prev, id);
        }
        glyphs.push(id.with_scale_and_position(scale, point(pen, baseline)));
        pen += f.h_advance(id);
        last = Some(id);
    }
    TextLayout {
        glyphs,
        width: pen - x,
        height: f.ascent() - f.descent(),
    }
}

/// Advance width of `text` at `px` pixels.
pub(crate) fn width(font: &FontArc, px: f32, text: &str) -> f32 {
    layout_text(font, px, 0.0, 0.0, text).width
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
    for glyph in layout_text(font, px, x, y, text).glyphs {
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
