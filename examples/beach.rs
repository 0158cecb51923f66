//! A beach (thesis Fig. 7.11): swell runs up a sandy slope on an ebbing
//! tide, wetting the sand, a rock in the surf and a wooden crate on the
//! upper beach; diffusion carries the wet beyond the water's reach and into
//! the crate where it stands on wet sand, and the sand dries behind the
//! retreating water. All three bodies share one voxel field.
//!
//! Writes the liquid textures in pseudo-colour (blue dry → red saturated,
//! as the thesis' Fig. 7.14) every N steps to `out/beach/`: `sand_*.png`
//! (the top of the slab fills the upper 60 % of the texture like a map, x
//! to the right, z down, the sea on the right), `rock_*.png`, `crate_*.png`.
//! Time-lapse: the liquid evaporates 1000× faster than water.
//!
//! `cargo run --release --example beach [-- STEPS [EVERY]]` (default 1200
//! steps of 0.1 s, a frame every 100).

use std::path::Path;
use std::time::Instant;

use soak::wet::scenes::{Beach, BeachOptions};
use soak::wet::write_liquid_png;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let steps: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(1200);
    let every: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(100).max(1);
    let out = Path::new("out/beach");
    std::fs::create_dir_all(out)?;

    let built = Instant::now();
    let mut beach = Beach::new(BeachOptions::default())?;
    println!(
        "beach: {} sand texels, {} rock, {} crate; field {:?} voxels of {} m; built in {:.1} s",
        beach.bodies[0].atlas.len(),
        beach.bodies[1].atlas.len(),
        beach.bodies[2].atlas.len(),
        beach.field.grid().dims,
        beach.field.grid().voxel_size,
        built.elapsed().as_secs_f64()
    );
    println!(
        "{:>6} {:>7} {:>10} {:>10} {:>10} {:>10} {:>10} {:>9}",
        "step", "time s", "tide m", "sand m³", "wet m²", "rock m³", "crate m³", "ms/step"
    );
    let frame = |beach: &Beach, step: usize, ms: f64| -> Result<(), Box<dyn std::error::Error>> {
        for b in &beach.bodies {
            let path = out.join(format!("{}_{step:05}.png", b.name));
            write_liquid_png(
                &b.atlas,
                b.wetting.liquid(),
                b.wetting.material().saturation,
                &path,
            )?;
        }
        let stats: Vec<_> = beach
            .bodies
            .iter()
            .map(|b| b.wetting.stats(&b.atlas))
            .collect::<Result<_, _>>()?;
        let tide = 0.25 * (std::f64::consts::TAU * beach.time / 120.0).cos();
        println!(
            "{step:>6} {:>7.1} {tide:>10.3} {:>10.4} {:>10.1} {:>10.2e} {:>10.2e} {ms:>9.1}",
            beach.time, stats[0].total, stats[0].wet_area, stats[1].total, stats[2].total
        );
        Ok(())
    };
    frame(&beach, 0, 0.0)?;
    let mut clock = Instant::now();
    for step in 1..=steps {
        beach.step()?;
        if step % every == 0 {
            let ms = clock.elapsed().as_secs_f64() * 1e3 / every as f64;
            frame(&beach, step, ms)?;
            clock = Instant::now();
        }
    }
    println!("frames in {}", out.display());
    Ok(())
}
