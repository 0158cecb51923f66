//! Added mass against its references: the initial acceleration of a
//! sphere released from rest under water, `(ρ_w − ρ_b)/(ρ_b + ½ ρ_w) g`;
//! the heave period of a floating vertical cylinder,
//! `2π √((m + m_a)/(ρ g A_wp))` with the added mass soak states; a body
//! too light for the step without it is refused by name.

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{AddedMass, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakError};

const RHO: f64 = 1000.0;

fn sphere_world(density: f64, added: bool, depth: f64) -> (PhysicsWorld, ForceGenerator, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -depth as f32, 0.0)));
    let atlas = Atlas::bake(&builtin::sphere(0.5, 48, 24), BakeOptions::square(128)).unwrap();
    let mut effects = Effects::buoyancy();
    if added {
        effects = effects.with_added_mass(AddedMass::of_atlas(&atlas).unwrap());
    }
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: format!("sphere of {density} kg/m³"),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density },
            effects,
        },
    )
    .unwrap();
    (world, soak, handle)
}

#[test]
fn a_submerged_sphere_starts_at_the_potential_flow_acceleration() {
    println!("| ρ_b (kg/m³) | soak a (m/s²) | (ρ_w − ρ_b)/(ρ_b + ½ ρ_w) g | error | without added mass |");
    println!("|---|---|---|---|---|");
    for density in [1e-9, 1.0, 100.0, 500.0, 2000.0] {
        let (mut world, mut soak, handle) = sphere_world(density, true, 100.0);
        let g = -world.gravity.y as f64;
        let dt = world.integration_parameters.dt as f64;
        soak.step(&mut world).unwrap();
        let a = world.bodies[handle].linvel().y as f64 / dt;
        let want = (RHO - density) / (density + 0.5 * RHO) * g;
        let error = a / want - 1.0;
        let without = if density >= 1e-3 {
            let (mut world, mut soak, handle) = sphere_world(density, false, 100.0);
            soak.step(&mut world).unwrap();
            format!("{:.2}", world.bodies[handle].linvel().y as f64 / dt)
        } else {
            "refused".to_string()
        };
        println!(
            "| {density} | {a:.4} | {want:.4} | {:+.2} % | {without} |",
            100.0 * error
        );
        assert!(error.abs() < 0.02, "ρ_b {density}: {a} m/s² vs {want}");
    }
    // A second later a bubble of 1 kg/m³ has reached about 2 g × 1 s, not
    // the ~390 m/s buoyancy alone gives it.
    let (mut world, mut soak, handle) = sphere_world(1.0, true, 100.0);
    for _ in 0..60 {
        soak.step(&mut world).unwrap();
    }
    let v = world.bodies[handle].linvel().y;
    assert!((v - 2.0 * 9.81).abs() < 0.5, "{v} m/s after 1 s");
}

#[test]
fn a_body_too_light_for_the_step_is_refused_by_name_without_added_mass() {
    let mut world = PhysicsWorld::new();
    let handle = world.bodies.insert(RigidBodyBuilder::dynamic());
    let atlas = Atlas::bake(&builtin::sphere(0.5, 24, 12), BakeOptions::square(32)).unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let e = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "feather".into(),
                atlas: atlas.into(),
                mass_model: MassModel::Solid { density: 1e-9 },
                effects: Effects::buoyancy(),
            },
        )
        .unwrap_err();
    assert!(
        matches!(e, SoakError::TooLight { ref name, .. } if name == "feather"),
        "{e}"
    );
    assert!(e.to_string().contains("added mass"), "{e}");
}

/// Heave of a vertical cylinder (r = 0.5 m, 0.4 m tall, 500 kg/m³: upright
/// it is stable, its metacentre 0.21 m over its centre of mass) floating
/// half submerged, let go 2 cm below its equilibrium: its period against
/// `2π √((m + m_a)/(ρ g A_wp))`, `A_wp` the 48-gon's area and `m_a` the
/// vertical added mass soak states (the equivalent ellipsoid's, half of
/// it for half the volume under water); without added mass, against
/// `2π √(m/(ρ g A_wp))`.
#[test]
fn a_floating_cylinder_heaves_with_the_period_of_its_mass_and_the_waters() {
    let (r, segments) = (0.5, 48);
    let mesh = builtin::cylinder(r, 0.4, segments);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(256)).unwrap();
    let added = AddedMass::of_atlas(&atlas).unwrap();
    let n = segments as f64;
    let water_plane = 0.5 * n * r * r * (2.0 * std::f64::consts::PI / n).sin();
    let m = 500.0 * atlas.volume();
    for with_added in [false, true] {
        let mut world = PhysicsWorld::new();
        world.integration_parameters.dt = 1.0 / 120.0;
        let g = -world.gravity.y as f64;
        // Equilibrium: the centre at the surface (half submerged).
        let handle = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -0.02, 0.0)));
        let mut effects = Effects::buoyancy();
        if with_added {
            effects = effects.with_added_mass(added);
        }
        let mut soak = ForceGenerator::new(Water::calm(0.0));
        soak.register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "spar".into(),
                atlas: atlas.clone().into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects,
            },
        )
        .unwrap();
        // Upward zero crossings of the heave.
        let mut crossings = Vec::new();
        let mut last = -0.02;
        for k in 1..=2400 {
            soak.step(&mut world).unwrap();
            let y = world.bodies[handle].translation().y as f64;
            if last < 0.0 && y >= 0.0 {
                let t = (k as f64 - y / (y - last)) * world.integration_parameters.dt as f64;
                crossings.push(t);
            }
            last = y;
        }
        let periods = crossings.len() - 1;
        let measured = (crossings[periods] - crossings[0]) / periods as f64;
        // The added mass soak states for the body at rest, half submerged
        // (ρ_b/ρ_w of it under water; its pose turns nothing).
        let m_a = if with_added {
            RHO * added.fraction(0.5 * added.volume) * added.translation[(1, 1)]
        } else {
            0.0
        };
        let want = 2.0 * std::f64::consts::PI * ((m + m_a) / (RHO * g * water_plane)).sqrt();
        println!(
            "heave, added mass {with_added}: m = {m:.1} kg, m_a = {m_a:.1} kg, period {measured:.4} s over {periods} \
             periods, 2π √((m + m_a)/(ρ g A_wp)) = {want:.4} s ({:+.2} %)",
            100.0 * (measured / want - 1.0)
        );
        assert!(
            (measured / want - 1.0).abs() < 0.02,
            "added mass {with_added}: {measured} vs {want}"
        );
    }
}
