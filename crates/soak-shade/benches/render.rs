//! Rendering one 640×360 frame (4× MSAA, 2048² shadow map, readback
//! included): a wet boat, a half-wet sphere and a box on a Gerstner sea,
//! with force arrows; the same with the subsurface term; and the liquid
//! debug view.
//!
//! The adapter is named in the group names and printed first: on a
//! software adapter (llvmpipe, lavapipe) these are CPU timings of the
//! rasteriser, not GPU timings. `WGPU_BACKEND=vulkan|gl` picks the backend.

use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::builtin;
use soak_hydro::{Gerstner, GerstnerWave};
use soak_shade::render::{
    Albedo, Arrow, Camera, DebugView, LiquidImage, RenderObject, RenderScene, RenderWater, Renderer,
    Subsurface, adapter_label, blotches, headless_device, is_software, speckled, wood_planks,
};
use soak_shade::{Liquid, WetMaterial};

fn scene() -> RenderScene {
    let sea = Gerstner::new(
        0.0,
        vec![
            GerstnerWave {
                amplitude: 0.15,
                wavelength: 9.0,
                direction_deg: 20.0,
                steepness: 0.6,
                phase: 0.0,
            },
            GerstnerWave {
                amplitude: 0.05,
                wavelength: 3.1,
                direction_deg: -35.0,
                steepness: 0.5,
                phase: 1.3,
            },
        ],
        9.81,
    )
    .unwrap();
    let camera = Camera::perspective(Point3::new(3.6, 2.5, 5.4), Point3::new(0.3, 0.2, 0.0), 40.0);
    let mut scene = RenderScene::new(camera);
    scene.water = Some(RenderWater::gerstner(sea, 2.0));
    // Wet below v = 0.6 of the UV square.
    let band = LiquidImage::from_fn(256, 256, |_, y| image::Luma([if y > 150 { 1.0 } else { 0.1 }]));
    scene.objects.push(
        RenderObject::new(
            builtin::boat(4.0, 1.2, 0.6),
            Isometry3::new(Vector3::new(0.0, -0.25, 0.0), Vector3::new(0.1, 0.45, 0.0)),
        )
        .with_albedo(Albedo::texture(wood_planks(512, 512, 14, [0.62, 0.40, 0.22], 7)))
        .with_liquid(band.clone()),
    );
    scene.objects.push(
        RenderObject::new(
            builtin::sphere(0.4, 64, 32),
            Isometry3::translation(2.4, 0.1, -1.5),
        )
        .with_albedo(Albedo::Constant([0.7, 0.3, 0.2]))
        .with_liquid(blotches(256, 128, 5.0, 0.5, 0.03, 3))
        .with_material(WetMaterial {
            liquid: Liquid::from_colour(1.34, [0.45, 0.2, 0.06], 1e-2, 2e-3),
            ..WetMaterial::default()
        }),
    );
    scene.objects.push(
        RenderObject::new(
            builtin::cuboid(0.8, 0.8, 0.8),
            Isometry3::new(Vector3::new(-2.5, 0.1, -2.0), Vector3::new(0.0, 0.6, 0.2)),
        )
        .with_albedo(Albedo::texture(speckled(
            256,
            256,
            [0.6, 0.55, 0.45],
            0.2,
            8.0,
            1,
        )))
        .with_liquid(band),
    );
    scene.arrows = vec![
        Arrow::weight(Point3::new(0.0, 0.05, 0.0), Vector3::new(0.0, -1.1, 0.0), 1.0),
        Arrow::buoyancy(Point3::new(0.0, -0.1, 0.0), Vector3::new(0.0, 1.1, 0.0), 1.0),
    ];
    scene
}

fn render(c: &mut Criterion) {
    let (device, queue, info) = match headless_device() {
        Ok(d) => d,
        Err(e) => {
            eprintln!("no GPU adapter: skipping the render benches ({e})");
            return;
        }
    };
    let label = adapter_label(&info);
    eprintln!("render benches on {label}");
    if is_software(&info) {
        eprintln!("  software adapter: these are CPU timings of the rasteriser, not GPU timings");
    }
    let tag = format!(
        "{:?}{}",
        info.backend,
        if is_software(&info) { "-software" } else { "" }
    )
    .to_lowercase();
    let mut renderer = Renderer::new(&device, &queue, 640, 360).unwrap();
    let mut scene = scene();
    // Compile the pipelines' shaders (lazily, on some drivers) first.
    renderer.render(&scene).unwrap();

    let mut group = c.benchmark_group(format!("render 640x360 [{tag}]"));
    group.sample_size(20).measurement_time(Duration::from_secs(8));
    group.bench_function("boat, sphere, box on a Gerstner sea", |b| {
        b.iter(|| renderer.render(&scene).unwrap())
    });
    scene.subsurface = Some(Subsurface::default());
    renderer.render(&scene).unwrap();
    group.bench_function("same, with subsurface (256², 3 Gaussians)", |b| {
        b.iter(|| renderer.render(&scene).unwrap())
    });
    scene.subsurface = None;
    scene.view = DebugView::Liquid;
    renderer.render(&scene).unwrap();
    group.bench_function("liquid debug view", |b| {
        b.iter(|| renderer.render(&scene).unwrap())
    });
    group.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
