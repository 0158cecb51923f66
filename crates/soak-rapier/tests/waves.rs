//! Bodies that make waves and float on them ([`WaveCoupling`]): a heaving
//! ball radiates its energy into the waves (and keeps it without them), a
//! hull towed through Rapier leaves a Kelvin wake of 19.5°, a dropped ball
//! sends out a ring whose crests move at the group velocity, a passing
//! boat rocks a moored buoy.

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{InteractiveWaves, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakError, SoakId, WaveCoupling};

const RHO: f64 = 1000.0;

/// A ball of radius `a` (m) and density 500 kg/m³ at height `y` (m), free
/// to move as `builder` allows, on calm water with waves as `waves` says.
fn ball_world(
    a: f64,
    density: f64,
    builder: RigidBodyBuilder,
    waves: Option<WaveCoupling>,
    dt: f64,
) -> (PhysicsWorld, ForceGenerator, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt as f32;
    let handle = world.bodies.insert(builder);
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    if let Some(w) = waves {
        soak = soak.with_waves(w).unwrap();
    }
    let atlas = Atlas::bake(&builtin::sphere(a, 64, 32), BakeOptions::square(256)).unwrap();
    soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "ball".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density },
            effects: Effects::buoyancy(),
        },
    )
    .unwrap();
    (world, soak, handle)
}

/// A vertical cylinder (r = 1 m, 1 m tall, 64 sides, 500 kg/m³: it floats
/// half under) held 10 cm below its floating level in still water and let
/// go, free to heave alone, for 10 s: with the waves it radiates rings and
/// its heave dies away, the energy it loses (kinetic, weight and the
/// buoyancy's potential `½ ρ g A d²`, exact for a prism of water-plane `A`
/// at draft `d`) equal to the waves' energy about the depression it holds
/// plus what the sponge took; without them it heaves on undamped.
#[test]
fn a_heaving_cylinder_radiates_its_energy_into_the_waves() {
    let (r, segments, z0, dt) = (1.0, 64, 0.1, 1.0 / 60.0);
    let area = 0.5 * segments as f64 * r * r * (2.0 * std::f64::consts::PI / segments as f64).sin();
    let atlas = Atlas::bake(&builtin::cylinder(r, 1.0, segments), BakeOptions::square(256)).unwrap();
    let rule = WaveCoupling {
        size: 32.0,
        cells: 128,
        ..WaveCoupling::default()
    };
    println!(
        "| waves | t (s) | heave amplitude over the last 2 s (m) | energy the cylinder lost (J) | in the waves (J) | ratio |"
    );
    println!("|---|---|---|---|---|---|");
    let mut late = [0.0; 2];
    for (i, waves) in [None, Some(rule)].into_iter().enumerate() {
        let mut world = PhysicsWorld::new();
        world.integration_parameters.dt = dt as f32;
        let handle = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, -z0 as f32, 0.0))
                .enabled_translations(false, true, false)
                .lock_rotations(),
        );
        let mut soak = ForceGenerator::new(Water::calm(0.0));
        if let Some(w) = waves {
            soak = soak.with_waves(w).unwrap();
        }
        soak.register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "cylinder".into(),
                atlas: atlas.clone().into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects: Effects::buoyancy(),
            },
        )
        .unwrap();
        let g = -world.gravity.y as f64;
        let m = world.bodies[handle].mass() as f64;
        let energy = |w: &PhysicsWorld| {
            let rb = &w.bodies[handle];
            let (y, v) = (rb.translation().y as f64, rb.linvel().y as f64);
            0.5 * m * v * v + m * g * y + 0.5 * RHO * g * area * (0.5 - y).powi(2)
        };
        let start = energy(&world);
        let mut amplitude: f64 = 0.0;
        for step in 1..=600 {
            soak.step(&mut world).unwrap();
            amplitude = amplitude.max(world.bodies[handle].translation().y.abs() as f64);
            if step % 120 == 0 {
                let lost = start - energy(&world);
                let radiated = soak
                    .waves()
                    .map_or(0.0, |w| w.energy_about(&[soak.pressed(SoakId(0))]) + w.absorbed());
                let on = waves.is_some();
                let ratio = if on { radiated / lost } else { f64::NAN };
                println!(
                    "| {} | {:.0} | {amplitude:.4} | {lost:.1} | {radiated:.1} | {ratio:.3} |",
                    if on { "on" } else { "off" },
                    step as f64 * dt
                );
                if on && step >= 240 {
                    assert!(
                        (ratio - 1.0).abs() < 0.1,
                        "t {}: {radiated} J of {lost} J",
                        step as f64 * dt
                    );
                }
                late[i] = amplitude;
                amplitude = 0.0;
            }
        }
    }
    assert!(late[0] > 0.9 * z0, "without waves: {}", late[0]);
    assert!(late[1] < 0.2 * z0, "with waves: {}", late[1]);
}

/// A ball (r = 0.5 m, floating half under) towed along +x at 1.5 and
/// 2.5 m/s for 40 m (its speed eased in over 4 s), heave and turning
/// locked: the wake's half-angle 11 to 20 m behind it is Kelvin's 19.47°.
#[test]
fn a_towed_ball_leaves_a_kelvin_wake_through_rapier() {
    let dt = 1.0 / 30.0;
    println!("| speed (m/s) | 11 m behind | 14 m | 17 m | 20 m | mean (°) | Kelvin (°) |");
    println!("|---|---|---|---|---|---|---|");
    for speed in [1.5, 2.5] {
        let start = -24.0;
        let builder = RigidBodyBuilder::dynamic()
            .translation(Vector::new(start as f32, 0.0, 0.0))
            .enabled_translations(true, false, false)
            .lock_rotations();
        let rule = WaveCoupling {
            follow: false,
            ..WaveCoupling::default()
        };
        let (mut world, mut soak, handle) = ball_world(0.5, 500.0, builder, Some(rule), dt);
        let steps = (40.0 / speed / dt) as usize;
        let mut x = start;
        for k in 0..steps {
            let t = (k as f64 + 0.5) * dt;
            let ease = (t / 4.0).min(1.0);
            let u = speed * ease * ease * (3.0 - 2.0 * ease);
            world.bodies[handle].set_linvel(Vector::new(u as f32, 0.0, 0.0), true);
            soak.step(&mut world).unwrap();
            x = world.bodies[handle].translation().x as f64;
        }
        let waves = soak.waves().unwrap();
        let angles: Vec<f64> = [11.0, 14.0, 17.0, 20.0]
            .iter()
            .map(|&s| waves.wake_half_angle([x, 0.0], 0.0, s))
            .collect();
        let mean = angles.iter().sum::<f64>() / angles.len() as f64;
        println!(
            "| {speed} | {:.1} | {:.1} | {:.1} | {:.1} | {mean:.2} | 19.47 |",
            angles[0], angles[1], angles[2], angles[3]
        );
        assert!((mean - 19.47).abs() < 2.0, "{speed} m/s: {mean}°");
    }
}

/// A stone (a ball r = 0.5 m of 2,500 kg/m³) dropped from 1 m into still
/// water: the ring it sends out as it goes in has its crests where the
/// deep-water group velocity carries each wavelength, `r = ½ √(g/k) t`
/// (stationary phase: `g t²/(4r)` grows by 2π from one crest to the next
/// inwards). Read inside the leading crest (the displaced volume's mean
/// rise, not a wave train).
#[test]
fn a_dropped_stones_ring_spreads_at_the_group_velocity() {
    let dt = 1.0 / 60.0;
    let builder = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, 1.0, 0.0))
        .enabled_translations(false, true, false)
        .lock_rotations();
    let rule = WaveCoupling {
        follow: false,
        ..WaveCoupling::default()
    };
    let (mut world, mut soak, handle) = ball_world(0.5, 2500.0, builder, Some(rule), dt);
    let g = -world.gravity.y as f64;
    // The stone meets the water when its bottom does.
    let mut impact = None;
    let mut checked = 0;
    println!("| t after impact (s) | crest r (m) | next crest r (m) | Δ(g t²/4r) / 2π |");
    println!("|---|---|---|---|");
    for step in 1..=(13.0 / dt) as usize {
        soak.step(&mut world).unwrap();
        let time = step as f64 * dt;
        if impact.is_none() && world.bodies[handle].translation().y < 0.5 {
            impact = Some(time);
        }
        let Some(t0) = impact else { continue };
        let t = time - t0;
        if ![6.0, 8.0, 10.0, 12.0]
            .iter()
            .any(|&s: &f64| (t - s).abs() < 0.5 * dt)
        {
            continue;
        }
        let crests = soak.waves().unwrap().crests([0.0, 0.0], 0.0, 2.0, 24.0);
        // Inside the leading crest; waves of six cells and more.
        let inside = crests.len().saturating_sub(1);
        for (r1, r2, ratio) in InteractiveWaves::phase_steps(&crests[..inside], t, g, 6.0 * 0.25) {
            println!("| {t:.2} | {r1:.2} | {r2:.2} | {ratio:.3} |");
            assert!(
                (ratio - 1.0).abs() < 0.1,
                "t {t}: crests at {r1} and {r2}: {ratio}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 4, "{checked} crest pairs");
}

/// A region the waves cannot have is refused by name.
#[test]
fn a_bad_wave_region_is_refused() {
    for rule in [
        WaveCoupling {
            cells: 7,
            ..WaveCoupling::default()
        },
        WaveCoupling {
            size: f64::NAN,
            ..WaveCoupling::default()
        },
        WaveCoupling {
            sponge: 100,
            ..WaveCoupling::default()
        },
        WaveCoupling {
            cells: 1 << 20,
            ..WaveCoupling::default()
        },
    ] {
        let err = ForceGenerator::new(Water::calm(0.0))
            .with_waves(rule)
            .unwrap_err();
        assert!(matches!(err, SoakError::Waves(_)), "{err}");
        assert!(err.to_string().starts_with("waves: "), "{err}");
    }
}

/// One body on the waves at `pose`, its motion as `builder` allows, for
/// `steps` steps of `dt`: the body's path (its centre's height per step).
fn run_on_waves(
    mesh: soak_bake::Mesh,
    density: f64,
    builder: RigidBodyBuilder,
    rule: Option<WaveCoupling>,
    dt: f64,
    steps: usize,
) -> Vec<f64> {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt as f32;
    let handle = world.bodies.insert(builder);
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    if let Some(rule) = rule {
        soak = soak.with_waves(rule).unwrap();
    }
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "body".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density },
            effects: Effects::buoyancy(),
        },
    )
    .unwrap();
    (0..steps)
        .map(|_| {
            soak.step(&mut world).unwrap();
            let rb = &world.bodies[handle];
            let p = rb.translation();
            assert!(p.x.is_finite() && p.y.is_finite() && p.z.is_finite());
            if let Some(w) = soak.waves() {
                assert!(w.heights().iter().all(|h| h.is_finite()));
            }
            p.y as f64
        })
        .collect()
}

/// Hard cases on the waves: the heaving cylinder at 1/10 s and 1/30 s
/// steps (let go 0.1 m down, it stays within 0.15 m and dies away: the
/// waves' push comes a step late, and at 1/10 s its first rebound
/// overshoots to 0.127 m); a body larger than the waves' region; a
/// body smaller than a cell; a body outside the region, which floats as on
/// the water without waves, bit for bit; a dense stone dropped from 5 m
/// at 1/10 s. All finite and bounded.
#[test]
fn hard_cases_on_the_waves_stay_finite_and_bounded() {
    let free_heave = |y: f32| {
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, y, 0.0))
            .enabled_translations(false, true, false)
            .lock_rotations()
    };
    let small = WaveCoupling {
        size: 32.0,
        cells: 128,
        ..WaveCoupling::default()
    };
    println!("| case | lowest y (m) | highest y (m) | last y (m) |");
    println!("|---|---|---|---|");
    let show = |case: &str, ys: &[f64]| {
        let lo = ys.iter().copied().fold(f64::MAX, f64::min);
        let hi = ys.iter().copied().fold(f64::MIN, f64::max);
        println!("| {case} | {lo:.4} | {hi:.4} | {:.4} |", ys[ys.len() - 1]);
        (lo, hi)
    };
    for dt in [0.1, 1.0 / 30.0] {
        let steps = (20.0 / dt) as usize;
        let ys = run_on_waves(
            builtin::cylinder(1.0, 1.0, 64),
            500.0,
            free_heave(-0.1),
            Some(small),
            dt,
            steps,
        );
        let (lo, hi) = show(&format!("cylinder heaving, dt {dt:.3} s"), &ys);
        assert!(lo > -0.15 && hi < 0.15, "{lo} {hi}");
        let late = ys[ys.len() / 2..].iter().fold(0.0_f64, |a, y| a.max(y.abs()));
        assert!(late < 0.1, "dt {dt}: still {late} m after 10 s");
    }
    // A 100 m × 2 m × 100 m raft on a 32 m region, half as dense as water.
    let ys = run_on_waves(
        builtin::cuboid(100.0, 2.0, 100.0),
        500.0,
        free_heave(0.0),
        Some(small),
        1.0 / 60.0,
        300,
    );
    let (lo, hi) = show("raft 100 m wide on a 32 m region", &ys);
    assert!(lo > -0.5 && hi < 0.5, "{lo} {hi}");
    // A 1 cm ball on 0.25 m cells.
    let ys = run_on_waves(
        builtin::sphere(0.01, 16, 8),
        500.0,
        free_heave(0.0),
        Some(small),
        1.0 / 60.0,
        300,
    );
    let (lo, hi) = show("1 cm ball on 25 cm cells", &ys);
    assert!(lo > -0.02 && hi < 0.02, "{lo} {hi}");
    // Outside the region: the same path as without waves, bit for bit.
    let away = |y: f32| {
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(500.0, y, 0.0))
            .enabled_translations(false, true, false)
            .lock_rotations()
    };
    let fixed = WaveCoupling {
        follow: false,
        ..small
    };
    let on = run_on_waves(
        builtin::sphere(0.5, 32, 16),
        500.0,
        away(-0.1),
        Some(fixed),
        1.0 / 60.0,
        120,
    );
    let off = run_on_waves(
        builtin::sphere(0.5, 32, 16),
        500.0,
        away(-0.1),
        None,
        1.0 / 60.0,
        120,
    );
    assert_eq!(on, off);
    // A stone dropped from 5 m at 1/10 s: it goes in and sinks.
    let ys = run_on_waves(
        builtin::sphere(0.3, 32, 16),
        2500.0,
        free_heave(5.0),
        Some(small),
        0.1,
        60,
    );
    let (_, hi) = show("stone dropped from 5 m, dt 0.1 s", &ys);
    assert!(hi <= 5.0 && ys[ys.len() - 1] < -1.0, "{ys:?}");
}
