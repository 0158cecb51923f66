//! A ballasted buoy riding a Gerstner sea (thesis Fig. 7.2/7.3): buoyancy in
//! pressure mode, so the wave slope pushes it sideways too.
//!
//! `cargo run --release --example buoy_on_waves`

use nalgebra::Point3;
use rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::hydro::{BuoyancyMode, Drag, Gerstner, GerstnerWave, MassModel, MassProperties, Water};
use soak::rapier::{BodyDesc, Effects, ForceGenerator};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let sea = Gerstner::new(
        0.0,
        vec![
            GerstnerWave {
                amplitude: 0.3,
                wavelength: 12.0,
                direction_deg: 0.0,
                steepness: 0.6,
                phase: 0.0,
            },
            GerstnerWave {
                amplitude: 0.08,
                wavelength: 5.0,
                direction_deg: 30.0,
                steepness: 0.5,
                phase: 1.3,
            },
        ],
        9.81,
    )?;
    let mut world = PhysicsWorld::new();
    let buoy = world.bodies.insert(RigidBodyBuilder::dynamic());
    let atlas = Atlas::bake(&builtin::capsule(0.3, 0.6, 32), BakeOptions::square(128))?;
    let mut soak = ForceGenerator::new(Water::new(sea));
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        buoy,
        BodyDesc {
            name: "buoy".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density: 150.0 },
            effects: Effects::buoyancy()
                .with_mode(BuoyancyMode::Pressure)
                .with_drag(Drag {
                    coefficient: 0.8,
                    linear: 60.0,
                }),
        },
    )?;
    // 75 kg of ballast low in the hull keeps it upright.
    let ballast = MassProperties::point(75.0, Point3::new(0.0, -0.55, 0.0));
    soak.set_extra_mass(id, Some(ballast), &mut world.bodies, &world.colliders)?;

    for step in 0..=1200 {
        soak.step(&mut world)?;
        if step % 60 == 0 {
            let p = world.bodies[buoy].translation();
            let sea_y = soak.water().surface.height(p.x as f64, p.z as f64, soak.time());
            let f = soak.body(id).expect("registered").forces();
            println!(
                "t = {:>5.2} s   buoy y {:>6.3} m   sea {:>6.3} m   drift x {:>6.3} m   buoyancy {:>7.1} N",
                soak.time(),
                p.y,
                sea_y,
                p.x,
                f.buoyancy.force.y
            );
        }
    }
    Ok(())
}
