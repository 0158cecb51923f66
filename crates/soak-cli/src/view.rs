//! `soak view SCENE.toml`: a scene live in a window (`soak_view::run`).

use std::path::PathBuf;

use anyhow::{Context, Result, bail};

use crate::render::View;

/// The scenes `soak view demo:NAME` shows, as shipped with `soak`.
const DEMO_SCENES: [(&str, &str); 5] = [
    ("buoy_on_waves", include_str!("../scenes/buoy_on_waves.toml")),
    ("rain_and_splash", include_str!("../scenes/rain_and_splash.toml")),
    ("sinking_boat", include_str!("../scenes/sinking_boat.toml")),
    ("three_boxes", include_str!("../scenes/three_boxes.toml")),
    ("wet_crate", include_str!("../scenes/wet_crate.toml")),
];

/// `soak view SCENE.toml`
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML), reloaded when saved; or `demo:NAME` for a scene
    /// shipped with soak (`demo:sinking_boat`, `demo:buoy_on_waves`,
    /// `demo:wet_crate`, `demo:three_boxes`, `demo:rain_and_splash`).
    pub scene: String,
    /// Window width, pixels.
    #[arg(long, default_value_t = 960)]
    pub width: u32,
    /// Window height, pixels.
    #[arg(long, default_value_t = 540)]
    pub height: u32,
    /// What the frames show at first (keys 1–4 change it).
    #[arg(long, value_enum, default_value_t = View::Shaded)]
    pub view: View,
    /// Draw weight and buoyancy as arrows (key F).
    #[arg(long)]
    pub forces: bool,
    /// Start paused (Space plays).
    #[arg(long)]
    pub paused: bool,
    /// Simulated seconds per second of wall clock (keys + and -).
    #[arg(long, default_value_t = 1.0)]
    pub time_scale: f64,
    /// Hide the overlay (key H).
    #[arg(long)]
    pub no_overlay: bool,
    /// Advance this many steps before the window opens, then pause: the
    /// frame `soak render --frame N` draws.
    #[arg(long)]
    pub steps: Option<u64>,
    /// Close after this many frames (tests, recordings).
    #[arg(long)]
    pub frames: Option<u64>,
    /// Close after this many seconds of wall clock.
    #[arg(long)]
    pub seconds: Option<f64>,
    /// Write the last frame presented, read back from the window, as a PNG.
    #[arg(long, value_name = "PNG")]
    pub screenshot: Option<PathBuf>,
    /// Write the bodies' time series as CSV, the columns of `soak simulate
    /// --csv` (a row per body every `output.every` steps, handed to the
    /// file at least once a second), from the moment the window opens; a
    /// restart or a reload starts the time column again in the same file.
    #[arg(long, value_name = "CSV")]
    pub csv: Option<PathBuf>,
}

/// `soak view`.
pub fn run(args: &Args) -> Result<()> {
    if !(args.time_scale.is_finite() && args.time_scale > 0.0) {
        bail!("--time-scale must be a positive number, not {}", args.time_scale);
    }
    if args.seconds.is_some_and(|s| !(s.is_finite() && s > 0.0)) {
        bail!("--seconds must be a positive number");
    }
    if args.width == 0 || args.height == 0 || args.width > 8192 || args.height > 8192 {
        bail!("--width and --height must be within 1..=8192 pixels");
    }
    let (path, _temporary) = match args.scene.strip_prefix("demo:") {
        Some(name) => {
            let Some((_, text)) = DEMO_SCENES.iter().find(|(n, _)| *n == name) else {
                let names: Vec<&str> = DEMO_SCENES.iter().map(|(n, _)| *n).collect();
                bail!("no demo scene `{name}`; there are {}", names.join(", "));
            };
            // Written out so that it can be read (and edited, and reloaded),
            // beside the liquid graph the sinking boat names.
            let dir = std::env::temp_dir().join(format!("soak-view-{}", std::process::id()));
            let path = dir.join("scenes").join(format!("{name}.toml"));
            let graph = dir.join("graphs").join("boat.toml");
            for (file, text) in [(&path, *text), (&graph, include_str!("../graphs/boat.toml"))] {
                let parent = file.parent().unwrap_or(&dir);
                std::fs::create_dir_all(parent)
                    .with_context(|| format!("cannot create {}", parent.display()))?;
                std::fs::write(file, text).with_context(|| format!("cannot write {}", file.display()))?;
            }
            println!(
                "demo scene `{name}` written to {} (edit it: the view reloads)",
                path.display()
            );
            (path, Some(TempDir(dir)))
        }
        None => (PathBuf::from(&args.scene), None),
    };
    let options = soak_view::ViewOptions {
        size: (args.width, args.height),
        view: args.view.into(),
        forces: args.forces,
        play: !args.paused,
        time_scale: args.time_scale,
        overlay: !args.no_overlay,
        watch: true,
        steps: args.steps,
        frames: args.frames,
        seconds: args.seconds,
        screenshot: args.screenshot.clone(),
        csv: args.csv.clone(),
    };
    let report = soak_view::run(&path, options)?;
    println!(
        "{} frame(s) on {}: {:.0} ms each (at most {:.0}); input to frame {:.0} ms (at most {:.0}); \
         steps {:.1} ms, {:.2} simulated seconds per second; t = {:.2} s; {} reload(s), {} refused",
        report.frames,
        report.adapter,
        report.frame_ms[0],
        report.frame_ms[1],
        report.input_to_frame_ms[0],
        report.input_to_frame_ms[1],
        report.step_ms,
        report.speed,
        report.time,
        report.reloads[0],
        report.reloads[1],
    );
    if let Some(name) = &report.selected {
        println!("selected: {name}");
    }
    for reason in &report.refused {
        println!("reload refused: {reason}");
    }
    if let Some(shot) = &args.screenshot {
        println!("wrote {}", shot.display());
    }
    Ok(())
}

/// A temporary folder removed when dropped.
struct TempDir(PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
