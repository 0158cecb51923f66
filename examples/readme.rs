//! A boat of solid pine floats on calm water; after 10 s it prints its draft.

use rapier3d::prelude::*;
use soak::prelude::*;

fn main() -> soak::Result<()> {
    let mut world = PhysicsWorld::new();
    let hull = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    let mesh = load_mesh("builtin:boat")?; // or a .obj / .gltf / .glb path
    let atlas = Atlas::bake(&mesh, BakeOptions::square(256))?; // once per mesh
    let mut water = ForceGenerator::new(Water::calm(0.0));
    let boat = water.register(
        &mut world.bodies,
        &world.colliders,
        hull,
        BodyDesc {
            name: "boat".into(),
            atlas: atlas.into(), // an Arc<Atlas>: bodies of one mesh share it
            mass_model: MassModel::Solid { density: 400.0 },
            effects: Effects::buoyancy().with_drag(Drag::default()),
        },
    )?;
    for _ in 0..600 {
        water.step(&mut world)?; // runs every body's effects, then steps the world
    }
    let draft = water.draft(boat, &world.bodies).unwrap_or(0.0);
    println!("after {:.0} s the boat floats {draft:.3} m deep", water.time());
    Ok(())
}
