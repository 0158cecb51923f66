//! A balloon inflating while it rises through air (thesis Fig. 7.9): its mesh
//! deforms every step and the atlas follows from its barycentrics, no re-bake.
//!
//! `cargo run --release --example balloon`

use nalgebra::Point3;
use rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::hydro::{Drag, MassModel, Water, volume_moments};
use soak::rapier::{BodyDesc, Effects, ForceGenerator};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    let balloon = world.bodies.insert(RigidBodyBuilder::dynamic());
    let mesh = builtin::sphere(1.0, 48, 24);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let fabric_kg = 3.0;
    let mut soak = ForceGenerator::new(Water::air());
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        balloon,
        BodyDesc {
            name: "balloon".into(),
            mass_model: MassModel::Shell {
                areal_density: fabric_kg / atlas.area(),
            },
            atlas: atlas.into(),
            effects: Effects::buoyancy().with_drag(Drag {
                coefficient: 0.5,
                linear: 0.0,
            }),
        },
    )?;
    for step in 0..=1200 {
        // Inflate from 1 m to 2.5 m radius over the first 12 s.
        let r = 1.0 + 1.5 * (soak.time() / 12.0).min(1.0);
        let inflated: Vec<Point3<f64>> = mesh
            .positions
            .iter()
            .map(|p| Point3::from(p.coords * r))
            .collect();
        soak.deform(id, &inflated, &mut world.bodies, &world.colliders)?;
        // The fabric stretches (its mass stays); the helium inside weighs 0.17 kg/m³.
        let body = soak.body(id).expect("registered");
        let (area, helium) = (body.atlas().area(), volume_moments(body.atlas()).solid(0.17));
        soak.set_mass_model(
            id,
            MassModel::Shell {
                areal_density: fabric_kg / area,
            },
            &mut world.bodies,
            &world.colliders,
        )?;
        soak.set_extra_mass(id, Some(helium), &mut world.bodies, &world.colliders)?;
        soak.step(&mut world)?;
        if step % 120 == 0 {
            let f = soak.body(id).expect("registered").forces();
            println!(
                "t = {:>4.1} s   radius {r:.2} m   altitude {:>7.2} m   volume {:>6.2} m³   lift {:>6.1} N   weight {:>6.1} N",
                soak.time(),
                world.bodies[balloon].translation().y,
                f.submerged_volume,
                f.buoyancy.force.y,
                world.bodies[balloon].mass() * 9.81
            );
        }
    }
    Ok(())
}
