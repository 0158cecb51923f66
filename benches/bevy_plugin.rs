//! 1,000 floating bodies through the Bevy plugin against the same through
//! soak-rapier, in one run: boxes and spheres of `soak bench`'s world
//! (128² atlases shared by mesh, half as dense as water, 2 m apart, at
//! their floating level on calm water), buoyancy alone and with drag.
//!
//! Four worlds per case, stepped in turn (one step each, round after
//! round, so that the machine's drift falls on all alike): soak-rapier's
//! generator over rapier3d 0.36, rapier3d alone (the same bodies, their
//! mass on their colliders), the plugin over bevy_rapier3d 0.36 (rapier3d
//! 0.35), and bevy_rapier alone.
//!
//! Two measures of the plugin's overhead: soak's own work in each (the
//! generator's work before Rapier steps, timed around it; the plugin's
//! system, which reads every body from the ECS, runs the same driver and
//! writes the forces and reports back, timed inside it), and the whole
//! step with soak less the same engine's step without it (which also
//! counts bevy_rapier handing the changed `ExternalForce`s to Rapier).
//!
//! `cargo bench --features bevy --bench bevy_plugin` (`-- --bodies N --rounds R`).

use std::sync::Arc;
use std::time::Instant;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier3d::prelude::*;
use rapier3d::prelude as rp;
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::driver::{BodyDesc, Effects};
use soak::hydro::{Drag, MassModel, Water};
use soak_bevy::prelude::{Floating, FloatingMesh, SoakPlugin, SoakWater};

const DT: f32 = 1.0 / 60.0;
const DENSITY: f64 = 500.0;
const SPACING: f32 = 2.0;
const BOX: [f32; 3] = [1.0, 0.6, 0.8];
const RADIUS: f32 = 0.5;

struct Fleet {
    atlases: [Arc<Atlas>; 2],
    masses: [f64; 2],
}

fn grid(i: usize, n: usize) -> (f32, f32) {
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    ((i % side) as f32 * SPACING, (i / side) as f32 * SPACING)
}

/// soak-rapier's world (with `effects`), or Rapier alone (`None`).
fn rapier_world(
    fleet: &Fleet,
    n: usize,
    effects: Option<&Effects>,
) -> (rp::PhysicsWorld, Option<soak::rapier::ForceGenerator>) {
    let mut world = rp::PhysicsWorld::new();
    world.integration_parameters.dt = DT;
    let mut soak = effects.map(|_| soak::rapier::ForceGenerator::new(Water::calm(0.0)));
    for i in 0..n {
        let (x, z) = grid(i, n);
        let handle = world
            .bodies
            .insert(rp::RigidBodyBuilder::dynamic().translation(rp::Vector::new(x, 0.0, z)));
        let shape = if i % 2 == 0 {
            rp::ColliderBuilder::cuboid(BOX[0] / 2.0, BOX[1] / 2.0, BOX[2] / 2.0)
        } else {
            rp::ColliderBuilder::ball(RADIUS)
        };
        let collider = match (&soak, effects) {
            (Some(_), _) => shape.density(0.0),
            _ => shape.mass(fleet.masses[i % 2] as f32),
        };
        world
            .colliders
            .insert_with_parent(collider, handle, &mut world.bodies);
        if let (Some(soak), Some(effects)) = (&mut soak, effects) {
            soak.register(
                &mut world.bodies,
                &world.colliders,
                handle,
                BodyDesc {
                    name: format!("body {i}"),
                    atlas: fleet.atlases[i % 2].clone(),
                    mass_model: MassModel::Solid { density: DENSITY },
                    effects: effects.clone(),
                },
            )
            .expect("registers");
        }
    }
    (world, soak)
}

/// The plugin's app (with `effects`), or bevy_rapier alone (`None`).
fn bevy_app(fleet: &Fleet, n: usize, effects: Option<&Effects>) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(Time::<Fixed>::from_seconds(DT as f64))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .insert_resource(TimestepMode::Fixed { dt: DT, substeps: 1 })
        .add_plugins(RapierPhysicsPlugin::<NoUserData>::default().in_fixed_schedule());
    if effects.is_some() {
        app.add_plugins(SoakPlugin::default())
            .insert_resource(SoakWater::new(Water::calm(0.0)));
    }
    app.finish();
    app.cleanup();
    for i in 0..n {
        let (x, z) = grid(i, n);
        let collider = if i % 2 == 0 {
            Collider::cuboid(BOX[0] / 2.0, BOX[1] / 2.0, BOX[2] / 2.0)
        } else {
            Collider::ball(RADIUS)
        };
        let mut e = app
            .world_mut()
            .spawn((RigidBody::Dynamic, collider, Transform::from_xyz(x, 0.0, z)));
        match effects {
            Some(effects) => {
                e.insert(
                    Floating::new(
                        format!("body {i}"),
                        FloatingMesh::Atlas(fleet.atlases[i % 2].clone()),
                    )
                    .with_mass_model(MassModel::Solid { density: DENSITY })
                    .with_effects(effects.clone()),
                );
            }
            None => {
                e.insert(ColliderMassProperties::Mass(fleet.masses[i % 2] as f32));
            }
        }
    }
    // Start-up, then the first steps: the bodies registered and stepping.
    for _ in 0..3 {
        app.update();
    }
    if effects.is_some() {
        let registered = app.world().resource::<SoakWater>().driver().bodies().len();
        assert_eq!(registered, n, "every body registered");
    }
    app
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

fn main() {
    let mut n = 1000;
    let mut rounds = 300;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--bodies" => n = args.next().and_then(|v| v.parse().ok()).unwrap_or(n),
            "--rounds" => rounds = args.next().and_then(|v| v.parse().ok()).unwrap_or(rounds),
            // cargo bench passes `--bench`.
            _ => {}
        }
    }
    let boxed = Atlas::bake(
        &builtin::cuboid(BOX[0] as f64, BOX[1] as f64, BOX[2] as f64),
        BakeOptions::square(128),
    )
    .expect("box bakes");
    let sphere =
        Atlas::bake(&builtin::sphere(RADIUS as f64, 48, 24), BakeOptions::square(128)).expect("sphere bakes");
    let masses = [boxed.volume() * DENSITY, sphere.volume() * DENSITY];
    let fleet = Fleet {
        atlases: [Arc::new(boxed), Arc::new(sphere)],
        masses,
    };
    println!("{n} bodies, 128² atlases, calm water, dt = 1/60 s; median of {rounds} steps each, ms");
    println!();
    let mut rows = Vec::new();
    let cases = [
        ("buoyancy", Effects::buoyancy()),
        (
            "buoyancy + drag",
            Effects::buoyancy().with_drag(Drag {
                coefficient: 0.8,
                linear: 20.0,
            }),
        ),
    ];
    for (label, effects) in cases {
        let (mut world, mut soak) = rapier_world(&fleet, n, Some(&effects));
        let (mut bare, _) = rapier_world(&fleet, n, None);
        let mut app = bevy_app(&fleet, n, Some(&effects));
        let mut bare_app = bevy_app(&fleet, n, None);
        let soak = soak.as_mut().expect("a generator");
        let mut times = [(); 6].map(|_| Vec::with_capacity(rounds));
        // Warm up: the bodies settle, caches fill.
        for _ in 0..60 {
            soak.step(&mut world).expect("steps");
            bare.step();
            app.update();
            bare_app.update();
        }
        for _ in 0..rounds {
            // ForceGenerator::step, its parts timed.
            let s = Instant::now();
            soak.sync_gravity(&world);
            let params = soak::rapier::step_params(&world.integration_parameters);
            let inner = Instant::now();
            soak.before_step(
                &mut soak::rapier::RapierBodies::new(&mut world.bodies, &world.colliders),
                &params,
            )
            .expect("steps");
            times[4].push(inner.elapsed().as_secs_f64() * 1e3);
            world.step();
            soak.after_step(params.dt);
            soak.tear(&world).expect("tears");
            times[0].push(s.elapsed().as_secs_f64() * 1e3);
            let s = Instant::now();
            bare.step();
            times[1].push(s.elapsed().as_secs_f64() * 1e3);
            let s = Instant::now();
            app.update();
            times[2].push(s.elapsed().as_secs_f64() * 1e3);
            let system = app.world().resource::<SoakWater>().last_step_time();
            times[5].push(system.as_secs_f64() * 1e3);
            let s = Instant::now();
            bare_app.update();
            times[3].push(s.elapsed().as_secs_f64() * 1e3);
        }
        rows.push((label, times.map(median)));
    }
    println!("soak's own work: the generator's before Rapier's step, the plugin's system");
    println!();
    println!("| effects | soak-rapier | soak-bevy | plugin overhead |");
    println!("|---|---:|---:|---:|");
    for (label, [.., generator, system]) in &rows {
        println!(
            "| {label} | {generator:.3} | {system:.3} | {:+.1} % |",
            100.0 * (system / generator - 1.0)
        );
    }
    println!();
    println!("whole steps, and each engine's step with soak less the same without it");
    println!();
    println!(
        "| effects | soak-rapier | rapier alone | soak's cost | soak-bevy | bevy_rapier alone | soak's cost | overhead |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (label, [a, b, c, d, ..]) in &rows {
        let (rapier_cost, bevy_cost) = (a - b, c - d);
        println!(
            "| {label} | {a:.3} | {b:.3} | {rapier_cost:.3} | {c:.3} | {d:.3} | {bevy_cost:.3} | {:+.1} % |",
            100.0 * (bevy_cost / rapier_cost - 1.0)
        );
    }
}
