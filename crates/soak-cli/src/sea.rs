//! `soak sea SCENE`: a scene's spectral sea as realised, against the
//! spectrum it was asked for: its significant height and peak period from
//! the scene's seed and averaged over more seeds, the spectrum binned at
//! the tile's own frequency resolution beside the target (a table, a plot),
//! and a still of the sea drawn as `soak render` and the viewer draw it.

use std::f64::consts::TAU;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use nalgebra::{Point3, Vector3};
use serde::Serialize;
use soak_hydro::{SpectralSea, SpectralSurface, SpectrumShape, Surface};
use soak_rapier::scene::{LoadedScene, WaterKind};
use soak_report::chart::{Axis, Chart, Figure, Line, Marker, Series, palette};
use soak_shade::render::{Camera, DirectionalLight, RenderScene, RenderWater, Renderer, headless_device};

/// Arguments of `soak sea`.
#[derive(clap::Args)]
pub struct Args {
    /// A scene file whose `[water]` is `kind = "spectrum"`.
    scene: PathBuf,
    /// How many seeds the recovery is averaged over: the scene's and the
    /// ones after it.
    #[arg(long, default_value_t = 16)]
    seeds: u64,
    /// The time the tile is evaluated at for its elevation's statistics,
    /// the profile and the still, s.
    #[arg(long, default_value_t = 0.0)]
    time: f64,
    /// Write the plots (the spectrum against the target; a profile of the
    /// surface along the mean direction) to this PNG.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Render a still of the sea (the water alone) to this PNG.
    #[arg(long)]
    still: Option<PathBuf>,
    /// Width of the still, pixels.
    #[arg(long, default_value_t = 960)]
    width: u32,
    /// Height of the still, pixels.
    #[arg(long, default_value_t = 540)]
    height: u32,
    /// Print one JSON object instead of the tables.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Target {
    /// "jonswap" or "pierson_moskowitz"
    spectrum: &'static str,
    /// JONSWAP's peak enhancement
    gamma: Option<f64>,
    /// m
    significant_height: f64,
    /// s
    peak_period: f64,
    /// m
    peak_wavelength: f64,
    /// degrees from +x toward +z
    direction_deg: f64,
    /// the cos-2s exponent
    spreading: f64,
}

#[derive(Serialize)]
struct Tile {
    /// m
    size: f64,
    cells: usize,
    /// modes with energy
    modes: usize,
    /// the shortest wave the tile holds, m
    shortest_wavelength: f64,
    choppiness: f64,
    seed: u64,
}

#[derive(Serialize)]
struct Realised {
    /// over the modes, `4 √(Σ |A|²/2)`, m
    significant_height: f64,
    /// over the tile's nodes at `time`, `4 √⟨η²⟩`, m
    significant_height_nodes: f64,
    /// s
    time: f64,
    /// the period of the binned spectrum's highest bin, s
    peak_period: f64,
    /// the highest and lowest elevation over the nodes at `time`, m
    crest: f64,
    trough: f64,
    /// the share of nodes where the choppy map folds over (its Jacobian ≤ 0)
    folded: f64,
}

#[derive(Serialize)]
struct Averaged {
    seeds: u64,
    /// rms over the seeds of the nodes' significant height, m
    significant_height: f64,
    /// s
    peak_period: f64,
    /// the peak's frequency against the target's, in bins
    peak_off_by_bins: f64,
}

#[derive(Serialize)]
struct Bin {
    /// bin centre, rad/s
    omega: f64,
    /// the target's density averaged over the bin, m²·s/rad
    target: f64,
    /// the scene's seed's realised density
    realised: f64,
    /// the realised density averaged over the seeds
    mean: f64,
}

#[derive(Serialize)]
struct Report {
    scene: String,
    target: Target,
    tile: Tile,
    /// bins' width: the tile's frequency resolution at the peak, rad/s
    bin: f64,
    realised: Realised,
    averaged: Averaged,
    bins: Vec<Bin>,
}

/// The period (s) at the centre of the highest bin.
fn peak_period(density: &[f64], bin: f64) -> f64 {
    let top = density
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(b, _)| b);
    TAU / ((top as f64 + 0.5) * bin)
}

pub fn run(args: &Args) -> Result<()> {
    if args.seeds == 0 {
        bail!("--seeds must be at least 1");
    }
    if !args.time.is_finite() {
        bail!("--time {} is not a finite number of seconds", args.time);
    }
    let loaded = LoadedScene::from_file(&args.scene)?;
    let water = &loaded.scene.water;
    if water.kind != WaterKind::Spectrum {
        bail!(
            "scene `{}`: its water is {:?}, not a spectral sea (`[water] kind = \"spectrum\"`)",
            args.scene.display(),
            water.kind
        );
    }
    let g = Vector3::from(loaded.scene.gravity).norm();
    let spectrum = water.sea_spectrum().context("the scene's sea")?;
    let sea = water.spectral_sea(g).context("the scene's sea")?;
    let seed = water.seed.unwrap_or(0);
    let wp = spectrum.peak_frequency();
    let bin = sea.frequency_resolution(wp);
    let bins = ((3.0 * wp / bin).ceil() as usize).max(8);

    // The target's density averaged over each bin (Simpson, 16 panels).
    let target: Vec<f64> = (0..bins)
        .map(|b| {
            let lo = b as f64 * bin;
            let omegas: Vec<f64> = (0..=16).map(|i| lo + bin * i as f64 / 16.0).collect();
            let d = spectrum.densities(&omegas);
            let simpson: f64 = d
                .iter()
                .enumerate()
                .map(|(i, v)| match i {
                    0 | 16 => *v,
                    i if i % 2 == 1 => 4.0 * v,
                    _ => 2.0 * v,
                })
                .sum();
            simpson / 48.0
        })
        .collect();
    let realised = sea.frequency_spectrum(bin, bins);
    let fields = sea.fields(args.time);
    let variance: f64 = sea.modes().map(|(_, _, a2)| 0.5 * a2).sum();
    let folded = (0..fields.height.len())
        .filter(|&i| {
            let [dxx, dxz, dzz] = &fields.displacement_gradient;
            (1.0 + dxx[i]) * (1.0 + dzz[i]) - dxz[i] * dxz[i] <= 0.0
        })
        .count() as f64
        / fields.height.len() as f64;
    let this = Realised {
        significant_height: 4.0 * variance.sqrt(),
        significant_height_nodes: fields.significant_height(),
        time: args.time,
        peak_period: peak_period(&realised, bin),
        crest: fields.height.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        trough: fields.height.iter().copied().fold(f64::INFINITY, f64::min),
        folded,
    };

    // The same sea from the next seeds.
    let mut mean = vec![0.0; bins];
    let mut hs2 = 0.0;
    for s in seed..seed.saturating_add(args.seeds) {
        let mut spec = water.clone();
        spec.seed = Some(s);
        let other = if s == seed {
            sea.clone()
        } else {
            spec.spectral_sea(g).context("the scene's sea")?
        };
        hs2 += other.fields(args.time).significant_height().powi(2);
        for (m, r) in mean.iter_mut().zip(other.frequency_spectrum(bin, bins)) {
            *m += r / args.seeds as f64;
        }
    }
    let averaged_peak = peak_period(&mean, bin);
    let averaged = Averaged {
        seeds: args.seeds,
        significant_height: (hs2 / args.seeds as f64).sqrt(),
        peak_period: averaged_peak,
        peak_off_by_bins: (TAU / averaged_peak - wp) / bin,
    };
    let (name, gamma) = match spectrum.shape {
        SpectrumShape::Jonswap { gamma } => ("jonswap", Some(gamma)),
        SpectrumShape::PiersonMoskowitz => ("pierson_moskowitz", None),
    };
    let report = Report {
        scene: args.scene.display().to_string(),
        target: Target {
            spectrum: name,
            gamma,
            significant_height: spectrum.significant_height,
            peak_period: spectrum.peak_period,
            peak_wavelength: spectrum.peak_wavelength(g),
            direction_deg: spectrum.direction_deg,
            spreading: spectrum.spreading,
        },
        tile: Tile {
            size: sea.size,
            cells: sea.cells,
            modes: sea.modes().count(),
            shortest_wavelength: 2.0 * sea.size / sea.cells as f64,
            choppiness: sea.choppiness,
            seed,
        },
        bin,
        realised: this,
        averaged,
        bins: (0..bins)
            .map(|b| Bin {
                omega: (b as f64 + 0.5) * bin,
                target: target[b],
                realised: realised[b],
                mean: mean[b],
            })
            .collect(),
    };
    if let Some(path) = &args.plot {
        plot(&report, &sea, args.time, path)?;
    }
    if let Some(path) = &args.still {
        still(&sea, args.time, (args.width, args.height), path)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print_report(&report);
    for (what, path) in [("plots", &args.plot), ("still", &args.still)] {
        if let Some(path) = path {
            println!("{what} in {}", path.display());
        }
    }
    Ok(())
}

fn percent(value: f64, target: f64) -> String {
    format!("{:+.1} %", 100.0 * (value / target - 1.0))
}

fn print_report(r: &Report) {
    let t = &r.target;
    println!(
        "{}: {}{}, Hs {} m, Tp {} s (peak wavelength {:.1} m), toward {}°, spreading s = {}",
        r.scene,
        if t.spectrum == "jonswap" {
            "JONSWAP"
        } else {
            "Pierson–Moskowitz"
        },
        t.gamma.map_or(String::new(), |g| format!(" (γ {g})")),
        t.significant_height,
        t.peak_period,
        t.peak_wavelength,
        t.direction_deg,
        t.spreading
    );
    println!(
        "tile {:.1} m, {}² cells of {:.3} m: {} modes, waves {:.2} m and longer, choppiness {}, seed {}",
        r.tile.size,
        r.tile.cells,
        r.tile.size / r.tile.cells as f64,
        r.tile.modes,
        r.tile.shortest_wavelength,
        r.tile.choppiness,
        r.tile.seed
    );
    let s = &r.realised;
    println!(
        "seed {}: Hs {:.4} m over the modes ({}), {:.4} m over the nodes at t = {} s; crest {:+.3} m, trough {:+.3} m; \
         the choppy map folds at {:.2} % of the nodes",
        r.tile.seed,
        s.significant_height,
        percent(s.significant_height, t.significant_height),
        s.significant_height_nodes,
        s.time,
        s.crest,
        s.trough,
        100.0 * s.folded
    );
    println!(
        "seed {}: peak period {:.3} s (its spectrum's highest bin, {:.4} rad/s wide)",
        r.tile.seed, s.peak_period, r.bin
    );
    let a = &r.averaged;
    println!(
        "{} seeds: Hs {:.4} m ({}), peak period {:.3} s against {} s ({:+.2} bins)",
        a.seeds,
        a.significant_height,
        percent(a.significant_height, t.significant_height),
        a.peak_period,
        t.peak_period,
        a.peak_off_by_bins
    );
    println!();
    println!(
        "{:>9} {:>8} | {:>12} {:>12} {:>12}",
        "ω rad/s", "T s", "target", "seed", "mean"
    );
    // The bins that hold any of the sea: above a ten-thousandth of the
    // target's peak density.
    let top = r.bins.iter().map(|b| b.target.max(b.mean)).fold(0.0, f64::max);
    for b in r.bins.iter().filter(|b| b.target.max(b.mean) > 1e-4 * top) {
        println!(
            "{:>9.4} {:>8.3} | {:>12.4e} {:>12.4e} {:>12.4e}",
            b.omega,
            TAU / b.omega,
            b.target,
            b.realised,
            b.mean
        );
    }
    println!("(densities in m²·s/rad, each over its bin; bins below a ten-thousandth of the peak left out)");
}

fn plot(r: &Report, sea: &SpectralSea, time: f64, path: &std::path::Path) -> Result<()> {
    let series = |label: &str, f: &dyn Fn(&Bin) -> f64| {
        Series::new(label, r.bins.iter().map(|b| (b.omega, f(b))).collect())
    };
    let spectrum = Chart::new("Frequency spectrum")
        .x(Axis::linear("ω (rad/s)"))
        .y(Axis::linear("S(ω) (m²·s/rad)"))
        .series(series("target", &|b| b.target).color(palette(0)).width(2))
        .series(
            series(&format!("seed {}", r.tile.seed), &|b| b.realised)
                .color(palette(1))
                .line(Line::None)
                .marker(Marker::Circle),
        )
        .series(
            series(&format!("mean of {} seeds", r.averaged.seeds), &|b| b.mean)
                .color(palette(2))
                .line(Line::Dashed),
        );
    // The surface along the mean direction over one tile, read as bodies
    // read it (the choppy map inverted), and the nodes' particles.
    let surface = SpectralSurface::new(sea.clone());
    let dir = r.target.direction_deg.to_radians();
    let (c, s) = (dir.cos(), dir.sin());
    let n = 4 * sea.cells;
    let profile: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let d = sea.size * i as f64 / n as f64;
            (d, surface.height(d * c, d * s, time) - sea.level)
        })
        .collect();
    let profile = Chart::new(format!(
        "Surface along {}° at t = {time} s",
        r.target.direction_deg
    ))
    .x(Axis::linear("distance (m)"))
    .y(Axis::linear("elevation (m)"))
    .series(Series::new("surface", profile).color(palette(0)));
    Figure::new(1400, 450)
        .title(format!(
            "soak sea {}: Hs {} m, Tp {} s",
            r.scene, r.target.significant_height, r.target.peak_period
        ))
        .panel(spectrum)
        .panel(profile)
        .write_png(path)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// The sea alone at `time`, seen from above its mean level at a distance
/// of two peak wavelengths, as the renderer draws it.
fn still(sea: &SpectralSea, time: f64, (width, height): (u32, u32), path: &std::path::Path) -> Result<()> {
    if !(1..=8192).contains(&width) || !(1..=8192).contains(&height) {
        bail!("--width and --height must be within 1..=8192 pixels");
    }
    let (device, queue, _) = headless_device()?;
    let mut renderer = Renderer::new(&device, &queue, width, height)?;
    let span = (sea.size / 4.0).max(1.0);
    let target = Point3::new(0.0, sea.level, 0.0);
    let eye = target + Vector3::new(0.55, 0.32, 1.0).normalize() * span;
    let mut scene = RenderScene::new(Camera::perspective(eye, target, 45.0));
    scene.light = DirectionalLight::from_angles(38.0, 25.0, [2.7, 2.5, 2.3]);
    let mut water = RenderWater::spectral(std::sync::Arc::new(sea.fields(time)));
    water.extent = 4.0 * span;
    water.resolution = 512;
    scene.water = Some(water);
    renderer
        .render(&scene)?
        .save(path)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}
