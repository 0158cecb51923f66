//! One driver, two engines: the same three bodies stepped by soak-rapier's
//! generator over rapier3d 0.36 and by the Bevy plugin over bevy_rapier3d
//! 0.36 (rapier3d 0.35) follow the same trajectories. Needs the `bevy`
//! feature (`cargo test --features bevy --test engines_agree`).
#![cfg(feature = "bevy")]

use std::sync::Arc;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::driver::Effects;
use soak::hydro::{Drag, MassModel, Water};
use soak_bevy::prelude::{Floating, FloatingMesh, SoakPlugin, SoakWater};

/// The physics step, s (Rapier's default).
const DT: f32 = 1.0 / 60.0;

/// The same three bodies, stepped by soak-rapier's generator in a rapier3d
/// 0.36 world and by the plugin over bevy_rapier3d (rapier3d 0.35), follow
/// the same trajectories over 10 s.
#[test]
fn soak_rapier_and_the_plugin_agree() {
    use rapier3d::prelude as rp;
    let bodies: Vec<(&str, soak_bake::Mesh, [f32; 3], f64, Effects)> = vec![
        (
            "boat",
            builtin::boat(4.0, 1.6, 0.8),
            [0.0, 0.6, 0.0],
            300.0,
            Effects::buoyancy().with_drag(Drag::default()),
        ),
        (
            "crate",
            builtin::cuboid(1.0, 0.6, 0.8),
            [6.0, 0.8, 0.0],
            500.0,
            Effects::buoyancy(),
        ),
        (
            "ball",
            builtin::sphere(0.4, 32, 16),
            [-6.0, 1.0, 2.0],
            700.0,
            Effects::buoyancy().with_drag(Drag {
                coefficient: 0.5,
                linear: 20.0,
            }),
        ),
    ];
    let atlases: Vec<Arc<Atlas>> = bodies
        .iter()
        .map(|(_, m, ..)| Arc::new(Atlas::bake(m, BakeOptions::square(64)).unwrap()))
        .collect();
    let steps = (10.0 / DT) as usize;

    // soak-rapier.
    let mut world = rp::PhysicsWorld::new();
    world.integration_parameters.dt = DT;
    let mut soak = soak::rapier::ForceGenerator::new(Water::calm(0.0));
    let mut handles = Vec::new();
    for ((name, _, p, density, effects), atlas) in bodies.iter().zip(&atlases) {
        let h = world
            .bodies
            .insert(rp::RigidBodyBuilder::dynamic().translation(rp::Vector::new(p[0], p[1], p[2])));
        soak.register(
            &mut world.bodies,
            &world.colliders,
            h,
            soak::driver::BodyDesc {
                name: name.to_string(),
                atlas: atlas.clone(),
                mass_model: MassModel::Solid { density: *density },
                effects: effects.clone(),
            },
        )
        .unwrap();
        handles.push(h);
    }
    // Each step, every body's position.
    let mut rapier_path: Vec<Vec<[f32; 3]>> = Vec::with_capacity(steps);
    for _ in 0..steps {
        soak.step(&mut world).unwrap();
        rapier_path.push(
            handles
                .iter()
                .map(|h| {
                    let t = world.bodies[*h].translation();
                    [t.x, t.y, t.z]
                })
                .collect(),
        );
    }

    // The plugin: the bodies are registered at once (atlases given), so
    // both runs start at the same step.
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(Time::<Fixed>::from_seconds(DT as f64))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .insert_resource(TimestepMode::Fixed { dt: DT, substeps: 1 })
        .add_plugins(RapierPhysicsPlugin::<NoUserData>::default().in_fixed_schedule())
        .add_plugins(SoakPlugin::default())
        .insert_resource(SoakWater::new(Water::calm(0.0)));
    app.finish();
    app.cleanup();
    // The first update runs the start-up schedules and no fixed step.
    app.update();
    let entities: Vec<Entity> = bodies
        .iter()
        .zip(&atlases)
        .map(|((name, _, p, density, effects), atlas)| {
            app.world_mut()
                .spawn((
                    RigidBody::Dynamic,
                    Transform::from_xyz(p[0], p[1], p[2]),
                    Floating::new(*name, FloatingMesh::Atlas(atlas.clone()))
                        .with_mass_model(MassModel::Solid { density: *density })
                        .with_effects(effects.clone()),
                ))
                .id()
        })
        .collect();
    let mut worst = 0.0f64;
    for at in &rapier_path {
        app.update();
        for (e, r) in entities.iter().zip(at) {
            let t = app.world().get::<Transform>(*e).unwrap().translation;
            let d = ((t.x - r[0]) as f64)
                .hypot((t.y - r[1]) as f64)
                .hypot((t.z - r[2]) as f64);
            worst = worst.max(d);
        }
    }
    println!("largest distance between the two runs' bodies over 10 s: {worst:.3e} m");
    assert!(worst <= 1e-6, "the runs differ by {worst} m");
}
