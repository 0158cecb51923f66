//! Line charts written as PNG: a title, axis labels with units, several
//! series (lines, dashed lines, markers), linear or logarithmic axes, a legend
//! that never covers the data, and text notes at data coordinates. Several
//! charts side by side make one figure.
//!
//! Text is set in DejaVu Sans, embedded in the crate (`assets/`), laid out
//! by [`soak_shade::render::layout_text`] (as the renderer's figure labels)
//! and drawn by the backend here, so the plots look the same on every
//! machine and need no system fonts.
//!
//! ```no_run
//! use soak_report::chart::{Axis, Chart, Figure, Marker, Series};
//!
//! let points = vec![(0.0, 1e-2), (0.5, 3e-3), (1.0, 1e-3)];
//! let chart = Chart::new("Submerged volume")
//!     .x(Axis::linear("water level d (m)"))
//!     .y(Axis::log10("error (fraction of the volume)"))
//!     .series(Series::new("texels 256²", points).marker(Marker::Circle));
//! Figure::new(1200, 600).panel(chart).write_png("out/volume.png".as_ref())?;
//! # Ok::<(), soak_report::chart::ChartError>(())
//! ```

mod axis;
mod canvas;
mod error;
mod figure;
mod panel;
mod series;

pub use axis::{Axis, Scale, power_of_ten};
pub use canvas::FONT;
pub use error::ChartError;
pub use figure::Figure;
pub use panel::Chart;
pub use series::{BLACK_INK, Legend, Line, Marker, Note, RGBColor, Series, palette};
