//! Slamming against von Kármán's wedge: a long prism of deadrise 10°, 20°
//! and 30° driven into calm water at constant speed, its slamming force per
//! unit length against `ρ π V c ċ` (`c = V t / tan β` the half-width the
//! undisturbed surface wets) while the chines are dry; and a body dropped
//! on the water is stopped no faster than the cap allows.

use nalgebra::Point3;
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, Mesh, UnwrapOptions, unwrap};
use soak_hydro::{BuoyancyMode, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, Slamming, SoakError};

const RHO: f64 = 1000.0;

/// A prism of triangular section along z, `length` long: its keel at the
/// origin, its chines `half_beam` either side at the height the deadrise
/// `beta` gives, a flat deck across them.
fn wedge(half_beam: f64, beta: f64, length: f64) -> Mesh {
    let top = half_beam * beta.tan();
    let z = 0.5 * length;
    let positions = vec![
        Point3::new(0.0, 0.0, -z),
        Point3::new(0.0, 0.0, z),
        Point3::new(-half_beam, top, -z),
        Point3::new(-half_beam, top, z),
        Point3::new(half_beam, top, -z),
        Point3::new(half_beam, top, z),
    ];
    let quad = |a: u32, b: u32, c: u32, d: u32| [[a, b, c], [a, c, d]];
    let mut triangles = Vec::new();
    triangles.extend(quad(0, 4, 5, 1)); // starboard bottom
    triangles.extend(quad(0, 1, 3, 2)); // port bottom
    triangles.extend(quad(2, 3, 5, 4)); // deck
    triangles.push([0, 2, 4]);
    triangles.push([1, 5, 3]);
    let mut mesh = Mesh::new("wedge", positions, None, triangles);
    if mesh.volume() < 0.0 {
        mesh = mesh.flipped();
    }
    unwrap(&mesh, UnwrapOptions::default()).unwrap().0
}

#[test]
fn a_wedge_entering_calm_water_feels_von_karmans_force() {
    let (half_beam, length, speed) = (0.2, 4.0, 0.1);
    println!("| deadrise | c / half-beam | soak F/L (N/m) | von Kármán ρ π V c ċ (N/m) | ratio |");
    println!("|---|---|---|---|---|");
    for degrees in [10.0f64, 20.0, 30.0] {
        let beta = degrees.to_radians();
        let atlas = Atlas::bake(&wedge(half_beam, beta, length), BakeOptions::square(1024)).unwrap();
        let mut world = PhysicsWorld::new();
        world.integration_parameters.dt = 1.0 / 240.0;
        let dt = 1.0 / 240.0;
        // The keel starts 1 cm above the surface.
        let y0: f64 = 0.01;
        let handle = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, y0 as f32, 0.0)));
        let mut soak = ForceGenerator::new(Water::calm(0.0));
        let id = soak
            .register(
                &mut world.bodies,
                &world.colliders,
                handle,
                BodyDesc {
                    name: format!("wedge {degrees}°"),
                    atlas: atlas.into(),
                    mass_model: MassModel::Solid { density: 500.0 },
                    effects: Effects {
                        buoyancy: Some(BuoyancyMode::Off),
                        ..Effects::default()
                    }
                    .with_slamming(Slamming::default()),
                },
            )
            .unwrap();
        // (half-width wetted at the evaluation, force) per step, driven at
        // constant speed.
        let substeps = world.integration_parameters.num_solver_iterations.max(1) as f64;
        let lookahead = (substeps - 1.0) / (2.0 * substeps) * dt;
        let mut samples = Vec::new();
        for k in 0..100_000 {
            let t = k as f64 * dt;
            let rb = &mut world.bodies[handle];
            rb.set_translation(Vector::new(0.0, (y0 - speed * t) as f32, 0.0), true);
            rb.set_linvel(Vector::new(0.0, -speed as f32, 0.0), true);
            rb.set_angvel(Vector::ZERO, true);
            soak.step(&mut world).unwrap();
            let report = soak.body(id).unwrap().slamming().copied().unwrap();
            // The keel's depth at the pose the step was evaluated at.
            let depth = speed * (t + lookahead) - y0;
            let c = depth.max(0.0) / beta.tan();
            if c >= half_beam {
                break;
            }
            samples.push((c, report.force.y, report.capped));
        }
        assert!(
            samples.iter().all(|s| !s.2),
            "driven at constant speed, nothing is capped"
        );
        // The force averaged over windows of the wetted half-width (a texel
        // row goes under every few steps), against the same average of
        // von Kármán's: the momentum ½ ρ π c² V L taken over the window.
        for window in [(0.2, 0.4), (0.4, 0.6), (0.6, 0.8), (0.8, 0.95)] {
            let (c1, c2) = (window.0 * half_beam, window.1 * half_beam);
            let inside: Vec<&(f64, f64, bool)> = samples.iter().filter(|s| s.0 > c1 && s.0 <= c2).collect();
            let soak_force = inside.iter().map(|s| s.1).sum::<f64>() / inside.len() as f64 / length;
            let span = inside.len() as f64 * dt;
            let (first, last) = (inside[0].0, inside[inside.len() - 1].0);
            // Each step's force is the growth since the step before: the
            // window covers c from one step before its first sample.
            let before = first - speed * dt / beta.tan();
            let reference = 0.5 * RHO * std::f64::consts::PI * (last * last - before * before) * speed / span;
            let ratio = soak_force / reference;
            println!(
                "| {degrees}° | {:.1}–{:.2} | {soak_force:.2} | {reference:.2} | {ratio:.3} |",
                window.0, window.1
            );
            assert!(
                (ratio - 1.0).abs() < 0.2,
                "{degrees}°, c in {window:?}: {soak_force} vs {reference}"
            );
        }
    }
}

#[test]
fn slamming_settings_out_of_range_are_refused_by_name() {
    let mut world = PhysicsWorld::new();
    let handle = world.bodies.insert(RigidBodyBuilder::dynamic());
    let atlas = Atlas::bake(&wedge(0.2, 0.3, 1.0), BakeOptions::square(32)).unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let e = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "hull".into(),
                atlas: atlas.into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects: Effects::buoyancy().with_slamming(Slamming { cap: 1.5 }),
            },
        )
        .unwrap_err();
    assert!(
        matches!(e, SoakError::Slamming { ref name, .. } if name == "hull"),
        "{e}"
    );
}

/// A light crate (100 kg/m³, 1 m) dropped 2 m onto calm water with
/// slamming and added mass, at a long and a short step: the impact is
/// reported, stays finite, and at the long step the cap holds it to
/// stopping the fall, never throwing the crate back up higher than it fell.
#[test]
fn a_dropped_crate_is_stopped_by_the_impact_but_never_thrown_back() {
    let mesh = soak_bake::builtin::cuboid(1.0, 1.0, 1.0);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    let added = soak_hydro::AddedMass::of_atlas(&atlas).unwrap();
    for rate in [240.0f32, 10.0] {
        let mut world = PhysicsWorld::new();
        world.integration_parameters.dt = 1.0 / rate;
        let handle = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 2.5, 0.0)));
        let mut soak = ForceGenerator::new(Water::calm(0.0));
        let id = soak
            .register(
                &mut world.bodies,
                &world.colliders,
                handle,
                BodyDesc {
                    name: "crate".into(),
                    atlas: atlas.clone().into(),
                    mass_model: MassModel::Solid { density: 100.0 },
                    effects: Effects::buoyancy()
                        .with_added_mass(added)
                        .with_slamming(Slamming::default()),
                },
            )
            .unwrap();
        let mut capped = false;
        let mut highest_after = f32::NEG_INFINITY;
        let steps = (8.0 * rate) as usize;
        for k in 0..steps {
            soak.step(&mut world).unwrap();
            let report = *soak.body(id).unwrap().slamming().unwrap();
            assert!(report.force.iter().all(|f| f.is_finite()) && report.force.y >= 0.0);
            capped |= report.capped;
            let y = world.bodies[handle].translation().y;
            assert!(y.is_finite());
            if k as f32 > 2.0 * rate {
                highest_after = highest_after.max(y);
            }
        }
        let report = *soak.body(id).unwrap().slamming().unwrap();
        println!(
            "dt = 1/{rate} s: peak slamming force {:.0} N at {:.3} s, capped in some step: {capped}, highest after 2 s \
             {highest_after:.3} m",
            report.peak, report.peak_time
        );
        // It hits at about 0.64 s (2 m of free fall), and the peak comes then.
        assert!(
            report.peak > 0.0 && (0.55..0.9).contains(&report.peak_time),
            "{report:?}"
        );
        assert!(highest_after < 2.5, "thrown back up to {highest_after} m");
    }
}
