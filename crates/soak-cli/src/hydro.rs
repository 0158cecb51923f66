//! `soak hydro MESH`: mass properties and hydrostatics at a pose, beside the
//! exact clipping reference, with the time each path takes.

use serde::Serialize;
use soak_hydro::reference::{self, ClipPlane};
use soak_hydro::{BodyState, HydroOptions, MassModel, TiledAtlas, Water, evaluate};
use soak_report::Gpu;

use crate::common::{self, arr, rows, time_ms, vec3};

/// Arguments of `soak hydro`.
#[derive(clap::Args)]
pub struct Args {
    /// A mesh file (.obj, .gltf, .glb) or a builtin name.
    mesh: String,
    /// Texture side in texels.
    #[arg(long, short, default_value_t = 512)]
    resolution: u32,
    /// Solid body of this density, kg/m³ (the default, 500).
    #[arg(long, conflicts_with = "shell")]
    density: Option<f64>,
    /// Thin shell of this areal density, kg/m², instead of a solid.
    #[arg(long)]
    shell: Option<f64>,
    /// Height of the (calm, fresh) water surface, m.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    water_level: f64,
    /// Position of the mesh origin, m: X,Y,Z (by default the body is
    /// placed with its centre of mass at the water level).
    #[arg(long, value_parser = common::triple, allow_hyphen_values = true)]
    position: Option<[f64; 3]>,
    /// Rotation, degrees about x, then y, then z: RX,RY,RZ.
    #[arg(long, value_parser = common::triple, default_value = "0,0,0", allow_hyphen_values = true)]
    rotation: [f64; 3],
    /// Replace the mesh's UVs with a generated physics atlas.
    #[arg(long)]
    unwrap: bool,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
    /// Where the texel sums run: `cpu` or `gpu` (wgpu; also times the GPU path).
    #[arg(long, value_enum, default_value = "cpu")]
    backend: HydroBackend,
}

/// Where `soak hydro` evaluates the texel sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum HydroBackend {
    /// rayon on the CPU.
    Cpu,
    /// wgpu compute.
    Gpu,
}

#[derive(Serialize)]
struct Props {
    /// m³
    volume: f64,
    /// kg
    mass: f64,
    /// object frame, m
    center_of_mass: [f64; 3],
    /// about the centre of mass, object axes, kg·m²
    inertia: [[f64; 3]; 3],
    /// m³
    submerged_volume: f64,
    /// world, m
    center_of_buoyancy: [f64; 3],
    /// world, N
    buoyancy_force: [f64; 3],
}

#[derive(Serialize)]
struct EvalMs {
    #[serde(skip_serializing_if = "Option::is_none")]
    gpu: Option<f64>,
    per_texel: f64,
    tiled: f64,
    exact: f64,
    per_triangle_baseline: f64,
}

#[derive(Serialize)]
struct Report {
    mesh: String,
    backend: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    adapter: Option<String>,
    resolution: u32,
    texels: usize,
    water_level: f64,
    /// How the body is made: `solid, 500 kg/m³` or `shell, 2 kg/m²`.
    mass_model: String,
    /// Position of the mesh origin, m.
    position: [f64; 3],
    /// Degrees about x, then y, then z.
    rotation_deg: [f64; 3],
    /// Whether the position was given (else the centre of mass is at the
    /// water level).
    position_given: bool,
    #[serde(flatten)]
    texel: Props,
    exact: Props,
    per_triangle_baseline_volume: f64,
    eval_ms: EvalMs,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let mesh = common::mesh(&args.mesh, args.unwrap)?;
    let (atlas, _) = common::bake(&mesh, args.resolution)?;
    let (model, exact_mass) = match args.shell {
        Some(sigma) => {
            let e = reference::shell_mass_properties(&mesh, sigma);
            (
                MassModel::Shell { areal_density: sigma },
                (e.mass, e.centroid, e.inertia),
            )
        }
        None => {
            let rho = args.density.unwrap_or(500.0);
            let e = reference::solid_mass_properties(&mesh, rho);
            (MassModel::Solid { density: rho }, (e.mass, e.centroid, e.inertia))
        }
    };
    let mass = model.mass_properties(&atlas)?;
    // Without a position the centre of mass goes to the water level
    // (x = z = 0): a pose with something under water and something above.
    let position = args.position.unwrap_or_else(|| {
        let c = common::pose([0.0; 3], args.rotation) * mass.center_of_mass;
        [-c.x, args.water_level - c.y, -c.z]
    });
    let pose = common::pose(position, args.rotation);
    let state = BodyState::at_rest(pose);
    let water = Water::calm(args.water_level);
    let opts = HydroOptions::default();
    let mut f = evaluate(&atlas, &water, &state, &mass, 0.0, &opts)?;
    let (mut gpu_ms, mut adapter) = (None, None);
    let mut texel_mass = mass;
    if args.backend == HydroBackend::Gpu {
        let mut gpu = Gpu::new().map_err(|e| anyhow::anyhow!("--backend gpu: {e}"))?;
        let (g, ms) = gpu.evaluate_timed(&atlas, &water, &state, &mass, &opts, 7)?;
        texel_mass = gpu.mass_properties(&atlas, &model)?;
        f = g;
        gpu_ms = Some(ms);
        adapter = Some(gpu.label);
    }
    let plane = ClipPlane::horizontal(args.water_level);
    let sub = reference::submerged_part(&mesh, &pose, &plane);
    let base = reference::per_triangle_buoyancy(&mesh, &pose, &plane, water.density, water.gravity);
    let tiled = TiledAtlas::new(&atlas);
    let runs = 7;
    let eval_ms = EvalMs {
        gpu: gpu_ms,
        per_texel: time_ms(runs, || evaluate(&atlas, &water, &state, &mass, 0.0, &opts)),
        tiled: time_ms(runs, || tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts)),
        exact: time_ms(runs, || reference::submerged_part(&mesh, &pose, &plane)),
        per_triangle_baseline: time_ms(runs, || {
            reference::per_triangle_buoyancy(&mesh, &pose, &plane, water.density, water.gravity)
        }),
    };
    let report = Report {
        mesh: mesh.name.clone(),
        backend: match args.backend {
            HydroBackend::Cpu => "cpu",
            HydroBackend::Gpu => "gpu",
        },
        adapter,
        resolution: args.resolution,
        texels: atlas.len(),
        water_level: args.water_level,
        mass_model: match model {
            MassModel::Shell { areal_density } => format!("shell, {areal_density} kg/m²"),
            MassModel::Solid { density } => format!("solid, {density} kg/m³"),
            _ => format!("{model:?}"),
        },
        position,
        rotation_deg: args.rotation,
        position_given: args.position.is_some(),
        texel: Props {
            volume: atlas.volume(),
            mass: texel_mass.mass,
            center_of_mass: arr(&texel_mass.center_of_mass),
            inertia: rows(&texel_mass.inertia),
            submerged_volume: f.submerged_volume,
            center_of_buoyancy: arr(&f.center_of_buoyancy),
            buoyancy_force: vec3(&f.buoyancy.force),
        },
        exact: Props {
            volume: mesh.volume(),
            mass: exact_mass.0,
            center_of_mass: arr(&exact_mass.1),
            inertia: rows(&exact_mass.2),
            submerged_volume: sub.volume,
            center_of_buoyancy: arr(&sub.centroid),
            buoyancy_force: vec3(&sub.buoyancy_force(&plane, water.density, water.gravity)),
        },
        per_triangle_baseline_volume: base.volume,
        eval_ms,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    let (t, e) = (&report.texel, &report.exact);
    println!(
        "{} at {}² ({} texels), {}, water at y = {} m",
        report.mesh, report.resolution, report.texels, report.mass_model, report.water_level
    );
    let [x, y, z] = report.position;
    let [rx, ry, rz] = report.rotation_deg;
    println!(
        "origin at ({x:.4}, {y:.4}, {z:.4}) m, turned ({rx}, {ry}, {rz})°{}",
        if report.position_given {
            ""
        } else {
            " (no --position: the centre of mass at the water level)"
        }
    );
    if let Some(a) = &report.adapter {
        println!("texel sums on the GPU: {a}");
    }
    println!("{:<24}{:>16}{:>16}{:>12}", "", "texels", "exact", "error");
    // Errors relative to the exact value, or to a scale for positions.
    let scaled = |name: &str, a: f64, b: f64, scale: f64| {
        println!("{name:<24}{a:>16.6}{b:>16.6}{:>12.2e}", (a - b).abs() / scale);
    };
    let row = |name: &str, a: f64, b: f64| scaled(name, a, b, b.abs().max(f64::MIN_POSITIVE));
    let diameter = mesh.diagonal();
    row("volume (m³)", t.volume, e.volume);
    row("mass (kg)", t.mass, e.mass);
    for k in 0..3 {
        let name = format!("centre of mass {} (m)", ["x", "y", "z"][k]);
        scaled(&name, t.center_of_mass[k], e.center_of_mass[k], diameter);
    }
    for k in 0..3 {
        row(
            &format!("inertia {0}{0} (kg·m²)", ["x", "y", "z"][k]),
            t.inertia[k][k],
            e.inertia[k][k],
        );
    }
    if e.submerged_volume > 0.0 {
        row("submerged volume (m³)", t.submerged_volume, e.submerged_volume);
        for k in 0..3 {
            let name = format!("buoyancy centre {} (m)", ["x", "y", "z"][k]);
            scaled(&name, t.center_of_buoyancy[k], e.center_of_buoyancy[k], diameter);
        }
        row("buoyancy force y (N)", t.buoyancy_force[1], e.buoyancy_force[1]);
    } else {
        println!(
            "nothing is under water at this pose (texel sums: {:.3e} m³); no buoyancy to compare",
            t.submerged_volume
        );
    }
    println!("(positions: error as a fraction of the bounding-box diagonal; others: relative)");
    println!(
        "per-triangle baseline volume {:.6} m³",
        report.per_triangle_baseline_volume
    );
    let m = &report.eval_ms;
    let gpu = m.gpu.map(|g| format!("GPU {g:.3} ms, ")).unwrap_or_default();
    println!(
        "time per evaluation: {gpu}per-texel {:.3} ms, tiled {:.3} ms, exact clipping {:.3} ms, per-triangle {:.3} ms",
        m.per_texel, m.tiled, m.exact, m.per_triangle_baseline
    );
    Ok(())
}
