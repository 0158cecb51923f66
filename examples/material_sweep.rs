//! The thesis' Fig. 6.3 for several materials and liquids: dry, partly wet,
//! damp and saturated spheres, rendered with the wet-shading renderer.
//! Writes `out/material_sweep.png`.
//!
//! `cargo run --release --features render --example material_sweep`

use soak::shade::render::{MaterialSweep, adapter_label, headless_device, material_sweep};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("out");
    std::fs::create_dir_all(&out)?;
    let mut sweep = MaterialSweep::thesis_fig_6_3();
    // Labels, if the CLI's font is there.
    let font_path = root.join("crates/soak-cli/assets/DejaVuSans.ttf");
    if let Ok(bytes) = std::fs::read(&font_path) {
        sweep.font = Some(ab_glyph_font(bytes)?);
    }
    let (device, queue, info) = headless_device()?;
    let image = material_sweep(&device, &queue, &sweep)?;
    let path = out.join("material_sweep.png");
    image.save(&path)?;
    println!(
        "wrote {} ({}×{}) on {}",
        path.display(),
        image.width(),
        image.height(),
        adapter_label(&info)
    );
    Ok(())
}

fn ab_glyph_font(bytes: Vec<u8>) -> Result<soak::shade::render::Font, Box<dyn std::error::Error>> {
    Ok(soak::shade::render::Font::try_from_vec(bytes)?)
}
