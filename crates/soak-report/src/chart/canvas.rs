//! The plotters backend that sets text itself in the embedded DejaVu Sans.

use std::sync::OnceLock;

use ab_glyph::Font as _;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform,
};
use soak_shade::render::{Font, TextLayout, layout_text};

use super::ChartError;

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVuSans-LICENSE.txt`).
pub const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
/// The family name text styles carry; every family is drawn in [`FONT`].
pub(super) const FAMILY: &str = "sans-serif";

/// The embedded font, parsed once per process.
pub(super) fn font() -> Result<&'static Font, ChartError> {
    static PARSED: OnceLock<Option<Font>> = OnceLock::new();
    PARSED
        .get_or_init(|| Font::try_from_slice(FONT).ok())
        .as_ref()
        .ok_or(ChartError::Font)
}

/// A bitmap backend that sets text itself with `ab_glyph`: glyphs placed at
/// their pixel bounds (side bearings and kerning kept), anchors and the
/// quarter-turn rotations plotters asks for. Everything else goes to
/// plotters' `BitMapBackend`.
pub(super) struct Canvas<'a> {
    pub(super) inner: BitMapBackend<'a>,
    pub(super) font: &'static Font,
}

/// Glyphs of `text` at `size` px laid out from the origin on the ascent line:
/// the glyphs, the advance width and the line height (ascent − descent), px.
fn layout(font: &Font, text: &str, size: f64) -> TextLayout {
    layout_text(font, size as f32, 0.0, 0.0, text)
}

impl DrawingBackend for Canvas<'_> {
    type ErrorType = <BitMapBackend<'static> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }

    fn draw_pixel(
        &mut self,
        p: BackendCoord,
        c: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(p, c)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(a, b, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        centre: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(centre, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vertices: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(vertices, style)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (w, h): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.blit_bitmap(pos, (w, h), src)
    }

    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let TextLayout {
            glyphs,
            width,
            height,
        } = layout(self.font, text, style.size());
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Center => -width / 2.0,
            HPos::Right => -width,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0.0,
            VPos::Center => -height / 2.0,
            VPos::Bottom => -height,
        };
        let turn: FontTransform = style.transform();
        for g in glyphs {
            let Some(outline) = self.font.outline_glyph(g) else {
                continue;
            };
            let b = outline.px_bounds();
            let mut pixels = Vec::new();
            outline.draw(|x, y, coverage| {
                if coverage > 0.0 {
                    let lx = (b.min.x + dx).round() as i32 + x as i32;
                    let ly = (b.min.y + dy).round() as i32 + y as i32;
                    pixels.push((lx, ly, coverage.min(1.0)));
                }
            });
            for (lx, ly, coverage) in pixels {
                let (tx, ty) = turn.transform(lx, ly);
                let c = BackendColor {
                    alpha: color.alpha * coverage as f64,
                    rgb: color.rgb,
                };
                self.inner.draw_pixel((pos.0 + tx, pos.1 + ty), c)?;
            }
        }
        Ok(())
    }

    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let TextLayout { width, height, .. } = layout(self.font, text, style.size());
        Ok((width.ceil() as u32, height.ceil() as u32))
    }
}
