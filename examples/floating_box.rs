//! A wooden crate dropped into calm water settles at its draft.
//!
//! `cargo run --release --example floating_box`

use rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::hydro::{Drag, MassModel, Water};
use soak::rapier::{BodyDesc, Effects, ForceGenerator};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    let crate_body = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));

    // 1 m × 0.6 m × 0.8 m of pine (500 kg/m³): it should float with 0.3 m under water.
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(128))?;
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    soak.register(
        &mut world.bodies,
        &world.colliders,
        crate_body,
        BodyDesc {
            name: "crate".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density: 500.0 },
            effects: Effects::buoyancy().with_drag(Drag {
                coefficient: 1.0,
                linear: 200.0,
            }),
        },
    )?;

    for step in 0..=1200 {
        soak.step(&mut world)?;
        if step % 120 == 0 {
            let y = world.bodies[crate_body].translation().y;
            println!(
                "t = {:>4.1} s   bottom at {:>6.3} m   draft {:.3} m",
                soak.time(),
                y - 0.3,
                0.3 - y
            );
        }
    }
    Ok(())
}
