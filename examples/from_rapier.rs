//! The five things a Rapier user does with soak, in order: register a
//! body, choose its effects, step, read the results, save and resume.
//!
//! `cargo run --release --example from_rapier`

use rapier3d::prelude::*;
use soak::Context;
use soak::hydro::BuoyancyMode;
use soak::prelude::*;
use soak::rapier::GeneratorState;

/// A 1 m × 0.6 m × 0.8 m crate of pine on calm water, after `seconds`,
/// saved halfway and resumed in a second world: its draft (m) in each.
fn run(seconds: f64) -> soak::Result<(f64, f64)> {
    // 1. Register a body: a Rapier rigid body (its colliders massless:
    //    soak sets the mass) and an atlas baked once per mesh.
    let mut world = PhysicsWorld::new();
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    let atlas = std::sync::Arc::new(Atlas::bake(
        &builtin::cuboid(1.0, 0.6, 0.8),
        BakeOptions::square(128),
    )?);
    let mut water = ForceGenerator::new(Water::calm(0.0));
    // 2. Choose its effects: buoyancy (Archimedes, or pressure integrated
    //    over the wet surface) and drag; flooding and wetting are further
    //    `with_…` calls.
    let effects = Effects::buoyancy()
        .with_mode(BuoyancyMode::Archimedes)
        .with_drag(Drag {
            coefficient: 1.0,
            linear: 200.0,
        });
    let desc = |atlas: &std::sync::Arc<Atlas>| BodyDesc {
        name: "crate".into(),
        atlas: atlas.clone(),
        mass_model: MassModel::Solid { density: 500.0 },
        effects: effects.clone(),
    };
    let id = water.register(&mut world.bodies, &world.colliders, handle, desc(&atlas))?;
    // 3. Step: the fluid's forces, then Rapier's own step.
    let steps = (seconds / world.integration_parameters.dt as f64).round() as usize;
    for _ in 0..steps / 2 {
        water.step(&mut world)?;
    }
    // 5. Save: the generator's state is serde data (the Rapier world is
    //    saved with Rapier's own serialisation, or rebuilt).
    let saved = serde_json::to_string(&water.state())?;
    let pose = *world.bodies[handle].position();
    let (linvel, angvel) = (world.bodies[handle].linvel(), world.bodies[handle].angvel());
    for _ in steps / 2..steps {
        water.step(&mut world)?;
    }
    // 4. Read the results: the draft at the body's pose, the volume under
    //    water and the forces handed to Rapier at the last step.
    let draft = water.draft(id, &world.bodies).context("no such body")?;
    let body = water.body(id).context("no such body")?;
    println!(
        "t = {:.1} s: draft {draft:.4} m, {:.1} % under water, buoyancy and drag {:.1} N up",
        water.time(),
        100.0 * body.submerged_fraction(),
        body.applied().force.y
    );
    // 5. Resume: the same bodies registered again, then the saved state.
    let mut again = PhysicsWorld::new();
    let h = again.bodies.insert(
        RigidBodyBuilder::dynamic()
            .pose(pose)
            .linvel(linvel)
            .angvel(angvel),
    );
    let mut resumed = ForceGenerator::new(Water::calm(0.0));
    let id2 = resumed.register(&mut again.bodies, &again.colliders, h, desc(&atlas))?;
    resumed.restore_state(&serde_json::from_str::<GeneratorState>(&saved)?)?;
    for _ in steps / 2..steps {
        resumed.step(&mut again)?;
    }
    let draft_resumed = resumed.draft(id2, &again.bodies).context("no such body")?;
    println!(
        "resumed from t = {:.1} s: draft {draft_resumed:.4} m",
        seconds / 2.0
    );
    Ok((draft, draft_resumed))
}

fn main() -> soak::Result<()> {
    run(20.0)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    /// The crate floats at its draft (half its 0.6 m height), and the
    /// resumed run ends where the first one does.
    #[test]
    fn the_five_steps_float_the_crate_and_resume_it() {
        let (draft, resumed) = super::run(20.0).unwrap();
        assert!((draft - 0.3).abs() < 1e-3, "draft {draft}");
        assert!(
            (resumed - draft).abs() < 1e-6,
            "resumed {resumed} against {draft}"
        );
    }
}
