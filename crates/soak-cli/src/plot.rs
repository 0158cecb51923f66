//! Line charts written as PNG: a title, axis labels with units, several
//! series (lines, dashed lines, markers), linear or logarithmic axes, a legend
//! that never covers the data, and text notes at data coordinates. Several
//! charts side by side make one figure.
//!
//! Text is set in DejaVu Sans, embedded in the binary (`assets/`), laid out
//! by [`soak_shade::render::layout_text`] (as the renderer's figure labels)
//! and drawn by the backend here, so the plots look the same on every
//! machine and need no system fonts.
//!
//! ```ignore
//! let chart = Chart::new("Submerged volume")
//!     .x(Axis::linear("water level d (m)"))
//!     .y(Axis::log10("error (fraction of the volume)"))
//!     .series(Series::new("texels 256²", points).marker(Marker::Circle));
//! Figure::new(1200, 600).panel(chart).write_png("out/volume.png")?;
//! ```

// A small toolkit: each command uses the parts it needs.
#![allow(dead_code)]

use std::path::Path;
use std::sync::OnceLock;

use ab_glyph::Font as _;
use anyhow::{Context, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
/// Colours of series and notes.
pub use plotters::style::RGBColor;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform,
};
use soak_shade::render::{Font, TextLayout, layout_text};

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVuSans-LICENSE.txt`).
pub(crate) const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
/// The family name text styles carry; every family is drawn in [`FONT`].
const FAMILY: &str = "sans-serif";

/// The embedded font, parsed once per process.
fn font() -> anyhow::Result<&'static Font> {
    static PARSED: OnceLock<Option<Font>> = OnceLock::new();
    PARSED
        .get_or_init(|| Font::try_from_slice(FONT).ok())
        .as_ref()
        .ok_or_else(|| anyhow!("the embedded DejaVu Sans font could not be parsed"))
}

/// A bitmap backend that sets text itself with `ab_glyph`: glyphs placed at
/// their pixel bounds (side bearings and kerning kept), anchors and the
/// quarter-turn rotations plotters asks for. Everything else goes to
/// plotters' `BitMapBackend`.
struct Canvas<'a> {
    inner: BitMapBackend<'a>,
    font: &'static Font,
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

/// How an axis maps values to the page.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Evenly spaced values.
    Linear,
    /// Decades evenly spaced; ticks at powers of ten. Values ≤ 0 are not drawn.
    Log10,
    /// Octaves evenly spaced; ticks at powers of two. Values ≤ 0 are not drawn.
    Log2,
}

impl Scale {
    fn forward(self, v: f64) -> Option<f64> {
        let t = match self {
            Scale::Linear => v,
            Scale::Log10 if v > 0.0 => v.log10(),
            Scale::Log2 if v > 0.0 => v.log2(),
            _ => return None,
        };
        t.is_finite().then_some(t)
    }

    fn inverse(self, t: f64) -> f64 {
        match self {
            Scale::Linear => t,
            Scale::Log10 => 10f64.powf(t),
            Scale::Log2 => t.exp2(),
        }
    }
}

/// One axis: its label (with units), scale, optional range and tick format.
#[derive(Clone, Debug)]
pub struct Axis {
    label: String,
    scale: Scale,
    range: Option<(f64, f64)>,
    format: Option<fn(f64) -> String>,
}

impl Axis {
    /// A linear axis labelled `label` (put the units in it: "depth (m)").
    pub fn linear(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            scale: Scale::Linear,
            range: None,
            format: None,
        }
    }

    /// A base-10 logarithmic axis.
    pub fn log10(label: impl Into<String>) -> Self {
        Self {
            scale: Scale::Log10,
            ..Self::linear(label)
        }
    }

    /// A base-2 logarithmic axis (texture sizes, say).
    pub fn log2(label: impl Into<String>) -> Self {
        Self {
            scale: Scale::Log2,
            ..Self::linear(label)
        }
    }

    /// Fixes the range (in data units); otherwise it fits the data. On log
    /// axes the range widens to whole decades (octaves).
    pub fn range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }

    /// Formats tick values (data units). Defaults: plain numbers on linear
    /// axes, `10⁻³`-style powers on log10 axes, plain numbers on log2 axes.
    pub fn format(mut self, f: fn(f64) -> String) -> Self {
        self.format = Some(f);
        self
    }

    fn tick_label(&self, t: f64) -> String {
        match self.scale {
            Scale::Linear => match self.format {
                Some(f) => f(t),
                None => linear_label(t),
            },
            Scale::Log10 | Scale::Log2 => {
                if (t - t.round()).abs() > 1e-6 {
                    return String::new();
                }
                let v = self.scale.inverse(t.round());
                match (self.format, self.scale) {
                    (Some(f), _) => f(v),
                    (None, Scale::Log10) => power_of_ten(t.round() as i32),
                    _ => linear_label(v),
                }
            }
        }
    }
}

/// A plain tick label: no trailing zeros, no `-0`.
fn linear_label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// `10⁻³`, `10⁰`, `10²`.
pub fn power_of_ten(k: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for c in k.unsigned_abs().to_string().chars() {
        s.push(SUP[c.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}

/// How a series joins its points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Line {
    /// A solid line.
    Solid,
    /// A dashed line.
    Dashed,
    /// Markers only.
    None,
}

/// The mark drawn at every point of a series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// No mark.
    None,
    /// A filled circle.
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle.
    Triangle,
    /// A diagonal cross.
    Cross,
    /// An open circle.
    Ring,
}

/// One data series. Points that a log axis cannot show (≤ 0) or that are not
/// finite break the line there.
#[derive(Clone, Debug)]
pub struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    color: Option<RGBColor>,
    line: Line,
    marker: Marker,
    width: u32,
}

impl Series {
    /// A solid 2-pixel line without markers, coloured by its position in the
    /// chart (see [`palette`]) unless [`Series::color`] says otherwise. An
    /// empty label keeps the series out of the legend.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            color: None,
            line: Line::Solid,
            marker: Marker::None,
            width: 2,
        }
    }

    /// Sets the colour.
    pub fn color(mut self, c: RGBColor) -> Self {
        self.color = Some(c);
        self
    }

    /// Sets the line style.
    pub fn line(mut self, l: Line) -> Self {
        self.line = l;
        self
    }

    /// Sets the marker.
    pub fn marker(mut self, m: Marker) -> Self {
        self.marker = m;
        self
    }

    /// Sets the line width, pixels.
    pub fn width(mut self, w: u32) -> Self {
        self.width = w.max(1);
        self
    }

    fn rgb(&self) -> RGBColor {
        self.color.unwrap_or(BLACK_INK)
    }
}

/// Ten colours that stay apart (Tableau 10).
pub fn palette(i: usize) -> RGBColor {
    const C: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    C[i % C.len()]
}

/// Black, for reference curves.
pub const BLACK_INK: RGBColor = RGBColor(0, 0, 0);

/// Where the legend goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Legend {
    /// In a strip under the chart: never covers data (the default).
    Below,
    /// Inside the plotting area, upper left.
    UpperLeft,
    /// Inside the plotting area, upper right.
    UpperRight,
    /// Inside the plotting area, lower left.
    LowerLeft,
    /// Inside the plotting area, lower right.
    LowerRight,
    /// No legend.
    Hidden,
}

/// A text note at a data point, its top-left corner offset by some pixels.
#[derive(Clone, Debug)]
pub struct Note {
    x: f64,
    y: f64,
    text: String,
    color: RGBColor,
    offset: (i32, i32),
}

/// One chart: title, axes, series, notes, legend.
#[derive(Clone, Debug)]
pub struct Chart {
    title: String,
    x: Axis,
    y: Axis,
    series: Vec<Series>,
    notes: Vec<Note>,
    legend: Legend,
    auto_colors: usize,
}

impl Chart {
    /// An empty chart with linear axes.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x: Axis::linear(""),
            y: Axis::linear(""),
            series: Vec::new(),
            notes: Vec::new(),
            legend: Legend::Below,
            auto_colors: 0,
        }
    }

    /// Sets the x axis.
    pub fn x(mut self, a: Axis) -> Self {
        self.x = a;
        self
    }

    /// Sets the y axis.
    pub fn y(mut self, a: Axis) -> Self {
        self.y = a;
        self
    }

    /// Adds a series; one without a colour takes the next palette colour.
    pub fn series(mut self, mut s: Series) -> Self {
        if s.color.is_none() {
            s.color = Some(palette(self.auto_colors));
            self.auto_colors += 1;
        }
        self.series.push(s);
        self
    }

    /// Adds a text note just above and right of `(x, y)`, data units.
    pub fn note(self, x: f64, y: f64, text: impl Into<String>, color: RGBColor) -> Self {
        self.note_offset(x, y, text, color, (6, -16))
    }

    /// Adds a text note whose top-left corner sits `offset` pixels (right,
    /// down) from `(x, y)`, data units.
    pub fn note_offset(
        mut self,
        x: f64,
        y: f64,
        text: impl Into<String>,
        color: RGBColor,
        offset: (i32, i32),
    ) -> Self {
        self.notes.push(Note {
            x,
            y,
            text: text.into(),
            color,
            offset,
        });
        self
    }

    /// Sets where the legend goes.
    pub fn legend(mut self, l: Legend) -> Self {
        self.legend = l;
        self
    }

    /// Data range on one axis in scale units, padded; whole decades on log axes.
    fn extent(axis: &Axis, values: impl Iterator<Item = f64>) -> (f64, f64) {
        let (mut lo, mut hi) = match axis.range {
            Some((a, b)) => (
                axis.scale.forward(a).unwrap_or(0.0),
                axis.scale.forward(b).unwrap_or(1.0),
            ),
            None => values
                .filter_map(|v| axis.scale.forward(v))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), t| {
                    (l.min(t), h.max(t))
                }),
        };
        if !lo.is_finite() || !hi.is_finite() {
            (lo, hi) = (0.0, 1.0);
        }
        if hi < lo {
            std::mem::swap(&mut lo, &mut hi);
        }
        match axis.scale {
            Scale::Linear => {
                if axis.range.is_none() {
                    let pad = ((hi - lo) * 0.04).max(1e-12 * hi.abs().max(1.0));
                    (lo - pad, hi + pad)
                } else if hi > lo {
                    (lo, hi)
                } else {
                    (lo - 0.5, hi + 0.5)
                }
            }
            Scale::Log10 | Scale::Log2 => {
                let (a, mut b) = (lo.floor(), hi.ceil());
                if b - a < 1.0 {
                    b = a + 1.0;
                }
                if axis.range.is_none() && b - a < 2.0 {
                    b = a + 2.0;
                }
                (a, b)
            }
        }
    }

    fn draw(&self, area: &DrawingArea<Canvas<'_>, Shift>) -> anyhow::Result<()> {
        let err = |e: &dyn std::fmt::Display| anyhow!("drawing chart `{}`: {e}", self.title);
        let (w, h) = area.dim_in_pixel();
        let legend_font = TextStyle::from((FAMILY, 15).into_font());
        // Legend strip under the chart: lay entries out in rows first.
        let entries: Vec<(usize, u32)> = self
            .series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| {
                let tw = area
                    .estimate_text_size(&s.label, &legend_font)
                    .map_or(8 * s.label.len() as u32, |d| d.0);
                (i, 44 + tw + 22)
            })
            .collect();
        let mut rows: Vec<Vec<(usize, u32)>> = Vec::new();
        let usable = w.saturating_sub(80).max(200);
        for e in entries {
            match rows.last_mut() {
                Some(r) if r.iter().map(|x| x.1).sum::<u32>() + e.1 <= usable => r.push(e),
                _ => rows.push(vec![e]),
            }
        }
        let below = self.legend == Legend::Below && !rows.is_empty();
        let row_h = 22u32;
        let strip = if below { rows.len() as u32 * row_h + 12 } else { 0 };
        let (chart_area, legend_area) = area.split_vertically(h.saturating_sub(strip));

        let xs = Self::extent(
            &self.x,
            self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
        );
        let ys = Self::extent(
            &self.y,
            self.series.iter().flat_map(|s| s.points.iter().map(|p| p.1)),
        );
        let mut chart = ChartBuilder::on(&chart_area)
            .caption(&self.title, (FAMILY, 22).into_font())
            .margin(12)
            .margin_right(24)
            .x_label_area_size(52)
            .y_label_area_size(78)
            .build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)
            .map_err(|e| err(&e))?;
        let fx = |t: &f64| self.x.tick_label(*t);
        let fy = |t: &f64| self.y.tick_label(*t);
        let n_labels = |a: &Axis, r: (f64, f64)| match a.scale {
            Scale::Linear => 8,
            _ => ((r.1 - r.0).round() as usize + 1).min(13),
        };
        let light = |a: &Axis| if a.scale == Scale::Linear { 4 } else { 0 };
        chart
            .configure_mesh()
            .x_desc(self.x.label.as_str())
            .y_desc(self.y.label.as_str())
            .x_labels(n_labels(&self.x, xs))
            .y_labels(n_labels(&self.y, ys))
            .x_max_light_lines(light(&self.x))
            .y_max_light_lines(light(&self.y))
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style((FAMILY, 14).into_font())
            .axis_desc_style((FAMILY, 16).into_font())
            .bold_line_style(RGBColor(200, 200, 200))
            .light_line_style(RGBColor(236, 236, 236))
            .draw()
            .map_err(|e| err(&e))?;
        // Minor grid lines of log axes: 2…9 × each decade.
        let grey = RGBColor(236, 236, 236);
        let minor = |a: &Axis, r: (f64, f64)| -> Vec<f64> {
            let steps: &[f64] = match a.scale {
                Scale::Linear => &[],
                Scale::Log10 => &[2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
                Scale::Log2 => &[1.5],
            };
            let mut v = Vec::new();
            let mut k = r.0.floor();
            while k < r.1 && r.1 - r.0 <= 16.0 {
                for m in steps {
                    let t = k + a.scale.forward(*m).unwrap_or(0.0);
                    if t > r.0 && t < r.1 {
                        v.push(t);
                    }
                }
                k += 1.0;
            }
            v
        };
        for t in minor(&self.y, ys) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(xs.0, t), (xs.1, t)],
                    grey,
                )))
                .map_err(|e| err(&e))?;
        }
        for t in minor(&self.x, xs) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(t, ys.0), (t, ys.1)],
                    grey,
                )))
                .map_err(|e| err(&e))?;
        }

        for s in &self.series {
            let style = ShapeStyle::from(s.rgb()).stroke_width(s.width);
            let fill = ShapeStyle::from(s.rgb()).filled();
            let mapped: Vec<Option<(f64, f64)>> = s
                .points
                .iter()
                .map(|&(x, y)| Some((self.x.scale.forward(x)?, self.y.scale.forward(y)?)))
                .collect();
            for run in mapped.split(Option::is_none) {
                let run: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
                if run.len() < 2 {
                    continue;
                }
                match s.line {
                    Line::Solid => {
                        chart
                            .draw_series(LineSeries::new(run, style))
                            .map_err(|e| err(&e))?;
                    }
                    Line::Dashed => {
                        chart
                            .draw_series(DashedLineSeries::new(run, 9, 6, style))
                            .map_err(|e| err(&e))?;
                    }
                    Line::None => {}
                }
            }
            let points = mapped.iter().flatten().copied();
            let r = 5;
            match s.marker {
                Marker::None => {}
                Marker::Circle => {
                    chart
                        .draw_series(points.map(|p| Circle::new(p, r, fill)))
                        .map_err(|e| err(&e))?;
                }
                Marker::Ring => {
                    chart
                        .draw_series(points.map(|p| Circle::new(p, r, style.stroke_width(2))))
                        .map_err(|e| err(&e))?;
                }
                Marker::Square => {
                    chart
                        .draw_series(points.map(|p| {
                            EmptyElement::at(p) + Rectangle::new([(-r + 1, -r + 1), (r - 1, r - 1)], fill)
                        }))
                        .map_err(|e| err(&e))?;
                }
                Marker::Triangle => {
                    chart
                        .draw_series(points.map(|p| TriangleMarker::new(p, r + 1, fill)))
                        .map_err(|e| err(&e))?;
                }
                Marker::Cross => {
                    chart
                        .draw_series(points.map(|p| Cross::new(p, r, style.stroke_width(2))))
                        .map_err(|e| err(&e))?;
                }
            }
        }
        // Notes: the first of a few nearby spots that no earlier note took.
        let base = chart_area.get_base_pixel();
        let mut taken: Vec<[i32; 4]> = Vec::new();
        for n in &self.notes {
            let (Some(x), Some(y)) = (self.x.scale.forward(n.x), self.y.scale.forward(n.y)) else {
                continue;
            };
            let font = TextStyle::from((FAMILY, 13).into_font()).color(&n.color);
            let (tw, th) = chart_area
                .estimate_text_size(&n.text, &font)
                .map_err(|e| err(&e))?;
            let (tw, th) = (tw as i32, th as i32);
            let (px, py) = chart.backend_coord(&(x, y));
            let (px, py) = (px - base.0, py - base.1);
            let (dx, dy) = n.offset;
            let spots = [(dx, dy), (dx, 6), (dx, -th - 6), (dx, 6 + th), (dx, -2 * th - 6)];
            let boxed = |(ox, oy): (i32, i32)| [px + ox, py + oy, px + ox + tw, py + oy + th];
            let free = |b: &[i32; 4]| {
                taken
                    .iter()
                    .all(|t| b[2] <= t[0] || t[2] <= b[0] || b[3] <= t[1] || t[3] <= b[1])
            };
            let spot = spots
                .iter()
                .map(|&o| boxed(o))
                .find(free)
                .unwrap_or_else(|| boxed(spots[0]));
            taken.push(spot);
            chart_area
                .draw(&Text::new(n.text.clone(), (spot[0], spot[1]), font))
                .map_err(|e| err(&e))?;
        }

        let labelled: Vec<&Series> = self.series.iter().filter(|s| !s.label.is_empty()).collect();
        let text_style = |color: &'static RGBColor| {
            legend_font
                .clone()
                .color(color)
                .pos(Pos::new(HPos::Left, VPos::Center))
        };
        if below {
            for (k, row) in rows.iter().enumerate() {
                let total: u32 = row.iter().map(|e| e.1).sum();
                let mut x = (w.saturating_sub(total) / 2) as i32;
                let y = 6 + (k as u32 * row_h) as i32 + row_h as i32 / 2;
                for &(i, width) in row {
                    let s = &self.series[i];
                    draw_swatch(&legend_area, (x + 20, y), s).map_err(|e| err(&e))?;
                    legend_area
                        .draw(&Text::new(s.label.clone(), (x + 44, y), text_style(&BLACK_INK)))
                        .map_err(|e| err(&e))?;
                    x += width as i32;
                }
            }
        } else if self.legend != Legend::Hidden && !labelled.is_empty() {
            let plot = chart.plotting_area().strip_coord_spec();
            let (pw, ph) = plot.dim_in_pixel();
            let text_w = labelled
                .iter()
                .map(|s| plot.estimate_text_size(&s.label, &legend_font).map_or(0, |d| d.0))
                .max()
                .unwrap_or(0);
            let (bw, bh) = (text_w as i32 + 58, labelled.len() as i32 * row_h as i32 + 8);
            let (left, top) = match self.legend {
                Legend::UpperLeft => (8, 8),
                Legend::UpperRight => (pw as i32 - bw - 8, 8),
                Legend::LowerLeft => (8, ph as i32 - bh - 8),
                _ => (pw as i32 - bw - 8, ph as i32 - bh - 8),
            };
            plot.draw(&Rectangle::new(
                [(left, top), (left + bw, top + bh)],
                WHITE.mix(0.9).filled(),
            ))
            .map_err(|e| err(&e))?;
            plot.draw(&Rectangle::new(
                [(left, top), (left + bw, top + bh)],
                RGBColor(170, 170, 170),
            ))
            .map_err(|e| err(&e))?;
            for (k, s) in labelled.iter().enumerate() {
                let y = top + 4 + k as i32 * row_h as i32 + row_h as i32 / 2;
                draw_swatch(&plot, (left + 22, y), s).map_err(|e| err(&e))?;
                plot.draw(&Text::new(
                    s.label.clone(),
                    (left + 46, y),
                    text_style(&BLACK_INK),
                ))
                .map_err(|e| err(&e))?;
            }
        }
        Ok(())
    }
}

/// Draws a legend swatch centred at `(x, y)` (pixels of `area`): a stretch
/// of the series' line with its marker on it.
fn draw_swatch<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    s: &Series,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let c = s.rgb();
    let style = ShapeStyle::from(c).stroke_width(s.width);
    let fill = ShapeStyle::from(c).filled();
    let segments: &[(i32, i32)] = match s.line {
        Line::Solid => &[(-16, 16)],
        Line::Dashed => &[(-16, -9), (-4, 3), (8, 15)],
        Line::None => &[],
    };
    for &(a, b) in segments {
        area.draw(&PathElement::new(vec![(x + a, y), (x + b, y)], style))?;
    }
    let r = 5;
    match s.marker {
        Marker::None => Ok(()),
        Marker::Circle => area.draw(&Circle::new((x, y), r, fill)),
        Marker::Ring => area.draw(&Circle::new((x, y), r, style.stroke_width(2))),
        Marker::Square => area.draw(&Rectangle::new(
            [(x - r + 1, y - r + 1), (x + r - 1, y + r - 1)],
            fill,
        )),
        Marker::Triangle => area.draw(&TriangleMarker::new((x, y), r + 1, fill)),
        Marker::Cross => area.draw(&Cross::new((x, y), r, style.stroke_width(2))),
    }
}

/// A figure: charts side by side, optionally under a common title.
#[derive(Clone, Debug)]
pub struct Figure {
    width: u32,
    height: u32,
    title: Option<String>,
    panels: Vec<Chart>,
}

impl Figure {
    /// An empty figure of `width`×`height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            title: None,
            panels: Vec::new(),
        }
    }

    /// A title above all panels.
    pub fn title(mut self, t: impl Into<String>) -> Self {
        self.title = Some(t.into());
        self
    }

    /// Adds a chart as the next panel, left to right.
    pub fn panel(mut self, c: Chart) -> Self {
        self.panels.push(c);
        self
    }

    /// Renders to 8-bit RGB pixels, row by row.
    pub fn render(&self) -> anyhow::Result<Vec<u8>> {
        let font = font()?;
        let (w, h) = (self.width.max(64), self.height.max(64));
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let canvas = Canvas {
                inner: BitMapBackend::with_buffer(&mut buf, (w, h)),
                font,
            };
            let root = canvas.into_drawing_area();
            root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
            let body = match &self.title {
                Some(t) => {
                    let (top, rest) = root.split_vertically(40);
                    top.titled(t, (FAMILY, 24).into_font())
                        .map_err(|e| anyhow!("{e}"))?;
                    rest
                }
                None => root.clone(),
            };
            let n = self.panels.len().max(1);
            let areas = body.split_evenly((1, n));
            for (c, a) in self.panels.iter().zip(&areas) {
                c.draw(a)?;
            }
            root.present().map_err(|e| anyhow!("{e}"))?;
        }
        Ok(buf)
    }

    /// Renders and writes a PNG at `path` (creating its folder).
    pub fn write_png(&self, path: &Path) -> anyhow::Result<()> {
        let buf = self.render()?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        let img = image::RgbImage::from_raw(self.width.max(64), self.height.max(64), buf)
            .ok_or_else(|| anyhow!("pixel buffer has the wrong size"))?;
        img.save_with_format(path, image::ImageFormat::Png)
            .with_context(|| format!("writing {}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ink(buf: &[u8]) -> usize {
        buf.chunks(3).filter(|p| p.iter().any(|&c| c < 128)).count()
    }

    #[test]
    fn draws_every_kind_of_series_and_legend() {
        let pts: Vec<(f64, f64)> = (1..=20).map(|i| (i as f64, (i as f64).powi(2))).collect();
        let mut fig = Figure::new(900, 400).title("all features");
        for legend in [
            Legend::Below,
            Legend::UpperRight,
            Legend::LowerLeft,
            Legend::Hidden,
        ] {
            let chart = Chart::new("log–log")
                .x(Axis::log2("size (texels)").format(|v| format!("{v}²")))
                .y(Axis::log10("error (1)"))
                .legend(legend)
                .series(Series::new("solid", pts.clone()).marker(Marker::Circle))
                .series(
                    Series::new("dashed", pts.iter().map(|&(x, y)| (x, y * 3.0)).collect())
                        .line(Line::Dashed),
                )
                .series(
                    Series::new("cross", vec![(2.0, 5.0), (3.0, f64::NAN), (4.0, -1.0)])
                        .marker(Marker::Cross),
                )
                .series(
                    Series::new("", vec![(5.0, 50.0)])
                        .line(Line::None)
                        .marker(Marker::Square),
                )
                .series(Series::new("empty", vec![]).marker(Marker::Triangle))
                .note(4.0, 16.0, "4²", palette(2));
            fig = fig.panel(chart);
        }
        let buf = fig.render().expect("renders");
        assert_eq!(buf.len(), 900 * 400 * 3);
        assert!(ink(&buf) > 5_000, "text and lines were drawn");
    }

    #[test]
    fn linear_chart_with_fixed_range_writes_a_png() {
        let chart = Chart::new("linear")
            .x(Axis::linear("time (s)").range(0.0, 10.0))
            .y(Axis::linear("height (m)"))
            .series(
                Series::new("y = x/2", vec![(0.0, 0.0), (10.0, 5.0)])
                    .color(BLACK_INK)
                    .width(3),
            );
        let dir = std::env::temp_dir().join(format!("soak-plot-{}", std::process::id()));
        let path = dir.join("linear.png");
        Figure::new(400, 300)
            .panel(chart)
            .write_png(&path)
            .expect("writes");
        let bytes = std::fs::read(&path).expect("reads");
        assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn tick_labels() {
        assert_eq!(power_of_ten(-3), "10⁻³");
        assert_eq!(power_of_ten(12), "10¹²");
        assert_eq!(linear_label(0.25), "0.25");
        assert_eq!(linear_label(-0.0), "0");
        assert_eq!(Axis::log10("").tick_label(-2.0), "10⁻²");
        assert_eq!(Axis::log10("").tick_label(-2.5), "");
        assert_eq!(Axis::log2("").tick_label(5.0), "32");
    }
}
