//! `soak simulate SCENE.toml`: run a scene headless.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::Context;
use serde::{Deserialize, Serialize};
use soak_rapier::scene::{DEFAULT_TOLERANCE, ResolutionSpec};
use soak_rapier::{
    Backend, LoadedScene, Sample, SampleCsv, SavedSimulation, Simulation, read_checkpoint, write_atomically,
    write_checkpoint,
};

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
    /// Write the time series (pose, forces, submerged volume, mass) as CSV,
    /// row by row as the run makes them (flushed to the file at least once
    /// a second, and at every checkpoint): a run killed at any moment
    /// keeps what it had written.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Write the run as an animated glTF binary (`.glb`): each body a node
    /// with its mesh, its poses sampled at the scene's output rate
    /// (`output.every` steps), for Blender or any glTF viewer.
    #[arg(long, value_name = "FILE.glb")]
    gltf: Option<PathBuf>,
    /// Override the scene's duration: seconds, or `forever` (run until
    /// stopped, with Ctrl-C or a signal; see `--checkpoint`).
    #[arg(long, value_parser = parse_duration)]
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
    /// Save the run to FILE every `--checkpoint-every` seconds of simulated
    /// time, when stopped by Ctrl-C and at the end, each time whole or not
    /// at all (the previous checkpoint stays until the new one is
    /// complete): `--resume FILE` continues it.
    #[arg(long, value_name = "FILE")]
    checkpoint: Option<PathBuf>,
    /// Simulated seconds between checkpoints (rounded to whole steps, at
    /// least one): the same steps whatever the machine's speed, so that a
    /// resumed run is the uninterrupted one.
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0, requires = "checkpoint")]
    checkpoint_every: f64,
    /// Continue the run a checkpoint saved: the same scene file (unchanged)
    /// and the same options must be given again; the CSV is cut back to
    /// the checkpoint's rows and continued, so it ends as the uninterrupted
    /// run's. A checkpoint of another scene or options, of another state
    /// format, truncated or corrupted is refused before anything runs.
    #[arg(long, value_name = "FILE")]
    resume: Option<PathBuf>,
}

/// `--duration`: a positive number of seconds or `forever`.
fn parse_duration(s: &str) -> Result<f64, String> {
    if s.trim() == "forever" {
        return Ok(f64::INFINITY);
    }
    match s.trim().parse::<f64>() {
        Ok(d) if d.is_finite() && d > 0.0 => Ok(d),
        _ => Err(format!("`{s}` is not a positive number of seconds nor `forever`")),
    }
}

/// The longest run `soak simulate` starts without being told it may run
/// forever: seven days of wall time, estimated from the first steps.
const LONGEST: Duration = Duration::from_secs(7 * 86_400);

/// What shapes a run and its outputs: checked against a checkpoint's on
/// resuming, so that a run is never continued under other options.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct RunOptions {
    duration: Option<f64>,
    backend: Option<String>,
    csv: Option<PathBuf>,
    gltf: Option<PathBuf>,
    liquid_png_every: Option<usize>,
    out: PathBuf,
    checkpoint_every: f64,
}

impl RunOptions {
    fn of(args: &Args) -> Self {
        Self {
            duration: args.duration,
            backend: args.backend.map(|b| format!("{b:?}").to_lowercase()),
            csv: args.csv.clone(),
            gltf: args.gltf.clone(),
            liquid_png_every: args.liquid_png_every,
            out: args.out.clone(),
            checkpoint_every: args.checkpoint_every,
        }
    }

    /// The first option given otherwise than when `saved` was written.
    fn differs_from(&self, saved: &RunOptions) -> Option<String> {
        fn show<T: std::fmt::Debug>(v: &Option<T>) -> String {
            v.as_ref()
                .map_or_else(|| "not given".to_string(), |v| format!("{v:?}"))
        }
        let pairs: [(&str, String, String); 7] = [
            ("--duration", show(&saved.duration), show(&self.duration)),
            ("--backend", show(&saved.backend), show(&self.backend)),
            ("--csv", show(&saved.csv), show(&self.csv)),
            ("--gltf", show(&saved.gltf), show(&self.gltf)),
            (
                "--liquid-png-every",
                show(&saved.liquid_png_every),
                show(&self.liquid_png_every),
            ),
            ("--out", show(&Some(&saved.out)), show(&Some(&self.out))),
            (
                "--checkpoint-every",
                show(&Some(saved.checkpoint_every)),
                show(&Some(self.checkpoint_every)),
            ),
        ];
        pairs
            .into_iter()
            .find(|(_, a, b)| a != b)
            .map(|(flag, a, b)| format!("{flag} was {a} when the checkpoint was written, {b} now"))
    }
}

/// What a `soak simulate` checkpoint holds: the run, the options it was
/// started with and how far its outputs had got.
#[derive(Serialize, Deserialize)]
struct RunCheckpoint {
    /// The options.
    options: RunOptions,
    /// The run.
    saved: SavedSimulation,
    /// Bytes of the CSV written (and on disk) at the checkpoint.
    csv_bytes: Option<u64>,
    /// The samples recorded so far, kept for the glTF (empty without it).
    samples: Vec<Sample>,
    /// Liquid PNGs written so far.
    pngs: usize,
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
    let begun = Instant::now();
    let options = RunOptions::of(args);
    let checkpoint: Option<RunCheckpoint> = match &args.resume {
        Some(path) => Some(read_checkpoint(path)?),
        None => None,
    };
    let mut loaded = LoadedScene::from_file(&args.scene)?;
    if let Some(d) = args.duration {
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
    anyhow::ensure!(
        args.checkpoint_every.is_finite() && args.checkpoint_every > 0.0,
        "--checkpoint-every must be a positive number of seconds"
    );
    let png_every = args.liquid_png_every.or(loaded.scene.output.liquid_png_every);
    // The glTF needs every sample at the end; the CSV takes them as they come.
    let keep_samples = args.gltf.is_some();
    let (mut sim, mut csv, mut pngs) = match &checkpoint {
        Some(c) => {
            let path = args.resume.as_deref().unwrap_or(Path::new(""));
            if let Some(difference) = options.differs_from(&c.options) {
                anyhow::bail!(
                    "checkpoint {} is of another run: {difference}; give the options it was written with",
                    path.display()
                );
            }
            let mut sim = Simulation::resume_scene(&loaded, &c.saved)
                .with_context(|| format!("resuming checkpoint {}", path.display()))?;
            if args.csv.is_some() || keep_samples {
                sim.resume_recording(c.samples.clone());
            }
            let csv = match (&args.csv, c.csv_bytes) {
                (Some(p), Some(bytes)) => Some(
                    SampleCsv::resume(p, bytes)
                        .with_context(|| format!("continuing the CSV {}", p.display()))?,
                ),
                _ => None,
            };
            eprintln!(
                "resuming {} at t = {:.3} s (step {})",
                args.scene.display(),
                sim.time(),
                sim.steps_taken()
            );
            (sim, csv, c.pngs)
        }
        None => {
            let mut sim = Simulation::from_scene(&loaded)?;
            sim.record(args.csv.is_some() || keep_samples);
            let csv = match args.csv.as_deref() {
                Some(p) => {
                    Some(SampleCsv::create(p).with_context(|| format!("cannot write {}", p.display()))?)
                }
                None => None,
            };
            (sim, csv, 0)
        }
    };
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
    if png_every.is_some() && checkpoint.is_none() {
        pngs += sim.write_liquid_pngs(&args.out)?.len();
    }
    let forever = loaded.scene.duration.is_infinite();
    let total = sim.total_steps();
    anyhow::ensure!(
        forever || loaded.scene.duration / sim.dt() < 9.0e15,
        "{}: duration = {} s is {:e} steps of {} s, more than can be counted; shorten `duration` (line {}) or pass --duration, or set duration = \"forever\" to run until stopped",
        args.scene.display(),
        crate::progress::seconds(loaded.scene.duration),
        loaded.scene.duration / sim.dt(),
        sim.dt(),
        loaded.line_of("duration")
    );
    let every = (args.checkpoint_every / sim.dt()).round().max(1.0) as u64;
    let duration = if forever {
        "forever".to_string()
    } else {
        crate::progress::seconds(loaded.scene.duration)
    };
    let first = sim.steps_taken();
    crate::interrupt::install();
    let mut progress = Progress::new(
        args.scene.display().to_string(),
        "steps",
        if forever {
            u64::MAX
        } else {
            total - first.min(total)
        },
    );
    let (mut judged, mut timing) = (forever, None::<(Instant, u64)>);
    // The samples already in the CSV: a resumed run's (kept for the glTF);
    // none of a new run's (its first, at t = 0, is written with the
    // first step's).
    let mut cursor = if keep_samples && checkpoint.is_some() {
        sim.samples().len()
    } else {
        0
    };
    let mut steps = first;
    let set_up = begun.elapsed();
    // The time in the steps alone (not in writing what they give).
    let mut stepping = Duration::ZERO;
    while steps < total {
        if crate::interrupt::requested() {
            break;
        }
        let before = Instant::now();
        sim.step()?;
        stepping += before.elapsed();
        steps += 1;
        let k = steps;
        // Refuse, from its first steps, a run that cannot end in any
        // reasonable time (unless it was asked to run forever): the rate
        // of the steps after the first (which pays for what is set up
        // lazily), over 64 steps or a second.
        if !judged {
            match timing {
                None => timing = Some((Instant::now(), k)),
                Some((since, k0)) => {
                    let spent = since.elapsed().as_secs_f64();
                    let n = k - k0;
                    if spent >= 1.0 || n >= 64 {
                        judged = true;
                        let per_step = spent / n as f64;
                        if per_step * (total - k) as f64 > LONGEST.as_secs_f64() {
                            progress.finish();
                            anyhow::bail!(
                                "{}: duration = {} s is {total} steps of {} s; at {:.2} ms a step (measured on its first steps here) that is {}; shorten `duration` (line {}) or pass --duration, or set duration = \"forever\" (or --duration forever) to run until stopped",
                                args.scene.display(),
                                crate::progress::seconds(loaded.scene.duration),
                                sim.dt(),
                                1e3 * per_step,
                                crate::progress::time_left(spent, n, total - k + n).replace(" left", ""),
                                loaded.line_of("duration"),
                            );
                        }
                    }
                }
            }
        }
        if let Some(csv) = &mut csv {
            let samples = sim.samples();
            if samples.len() > cursor {
                csv.rows(&sim, &samples[cursor..])
                    .with_context(|| format!("writing {}", csv.path().display()))?;
            }
            if keep_samples {
                cursor = sim.samples().len();
            } else {
                sim.take_samples();
            }
        }
        progress.set(k - first, || {
            if forever {
                format!("t = {:.2} s", sim.time())
            } else {
                format!("t = {:.2} s of {duration} s", sim.time())
            }
        });
        if let Some(n) = png_every
            && k % n as u64 == 0
        {
            pngs += sim.write_liquid_pngs(&args.out)?.len();
        }
        if let Some(path) = &args.checkpoint
            && k % every == 0
            && k < total
        {
            save(path, &loaded, &sim, &options, &mut csv, keep_samples, pngs)?;
        }
    }
    progress.finish();
    if steps > first {
        eprintln!(
            "{}: set up in {:.2} s; {} steps in {:.2} s ({:.3} ms a step)",
            args.scene.display(),
            set_up.as_secs_f64(),
            steps - first,
            stepping.as_secs_f64(),
            1e3 * stepping.as_secs_f64() / (steps - first) as f64
        );
    }
    if let Some(csv) = &mut csv {
        sync(csv)?;
    }
    let last_checkpoint = match &args.checkpoint {
        Some(path) => Some(save(path, &loaded, &sim, &options, &mut csv, keep_samples, pngs)?),
        None => None,
    };
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
        if let (Some(path), Some((bytes, seconds))) = (&args.checkpoint, last_checkpoint) {
            println!(
                "checkpoint in {} ({:.1} kB, written in {:.1} ms)",
                path.display(),
                bytes as f64 / 1e3,
                1e3 * seconds
            );
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
                "at t = {:.3} s{}; the results above are of that time",
                sim.time(),
                if forever {
                    format!(" ({steps} steps)")
                } else {
                    format!(" of {duration} s ({steps} of {total} steps)")
                }
            ),
        }
        .into());
    }
    Ok(())
}

/// The CSV on disk; its bytes.
fn sync(csv: &mut SampleCsv) -> anyhow::Result<u64> {
    csv.sync()
        .with_context(|| format!("writing {}", csv.path().display()))
}

/// Writes a checkpoint of the run now: the CSV synced to disk first, so
/// that the checkpoint never counts rows the file does not hold.
fn save(
    path: &Path,
    loaded: &LoadedScene,
    sim: &Simulation,
    options: &RunOptions,
    csv: &mut Option<SampleCsv>,
    keep_samples: bool,
    pngs: usize,
) -> anyhow::Result<(u64, f64)> {
    let start = Instant::now();
    let csv_bytes = csv.as_mut().map(sync).transpose()?;
    let checkpoint = RunCheckpoint {
        options: options.clone(),
        saved: sim.save(loaded)?,
        csv_bytes,
        samples: if keep_samples {
            sim.samples().to_vec()
        } else {
            Vec::new()
        },
        pngs,
    };
    let bytes = write_checkpoint(path, &checkpoint)?;
    Ok((bytes, start.elapsed().as_secs_f64()))
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
    let mut failure = None;
    write_atomically(path, |w| {
        run.write_glb(w).map_err(|e| {
            let message = e.to_string();
            failure = Some(e);
            std::io::Error::other(message)
        })
    })
    .map_err(|e| match failure {
        Some(e) => anyhow::Error::from(e),
        None => anyhow::Error::from(e),
    })
    .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}
