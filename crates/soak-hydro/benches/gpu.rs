//! GPU hydrostatics (feature `gpu`): one body at 512², 1024² and 2048²
//! (dispatch, reduction and readback included), and the per-body cost of a
//! batch of 100 bodies in one submission. The CPU `evaluate` of the same
//! body is measured beside each for scale.
//!
//! The two-wave swell of `buoy_on_waves.toml` at 512² and 1024², with drag,
//! read both ways: sampled once per evaluation on the CPU and read as a
//! patch by the kernel (the default), and the Gerstner map inverted at every
//! texel on the device (`SeaSampling::Exact`).
//!
//! The adapter is named in the group names and printed first: on a software
//! adapter (llvmpipe, lavapipe) these are CPU timings of the kernels, not
//! GPU timings. `WGPU_BACKEND=vulkan|gl` picks the backend.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::gpu::{GpuAtlasId, GpuBody, GpuHydro, GpuWaves, adapter_label, headless_device, is_software};
use soak_hydro::{
    BodyState, Drag, Gerstner, GerstnerWave, HydroOptions, MassModel, MassProperties, SeaSampling, Water,
    evaluate,
};

/// The two-wave swell of `data/scenes/buoy_on_waves.toml`.
fn swell() -> Water {
    let waves = GerstnerWave::SWELL.to_vec();
    Water::new(Gerstner::new(0.0, waves, 9.80665).expect("valid waves"))
}

fn state(k: usize) -> BodyState {
    let a = k as f64;
    let pose = Isometry3::from_parts(
        Vector3::new(0.37 * a % 5.0, 0.1 - 0.01 * (a % 20.0), 0.53 * a % 7.0).into(),
        UnitQuaternion::from_euler_angles(0.3 + 0.1 * a, 0.2, 0.1 - 0.05 * a),
    );
    BodyState {
        pose,
        linear_velocity: Vector3::new(0.5, -0.2, 0.1),
        angular_velocity: Vector3::new(0.1, 0.3, -0.2),
    }
}

/// `mesh` baked at `n`², a solid of half the water's density, uploaded.
fn uploaded(hydro: &mut GpuHydro, mesh: &Mesh, n: u32) -> (Atlas, MassProperties, GpuAtlasId) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    let id = hydro.upload(&atlas).unwrap();
    (atlas, mass, id)
}

fn gpu(c: &mut Criterion) {
    let (device, queue, info) = match headless_device() {
        Ok(d) => d,
        Err(e) => {
            eprintln!("no GPU adapter: skipping the GPU benches ({e})");
            return;
        }
    };
    let label = adapter_label(&info);
    eprintln!("GPU benches on {label}");
    if is_software(&info) {
        eprintln!("  software adapter: these are CPU timings of the kernels, not GPU timings");
    }
    let tag = format!(
        "{:?}{}",
        info.backend,
        if is_software(&info) { "-software" } else { "" }
    )
    .to_lowercase();
    let mut hydro = GpuHydro::new(&device, &queue).unwrap();
    let mesh = builtin::sphere(0.5, 64, 32);
    let water = Water::calm(0.0);
    let plain = HydroOptions::default();
    let with_drag = HydroOptions {
        drag: Some(Drag {
            coefficient: 1.0,
            linear: 0.5,
        }),
        ..HydroOptions::default()
    };

    let mut g = c.benchmark_group(format!("gpu_{tag}_one_body"));
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for n in [512u32, 1024, 2048] {
        let (atlas, mass, id) = uploaded(&mut hydro, &mesh, n);
        let s = state(1);
        g.throughput(Throughput::Elements(atlas.len() as u64));
        g.bench_with_input(BenchmarkId::new("gpu_buoyancy", n), &n, |b, _| {
            b.iter(|| hydro.evaluate(id, &water, &s, &mass, 0.0, &plain).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("gpu_buoyancy_drag", n), &n, |b, _| {
            b.iter(|| hydro.evaluate(id, &water, &s, &mass, 0.0, &with_drag).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("cpu_buoyancy_drag", n), &n, |b, _| {
            b.iter(|| evaluate(&atlas, &water, &s, &mass, 0.0, &with_drag).unwrap())
        });
    }
    g.finish();

    let sea = swell();
    let exact = HydroOptions {
        sea: SeaSampling::Exact,
        ..with_drag
    };
    let mut g = c.benchmark_group(format!("gpu_{tag}_swell"));
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for n in [512u32, 1024] {
        let (atlas, mass, id) = uploaded(&mut hydro, &mesh, n);
        let s = state(1);
        g.throughput(Throughput::Elements(atlas.len() as u64));
        g.bench_with_input(BenchmarkId::new("gpu_swell_sampled_drag", n), &n, |b, _| {
            b.iter(|| hydro.evaluate(id, &sea, &s, &mass, 0.0, &with_drag).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("gpu_swell_exact_drag", n), &n, |b, _| {
            b.iter(|| hydro.evaluate(id, &sea, &s, &mass, 0.0, &exact).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("cpu_swell_sampled_drag", n), &n, |b, _| {
            b.iter(|| evaluate(&atlas, &sea, &s, &mass, 0.0, &with_drag).unwrap())
        });
    }
    g.finish();

    let mut g = c.benchmark_group(format!("gpu_{tag}_batch_of_100"));
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for n in [256u32, 512] {
        let atlas = Atlas::bake(&mesh, BakeOptions::square(n)).unwrap();
        let mass = MassModel::Solid { density: 500.0 }
            .mass_properties(&atlas)
            .unwrap();
        let id = hydro.upload(&atlas).unwrap();
        let bodies: Vec<GpuBody> = (0..100)
            .map(|k| GpuBody::from((id, &water, state(k), mass, with_drag)))
            .collect();
        // Elements are bodies: time per element is the per-body cost.
        g.throughput(Throughput::Elements(100));
        g.bench_with_input(BenchmarkId::new("gpu_batch", n), &n, |b, _| {
            b.iter(|| hydro.evaluate_batch(&bodies, 0.0).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("gpu_100_single", n), &n, |b, _| {
            b.iter(|| {
                for body in &bodies {
                    hydro
                        .evaluate(
                            body.atlas,
                            body.water,
                            &body.state,
                            &body.mass,
                            0.0,
                            &body.options,
                        )
                        .unwrap();
                }
            })
        });
    }
    g.finish();
}

/// The interactive waves' step on the device: 64 m at 0.5 m and 0.25 m
/// cells (one submission; the elevation read back, as a coupled step needs
/// it), against the CPU's step of the same region in the same run.
fn waves(c: &mut Criterion) {
    let Ok((device, queue, info)) = headless_device() else {
        eprintln!("no GPU adapter: skipping the GPU waves bench");
        return;
    };
    let tag = format!(
        "{:?}{}",
        info.backend,
        if is_software(&info) { "-software" } else { "" }
    )
    .to_lowercase();
    let mut g = c.benchmark_group("waves_step");
    g.sample_size(10);
    for cells in [128usize, 256] {
        let region = soak_hydro::WaveRegion {
            centre: [0.0, 0.0],
            size: 64.0,
            cells,
        };
        let mut cpu = soak_hydro::InteractiveWaves::new(region, 9.81, 1000.0, 16).unwrap();
        cpu.add_gaussian(0.0, 0.0, 0.5, 0.05);
        let pressure = cpu.pressure_mut().to_vec();
        let mut gpu = GpuWaves::new(&device, &queue, region, 9.81, 16).unwrap();
        gpu.set_pressure(&pressure).unwrap();
        g.bench_function(BenchmarkId::new(format!("gpu_{tag}"), cells), |b| {
            b.iter(|| {
                gpu.step(1.0 / 60.0).unwrap();
                gpu.heights().unwrap()
            })
        });
        g.bench_function(BenchmarkId::new("cpu", cells), |b| {
            b.iter(|| cpu.step(1.0 / 60.0).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, gpu, waves);
criterion_main!(benches);
