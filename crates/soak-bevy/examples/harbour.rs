//! The harbour: a boat, three crates and a buoy on a Gerstner sea, drawn by
//! Bevy. The water mesh is displaced by the same sea the physics reads
//! (`SoakWater::height`); one crate soaks up the sea where it dips and
//! darkens as it does (its albedo wet by Lekner and Dorf's model, weighted
//! by how wet its surface is). Drag with the left mouse button to orbit,
//! scroll to zoom.
//!
//! `cargo run --release -p soak-bevy --example harbour`
//!
//! `-- --screenshot FILE [--frames N]` saves the window after N frames
//! (default 120) and quits, printing what the water did.

use std::path::PathBuf;
use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::mesh::{Indices, PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use bevy_rapier3d::prelude::*;
use soak_bake::builtin;
use soak_bevy::prelude::*;
use soak_hydro::{Gerstner, GerstnerWave};
use soak_wet::{Liquid, Material, Wetting};

/// What the command line asked for.
#[derive(Resource, Clone, Default)]
struct Args {
    screenshot: Option<PathBuf>,
    frames: u32,
}

impl Args {
    fn parse() -> Self {
        let mut args = Self {
            screenshot: None,
            frames: 120,
        };
        let mut it = std::env::args().skip(1);
        while let Some(a) = it.next() {
            match a.as_str() {
                "--screenshot" => args.screenshot = it.next().map(PathBuf::from),
                "--frames" => args.frames = it.next().and_then(|n| n.parse().ok()).unwrap_or(args.frames),
                other => eprintln!("harbour: ignoring `{other}` (options: --screenshot FILE, --frames N)"),
            }
        }
        args
    }
}

/// The swell: two Gerstner waves, 0.25 m and 0.1 m.
fn sea() -> Water {
    let waves = vec![
        GerstnerWave {
            amplitude: 0.25,
            wavelength: 9.0,
            direction_deg: 0.0,
            steepness: 0.6,
            phase: 0.0,
        },
        GerstnerWave {
            amplitude: 0.10,
            wavelength: 4.0,
            direction_deg: 35.0,
            steepness: 0.4,
            phase: 1.0,
        },
    ];
    Water::new(Gerstner::new(0.0, waves, 9.81).expect("valid waves"))
}

fn main() {
    let args = Args::parse();
    App::new()
        .add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: "soak: the harbour".into(),
                resolution: (960u32, 540u32).into(),
                ..default()
            }),
            ..default()
        }))
        .insert_resource(args)
        .insert_resource(ClearColor(Color::srgb(0.66, 0.78, 0.90)))
        // One Rapier step per fixed step, soak's forces computed for it.
        .insert_resource(Time::<Fixed>::from_hz(60.0))
        .insert_resource(TimestepMode::Fixed {
            dt: 1.0 / 60.0,
            substeps: 1,
        })
        .add_plugins(RapierPhysicsPlugin::<NoUserData>::default().in_fixed_schedule())
        .add_plugins(SoakPlugin::default())
        .insert_resource(SoakWater::new(sea()))
        .add_systems(Startup, setup)
        .add_systems(Update, (move_water, orbit, darken_wet_crate, readout, screenshot))
        .run();
}

/// The water's mesh, displaced every frame.
#[derive(Component)]
struct WaterMesh;

/// The crate that soaks, and its dry albedo (linear RGB).
#[derive(Component)]
struct WetCrate([f64; 3]);

/// The on-screen readout.
#[derive(Component)]
struct Readout;

/// The orbit camera's angles (rad) and distance (m) about its focus.
#[derive(Component)]
struct Orbit {
    yaw: f32,
    pitch: f32,
    distance: f32,
}

/// A soak mesh as a flat-shaded Bevy mesh.
fn bevy_mesh(mesh: &soak_bake::Mesh) -> Mesh {
    let positions: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    let indices = mesh.triangles.iter().flatten().copied().collect();
    let mut m = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
        .with_inserted_indices(Indices::U32(indices));
    m.duplicate_vertices();
    m.compute_flat_normals();
    m
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Tonemapping::AcesFitted,
        Transform::default(),
        Orbit {
            yaw: 0.6,
            pitch: 0.35,
            distance: 16.0,
        },
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9000.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(4.0, 10.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });

    // The sea: a 48 m square of 96 × 96 cells, its heights set each frame.
    let water = Plane3d::default()
        .mesh()
        .size(48.0, 48.0)
        .subdivisions(95)
        .build();
    commands.spawn((
        Mesh3d(meshes.add(water)),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.05, 0.25, 0.45),
            perceptual_roughness: 0.15,
            double_sided: true,
            cull_mode: None,
            ..default()
        })),
        Transform::default(),
        WaterMesh,
    ));

    // The boat: pine-coloured, 4 m long.
    let hull = builtin::boat(4.0, 1.6, 0.8);
    let points: Vec<Vec3> = hull
        .positions
        .iter()
        .map(|p| Vec3::new(p.x as f32, p.y as f32, p.z as f32))
        .collect();
    commands.spawn((
        RigidBody::Dynamic,
        Collider::convex_hull(&points).expect("a hull"),
        Mesh3d(meshes.add(bevy_mesh(&hull))),
        MeshMaterial3d(materials.add(Color::srgb(0.85, 0.32, 0.18))),
        Transform::from_xyz(0.0, 0.4, 0.0),
        Floating::new("boat", FloatingMesh::Mesh(Arc::new(hull)))
            .with_mass_model(MassModel::Solid { density: 300.0 })
            .with_effects(soak_driver::Effects::buoyancy().with_drag(Drag {
                coefficient: 1.0,
                linear: 50.0,
            })),
    ));

    // Three crates of one mesh (one bake), the first one soaking.
    let side = 0.8;
    let crate_mesh = Arc::new(builtin::cuboid(side, side, side));
    let crate_shape = meshes.add(bevy_mesh(&crate_mesh));
    let dry = [0.42, 0.24, 0.09];
    for (k, (x, z)) in [(4.0, 2.0), (5.2, -1.0), (3.0, -3.0)].into_iter().enumerate() {
        let floating = Floating::new(format!("crate {k}"), FloatingMesh::Mesh(crate_mesh.clone()))
            .with_mass_model(MassModel::Solid { density: 450.0 })
            .with_effects(soak_driver::Effects::buoyancy().with_drag(Drag {
                coefficient: 1.0,
                linear: 80.0,
            }));
        let colour = Color::LinearRgba(LinearRgba::rgb(dry[0] as f32, dry[1] as f32, dry[2] as f32));
        let mut e = commands.spawn((
            RigidBody::Dynamic,
            Collider::cuboid(side as f32 / 2.0, side as f32 / 2.0, side as f32 / 2.0),
            Mesh3d(crate_shape.clone()),
            MeshMaterial3d(materials.add(colour)),
            Transform::from_xyz(x, 0.6, z).with_rotation(Quat::from_rotation_y(0.3 * k as f32)),
        ));
        if k == 0 {
            // Weathered planks and a time-lapse sun (as the wet crate scene):
            // a minute shows hours of soaking and drying.
            e.insert((
                WetCrate(dry),
                floating.with_atlas_effects(|atlas, effects| {
                    let planks = Material {
                        permeability: 1e-11,
                        thickness: 0.005,
                        saturation: 0.001,
                    };
                    let liquid = Liquid {
                        viscosity: 1e-3,
                        evaporation_rate: 1e6,
                    };
                    let wetting = Wetting::new(atlas, planks, liquid).map_err(|e| e.to_string())?;
                    Ok(effects.with_wetting(wetting))
                }),
            ));
        } else {
            e.insert(floating);
        }
    }

    // A buoy: a capsule, red.
    let buoy = builtin::capsule(0.3, 0.6, 24);
    commands.spawn((
        RigidBody::Dynamic,
        Collider::capsule_y(0.3, 0.3),
        Mesh3d(meshes.add(bevy_mesh(&buoy))),
        MeshMaterial3d(materials.add(Color::srgb(0.9, 0.1, 0.1))),
        Transform::from_xyz(-4.0, 0.3, 3.0),
        Floating::new("buoy", FloatingMesh::Mesh(Arc::new(buoy)))
            .with_mass_model(MassModel::Solid { density: 450.0 })
            .with_effects(soak_driver::Effects::buoyancy().with_drag(Drag {
                coefficient: 0.8,
                linear: 20.0,
            })),
    ));

    commands.spawn((
        Text::new("soak: the harbour"),
        TextFont::from_font_size(15.0),
        TextColor(Color::BLACK),
        Node {
            position_type: PositionType::Absolute,
            top: px(8),
            left: px(8),
            ..default()
        },
        Readout,
    ));
}

/// Lays the water mesh on the sea the bodies float on.
fn move_water(
    water: Res<SoakWater>,
    query: Query<&Mesh3d, With<WaterMesh>>,
    mut meshes: ResMut<Assets<Mesh>>,
) {
    for handle in &query {
        let Some(mut mesh) = meshes.get_mut(handle) else {
            continue;
        };
        if let Some(VertexAttributeValues::Float32x3(positions)) =
            mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION)
        {
            for p in positions.iter_mut() {
                p[1] = water.height(p[0] as f64, p[2] as f64) as f32;
            }
        }
        mesh.compute_normals();
    }
}

/// Orbits the camera about the boat with the left button; zooms with the
/// wheel.
fn orbit(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut cameras: Query<(&mut Transform, &mut Orbit)>,
) {
    for (mut transform, mut orbit) in &mut cameras {
        if buttons.pressed(MouseButton::Left) {
            orbit.yaw -= motion.delta.x * 0.005;
            orbit.pitch = (orbit.pitch + motion.delta.y * 0.005).clamp(0.05, 1.4);
        }
        orbit.distance = (orbit.distance * (1.0 - 0.1 * scroll.delta.y)).clamp(4.0, 60.0);
        let (sy, cy) = orbit.yaw.sin_cos();
        let (sp, cp) = orbit.pitch.sin_cos();
        let eye = Vec3::new(cy * cp, sp, sy * cp) * orbit.distance;
        *transform = Transform::from_translation(eye).looking_at(Vec3::new(0.0, 0.0, 0.0), Vec3::Y);
    }
}

/// The soaking crate's colour: its dry albedo, wet by Lekner and Dorf's
/// model (water, n = 1.33, under diffuse light), weighted by how wet its
/// surface is.
fn darken_wet_crate(
    crates: Query<(&WetCrate, &FloatReport, &MeshMaterial3d<StandardMaterial>)>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let n = 1.33;
    for (WetCrate(dry), report, material) in &crates {
        let wet = soak_shade::wet_albedo_rgb(
            *dry,
            [1.0; 3],
            soak_shade::stern_mean_reflectance(n),
            soak_shade::internal_reflectance(n),
        );
        let c = soak_shade::blend_rgb(*dry, wet, report.wetness);
        if let Some(mut m) = materials.get_mut(&material.0) {
            m.base_color = Color::LinearRgba(LinearRgba::rgb(c[0] as f32, c[1] as f32, c[2] as f32));
        }
    }
}

/// What the water does, on screen.
fn readout(
    water: Res<SoakWater>,
    bodies: Query<(&Floating, &FloatReport, &Transform)>,
    mut text: Query<&mut Text, With<Readout>>,
) {
    let mut lines = vec![format!("soak: the harbour   t = {:.1} s", water.time())];
    for (floating, report, transform) in &bodies {
        let mut line = format!(
            "{:<8} y {:+.2} m  submerged {:>3.0} %",
            floating.name,
            transform.translation.y,
            100.0 * report.submerged_fraction
        );
        if report.surface_liquid > 0.0 {
            line += &format!("  wet {:>3.0} %", 100.0 * report.wetness);
        }
        lines.push(line);
    }
    lines.push("drag: orbit   wheel: zoom".into());
    for mut t in &mut text {
        **t = lines.join("\n");
    }
}

/// With `--screenshot`: saves the window after `--frames` frames, says
/// what the water did, and quits a few frames later.
fn screenshot(
    mut commands: Commands,
    args: Res<Args>,
    mut frame: Local<u32>,
    water: Res<SoakWater>,
    bodies: Query<(&Floating, &FloatReport)>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(path) = &args.screenshot else {
        return;
    };
    *frame += 1;
    if *frame == args.frames {
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(path.clone()));
    }
    // The capture lands a few frames later.
    if *frame == args.frames + 8 {
        let floating: Vec<String> = bodies
            .iter()
            .map(|(f, r)| format!("{} {:.2}", f.name, r.submerged_fraction))
            .collect();
        println!(
            "harbour: t = {:.2} s, {} bodies floating ({}), screenshot {}",
            water.time(),
            floating.len(),
            floating.join(", "),
            path.display()
        );
        exit.write(AppExit::Success);
    }
}
