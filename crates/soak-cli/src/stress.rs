//! `soak stress`: the stability matrix ([`soak_report::stress`]), run and
//! printed as a table, Markdown or JSON; the exit status says whether every
//! cell passed.

use std::time::Instant;

use anyhow::bail;
use soak_hydro::BuoyancyMode;
use soak_report::stress::{self, StressOptions, markdown_table, text_table};

/// Run the stability matrix and print a table of its cells.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The reduced matrix for CI: every mesh, water and effect, each with
    /// one of the extreme densities, scales and time steps.
    #[arg(long)]
    pub quick: bool,
    /// Print the table as Markdown (one row per mesh, water and effects,
    /// summing its cells; failing cells listed below).
    #[arg(long, conflicts_with = "json")]
    pub markdown: bool,
    /// Print every cell as JSON.
    #[arg(long)]
    pub json: bool,
    /// Only the cells whose name contains this text (e.g. `torus/sea`).
    #[arg(long)]
    pub only: Option<String>,
    /// Atlas resolution, texels per side [default: 32].
    #[arg(long)]
    pub resolution: Option<u32>,
    /// Most steps per cell [default: 150 with --quick, 300 otherwise].
    #[arg(long)]
    pub max_steps: Option<usize>,
    /// Cells run at once [default: the number of cores].
    #[arg(long)]
    pub threads: Option<usize>,
    /// Buoyancy mode of every cell: `archimedes` (ρ g V_s, vertical, at the
    /// centre of buoyancy) or `pressure` (the sum of each submerged texel's
    /// pressure force and its moment).
    #[arg(long, value_enum, default_value_t = ModeArg::Archimedes)]
    pub buoyancy: ModeArg,
}

/// `--buoyancy`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeArg {
    /// `BuoyancyMode::Archimedes`.
    Archimedes,
    /// `BuoyancyMode::Pressure`.
    Pressure,
}

impl ModeArg {
    fn mode(self) -> BuoyancyMode {
        match self {
            ModeArg::Archimedes => BuoyancyMode::Archimedes,
            ModeArg::Pressure => BuoyancyMode::Pressure,
        }
    }
}

/// Runs `soak stress`.
pub fn run(args: &Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let cells = stress::select(args.quick, args.only.as_deref())?;
    let defaults = StressOptions::default();
    let options = StressOptions {
        resolution: args.resolution.unwrap_or(defaults.resolution),
        max_steps: args
            .max_steps
            .unwrap_or(if args.quick { 150 } else { defaults.max_steps }),
        threads: args.threads.unwrap_or(defaults.threads).max(1),
        mode: args.buoyancy.mode(),
    };
    crate::interrupt::install();
    let progress = std::sync::Mutex::new(crate::progress::Progress::new(
        "soak stress",
        "cells",
        cells.len() as u64,
    ));
    let outcomes = stress::run_with(
        &cells,
        &options,
        &stress::Control {
            stop: &crate::interrupt::requested,
            done: &|done, _| {
                if let Ok(mut p) = progress.lock() {
                    p.set(done as u64, || {
                        format!("{:.0} s in", start.elapsed().as_secs_f64())
                    });
                }
            },
        },
    )?;
    if let Ok(p) = progress.into_inner() {
        p.finish();
    }
    let seconds = start.elapsed().as_secs_f64();

    if args.json {
        println!("{}", serde_json::to_string_pretty(&outcomes)?);
    } else if args.markdown {
        print!(
            "{}",
            markdown_table(
                &outcomes,
                args.quick,
                options.resolution,
                options.max_steps,
                seconds
            )
        );
    } else {
        print!(
            "{}",
            text_table(&outcomes, options.resolution, options.max_steps, seconds)
        );
    }

    let failing: Vec<&stress::Outcome> = outcomes.iter().filter(|o| !o.pass).collect();
    if !failing.is_empty() {
        eprintln!("{} of {} cells failed:", failing.len(), outcomes.len());
        for o in &failing {
            eprintln!("  {}: {}", o.cell, o.failures.join("; "));
        }
        bail!("{} of {} stress cells failed", failing.len(), outcomes.len());
    }
    if outcomes.len() < cells.len() {
        return Err(crate::interrupt::Interrupted {
            done: format!(
                "after {} of {} cells (all of them passed; the table above is theirs)",
                outcomes.len(),
                cells.len()
            ),
        }
        .into());
    }
    Ok(())
}
