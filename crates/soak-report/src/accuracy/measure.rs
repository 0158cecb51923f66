//! The measurement: each case's exact references, each atlas's errors and times.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use nalgebra::{Isometry3, Point3};
use soak_bake::{Atlas, BakeOptions};
use soak_hydro::reference::{self, ClipPlane, analytic};
use soak_hydro::{BodyState, HydroOptions, MassModel, TiledAtlas, Water, evaluate, streaming_read};

use super::AccuracyError;
use super::cases::{Case, DENSITY, MIN_SUBMERGED, Plan, RADIUS, cases, linspace, pose};
use super::figures::write_figures;
use super::report::{Curve, Report, Row, Speedup, Sweep};
use super::timing::per_call_ms;
use crate::Gpu;

/// Error of a texel atlas over a sweep.
struct Measured {
    gpu_ms: Option<f64>,
    texels: usize,
    volume: Vec<f64>,
    volume_error: f64,
    cob_error: f64,
    inertia_error: f64,
    tiled_diff: f64,
    per_texel_ms: f64,
    tiled_ms: f64,
    /// Per-texel time over a streaming read of the same atlas, timed in turn
    /// with it (and with the tiled path).
    over_floor: f64,
}

/// Exact references of one case.
struct Exact {
    pose: Isometry3<f64>,
    levels: Vec<f64>,
    volume: Vec<f64>,
    centroid: Vec<Point3<f64>>,
    body_volume: f64,
    diagonal: f64,
    inertia: nalgebra::Matrix3<f64>,
    /// Index of the level the paths are timed at (mid-height of the body).
    timing_level: usize,
}

fn measure(
    case: &Case,
    ex: &Exact,
    n: u32,
    moment_matching: bool,
    runs: usize,
    gpu: Option<&mut Gpu>,
) -> Result<Measured, AccuracyError> {
    let options = BakeOptions {
        moment_matching,
        ..BakeOptions::square(n)
    };
    let atlas = Atlas::bake(&case.mesh, options)?;
    let tiled = TiledAtlas::new(&atlas);
    let mass = MassModel::Solid { density: DENSITY }.mass_properties(&atlas)?;
    let state = BodyState::at_rest(ex.pose);
    let opts = HydroOptions::default();
    let (mut volume_error, mut cob_error, mut tiled_diff) = (0.0f64, 0.0f64, 0.0f64);
    let mut volume = Vec::with_capacity(ex.levels.len());
    for (k, &level) in ex.levels.iter().enumerate() {
        let water = Water::calm(level);
        let f = evaluate(&atlas, &water, &state, &mass, 0.0, &opts)?;
        let g = tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts)?;
        volume.push(f.submerged_volume);
        volume_error = volume_error.max((f.submerged_volume - ex.volume[k]).abs() / ex.body_volume);
        tiled_diff = tiled_diff.max((g.submerged_volume - f.submerged_volume).abs() / ex.body_volume);
        if ex.volume[k] >= MIN_SUBMERGED * ex.body_volume {
            cob_error = cob_error.max((f.center_of_buoyancy - ex.centroid[k]).norm() / ex.diagonal);
        }
    }
    let trace = ex.inertia.trace();
    let inertia_error = (mass.inertia - ex.inertia).abs().max() / trace;
    let water = Water::calm(ex.levels[ex.timing_level]);
    let [per_texel_ms, tiled_ms, floor_ms] = per_call_ms(
        runs,
        [
            &mut || {
                let _ = black_box(evaluate(&atlas, &water, &state, &mass, 0.0, &opts));
            },
            &mut || {
                let _ = black_box(tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts));
            },
            &mut || {
                black_box(streaming_read(&atlas));
            },
        ],
    );
    let gpu_ms = match gpu {
        Some(g) => Some(
            g.evaluate_timed(&atlas, &water, &state, &mass, &opts, runs.clamp(1, 5))?
                .1,
        ),
        None => None,
    };
    Ok(Measured {
        gpu_ms,
        texels: atlas.len(),
        volume,
        volume_error,
        cob_error,
        inertia_error,
        tiled_diff,
        per_texel_ms,
        tiled_ms,
        over_floor: per_texel_ms / floor_ms,
    })
}

/// Runs the whole measurement and writes the plots into `out`.
///
/// `quick` runs fewer resolutions (32²–256²), water levels and timing
/// runs; `gpu`, when given, fills the GPU column.
///
/// # Errors
/// A mesh that cannot be made or baked, an evaluation that fails, the GPU
/// path failing, or a figure that cannot be written.
pub fn compute(quick: bool, out: &Path, mut gpu: Option<&mut Gpu>) -> Result<Report, AccuracyError> {
    let start = Instant::now();
    let plan = Plan::new(quick);
    let mut rows = Vec::new();
    let mut sweeps = Vec::new();
    for case in cases()? {
        let pose = pose([0.0; 3], case.rotation_deg);
        let ys = case.mesh.positions.iter().map(|p| (pose * p).y);
        let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), y| {
            (l.min(y), h.max(y))
        });
        let levels = linspace(lo, hi, plan.levels);
        let parts: Vec<_> = levels
            .iter()
            .map(|&l| reference::submerged_part(&case.mesh, &pose, &ClipPlane::horizontal(l)))
            .collect();
        let per_triangle: Vec<f64> = levels
            .iter()
            .map(|&l| {
                reference::per_triangle_buoyancy(&case.mesh, &pose, &ClipPlane::horizontal(l), 1000.0, 9.81)
                    .volume
            })
            .collect();
        let solid = reference::solid_mass_properties(&case.mesh, DENSITY);
        let timing_level = levels.len() / 2;
        let plane = ClipPlane::horizontal(levels[timing_level]);
        let [exact_ms, per_triangle_ms] = per_call_ms(
            plan.runs,
            [
                &mut || {
                    black_box(reference::submerged_part(&case.mesh, &pose, &plane));
                },
                &mut || {
                    black_box(reference::per_triangle_buoyancy(
                        &case.mesh, &pose, &plane, 1000.0, 9.81,
                    ));
                },
            ],
        );
        let ex = Exact {
            pose,
            volume: parts.iter().map(|p| p.volume).collect(),
            centroid: parts.iter().map(|p| p.centroid).collect(),
            body_volume: solid.volume,
            diagonal: case.mesh.diagonal(),
            inertia: solid.inertia,
            timing_level,
            levels,
        };
        let per_triangle_volume_error = per_triangle
            .iter()
            .zip(&ex.volume)
            .map(|(b, e)| (b - e).abs() / ex.body_volume)
            .fold(0.0, f64::max);
        let mut curves = Vec::new();
        for &n in &plan.resolutions {
            let mm = measure(&case, &ex, n, true, plan.runs, gpu.as_deref_mut())?;
            let centres = measure(&case, &ex, n, false, plan.runs, None)?;
            if case.in_table {
                rows.push(Row {
                    mesh: case.name.to_string(),
                    triangles: case.mesh.triangles.len(),
                    resolution: n,
                    texels: mm.texels,
                    volume_error: mm.volume_error,
                    volume_error_centres: centres.volume_error,
                    cob_error: mm.cob_error,
                    cob_error_centres: centres.cob_error,
                    inertia_error: mm.inertia_error,
                    inertia_error_centres: centres.inertia_error,
                    tiled_vs_per_texel: mm.tiled_diff.max(centres.tiled_diff),
                    per_texel_ms: mm.per_texel_ms,
                    tiled_ms: mm.tiled_ms,
                    per_texel_over_floor: mm.over_floor,
                    gpu_ms: mm.gpu_ms,
                    exact_ms,
                    per_triangle_ms,
                    per_triangle_volume_error,
                });
            }
            for (m, flag) in [(mm, true), (centres, false)] {
                curves.push(Curve {
                    resolution: n,
                    moment_matching: flag,
                    volume: m.volume,
                    per_texel_ms: m.per_texel_ms,
                    tiled_ms: m.tiled_ms,
                });
            }
        }
        sweeps.push(Sweep {
            mesh: case.name.to_string(),
            triangles: case.mesh.triangles.len(),
            body_volume: ex.body_volume,
            analytic: case.sphere.then(|| {
                ex.levels
                    .iter()
                    .map(|&l| analytic::sphere_submerged(RADIUS, l).volume)
                    .collect()
            }),
            levels: ex.levels,
            exact: ex.volume,
            per_triangle,
            exact_ms,
            per_triangle_ms,
            texel: curves,
        });
    }
    let at = if plan.resolutions.contains(&1024) {
        1024
    } else {
        *plan.resolutions.last().unwrap_or(&0)
    };
    let tiled_speedup = rows
        .iter()
        .filter(|r| r.resolution == at)
        .map(|r| Speedup {
            mesh: r.mesh.clone(),
            resolution: at,
            speedup: r.per_texel_ms / r.tiled_ms,
            per_texel_over_floor: r.per_texel_over_floor,
        })
        .collect();
    let mut report = Report {
        quick,
        resolutions: plan.resolutions,
        levels: plan.levels,
        timing_runs: plan.runs,
        threads: rayon_threads(),
        rows,
        tiled_speedup,
        sweeps,
        sea: super::sea::sea_rows(if quick { 128 } else { 1024 }, plan.runs)?,
        spectral: super::sea::spectral_rows(if quick { 128 } else { 1024 }, plan.runs)?,
        band: super::band::band_rows(if quick { 128 } else { 1024 }, plan.runs)?,
        plane: super::plane::plane_rows(if quick { 128 } else { 1024 }, plan.runs)?,
        drag_texels: super::drag_texels::drag_texel_rows(if quick { 256 } else { 1024 }, plan.runs)?,
        files: Vec::new(),
        seconds: 0.0,
        adapter: None,
    };
    report.files = write_figures(&report, out)?;
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
