//! `soak accuracy`: what each digit of accuracy costs in time.
//!
//! Reproduces and extends the thesis' Fig. 7.10 (submerged volume of a sphere
//! r = 0.5 m against water level, texture sizes 32²…1024², against the
//! analytic cap and the per-triangle game method) and Table 7.1 (time per
//! evaluation): for several meshes and every resolution, the worst error over
//! a sweep of water levels of
//! - the submerged volume (fraction of the body's volume),
//! - the centre of buoyancy (fraction of the bounding-box diagonal),
//! - the solid inertia tensor (largest component error over the trace),
//!
//! all against the exact references of `soak_hydro::reference` (clipping the
//! same mesh), for texel sampling with moment matching (the default) and at
//! plain texel centres (the thesis), beside the median time per evaluation of
//! each path: per-texel sums, tiled sums, exact clipping, the per-triangle
//! game baseline; GPU is a column left for the `gpu` feature.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use nalgebra::{Isometry3, Point3};
use serde::Serialize;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin, load_mesh};
use soak_hydro::reference::{self, ClipPlane, analytic};
use soak_hydro::{BodyState, HydroOptions, MassModel, TiledAtlas, Water, evaluate, streaming_read};

use crate::common::{self, ms};
use crate::gpu::Gpu;
use crate::plot::{Axis, BLACK_INK, Chart, Figure, Legend, Line, Marker, RGBColor, Series, palette};

/// Arguments of `soak accuracy`.
#[derive(clap::Args)]
pub struct Args {
    /// Fewer resolutions (32²–256²), water levels and timing runs: seconds, for tests.
    #[arg(long)]
    pub quick: bool,
    /// Folder for the PNG plots.
    #[arg(long, default_value = "out/accuracy")]
    pub out: PathBuf,
    /// Print one JSON document (every row and sweep) instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also write the table as markdown (for the README) to this file.
    #[arg(long)]
    pub markdown: Option<PathBuf>,
    /// Also time the GPU path (wgpu; labelled with the adapter's name).
    #[arg(long)]
    pub gpu: bool,
}

/// Density of the solid whose inertia is compared, kg/m³ (any value: errors are relative).
const DENSITY: f64 = 500.0;
/// Sphere radius of the thesis' Fig. 7.10, m.
const RADIUS: f64 = 0.5;
/// Centre-of-buoyancy errors count only where at least this fraction of the
/// body is under water: below, the centre of a sliver is ill-conditioned for
/// every method and says nothing about the rest of the sweep.
const MIN_SUBMERGED: f64 = 0.01;

/// What the run covers.
struct Plan {
    resolutions: Vec<u32>,
    levels: usize,
    runs: usize,
}

impl Plan {
    fn new(quick: bool) -> Self {
        if quick {
            Self {
                resolutions: vec![32, 64, 128, 256],
                levels: 11,
                runs: 3,
            }
        } else {
            Self {
                resolutions: vec![32, 64, 128, 256, 512, 1024, 2048],
                levels: 41,
                runs: 15,
            }
        }
    }
}

/// One mesh at one pose, swept through the water.
struct Case {
    /// Short name in the table.
    name: &'static str,
    mesh: Mesh,
    /// XYZ Euler angles, degrees (as `soak hydro --rotation`).
    rotation_deg: [f64; 3],
    /// In the table (the fine sphere only feeds the figures).
    in_table: bool,
    /// A sphere of radius [`RADIUS`] centred at the origin: has an analytic curve.
    sphere: bool,
}

fn cases() -> anyhow::Result<Vec<Case>> {
    Ok(vec![
        Case {
            name: "sphere 64×32",
            mesh: builtin::sphere(RADIUS, 64, 32),
            rotation_deg: [0.0; 3],
            in_table: true,
            sphere: true,
        },
        Case {
            name: "sphere 256×128",
            mesh: builtin::sphere(RADIUS, 256, 128),
            rotation_deg: [0.0; 3],
            in_table: false,
            sphere: true,
        },
        Case {
            name: "box 4×1×1 at 17°,29°,43°",
            mesh: load_mesh("builtin:box:4x1x1")?,
            rotation_deg: [17.0, 29.0, 43.0],
            in_table: true,
            sphere: false,
        },
        Case {
            name: "boat, heel 15°, trim 4°",
            mesh: load_mesh("builtin:boat")?,
            rotation_deg: [15.0, 0.0, 4.0],
            in_table: true,
            sphere: false,
        },
        Case {
            name: "sphere 316×158 (100k)",
            mesh: builtin::sphere(RADIUS, 316, 158),
            rotation_deg: [0.0; 3],
            in_table: true,
            sphere: true,
        },
    ])
}

/// One table row: a mesh at a resolution.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Mesh and pose.
    pub mesh: String,
    /// Triangles in the mesh.
    pub triangles: usize,
    /// Texture side, texels.
    pub resolution: u32,
    /// Samples in the atlas (covered texels plus centroid samples of
    /// triangles too small to cover a texel centre).
    pub texels: usize,
    /// Max over the sweep of |V − V_exact| / V_body, moment matching.
    pub volume_error: f64,
    /// The same at plain texel centres (the thesis).
    pub volume_error_centres: f64,
    /// Max over the sweep of |C_B − C_B,exact| / bounding-box diagonal,
    /// moment matching (levels with ≥ 1 % of the body under water).
    pub cob_error: f64,
    /// The same at plain texel centres.
    pub cob_error_centres: f64,
    /// max_ij |I − I_exact|_ij / tr I_exact of the solid, moment matching.
    pub inertia_error: f64,
    /// The same at plain texel centres.
    pub inertia_error_centres: f64,
    /// Largest |V_tiled − V_per-texel| / V_body over the sweep (the two paths
    /// compute the same sums).
    pub tiled_vs_per_texel: f64,
    /// Median time of one per-texel evaluation (`evaluate`), ms.
    pub per_texel_ms: f64,
    /// Median time of one tiled evaluation (`TiledAtlas::evaluate`), ms.
    pub tiled_ms: f64,
    /// Per-texel time over a plain streaming read of the same atlas
    /// (`soak_hydro::streaming_read`), the two timed in turn.
    pub per_texel_over_floor: f64,
    /// GPU time per evaluation, ms: `None` until the `gpu` feature fills it.
    pub gpu_ms: Option<f64>,
    /// Median time of exact clipping (`reference::submerged_part`), ms.
    pub exact_ms: f64,
    /// Median time of the per-triangle game method, ms.
    pub per_triangle_ms: f64,
    /// Max over the sweep of the per-triangle method's |V − V_exact| / V_body.
    pub per_triangle_volume_error: f64,
}

/// Submerged volume against water level for one atlas.
#[derive(Clone, Debug, Serialize)]
pub struct Curve {
    /// Texture side, texels.
    pub resolution: u32,
    /// Moment-matched samples (true) or plain texel centres.
    pub moment_matching: bool,
    /// Submerged volume at each level, m³ (per-texel path).
    pub volume: Vec<f64>,
    /// Median time of one per-texel evaluation, ms.
    pub per_texel_ms: f64,
    /// Median time of one tiled evaluation, ms.
    pub tiled_ms: f64,
}

/// One mesh swept through the water.
#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    /// Mesh and pose.
    pub mesh: String,
    /// Triangles in the mesh.
    pub triangles: usize,
    /// The body's volume (exact, of the mesh), m³.
    pub body_volume: f64,
    /// Heights of the water plane, m (the body stays put).
    pub levels: Vec<f64>,
    /// Exact clipping of the mesh, m³.
    pub exact: Vec<f64>,
    /// The per-triangle game method, m³.
    pub per_triangle: Vec<f64>,
    /// Analytic sphere cap, m³ (spheres only).
    pub analytic: Option<Vec<f64>>,
    /// Median time of exact clipping, ms.
    pub exact_ms: f64,
    /// Median time of the per-triangle method, ms.
    pub per_triangle_ms: f64,
    /// Texel curves, per resolution and sampling.
    pub texel: Vec<Curve>,
}

/// Per-texel time over tiled time at one resolution.
#[derive(Clone, Debug, Serialize)]
pub struct Speedup {
    /// Mesh and pose.
    pub mesh: String,
    /// Texture side, texels.
    pub resolution: u32,
    /// per_texel_ms / tiled_ms.
    pub speedup: f64,
    /// Per-texel time over a plain streaming read of the same atlas
    /// (positions, area vectors, areas), the two timed in turn.
    pub per_texel_over_floor: f64,
}

/// Everything `soak accuracy` measured.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// Whether this was a `--quick` run.
    pub quick: bool,
    /// Texture sides, texels.
    pub resolutions: Vec<u32>,
    /// Water levels per sweep.
    pub levels: usize,
    /// Timed runs per path (each run repeats fast calls to ≥ 0.5 ms).
    pub timing_runs: usize,
    /// Worker threads of the texel paths (exact clipping and the
    /// per-triangle method run on one).
    pub threads: usize,
    /// The table.
    pub rows: Vec<Row>,
    /// Tiled speed-up over per-texel at 1024² (or the largest resolution).
    pub tiled_speedup: Vec<Speedup>,
    /// The curves behind the figures.
    pub sweeps: Vec<Sweep>,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Wall time of the whole run, s.
    pub seconds: f64,
    /// The adapter the GPU column ran on, if it ran.
    pub adapter: Option<String>,
}

/// How many calls of `f` make one timed sample of about 0.5 ms, so that
/// microsecond calls are measurable.
fn calls_per_sample(f: &mut dyn FnMut()) -> usize {
    let start = Instant::now();
    f();
    ((0.5 / ms(start).max(1e-6)).ceil() as usize).clamp(1, 10_000)
}

/// Time per call of `f` over `calls` calls, ms.
fn sample_ms(calls: usize, f: &mut dyn FnMut()) -> f64 {
    let start = Instant::now();
    for _ in 0..calls {
        f();
    }
    ms(start) / calls as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Median time per call of each path, ms, from `runs` samples each, taken
/// in turn so that drift on a shared machine hits every path alike (their
/// ratios are what matters). Each path's result goes through `black_box`.
fn per_call_ms<const N: usize>(runs: usize, paths: [&mut dyn FnMut(); N]) -> [f64; N] {
    let mut paths = paths;
    let calls: Vec<usize> = paths.iter_mut().map(|p| calls_per_sample(*p)).collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::with_capacity(runs); N];
    for _ in 0..runs.max(1) {
        for ((p, &n), t) in paths.iter_mut().zip(&calls).zip(&mut times) {
            t.push(sample_ms(n, *p));
        }
    }
    let mut medians = times.into_iter().map(median);
    std::array::from_fn(|_| medians.next().unwrap_or(f64::NAN))
}

/// `n` evenly spaced values from `lo` to `hi`, both included.
fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect()
}

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
) -> anyhow::Result<Measured> {
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
pub fn compute(quick: bool, out: &Path, mut gpu: Option<&mut Gpu>) -> anyhow::Result<Report> {
    let start = Instant::now();
    let plan = Plan::new(quick);
    let mut rows = Vec::new();
    let mut sweeps = Vec::new();
    for case in cases()? {
        let pose = common::pose([0.0; 3], case.rotation_deg);
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
        files: Vec::new(),
        seconds: 0.0,
        adapter: None,
    };
    report.files = figures(&report, out)?;
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `soak accuracy`.
pub fn run(args: &Args) -> anyhow::Result<()> {
    let mut device = match args.gpu {
        true => Some(Gpu::new().map_err(|e| anyhow::anyhow!("--gpu: {e}"))?),
        false => None,
    };
    let mut report = compute(args.quick, &args.out, device.as_mut())?;
    report.adapter = device.map(|d| d.label);
    let mut files = report.files.clone();
    if let Some(path) = &args.markdown {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(path, markdown(&report, path))?;
        files.push(path.clone());
    }
    if args.json {
        let mut report = report;
        report.files = files;
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print!("{}", text_table(&report));
    for f in &files {
        println!("wrote {}", f.display());
    }
    Ok(())
}

// ---------------------------------------------------------------- tables

/// `1.2e-4` below 0.1, `0.25` above; a true zero prints as `0`.
fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 0.1 {
        format!("{v:.2}")
    } else {
        format!("{v:.1e}")
    }
}

/// Milliseconds with three significant digits.
fn msf(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else if v >= 0.01 {
        format!("{v:.3}")
    } else {
        format!("{v:.1e}")
    }
}

fn gpu(v: Option<f64>) -> String {
    v.map_or("—".into(), msf)
}

const HEADERS: [&str; 16] = [
    "mesh",
    "triangles",
    "texture",
    "texels",
    "volume err",
    "(centres)",
    "CoB err",
    "(centres)",
    "inertia err",
    "(centres)",
    "per-texel ms",
    "tiled ms",
    "GPU ms",
    "exact ms",
    "per-tri ms",
    "per-tri vol err",
];

fn cells(r: &Row) -> [String; 16] {
    [
        r.mesh.clone(),
        r.triangles.to_string(),
        format!("{}²", r.resolution),
        r.texels.to_string(),
        sci(r.volume_error),
        sci(r.volume_error_centres),
        sci(r.cob_error),
        sci(r.cob_error_centres),
        sci(r.inertia_error),
        sci(r.inertia_error_centres),
        msf(r.per_texel_ms),
        msf(r.tiled_ms),
        gpu(r.gpu_ms),
        msf(r.exact_ms),
        msf(r.per_triangle_ms),
        sci(r.per_triangle_volume_error),
    ]
}

fn speedup_line(report: &Report) -> String {
    let parts: Vec<String> = report
        .tiled_speedup
        .iter()
        .map(|s| format!("{} ×{:.1}", s.mesh, s.speedup))
        .collect();
    let floors: Vec<String> = report
        .tiled_speedup
        .iter()
        .map(|s| format!("{} ×{:.2}", s.mesh, s.per_texel_over_floor))
        .collect();
    match report.tiled_speedup.first() {
        Some(s) => format!(
            "tiled speed-up over per-texel at {r}²: {}; per-texel time over a streaming read of the same atlas at {r}²: {}",
            parts.join(", "),
            floors.join(", "),
            r = s.resolution,
        ),
        None => String::new(),
    }
}

/// The table as aligned text.
fn text_table(report: &Report) -> String {
    let mut all: Vec<[String; 16]> = vec![HEADERS.map(String::from)];
    all.extend(report.rows.iter().map(cells));
    let widths: Vec<usize> = (0..16)
        .map(|c| all.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut s = String::new();
    s.push_str(&format!(
        "soak accuracy{}: max error over {} water levels against exact clipping; times are medians of {} runs, texel paths on {} threads\n",
        if report.quick { " --quick" } else { "" },
        report.levels,
        report.timing_runs,
        report.threads
    ));
    let mut last = String::new();
    for (i, r) in all.iter().enumerate() {
        if i > 1 && r[0] != last {
            s.push('\n');
        }
        last = r[0].clone();
        for (c, cell) in r.iter().enumerate() {
            let pad = widths[c] - cell.chars().count();
            if c == 0 {
                s.push_str(cell);
                s.push_str(&" ".repeat(pad));
            } else {
                s.push_str("  ");
                s.push_str(&" ".repeat(pad));
                s.push_str(cell);
            }
        }
        s.push('\n');
    }
    s.push_str("volume err: |V − V_exact| / V_body; CoB err: |C − C_exact| / bounding-box diagonal (levels ≥ 1 % submerged);\n");
    s.push_str("inertia err: largest |I − I_exact| component / tr I_exact; (centres): texel centres as in the thesis, no moment matching.\n");
    s.push_str(&speedup_line(report));
    s.push('\n');
    s.push_str(&format!("{:.1} s in total\n", report.seconds));
    s
}

/// `to` relative to the folder of `from` when it lies inside it.
fn relative(to: &Path, from: &Path) -> String {
    let base = from.parent().unwrap_or(Path::new(""));
    let p = to.strip_prefix(base).unwrap_or(to);
    p.to_string_lossy().replace('\\', "/")
}

/// The table as markdown, for the README; image links relative to `path`.
fn markdown(report: &Report, path: &Path) -> String {
    let mut s = String::new();
    s.push_str("<!-- generated by `soak accuracy --markdown`; do not edit by hand -->\n");
    s.push_str("# Accuracy costs time\n\n");
    s.push_str(&format!(
        "Worst error over {} water levels, from dry to fully submerged, against the exact clipping of the \
         same mesh; times per evaluation are medians of {} runs measured in the same run (compare ratios: \
         absolute times drift on shared machines). The texel paths ran on {} threads, exact clipping and \
         the per-triangle method on one.\n\n",
        report.levels, report.timing_runs, report.threads
    ));
    if let Some(a) = &report.adapter {
        s.push_str(&format!("The GPU column ran on {a}.\n\n"));
    }
    s.push_str(
        "- **volume err**: |V − V_exact| / V_body; **CoB err**: |C_B − C_B,exact| / bounding-box diagonal, \
         over the levels with at least 1 % of the body submerged; **inertia err**: largest component of \
         |I − I_exact| / tr I_exact (solid of uniform density).\n\
         - **(centres)**: samples at plain texel centres, as in the thesis; the other columns use moment \
         matching (each triangle's samples nudged so their mean and covariance are the triangle's).\n\
         - **texels**: samples in the atlas, including one centroid sample per triangle too small to cover a \
         texel centre.\n\
         - **per-texel**: `evaluate`; **tiled**: `TiledAtlas::evaluate` (one closed form for the runs of \
         tiles wholly under water, the per-texel kernel on the smaller side of each cut tile; same sums); **GPU**: `gpu::GpuHydro::evaluate` (one body per submission, \
         readback included; `--gpu`); **exact**: `reference::submerged_part`; **per-tri**: the per-triangle \
         game method (AQUAS-style water columns, the baseline of the thesis' Fig. 7.10) and its volume \
         error.\n\n",
    );
    s.push_str(&format!("| {} |\n", HEADERS.join(" | ")));
    s.push_str(&format!(
        "|{}\n",
        HEADERS
            .iter()
            .enumerate()
            .map(|(i, _)| if i == 0 { " --- |" } else { " ---: |" })
            .collect::<String>()
    ));
    for r in &report.rows {
        s.push_str(&format!("| {} |\n", cells(r).join(" | ")));
    }
    s.push('\n');
    s.push_str(&speedup_line(report));
    s.push_str(".\n\n");
    for f in &report.files {
        let name = f
            .file_stem()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        s.push_str(&format!("![{name}]({})\n\n", relative(f, path)));
    }
    s
}

// ---------------------------------------------------------------- figures

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
fn figures(report: &Report, out: &Path) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(out)?;
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
fn sphere_figure(report: &Report) -> anyhow::Result<Figure> {
    let sphere = report
        .sweeps
        .first()
        .ok_or_else(|| anyhow::anyhow!("no sweep to plot"))?;
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
fn cost_figure(report: &Report) -> anyhow::Result<Figure> {
    let sphere = report
        .sweeps
        .first()
        .ok_or_else(|| anyhow::anyhow!("no sweep to plot"))?;
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
