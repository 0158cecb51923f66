//! The plugin headless (`MinimalPlugins`, one bevy_rapier step per
//! update): bodies float at their analytic draft, a Bevy mesh asset is
//! unwrapped, bodies float on a sea with the waves they make, bodies come
//! and go, and bad input is a message, never a panic. (That the plugin and
//! soak-rapier step the same scene alike is the facade's
//! `tests/engines_agree.rs`: soak-bevy does not depend on soak-rapier.)

use std::sync::Arc;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_bevy::FloatingFailed;
use soak_bevy::prelude::*;
use soak_driver::Effects;

/// The physics step of these tests, s (Rapier's default).
const DT: f32 = 1.0 / 60.0;

/// The plugin's messages, kept (Bevy drops a message two updates on).
#[derive(Resource, Default)]
struct Said(Vec<(Entity, String, String)>);

fn keep_messages(mut said: ResMut<Said>, mut errors: MessageReader<FloatingError>) {
    for e in errors.read() {
        said.0
            .push((e.entity, format!("{:?}", e.kind), e.kind.to_string()));
    }
}

/// A headless app: bevy_rapier in the fixed schedule, one step of `DT`
/// per update, soak's plugin in `water`.
fn app(water: SoakWater) -> App {
    let mut app = App::new();
    app.init_resource::<Said>()
        .add_systems(Last, keep_messages)
        .add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(Time::<Fixed>::from_seconds(DT as f64))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .insert_resource(TimestepMode::Fixed { dt: DT, substeps: 1 })
        .add_plugins(RapierPhysicsPlugin::<NoUserData>::default().in_fixed_schedule())
        .add_plugins(SoakPlugin::default())
        .insert_resource(water);
    app.finish();
    app.cleanup();
    // The first update runs the start-up schedules and no fixed step.
    app.update();
    app
}

/// Steps until `done` holds or `limit` updates have run.
fn run_until(app: &mut App, limit: usize, mut done: impl FnMut(&mut App) -> bool) -> usize {
    for k in 0..limit {
        if done(app) {
            return k;
        }
        app.update();
    }
    limit
}

/// The messages the plugin sent so far (their kinds, `Debug`).
fn errors(app: &mut App) -> Vec<String> {
    app.world()
        .resource::<Said>()
        .0
        .iter()
        .map(|(_, kind, _)| kind.clone())
        .collect()
}

fn registered(app: &mut App, entity: Entity) -> bool {
    app.world().resource::<SoakWater>().id(entity).is_some()
}

/// A crate of 500 kg/m³, 1 × 0.6 × 0.8 m, floats with half its height
/// under water: a draft of 0.3 m, within 1 mm.
#[test]
fn a_box_floats_at_its_analytic_draft() {
    let mut app = app(SoakWater::new(Water::calm(0.0)));
    let mesh = builtin::cuboid(1.0, 0.6, 0.8);
    let entity = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::cuboid(0.5, 0.3, 0.4),
            Transform::from_xyz(0.0, 0.5, 0.0),
            Floating::new("crate", FloatingMesh::Mesh(Arc::new(mesh))).with_effects(
                Effects::buoyancy().with_drag(Drag {
                    coefficient: 1.0,
                    linear: 200.0,
                }),
            ),
        ))
        .id();
    // The bake runs on another thread: the app keeps stepping meanwhile.
    let waited = run_until(&mut app, 6000, |app| registered(app, entity));
    assert!(waited < 6000, "never registered: {:?}", errors(&mut app));
    for _ in 0..1200 {
        app.update();
    }
    let transform = *app.world().get::<Transform>(entity).unwrap();
    let water = app.world().resource::<SoakWater>();
    let draft = water.draft(entity, &transform).unwrap();
    assert!((draft - 0.3).abs() < 1e-3, "draft {draft} m");
    let report = *app.world().get::<FloatReport>(entity).unwrap();
    assert!((report.submerged_fraction - 0.5).abs() < 2e-3, "{report:?}");
    // Its weight, 0.48 m³ × 500 kg/m³ × g, held by the water.
    let weight = 0.48 * 500.0 * 9.81;
    assert!(
        (report.buoyancy.y as f64 - weight).abs() < 5e-3 * weight,
        "{report:?}"
    );
    assert!(errors(&mut app).is_empty());
}

/// A Bevy mesh asset (a `Cuboid`, whose faces share the UV square: not
/// an atlas) is unwrapped and floats like the soak mesh.
#[test]
fn a_bevy_mesh_asset_is_unwrapped_and_floats() {
    let mut app = App::new();
    app.init_resource::<Said>()
        .add_systems(Last, keep_messages)
        .add_plugins((MinimalPlugins, TransformPlugin, AssetPlugin::default()))
        .init_asset::<Mesh>()
        .insert_resource(Time::<Fixed>::from_seconds(DT as f64))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .insert_resource(TimestepMode::Fixed { dt: DT, substeps: 1 })
        .add_plugins(RapierPhysicsPlugin::<NoUserData>::default().in_fixed_schedule())
        .add_plugins(SoakPlugin::default());
    app.finish();
    app.cleanup();
    app.update();
    let handle = app
        .world_mut()
        .resource_mut::<Assets<Mesh>>()
        .add(Cuboid::new(1.0, 0.6, 0.8));
    let spawn = |app: &mut App, x: f32| {
        app.world_mut()
            .spawn((
                RigidBody::Dynamic,
                Transform::from_xyz(x, 0.5, 0.0),
                Floating::new("cuboid", FloatingMesh::Asset(handle.clone())).with_effects(
                    Effects::buoyancy().with_drag(Drag {
                        coefficient: 1.0,
                        linear: 200.0,
                    }),
                ),
            ))
            .id()
    };
    let (a, b) = (spawn(&mut app, 0.0), spawn(&mut app, 3.0));
    let waited = run_until(&mut app, 6000, |app| registered(app, a) && registered(app, b));
    assert!(waited < 6000, "never registered: {:?}", errors(&mut app));
    for _ in 0..1200 {
        app.update();
    }
    let water = app.world().resource::<SoakWater>();
    // One bake for the two bodies of one asset.
    let (ba, bb) = (water.body(a).unwrap(), water.body(b).unwrap());
    assert!(std::ptr::eq(ba.atlas(), bb.atlas()));
    let transform = *app.world().get::<Transform>(a).unwrap();
    let draft = water.draft(a, &transform).unwrap();
    assert!((draft - 0.3).abs() < 2e-3, "draft {draft} m");
}

/// On the harbour's two-wave swell with the waves bodies make laid over
/// it: a crate and a buoy float on it for 10 s, riding the swell (never
/// thrown out of the water nor sunk), the waves take energy from them, and
/// nothing is rejected.
#[test]
fn bodies_float_on_a_sea_with_the_waves_they_make() {
    let waves = vec![
        soak_hydro::GerstnerWave {
            amplitude: 0.25,
            wavelength: 9.0,
            direction_deg: 0.0,
            steepness: 0.6,
            phase: 0.0,
        },
        soak_hydro::GerstnerWave {
            amplitude: 0.10,
            wavelength: 4.0,
            direction_deg: 35.0,
            steepness: 0.4,
            phase: 1.0,
        },
    ];
    let sea = Water::new(soak_hydro::Gerstner::new(0.0, waves, 9.81).unwrap());
    let coupling = WaveCoupling {
        size: 32.0,
        cells: 128,
        ..WaveCoupling::default()
    };
    let mut app = app(SoakWater::new(sea).with_waves(coupling).unwrap());
    let drag = Drag {
        coefficient: 1.0,
        linear: 50.0,
    };
    let shapes = [
        ("crate", builtin::cuboid(0.8, 0.8, 0.8), [2.0, 0.0, 0.0], 450.0),
        ("buoy", builtin::sphere(0.4, 32, 16), [-2.0, 0.0, 1.0], 500.0),
    ];
    let entities: Vec<Entity> = shapes
        .into_iter()
        .map(|(name, mesh, p, density)| {
            let atlas = Arc::new(Atlas::bake(&mesh, BakeOptions::square(64)).unwrap());
            app.world_mut()
                .spawn((
                    RigidBody::Dynamic,
                    Transform::from_xyz(p[0], p[1], p[2]),
                    Floating::new(name, FloatingMesh::Atlas(atlas))
                        .with_mass_model(MassModel::Solid { density })
                        .with_effects(Effects::buoyancy().with_drag(drag)),
                ))
                .id()
        })
        .collect();
    let mut lowest = f32::INFINITY;
    let mut highest = f32::NEG_INFINITY;
    let mut fraction = [0.0; 2];
    let steps = 600;
    for _ in 0..steps {
        app.update();
        for (k, e) in entities.iter().enumerate() {
            let y = app.world().get::<Transform>(*e).unwrap().translation.y;
            assert!(y.is_finite());
            (lowest, highest) = (lowest.min(y), highest.max(y));
            fraction[k] += app.world().get::<FloatReport>(*e).unwrap().submerged_fraction / steps as f64;
        }
    }
    println!("heights {lowest:.3} to {highest:.3} m, mean submerged fractions {fraction:?}");
    assert!(lowest > -1.0 && highest < 1.0, "heights {lowest} to {highest} m");
    for f in fraction {
        assert!((0.3..0.7).contains(&f), "mean submerged fraction {f}");
    }
    let water = app.world().resource::<SoakWater>();
    let energy = water.driver().waves().unwrap().energy();
    assert!(energy > 0.0, "the waves hold {energy} J");
    assert_eq!(water.driver().firewall().count(), 0);
    assert!(errors(&mut app).is_empty());
}

/// A body despawned mid-run is forgotten (its state dropped, its id
/// retired); the others float on.
#[test]
fn a_body_despawned_mid_run_is_forgotten() {
    let mut app = app(SoakWater::new(Water::calm(0.0)));
    let atlas = Arc::new(Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(64)).unwrap());
    let spawn = |app: &mut App, x: f32| {
        app.world_mut()
            .spawn((
                RigidBody::Dynamic,
                Transform::from_xyz(x, 0.3, 0.0),
                Floating::new("crate", FloatingMesh::Atlas(atlas.clone())),
            ))
            .id()
    };
    let (gone, stays) = (spawn(&mut app, 0.0), spawn(&mut app, 3.0));
    for _ in 0..120 {
        app.update();
    }
    let id = app.world().resource::<SoakWater>().id(gone).unwrap();
    app.world_mut().despawn(gone);
    for _ in 0..600 {
        app.update();
    }
    let water = app.world().resource::<SoakWater>();
    assert!(water.id(gone).is_none());
    assert!(water.driver().body(id).unwrap().is_retired());
    let transform = *app.world().get::<Transform>(stays).unwrap();
    let draft = water.draft(stays, &transform).unwrap();
    assert!((draft - 0.3).abs() < 0.05, "draft {draft} m");
    // `Floating` taken off a body that stays: it no longer floats (its
    // force zeroed, its state dropped) and sinks, falling freely.
    let id = app.world().resource::<SoakWater>().id(stays).unwrap();
    app.world_mut().entity_mut(stays).remove::<Floating>();
    for _ in 0..60 {
        app.update();
    }
    let water = app.world().resource::<SoakWater>();
    assert!(water.id(stays).is_none() && water.driver().body(id).unwrap().is_retired());
    assert_eq!(
        *app.world().get::<ExternalForce>(stays).unwrap(),
        ExternalForce::default()
    );
    assert!(app.world().get::<Transform>(stays).unwrap().translation.y < -1.0);
    assert!(errors(&mut app).is_empty());
}

/// A mesh that cannot be baked (a NaN vertex) is a clear message on that
/// entity, which is left alone; nothing panics and the app steps on.
#[test]
fn a_bake_that_fails_is_a_message() {
    let mut app = app(SoakWater::new(Water::calm(0.0)));
    let mut mesh = builtin::cuboid(1.0, 1.0, 1.0);
    mesh.positions[3].y = f64::NAN;
    let entity = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Transform::from_xyz(0.0, 1.0, 0.0),
            Floating::new("broken", FloatingMesh::Mesh(Arc::new(mesh))),
        ))
        .id();
    run_until(&mut app, 6000, |app| {
        app.world().get::<FloatingFailed>(entity).is_some()
    });
    assert!(app.world().get::<FloatingFailed>(entity).is_some());
    let said: Vec<String> = app
        .world()
        .resource::<Said>()
        .0
        .iter()
        .map(|m| m.2.clone())
        .collect();
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0].contains("`broken`") && said[0].contains("vertex 3"),
        "{said:?}"
    );
    println!("{}", said[0]);
    for _ in 0..10 {
        app.update();
    }
    assert!(!registered(&mut app, entity));
}

/// `Floating` on an entity without a rigid body, or on a fixed one, or on
/// a body whose collider has mass: a message naming the body.
#[test]
fn floating_without_a_dynamic_massless_body_is_a_message() {
    let mut app = app(SoakWater::new(Water::calm(0.0)));
    let atlas = Arc::new(Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(32)).unwrap());
    let floating = |name: &str| Floating::new(name, FloatingMesh::Atlas(atlas.clone()));
    let loose = app
        .world_mut()
        .spawn((Transform::default(), floating("loose")))
        .id();
    let fixed = app
        .world_mut()
        .spawn((RigidBody::Fixed, Transform::default(), floating("pier")))
        .id();
    let heavy = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::cuboid(0.5, 0.3, 0.4),
            ColliderMassProperties::Density(700.0),
            Transform::default(),
            floating("heavy"),
        ))
        .id();
    for _ in 0..5 {
        app.update();
    }
    for e in [loose, fixed, heavy] {
        assert!(app.world().get::<FloatingFailed>(e).is_some());
        assert!(!registered(&mut app, e));
    }
    let said = &app.world().resource::<Said>().0;
    assert_eq!(said.len(), 3, "{said:?}");
    let of = |e: Entity| {
        said.iter()
            .find(|m| m.0 == e)
            .map(|m| (m.1.as_str(), m.2.as_str()))
            .unwrap()
    };
    assert!(
        of(loose).0.starts_with("NoRigidBody") && of(loose).1.contains("`loose`"),
        "{said:?}"
    );
    assert!(
        of(fixed).0.starts_with("NotDynamic") && of(fixed).1.contains("`pier`: its RigidBody is Fixed"),
        "{said:?}"
    );
    assert!(
        of(heavy).0.starts_with("ColliderHasMass") && of(heavy).1.contains("Density(700.0)"),
        "{said:?}"
    );
    assert!(of(heavy).1.contains("Density(0.0)"), "{said:?}");
}
