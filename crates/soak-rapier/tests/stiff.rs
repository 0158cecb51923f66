//! A body whose heave period is far shorter than the step (a light
//! millimetre body at dt = 1/10 s) stays in the water: the generator
//! integrates the restoring part of the buoyancy implicitly.

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator};

#[test]
fn a_very_light_body_at_a_tenth_of_a_second_step_does_not_gain_energy() {
    // A 1 mm cube at 1 % of water's density: its heave period is ~2 ms, the
    // step 50 times longer. It floats with a draft of 10 µm; start it 50 µm
    // deeper, at rest.
    let size = 1e-3;
    let density = 10.0;
    let draft = 0.01 * size;
    let y0 = 0.5 * size - draft - 0.05 * size;
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 0.1;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, y0 as f32, 0.0)));
    let atlas = Atlas::bake(&builtin::cuboid(size, size, size), BakeOptions::square(32)).unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "speck".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density },
            effects: Effects::buoyancy(),
        },
    )
    .unwrap();
    let g = 9.81;
    // Specific energy relative to the floating equilibrium: kinetic, gravity
    // and the buoyancy's potential of a box (water-plane area size²).
    let energy = |world: &PhysicsWorld| {
        let b = &world.bodies[handle];
        let y = b.translation().y as f64;
        let v = b.linvel().length() as f64;
        let depth = (0.5 * size - y).clamp(0.0, size);
        let potential = 1000.0 * g * size * size * depth * depth / 2.0 / (density * size.powi(3));
        0.5 * v * v + g * y + potential
    };
    let e0 = energy(&world);
    let mut worst: f64 = 0.0;
    let mut fastest: f64 = 0.0;
    for _ in 0..60 {
        soak.step(&mut world).unwrap();
        worst = worst.max(energy(&world) - e0);
        fastest = fastest.max(world.bodies[handle].linvel().length() as f64);
    }
    // Before the fix it left the water at ~50 m/s, gaining kJ/kg.
    let allowance = 0.02 * g * size;
    assert!(fastest < 0.01, "the body reached {fastest} m/s");
    assert!(
        worst <= allowance,
        "energy grew by {worst:.3e} J/kg, allowance {allowance:.3e}"
    );
    let y = world.bodies[handle].translation().y as f64;
    assert!(
        (y - (0.5 * size - draft)).abs() < 0.05 * size,
        "it ended at y = {y:.3e} m, the draft puts it at {:.3e}",
        0.5 * size - draft
    );
}
