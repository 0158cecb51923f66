//! The bench as a log–log plot: step time against the number of bodies,
//! one line per column, and a line of slope 1 for reference.

use std::path::{Path, PathBuf};

use super::{Column, Device, ScalingError, ScalingReport, Variant, WaterKind};
use crate::chart::{Axis, BLACK_INK, Chart, Figure, Line, Marker, Series, palette};

fn count_label(v: f64) -> String {
    let n = v.round() as u64;
    if n >= 1000 && n.is_multiple_of(1000) {
        format!("{},000", n / 1000)
    } else {
        n.to_string()
    }
}

fn ms_label(v: f64) -> String {
    super::table::format_ms(v)
}

fn look(c: &Column) -> (usize, Line, Marker) {
    let colour = match (c.variant, c.water) {
        (Variant::RapierAlone, _) => 7,
        (Variant::Buoyancy, Some(WaterKind::Calm)) => 0,
        (Variant::BuoyancyDrag, Some(WaterKind::Calm)) => 1,
        (Variant::Buoyancy, Some(WaterKind::Swell)) => 2,
        (Variant::BuoyancyDrag, Some(WaterKind::Swell)) => 3,
        (Variant::BuoyancyRadiation, Some(WaterKind::Calm)) => 5,
        (Variant::BuoyancyRadiation, Some(WaterKind::Swell)) => 6,
        (Variant::Buoyancy, Some(WaterKind::Jonswap)) => 8,
        (Variant::BuoyancyDrag, Some(WaterKind::Jonswap)) => 9,
        (Variant::BuoyancyRadiation, Some(WaterKind::Jonswap)) => 4,
        _ => 4,
    };
    let marker = match c.variant {
        Variant::RapierAlone => Marker::Cross,
        Variant::Buoyancy => Marker::Circle,
        Variant::BuoyancyDrag => Marker::Square,
        Variant::BuoyancyRadiation => Marker::Triangle,
    };
    let line = if c.device == Device::Gpu {
        Line::Dashed
    } else {
        Line::Solid
    };
    (colour, line, marker)
}

/// The plot of a run.
pub fn figure(report: &ScalingReport) -> Figure {
    let mut chart = Chart::new("Step time against the number of floating bodies")
        .x(Axis::log10("bodies N").format(count_label))
        .y(Axis::log10("time per step (median)").format(ms_label));
    for c in &report.columns {
        let points: Vec<(f64, f64)> = report
            .measurements
            .iter()
            .filter(|m| m.case.column == *c)
            .map(|m| (m.case.bodies as f64, m.median_ms))
            .collect();
        let (colour, line, marker) = look(c);
        let label = if c.device == Device::Gpu {
            format!("{} (software adapter)", c.label())
        } else {
            c.label()
        };
        chart = chart.series(
            Series::new(label, points)
                .color(palette(colour))
                .line(line)
                .marker(marker),
        );
    }
    // Slope 1 through the slowest CPU column's largest count.
    let anchor = report
        .measurements
        .iter()
        .filter(|m| m.case.column.device == Device::Cpu)
        .max_by(|a, b| {
            (a.case.bodies, a.median_ms)
                .partial_cmp(&(b.case.bodies, b.median_ms))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
    let lo = report.measurements.iter().map(|m| m.case.bodies).min();
    if let (Some(a), Some(lo)) = (anchor, lo) {
        let (n1, t1) = (a.case.bodies as f64, a.median_ms);
        let n0 = lo as f64;
        chart = chart.series(
            Series::new("slope 1 (time ∝ N)", vec![(n0, t1 * n0 / n1), (n1, t1)])
                .color(BLACK_INK)
                .line(Line::Dashed)
                .width(1),
        );
    }
    Figure::new(1400, 900)
        .title(format!(
            "soak bench: half boxes, half spheres, {r}² atlases, density 500, 60 Hz, {t} threads",
            r = report.options.resolution,
            t = report.threads
        ))
        .panel(chart)
}

/// Writes the plot as `scaling.png` in `out` and returns its path.
///
/// # Errors
/// The folder or the PNG cannot be written.
pub fn write_figure(report: &ScalingReport, out: &Path) -> Result<PathBuf, ScalingError> {
    std::fs::create_dir_all(out).map_err(|source| ScalingError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let path = out.join("scaling.png");
    figure(report).write_png(&path)?;
    Ok(path)
}
