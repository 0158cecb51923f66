//! Runs a scene file (default: `data/scenes/three_boxes.toml`) and prints
//! where every body ended: the same as `soak simulate`, from code.
//!
//! `cargo run --release --example scene_file -- data/scenes/buoy_on_waves.toml`

use soak::rapier::{LoadedScene, Simulation};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "data/scenes/three_boxes.toml".into());
    let scene = LoadedScene::from_file(path.as_ref())?;
    let mut sim = Simulation::from_scene(&scene)?;
    sim.run(|_| {})?;
    for body in sim.report() {
        println!(
            "{:<10} at ({:.3}, {:.3}, {:.3}) m, {:.1} % submerged",
            body.name,
            body.position[0],
            body.position[1],
            body.position[2],
            100.0 * body.submerged_fraction
        );
    }
    Ok(())
}
