//! The GPU backend of the force generator is interchangeable with the CPU's.
#![cfg(feature = "gpu")]

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, load_mesh};
use soak_hydro::{
    Drag, Gerstner, GerstnerWave, MassModel, SeaSampling, SeaSpectrum, SpectralSea, SpectralSurface, Water,
};
use soak_rapier::{BodyDesc, Effects, ForceGenerator};

/// A device of its own for the test; `None` without an adapter (a failure
/// under `CI=true`).
fn device() -> Option<(wgpu::Device, wgpu::Queue)> {
    soak_hydro::gpu::test_device().map(|(d, q, _)| (d, q))
}

/// The boat, a sphere and a torus on `water`, each reading a sea as `reads`
/// says (`None`: the generator's exact read).
fn world(
    water: Water,
    gpu: Option<&(wgpu::Device, wgpu::Queue)>,
    reads: [Option<SeaSampling>; 3],
) -> (PhysicsWorld, ForceGenerator, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    // Both paths read the sea exactly here (the GPU inverts the Gerstner map
    // at every texel, the CPU too); the sampled read, the default, is held
    // to the exact one in soak-hydro's `sea_sampling` tests, and the GPU's
    // sampled read to the CPU's in its `gpu` tests.
    let mut soak = ForceGenerator::new(water).with_sea_sampling(SeaSampling::Exact);
    if let Some((d, q)) = gpu {
        soak = soak.with_gpu(d, q).unwrap();
    }
    let mut handles = Vec::new();
    for (i, name) in ["builtin:boat", "builtin:sphere:0.5:32", "builtin:torus"]
        .iter()
        .enumerate()
    {
        let h = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(3.0 * i as f32, 0.2, 0.0)));
        let atlas = Atlas::bake(&load_mesh(name).unwrap(), BakeOptions::square(128)).unwrap();
        let mut effects = Effects::buoyancy().with_drag(Drag {
            coefficient: 0.8,
            linear: 10.0,
        });
        effects.sea = reads[i];
        soak.register(
            &mut world.bodies,
            &world.colliders,
            h,
            BodyDesc {
                name: name.to_string(),
                atlas: atlas.into(),
                mass_model: MassModel::Solid {
                    density: 400.0 + 100.0 * i as f64,
                },
                effects,
            },
        )
        .unwrap();
        handles.push(h);
    }
    (world, soak, handles)
}

#[test]
fn gpu_and_cpu_worlds_follow_the_same_trajectories() {
    let Some(gpu) = device() else { return };
    // Calm water, a Gerstner wave, and a JONSWAP sea (its tile evaluated
    // on the device in each step's batch).
    let make = |kind: usize| match kind {
        0 => Water::calm(0.0),
        1 => {
            let wave = GerstnerWave {
                amplitude: 0.2,
                wavelength: 7.0,
                direction_deg: 20.0,
                steepness: 0.5,
                phase: 0.0,
            };
            Water::new(Gerstner::new(0.0, vec![wave], 9.81).unwrap())
        }
        _ => {
            let spectrum = SeaSpectrum::jonswap(0.5, 3.0);
            let sea = SpectralSea::realize(&spectrum, 0.0, spectrum.default_tile(9.81), 64, 3, 9.81).unwrap();
            Water::new(SpectralSurface::new(sea))
        }
    };
    // Then, on both seas, the sphere reads its sea as one plane and the
    // torus samples it, among bodies read exactly (the device then reads
    // the others' seas itself in the same batch).
    let mixed = [
        None,
        Some(SeaSampling::Plane),
        Some(SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH)),
    ];
    for (kind, reads) in [
        (0, [None; 3]),
        (1, [None; 3]),
        (2, [None; 3]),
        (1, mixed),
        (2, mixed),
    ] {
        let (mut wc, mut sc, hc) = world(make(kind), None, reads);
        let (mut wg, mut sg, hg) = world(make(kind), Some(&gpu), reads);
        assert!(sg.uses_gpu() && !sc.uses_gpu());
        // One second: forces agree closely step by step, trajectories stay together.
        for step in 0..60 {
            sc.step(&mut wc).unwrap();
            sg.step(&mut wg).unwrap();
            for (k, (a, b)) in hc.iter().zip(&hg).enumerate() {
                let (fa, fb) = (sc.bodies()[k].applied(), sg.bodies()[k].applied());
                let scale = fa.force.norm().max(100.0);
                assert!(
                    (fa.force - fb.force).norm() < 2e-3 * scale,
                    "water {kind} ({reads:?}) step {step} body {k}: {} vs {}",
                    fa.force,
                    fb.force
                );
                let (pa, pb) = (wc.bodies[*a].translation(), wg.bodies[*b].translation());
                assert!(
                    (pa - pb).length() < 1e-3,
                    "water {kind} ({reads:?}) step {step} body {k}: {pa} vs {pb}"
                );
            }
        }
        assert_eq!(sg.firewall().count(), 0);
    }
}

/// A cylinder heaving on the waves it makes, the waves stepped on the GPU
/// (set before or after the GPU backend) or on the CPU: the same heave
/// within 1 mm and the same surface within 1e-4 m over 5 s.
#[test]
fn waves_on_the_gpu_follow_the_cpus() {
    let Some(gpu) = device() else { return };
    let atlas = Atlas::bake(
        &load_mesh("builtin:cylinder:1:1:64").unwrap(),
        BakeOptions::square(128),
    )
    .unwrap();
    let rule = soak_rapier::WaveCoupling {
        size: 32.0,
        cells: 128,
        ..soak_rapier::WaveCoupling::default()
    };
    let make = |on_gpu: Option<bool>| {
        let mut world = PhysicsWorld::new();
        let h = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, -0.1, 0.0))
                .enabled_translations(false, true, false)
                .lock_rotations(),
        );
        let mut soak = ForceGenerator::new(Water::calm(0.0));
        soak = match on_gpu {
            None => soak.with_waves(rule).unwrap(),
            Some(true) => soak.with_gpu(&gpu.0, &gpu.1).unwrap().with_waves(rule).unwrap(),
            Some(false) => soak.with_waves(rule).unwrap().with_gpu(&gpu.0, &gpu.1).unwrap(),
        };
        soak.register(
            &mut world.bodies,
            &world.colliders,
            h,
            BodyDesc {
                name: "cylinder".into(),
                atlas: atlas.clone().into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects: Effects::buoyancy(),
            },
        )
        .unwrap();
        (world, soak, h)
    };
    for order in [true, false] {
        let (mut wc, mut sc, hc) = make(None);
        let (mut wg, mut sg, hg) = make(Some(order));
        let (mut worst_y, mut worst_h) = (0.0_f64, 0.0_f64);
        for _ in 0..300 {
            sc.step(&mut wc).unwrap();
            sg.step(&mut wg).unwrap();
            let (yc, yg) = (wc.bodies[hc].translation().y, wg.bodies[hg].translation().y);
            worst_y = worst_y.max((yc - yg).abs() as f64);
        }
        let (a, b) = (sc.waves().unwrap().heights(), sg.waves().unwrap().heights());
        for (x, y) in a.iter().zip(b) {
            worst_h = worst_h.max((x - y).abs());
        }
        let when = if order {
            "after the GPU backend"
        } else {
            "before it"
        };
        println!(
            "waves on the GPU (set {when}): heave within {worst_y:.2e} m, surface within {worst_h:.2e} m"
        );
        assert!(worst_y < 1e-3 && worst_h < 1e-4, "{worst_y} {worst_h}");
        assert_eq!(sg.firewall().count(), 0);
    }
}
