//! Radiation in the time domain: bodies released from rest on calm water
//! decay as the frequency-domain coefficients of the same model predict
//! (period within 2 %, peak ratio within 5 %), and a floating sphere as
//! linear theory's floating hemisphere; the memory is saved and resumed
//! bit for bit, and what does not fit is refused.

use std::sync::Arc;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, FreeHandle, SoakError, StepParams};
use soak_hydro::{MassModel, Water};
use soak_seakeeping::{FloatingBody, RadiationModel, RadiationSettings};

/// A mesh's atlas, mass model and radiation model (baked with the mass
/// properties the driver will give the body).
struct Floating {
    atlas: Arc<Atlas>,
    mass_model: MassModel,
    model: Arc<RadiationModel>,
}

fn floating(mesh: &Mesh, resolution: u32, density: f64, panels: usize) -> Floating {
    let atlas: Arc<Atlas> = Atlas::bake(mesh, BakeOptions::square(resolution)).unwrap().into();
    let mass_model = MassModel::Solid { density };
    let mass = mass_model.mass_properties(&atlas).unwrap();
    let settings = RadiationSettings {
        panels,
        frequencies: 32,
        ..RadiationSettings::default()
    };
    let model = RadiationModel::bake(
        &FloatingBody {
            mesh,
            mass: mass.mass,
            center_of_mass: mass.center_of_mass,
            inertia: mass.inertia,
            rotation: UnitQuaternion::identity(),
        },
        &settings,
    )
    .unwrap();
    Floating {
        atlas,
        mass_model,
        model: model.into(),
    }
}

/// Released at rest from its rest pose moved by `mode` (1 heave, 3 roll
/// about x, 5 pitch about z) by `x0` (m or rad); that coordinate every
/// step for `seconds`.
fn release(f: &Floating, mode: usize, x0: f64, step: &StepParams, seconds: f64) -> Vec<f64> {
    let com = f.mass_model.mass_properties(&f.atlas).unwrap().center_of_mass;
    let height = f.model.hydrostatics().center_of_mass_height;
    // The rest orientation is the model's (the stable one the bake found).
    let rest = *f.model.rotation();
    let turn = match mode {
        3 => UnitQuaternion::from_axis_angle(&Vector3::x_axis(), x0),
        5 => UnitQuaternion::from_axis_angle(&Vector3::z_axis(), x0),
        _ => UnitQuaternion::identity(),
    } * rest;
    let lift = if mode == 1 { x0 } else { 0.0 };
    let centre = Vector3::new(0.0, height + lift, 0.0);
    let pose = Isometry3::from_parts(Translation3::from(centre - turn * com.coords), turn);
    let mut engine = FreeBodies::new(9.81);
    let handle = engine.insert(pose);
    let mut soak = Driver::new(Water::calm(0.0));
    soak.register(
        &mut engine,
        handle,
        BodyDesc {
            name: "body".into(),
            atlas: f.atlas.clone(),
            mass_model: f.mass_model.clone(),
            effects: Effects::buoyancy().with_radiation(f.model.clone()),
        },
    )
    .unwrap();
    let coordinate = |engine: &FreeBodies| {
        let body = engine.get(handle).unwrap();
        match mode {
            1 => (body.pose * com).y - height,
            3 => (body.pose.rotation * rest.inverse()).scaled_axis().x,
            _ => (body.pose.rotation * rest.inverse()).scaled_axis().z,
        }
    };
    let mut x = vec![coordinate(&engine)];
    for _ in 0..(seconds / step.dt).round() as usize {
        soak.before_step(&mut engine, step).unwrap();
        engine.step(step);
        soak.after_step(step.dt);
        x.push(coordinate(&engine));
    }
    x
}

/// Period (s) and mean ratio of the first two pairs of successive
/// positive peaks of a release from a positive `x[0]`.
fn period_and_decay(x: &[f64], dt: f64) -> (f64, f64) {
    let crossings: Vec<f64> = x
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0] > 0.0 && w[1] <= 0.0)
        .map(|(n, w)| (n as f64 + w[0] / (w[0] - w[1])) * dt)
        .take(4)
        .collect();
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let mut peaks = vec![x[0]];
    peaks.extend(
        x.windows(3)
            .filter(|w| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.0)
            .map(|w| w[1]),
    );
    let ratios: Vec<f64> = peaks.windows(2).take(2).map(|p| p[1] / p[0]).collect();
    (period, ratios.iter().sum::<f64>() / ratios.len() as f64)
}

/// The time-domain release of `mode` against the model's frequency-domain
/// prediction; returns both (period, ratio).
fn agrees(f: &Floating, mode: usize, x0: f64, step: &StepParams, seconds: f64) -> ((f64, f64), (f64, f64)) {
    let time_domain = release(f, mode, x0, step, seconds);
    let times: Vec<f64> = (0..time_domain.len()).map(|n| n as f64 * step.dt).collect();
    let predicted = f.model.release(mode, x0, &times).unwrap();
    let ours = period_and_decay(&time_domain, step.dt);
    let theirs = period_and_decay(&predicted, step.dt);
    eprintln!(
        "mode {mode} at dt {:.4}: time domain {:.3} s, {:.3}; frequency domain {:.3} s, {:.3}",
        step.dt, ours.0, ours.1, theirs.0, theirs.1
    );
    assert!(
        (ours.0 / theirs.0 - 1.0).abs() < 0.02,
        "period {} vs {}",
        ours.0,
        theirs.0
    );
    assert!(
        (ours.1 / theirs.1 - 1.0).abs() < 0.05,
        "peak ratio {} vs {}",
        ours.1,
        theirs.1
    );
    (ours, theirs)
}

#[test]
fn a_floating_sphere_decays_as_the_floating_hemisphere() {
    // Radius 1 m, half the water's density: linear theory's floating
    // hemisphere heaves at about 1.955 s with peaks falling to 0.554 a
    // cycle (the frequency-domain decay of the hemisphere's coefficients,
    // see soak-seakeeping's tests); buoyancy alone bobs at 1.64 s forever.
    let sphere = floating(&builtin::sphere(1.0, 24, 12), 128, 500.0, 300);
    for step in [StepParams::new(1.0 / 60.0, 4), StepParams::new(1.0 / 30.0, 1)] {
        let (ours, _) = agrees(&sphere, 1, 0.05, &step, 8.0);
        assert!((ours.0 / 1.955 - 1.0).abs() < 0.03, "{}", ours.0);
        assert!((ours.1 / 0.554 - 1.0).abs() < 0.1, "{}", ours.1);
    }
}

#[test]
fn a_box_barge_decays_in_heave_roll_and_pitch_as_its_coefficients_predict() {
    // 4 × 1 × 2 m (x, y, z), half the water's density: 0.5 m draft.
    let barge = floating(&builtin::cuboid(4.0, 1.0, 2.0), 64, 500.0, 240);
    let step = StepParams::new(1.0 / 60.0, 4);
    agrees(&barge, 1, 0.05, &step, 10.0);
    agrees(&barge, 3, 0.05, &step, 12.0);
    agrees(&barge, 5, 0.02, &step, 12.0);
}

#[test]
fn the_memory_is_saved_and_resumed_bit_for_bit() {
    let f = floating(&builtin::sphere(0.5, 16, 8), 32, 500.0, 80);
    let step = StepParams::new(1.0 / 60.0, 2);
    let setup = || {
        let mut engine = FreeBodies::new(9.81);
        let handle = engine.insert(Isometry3::translation(0.1, 0.08, 0.0));
        let mut soak = Driver::new(Water::calm(0.0));
        soak.register(
            &mut engine,
            handle,
            BodyDesc {
                name: "buoy".into(),
                atlas: f.atlas.clone(),
                mass_model: f.mass_model.clone(),
                effects: Effects::buoyancy().with_radiation(f.model.clone()),
            },
        )
        .unwrap();
        (engine, handle, soak)
    };
    let advance = |engine: &mut FreeBodies, soak: &mut Driver<FreeHandle>, steps: usize| {
        for _ in 0..steps {
            soak.before_step(engine, &step).unwrap();
            engine.step(&step);
            soak.after_step(step.dt);
        }
    };
    let (mut engine, handle, mut soak) = setup();
    advance(&mut engine, &mut soak, 40);
    let saved = serde_json::to_string(&soak.state()).unwrap();
    let body = *engine.get(handle).unwrap();
    advance(&mut engine, &mut soak, 40);
    let straight = *engine.get(handle).unwrap();
    assert!(
        soak.body(soak_driver::SoakId(0))
            .unwrap()
            .radiation_force()
            .is_some_and(|w| w.force.norm() > 0.0)
    );

    let (mut engine, handle, mut soak) = setup();
    *engine.get_mut(handle).unwrap() = body;
    soak.restore_state(&serde_json::from_str(&saved).unwrap())
        .unwrap();
    advance(&mut engine, &mut soak, 40);
    let resumed = *engine.get(handle).unwrap();
    assert_eq!(resumed.pose, straight.pose);
    assert_eq!(resumed.linear_velocity, straight.linear_velocity);
    assert_eq!(resumed.angular_velocity, straight.angular_velocity);
}

#[test]
fn radiation_that_does_not_fit_is_refused() {
    let f = floating(&builtin::sphere(0.5, 16, 8), 32, 500.0, 80);
    let mut engine = FreeBodies::new(9.81);
    let handle = engine.insert(Isometry3::identity());
    let mut soak = Driver::new(Water::calm(0.0));
    // Baked for 500 kg/m³, registered at 700.
    let result = soak.register(
        &mut engine,
        handle,
        BodyDesc {
            name: "heavier".into(),
            atlas: f.atlas.clone(),
            mass_model: MassModel::Solid { density: 700.0 },
            effects: Effects::buoyancy().with_radiation(f.model.clone()),
        },
    );
    match result {
        Err(SoakError::Radiation { name, reason }) => {
            assert_eq!(name, "heavier");
            assert!(reason.contains("mass"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
    // Sea water: another density.
    let mut salt = Driver::new(Water {
        density: 1025.0,
        ..Water::calm(0.0)
    });
    let result = salt.register(
        &mut engine,
        handle,
        BodyDesc {
            name: "buoy".into(),
            atlas: f.atlas.clone(),
            mass_model: f.mass_model.clone(),
            effects: Effects::buoyancy().with_radiation(f.model.clone()),
        },
    );
    assert!(matches!(result, Err(SoakError::Radiation { .. })), "{result:?}");
}
