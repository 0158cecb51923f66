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
use soak_seakeeping::{FloatingBody, RadiationModel, RadiationSettings, decay_measure};

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

/// `f` as a body with radiation, named `name`.
fn desc(f: &Floating, name: &str) -> BodyDesc {
    BodyDesc {
        name: name.into(),
        atlas: f.atlas.clone(),
        mass_model: f.mass_model.clone(),
        effects: Effects::buoyancy().with_radiation(f.model.clone()),
    }
}

/// `f` at `pose` in `water`, in soak's own engine (under the water's gravity).
fn driven(f: &Floating, pose: Isometry3<f64>, water: Water) -> (FreeBodies, FreeHandle, Driver<FreeHandle>) {
    let mut engine = FreeBodies::new(water.gravity);
    let handle = engine.insert(pose);
    let mut soak = Driver::new(water);
    soak.register(&mut engine, handle, desc(f, "body")).unwrap();
    (engine, handle, soak)
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
    run(f, pose, Water::calm(0.0), mode, step, seconds)
}

/// `f` from `pose` in `water` for `seconds`: its coordinate of `mode` (1
/// heave, 3 roll about x, 5 pitch about z, from the model's rest pose)
/// at the start and after every step.
fn run(
    f: &Floating,
    pose: Isometry3<f64>,
    water: Water,
    mode: usize,
    step: &StepParams,
    seconds: f64,
) -> Vec<f64> {
    let com = f.mass_model.mass_properties(&f.atlas).unwrap().center_of_mass;
    let height = f.model.hydrostatics().center_of_mass_height;
    let rest = *f.model.rotation();
    let (mut engine, handle, mut soak) = driven(f, pose, water);
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

/// The time-domain release of `mode` against the model's frequency-domain
/// prediction; returns both (period, ratio). The time domain's motion is
/// taken relative to the same body released at the model's rest pose:
/// the texels' hydrostatics float it a few millimetres from the panels'
/// rest, and a heavily damped release (a boat's heave) has fallen to
/// that within a cycle.
fn agrees(f: &Floating, mode: usize, x0: f64, step: &StepParams, seconds: f64) -> ((f64, f64), (f64, f64)) {
    let rest = release(f, mode, 0.0, step, seconds);
    let time_domain: Vec<f64> = release(f, mode, x0, step, seconds)
        .iter()
        .zip(&rest)
        .map(|(x, r)| x - r)
        .collect();
    let times: Vec<f64> = (0..time_domain.len()).map(|n| n as f64 * step.dt).collect();
    let predicted = f.model.release(mode, x0, &times).unwrap();
    let ours = decay_measure(&time_domain, step.dt).unwrap();
    let theirs = decay_measure(&predicted, step.dt).unwrap();
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
    // hemisphere heaves at 1.958 s with peaks falling to 0.591 a cycle
    // (the frequency-domain release of the hemisphere's coefficients, by
    // the same measure: soak-seakeeping's tests/decay.rs); buoyancy alone
    // bobs at 1.64 s forever.
    let sphere = floating(&builtin::sphere(1.0, 24, 12), 128, 500.0, 300);
    for step in [StepParams::new(1.0 / 60.0, 4), StepParams::new(1.0 / 30.0, 1)] {
        let (ours, _) = agrees(&sphere, 1, 0.05, &step, 8.0);
        assert!((ours.0 / 1.958 - 1.0).abs() < 0.02, "{}", ours.0);
        assert!((ours.1 / 0.591 - 1.0).abs() < 0.05, "{}", ours.1);
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
fn a_boat_decays_in_heave_roll_and_pitch_as_its_coefficients_predict() {
    // The built-in boat, 4 × 0.6 × 1.2 m (x, y, z), 0.4 of the water's
    // density: a hull with a bow and a fuller stern, whose heave is damped
    // about a quarter of critical.
    let boat = builtin::boat(4.0, 1.2, 0.6);
    let f = floating(&boat, 64, 400.0, 240);
    let step = StepParams::new(1.0 / 60.0, 4);
    agrees(&f, 1, 0.03, &step, 8.0);
    agrees(&f, 3, 0.05, &step, 12.0);
    agrees(&f, 5, 0.02, &step, 8.0);
}

#[test]
fn the_memory_is_saved_and_resumed_bit_for_bit() {
    let f = floating(&builtin::sphere(0.5, 16, 8), 32, 500.0, 80);
    let step = StepParams::new(1.0 / 60.0, 2);
    let setup = || driven(&f, Isometry3::translation(0.1, 0.08, 0.0), Water::calm(0.0));
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
    let result = salt.register(&mut engine, handle, desc(&f, "buoy"));
    assert!(matches!(result, Err(SoakError::Radiation { .. })), "{result:?}");
}

/// Heave amplitude at `omega` of `x` sampled every `dt` from `start`
/// (least squares on cos, sin and a constant).
fn amplitude_at(x: &[f64], dt: f64, start: usize, omega: f64) -> f64 {
    let (mut cc, mut ss, mut cs, mut xc, mut xs, mut n, mut sum_c, mut sum_s, mut sum_x) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (k, &v) in x.iter().enumerate().skip(start) {
        let (s, c) = (omega * k as f64 * dt).sin_cos();
        cc += c * c;
        ss += s * s;
        cs += c * s;
        xc += v * c;
        xs += v * s;
        n += 1.0;
        sum_c += c;
        sum_s += s;
        sum_x += v;
    }
    let m = nalgebra::Matrix3::new(cc, cs, sum_c, cs, ss, sum_s, sum_c, sum_s, n);
    let rhs = nalgebra::Vector3::new(xc, xs, sum_x);
    let p = m.lu().solve(&rhs).unwrap();
    p.x.hypot(p.y)
}

/// The amplitude of `mode` (m or rad per metre of wave amplitude) of `f`
/// released at its rest pose into regular waves of `amplitude` (m) and
/// each of `omegas` (rad/s) travelling along `direction_deg`, measured
/// over the second half of `seconds` (the release's transient gone),
/// beside the frequency-domain RAO of the same model, heave, roll and
/// pitch moving together ([`RadiationModel::coupled_rao`]).
fn raos_in_waves(
    f: &Floating,
    mode: usize,
    direction_deg: f64,
    amplitude: f64,
    omegas: &[f64],
    seconds: f64,
) -> Vec<(f64, f64)> {
    let rest = *f.model.rotation();
    let com = f.mass_model.mass_properties(&f.atlas).unwrap().center_of_mass;
    let height = f.model.hydrostatics().center_of_mass_height;
    let step = StepParams::new(1.0 / 60.0, 4);
    let g = f.model.gravity();
    let pose = Isometry3::from_parts(
        Translation3::from(Vector3::new(0.0, height, 0.0) - rest * com.coords),
        rest,
    );
    let name = match mode {
        1 => "heave",
        3 => "roll",
        _ => "pitch",
    };
    omegas
        .iter()
        .map(|&omega| {
            let wavelength = std::f64::consts::TAU * g / (omega * omega);
            let sea = soak_hydro::Gerstner::new(
                0.0,
                vec![soak_hydro::GerstnerWave {
                    amplitude,
                    wavelength,
                    direction_deg,
                    steepness: 0.0,
                    phase: 0.0,
                }],
                g,
            )
            .unwrap();
            let x = run(f, pose, Water::new(sea), mode, &step, seconds);
            let measured = amplitude_at(&x, step.dt, x.len() / 2, omega) / amplitude;
            let coupled = f.model.coupled_rao(omega, direction_deg.to_radians()).unwrap();
            let predicted = coupled[(mode - 1) / 2];
            eprintln!(
                "ω {omega:.1} rad/s: {name} RAO time domain {measured:.4}, frequency domain {predicted:.4}"
            );
            (measured, predicted)
        })
        .collect()
}

/// Each of `raos` (time domain, frequency domain) within 5 %, at
/// `omegas`, and the frequency domain's peak at `resonance` if given.
fn assert_raos_agree(name: &str, omegas: &[f64], raos: &[(f64, f64)], resonance: Option<f64>) {
    for (omega, (ours, theirs)) in omegas.iter().zip(raos) {
        assert!(
            (ours / theirs - 1.0).abs() < 0.05,
            "ω {omega}: {name} RAO {ours:.4} against {theirs:.4}"
        );
    }
    if let Some(resonance) = resonance {
        let peak = (0..raos.len())
            .max_by(|&a, &b| raos[a].1.total_cmp(&raos[b].1))
            .unwrap();
        assert_eq!(
            omegas[peak], resonance,
            "{name}: the resonance among the frequencies"
        );
    }
}

/// Heave in small regular waves (2 cm) against the frequency-domain RAO
/// of the same model, at five frequencies around the sphere's resonance
/// (KR 0.6–1.8): within 5 %. The time domain's excitation is the texels'
/// hydrostatic columns under the Gerstner surface plus what linear theory
/// adds to them (the pressure's decay with depth and the diffraction,
/// `RadiationModel::excitation_beyond_columns`); without that addition the
/// columns alone drove the sphere 1.6 to 2.5 times too hard.
#[test]
fn heave_in_small_regular_waves_follows_the_frequency_domain_rao() {
    let sphere = floating(&builtin::sphere(1.0, 24, 12), 128, 500.0, 300);
    let omegas = [2.4, 2.8, 3.2, 3.6, 4.2];
    // The release's transient has died out by half way (its peaks fall
    // to 0.59 a cycle).
    let raos = raos_in_waves(&sphere, 1, 0.0, 0.02, &omegas, 40.0);
    assert_raos_agree("heave", &omegas, &raos, Some(3.2));
}

/// The boat's roll in beam waves and its pitch in head waves against the
/// frequency-domain RAO of the same model (heave, roll and pitch coupled
/// as the time domain couples them: the boat's fuller stern couples its
/// heave and pitch), at five frequencies around each resonance: within
/// 5 %. The time domain's moments are the texels' (the columns of water
/// under the surface and the push of its slope on the hull's sides) and
/// what linear theory adds to them. Taken for the columns alone (the
/// push counted twice), the roll came out 0.16–0.38 of the frequency
/// domain's; with the texels' moments alone, 0.79–1.46 of it. The roll is lightly
/// damped (a fifth lost a cycle) and the boat's metacentric height a
/// quarter of its metacentric radius: a percent of the water-plane's
/// inertia moves its resonance half a percent and its RAO beside the
/// peak by up to 10 %, so the atlas is 128² (at 64² and 256², whose
/// texels' water-planes differ from the panels' by about that, the RAOs
/// beside the peak are 10–17 % off; the pitch's within 3 % at all three).
#[test]
fn the_boat_rolls_and_pitches_in_small_regular_waves_as_the_frequency_domain_says() {
    let boat = floating(&builtin::boat(4.0, 1.2, 0.6), 128, 400.0, 240);
    // Roll resonates near 3.7 rad/s: 60 s, 1 mm waves (16 mrad of roll).
    let roll = [3.0, 3.4, 3.7, 4.0, 4.4];
    let raos = raos_in_waves(&boat, 3, 90.0, 0.001, &roll, 60.0);
    assert_raos_agree("roll", &roll, &raos, Some(3.7));
    // Pitch near 4.6 rad/s, damped to 0.4 a cycle: 30 s, 1 cm waves. Its
    // RAO falls through the resonance (the boat is 1.4 of these waves
    // long, and their excitation cancels along it).
    let pitch = [3.4, 3.8, 4.2, 4.6, 5.0];
    let raos = raos_in_waves(&boat, 5, 0.0, 0.01, &pitch, 30.0);
    assert_raos_agree("pitch", &pitch, &raos, None);
}
