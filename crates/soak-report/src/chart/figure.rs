//! A figure: charts side by side under a common title, rendered to PNG.

use std::path::Path;

use plotters::prelude::*;

use super::ChartError;
use super::canvas::{Canvas, FAMILY, font};
use super::panel::Chart;

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
    pub fn render(&self) -> Result<Vec<u8>, ChartError> {
        let font = font()?;
        let (w, h) = (self.width.max(64), self.height.max(64));
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let canvas = Canvas {
                inner: BitMapBackend::with_buffer(&mut buf, (w, h)),
                font,
            };
            let root = canvas.into_drawing_area();
            root.fill(&WHITE).map_err(|e| ChartError::Figure(e.to_string()))?;
            let body = match &self.title {
                Some(t) => {
                    let (top, rest) = root.split_vertically(40);
                    top.titled(t, (FAMILY, 24).into_font())
                        .map_err(|e| ChartError::Figure(e.to_string()))?;
                    rest
                }
                None => root.clone(),
            };
            let n = self.panels.len().max(1);
            let areas = body.split_evenly((1, n));
            for (c, a) in self.panels.iter().zip(&areas) {
                c.draw(a)?;
            }
            root.present().map_err(|e| ChartError::Figure(e.to_string()))?;
        }
        Ok(buf)
    }

    /// Renders and writes a PNG at `path` (creating its folder).
    pub fn write_png(&self, path: &Path) -> Result<(), ChartError> {
        let buf = self.render()?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|source| ChartError::CreateDir {
                path: dir.to_path_buf(),
                source,
            })?;
        }
        let img = image::RgbImage::from_raw(self.width.max(64), self.height.max(64), buf)
            .ok_or(ChartError::BufferSize)?;
        img.save_with_format(path, image::ImageFormat::Png)
            .map_err(|source| ChartError::Write {
                path: path.to_path_buf(),
                source,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chart::{Axis, BLACK_INK, Legend, Line, Marker, Series, palette};

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
}
