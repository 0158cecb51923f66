//! `soak demo`: the demo's cases ([`soak_report::demo::CASES`]) from an
//! embedded scene, with plots and CSV written to an output folder, and the
//! rendered stills.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use soak_report::demo::{CASES, Case};

/// Arguments of `soak demo`.
#[derive(clap::Args)]
pub struct Args {
    /// Folder for the plots and CSV files.
    #[arg(long, default_value = "out/demo")]
    out: PathBuf,
    /// Shorter runs (for a quick look or a smoke test).
    #[arg(long)]
    quick: bool,
    /// Skip the rendered stills (buoy, sinking boat, wet beach, stain).
    #[arg(long)]
    no_stills: bool,
    /// Only the rendered stills, not the plotted cases.
    #[arg(long, conflicts_with = "no_stills")]
    stills_only: bool,
    /// Only the plotted case of this name (buoy, top_heavy_ball,
    /// moving_mass, balloon, sinking_boats, passing_boat).
    #[arg(long)]
    only: Option<String>,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let start = Instant::now();
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let s = if args.quick { 0.25 } else { 1.0 };
    if let Some(only) = &args.only
        && !CASES.iter().any(|c| c.0 == only)
    {
        anyhow::bail!("no demo case named `{only}`");
    }
    let chosen = |name: &str| args.only.as_deref().is_none_or(|only| only == name);
    let cases: Vec<(&str, Case, f64)> = CASES
        .into_iter()
        .filter(|c| !args.stills_only && chosen(c.0))
        .collect();
    for (name, case, seconds) in cases {
        let t0 = Instant::now();
        let line = case(seconds * s, &args.out).with_context(|| format!("demo case `{name}`"))?;
        println!("{line}  ({:.1} s)", t0.elapsed().as_secs_f64());
    }
    if !args.no_stills {
        for line in crate::stills::render_stills(&args.out, args.quick).context("rendering the stills")? {
            println!("{line}");
        }
    }
    println!(
        "plots, CSV and stills in {} ({:.1} s in all)",
        args.out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
