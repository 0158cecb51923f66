//! `soak seakeeping MESH`: a mesh floating at rest, its radiation
//! coefficients and RAOs over frequencies (a table, optionally JSON and a
//! plot) and the free decay of its restoring modes, from the frequency
//! domain.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use nalgebra::{Isometry3, Translation3, Vector3};
use serde::Serialize;
use soak_bake::Mesh;
use soak_hydro::MassModel;
use soak_report::chart::{Axis, Chart, Figure, Line, Series, palette};
use soak_seakeeping::{FloatingBody, RadiationModel, RadiationSettings, SeakeepingError, wetted_panels};

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
    /// Write the hull the radiation was baked on to this Wavefront OBJ
    /// (vertices in m, triangles counter-clockwise seen from outside), at
    /// its rest pose in the water's frame: y up, the still water at y = 0,
    /// the centre of mass at x = z = 0. A mesh with many more wetted
    /// triangles than --panels is baked on a simplified copy, and that copy
    /// is written; should it not displace the model's volume at the rest
    /// pose (the bake changed its rule), it is written anyway with a warning.
    /// For another panel code: scripts/references/capytaine_hull.py.
    #[arg(long, value_name = "FILE")]
    hull_obj: Option<PathBuf>,
    /// Instead of a mesh: the panel method against the references of two
    /// classical bodies (Hulme's surging hemisphere, the truncated
    /// cylinder's heave by eigenfunction expansions), a table and this PNG.
    #[arg(long, conflicts_with_all = ["mesh", "plot", "json", "hull_obj"])]
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
    /// heave (m/m), roll and pitch (rad/m) at the heading, moving
    /// together as the time domain moves them
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

/// The hull `--hull-obj` wrote.
#[derive(Serialize)]
struct HullObj {
    path: PathBuf,
    vertices: usize,
    triangles: usize,
    /// whether it is the bake's simplified copy of the mesh
    simplified: bool,
    /// volume under the still water at the rest pose, m³ (`displaced`
    /// when it is the hull baked)
    displaced: f64,
}

#[derive(Serialize)]
struct Report {
    mesh: String,
    /// fluid density, kg/m³
    water_density: f64,
    /// m/s²
    gravity: f64,
    /// kg
    mass: f64,
    /// centre of mass, the mesh's own frame, m
    center_of_mass: [f64; 3],
    /// m³
    displaced: f64,
    /// m²
    waterplane_area: f64,
    /// centre of mass above the still water plane, m
    center_of_mass_height: f64,
    /// rest orientation found, as a rotation vector (rad)
    rest_rotation: [f64; 3],
    /// with `rest_rotation` R, the rest pose: a point p of the mesh is at
    /// R p + t in the water's frame (m)
    rest_translation: [f64; 3],
    /// heave N/m, roll and pitch N·m/rad
    stiffness: [f64; 3],
    panels: usize,
    /// per mode
    states: [usize; 6],
    /// the infinite-frequency added mass per mode
    infinite: [f64; 6],
    bake_seconds: f64,
    /// the hull written by `--hull-obj`
    #[serde(skip_serializing_if = "Option::is_none")]
    hull_obj: Option<HullObj>,
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
            rao: {
                let coupled = radiation.coupled_rao(c.omega, heading);
                std::array::from_fn(|i| coupled.map(|r| r[i]))
            },
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
    let hull_obj = match &args.hull_obj {
        Some(path) => Some(write_hull(&mesh, &radiation, args.panels, path)?),
        None => None,
    };
    let pose = rest_pose(&radiation, h.center_of_mass_height);
    let rest = pose.rotation.scaled_axis();
    let report = Report {
        mesh: mesh.name.clone(),
        water_density: radiation.density(),
        gravity: g,
        mass: radiation.mass(),
        center_of_mass: common::arr(radiation.center_of_mass()),
        displaced: h.volume,
        waterplane_area: h.waterplane_area,
        center_of_mass_height: h.center_of_mass_height,
        rest_rotation: [rest.x, rest.y, rest.z],
        rest_translation: common::vec3(&pose.translation.vector),
        stiffness: RESTORING.map(|m| h.stiffness[(m, m)]),
        panels: radiation.panel_count(),
        states: std::array::from_fn(|m| radiation.kernel(m).poles.len()),
        infinite: std::array::from_fn(|m| radiation.infinite()[(m, m)]),
        bake_seconds,
        hull_obj,
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
    if let Some(hull) = &report.hull_obj {
        println!(
            "hull at rest in {} ({} triangles{}, displacing {:.5} m³)",
            hull.path.display(),
            hull.triangles,
            if hull.simplified {
                ", the bake's simplified copy"
            } else {
                ""
            },
            hull.displaced
        );
    }
    Ok(())
}

/// The model's rest pose with the centre of mass `height` m above the
/// still water: the mesh's frame → the water's (y up, the centre of mass
/// at x = z = 0), as the bake places the body.
fn rest_pose(radiation: &RadiationModel, height: f64) -> Isometry3<f64> {
    let rotation = *radiation.rotation();
    let com = rotation * radiation.center_of_mass().coords;
    Isometry3::from_parts(
        Translation3::from(Vector3::new(-com.x, height - com.y, -com.z)),
        rotation,
    )
}

/// `--hull-obj`: the hull `radiation` was baked on, placed at its rest
/// pose, written to `path` as Wavefront OBJ. The bake floats a mesh with
/// more than 3/2 as many wetted triangles as `panels` (at the draft where
/// it displaces the mass) as a copy simplified to about `panels` of them
/// within 0.5 % of its extent; that copy is made here by the same rule,
/// and the volume it displaces at the rest pose, checked against the
/// model's, tells whether it is the hull baked (a warning when not).
fn write_hull(
    mesh: &Mesh,
    radiation: &RadiationModel,
    panels: usize,
    path: &std::path::Path,
) -> anyhow::Result<HullObj> {
    // Volume under the still water, m³, of `hull` with its centre of mass
    // `height` m above it.
    let displaced = |hull: &Mesh, height: f64| -> Result<f64, SeakeepingError> {
        match wetted_panels(hull, &rest_pose(radiation, height), 1e9) {
            Ok(panels) => Ok(panels.iter().map(|p| p.area * p.normal.y * p.centroid.y).sum()),
            Err(SeakeepingError::NoWettedSurface) => Ok(0.0),
            Err(e) => Err(e),
        }
    };
    // The mesh's own draft for the mass, by the bake's bisection.
    let target = radiation.mass() / radiation.density();
    let rotation = radiation.rotation();
    let com = rotation * radiation.center_of_mass().coords;
    let reach = mesh
        .positions
        .iter()
        .map(|p| (rotation * p.coords - com).norm())
        .fold(0.0f64, f64::max);
    let (mut low, mut high) = (-1.01 * reach, 1.01 * reach);
    for _ in 0..60 {
        let mid = 0.5 * (low + high);
        if displaced(mesh, mid)? > target {
            low = mid;
        } else {
            high = mid;
        }
    }
    let wetted = wetted_panels(mesh, &rest_pose(radiation, 0.5 * (low + high)), 1e9)
        .with_context(|| format!("the wetted surface of {}", mesh.name))?
        .len();
    let simplified = wetted > panels * 3 / 2;
    let hull = if simplified {
        let share = panels as f64 / wetted as f64;
        mesh.simplified_within(((mesh.triangles.len() as f64 * share) as usize).max(8), 0.005)
    } else {
        mesh.clone()
    };
    let h = radiation.hydrostatics();
    let volume = displaced(&hull, h.center_of_mass_height)
        .with_context(|| format!("the wetted surface of {}", mesh.name))?;
    if (volume - h.volume).abs() > 1e-6 * h.volume {
        eprintln!(
            "warning: the hull written to {} displaces {volume:.6} m³ at the rest pose, the model's \
             hull {:.6} m³: not the hull the radiation was baked on",
            path.display(),
            h.volume
        );
    }
    // Seams welded, only the vertices the triangles use, in their order.
    let pose = rest_pose(radiation, h.center_of_mass_height);
    let mut index = vec![u32::MAX; hull.positions.len()];
    let mut positions = Vec::new();
    let triangles = hull
        .welded_triangles()
        .into_iter()
        .map(|t| {
            t.map(|v| {
                let slot = &mut index[v as usize];
                if *slot == u32::MAX {
                    *slot = positions.len() as u32;
                    positions.push(pose * hull.positions[v as usize]);
                }
                *slot
            })
        })
        .collect();
    let placed = Mesh {
        name: format!(
            "{}{} at rest: y up, still water y = 0, centre of mass at x = z = 0 and y = {} m",
            mesh.name,
            if simplified {
                " (simplified for the bake)"
            } else {
                ""
            },
            h.center_of_mass_height
        ),
        positions,
        uvs: None,
        triangles,
        openings: Vec::new(),
        source: None,
    };
    std::fs::write(path, placed.to_obj()).with_context(|| format!("writing {}", path.display()))?;
    Ok(HullObj {
        path: path.to_path_buf(),
        vertices: placed.positions.len(),
        triangles: placed.triangles.len(),
        simplified,
        displaced: volume,
    })
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use nalgebra::{Point3, UnitQuaternion};

    use super::*;

    /// `source` solid at half the water's density, baked on about `panels`
    /// panels at 8 frequencies, as `soak seakeeping` bakes it.
    fn baked(source: &str, panels: usize) -> (Mesh, RadiationModel) {
        let mesh = common::mesh(source, false).expect("a builtin");
        let (atlas, _) = common::bake(&mesh, 32).expect("its atlas");
        let mass = MassModel::Solid { density: 500.0 }
            .mass_properties(&atlas)
            .expect("its mass");
        let radiation = RadiationModel::bake(
            &FloatingBody {
                mesh: &mesh,
                mass: mass.mass,
                center_of_mass: mass.center_of_mass,
                inertia: mass.inertia,
                rotation: UnitQuaternion::identity(),
            },
            &RadiationSettings {
                panels,
                frequencies: 8,
                ..RadiationSettings::default()
            },
        )
        .expect("its radiation");
        (mesh, radiation)
    }

    /// The OBJ at `path` read back: the volume it puts under y = 0 (m³)
    /// and the centroid of all it encloses (m).
    fn read_back(path: &Path) -> (f64, Point3<f64>) {
        let hull = soak_bake::load_mesh(path.to_str().expect("a UTF-8 path")).expect("reads the OBJ");
        let under: f64 = wetted_panels(&hull, &Isometry3::identity(), 1e9)
            .expect("its wetted part")
            .iter()
            .map(|p| p.area * p.normal.y * p.centroid.y)
            .sum();
        let (mut volume, mut moment) = (0.0, Vector3::zeros());
        for t in 0..hull.triangles.len() {
            let [a, b, c] = hull.triangle_points(t);
            let v = a.coords.dot(&b.coords.cross(&c.coords)) / 6.0;
            volume += v;
            moment += v * (a.coords + b.coords + c.coords) / 4.0;
        }
        (under, Point3::from(moment / volume))
    }

    #[test]
    fn the_hull_is_written_at_rest_as_it_was_baked() {
        let dir = std::env::temp_dir().join(format!("soak-seakeeping-hull-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch folder");
        let path = dir.join("hull.obj");
        // A cube of half the water's density turns some 57° to its rest and
        // is written as given (12 triangles); a fine sphere (4,000) is baked
        // on a simplified copy, and that copy is written.
        for (source, simplified) in [("builtin:box", false), ("builtin:sphere", true)] {
            let (mesh, radiation) = baked(source, 60);
            let hull = write_hull(&mesh, &radiation, 60, &path).expect("writes the OBJ");
            let h = radiation.hydrostatics();
            assert_eq!(hull.simplified, simplified, "{source}");
            let (under, centroid) = read_back(&path);
            // Counter-clockwise seen from outside, at rest: the volume the
            // model displaces (to the rounding of its finer panels, as
            // `write_hull` judges it), its centre of mass (the solid's
            // centroid) at x = z = 0, `center_of_mass_height` up.
            for volume in [hull.displaced, under] {
                assert!(
                    (volume / h.volume - 1.0).abs() < 1e-6,
                    "{source}: {volume} against {}",
                    h.volume
                );
            }
            let off = centroid - Point3::new(0.0, h.center_of_mass_height, 0.0);
            assert!(off.norm() < 0.01, "{source}: centroid {centroid}");
        }
        // A path that cannot be written: the error names it, no panic.
        let (mesh, radiation) = baked("builtin:box", 60);
        let missing = dir.join("missing").join("hull.obj");
        let Err(e) = write_hull(&mesh, &radiation, 60, &missing) else {
            panic!("wrote into a folder that does not exist");
        };
        assert!(format!("{e:#}").contains(&missing.display().to_string()), "{e:#}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
