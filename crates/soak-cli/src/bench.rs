//! `soak bench`: the step time of a Rapier world against the number of
//! floating bodies ([`soak_report::scaling`]), printed as a table,
//! Markdown or JSON, and plotted as PNG.

use std::path::PathBuf;

use soak_report::scaling::{self, ScalingOptions, markdown_table, phases_table, text_table, write_figure};

/// Arguments of `soak bench`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Up to 1,000 bodies and a few steps per case: seconds, for tests.
    #[arg(long)]
    pub quick: bool,
    /// Print the table as Markdown (for the README).
    #[arg(long, conflicts_with = "json")]
    pub markdown: bool,
    /// Print every measurement as JSON.
    #[arg(long)]
    pub json: bool,
    /// Folder for the plot (`scaling.png`).
    #[arg(long, default_value = "out/bench")]
    pub out: PathBuf,
    /// Body counts instead of the default ones (e.g. `--sizes 1,10,100`).
    #[arg(long, value_delimiter = ',')]
    pub sizes: Option<Vec<usize>>,
    /// Most timed steps per case [default: 200, 10 with --quick].
    #[arg(long)]
    pub max_steps: Option<usize>,
    /// Seconds of timed steps per case, once the fewest are done
    /// [default: 2, 0.2 with --quick].
    #[arg(long)]
    pub budget: Option<f64>,
    /// Also run the generator's columns on the GPU (skipped with a note
    /// when there is no adapter).
    #[arg(long)]
    pub gpu: bool,
    /// Largest body count run on the GPU.
    #[arg(long, default_value_t = 1_000)]
    pub gpu_max_bodies: usize,
    /// The waters measured, of `calm`, `swell` and `jonswap` (e.g.
    /// `--water calm,jonswap`) [default: all three].
    #[arg(long, value_delimiter = ',', value_parser = parse_water)]
    pub water: Option<Vec<scaling::WaterKind>>,
    /// Build every column's world of a size first and step them in turn,
    /// one step each per round, so that the ratios between columns are of
    /// one moment on a machine whose speed drifts (the budget is then the
    /// size's whole, and the memory counts every world of the size)
    #[arg(long)]
    pub interleave: bool,
    /// Sum the drag columns' drag over each atlas coarsened by this
    /// factor (K × K texels merged into one drag texel) rather than over
    /// its own texels
    #[arg(long, value_name = "K")]
    pub drag_coarsening: Option<u32>,
    /// How the bodies read the seas: `auto` (each body as it is against
    /// the waves: one plane over a body at most an eighth of the shortest
    /// wave across, the sea sampled over any other), `plane` (one plane
    /// fitted over each body, the sea's velocity at its centre), `exact`
    /// (every texel), or a number of nodes per shortest wave (the sea
    /// sampled over each body) [default: auto; the GPU's JONSWAP exactly]
    #[arg(long, value_name = "READ", value_parser = parse_sea)]
    pub sea_sampling: Option<soak_hydro::SeaSampling>,
    /// Also print where the generator's step goes: each phase of its step
    /// (predicting the poses, preparing, evaluating, handing over, the
    /// wrenches to Rapier), the mean over the timed steps, per case
    #[arg(long, conflicts_with = "json")]
    pub phases: bool,
}

/// A water of the bench by its label.
fn parse_water(label: &str) -> Result<scaling::WaterKind, String> {
    scaling::WaterKind::from_label(label)
        .ok_or_else(|| format!("no water `{label}` in the bench (calm, swell or jonswap)"))
}

/// How the bench's bodies read the seas, from `auto`, `plane`, `exact`
/// or a number of nodes per shortest wave.
fn parse_sea(read: &str) -> Result<soak_hydro::SeaSampling, String> {
    match read {
        "auto" => Ok(soak_hydro::SeaSampling::Auto),
        "plane" => Ok(soak_hydro::SeaSampling::Plane),
        "exact" => Ok(soak_hydro::SeaSampling::Exact),
        n => match n.parse::<f64>() {
            Ok(n) if n.is_finite() && n > 0.0 => Ok(soak_hydro::SeaSampling::PerWavelength(n)),
            _ => Err(format!(
                "no sea read `{read}` (auto, plane, exact, or a positive number of nodes per shortest wave)"
            )),
        },
    }
}

/// Runs `soak bench`.
pub fn run(args: &Args) -> anyhow::Result<()> {
    let mut options = if args.quick {
        ScalingOptions::quick()
    } else {
        ScalingOptions::full()
    };
    if let Some(sizes) = &args.sizes {
        options.sizes = sizes.clone();
    }
    if let Some(m) = args.max_steps {
        options.max_steps = m;
        options.min_steps = options.min_steps.min(m);
    }
    if let Some(b) = args.budget {
        options.budget_s = b;
    }
    if let Some(waters) = &args.water {
        options.waters = waters.clone();
    }
    options.gpu = args.gpu;
    options.gpu_max_bodies = args.gpu_max_bodies;
    options.interleave = args.interleave;
    options.drag_coarsening = args.drag_coarsening;
    options.sea_sampling = args.sea_sampling;
    let report = scaling::run(&options, |m| {
        eprintln!(
            "{:>6} bodies, {:<34} {:>10} per step ({} steps, setup {})",
            m.case.bodies,
            m.case.column.label(),
            scaling::format_ms(m.median_ms),
            m.steps,
            scaling::format_ms(m.setup_ms)
        );
    })?;
    // The table first: a run of minutes is not lost to a plot that cannot be written.
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else if args.markdown {
        print!("{}", markdown_table(&report));
    } else {
        print!("{}", text_table(&report));
    }
    if args.phases {
        print!("{}", phases_table(&report));
    }
    let figure = write_figure(&report, &args.out)?;
    eprintln!("wrote {}", figure.display());
    Ok(())
}
