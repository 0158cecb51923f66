//! Cost of one wetting step for a 1024² atlas (a 1 m cube half under calm
//! water) with a 64³ field, CPU and GPU, effect by effect: absorption only, then
//! with evaporation, then with diffusion (conservative, and the thesis' scheme),
//! and absorption with evaporation under a plane whose current changes over
//! space.
//! Without diffusion no field exists: its cost is gone, not skipped.
//!
//! The material's saturation is set high (10 m) so absorption never
//! saturates during the run and every step does the same work. The GPU
//! step is timed to completion (`GpuWetting::wait`); on a software adapter
//! (llvmpipe, lavapipe) those are CPU timings of the kernels.
//!
//! `cargo bench -p soak-wet --bench wet` (`--features gpu` for the GPU rows).

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;

struct Setup {
    name: &'static str,
    env: Environment,
    diffusion: Option<DiffusionMode>,
}

fn setups() -> Vec<Setup> {
    let humid = Environment {
        relative_humidity: 1.0,
        ..Environment::default()
    };
    vec![
        Setup {
            name: "absorption",
            env: humid,
            diffusion: None,
        },
        Setup {
            name: "absorption+evaporation",
            env: Environment::default(),
            diffusion: None,
        },
        Setup {
            name: "absorption+evaporation+diffusion",
            env: Environment::default(),
            diffusion: Some(DiffusionMode::Conservative),
        },
        Setup {
            name: "absorption+evaporation+diffusion_thesis",
            env: Environment::default(),
            diffusion: Some(DiffusionMode::Thesis),
        },
    ]
}

fn wetting(atlas: &Atlas, mode: Option<DiffusionMode>) -> Wetting {
    let material = Material {
        saturation: 10.0,
        ..Material::sand()
    };
    let liquid = Liquid {
        evaporation_rate: 1e7,
        ..Liquid::water()
    };
    let mut w = Wetting::new(atlas, material, liquid).unwrap();
    if let Some(mode) = mode {
        w.set_diffusion(Some(
            Diffusion::new(1e-3)
                .with_mode(mode)
                .with_resolution(FieldResolution::Cells(64)),
        ))
        .unwrap();
    }
    w
}

fn bench(c: &mut Criterion) {
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(1024)).unwrap();
    let water = Water::calm(0.0);
    let pose = Isometry3::identity();
    let dt = 0.1;
    eprintln!("{} texels", atlas.len());

    let mut g = c.benchmark_group("wet_step_1024_cells64");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4))
        .throughput(Throughput::Elements(atlas.len() as u64));
    for s in setups() {
        let mut w = wetting(&atlas, s.diffusion);
        let mut t = 0.0;
        for _ in 0..3 {
            let r = w.step(&atlas, &pose, &water, &s.env, t, dt).unwrap();
            t += dt;
            if let Some(d) = r.diffusion {
                eprintln!(
                    "{}: {:?} field, {} defined voxels, Count_max {}, {} substep(s)",
                    s.name,
                    w.field_grid().unwrap().dims,
                    d.voxels,
                    d.count_max,
                    d.plan.substeps
                );
            }
        }
        // A fingerprint of the liquid after the warm-up steps: variants of
        // the kernels that compute the same bits print the same value.
        let bits = w
            .liquid()
            .iter()
            .fold(0u64, |acc, h| acc.rotate_left(5) ^ h.to_bits());
        eprintln!(
            "{}: total {:.15e} m³, bits {bits:016x}",
            s.name,
            w.total_liquid(&atlas)
        );
        g.bench_function(BenchmarkId::new("cpu", s.name), |b| {
            b.iter(|| {
                t += dt;
                w.step(&atlas, &pose, &water, &s.env, t, dt).unwrap()
            })
        });
    }
    // Absorption and evaporation again under a plane whose current
    // changes over space (what a sea read as one plane hands a large
    // body): its heights are the plane's, and so is its path.
    let flow = soak_hydro::Plane::horizontal(0.0)
        .with_gradient(nalgebra::Matrix3::identity() * 0.1, nalgebra::Point3::origin())
        .unwrap();
    let under_flow = Water::new(flow);
    let s = &setups()[1];
    let mut w = wetting(&atlas, s.diffusion);
    let mut t = 0.0;
    g.bench_function(
        BenchmarkId::new("cpu", "absorption+evaporation_flow_plane"),
        |b| {
            b.iter(|| {
                t += dt;
                w.step(&atlas, &pose, &under_flow, &s.env, t, dt).unwrap()
            })
        },
    );
    gpu(&mut g, &atlas, &water, &pose, dt);
    g.finish();
}

#[cfg(feature = "gpu")]
fn gpu(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    atlas: &Atlas,
    water: &Water,
    pose: &Isometry3<f64>,
    dt: f64,
) {
    use soak_wet::gpu::{GpuWetting, adapter_label, headless_device, is_software};
    let (device, queue, info) = match headless_device() {
        Ok(d) => d,
        Err(e) => {
            eprintln!("no GPU adapter: skipping the GPU rows ({e})");
            return;
        }
    };
    eprintln!(
        "GPU rows on {}{}",
        adapter_label(&info),
        if is_software(&info) {
            ": a software adapter, so CPU timings of the kernels"
        } else {
            ""
        }
    );
    let gpu = GpuWetting::new(&device, &queue).unwrap();
    for s in setups() {
        let w = wetting(atlas, s.diffusion);
        let mut body = gpu.upload(atlas, &w).unwrap();
        let mut t = 0.0;
        for _ in 0..3 {
            gpu.step(&mut body, pose, water, &s.env, t, dt).unwrap();
            t += dt;
        }
        gpu.wait().unwrap();
        g.bench_function(BenchmarkId::new("gpu", s.name), |b| {
            b.iter(|| {
                t += dt;
                gpu.step(&mut body, pose, water, &s.env, t, dt).unwrap();
                gpu.wait().unwrap();
            })
        });
    }
}

#[cfg(not(feature = "gpu"))]
fn gpu(
    _: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    _: &Atlas,
    _: &Water,
    _: &Isometry3<f64>,
    _: f64,
) {
    eprintln!("built without the `gpu` feature: no GPU rows");
}

criterion_group!(benches, bench);
criterion_main!(benches);
