//! Series and their looks: lines, markers, colours, legends, notes.

/// Colours of series and notes.
pub use plotters::style::RGBColor;

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
    pub(super) label: String,
    pub(super) points: Vec<(f64, f64)>,
    pub(super) color: Option<RGBColor>,
    pub(super) line: Line,
    pub(super) marker: Marker,
    pub(super) width: u32,
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

    pub(super) fn rgb(&self) -> RGBColor {
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
    pub(super) x: f64,
    pub(super) y: f64,
    pub(super) text: String,
    pub(super) color: RGBColor,
    pub(super) offset: (i32, i32),
}
