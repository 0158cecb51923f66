//! A boat floating on a Gerstner sea, wet below its waterline (and damp in a
//! splash band above it), with its weight (red, at the centre of mass) and
//! buoyancy (green, at the centre of buoyancy) drawn as in the thesis'
//! Fig. 7.3. Writes `out/render_frame.png` and the liquid texture in
//! pseudo-colour, `out/render_frame_liquid.png`.
//!
//! `cargo run --release --features render --example render_frame`

use nalgebra::{Isometry3, Point3, Vector3};
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::hydro::{BodyState, Gerstner, GerstnerWave, HydroOptions, MassModel, Water, evaluate};
use soak::shade::render::{
    Albedo, Arrow, Camera, DebugView, DirectionalLight, RenderObject, RenderScene, RenderWater, Renderer,
    adapter_label, fractal_noise, headless_device, liquid_image_from_texels, wood_planks,
};
use soak::shade::{Gamma, Liquid, WetMaterial};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 720;
const TIME: f64 = 3.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("out");
    std::fs::create_dir_all(&out)?;

    let sea = Gerstner::new(
        0.0,
        vec![
            GerstnerWave {
                amplitude: 0.16,
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
            GerstnerWave {
                amplitude: 0.02,
                wavelength: 1.3,
                direction_deg: 70.0,
                steepness: 0.4,
                phase: 0.4,
            },
        ],
        9.81,
    )?;
    let water = Water::new(sea.clone());

    // The hull, baked so its texels give wetness and hydrostatics.
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(256))?;
    let mass = MassModel::Solid { density: 230.0 }.mass_properties(&atlas)?;

    // Float it: bisect the height at which buoyancy equals weight, with a
    // little roll and pitch.
    let rotation = Vector3::new(0.10, 0.45, -0.04);
    let weight = mass.mass * 9.81;
    let pose_at = |y: f64| Isometry3::new(Vector3::new(0.0, y, 0.0), rotation);
    let buoyancy_at = |y: f64| -> Result<f64, Box<dyn std::error::Error>> {
        let f = evaluate(
            &atlas,
            &water,
            &BodyState::at_rest(pose_at(y)),
            &mass,
            TIME,
            &HydroOptions::default(),
        )?;
        Ok(f.buoyancy.force.y)
    };
    let (mut lo, mut hi) = (-0.6, 0.6);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if buoyancy_at(mid)? > weight {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let pose = pose_at(0.5 * (lo + hi));
    let forces = evaluate(
        &atlas,
        &water,
        &BodyState::at_rest(pose),
        &mass,
        TIME,
        &HydroOptions::default(),
    )?;

    // Liquid texture: saturated up to 12 cm above the local water height
    // (where the waves wash), then drying within a few cm: the hull above
    // water is half wet. The deck has a few splashes.
    let saturation: Vec<f32> = (0..atlas.len())
        .map(|i| {
            let p = pose * atlas.position(i);
            let above = p.y - water.surface.height(p.x, p.z, TIME) - 0.12;
            let hull = if above <= 0.0 { 1.0 } else { (-above / 0.03).exp() };
            let q = atlas.position(i);
            let splash = fractal_noise(1.6 * q.x + 7.0, 1.6 * q.z, 4, 11);
            let deck = if atlas.area_vectors().get(i)[1] > 0.0 && q.y > 0.55 {
                ((splash - 0.58) / 0.04).clamp(0.0, 1.0)
            } else {
                0.0
            };
            hull.max(deck) as f32
        })
        .collect();
    let liquid = liquid_image_from_texels(atlas.width(), atlas.height(), atlas.texels(), &saturation, 3);

    let hull = RenderObject::new(mesh, pose)
        .with_name("boat")
        .with_albedo(Albedo::texture(wood_planks(512, 512, 14, [0.62, 0.40, 0.22], 7)))
        .with_liquid(liquid)
        .with_material(WetMaterial {
            liquid: Liquid::water(),
            gamma: Gamma::Arctan { roughness: 8.0 },
        });

    // A striped buoy nearby, dry above the water.
    let buoy_mesh = builtin::capsule(0.25, 0.5, 48);
    let buoy_pose = Isometry3::translation(2.6, sea.particle(2.6, -1.8, TIME).y - 0.2, -1.8);
    let buoy = RenderObject::new(buoy_mesh, buoy_pose)
        .with_name("buoy")
        .with_albedo(Albedo::Constant([0.75, 0.18, 0.08]));

    let target = Point3::new(0.3, 0.2, 0.0);
    let camera = Camera::perspective(Point3::new(3.0, 1.9, 5.0), target, 40.0);
    let mut scene = RenderScene::new(camera);
    // Afternoon sun over the camera's right shoulder, lighting the hull side.
    scene.light = DirectionalLight::from_angles(38.0, 60.0, [2.7, 2.5, 2.3]);
    scene.water = Some(RenderWater::gerstner(sea.clone(), TIME));
    scene.objects = vec![hull, buoy];
    let metres_per_newton = 1.1 / weight;
    let com = pose * mass.center_of_mass;
    scene.arrows = vec![
        Arrow::weight(com, Vector3::new(0.0, -weight, 0.0), metres_per_newton).with_radius(0.03),
        Arrow::buoyancy(
            forces.center_of_buoyancy,
            forces.buoyancy.force,
            metres_per_newton,
        )
        .with_radius(0.03),
    ];

    let (device, queue, info) = headless_device()?;
    let mut renderer = Renderer::new(&device, &queue, WIDTH, HEIGHT)?;
    let start = std::time::Instant::now();
    let image = renderer.render(&scene)?;
    let elapsed = start.elapsed();

    image.save(out.join("render_frame.png"))?;
    // A close-up of the waterline: wet wood is darker and glossier.
    let wide = scene.camera;
    scene.camera = Camera::perspective(Point3::new(1.2, 0.9, 2.6), Point3::new(0.2, 0.1, 0.3), 35.0);
    renderer
        .render(&scene)?
        .save(out.join("render_frame_closeup.png"))?;
    scene.camera = wide;
    scene.view = DebugView::Liquid;
    scene.arrows.clear();
    renderer
        .render(&scene)?
        .save(out.join("render_frame_liquid.png"))?;
    println!(
        "boat: mass {:.0} kg, submerged volume {:.3} m³, draft at y = {:.3} m; rendered {WIDTH}×{HEIGHT} in {:.0} ms on {}",
        mass.mass,
        forces.submerged_volume,
        pose.translation.y,
        elapsed.as_secs_f64() * 1e3,
        adapter_label(&info)
    );
    println!("wrote {}", out.join("render_frame.png").display());
    Ok(())
}
