//! Cost of one world step for a crate (1 × 0.5 × 0.8 m box, 128² atlas,
//! about 10k texels) floating in a Gerstner swell: without wetting, with
//! wetting (absorption and evaporation), and with wetting and diffusion on
//! 5 cm voxels. Without wetting the generator holds no wetting state and
//! the step should cost what it did before wetting existed.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Drag, Gerstner, GerstnerWave, MassModel, Water};
use soak_rapier::soak_wet::{Diffusion, FieldResolution, Liquid, Material, Wetting};
use soak_rapier::{BodyDesc, Effects, ForceGenerator};

#[derive(Clone, Copy, Debug)]
enum Variant {
    Dry,
    Wet,
    WetDiffusing,
}

fn setup(variant: Variant) -> (PhysicsWorld, ForceGenerator) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.05, 0.0)));
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 0.5, 0.8), BakeOptions::square(128)).unwrap();
    let sea = Gerstner::new(
        0.0,
        vec![GerstnerWave {
            amplitude: 0.15,
            wavelength: 9.0,
            direction_deg: 0.0,
            steepness: 0.5,
            phase: 0.0,
        }],
        9.81,
    )
    .unwrap();
    let mut soak = ForceGenerator::new(Water::new(sea));
    let wetting = match variant {
        Variant::Dry => None,
        Variant::Wet => Some(Wetting::new(&atlas, Material::wood(), Liquid::water()).unwrap()),
        Variant::WetDiffusing => Some(
            Wetting::new(&atlas, Material::wood(), Liquid::water())
                .unwrap()
                .with_diffusion(Diffusion::new(1e-4).with_resolution(FieldResolution::VoxelSize(0.05))),
        ),
    };
    soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "crate".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density: 400.0 },
            effects: Effects {
                wetting: wetting.map(Box::new),
                ..Effects::buoyancy().with_drag(Drag::default())
            },
        },
    )
    .unwrap();
    // Settle and build the diffusion field before measuring.
    for _ in 0..60 {
        soak.step(&mut world).unwrap();
    }
    (world, soak)
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("crate_step");
    group.sample_size(30);
    for variant in [Variant::Dry, Variant::Wet, Variant::WetDiffusing] {
        let (mut world, mut soak) = setup(variant);
        group.bench_function(BenchmarkId::from_parameter(format!("{variant:?}")), |b| {
            b.iter(|| soak.step(&mut world).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
