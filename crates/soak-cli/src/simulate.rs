//! `soak simulate SCENE.toml`: run a scene headless.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context;
use soak_rapier::scene::{DEFAULT_TOLERANCE, ResolutionSpec};
use soak_rapier::{Backend, LoadedScene, Sample, Simulation};

use crate::interrupt::Interrupted;
use crate::progress::Progress;

/// Arguments of `soak simulate`.
#[derive(clap::Args)]
pub struct Args {
    /// The scene file (TOML).
    scene: PathBuf,
    /// Print the final state of every body as JSON.
    #[arg(long)]
    json: bool,
    /// Write the time series (pose, forces, submerged volume, mass) as CSV.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Write the run as an animated glTF binary (`.glb`): each body a node
    /// with its mesh, its poses sampled at the scene's output rate
    /// (`output.every` steps), for Blender or any glTF viewer.
    #[arg(long, value_name = "FILE.glb")]
    gltf: Option<PathBuf>,
    /// Override the scene's duration, s.
    #[arg(long)]
    duration: Option<f64>,
    /// Override the scene's backend: `cpu` (tiled), `per-texel` or `gpu`.
    #[arg(long, value_enum)]
    backend: Option<SimBackend>,
    /// Write each wet body's liquid texture as a pseudo-colour PNG (dark
    /// blue dry to dark red saturated) at the start and every N steps
    /// (overrides the scene's `output.liquid_png_every`).
    #[arg(long, value_name = "N")]
    liquid_png_every: Option<usize>,
    /// Directory for the liquid PNGs (`BODY_liquid_STEP.png`).
    #[arg(long, default_value = "out/simulate")]
    out: PathBuf,
}

/// Where `soak simulate` evaluates the texel sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SimBackend {
    /// The CPU, tiled for planar water.
    Cpu,
    /// The CPU, every texel.
    PerTexel,
    /// The GPU, all bodies in one batch per step.
    Gpu,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let mut loaded = LoadedScene::from_file(&args.scene)?;
    if let Some(d) = args.duration {
        anyhow::ensure!(
            d.is_finite() && d > 0.0,
            "--duration must be a positive number of seconds"
        );
        loaded.scene.duration = d;
    }
    if let Some(b) = args.backend {
        loaded.scene.backend = match b {
            SimBackend::Cpu => Backend::Tiled,
            SimBackend::PerTexel => Backend::PerTexel,
            SimBackend::Gpu => Backend::Gpu,
        };
    }
    if let Some(n) = args.liquid_png_every {
        anyhow::ensure!(n >= 1, "--liquid-png-every must be at least 1");
    }
    let png_every = args.liquid_png_every.or(loaded.scene.output.liquid_png_every);
    let mut sim = Simulation::from_scene(&loaded)?;
    sim.record(args.csv.is_some() || args.gltf.is_some());
    // Say which side `resolution = "auto"` chose for each body that asked.
    for (spec, body) in loaded.scene.bodies.iter().zip(&sim.bodies) {
        if matches!(spec.resolution, ResolutionSpec::Auto(_)) {
            eprintln!(
                "{}: atlas {}² chosen for a tolerance of {:.1e} of its volume",
                body.name,
                body.resolution,
                spec.tolerance.unwrap_or(DEFAULT_TOLERANCE)
            );
        }
    }
    let mut pngs = 0;
    if png_every.is_some() {
        pngs += sim.write_liquid_pngs(&args.out)?.len();
    }
    let total = sim.total_steps();
    let duration = crate::progress::seconds(loaded.scene.duration);
    crate::interrupt::install();
    let mut progress = Progress::new(args.scene.display().to_string(), "steps", total);
    let mut steps = 0;
    for k in 1..=total {
        if crate::interrupt::requested() {
            break;
        }
        sim.step()?;
        steps = k;
        progress.set(k, || format!("t = {:.2} s of {duration} s", sim.time()));
        if let Some(n) = png_every
            && k % n as u64 == 0
        {
            pngs += sim.write_liquid_pngs(&args.out)?.len();
        }
    }
    progress.finish();
    if let Some(path) = &args.csv {
        write_csv(path, &sim)?;
    }
    if let Some(path) = &args.gltf {
        write_gltf(path, &loaded, &sim)?;
    }
    let report = sim.report();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        println!(
            "{} after {:.2} s ({} steps):",
            args.scene.display(),
            sim.time(),
            steps
        );
        for r in &report {
            println!(
                "  {:<16} at ({:>8.3}, {:>8.3}, {:>8.3}) m, tilt ({:>7.2}, {:>7.2}, {:>7.2})°, {:>5.1} % submerged, {:.2} kg{}{}{}",
                r.name,
                r.position[0],
                r.position[1],
                r.position[2],
                r.euler_deg[0],
                r.euler_deg[1],
                r.euler_deg[2],
                100.0 * r.submerged_fraction,
                r.mass,
                r.liquid_inside
                    .map(|l| format!(", {l:.3} m³ of water inside"))
                    .unwrap_or_default(),
                r.surface_liquid
                    .map(|l| format!(", {:.3} L soaked into the surface", 1e3 * l))
                    .unwrap_or_default(),
                if r.non_finite { "  NON-FINITE" } else { "" }
            );
        }
        if let Some(path) = &args.csv {
            println!("time series in {}", path.display());
        }
        if let Some(path) = &args.gltf {
            println!("animated glTF in {}", path.display());
        }
        if pngs > 0 {
            println!("{pngs} liquid textures in {}", args.out.display());
        }
    }
    if sim.soak.firewall().count() > 0 {
        eprintln!(
            "warning: {} non-finite or absurd quantities were kept from Rapier",
            sim.soak.firewall().count()
        );
    }
    if steps < total {
        return Err(Interrupted {
            done: format!(
                "at t = {:.3} s of {duration} s ({steps} of {total} steps); the results above are of that time",
                sim.time()
            ),
        }
        .into());
    }
    Ok(())
}

/// Writes the recorded samples as an animated glTF binary, the bodies drawn
/// with their scene meshes, wet ones coloured by the liquid in them at the
/// end.
fn write_gltf(path: &std::path::Path, loaded: &LoadedScene, sim: &Simulation) -> anyhow::Result<()> {
    let meshes = (0..sim.bodies.len())
        .map(|i| loaded.body_mesh(i))
        .collect::<Result<Vec<_>, _>>()?;
    let names: Vec<String> = sim.bodies.iter().map(|b| b.name.clone()).collect();
    let mut run = soak_rapier::export::Recording::from_samples(&names, meshes, sim.samples())?;
    // Wet bodies carry the liquid soaked into them at the end, per vertex.
    for (i, b) in sim.bodies.iter().enumerate() {
        let Some(sb) = b.id.and_then(|id| sim.soak.body(id)) else {
            continue;
        };
        if let Some(w) = sb.wetting() {
            let fill = soak_rapier::export::vertex_fill(sb.atlas(), w.liquid(), w.material().saturation);
            run.set_liquid(i, fill)?;
        }
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let file = std::fs::File::create(path).with_context(|| format!("cannot write {}", path.display()))?;
    run.write_glb(std::io::BufWriter::new(file))
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// Writes recorded samples as CSV, one row per body and time.
pub fn write_csv(path: &std::path::Path, sim: &Simulation) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let file = std::fs::File::create(path).with_context(|| format!("cannot write {}", path.display()))?;
    let mut w = std::io::BufWriter::new(file);
    writeln!(
        w,
        "t_s,body,x_m,y_m,z_m,qx,qy,qz,qw,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,\
         buoyancy_x_n,buoyancy_y_n,buoyancy_z_n,drag_x_n,drag_y_n,drag_z_n,submerged_volume_m3,mass_kg,liquid_inside_m3,\
         surface_liquid_m3"
    )?;
    for s in sim.samples() {
        write_row(&mut w, &sim.bodies[s.body].name, s)?;
    }
    w.flush()?;
    Ok(())
}

fn write_row(w: &mut impl Write, name: &str, s: &Sample) -> std::io::Result<()> {
    let f = |v: &[f64]| v.iter().map(|x| format!("{x:.6}")).collect::<Vec<_>>().join(",");
    writeln!(
        w,
        "{:.5},{},{},{},{},{},{},{},{:.6},{:.4},{:.6},{:.9}",
        s.t,
        name,
        f(&s.position),
        f(&s.rotation),
        f(&s.linear_velocity),
        f(&s.angular_velocity),
        f(&s.buoyancy),
        f(&s.drag),
        s.submerged_volume,
        s.mass,
        s.liquid_inside,
        s.surface_liquid
    )
}
