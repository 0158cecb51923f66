//! A rowing boat — an open hull, no deck — floats on the air in it, carries
//! a load, is holed below the waterline and swamps.
//!
//! ```text
//! cargo run --release --example open_boat
//! ```
//!
//! The mesh `builtin:open_boat` is a single surface with one rim along the
//! gunwale; `cap_openings` closes the rim with a cap whose texels are the
//! boat's opening. The atlas bakes the closed shape (what displaces water
//! while none comes aboard), the walls carry the mass (`MassModel::Walls`:
//! 2.5 cm of density 600), and `Flooding::open_container` makes the
//! boat's inside a liquid graph whose caps let water in over the gunwale.
//! Five seconds in, a hole 24 cm across is opened in the bottom at a world
//! point (`open_hole_at`): water comes in through it at the orifice rate,
//! the boat settles until the gunwale meets the water, swamps over it and,
//! its walls and rowers outweighing the water its walls displace, sinks.

use rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, builtin, cap_openings};
use soak::graph::{Flooding, FlowOptions};
use soak::hydro::{Drag, MassModel, MassProperties, Water};
use soak::rapier::{BodyDesc, Effects, ForceGenerator, convert};

fn main() -> soak::Result<()> {
    let mesh = cap_openings(&builtin::open_boat(4.0, 1.2, 0.6))?;
    let rim = &mesh.openings[0];
    println!(
        "rim: {} vertices, {:.2} m long, cap {:.2} m² at y = {:.2} m",
        rim.rim.len(),
        rim.length,
        rim.area,
        rim.centroid[1]
    );
    let atlas = Atlas::bake(&mesh, BakeOptions::square(256))?;
    let (density, thickness) = (600.0, 0.025);
    let flooding = Flooding::open_container(&atlas, atlas.wall_area() * thickness, FlowOptions::default())?;

    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -0.1, 0.0)));
    let mut water = ForceGenerator::new(Water::calm(0.0));
    let id = water.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "rowing boat".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Walls { density, thickness },
            effects: Effects::buoyancy()
                .with_drag(Drag {
                    coefficient: 1.0,
                    linear: 40.0,
                })
                .with_flooding(flooding),
        },
    )?;
    // Two rowers, 150 kg, on the floor amidships.
    let load = MassProperties::point(150.0, nalgebra::Point3::new(0.0, 0.1, 0.0));
    water.set_ballast(id, Some(load), &mut world.bodies, &world.colliders)?;

    println!("   t (s)  freeboard (m)  water inside (m³)");
    for step in 1..=60 * 40 {
        water.step(&mut world)?;
        if step == 60 * 5 {
            // Under the keel amidships, where the boat is now.
            let pose = convert::pose(world.bodies[handle].position());
            let keel = pose * nalgebra::Point3::new(0.0, 0.0, 0.0);
            let texels = water.open_hole_at(id, &world.bodies, keel, 0.12)?;
            println!("   holed below the waterline: {texels} texels open");
        }
        if step % 300 == 0 {
            let pose = convert::pose(world.bodies[handle].position());
            let freeboard = rim
                .rim
                .iter()
                .map(|&v| (pose * mesh.positions[v as usize]).y)
                .fold(f64::INFINITY, f64::min);
            let inside = water.flooding(id).map_or(0.0, |f| f.inside());
            println!("{:>8.1}  {freeboard:>13.3}  {inside:>17.3}", water.time());
        }
    }
    Ok(())
}
