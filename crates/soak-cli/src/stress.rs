//! `soak stress`: the stability matrix ([`soak_report::stress`]), run and
//! printed as a table, Markdown or JSON; the exit status says whether every
//! cell passed.

use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

use anyhow::{Context, bail};
use serde::{Deserialize, Serialize};
use soak_hydro::BuoyancyMode;
use soak_report::stress::{self, Outcome, StressOptions, markdown_table, text_table};

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
    /// Write each cell's outcome to FILE (one JSON line per cell, flushed
    /// as each cell finishes): a run killed at any moment keeps every cell
    /// it finished, and `--resume` takes it up from there.
    #[arg(long, value_name = "FILE")]
    pub journal: Option<PathBuf>,
    /// Run only the cells the journal does not hold yet (the same matrix
    /// and options must be given again) and print the table of all of
    /// them.
    #[arg(long, requires = "journal")]
    pub resume: bool,
}

/// What shapes the matrix's cells: the journal's first line, checked on
/// resuming.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
struct JournalHead {
    soak_stress_journal: u32,
    quick: bool,
    only: Option<String>,
    resolution: u32,
    max_steps: usize,
    buoyancy: String,
}

/// The outcomes a journal holds, after checking its head against `head`.
/// A last line cut short by a kill is dropped (its cell runs again).
fn read_journal(path: &Path, head: &JournalHead) -> anyhow::Result<Vec<Outcome>> {
    let file =
        std::fs::File::open(path).with_context(|| format!("cannot read the journal {}", path.display()))?;
    let lines: Vec<String> = std::io::BufReader::new(file)
        .lines()
        .collect::<Result<_, _>>()
        .with_context(|| format!("reading the journal {}", path.display()))?;
    let Some(first) = lines.first() else {
        bail!(
            "the journal {} is empty: start the matrix again without --resume",
            path.display()
        );
    };
    let saved: JournalHead = serde_json::from_str(first).with_context(|| {
        format!(
            "{} is not a journal of `soak stress` (its first line)",
            path.display()
        )
    })?;
    if &saved != head {
        bail!(
            "the journal {} is of another matrix or options ({saved:?}); give those again, or start anew without --resume",
            path.display()
        );
    }
    let mut outcomes = Vec::new();
    for (n, line) in lines.iter().enumerate().skip(1) {
        match serde_json::from_str::<Outcome>(line) {
            Ok(o) => outcomes.push(o),
            Err(_) if n + 1 == lines.len() => {}
            Err(e) => bail!("the journal {}, line {}: {e}", path.display(), n + 1),
        }
    }
    Ok(outcomes)
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
    let all = stress::select(args.quick, args.only.as_deref())?;
    let defaults = StressOptions::default();
    let options = StressOptions {
        resolution: args.resolution.unwrap_or(defaults.resolution),
        max_steps: args
            .max_steps
            .unwrap_or(if args.quick { 150 } else { defaults.max_steps }),
        threads: args.threads.unwrap_or(defaults.threads).max(1),
        mode: args.buoyancy.mode(),
    };
    let head = JournalHead {
        soak_stress_journal: 1,
        quick: args.quick,
        only: args.only.clone(),
        resolution: options.resolution,
        max_steps: options.max_steps,
        buoyancy: format!("{:?}", args.buoyancy).to_lowercase(),
    };
    // The cells a journal already holds are not run again.
    let done_before = match (&args.journal, args.resume) {
        (Some(path), true) => read_journal(path, &head)?,
        _ => Vec::new(),
    };
    let journal = match &args.journal {
        Some(path) => {
            let mut file = if args.resume {
                std::fs::OpenOptions::new().append(true).open(path)
            } else {
                std::fs::File::create(path)
            }
            .with_context(|| format!("cannot write the journal {}", path.display()))?;
            if args.resume {
                // A line cut short by a kill is cut off: its cell runs again.
                let whole = std::fs::read(path)?;
                let keep = whole.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
                file.set_len(keep as u64)?;
            } else {
                writeln!(file, "{}", serde_json::to_string(&head)?)?;
            }
            Some(Mutex::new(file))
        }
        None => None,
    };
    let cells: Vec<stress::Cell> = all
        .iter()
        .filter(|c| !done_before.iter().any(|o| o.cell == c.name()))
        .cloned()
        .collect();
    if !done_before.is_empty() {
        eprintln!(
            "resuming: {} of {} cells are in the journal, {} to run",
            all.len() - cells.len(),
            all.len(),
            cells.len()
        );
    }
    crate::interrupt::install();
    let progress = Mutex::new(crate::progress::Progress::new(
        "soak stress",
        "cells",
        cells.len() as u64,
    ));
    let write_error: Mutex<Option<std::io::Error>> = Mutex::new(None);
    let ran = stress::run_with(
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
            finished: &|outcome| {
                let Some(journal) = &journal else { return };
                let Ok(line) = serde_json::to_string(outcome) else {
                    return;
                };
                if let Ok(mut file) = journal.lock()
                    && let Err(e) = writeln!(file, "{line}").and_then(|()| file.flush())
                    && let Ok(mut slot) = write_error.lock()
                {
                    slot.get_or_insert(e);
                }
            },
        },
    )?;
    if let Ok(p) = progress.into_inner() {
        p.finish();
    }
    if let Some(e) = write_error.into_inner().ok().flatten() {
        return Err(anyhow::Error::from(e).context("writing the journal"));
    }
    // Every cell's outcome, in the matrix's order.
    let mut outcomes: Vec<Outcome> = Vec::with_capacity(all.len());
    for c in &all {
        let name = c.name();
        if let Some(o) = done_before.iter().chain(&ran).find(|o| o.cell == name) {
            outcomes.push(o.clone());
        }
    }
    let cells = all;
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
