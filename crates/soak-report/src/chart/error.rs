//! What can stop a chart from being drawn or written, as values.

use std::path::PathBuf;

/// A chart could not be drawn or its PNG written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ChartError {
    /// The embedded font did not parse.
    #[error("the embedded DejaVu Sans font could not be parsed")]
    Font,
    /// Plotters failed while drawing a chart.
    #[error("drawing chart `{chart}`: {message}")]
    Draw {
        /// The chart's title.
        chart: String,
        /// Plotters' message.
        message: String,
    },
    /// Plotters failed while drawing the figure around its charts.
    #[error("{0}")]
    Figure(String),
    /// The rendered pixels do not fill the image (a bug).
    #[error("pixel buffer has the wrong size")]
    BufferSize,
    /// The folder of the PNG could not be made.
    #[error("creating {}: {source}", path.display())]
    CreateDir {
        /// The folder.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// The PNG could not be encoded or written.
    #[error("writing {}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: image::ImageError,
    },
}
