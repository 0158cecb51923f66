//! The GPU path (feature `gpu`) agrees with the CPU: the same scenes run
//! through `Wetting::step` and `GpuWetting::step`, and the liquid textures
//! are compared within stated tolerances, texel by texel.
//!
//! Needs a wgpu adapter: Mesa's lavapipe (`WGPU_BACKEND=vulkan`) or llvmpipe
//! (`WGPU_BACKEND=gl`) do. Without one the tests print a notice and pass,
//! except under `CI=true`, where they fail.
#![cfg(feature = "gpu")]

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Gerstner, GerstnerWave, HeightField, Water};
use soak_wet::gpu::{GpuWetError, GpuWetting};
use soak_wet::prelude::*;

/// Per-texel tolerance, as a fraction of the saturation, and relative
/// tolerance on the total liquid.
const TOL: f64 = 1e-4;

type Device = (wgpu::Device, wgpu::Queue, wgpu::AdapterInfo);

/// A headless device of its own for each test; `None` (with a notice)
/// without an adapter, a failure under `CI=true`.
fn device() -> Option<Device> {
    soak_wet::gpu::test_device()
}

fn sea() -> Water {
    Water::new(
        Gerstner::new(
            0.05,
            vec![
                GerstnerWave {
                    amplitude: 0.12,
                    wavelength: 4.0,
                    direction_deg: 30.0,
                    steepness: 0.6,
                    phase: 0.3,
                },
                GerstnerWave {
                    amplitude: 0.05,
                    wavelength: 1.7,
                    direction_deg: -60.0,
                    steepness: 0.4,
                    phase: 0.0,
                },
            ],
            9.81,
        )
        .unwrap(),
    )
}

struct Case {
    name: &'static str,
    atlas: Atlas,
    wetting: Wetting,
    water: Water,
    env: Environment,
    pose: fn(f64) -> Isometry3<f64>,
    steps: usize,
    dt: f64,
}

fn cases() -> Vec<Case> {
    let cube = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(128)).unwrap();
    let sphere = Atlas::bake(&builtin::sphere(0.5, 32, 16), BakeOptions::square(128)).unwrap();
    let liquid = Liquid {
        evaporation_rate: 1e7,
        ..Liquid::water()
    };
    let rainy = Environment {
        rain: Rain {
            rate: 2e-4,
            region: Region::Disc {
                center: [0.3, 0.1],
                radius: 0.5,
            },
        },
        ..Environment::default()
    };
    let mut spotted = Wetting::new(&sphere, Material::cotton(), liquid)
        .unwrap()
        .with_diffusion(Diffusion::new(2e-3).with_mode(DiffusionMode::Thesis));
    let map: Vec<f32> = (0..sphere.len()).map(|i| (i % 7) as f32 / 6.0).collect();
    spotted.set_permeability_map(&sphere, Some(map)).unwrap();
    let heights: Vec<f64> = (0..25)
        .map(|k| 0.1 * ((k % 5) as f64 - 2.0) + 0.02 * (k / 5) as f64)
        .collect();
    vec![
        Case {
            name: "cube rolling on a Gerstner sea in the rain, conservative",
            atlas: cube.clone(),
            wetting: Wetting::new(&cube, Material::sand(), liquid)
                .unwrap()
                .with_diffusion(Diffusion::new(2e-3).with_resolution(FieldResolution::Cells(24))),
            water: sea(),
            env: rainy,
            pose: |t| {
                Isometry3::from_parts(
                    Translation3::new(0.2, 0.3 * (0.9 * t).sin(), -0.1),
                    UnitQuaternion::from_euler_angles(0.3 * t, 0.2, 0.1 * t),
                )
            },
            steps: 100,
            dt: 0.05,
        },
        Case {
            name: "sphere with a permeability map over a height field, thesis",
            atlas: sphere,
            wetting: spotted,
            water: Water::new(HeightField::new([-1.0, -1.0], [0.5, 0.5], 5, 5, heights).unwrap()),
            env: Environment::default(),
            pose: |t| Isometry3::translation(0.0, 0.2 * (0.7 * t).cos(), 0.0),
            steps: 100,
            dt: 0.05,
        },
        Case {
            name: "cube rocking under a tilted plane whose current changes over space",
            atlas: cube.clone(),
            wetting: Wetting::new(&cube, Material::sand(), liquid).unwrap(),
            water: Water::new(
                soak_hydro::Plane::tilted(
                    nalgebra::Point3::new(0.0, 0.05, 0.0),
                    nalgebra::Vector3::new(0.1, 1.0, -0.05),
                )
                .unwrap()
                .with_current(nalgebra::Vector3::new(0.3, 0.0, 0.1))
                .with_gradient(
                    nalgebra::Matrix3::new(0.0, 0.2, 0.0, -0.1, 0.0, 0.0, 0.0, 0.0, 0.3),
                    nalgebra::Point3::new(1.0, 0.0, 0.0),
                )
                .unwrap(),
            ),
            env: Environment::default(),
            pose: |t| {
                Isometry3::from_parts(
                    Translation3::new(0.0, 0.25 * (0.8 * t).sin(), 0.0),
                    UnitQuaternion::from_euler_angles(0.3 * t, 0.0, 0.1),
                )
            },
            steps: 60,
            dt: 0.05,
        },
        Case {
            name: "cube without diffusion in calm water",
            atlas: cube.clone(),
            wetting: Wetting::new(&cube, Material::wood(), liquid).unwrap(),
            water: Water::calm(0.1),
            env: Environment::default(),
            pose: |_| Isometry3::rotation(nalgebra::Vector3::new(0.3, 0.0, 0.2)),
            steps: 50,
            dt: 0.1,
        },
    ]
}

#[test]
fn gpu_steps_agree_with_the_cpu() {
    let Some((device, queue, _)) = device() else {
        return;
    };
    let gpu = GpuWetting::new(&device, &queue).unwrap();
    for mut case in cases() {
        let mut body = gpu.upload(&case.atlas, &case.wetting).unwrap();
        for k in 0..case.steps {
            let t = k as f64 * case.dt;
            let pose = (case.pose)(t);
            case.wetting
                .step(&case.atlas, &pose, &case.water, &case.env, t, case.dt)
                .unwrap();
            let s = gpu
                .step(&mut body, &pose, &case.water, &case.env, t, case.dt)
                .unwrap();
            assert_eq!(s.diffusion.is_some(), case.wetting.diffusion().is_some());
        }
        let h_gpu = gpu.download(&body).unwrap();
        let h_cpu = case.wetting.liquid();
        let sat = case.wetting.material().saturation;
        let worst = h_gpu
            .iter()
            .zip(h_cpu)
            .map(|(g, c)| (g - c).abs())
            .fold(0.0, f64::max);
        let areas = case.atlas.areas();
        let total = |h: &[f64]| h.iter().zip(areas).map(|(h, &a)| h * a as f64).sum::<f64>();
        let (tg, tc) = (total(&h_gpu), total(h_cpu));
        eprintln!(
            "{}: worst texel {:.2e} of saturation, totals {tc:.6e} (CPU) vs {tg:.6e} m³ (GPU), {:+.2e} relative",
            case.name,
            worst / sat,
            (tg - tc) / tc
        );
        assert!(tc > 0.0);
        assert!(worst <= TOL * sat, "{}", case.name);
        assert!(((tg - tc) / tc).abs() <= TOL, "{}", case.name);
        // The device holds h_max in f32.
        let sat32 = sat as f32 as f64;
        assert!(h_gpu.iter().all(|&h| (0.0..=sat32).contains(&h)));
    }
}

#[test]
fn gpu_errors_are_values() {
    let Some((device, queue, _)) = device() else {
        return;
    };
    let gpu = GpuWetting::new(&device, &queue).unwrap();
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32)).unwrap();
    let wet = Wetting::new(&atlas, Material::sand(), Liquid::water()).unwrap();
    let mut body = gpu.upload(&atlas, &wet).unwrap();
    let other = Atlas::bake(&builtin::sphere(0.5, 8, 4), BakeOptions::square(32)).unwrap();
    assert!(matches!(gpu.upload(&other, &wet), Err(GpuWetError::Wet(_))));
    let env = Environment::default();
    let e = gpu
        .step(
            &mut body,
            &Isometry3::identity(),
            &Water::calm(0.0),
            &env,
            0.0,
            -1.0,
        )
        .unwrap_err();
    assert!(matches!(e, GpuWetError::Wet(WetError::TimeStep { .. })), "{e}");
    struct Custom;
    impl soak_hydro::Surface for Custom {
        fn height(&self, _x: f64, _z: f64, _t: f64) -> f64 {
            0.0
        }
    }
    let e = gpu
        .step(
            &mut body,
            &Isometry3::identity(),
            &Water::new(Custom),
            &env,
            0.0,
            0.1,
        )
        .unwrap_err();
    assert!(e.to_string().contains("GPU evaluates"), "{e}");
    assert!(gpu.upload_liquid(&body, &vec![1.0; atlas.len()]).is_err());
    gpu.upload_liquid(&body, &vec![1e-3; atlas.len()]).unwrap();
    let h = gpu.download(&body).unwrap();
    assert!(h.iter().all(|&h| (h - 1e-3).abs() < 1e-9));
    assert_eq!(body.field_bytes(), 0);
}
