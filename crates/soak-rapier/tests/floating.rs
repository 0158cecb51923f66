//! Bodies float, settle and right themselves as hydrostatics says.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{Drag, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, RapierSoakBody, SoakId, convert};

struct Sim {
    world: PhysicsWorld,
    soak: ForceGenerator,
    handle: RigidBodyHandle,
    id: SoakId,
}

fn sim(mesh: &Mesh, res: u32, model: MassModel, effects: Effects, pose: Pose, dt: f32) -> Sim {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt;
    let handle = world.bodies.insert(RigidBodyBuilder::dynamic().pose(pose));
    let atlas = Atlas::bake(mesh, BakeOptions::square(res)).unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: mesh.name.clone(),
                atlas: atlas.into(),
                mass_model: model,
                effects,
            },
        )
        .unwrap();
    Sim {
        world,
        soak,
        handle,
        id,
    }
}

impl Sim {
    fn run(&mut self, seconds: f64, mut each: impl FnMut(&Self)) {
        let n = (seconds / self.world.integration_parameters.dt as f64).round() as usize;
        for _ in 0..n {
            self.soak.step(&mut self.world).unwrap();
            each(self);
        }
    }
    fn body(&self) -> &RigidBody {
        &self.world.bodies[self.handle]
    }
    fn y(&self) -> f64 {
        self.body().translation().y as f64
    }
}

fn at(y: f32) -> Pose {
    Pose::from_translation(Vector::new(0.0, y, 0.0))
}

#[test]
fn boxes_settle_at_their_draft() {
    let h = 1.0;
    let mesh = builtin::cuboid(2.0, h, 1.5);
    for s in [0.25, 0.5, 0.75] {
        let mut sim = sim(
            &mesh,
            128,
            MassModel::Solid { density: 1000.0 * s },
            // Heave is damped only by skin friction on the sides (no wave
            // radiation is modelled), so a strong one lets it settle in a minute.
            Effects::buoyancy().with_drag(Drag {
                coefficient: 1.0,
                linear: 400.0,
            }),
            at(0.3),
            1.0 / 60.0,
        );
        sim.run(60.0, |_| {});
        // Centre at −(draft − h/2): draft = s·h.
        let draft = h / 2.0 - sim.y();
        assert!((draft - s * h).abs() < 0.01 * s * h, "s = {s}: draft {draft}");
        assert!(
            sim.body().linvel().length() < 1e-3,
            "s = {s}: v {:?} w {:?}",
            sim.body().linvel(),
            sim.body().angvel()
        );
    }
}

#[test]
fn a_half_dense_sphere_floats_centred_on_the_waterline_and_a_dense_one_sinks() {
    let r = 0.5;
    let mesh = builtin::sphere(r, 48, 24);
    let drag = Drag {
        coefficient: 0.5,
        linear: 10.0,
    };
    let mut sim = sim(
        &mesh,
        128,
        MassModel::Solid { density: 500.0 },
        Effects::buoyancy().with_drag(drag),
        at(0.2),
        1.0 / 60.0,
    );
    sim.run(60.0, |_| {});
    assert!(sim.y().abs() < 0.01 * r, "centre at {}", sim.y());
    let mut sim = self::sim(
        &mesh,
        128,
        MassModel::Solid { density: 1200.0 },
        Effects::buoyancy().with_drag(drag),
        at(0.0),
        1.0 / 60.0,
    );
    sim.run(10.0, |_| {});
    assert!(sim.y() < -3.0, "a denser body must sink: at {}", sim.y());
    assert!(sim.body().linvel().y < 0.0);
}

#[test]
fn undamped_heave_keeps_its_amplitude_for_ten_minutes() {
    // No drag: a box released 20 cm below equilibrium oscillates; the
    // amplitude must neither grow nor decay (no numerical energy gain or loss).
    // A flat box, stable in roll and pitch (a cube at s = 0.5 is not and
    // would trade heave for rolling over).
    let mesh = builtin::cuboid(2.0, 1.0, 2.0);
    for dt in [1.0 / 60.0, 1.0 / 15.0] {
        let equilibrium = 0.0f64; // s = 0.5: centre on the waterline
        let mut sim = sim(
            &mesh,
            64,
            MassModel::Solid { density: 500.0 },
            Effects::buoyancy(),
            at(-0.2),
            dt,
        );
        let mut peaks: Vec<f64> = Vec::new();
        let (mut prev, mut prev2) = (sim.y(), sim.y());
        let mut finite = true;
        sim.run(600.0, |s| {
            let y = s.y();
            finite &= y.is_finite() && s.body().linvel().is_finite();
            if prev > prev2 && prev >= y {
                peaks.push(prev - equilibrium);
            }
            prev2 = prev;
            prev = y;
        });
        assert!(finite, "dt {dt}: non-finite state");
        assert!(peaks.len() > 100, "dt {dt}: {} peaks", peaks.len());
        for p in &peaks {
            assert!(
                (p - 0.2).abs() < 0.02 * 0.2,
                "dt {dt}: peak {p} (first {}, last {})",
                peaks[0],
                peaks[peaks.len() - 1]
            );
        }
    }
}

#[test]
fn damped_heave_decays_peak_by_peak_and_settles() {
    let mesh = builtin::cuboid(2.0, 1.0, 2.0);
    for dt in [1.0 / 60.0, 1.0 / 15.0] {
        let drag = Drag {
            coefficient: 1.0,
            linear: 100.0,
        };
        let mut sim = sim(
            &mesh,
            64,
            MassModel::Solid { density: 500.0 },
            Effects::buoyancy().with_drag(drag),
            at(-0.2),
            dt,
        );
        let mut peaks = Vec::new();
        let (mut prev, mut prev2) = (sim.y(), sim.y());
        sim.run(600.0, |s| {
            let y = s.y();
            assert!(y.is_finite());
            if prev > prev2 && prev >= y && prev > 1e-4 {
                peaks.push(prev);
            }
            prev2 = prev;
            prev = y;
        });
        assert!(peaks.len() >= 2, "dt {dt}: peaks {peaks:?}");
        for w in peaks.windows(2) {
            assert!(w[1] < w[0], "dt {dt}: peak {} after {}", w[1], w[0]);
        }
        assert!(
            sim.y().abs() < 1e-3 && sim.body().linvel().length() < 1e-3,
            "dt {dt}: ends at {}",
            sim.y()
        );
    }
}

#[test]
fn a_bottom_heavy_body_rights_itself_after_a_30_degree_tilt() {
    // A box with a heavy keel: shell mass concentrated on the bottom face
    // puts the centre of mass far below the centre of buoyancy.
    let mesh = builtin::cuboid(2.0, 1.0, 1.0);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    let density: Vec<f32> = (0..atlas.len())
        .map(|i| {
            if atlas.area_vectors().get(i)[1] < -1e-9 {
                600.0
            } else {
                5.0
            }
        })
        .collect();
    let tilt = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 30f64.to_radians());
    let pose = Pose::from_parts(Vector::new(0.0, 0.0, 0.0), convert::to_rotation(&tilt));
    let drag = Drag {
        coefficient: 1.0,
        linear: 20.0,
    };
    let mut s = sim(
        &mesh,
        128,
        MassModel::ShellTexture {
            areal_density: density,
        },
        Effects::buoyancy().with_drag(drag),
        pose,
        1.0 / 60.0,
    );
    let com = s.soak.body(s.id).unwrap().mass_properties().center_of_mass;
    assert!(com.y < -0.3, "centre of mass at {com}");
    s.run(60.0, |_| {});
    let up = convert::rotation(*s.body().rotation()) * Vector3::y();
    assert!(up.y > 0.999, "not upright: up = {up}");
}

#[test]
fn a_top_heavy_ball_rolls_to_a_new_equilibrium() {
    // Thesis Fig. 7.6: a ball whose centre of mass sits above its centre of
    // buoyancy turns over and does not return to its initial orientation.
    let mesh = builtin::sphere(0.5, 48, 24);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    let density: Vec<f32> = (0..atlas.len())
        .map(|i| if atlas.position(i).y > 0.2 { 60.0 } else { 5.0 })
        .collect();
    let nudge = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 2f64.to_radians());
    let pose = Pose::from_parts(Vector::new(0.0, 0.0, 0.0), convert::to_rotation(&nudge));
    let drag = Drag {
        coefficient: 0.5,
        linear: 20.0,
    };
    let mut s = sim(
        &mesh,
        128,
        MassModel::ShellTexture {
            areal_density: density,
        },
        Effects::buoyancy().with_drag(drag),
        pose,
        1.0 / 60.0,
    );
    s.run(60.0, |_| {});
    let up = convert::rotation(*s.body().rotation()) * Vector3::y();
    assert!(up.y < -0.9, "the heavy cap should end at the bottom: up = {up}");
}

#[test]
fn rapier_reports_the_mass_that_follows_the_shell_texture() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    let n = atlas.len();
    let mut s = sim(
        &mesh,
        128,
        MassModel::Shell { areal_density: 2.0 },
        Effects::buoyancy(),
        at(0.0),
        1.0 / 60.0,
    );
    let area = atlas.area();
    // Mass is readable at once after registration (Rapier's own mass()).
    assert!((s.body().mass() as f64 - 2.0 * area).abs() < 1e-3 * 2.0 * area);
    for k in 0..20 {
        let phase = k as f64 * 0.3;
        let dir = Vector3::new(phase.cos(), 0.0, phase.sin());
        let tex: Vec<f32> = (0..n)
            .map(|i| (2.0 + 1.5 * atlas.position(i).coords.normalize().dot(&dir)) as f32)
            .collect();
        let model = MassModel::ShellTexture { areal_density: tex };
        let expected = model.mass_properties(&atlas).unwrap();
        s.soak
            .set_mass_model(s.id, model, &mut s.world.bodies, &s.world.colliders)
            .unwrap();
        let rb = s.body();
        assert!(
            (rb.mass() as f64 - expected.mass).abs() < 1e-4 * expected.mass,
            "step {k}"
        );
        let com = convert::vector(rb.local_center_of_mass());
        assert!(
            (com - expected.center_of_mass.coords).norm() < 1e-5,
            "step {k}: {com}"
        );
        assert!(
            com.dot(&dir) > 0.01,
            "the centre of mass leans towards the heavy side"
        );
        s.run(1.0 / 60.0, |_| {});
    }
}

#[test]
fn forces_do_not_accumulate_across_steps() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    let mut s = sim(
        &mesh,
        64,
        MassModel::Solid { density: 500.0 },
        Effects::buoyancy(),
        at(0.0),
        1.0 / 60.0,
    );
    let params = s.world.integration_parameters;
    s.soak.apply(&mut s.world.bodies, &params);
    let once = s.body().user_force();
    s.soak.apply(&mut s.world.bodies, &params);
    let twice = s.body().user_force();
    assert_eq!(once, twice);
    assert!(
        (once.y as f64 - 1000.0 * 9.81 * 0.5).abs() < 0.02 * 1000.0 * 9.81 * 0.5,
        "{once}"
    );
}

#[test]
fn colliders_with_mass_are_refused_and_effects_off_cost_nothing() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(32)).unwrap();
    let mut world = PhysicsWorld::new();
    let h = world.bodies.insert(RigidBodyBuilder::dynamic());
    world
        .colliders
        .insert_with_parent(ColliderBuilder::cuboid(0.5, 0.5, 0.5), h, &mut world.bodies);
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let desc = BodyDesc {
        name: "heavy collider".into(),
        atlas: atlas.clone().into(),
        mass_model: MassModel::Solid { density: 500.0 },
        effects: Effects::buoyancy(),
    };
    let e = soak
        .register(&mut world.bodies, &world.colliders, h, desc)
        .unwrap_err();
    assert!(e.to_string().contains("density 0"), "{e}");
    // Effects off: no forces are touched.
    let h2 = world.bodies.insert(RigidBodyBuilder::dynamic().pose(at(-1.0)));
    world.colliders.insert_with_parent(
        ColliderBuilder::cuboid(0.5, 0.5, 0.5).density(0.0),
        h2,
        &mut world.bodies,
    );
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            h2,
            BodyDesc {
                name: "inert".into(),
                atlas: atlas.into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects: Effects::default(),
            },
        )
        .unwrap();
    soak.step(&mut world).unwrap();
    assert_eq!(world.bodies[h2].user_force(), Vector::ZERO);
    assert_eq!(soak.body(id).unwrap().forces().submerged_texels, 0);
    let _ = Point3::<f64>::origin();
}

#[test]
fn draft_and_submerged_fraction_read_the_pose_and_the_last_step() {
    // The boat's keel is at y = 0 of its mesh and its deck at 0.6 m; its
    // atlas origin is elsewhere (the centroid).
    let boat = builtin::boat(4.0, 1.2, 0.6);
    let effects = Effects::buoyancy();
    let mut s = sim(
        &boat,
        128,
        MassModel::Solid { density: 400.0 },
        effects,
        at(-0.25),
        1.0 / 60.0,
    );
    let draft = s.soak.draft(s.id, &s.world.bodies).unwrap();
    // The hull's lowest texel lies within a texel of the keel.
    assert!((draft - 0.25).abs() < 5e-3, "upright at −0.25 m: draft {draft}");
    // Upside down at +0.3 m: the deck (0.6 m above the keel) is lowest.
    s.world.bodies[s.handle].set_position(
        Pose::from_parts(
            Vector::new(0.0, 0.3, 0.0),
            Rotation::from_rotation_x(std::f32::consts::PI),
        ),
        true,
    );
    let draft = s.soak.draft(s.id, &s.world.bodies).unwrap();
    assert!((draft - 0.3).abs() < 1e-4, "upside down: draft {draft}");
    // Clear of the water: minus the height of the lowest point above it.
    s.world.bodies[s.handle].set_position(at(2.0), true);
    let draft = s.soak.draft(s.id, &s.world.bodies).unwrap();
    assert!((draft + 2.0).abs() < 5e-3, "in the air: draft {draft}");
    // Nothing has been stepped yet; after a step at rest half under water
    // the fraction is the displaced volume over the enclosed one.
    let b = s.soak.body(s.id).unwrap();
    assert_eq!(b.submerged_fraction(), 0.0);
    let mut sphere = sim(
        &builtin::sphere(0.5, 48, 24),
        128,
        MassModel::Solid { density: 500.0 },
        Effects::buoyancy(),
        at(0.0),
        1.0 / 60.0,
    );
    sphere.run(1.0 / 60.0, |_| {});
    let b = sphere.soak.body(sphere.id).unwrap();
    assert!(
        (b.submerged_fraction() - 0.5).abs() < 0.02,
        "{}",
        b.submerged_fraction()
    );
    assert!((b.submerged_volume() - 0.5 * b.volume()).abs() < 0.02 * b.volume());
    // Rapier's types back: the centre of buoyancy of a sphere centred at the
    // surface, 3r/8 below its centre; after the first step, the force handed
    // to Rapier is the buoyancy of the half under water, straight up.
    let cb = b.center_of_buoyancy();
    assert!(cb.x.abs() < 1e-3 && cb.z.abs() < 1e-3, "{cb}");
    assert!((cb.y + 3.0 / 16.0).abs() < 5e-3, "{cb}");
    let f = b.applied_force();
    let half = 1000.0 * 9.81 * 0.5 * b.volume();
    assert!(((f64::from(f.y) - half) / half).abs() < 0.03, "{f} vs {half}");
    assert!(f.x.abs() < 1e-3 * f.y && f.z.abs() < 1e-3 * f.y, "{f}");
    assert!(b.applied_torque().length() < 1e-3 * f.y, "{}", b.applied_torque());
}
