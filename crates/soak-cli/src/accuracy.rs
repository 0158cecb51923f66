//! `soak accuracy`: what each digit of accuracy costs in time (the thesis'
//! Fig. 7.10 reproduced); the measurement is `soak_report::accuracy`.

use std::path::PathBuf;

use soak_report::Gpu;
use soak_report::accuracy::{compute, markdown, text_table};

/// Arguments of `soak accuracy`.
#[derive(clap::Args)]
pub struct Args {
    /// Fewer resolutions (32²–256²), water levels and timing runs: seconds, for tests.
    #[arg(long)]
    pub quick: bool,
    /// Folder for the PNG plots.
    #[arg(long, default_value = "out/accuracy")]
    pub out: PathBuf,
    /// Print one JSON document (every row and sweep) instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also write the table as markdown (for the README) to this file.
    #[arg(long)]
    pub markdown: Option<PathBuf>,
    /// Also time the GPU path (wgpu; labelled with the adapter's name).
    #[arg(long)]
    pub gpu: bool,
}

/// `soak accuracy`.
pub fn run(args: &Args) -> anyhow::Result<()> {
    let mut device = match args.gpu {
        true => Some(Gpu::new().map_err(|e| anyhow::anyhow!("--gpu: {e}"))?),
        false => None,
    };
    let mut report = compute(args.quick, &args.out, device.as_mut())?;
    report.adapter = device.map(|d| d.label);
    let mut files = report.files.clone();
    if let Some(path) = &args.markdown {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(path, markdown(&report, path))?;
        files.push(path.clone());
    }
    if args.json {
        let mut report = report;
        report.files = files;
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    print!("{}", text_table(&report));
    for f in &files {
        println!("wrote {}", f.display());
    }
    Ok(())
}
