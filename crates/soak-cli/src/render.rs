//! `soak render`: frames of a scene file, shaded with the wet-surface optics
//! of `soak-shade` on an offscreen wgpu renderer.
//!
//! The scene is simulated up to the requested step and drawn: every body's
//! mesh at its pose with its liquid texture (when the body is wet), the
//! water surface, the sun and the sky; debug views show the liquid in
//! pseudo-colour, the compartments of a body's liquid graph (each triangle
//! coloured by its nearest node, the graph's pipes drawn between nodes; each
//! triangle apart for a body without one), or the normals, and `--forces`
//! draws weight (red, at the centre of mass) and buoyancy (green, at the
//! centre of buoyancy) as in the thesis' Fig. 7.3.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use nalgebra::Point3;
use soak_rapier::Simulation;
use soak_rapier::scene::LoadedScene;
use soak_view::{FrameOptions, SceneRenderer};

/// What the frames show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum View {
    /// The shaded scene.
    #[default]
    Shaded,
    /// Liquid saturation in pseudo-colour (blue dry, red saturated).
    Liquid,
    /// Compartments of the liquid graph (nearest node per triangle) with its pipes; each triangle apart for a body without a graph.
    Segments,
    /// World-space normals as colours.
    Normals,
}

impl From<View> for soak_view::View {
    fn from(v: View) -> Self {
        match v {
            View::Shaded => Self::Shaded,
            View::Liquid => Self::Liquid,
            View::Segments => Self::Segments,
            View::Normals => Self::Normals,
        }
    }
}

/// `soak render SCENE.toml [--frame N] [--every K]`
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Step to render (0 is the initial state); default: the scene's last step.
    #[arg(long)]
    pub frame: Option<u64>,
    /// Also write every K-th step before `--frame` as a numbered sequence
    /// (`frame_000000.png`, ...).
    #[arg(long)]
    pub every: Option<u64>,
    /// Also encode the frames written as a video (H.264 in MP4, at the
    /// simulation's pace) with the `ffmpeg` found on the `PATH`; needs
    /// `--every`.
    #[arg(long, value_name = "OUT.mp4", requires = "every")]
    pub video: Option<PathBuf>,
    /// Image width, pixels.
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Image height, pixels.
    #[arg(long, default_value_t = 360)]
    pub height: u32,
    /// What the image shows.
    #[arg(long, value_enum, default_value_t = View::Shaded)]
    pub view: View,
    /// Draw weight and buoyancy as arrows.
    #[arg(long)]
    pub forces: bool,
    /// Camera position `x,y,z` in m (default: framing the bodies).
    #[arg(long, value_parser = parse_point)]
    pub eye: Option<Point3<f64>>,
    /// Point the camera looks at, `x,y,z` in m (default: the bodies' centre).
    #[arg(long, value_parser = parse_point)]
    pub target: Option<Point3<f64>>,
    /// Output directory.
    #[arg(long, default_value = "out/render")]
    pub out: PathBuf,
    /// Continue a render that was stopped: frames already in `--out` are
    /// kept, not rendered again (each frame is written whole or not at
    /// all, so one that is there is complete); the scene is still stepped
    /// from the start to reach the others.
    #[arg(long)]
    pub resume: bool,
}

fn parse_point(s: &str) -> Result<Point3<f64>, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("`{s}`: {e} (expected x,y,z in metres)"))?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(Point3::new(x, y, z)),
        _ => Err(format!("`{s}`: expected three finite numbers x,y,z in metres")),
    }
}

/// Encodes `frames` (PNG files of one size), each shown `seconds` long, as
/// H.264 in MP4 with the `ffmpeg` on the `PATH`.
fn encode_video(frames: &[PathBuf], seconds: f64, video: &Path) -> Result<()> {
    use std::fmt::Write as _;
    if frames.is_empty() {
        bail!("no frame to encode into {}", video.display());
    }
    // The concat demuxer's list: the frames written, each for its time.
    let mut list = String::from("ffconcat version 1.0\n");
    for f in frames {
        let name = std::fs::canonicalize(f).with_context(|| format!("cannot find {}", f.display()))?;
        let _ = writeln!(list, "file '{}'\nduration {seconds}", name.display());
    }
    // The last frame once more, so that its duration counts.
    let last = std::fs::canonicalize(&frames[frames.len() - 1])?;
    let _ = writeln!(list, "file '{}'", last.display());
    let list_path = video.with_extension("ffconcat");
    std::fs::write(&list_path, list).with_context(|| format!("cannot write {}", list_path.display()))?;
    let run = std::process::Command::new("ffmpeg")
        .args(["-y", "-loglevel", "error", "-f", "concat", "-safe", "0", "-i"])
        .arg(&list_path)
        .args([
            "-c:v",
            "libx264",
            "-pix_fmt",
            "yuv420p",
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
        ])
        .arg(video)
        .output();
    let _ = std::fs::remove_file(&list_path);
    match run {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => bail!(
            "--video needs ffmpeg, which is not on the PATH (Debian: `apt install ffmpeg`); \
             the {} frame(s) are written, and `ffmpeg -framerate {:.3} -pattern_type glob -i 'frame_*.png' {}` \
             encodes them once it is installed",
            frames.len(),
            1.0 / seconds,
            video.display()
        ),
        Err(e) => Err(e).context("running ffmpeg"),
        Ok(out) if !out.status.success() => bail!(
            "ffmpeg could not encode {}: {}",
            video.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        ),
        Ok(_) => Ok(()),
    }
}

fn frame_path(out: &Path, step: u64) -> PathBuf {
    out.join(format!("frame_{step:06}.png"))
}

/// `soak render`.
pub fn run(args: &Args) -> Result<()> {
    let loaded = LoadedScene::from_file(&args.scene)?;
    let mut sim = Simulation::from_scene(&loaded)?;
    let last = args.frame.unwrap_or_else(|| sim.total_steps());
    if args.every == Some(0) {
        bail!("--every must be at least 1 (steps between frames)");
    }
    if args.width == 0 || args.height == 0 || args.width > 8192 || args.height > 8192 {
        bail!("--width and --height must be within 1..=8192 pixels");
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let mut renderer = SceneRenderer::new(
        &loaded,
        FrameOptions {
            size: (args.width, args.height),
            view: args.view.into(),
            forces: args.forces,
            eye: args.eye,
            target: args.target,
        },
    )?;
    let (mut written, mut kept) = (0, 0);
    let mut frames = Vec::new();
    let mut render_time = 0.0;
    crate::interrupt::install();
    let mut progress = crate::progress::Progress::new(args.scene.display().to_string(), "steps", last);
    let mut reached = 0;
    for step in 0..=last {
        if crate::interrupt::requested() {
            break;
        }
        if step > 0 {
            sim.step()?;
        }
        reached = step;
        progress.set(step, || {
            format!("t = {:.2} s, {written} frame(s) written", sim.time())
        });
        let wanted = step == last || args.every.is_some_and(|k| step.is_multiple_of(k));
        let path = frame_path(&args.out, step);
        if wanted && args.resume && path.is_file() {
            frames.push(path);
            kept += 1;
        } else if wanted {
            let start = Instant::now();
            let image = renderer.frame(&sim)?;
            render_time += start.elapsed().as_secs_f64();
            soak_rapier::write_atomically(&path, |w| {
                image
                    .write_to(w, image::ImageFormat::Png)
                    .map_err(std::io::Error::other)
            })
            .with_context(|| format!("cannot write {}", path.display()))?;
            frames.push(path);
            written += 1;
        }
    }
    progress.finish();
    println!(
        "wrote {written} frame(s) of {}×{} to {}{} (last: step {reached}, t = {:.3} s); {:.0} ms per frame on {}",
        args.width,
        args.height,
        args.out.display(),
        if kept > 0 {
            format!(", kept {kept} already there")
        } else {
            String::new()
        },
        sim.time(),
        1e3 * render_time / f64::from(written.max(1)),
        renderer.adapter()
    );
    if let (Some(video), Some(every)) = (&args.video, args.every) {
        let seconds_per_frame = sim.dt() * every as f64;
        encode_video(&frames, seconds_per_frame, video)?;
        println!(
            "encoded {} frame(s) at {:.1} frames per second into {}",
            frames.len(),
            1.0 / seconds_per_frame,
            video.display()
        );
    }
    if reached < last {
        return Err(crate::interrupt::Interrupted {
            done: format!("at step {reached} of {last}: {written} frame(s) written"),
        }
        .into());
    }
    Ok(())
}
