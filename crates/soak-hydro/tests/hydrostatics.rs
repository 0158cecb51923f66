//! Buoyancy and drag from texel sums against exact clipping and physics.
//!
//! One file on purpose: its tests share the fixtures and the comparison
//! helpers against exact clipping; each test names the case it checks.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin, load_mesh};
use soak_hydro::reference::{self, ClipPlane, analytic};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, Gerstner, GerstnerWave, HydroForces, HydroOptions, MassModel,
    MassProperties, Plane, SeaBand, SeaSampling, SeaVelocity, TiledAtlas, Water, evaluate,
};

const RHO: f64 = 1000.0;
const G: f64 = 9.80665;
/// Pressure mode, with the other options at their defaults.
const PRESSURE: HydroOptions = HydroOptions {
    buoyancy: BuoyancyMode::Pressure,
    drag: None,
    dt: 1.0 / 60.0,
    sea: SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH),
    sea_velocity: SeaVelocity::PerTile,
    sea_band: SeaBand::Full,
    added_mass: None,
};

/// A small deterministic generator for poses.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn pose(&mut self, spread: f64) -> Isometry3<f64> {
        let q = UnitQuaternion::from_euler_angles(
            self.range(-3.1, 3.1),
            self.range(-1.5, 1.5),
            self.range(-3.1, 3.1),
        );
        Isometry3::from_parts(
            Translation3::new(
                self.range(-1.0, 1.0),
                self.range(-spread, spread),
                self.range(-1.0, 1.0),
            ),
            q,
        )
    }
}

fn bake(mesh: &Mesh, res: u32) -> Atlas {
    Atlas::bake(mesh, BakeOptions::square(res)).unwrap()
}

fn solid(atlas: &Atlas) -> MassProperties {
    MassModel::Solid { density: 500.0 }
        .mass_properties(atlas)
        .unwrap()
}

fn at(atlas: &Atlas, water: &Water, pose: Isometry3<f64>, opts: &HydroOptions) -> HydroForces {
    evaluate(atlas, water, &BodyState::at_rest(pose), &solid(atlas), 0.0, opts).unwrap()
}

#[test]
fn sphere_submerged_volume_within_0_2_percent_at_1024_and_the_baseline_is_far_off() {
    let r = 0.5;
    let mesh = builtin::sphere(r, 64, 32);
    let atlas = bake(&mesh, 1024);
    let full = mesh.volume();
    let water = Water::calm(0.0);
    let mut worst: f64 = 0.0;
    let mut baseline_worst: f64 = 0.0;
    for k in 0..=20 {
        // Water level relative to the centre from −0.5 (dry) to 0.5 (submerged).
        let level = -0.5 + k as f64 * 0.05;
        let pose = Isometry3::translation(0.0, -level, 0.0);
        let f = at(&atlas, &water, pose, &HydroOptions::default());
        let exact = reference::submerged_part(&mesh, &pose, &ClipPlane::horizontal(0.0));
        worst = worst.max((f.submerged_volume - exact.volume).abs() / full);
        let base = reference::per_triangle_buoyancy(&mesh, &pose, &ClipPlane::horizontal(0.0), RHO, G);
        baseline_worst = baseline_worst.max((base.volume - exact.volume).abs() / full);
        if exact.volume > 1e-3 * full {
            let cb = (f.center_of_buoyancy - exact.centroid).norm() / (2.0 * r);
            assert!(
                cb < 2e-3,
                "level {level}: centre of buoyancy off by {cb} of the diameter"
            );
        }
    }
    assert!(worst < 0.002, "worst texel error {worst}");
    assert!(
        baseline_worst > 0.2,
        "the per-triangle baseline error is {baseline_worst}"
    );
    // Fine mesh: also within 0.2 % of the analytic sphere cap.
    let fine = builtin::sphere(r, 256, 128);
    let atlas = bake(&fine, 1024);
    for k in 0..=10 {
        let level = -0.5 + k as f64 * 0.1;
        let f = at(
            &atlas,
            &water,
            Isometry3::translation(0.0, -level, 0.0),
            &HydroOptions::default(),
        );
        let cap = analytic::sphere_submerged(r, level);
        let full = 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        assert!(
            (f.submerged_volume - cap.volume).abs() / full < 0.002,
            "level {level}"
        );
    }
}

#[test]
fn pressure_mode_equals_archimedes_on_a_plane() {
    let mut rng = Lcg(7);
    for name in [
        "builtin:boat",
        "builtin:torus",
        "builtin:box:4x1x1",
        "builtin:capsule",
    ] {
        let mesh = load_mesh(name).unwrap();
        let atlas = bake(&mesh, 512);
        let diameter = 2.0 * atlas.bounding_radius();
        for _ in 0..10 {
            let pose = rng.pose(0.6);
            let a = at(&atlas, &Water::calm(0.1), pose, &HydroOptions::default()).buoyancy;
            let p = at(&atlas, &Water::calm(0.1), pose, &PRESSURE).buoyancy;
            let mag = a.force.norm();
            if mag < 1.0 {
                continue;
            }
            assert!(
                (a.force - p.force).norm() / mag < 1e-3,
                "{name}: {} vs {}",
                a.force,
                p.force
            );
            let t = (a.torque - p.torque).norm() / (mag * diameter);
            assert!(t < 5e-3, "{name}: torque differs by {t} of |F|·diameter");
        }
    }
}

#[test]
fn on_a_wave_slope_pressure_pushes_sideways_and_archimedes_does_not() {
    let sea = Gerstner::new(
        0.0,
        vec![GerstnerWave {
            amplitude: 0.4,
            wavelength: 6.0,
            direction_deg: 0.0,
            steepness: 0.6,
            phase: 0.0,
        }],
        G,
    )
    .unwrap();
    let water = Water::new(sea);
    let atlas = bake(&builtin::sphere(0.5, 64, 32), 512);
    // A quarter wavelength from the crest the surface slopes; x = 1.5 m at t = 0.
    let pose = Isometry3::translation(1.5, 0.0, 0.0);
    let archimedes = at(&atlas, &water, pose, &HydroOptions::default()).buoyancy;
    let pressure = at(&atlas, &water, pose, &PRESSURE).buoyancy;
    assert_eq!(archimedes.force.x, 0.0);
    assert_eq!(archimedes.force.z, 0.0);
    let side = pressure.force.x.abs() / pressure.force.y;
    assert!(side > 0.05, "pressure mode has only {side} sideways");
    // And it pushes down the slope: the surface falls towards +x there.
    let h = |x: f64| soak_hydro::Surface::height(&*water.surface, x, 0.0, 0.0);
    let slope = (h(1.51) - h(1.49)) / 0.02;
    assert!(
        slope.signum() != pressure.force.x.signum(),
        "slope {slope}, force {}",
        pressure.force.x
    );
}

#[test]
fn tiled_equals_per_texel_at_arbitrary_poses() {
    let mut rng = Lcg(11);
    for name in [
        "builtin:sphere",
        "builtin:boat",
        "builtin:torus",
        "builtin:dumbbell",
    ] {
        let mesh = load_mesh(name).unwrap();
        let atlas = bake(&mesh, 256);
        let tiled = TiledAtlas::new(&atlas);
        let mass = solid(&atlas);
        for k in 0..20 {
            let state = BodyState {
                pose: rng.pose(0.8),
                linear_velocity: Vector3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.3),
                angular_velocity: Vector3::new(0.2, rng.range(-1.0, 1.0), 0.1),
            };
            let water = if k % 2 == 0 {
                Water::calm(rng.range(-0.3, 0.3))
            } else {
                Water::new(Plane::tilted(Point3::new(0.0, 0.1, 0.0), Vector3::new(0.1, 1.0, -0.2)).unwrap())
            };
            // Both modes: the tiles' closed forms and the cut tiles' texels
            // take Archimedes' sums in one and the pressure sums in the other.
            for mode in [BuoyancyMode::Archimedes, BuoyancyMode::Pressure] {
                let opts = HydroOptions {
                    buoyancy: mode,
                    drag: Some(Drag {
                        coefficient: 0.8,
                        linear: 0.3,
                    }),
                    ..Default::default()
                };
                let a = evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap();
                let b = tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap();
                let scale = a.buoyancy.force.norm().max(1.0);
                let close = |x: f64, y: f64, s: f64| (x - y).abs() <= 1e-6 * s.max(1e-12);
                assert!(
                    close(a.submerged_volume, b.submerged_volume, mesh.volume()),
                    "{name}"
                );
                assert_eq!(a.submerged_texels, b.submerged_texels, "{name}");
                // Component by component, on the force's scale and on the
                // torque's (that force times the radius).
                let same = |u: &Vector3<f64>, v: &Vector3<f64>, s: f64| {
                    for (x, y) in u.iter().zip(v.iter()) {
                        assert!(close(*x, *y, s), "{name} {mode:?}: {u} vs {v}");
                    }
                };
                same(&a.buoyancy.force, &b.buoyancy.force, scale);
                same(
                    &a.buoyancy.torque,
                    &b.buoyancy.torque,
                    scale * atlas.bounding_radius(),
                );
                if a.submerged_volume > 1e-6 {
                    assert!(
                        (a.center_of_buoyancy - b.center_of_buoyancy).norm() < 1e-6 * atlas.bounding_radius()
                    );
                }
                assert!((a.drag.force - b.drag.force).norm() <= 1e-6 * a.drag.force.norm().max(1e-9));
            }
        }
    }
}

/// Compares with the exact clipping reference at one pose.
fn check_exact(mesh: &Mesh, atlas: &Atlas, pose: Isometry3<f64>, level: f64, what: &str) {
    let f = at(atlas, &Water::calm(level), pose, &HydroOptions::default());
    let exact = reference::submerged_part(mesh, &pose, &ClipPlane::horizontal(level));
    let v = mesh.volume();
    assert!(
        f.submerged_volume.is_finite() && f.center_of_buoyancy.iter().all(|c| c.is_finite()),
        "{what}"
    );
    let p = at(atlas, &Water::calm(level), pose, &PRESSURE);
    assert!(f.buoyancy.is_finite() && p.buoyancy.is_finite(), "{what}");
    assert!(
        (f.submerged_volume - exact.volume).abs() / v < 2e-3,
        "{what}: {} vs {}",
        f.submerged_volume,
        exact.volume
    );
    if exact.volume > 1e-2 * v {
        let d = (f.center_of_buoyancy - exact.centroid).norm() / mesh.diagonal();
        assert!(d < 2e-3, "{what}: centre of buoyancy off by {d} of the diagonal");
    }
}

#[test]
fn hard_cases_waterline_dry_submerged_upside_down() {
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let atlas = bake(&mesh, 512);
    let v = mesh.volume();
    // Exactly at the waterline: the deck is in the surface plane.
    check_exact(
        &mesh,
        &atlas,
        Isometry3::translation(0.0, -0.6, 0.0),
        0.0,
        "deck at the waterline",
    );
    // Keel touching the water only.
    let f = at(
        &atlas,
        &Water::calm(0.0),
        Isometry3::identity(),
        &HydroOptions::default(),
    );
    assert_eq!(f.submerged_volume, 0.0);
    assert_eq!(f.buoyancy.force, Vector3::zeros());
    // Fully dry, far above.
    let f = at(
        &atlas,
        &Water::calm(0.0),
        Isometry3::translation(0.0, 50.0, 0.0),
        &HydroOptions::default(),
    );
    assert_eq!(f.submerged_volume, 0.0);
    assert!(f.center_of_buoyancy.iter().all(|c| c.is_finite()));
    // Fully submerged: the whole volume, centre of buoyancy at the centroid.
    let pose = Isometry3::translation(0.0, -30.0, 0.0);
    let f = at(&atlas, &Water::calm(0.0), pose, &HydroOptions::default());
    assert!((f.submerged_volume - v).abs() / v < 1e-6);
    let exact = reference::solid_mass_properties(&mesh, 1.0);
    assert!((f.center_of_buoyancy - pose * exact.centroid).norm() < 1e-5);
    // Upside down, half in.
    let flip = Isometry3::from_parts(
        Translation3::new(0.0, 0.3, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
    );
    check_exact(&mesh, &atlas, flip, 0.0, "upside down");
}

#[test]
fn hard_cases_waterline_through_a_vertex_and_along_an_edge() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    let atlas = bake(&mesh, 256);
    // A corner straight down: the waterline through the vertex, then a bit above it.
    let corner_down =
        UnitQuaternion::rotation_between(&Vector3::new(-1.0, -1.0, -1.0), &-Vector3::y()).unwrap();
    let depth_of_corner = 3f64.sqrt() / 2.0;
    for dz in [0.0, 1e-9, 0.1, depth_of_corner] {
        let pose = Isometry3::from_parts(Translation3::new(0.0, depth_of_corner - dz, 0.0), corner_down);
        check_exact(&mesh, &atlas, pose, 0.0, &format!("corner down, {dz} m in"));
    }
    // An edge along the waterline: rotated 45° about z, edge at depth 0.
    let edge_down = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_4);
    let half_diag = 2f64.sqrt() / 2.0;
    for level in [0.0, half_diag, 0.3] {
        let pose = Isometry3::from_parts(Translation3::new(0.0, half_diag, 0.0), edge_down);
        check_exact(&mesh, &atlas, pose, level, &format!("edge down, level {level}"));
    }
}

#[test]
fn hard_cases_tiny_and_huge_scales() {
    for s in [1e-3, 1.0, 1e3] {
        let mesh = builtin::sphere(0.5 * s, 48, 24);
        let atlas = bake(&mesh, 512);
        let pose = Isometry3::translation(0.0, 0.1 * s, 0.0);
        check_exact(&mesh, &atlas, pose, 0.0, &format!("scale {s}"));
        let f = at(&atlas, &Water::calm(0.0), pose, &HydroOptions::default());
        let exact = reference::submerged_part(&mesh, &pose, &ClipPlane::horizontal(0.0));
        let rel = (f.buoyancy.force.y - RHO * G * exact.volume).abs() / (RHO * G * mesh.volume());
        assert!(rel < 2e-3, "scale {s}: {rel}");
    }
}

#[test]
fn unbounded_air_immerses_everything() {
    let mesh = builtin::sphere(1.0, 64, 32);
    let atlas = bake(&mesh, 256);
    for y in [-100.0, 0.0, 1e4] {
        let f = at(
            &atlas,
            &Water::air(),
            Isometry3::translation(0.0, y, 0.0),
            &HydroOptions::default(),
        );
        assert!((f.submerged_volume - mesh.volume()).abs() / mesh.volume() < 1e-6);
        assert!((f.buoyancy.force.y - 1.2 * G * f.submerged_volume).abs() < 1e-6);
        assert!((f.center_of_buoyancy - Point3::new(0.0, y, 0.0)).norm() < 1e-4 * (1.0 + y.abs()));
    }
}

#[test]
fn drag_of_a_flat_plate_is_half_rho_cd_a_v_squared() {
    // A 1 m × 1 m plate, 1 cm thick, moving along its normal deep under water.
    let plate = builtin::cuboid(1.0, 0.01, 1.0);
    let atlas = bake(&plate, 256);
    let mass = solid(&atlas);
    for (v, cd) in [(0.5, 1.0), (2.0, 1.17), (-3.0, 0.9)] {
        let state = BodyState {
            pose: Isometry3::translation(0.0, -5.0, 0.0),
            linear_velocity: Vector3::new(0.0, v, 0.0),
            angular_velocity: Vector3::zeros(),
        };
        let opts = HydroOptions {
            buoyancy: BuoyancyMode::Off,
            drag: Some(Drag {
                coefficient: cd,
                linear: 0.0,
            }),
            dt: 0.0,
            ..HydroOptions::default()
        };
        let f = evaluate(&atlas, &Water::calm(0.0), &state, &mass, 0.0, &opts).unwrap();
        let expected = -0.5 * RHO * cd * 1.0 * v * v * v.signum();
        let got = f.drag_explicit.force.y;
        assert!(
            (got - expected).abs() / expected.abs() < 1e-4,
            "v {v}: {got} vs {expected}"
        );
        assert!(f.drag_explicit.force.x.abs() < 1e-6 * expected.abs());
        assert!(f.drag_explicit.torque.norm() < 1e-4 * expected.abs());
    }
}

#[test]
fn drag_never_reverses_the_relative_velocity() {
    let mesh = builtin::sphere(0.5, 48, 24);
    let atlas = bake(&mesh, 256);
    let mut rng = Lcg(3);
    for dt in [1.0 / 240.0, 1.0 / 60.0, 1.0 / 15.0, 0.1] {
        for rel_density in [0.01, 0.1, 1.0, 10.0] {
            let mass = MassModel::Solid {
                density: 1000.0 * rel_density,
            }
            .mass_properties(&atlas)
            .unwrap();
            let inv_inertia = mass.inertia.try_inverse().unwrap();
            for _ in 0..20 {
                let v = Vector3::new(
                    rng.range(-20.0, 20.0),
                    rng.range(-20.0, 20.0),
                    rng.range(-20.0, 20.0),
                );
                let w = Vector3::new(
                    rng.range(-30.0, 30.0),
                    rng.range(-30.0, 30.0),
                    rng.range(-30.0, 30.0),
                );
                let state = BodyState {
                    pose: Isometry3::translation(0.0, -3.0, 0.0),
                    linear_velocity: v,
                    angular_velocity: w,
                };
                let opts = HydroOptions {
                    buoyancy: BuoyancyMode::Off,
                    drag: Some(Drag {
                        coefficient: 1.2,
                        linear: 5.0,
                    }),
                    dt,
                    ..HydroOptions::default()
                };
                let f = evaluate(&atlas, &Water::calm(0.0), &state, &mass, 0.0, &opts).unwrap();
                let v1 = v + f.drag.force * dt / mass.mass;
                let w1 = w + inv_inertia * f.drag.torque * dt;
                // In the mass metric the step is a contraction: kinetic energy
                // never grows and the generalised velocity never reverses.
                let ke = |v: &Vector3<f64>, w: &Vector3<f64>| {
                    mass.mass * v.norm_squared() + w.dot(&(mass.inertia * w))
                };
                let cross = mass.mass * v1.dot(&v) + w1.dot(&(mass.inertia * w));
                assert!(
                    ke(&v1, &w1) <= ke(&v, &w) * (1.0 + 1e-9),
                    "dt {dt} s {rel_density}: energy grew"
                );
                assert!(cross >= 0.0, "dt {dt} s {rel_density}: velocity reversed");
                // The naive explicit impulse would overshoot for light bodies and long steps.
                if rel_density == 0.01 && dt >= 1.0 / 15.0 {
                    let naive = v + f.drag_explicit.force * dt / mass.mass;
                    assert!(naive.dot(&v) < 0.0, "explicit drag should reverse here");
                }
            }
        }
    }
}

#[test]
fn drag_never_reverses_a_pure_translation_or_rotation() {
    let atlas = bake(&builtin::boat(4.0, 1.2, 0.6), 256);
    for dt in [1.0 / 240.0, 1.0 / 60.0, 0.1] {
        for rel_density in [0.01, 1.0] {
            let mass = MassModel::Solid {
                density: 1000.0 * rel_density,
            }
            .mass_properties(&atlas)
            .unwrap();
            let inv_inertia = mass.inertia.try_inverse().unwrap();
            let opts = HydroOptions {
                buoyancy: BuoyancyMode::Off,
                drag: Some(Drag {
                    coefficient: 1.2,
                    linear: 5.0,
                }),
                dt,
                ..HydroOptions::default()
            };
            for dir in [
                Vector3::x(),
                Vector3::y(),
                -Vector3::z(),
                Vector3::new(1.0, -2.0, 0.5),
            ] {
                let pose = Isometry3::translation(0.0, -5.0, 0.0);
                let v = dir * 10.0;
                let s = BodyState {
                    pose,
                    linear_velocity: v,
                    angular_velocity: Vector3::zeros(),
                };
                let f = evaluate(&atlas, &Water::calm(0.0), &s, &mass, 0.0, &opts).unwrap();
                let v1 = v + f.drag.force * dt / mass.mass;
                assert!(v1.dot(&v) >= 0.0 && v1.norm() <= v.norm(), "dt {dt}: {v} -> {v1}");
                let w = dir * 10.0;
                let s = BodyState {
                    pose,
                    linear_velocity: Vector3::zeros(),
                    angular_velocity: w,
                };
                let f = evaluate(&atlas, &Water::calm(0.0), &s, &mass, 0.0, &opts).unwrap();
                let w1 = w + inv_inertia * f.drag.torque * dt;
                assert!(w1.dot(&(mass.inertia * w)) >= 0.0, "dt {dt}: {w} -> {w1}");
            }
        }
    }
}

#[test]
fn drag_follows_the_water_not_the_world() {
    // A body at rest in a current is pushed along with it; moving with the
    // current it feels nothing.
    let atlas = bake(&builtin::sphere(0.5, 32, 16), 128);
    let mass = solid(&atlas);
    let current = Vector3::new(1.5, 0.0, 0.0);
    let water = Water::new(Plane::horizontal(10.0).with_current(current));
    let opts = HydroOptions {
        buoyancy: BuoyancyMode::Off,
        drag: Some(Drag::default()),
        dt: 0.0,
        ..HydroOptions::default()
    };
    let rest = BodyState::at_rest(Isometry3::identity());
    let f = evaluate(&atlas, &water, &rest, &mass, 0.0, &opts).unwrap();
    assert!(f.drag_explicit.force.x > 0.0);
    let along = BodyState {
        linear_velocity: current,
        ..rest
    };
    let f = evaluate(&atlas, &water, &along, &mass, 0.0, &opts).unwrap();
    assert!(f.drag_explicit.force.norm() < 1e-9);
}

#[test]
fn bad_state_and_water_are_refused() {
    let atlas = bake(&builtin::sphere(0.5, 16, 8), 64);
    let mass = solid(&atlas);
    let mut state = BodyState::at_rest(Isometry3::identity());
    state.linear_velocity.x = f64::NAN;
    let e = evaluate(
        &atlas,
        &Water::calm(0.0),
        &state,
        &mass,
        0.0,
        &HydroOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "body state `linear_velocity` is not finite");
    let water = Water::calm(0.0).with_density(-1.0);
    let e = evaluate(
        &atlas,
        &water,
        &BodyState::at_rest(Isometry3::identity()),
        &mass,
        0.0,
        &HydroOptions::default(),
    );
    assert!(e.is_err());
    assert!(Plane::tilted(Point3::origin(), Vector3::new(1.0, 0.0, 0.0)).is_err());
    assert!(
        Gerstner::new(
            0.0,
            vec![GerstnerWave {
                amplitude: 1.0,
                wavelength: -2.0,
                direction_deg: 0.0,
                steepness: 0.5,
                phase: 0.0
            }],
            G
        )
        .is_err()
    );
}

/// The columns' potential `Σ −A_y d²/2` (m⁴) of the atlas at `pose`, summed
/// here from the surface's heights alone: the energy the water stores.
fn columns_potential(atlas: &Atlas, water: &Water, pose: &Isometry3<f64>) -> f64 {
    let mut u = 0.0;
    for (i, a) in atlas.area_vectors().iter().enumerate() {
        let p = pose * atlas.position(i);
        let d = water.surface.depth(&p, 0.0);
        if d > 0.0 {
            let ay = (pose.rotation * Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64)).y;
            u -= ay * d * d / 2.0;
        }
    }
    u
}

/// `−ρ g ∂U/∂θ` about the three world axes through `com`, `U` the columns'
/// potential of [`columns_potential`], by central differences of turns of
/// `eps` rad: the torque that conserves the water's energy.
fn potential_torque(
    atlas: &Atlas,
    water: &Water,
    pose: &Isometry3<f64>,
    com: &nalgebra::Point3<f64>,
    eps: f64,
) -> Vector3<f64> {
    let turned = |axis: Vector3<f64>, angle: f64| {
        let q = UnitQuaternion::from_scaled_axis(axis * angle);
        Isometry3::from_parts(Translation3::from(com.coords - q * com.coords), q) * pose
    };
    Vector3::from_fn(|k, _| {
        let axis = Vector3::ith(k, 1.0);
        let up = columns_potential(atlas, water, &turned(axis, eps));
        let down = columns_potential(atlas, water, &turned(axis, -eps));
        -RHO * G * (up - down) / (2.0 * eps)
    })
}

/// Over a surface that is not flat, Archimedes' torque is minus the
/// derivative of the columns' potential under a turn about the centre of
/// mass (central differences of [`columns_potential`], summed independently
/// from the surface's heights): what makes a floating body rocking over
/// waves or a step keep its energy. `ρ g V_s` at the centre of buoyancy
/// alone, the torque before, is off by far more than the tolerance.
#[test]
fn archimedes_torque_is_the_derivative_of_the_columns_potential() {
    let sea = Water::new(
        Gerstner::new(
            0.0,
            vec![GerstnerWave {
                amplitude: 0.3,
                wavelength: 5.0,
                direction_deg: 20.0,
                steepness: 0.6,
                phase: 0.3,
            }],
            G,
        )
        .unwrap(),
    );
    // A smooth bump sampled every 0.1 m (bilinear between samples).
    let n = 41;
    let heights = (0..n * n)
        .map(|k| {
            let (x, z) = (-2.0 + 0.1 * (k % n) as f64, -2.0 + 0.1 * (k / n) as f64);
            0.25 * (-(x - 0.4).powi(2) - (z + 0.2).powi(2)).exp()
        })
        .collect();
    let bump = Water::new(soak_hydro::HeightField::new([-2.0, -2.0], [0.1, 0.1], n, n, heights).unwrap());
    let atlas = bake(&builtin::cuboid(1.0, 0.6, 0.8), 256);
    let mass = solid(&atlas);
    let pose = Isometry3::from_parts(
        Translation3::new(0.2, 0.05, -0.1),
        UnitQuaternion::from_euler_angles(0.15, 0.4, -0.1),
    );
    for (name, water) in [("Gerstner sea", &sea), ("height-field bump", &bump)] {
        let f = evaluate(
            &atlas,
            water,
            &BodyState::at_rest(pose),
            &mass,
            0.0,
            &HydroOptions::default(),
        )
        .unwrap();
        assert!(
            f.submerged_volume > 0.05 && f.submerged_volume < 0.4,
            "{name}: {}",
            f.submerged_volume
        );
        let com = pose * mass.center_of_mass;
        let fd = potential_torque(&atlas, water, &pose, &com, 1e-4);
        let scale = RHO * G * f.submerged_volume * atlas.bounding_radius();
        let err = (f.buoyancy.torque - fd).norm() / scale;
        assert!(
            err < 2e-3,
            "{name}: torque {:?}, −∂U/∂θ {fd:?}, error {err:.2e}",
            f.buoyancy.torque
        );
        let classic = (f.center_of_buoyancy - com).cross(&f.buoyancy.force);
        let off = (classic - fd).norm() / scale;
        assert!(
            off > 10.0 * err.max(1e-4),
            "{name}: the classic torque is off by only {off:.2e}"
        );
        eprintln!("{name}: error {err:.2e} of ρ g V_s r; the classic torque's {off:.2e}");
    }
}

/// On calm water too, Archimedes' torque is the derivative of the
/// potential of the columns the texels sample, whatever their placement: a
/// 200:1 rod at 64², whose long faces' triangles are one centroid sample
/// each, a sixth of the face's width off its middle line. Cut halfway along
/// by the water, the rod's centre of buoyancy sits off its axis, and the
/// classic torque of `ρ g V_s` there has a component along the rod that
/// the potential does not (it spun the rod's small roll inertia up).
#[test]
fn on_calm_water_archimedes_torque_is_the_derivative_of_the_sampled_potential() {
    let atlas = bake(&builtin::cuboid(2.0, 0.01, 0.01), 64);
    assert!(!atlas.centroid_samples().is_empty());
    let mass = solid(&atlas);
    let water = Water::calm(0.0);
    let pose = Isometry3::from_parts(
        Translation3::new(0.0, 0.03, 0.0),
        UnitQuaternion::from_euler_angles(3f64.to_radians(), 0.0, 5f64.to_radians()),
    );
    let f = evaluate(
        &atlas,
        &water,
        &BodyState::at_rest(pose),
        &mass,
        0.0,
        &HydroOptions::default(),
    )
    .unwrap();
    let volume = atlas.volume();
    assert!(
        f.submerged_volume > 0.2 * volume && f.submerged_volume < 0.8 * volume,
        "{} of {volume}",
        f.submerged_volume
    );
    let com = pose * mass.center_of_mass;
    let fd = potential_torque(&atlas, &water, &pose, &com, 1e-5);
    // Along the rod, on the scale of ρ g V_s times its width.
    let along = pose.rotation * Vector3::x();
    let scale = RHO * G * f.submerged_volume * 0.01;
    let err = (f.buoyancy.torque - fd).dot(&along).abs() / scale;
    let classic = (f.center_of_buoyancy - com).cross(&f.buoyancy.force);
    let off = (classic - fd).dot(&along).abs() / scale;
    eprintln!(
        "{:.3} submerged; along the rod: error {err:.2e} of ρ g V_s w; the classic torque's {off:.2e}",
        f.submerged_volume / volume
    );
    assert!(err < 1e-3, "torque {:?}, −∂U/∂θ {fd:?}", f.buoyancy.torque);
    assert!(off > 0.05, "the classic torque is off by only {off:.2e}");
    // And across it, on the scale of ρ g V_s times the rod's half length.
    let whole = (f.buoyancy.torque - fd).norm() / (RHO * G * f.submerged_volume);
    assert!(whole < 1e-3, "error {whole:.2e} of ρ g V_s · 1 m");
}

/// A height field with a step: `high` for x < 0 and `-high` for x > 0, the
/// change between two samples `spacing` apart (bilinear between them).
fn cliff(high: f64, spacing: f64) -> Water {
    let n = 41;
    let origin = -spacing * ((n - 1) / 2) as f64 - 0.5 * spacing;
    let heights = (0..n * n)
        .map(|k| if k % n < n / 2 { high } else { -high })
        .collect();
    Water::new(soak_hydro::HeightField::new([origin, origin], [spacing, spacing], n, n, heights).unwrap())
}

/// `Σ −A_y d` over the texels under water and the smallest depth of any
/// texel, summed here from the surface's depths alone.
fn sampled_volume(atlas: &Atlas, water: &Water, pose: &Isometry3<f64>) -> (f64, f64) {
    let mut volume = 0.0;
    let mut shallowest = f64::INFINITY;
    for (i, a) in atlas.area_vectors().iter().enumerate() {
        let p = pose * atlas.position(i);
        let d = water.surface.depth(&p, 0.0);
        shallowest = shallowest.min(d);
        if d > 0.0 {
            let ay = (pose.rotation * Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64)).y;
            volume -= ay * d;
        }
    }
    (volume, shallowest)
}

/// Wholly under a surface that is not a plane, `Σ −A_y d` carries the
/// sampling error of `∮ h n_y dA`, which is zero for a closed surface: a
/// 200:1 rod at 32² (one centroid sample per long triangle) pitched across
/// a cliff's step as tall as its length sums a volume 9 % over its own.
/// Once every texel is deeper than its mean thickness `3V/A` (its width,
/// not its half length), Archimedes' force takes the rod's volume,
/// `2 × 0.01 × 0.01` m³; where the last texel has only just gone under, it
/// takes the sum as it is (no jump), and in between it moves from one to
/// the other.
#[test]
fn deep_under_a_step_archimedes_takes_the_enclosed_volume() {
    let mesh = builtin::cuboid(2.0, 0.01, 0.01);
    let atlas = bake(&mesh, 32);
    let exact = 2.0 * 0.01 * 0.01;
    let r = atlas.bounding_radius();
    let water = cliff(r, 0.1 * r);
    let turn = UnitQuaternion::from_euler_angles(0.05, 0.0, 0.09);
    let posed = |y: f64| Isometry3::from_parts(Translation3::new(0.02, y, 0.01), turn);
    // Deep: every texel more than r under its surface.
    let (deep_sum, shallowest) = sampled_volume(&atlas, &water, &posed(-3.0 * r));
    assert!(shallowest > 1.01 * r, "shallowest texel {shallowest} m deep");
    assert!(
        (deep_sum - exact).abs() > 0.05 * exact,
        "the samples' sum {deep_sum} is already the volume {exact}: the case does not test the correction"
    );
    eprintln!(
        "deep: the samples' sum is {:+.2} % off the volume",
        100.0 * (deep_sum / exact - 1.0)
    );
    let f = at(&atlas, &water, posed(-3.0 * r), &HydroOptions::default());
    assert_eq!(f.deep, 1.0);
    assert!(
        (f.submerged_volume - exact).abs() < 1e-6 * exact,
        "deep: {} m³ against {exact}",
        f.submerged_volume
    );
    assert!((f.buoyancy.force.y - RHO * G * exact).abs() < 1e-6 * RHO * G * exact);
    // The depth past which a texel is deep: the rod's width (3V/A =
    // 0.0075 m), not its half length.
    let delta = atlas.mean_thickness();
    assert!(
        (delta - 3.0 * exact / 0.0802).abs() < 1e-3 * delta && delta < 0.01 * r,
        "δ = {delta} m"
    );
    // Just under: the last texel 10⁻⁹ δ under its surface.
    let (_, at_zero) = sampled_volume(&atlas, &water, &posed(0.0));
    let y = at_zero - 1e-9 * delta;
    let (sum, shallowest) = sampled_volume(&atlas, &water, &posed(y));
    assert!(shallowest > 0.0 && shallowest < 1e-8 * delta, "{shallowest}");
    let f = at(&atlas, &water, posed(y), &HydroOptions::default());
    assert!(f.deep < 1e-8, "just under: φ = {}", f.deep);
    assert!(
        (f.submerged_volume - sum).abs() < 1e-6 * exact,
        "just under: {} m³ against the samples' {sum}",
        f.submerged_volume
    );
    // In between, the volume lies between the two and φ grows with depth.
    let (mut last, mut between) = (0.0, 0);
    for k in 1..10 {
        let pose = posed(y - 0.2 * delta * k as f64);
        let (sum, _) = sampled_volume(&atlas, &water, &pose);
        let f = at(&atlas, &water, pose, &HydroOptions::default());
        assert!(
            f.deep >= last && f.deep <= 1.0,
            "{k}: φ = {} after {last}",
            f.deep
        );
        let (lo, hi) = (sum.min(exact), sum.max(exact));
        assert!(
            f.submerged_volume >= lo - 1e-6 * exact && f.submerged_volume <= hi + 1e-6 * exact,
            "{k}: {} outside [{lo}, {hi}]",
            f.submerged_volume
        );
        last = f.deep;
        between += usize::from(f.deep > 0.0 && f.deep < 1.0);
    }
    assert!(
        between > 0 && last == 1.0,
        "φ = {last} at 1.8 δ, {between} steps in between"
    );
    // Partly dry, and under a plane, the sum is taken as it is.
    let f = at(&atlas, &water, posed(0.0), &HydroOptions::default());
    assert_eq!(f.deep, 0.0);
    let (sum, _) = sampled_volume(&atlas, &water, &posed(0.0));
    assert!(
        (f.submerged_volume - sum.max(0.0)).abs() < 1e-12,
        "{} {sum}",
        f.submerged_volume
    );
    let calm = Water::calm(0.0);
    let f = at(&atlas, &calm, posed(-0.2), &HydroOptions::default());
    let (sum, _) = sampled_volume(&atlas, &calm, &posed(-0.2));
    assert_eq!(f.deep, 1.0);
    assert!(
        (f.submerged_volume - sum).abs() < 1e-12 * exact,
        "{} {sum}",
        f.submerged_volume
    );
}

/// Saved forces from before `potential` and `deep` were reported still
/// load, with those two at 0; the rest round-trips.
#[test]
fn forces_saved_without_the_newer_fields_still_load() {
    let atlas = bake(&builtin::cuboid(1.0, 0.5, 0.8), 32);
    let pose = Isometry3::translation(0.0, -0.1, 0.0);
    let f = at(&atlas, &Water::calm(0.0), pose, &HydroOptions::default());
    assert!(f.potential > 0.0 && f.deep == 0.0);
    let mut json: serde_json::Value = serde_json::to_value(f).unwrap();
    let map = json.as_object_mut().unwrap();
    assert!(map.remove("potential").is_some() && map.remove("deep").is_some());
    let back: HydroForces = serde_json::from_value(json).unwrap();
    assert_eq!(back.potential, 0.0);
    assert_eq!(back.deep, 0.0);
    assert_eq!(back.submerged_texels, f.submerged_texels);
    assert!((back.submerged_volume - f.submerged_volume).abs() <= 1e-15 * f.submerged_volume);
    assert!((back.buoyancy.force - f.buoyancy.force).norm() <= 1e-12 * f.buoyancy.force.norm());
}
