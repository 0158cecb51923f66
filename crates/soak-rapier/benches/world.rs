//! Step time of a Rapier world with N floating spheres (N = 1, 10, 100,
//! 1000; builtin sphere at 128²): Rapier alone, Rapier with the force
//! generator, and with every body registered but its effects switched off
//! (which should cost nothing measurable). Then ten bodies on the
//! interactive waves they make (64 m at 0.25 m and at 0.5 m cells) against
//! the same ten without.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Drag, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, WaveCoupling};

/// How the bodies are driven.
#[derive(Clone, Copy)]
enum Variant {
    /// Rapier's own mass from a density-500 ball collider, no generator.
    Rapier,
    /// Registered with buoyancy and drag.
    Soak,
    /// Registered with no effects.
    EffectsOff,
}

fn world(
    n: usize,
    atlas: &std::sync::Arc<Atlas>,
    variant: Variant,
) -> (PhysicsWorld, Option<ForceGenerator>) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let side = (n as f64).cbrt().ceil() as usize;
    for i in 0..n {
        let (x, z) = ((i % side) as f32 * 2.0, ((i / side) % side) as f32 * 2.0);
        let y = (i / (side * side)) as f32 * 2.0 - 0.1;
        let handle = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(x, y, z)));
        let density = if matches!(variant, Variant::Rapier) {
            500.0
        } else {
            0.0
        };
        let collider = ColliderBuilder::ball(0.5).density(density);
        world
            .colliders
            .insert_with_parent(collider, handle, &mut world.bodies);
        let effects = match variant {
            Variant::Rapier => continue,
            Variant::Soak => Effects::buoyancy().with_drag(Drag::default()),
            Variant::EffectsOff => Effects::default(),
        };
        let desc = BodyDesc {
            name: format!("sphere {i}"),
            atlas: atlas.clone(),
            mass_model: MassModel::Solid { density: 500.0 },
            effects,
        };
        soak.register(&mut world.bodies, &world.colliders, handle, desc)
            .unwrap();
    }
    let soak = (!matches!(variant, Variant::Rapier)).then_some(soak);
    (world, soak)
}

fn step(c: &mut Criterion) {
    let atlas =
        std::sync::Arc::new(Atlas::bake(&builtin::sphere(0.5, 32, 16), BakeOptions::square(128)).unwrap());
    let mut g = c.benchmark_group("world_step");
    g.sample_size(10);
    for n in [1usize, 10, 100, 1000] {
        for (label, variant) in [
            ("rapier", Variant::Rapier),
            ("soak", Variant::Soak),
            ("effects_off", Variant::EffectsOff),
        ] {
            let (mut w, mut soak) = world(n, &atlas, variant);
            // Settle the start-up transient before timing.
            for _ in 0..30 {
                match &mut soak {
                    Some(s) => s.step(&mut w).unwrap(),
                    None => w.step(),
                }
            }
            g.bench_with_input(BenchmarkId::new(label, n), &n, |b, _| {
                b.iter(|| match &mut soak {
                    Some(s) => s.step(&mut w).unwrap(),
                    None => w.step(),
                })
            });
        }
    }
    g.finish();
}

/// Ten spheres in a row 3 m apart, floating with buoyancy and drag, on
/// interactive waves of `cells` per 64 m side (none for `None`).
fn waves_world(
    atlas: &std::sync::Arc<Atlas>,
    cells: Option<usize>,
    soak: ForceGenerator,
) -> (PhysicsWorld, ForceGenerator) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let mut soak = soak;
    if let Some(cells) = cells {
        soak = soak
            .with_waves(WaveCoupling {
                cells,
                ..WaveCoupling::default()
            })
            .unwrap();
    }
    for i in 0..10 {
        let x = 3.0 * i as f32 - 13.5;
        let handle = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(x, -0.1, 0.0)));
        let desc = BodyDesc {
            name: format!("sphere {i}"),
            atlas: atlas.clone(),
            mass_model: MassModel::Solid { density: 500.0 },
            effects: Effects::buoyancy().with_drag(Drag::default()),
        };
        soak.register(&mut world.bodies, &world.colliders, handle, desc)
            .unwrap();
    }
    (world, soak)
}

fn waves(c: &mut Criterion) {
    let atlas =
        std::sync::Arc::new(Atlas::bake(&builtin::sphere(0.5, 32, 16), BakeOptions::square(128)).unwrap());
    let mut g = c.benchmark_group("waves_step");
    g.sample_size(10);
    for (label, cells) in [("none", None), ("64m_128", Some(128)), ("64m_256", Some(256))] {
        let (mut w, mut soak) = waves_world(&atlas, cells, ForceGenerator::new(Water::calm(0.0)));
        for _ in 0..30 {
            soak.step(&mut w).unwrap();
        }
        g.bench_function(BenchmarkId::new("ten_bodies", label), |b| {
            b.iter(|| soak.step(&mut w).unwrap())
        });
    }
    // The same on the GPU backend (bodies and waves on the device), when
    // there is an adapter; a software one times the CPU running the kernels.
    #[cfg(feature = "gpu")]
    if let Ok((device, queue, info)) = soak_hydro::gpu::headless_device() {
        let tag = if soak_hydro::gpu::is_software(&info) {
            "gpu_software"
        } else {
            "gpu"
        };
        for (label, cells) in [("none", None), ("64m_128", Some(128)), ("64m_256", Some(256))] {
            let soak = ForceGenerator::new(Water::calm(0.0))
                .with_gpu(&device, &queue)
                .unwrap();
            let (mut w, mut soak) = waves_world(&atlas, cells, soak);
            for _ in 0..30 {
                soak.step(&mut w).unwrap();
            }
            g.bench_function(BenchmarkId::new(format!("ten_bodies_{tag}"), label), |b| {
                b.iter(|| soak.step(&mut w).unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, step, waves);
criterion_main!(benches);
