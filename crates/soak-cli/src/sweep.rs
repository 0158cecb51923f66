//! `soak sweep`: the thesis' Fig. 6.3 — dry, partly wet, damp and saturated
//! spheres for several materials and liquids — rendered with the same wet
//! shading as the scenes, as one labelled PNG.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use soak_shade::render::{Font, MaterialSweep, adapter_label, headless_device, material_sweep};

/// `soak sweep [--cell N] [--out FILE]`
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Side of one sphere's cell, pixels.
    #[arg(long, default_value_t = 160)]
    pub cell: u32,
    /// Where to write the image (PNG).
    #[arg(long, default_value = "out/material_sweep.png")]
    pub out: PathBuf,
}

/// `soak sweep`.
pub fn run(args: &Args) -> Result<()> {
    if !(16..=1024).contains(&args.cell) {
        bail!("--cell must be within 16..=1024 pixels (got {})", args.cell);
    }
    let mut sweep = MaterialSweep::thesis_fig_6_3();
    sweep.cell = args.cell;
    sweep.font = Some(Font::try_from_slice(soak_report::chart::FONT).context("the embedded font")?);
    let (device, queue, info) = headless_device().context("no GPU adapter for rendering")?;
    let start = Instant::now();
    let image = material_sweep(&device, &queue, &sweep)?;
    let ms = 1e3 * start.elapsed().as_secs_f64();
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    image
        .save(&args.out)
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    println!(
        "wrote {} ({}×{}: {} materials × {} wetness states) in {ms:.0} ms on {}",
        args.out.display(),
        image.width(),
        image.height(),
        sweep.rows.len(),
        sweep.columns.len(),
        adapter_label(&info)
    );
    for row in &sweep.rows {
        println!("  {}", row.label);
    }
    Ok(())
}
