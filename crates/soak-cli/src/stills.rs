//! The demo's stills: the buoy with its forces, the sinking boat, the wet
//! beach (and its liquid in pseudo-colour), a red-wine stain.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Gerstner;
use soak_rapier::Simulation;
use soak_rapier::scene::LoadedScene;
use soak_shade::render::{
    Albedo, Camera, DebugView, DirectionalLight, RenderObject, RenderScene, RenderWater, Renderer,
    fractal_noise, headless_device, liquid_image_from_texels, speckled, wood_planks,
};
use soak_shade::{Gamma, Liquid, WetMaterial};
use soak_wet::scenes::{Beach, BeachOptions};

use soak_view::{FrameOptions, SceneRenderer, View};

const SIZE: (u32, u32) = (640, 360);

/// Renders every still into `out`; returns one summary line per image.
/// Without a GPU adapter (not even a software one) it says so and draws
/// nothing.
pub fn render_stills(out: &Path, quick: bool) -> Result<Vec<String>> {
    if let Err(e) = headless_device() {
        return Ok(vec![format!("stills skipped: no GPU adapter ({e})")]);
    }
    let mut lines = Vec::new();
    lines.push(scene_still(
        out,
        "buoy",
        include_str!("../scenes/buoy_on_waves.toml"),
        "data/scenes/buoy_on_waves.toml",
        0.5,
        true,
        None,
    )?);
    lines.push(scene_still(
        out,
        "sinking_boat",
        include_str!("../scenes/sinking_boat.toml"),
        "data/scenes/sinking_boat.toml",
        if quick { 0.1 } else { 0.35 },
        false,
        None,
    )?);
    // Open containers, seen from above: the water they hold.
    for (name, text, path, eye) in [
        (
            "open_boat",
            include_str!("../scenes/open_boat.toml"),
            "data/scenes/open_boat.toml",
            [2.6, 2.6, 2.8],
        ),
        (
            "open_crates",
            include_str!("../scenes/open_crates.toml"),
            "data/scenes/open_crates.toml",
            [0.5, 2.6, 3.4],
        ),
        (
            "bucket",
            include_str!("../scenes/bucket.toml"),
            "data/scenes/bucket.toml",
            [0.0, 1.9, 1.9],
        ),
    ] {
        lines.push(scene_still(
            out,
            name,
            text,
            path,
            if quick { 0.2 } else { 1.0 },
            false,
            Some((eye, [0.0, -0.1, 0.0])),
        )?);
    }
    lines.extend(beach_still(out, quick)?);
    lines.push(stain_still(out)?);
    Ok(lines)
}

/// A scene file simulated to `fraction` of its duration and drawn, seen
/// from `view`'s eye towards its target (m), or as the scene frames itself.
fn scene_still(
    out: &Path,
    name: &str,
    text: &str,
    path: &str,
    fraction: f64,
    forces: bool,
    view: Option<([f64; 3], [f64; 3])>,
) -> Result<String> {
    let start = Instant::now();
    let loaded = LoadedScene::from_str(text, Path::new(path))?;
    let mut sim = Simulation::from_scene(&loaded)?;
    let steps = (fraction * sim.total_steps() as f64).round() as u64;
    for _ in 0..steps {
        sim.step()?;
    }
    let mut renderer = SceneRenderer::new(
        &loaded,
        FrameOptions {
            size: SIZE,
            view: View::Shaded,
            forces,
            eye: view.map(|v| Point3::from(v.0)),
            target: view.map(|v| Point3::from(v.1)),
        },
    )?;
    let file = out.join(format!("still_{name}.png"));
    renderer
        .frame(&sim)?
        .save(&file)
        .with_context(|| format!("writing {}", file.display()))?;
    Ok(format!(
        "still {}: {path} at t = {:.1} s ({:.1} s)",
        file.display(),
        sim.time(),
        start.elapsed().as_secs_f64()
    ))
}

fn renderer() -> Result<Renderer> {
    let (device, queue, _) = headless_device()?;
    Ok(Renderer::new(&device, &queue, SIZE.0, SIZE.1)?)
}

/// The beach of thesis Fig. 7.11 after the tide has ebbed for a while: the
/// band of sand the water left is dark and glossy, drying at its top.
fn beach_still(out: &Path, quick: bool) -> Result<Vec<String>> {
    let start = Instant::now();
    let mut beach = Beach::new(if quick {
        BeachOptions::small()
    } else {
        BeachOptions::default()
    })?;
    let steps = if quick { 100 } else { 400 };
    for _ in 0..steps {
        beach.step()?;
    }
    let mut objects = Vec::new();
    for (i, b) in beach.bodies.iter().enumerate() {
        let saturation = b.wetting.material().saturation;
        let values: Vec<f32> = b
            .wetting
            .liquid()
            .iter()
            .map(|h| (h / saturation).clamp(0.0, 1.0) as f32)
            .collect();
        let liquid =
            liquid_image_from_texels(b.atlas.width(), b.atlas.height(), b.atlas.texels(), &values, 3);
        let albedo = match b.name {
            "sand" => Albedo::texture(speckled(1024, 1024, [0.72, 0.60, 0.42], 0.10, 60.0, 5)),
            "crate" => Albedo::texture(wood_planks(512, 512, 6, [0.62, 0.42, 0.24], 9)),
            _ => Albedo::texture(speckled(512, 512, [0.42, 0.40, 0.38], 0.25, 12.0, 7 + i as u64)),
        };
        objects.push(
            RenderObject::new(b.mesh.clone(), b.pose)
                .with_name(b.name)
                .with_albedo(albedo)
                .with_liquid(liquid)
                .with_material(WetMaterial {
                    liquid: Liquid::water(),
                    gamma: Gamma::Arctan { roughness: 8.0 },
                }),
        );
    }
    let sea = Gerstner::new(
        beach.sea.waves.level + beach.sea.tide(beach.time),
        beach.sea.waves.waves.clone(),
        beach.sea.waves.gravity,
    )?;
    let camera = Camera::perspective(Point3::new(-8.5, 4.2, 8.0), Point3::new(0.5, -0.4, 0.0), 42.0);
    let mut scene = RenderScene::new(camera);
    scene.light = DirectionalLight::from_angles(40.0, 70.0, [2.7, 2.5, 2.3]);
    scene.water = Some(RenderWater::gerstner(sea, beach.time));
    scene.objects = objects;
    let mut r = renderer()?;
    let shaded = out.join("still_beach.png");
    r.render(&scene)?.save(&shaded)?;
    scene.view = DebugView::Liquid;
    let liquid = out.join("still_beach_liquid.png");
    r.render(&scene)?.save(&liquid)?;
    Ok(vec![format!(
        "stills {} and {}: the beach after {:.0} s of ebbing tide ({:.1} s)",
        shaded.display(),
        liquid.display(),
        beach.time,
        start.elapsed().as_secs_f64()
    )])
}

/// Red wine spilled on a pale wooden board (thesis Fig. 7.12): the stain is
/// darker and its hue moves towards the wine's.
fn stain_still(out: &Path) -> Result<String> {
    let start = Instant::now();
    let mesh = builtin::cuboid(2.0, 0.06, 1.4);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(512))?;
    // Wetness over the top face: a blotch of fractal outline, fully wet
    // inside, with a thin drying rim.
    let values: Vec<f32> = (0..atlas.len())
        .map(|i| {
            let p = atlas.position(i);
            if p.y < 0.0 {
                return 0.0;
            }
            let (x, z) = (p.x + 0.15, p.z - 0.05);
            let wobble = 0.18 * (fractal_noise(2.5 * x + 3.0, 2.5 * z + 1.0, 4, 3) - 0.5);
            let r = (x * x / 0.36 + z * z / 0.20).sqrt() + wobble;
            let splash = (-(((x - 0.62).powi(2) + (z + 0.28).powi(2)) / 0.004)).exp();
            (((0.62 - r) / 0.05).clamp(0.0, 1.0) + splash).min(1.0) as f32
        })
        .collect();
    let liquid = liquid_image_from_texels(atlas.width(), atlas.height(), atlas.texels(), &values, 3);
    let wine = Liquid::from_colour(1.34, [0.50, 0.03, 0.08], 1e-2, 2e-3);
    let board = RenderObject::new(
        mesh,
        Isometry3::new(Vector3::zeros(), Vector3::new(0.0, 0.25, 0.0)),
    )
    .with_name("board")
    .with_albedo(Albedo::texture(wood_planks(1024, 1024, 5, [0.78, 0.66, 0.50], 3)))
    .with_liquid(liquid)
    .with_material(WetMaterial {
        liquid: wine,
        gamma: Gamma::Arctan { roughness: 8.0 },
    });
    let camera = Camera::perspective(Point3::new(0.9, 1.55, 1.9), Point3::new(0.0, 0.0, 0.05), 38.0);
    let mut scene = RenderScene::new(camera);
    scene.light = DirectionalLight::from_angles(50.0, 30.0, [2.7, 2.5, 2.3]);
    scene.objects = vec![board];
    let file = out.join("still_stain.png");
    renderer()?.render(&scene)?.save(&file)?;
    Ok(format!(
        "still {}: red wine on a pale board ({:.1} s)",
        file.display(),
        start.elapsed().as_secs_f64()
    ))
}
