//! The figures: thesis Fig. 7.10 reproduced and extended, and error against time.

use std::path::{Path, PathBuf};

use super::AccuracyError;
use super::cases::RADIUS;
use super::report::{Curve, Report, Sweep};
use crate::chart::{Axis, BLACK_INK, Chart, Figure, Legend, Line, Marker, RGBColor, Series, palette};

fn texture_label(v: f64) -> String {
    format!("{}²", v.round() as u64)
}

fn ms_label(v: f64) -> String {
    if v >= 1.0 {
        format!("{v:.0} ms")
    } else {
        let digits = (-v.log10()).round() as usize;
        format!("{v:.digits$} ms")
    }
}

fn max_error(a: &[f64], b: &[f64], scale: f64) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max)
}

/// Worst volume error of a curve against the sweep's exact clipping.
fn vs_exact(s: &Sweep) -> impl Fn(&Curve) -> f64 + '_ {
    move |c: &Curve| max_error(&c.volume, &s.exact, s.body_volume)
}

/// Worst volume error of a curve against the analytic sphere.
fn vs_analytic(s: &Sweep) -> impl Fn(&Curve) -> f64 + '_ {
    let v_ball = 4.0 / 3.0 * std::f64::consts::PI * RADIUS.powi(3);
    move |c: &Curve| max_error(&c.volume, s.analytic.as_deref().unwrap_or_default(), v_ball)
}

fn curve(sweep: &Sweep, n: u32, mm: bool) -> Option<&Curve> {
    sweep
        .texel
        .iter()
        .find(|c| c.resolution == n && c.moment_matching == mm)
}

/// Writes the figures and returns their paths.
///
/// # Errors
/// The folder or a PNG cannot be written, or the report has no sweep.
pub fn write_figures(report: &Report, out: &Path) -> Result<Vec<PathBuf>, AccuracyError> {
    std::fs::create_dir_all(out).map_err(|source| AccuracyError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let fig1 = out.join("accuracy_sphere.png");
    sphere_figure(report)?.write_png(&fig1)?;
    let fig2 = out.join("accuracy_cost.png");
    cost_figure(report)?.write_png(&fig2)?;
    Ok(vec![fig1, fig2])
}

/// Volume of the analytic sphere, m³.
fn ball_volume() -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * RADIUS.powi(3)
}

/// The short mesh size of a sphere case ("64×32").
fn sphere_size(s: &Sweep) -> &str {
    s.mesh.split(' ').nth(1).unwrap_or("")
}

/// Thesis Fig. 7.10 reproduced (volume against water level) and extended
/// (error against water level, worst error against texture size).
///
/// # Errors
/// [`AccuracyError::NoSweep`] if the report has no sweep.
pub fn sphere_figure(report: &Report) -> Result<Figure, AccuracyError> {
    let sphere = report.sweeps.first().ok_or(AccuracyError::NoSweep)?;
    let fine = report.sweeps.iter().find(|s| s.mesh.starts_with("sphere 256"));
    let v_ball = ball_volume();
    let analytic = sphere.analytic.clone().unwrap_or_default();
    let pts =
        |ys: &[f64]| -> Vec<(f64, f64)> { sphere.levels.iter().copied().zip(ys.iter().copied()).collect() };
    let res = &report.resolutions;
    let (first, last) = (res[0], *res.last().unwrap_or(&res[0]));
    let shown: Vec<u32> = {
        let mut v = vec![first, res[res.len() / 2], last];
        v.dedup();
        v
    };

    // (a) Volume against water level, as in the thesis.
    let mut volume = Chart::new("Submerged volume (thesis Fig. 7.10)")
        .x(Axis::linear("water level above the centre d (m)"))
        .y(Axis::linear("submerged volume (m³)"))
        .legend(Legend::UpperLeft)
        .series(
            Series::new("analytic sphere", pts(&analytic))
                .color(BLACK_INK)
                .width(3),
        );
    for (k, &n) in shown.iter().enumerate() {
        if let Some(c) = curve(sphere, n, false) {
            volume = volume.series(
                Series::new(format!("texel centres {n}² (thesis)"), pts(&c.volume))
                    .color(palette(k))
                    .marker(Marker::Circle),
            );
        }
    }
    if let Some(c) = curve(sphere, last, true) {
        volume = volume.series(
            Series::new(format!("moment matching {last}²"), pts(&c.volume))
                .color(palette(4))
                .line(Line::None)
                .marker(Marker::Square),
        );
    }
    volume = volume.series(
        Series::new("per-triangle game method", pts(&sphere.per_triangle))
            .color(palette(3))
            .line(Line::Dashed)
            .width(3),
    );

    // (b) Signed error against water level: where the texel sums miss.
    let pct = |ys: &[f64], reference: &[f64], scale: f64| -> Vec<(f64, f64)> {
        sphere
            .levels
            .iter()
            .zip(ys.iter().zip(reference))
            .map(|(&l, (y, r))| (l, 100.0 * (y - r) / scale))
            .collect()
    };
    let mut signed = Chart::new("Texel sums against exact clipping of the same mesh")
        .x(Axis::linear("water level above the centre d (m)"))
        .y(Axis::linear("(V − V_exact) / V_body (%)"));
    for (k, &n) in shown.iter().enumerate() {
        if let Some(c) = curve(sphere, n, false) {
            signed = signed.series(
                Series::new(
                    format!("texel centres {n}²"),
                    pct(&c.volume, &sphere.exact, sphere.body_volume),
                )
                .color(palette(k))
                .marker(Marker::Circle),
            );
        }
    }
    for (k, &n) in [first, last].iter().enumerate() {
        if let Some(c) = curve(sphere, n, true) {
            signed = signed.series(
                Series::new(
                    format!("moment matching {n}²"),
                    pct(&c.volume, &sphere.exact, sphere.body_volume),
                )
                .color(palette(4 + k))
                .marker(Marker::Square),
            );
        }
    }
    signed = signed.series(
        Series::new(
            "exact clipping vs analytic sphere",
            pct(&sphere.exact, &analytic, v_ball),
        )
        .color(BLACK_INK)
        .line(Line::Dashed),
    );

    // (c) Worst error against texture size, log–log.
    let res_pts = |f: &dyn Fn(&Curve) -> f64, s: &Sweep, mm: bool| -> Vec<(f64, f64)> {
        res.iter()
            .filter_map(|&n| curve(s, n, mm).map(|c| (n as f64, f(c))))
            .collect()
    };
    let flat = |v: f64| vec![(first as f64, v), (last as f64, v)];
    let mut worst = Chart::new("Worst volume error over the sweep")
        .x(Axis::log2("texture size (texels)").format(texture_label))
        .y(Axis::log10("max |V − V_ref| / V_sphere"))
        .series(
            Series::new(
                "per-triangle game method vs analytic",
                flat(max_error(&sphere.per_triangle, &analytic, v_ball)),
            )
            .color(palette(3))
            .line(Line::Dashed)
            .width(3),
        )
        .series(
            Series::new(
                "texel centres vs exact clipping",
                res_pts(&vs_exact(sphere), sphere, false),
            )
            .color(palette(1))
            .marker(Marker::Square),
        )
        .series(
            Series::new(
                "moment matching vs exact clipping",
                res_pts(&vs_exact(sphere), sphere, true),
            )
            .color(palette(0))
            .marker(Marker::Circle),
        )
        .series(
            Series::new(
                "moment matching vs analytic",
                res_pts(&vs_analytic(sphere), sphere, true),
            )
            .color(palette(2))
            .marker(Marker::Triangle),
        )
        .series(
            Series::new(
                "exact clipping vs analytic (the mesh's own error)",
                flat(max_error(&sphere.exact, &analytic, v_ball)),
            )
            .color(RGBColor(0, 90, 0))
            .line(Line::Dashed)
            .width(1),
        );
    if let Some(f) = fine {
        let a = f.analytic.clone().unwrap_or_default();
        worst = worst
            .series(
                Series::new(
                    "256×128 mesh: moment matching vs analytic",
                    res_pts(&vs_analytic(f), f, true),
                )
                .color(palette(4))
                .marker(Marker::Triangle),
            )
            .series(
                Series::new(
                    "256×128 mesh: exact clipping vs analytic",
                    flat(max_error(&f.exact, &a, v_ball)),
                )
                .color(RGBColor(70, 0, 110))
                .line(Line::Dashed)
                .width(1),
            );
    }
    Ok(Figure::new(2100, 780)
        .title(format!(
            "Sphere r = 0.5 m ({} mesh unless noted), water level swept over {} heights",
            sphere_size(sphere),
            sphere.levels.len()
        ))
        .panel(volume)
        .panel(signed)
        .panel(worst))
}

/// Error against time per evaluation, every path.
///
/// # Errors
/// [`AccuracyError::NoSweep`] if the report has no sweep.
pub fn cost_figure(report: &Report) -> Result<Figure, AccuracyError> {
    let sphere = report.sweeps.first().ok_or(AccuracyError::NoSweep)?;
    let v_ball = ball_volume();
    let trade = |s: &Sweep, mm: bool, tiled: bool, reference: &dyn Fn(&Curve) -> f64| -> Vec<(f64, f64)> {
        report
            .resolutions
            .iter()
            .filter_map(|&n| curve(s, n, mm))
            .map(|c| (if tiled { c.tiled_ms } else { c.per_texel_ms }, reference(c)))
            .collect()
    };

    // Left: the spheres against the true sphere.
    let mut left = Chart::new("Spheres r = 0.5 m: error against the analytic sphere")
        .x(Axis::log10("time per evaluation (ms)").format(ms_label))
        .y(Axis::log10("max |V − V_sphere| / V_sphere over the sweep"));
    let p = trade(sphere, true, true, &vs_analytic(sphere));
    for (&(x, y), &n) in p.iter().zip(&report.resolutions) {
        left = left.note_offset(x, y, format!("{n}²"), palette(1), (-8, -20));
    }
    left = left
        .series(
            Series::new(format!("tiled, {}", sphere_size(sphere)), p)
                .color(palette(1))
                .marker(Marker::Square),
        )
        .series(
            Series::new(
                format!("per-texel, {}", sphere_size(sphere)),
                trade(sphere, true, false, &vs_analytic(sphere)),
            )
            .color(palette(0))
            .width(1)
            .marker(Marker::Ring),
        )
        .series(
            Series::new(
                format!("per-texel, texel centres, {}", sphere_size(sphere)),
                trade(sphere, false, false, &vs_analytic(sphere)),
            )
            .color(palette(7))
            .line(Line::Dashed)
            .marker(Marker::Ring),
        );
    let spheres: Vec<&Sweep> = report.sweeps.iter().filter(|s| s.analytic.is_some()).collect();
    for (k, s) in spheres.iter().enumerate().skip(1) {
        left = left.series(
            Series::new(
                format!("tiled, {}", sphere_size(s)),
                trade(s, true, true, &vs_analytic(s)),
            )
            .color(palette(3 + k))
            .marker(Marker::Triangle),
        );
    }
    for (k, s) in spheres.iter().enumerate() {
        let a = s.analytic.clone().unwrap_or_default();
        left = left.series(
            Series::new(
                format!("exact clipping, {}", sphere_size(s)),
                vec![(s.exact_ms, max_error(&s.exact, &a, v_ball))],
            )
            .color(if k == 0 { BLACK_INK } else { palette(3 + k) })
            .line(Line::None)
            .marker(Marker::Cross),
        );
    }
    left = left.series(
        Series::new(
            format!("per-triangle game method, {}", sphere_size(sphere)),
            vec![(
                sphere.per_triangle_ms,
                max_error(
                    sphere.per_triangle.as_slice(),
                    sphere.analytic.as_deref().unwrap_or_default(),
                    v_ball,
                ),
            )],
        )
        .color(palette(3))
        .line(Line::None)
        .marker(Marker::Triangle),
    );

    // Right: every table mesh against its own exact clipping.
    let mut right = Chart::new("Every mesh: error against exact clipping of the same mesh")
        .x(Axis::log10("time per evaluation (ms)").format(ms_label))
        .y(Axis::log10("max |V − V_exact| / V_body over the sweep"));
    let table: Vec<&Sweep> = report
        .sweeps
        .iter()
        .filter(|s| report.rows.iter().any(|r| r.mesh == s.mesh))
        .collect();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for s in &table {
        for c in &s.texel {
            let e = max_error(&c.volume, &s.exact, s.body_volume);
            if e > 0.0 {
                lo = lo.min(e);
            }
            hi = hi.max(e);
        }
        hi = hi.max(max_error(&s.per_triangle, &s.exact, s.body_volume));
    }
    let lo = if lo.is_finite() { lo } else { 1e-9 };
    for (k, s) in table.iter().enumerate() {
        let color = palette(k);
        right = right
            .series(
                Series::new(s.mesh.clone(), trade(s, true, true, &vs_exact(s)))
                    .color(color)
                    .marker(Marker::Square),
            )
            .series(
                Series::new("", trade(s, true, false, &vs_exact(s)))
                    .color(color)
                    .width(1)
                    .marker(Marker::Ring),
            )
            .series(
                Series::new("", vec![(s.exact_ms, lo * 0.5), (s.exact_ms, hi * 2.0)])
                    .color(color)
                    .line(Line::Dashed),
            )
            .series(
                Series::new(
                    "",
                    vec![(
                        s.per_triangle_ms,
                        max_error(&s.per_triangle, &s.exact, s.body_volume),
                    )],
                )
                .color(color)
                .line(Line::None)
                .marker(Marker::Cross),
            );
    }
    right = right
        .series(
            Series::new("tiled", vec![])
                .color(BLACK_INK)
                .marker(Marker::Square),
        )
        .series(
            Series::new("per-texel", vec![])
                .color(BLACK_INK)
                .width(1)
                .marker(Marker::Ring),
        )
        .series(
            Series::new("exact clipping: its time (error 0)", vec![])
                .color(BLACK_INK)
                .line(Line::Dashed),
        )
        .series(
            Series::new("per-triangle game method", vec![])
                .color(BLACK_INK)
                .line(Line::None)
                .marker(Marker::Cross),
        );
    Ok(Figure::new(1900, 860)
        .title(format!(
            "Accuracy against time per evaluation, medians of {} runs on {} threads (labels: texture size)",
            report.timing_runs, report.threads
        ))
        .panel(left)
        .panel(right))
}
