//! `soak seakeeping MESH`: a mesh floating at rest, its radiation
//! coefficients and RAOs over frequencies (a table, optionally JSON and a
//! plot) and the free decay of its restoring modes, from the frequency
//! domain.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use serde::Serialize;
use soak_hydro::MassModel;
use soak_report::chart::{Axis, Chart, Figure, Line, Series, palette};
use soak_seakeeping::{FloatingBody, RadiationModel, RadiationSettings};

use crate::common;

/// Arguments of `soak seakeeping`.
#[derive(clap::Args)]
pub struct Args {
    /// A mesh file (.obj, .gltf, .glb) or a builtin name.
    #[arg(required_unless_present = "references")]
    mesh: Option<String>,
    /// Solid body of this density, kg/m³ (the default, 500).
    #[arg(long, conflicts_with = "shell")]
    density: Option<f64>,
    /// Thin shell of this areal density, kg/m², instead of a solid.
    #[arg(long)]
    shell: Option<f64>,
    /// Orientation to float it from, degrees about x, then y, then z:
    /// RX,RY,RZ (it settles to the stable one nearest).
    #[arg(long, value_parser = common::triple, default_value = "0,0,0", allow_hyphen_values = true)]
    rotation: [f64; 3],
    /// Texture side of the atlas the mass properties are summed over.
    #[arg(long, short, default_value_t = 128)]
    resolution: u32,
    /// About how many panels the wetted surface is cut into.
    #[arg(long, default_value_t = 300)]
    panels: usize,
    /// How many frequencies are solved.
    #[arg(long, default_value_t = 40)]
    frequencies: usize,
    /// Wave heading for the RAOs, degrees from +x toward +z.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    heading: f64,
    /// Fluid density, kg/m³.
    #[arg(long, default_value_t = 1000.0)]
    water_density: f64,
    /// Write the plots (added mass, damping, RAOs, free decay) to this PNG.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print one JSON object instead of the tables.
    #[arg(long)]
    json: bool,
    /// Instead of a mesh: the panel method against the references of two
    /// classical bodies (Hulme's surging hemisphere, the truncated
    /// cylinder's heave by eigenfunction expansions), a table and this PNG.
    #[arg(long, conflicts_with_all = ["mesh", "plot", "json"])]
    references: Option<PathBuf>,
}

/// The modes' names, in the order of the 6×6 matrices.
const MODES: [&str; 6] = ["surge", "heave", "sway", "roll", "yaw", "pitch"];
/// The modes with a restoring stiffness: heave, roll (about x), pitch (about z).
const RESTORING: [usize; 3] = [1, 3, 5];

#[derive(Serialize)]
struct Row {
    /// rad/s
    omega: f64,
    /// wavenumber × the model's length
    kl: f64,
    /// per mode: kg, kg·m²
    added_mass: [f64; 6],
    /// per mode: kg/s, kg·m²/s
    damping: [f64; 6],
    /// heave (m/m), roll and pitch (rad/m) at the heading
    rao: [Option<f64>; 3],
}

#[derive(Serialize)]
struct Decay {
    mode: &'static str,
    /// s
    period: f64,
    /// ratio of successive positive peaks, first two cycles
    peak_ratio: f64,
}

#[derive(Serialize)]
struct Report {
    mesh: String,
    /// kg
    mass: f64,
    /// m³
    displaced: f64,
    /// m²
    waterplane_area: f64,
    /// centre of mass above the still water plane, m
    center_of_mass_height: f64,
    /// rest orientation found, as a rotation vector (rad)
    rest_rotation: [f64; 3],
    /// heave N/m, roll and pitch N·m/rad
    stiffness: [f64; 3],
    panels: usize,
    /// per mode
    states: [usize; 6],
    /// the infinite-frequency added mass per mode
    infinite: [f64; 6],
    bake_seconds: f64,
    rows: Vec<Row>,
    decay: Vec<Decay>,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let Some(name) = &args.mesh else {
        let path = args
            .references
            .as_ref()
            .expect("clap asks for a mesh or --references");
        return references(path);
    };
    let mesh = common::mesh(name, false)?;
    let (atlas, _) = common::bake(&mesh, args.resolution)?;
    let model = match args.shell {
        Some(areal_density) => MassModel::Shell { areal_density },
        None => MassModel::Solid {
            density: args.density.unwrap_or(500.0),
        },
    };
    let mass = model.mass_properties(&atlas).context("mass properties")?;
    let pose = common::pose([0.0; 3], args.rotation);
    let settings = RadiationSettings {
        density: args.water_density,
        panels: args.panels,
        frequencies: args.frequencies,
        ..RadiationSettings::default()
    };
    let start = Instant::now();
    let radiation = RadiationModel::bake(
        &FloatingBody {
            mesh: &mesh,
            mass: mass.mass,
            center_of_mass: mass.center_of_mass,
            inertia: mass.inertia,
            rotation: pose.rotation,
        },
        &settings,
    )
    .with_context(|| format!("radiation of {}", mesh.name))?;
    let bake_seconds = start.elapsed().as_secs_f64();
    let heading = args.heading.to_radians();
    let h = radiation.hydrostatics();
    let g = radiation.gravity();
    let rows: Vec<Row> = radiation
        .sweep()
        .frequencies
        .iter()
        .map(|c| Row {
            omega: c.omega,
            kl: c.omega * c.omega / g * radiation.length(),
            added_mass: std::array::from_fn(|m| c.added_mass[(m, m)]),
            damping: std::array::from_fn(|m| c.damping[(m, m)]),
            rao: RESTORING.map(|m| radiation.rao(m, c.omega, heading)),
        })
        .collect();
    // Free decay of each restoring mode, from the frequency domain.
    let dt = 0.01;
    let mut curves = Vec::new();
    let mut decay = Vec::new();
    for mode in RESTORING {
        let stiffness = h.stiffness[(mode, mode)];
        if stiffness <= 0.0 {
            continue;
        }
        let natural =
            (stiffness / (radiation.mode_inertia(mode) + radiation.infinite()[(mode, mode)])).sqrt();
        let length = (8.0 * std::f64::consts::TAU / natural / dt) as usize;
        let times: Vec<f64> = (0..length).map(|n| n as f64 * dt).collect();
        if let Some(x) = radiation.release(mode, 1.0, &times)
            && let Some((period, peak_ratio)) = soak_seakeeping::decay_measure(&x, dt)
        {
            decay.push(Decay {
                mode: MODES[mode],
                period,
                peak_ratio,
            });
            curves.push((MODES[mode], times.into_iter().zip(x).collect::<Vec<_>>()));
        }
    }
    let rest = radiation.rotation().scaled_axis();
    let report = Report {
        mesh: mesh.name.clone(),
        mass: radiation.mass(),
        displaced: h.volume,
        waterplane_area: h.waterplane_area,
        center_of_mass_height: h.center_of_mass_height,
        rest_rotation: [rest.x, rest.y, rest.z],
        stiffness: RESTORING.map(|m| h.stiffness[(m, m)]),
        panels: radiation.panel_count(),
        states: std::array::from_fn(|m| radiation.kernel(m).poles.len()),
        infinite: std::array::from_fn(|m| radiation.infinite()[(m, m)]),
        bake_seconds,
        rows,
        decay,
    };
    if let Some(path) = &args.plot {
        plot(&report, &curves, path)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print_report(&report, args.heading);
    if let Some(path) = &args.plot {
        println!("plots in {}", path.display());
    }
    Ok(())
}

fn print_report(r: &Report, heading: f64) {
    println!(
        "{}: {:.3} kg, floating with its centre of mass {:+.4} m from the still water, displacing {:.5} m³; \
         water-plane {:.4} m²; rest orientation {:.2}° ({} panels, {} kernel states, baked in {:.2} s)",
        r.mesh,
        r.mass,
        r.center_of_mass_height,
        r.displaced,
        r.waterplane_area,
        nalgebra::Vector3::from(r.rest_rotation).norm().to_degrees(),
        r.panels,
        r.states.iter().sum::<usize>(),
        r.bake_seconds
    );
    println!(
        "stiffness: heave {:.1} N/m, roll {:.1} N·m/rad, pitch {:.1} N·m/rad",
        r.stiffness[0], r.stiffness[1], r.stiffness[2]
    );
    println!(
        "A∞: {}",
        MODES
            .iter()
            .zip(r.infinite)
            .map(|(m, a)| format!("{m} {a:.4e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    println!();
    println!(
        "{:>8} {:>7} | {:>11} {:>11} | {:>11} {:>11} | {:>11} {:>11} | {:>11} {:>11} | RAO at {heading}°: {:>7} {:>7} {:>7}",
        "ω rad/s",
        "KL",
        "A surge",
        "B surge",
        "A heave",
        "B heave",
        "A roll",
        "B roll",
        "A pitch",
        "B pitch",
        "heave",
        "roll",
        "pitch"
    );
    let rao = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
    for row in &r.rows {
        println!(
            "{:>8.3} {:>7.3} | {:>11.4e} {:>11.4e} | {:>11.4e} {:>11.4e} | {:>11.4e} {:>11.4e} | {:>11.4e} {:>11.4e} | {:>7} {:>7} {:>7}",
            row.omega,
            row.kl,
            row.added_mass[0],
            row.damping[0],
            row.added_mass[1],
            row.damping[1],
            row.added_mass[3],
            row.damping[3],
            row.added_mass[5],
            row.damping[5],
            rao(row.rao[0]),
            rao(row.rao[1]),
            rao(row.rao[2]),
        );
    }
    println!();
    for d in &r.decay {
        println!(
            "free decay, {}: period {:.3} s, successive peaks {:.3}",
            d.mode, d.period, d.peak_ratio
        );
    }
}

fn plot(r: &Report, curves: &[(&str, Vec<(f64, f64)>)], path: &std::path::Path) -> anyhow::Result<()> {
    let series = |label: &str, k: usize, f: &dyn Fn(&Row) -> Option<f64>| {
        Series::new(
            label,
            r.rows
                .iter()
                .filter_map(|row| f(row).map(|v| (row.omega, v)))
                .collect(),
        )
        .color(palette(k))
    };
    let mut added = Chart::new("Added mass over A∞")
        .x(Axis::linear("ω (rad/s)"))
        .y(Axis::linear("A(ω)/A∞"));
    let mut damping = Chart::new("Damping over ω A∞")
        .x(Axis::linear("ω (rad/s)"))
        .y(Axis::linear("B(ω)/(ω A∞)"));
    for (k, &mode) in [0usize, 1, 3, 5].iter().enumerate() {
        let infinite = r.infinite[mode];
        if infinite.abs() < 1e-12 {
            continue;
        }
        added = added.series(series(MODES[mode], k, &|row| {
            Some(row.added_mass[mode] / infinite)
        }));
        damping = damping.series(series(MODES[mode], k, &|row| {
            Some(row.damping[mode] / (row.omega * infinite))
        }));
    }
    let mut rao = Chart::new("RAO")
        .x(Axis::linear("ω (rad/s)"))
        .y(Axis::linear("heave (m/m), roll and pitch (rad/m)"));
    for (k, name) in ["heave", "roll", "pitch"].iter().enumerate() {
        rao = rao.series(series(name, k + 1, &|row| row.rao[k]));
    }
    let mut decay = Chart::new("Free decay (frequency domain)")
        .x(Axis::linear("time (s)"))
        .y(Axis::linear("x / x₀"));
    for (k, (name, points)) in curves.iter().enumerate() {
        decay = decay.series(
            Series::new(*name, points.clone())
                .color(palette(k + 1))
                .line(if k == 0 { Line::Solid } else { Line::Dashed }),
        );
    }
    Figure::new(1600, 450)
        .title(format!("soak seakeeping {}: {} panels", r.mesh, r.panels))
        .panel(added)
        .panel(damping)
        .panel(rao)
        .panel(decay)
        .write_png(path)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// One reference curve against the panel method: `(Ka, reference,
/// panels)` for the added mass and for the damping (NaN where the
/// reference has none).
struct Comparison {
    title: &'static str,
    /// For a panel's title.
    short: &'static str,
    panels: usize,
    added: Vec<(f64, f64, f64)>,
    damping: Vec<(f64, f64, f64)>,
}

/// `--references`: the hemisphere in surge (576 panels) against Hulme
/// (1982) and the truncated cylinder in heave (1,152 panels) against the
/// eigenfunction solution, as `cargo test -p soak-seakeeping` checks them.
fn references(path: &std::path::Path) -> anyhow::Result<()> {
    use soak_seakeeping::references::{
        HULME_SURGE, TRUNCATED_CYLINDER_HEAVE, sphere_panels, truncated_cylinder_panels,
    };
    use soak_seakeeping::{Radiation, Surface};
    use std::f64::consts::PI;
    let (rho, g) = (1000.0, 9.81);
    let compare = |(title, short): (&'static str, &'static str),
                   panels: Vec<soak_seakeeping::Panel>,
                   mode: usize,
                   scale: f64,
                   table: &[(f64, f64, f64)]|
     -> anyhow::Result<Comparison> {
        let count = panels.len();
        let problem = Radiation::new(panels, nalgebra::Point3::origin(), rho, g)?;
        let (mut added, mut damping) = (Vec::new(), Vec::new());
        for &(ka, a_ref, b_ref) in table {
            let c = problem.solve(Surface::Wavenumber(ka))?;
            added.push((ka, a_ref, c.added_mass[(mode, mode)] / scale));
            damping.push((ka, b_ref, c.damping[(mode, mode)] / (c.omega * scale)));
        }
        Ok(Comparison {
            title,
            short,
            panels: count,
            added,
            damping,
        })
    };
    let hemisphere = compare(
        ("hemisphere, surge: Hulme (1982)", "hemisphere surge (Hulme)"),
        sphere_panels(1.0, nalgebra::Point3::origin(), PI / 2.0, 12, 48)?,
        0,
        rho * 2.0 / 3.0 * PI,
        &HULME_SURGE,
    )?;
    let cylinder = compare(
        (
            "truncated cylinder (draft = radius), heave: eigenfunctions",
            "cylinder heave (eigenfunctions)",
        ),
        truncated_cylinder_panels(1.0, 1.0, 12, 12, 48)?,
        1,
        rho * PI,
        &TRUNCATED_CYLINDER_HEAVE,
    )?;
    let mut figure =
        Figure::new(1800, 450).title("soak's panel method against classical references (a = 1 m)");
    for c in [&hemisphere, &cylinder] {
        println!("{} ({} panels)", c.title, c.panels);
        println!(
            "{:>6} {:>10} {:>10} {:>8} {:>10} {:>10} {:>8}",
            "Ka", "A ref", "A panels", "error", "B ref", "B panels", "error"
        );
        for ((ka, a_ref, a), (_, b_ref, b)) in c.added.iter().zip(&c.damping) {
            let error = |ours: f64, theirs: f64| {
                if theirs.is_finite() {
                    format!("{:+.2} %", 100.0 * (ours / theirs - 1.0))
                } else {
                    "-".to_string()
                }
            };
            println!(
                "{ka:>6} {a_ref:>10.4} {a:>10.4} {:>8} {b_ref:>10.5} {b:>10.5} {:>8}",
                error(*a, *a_ref),
                error(*b, *b_ref)
            );
        }
        println!();
        for (name, points) in [("added mass", &c.added), ("damping", &c.damping)] {
            let reference: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.1.is_finite())
                .map(|p| (p.0, p.1))
                .collect();
            let ours: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.2)).collect();
            figure = figure.panel(
                Chart::new(format!("{}: {name}", c.short))
                    .x(Axis::linear("Ka"))
                    .y(Axis::linear(if name == "added mass" {
                        "A / (ρ V)"
                    } else {
                        "B / (ρ ω V)"
                    }))
                    .series(Series::new(format!("panels ({})", c.panels), ours).color(palette(0)))
                    .series(
                        Series::new("reference", reference)
                            .color(palette(1))
                            .line(Line::None)
                            .marker(soak_report::chart::Marker::Circle),
                    ),
            );
        }
    }
    figure
        .write_png(path)
        .with_context(|| format!("writing {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}
