//! One chart: title, axes, series, notes and legend, drawn on a plotters area.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::ChartError;
use super::axis::{Axis, Scale};
use super::canvas::{Canvas, FAMILY};
use super::series::{BLACK_INK, Legend, Line, Marker, Note, RGBColor, Series, palette};

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

    pub(super) fn draw(&self, area: &DrawingArea<Canvas<'_>, Shift>) -> Result<(), ChartError> {
        let err = |e: &dyn std::fmt::Display| ChartError::Draw {
            chart: self.title.clone(),
            message: e.to_string(),
        };
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
