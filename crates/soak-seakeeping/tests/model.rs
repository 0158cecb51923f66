//! A body baked for the time domain: where it floats, its hydrostatics
//! against the geometry's, its release response against linear theory.

use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use soak_bake::builtin;
use soak_seakeeping::{
    FloatingBody, RadiationModel, RadiationSettings, RadiationState, SeakeepingError, decay_measure,
};
use std::f64::consts::PI;

/// The enclosed volume of a closed mesh, m³ (divergence theorem).
fn volume(mesh: &soak_bake::Mesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].coords);
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum()
}

/// A sphere of radius 1 m faceted 24 × 12 (its equator a ring of
/// vertices), half as dense as the water.
fn sphere_model() -> RadiationModel {
    let mesh = builtin::sphere(1.0, 24, 12);
    let mass = 500.0 * volume(&mesh);
    let body = FloatingBody {
        mesh: &mesh,
        mass,
        center_of_mass: Point3::origin(),
        inertia: Matrix3::identity() * (0.4 * mass),
        rotation: UnitQuaternion::identity(),
    };
    RadiationModel::bake(&body, &RadiationSettings::default()).unwrap()
}

#[test]
fn a_half_dense_sphere_floats_at_its_centre_and_heaves_as_the_hemisphere() {
    let start = std::time::Instant::now();
    let model = sphere_model();
    let h = model.hydrostatics();
    eprintln!(
        "{} panels, {} states, baked in {:.2} s; V {:.4}, A_wp {:.4}, height {:.2e}",
        model.panel_count(),
        model.state_count(),
        start.elapsed().as_secs_f64(),
        h.volume,
        h.waterplane_area,
        h.center_of_mass_height
    );
    // A∞ symmetric as potential theory makes it, to the last bit (the
    // panel solve's own is out by 2e-3 of its surge in the surge–sway pair).
    let a = model.infinite();
    assert_eq!(a, &a.transpose());
    // Half as dense: it floats with its equator on the water, and its
    // water-plane is the regular 24-gon of circumradius 1.
    let polygon = 12.0 * (2.0 * PI / 24.0).sin();
    assert!(
        h.center_of_mass_height.abs() < 1e-9,
        "{}",
        h.center_of_mass_height
    );
    assert!(
        (h.waterplane_area / polygon - 1.0).abs() < 1e-9,
        "{}",
        h.waterplane_area
    );
    assert!((h.volume / (0.5 * volume(&builtin::sphere(1.0, 24, 12))) - 1.0).abs() < 1e-9);
    // The centre of buoyancy of a hemisphere, 3R/8 below the plane (the
    // facets move it by a little).
    assert!(
        (h.center_of_buoyancy.y + 0.375).abs() < 0.005,
        "{}",
        h.center_of_buoyancy
    );
    assert!(h.center_of_buoyancy.x.abs() < 1e-9 && h.center_of_buoyancy.z.abs() < 1e-9);
    assert!((h.stiffness[(1, 1)] / (1000.0 * model.gravity() * polygon) - 1.0).abs() < 1e-9);
    // A sphere about its centre: buoyancy through it whatever its tilt, no
    // rotational stiffness, ρ g (I_wp + V (y_b − y_g)) = ρ g (π/4 − π/4) = 0
    // (to within the facets').
    assert!(
        h.stiffness[(3, 3)].abs() < 0.03 * 1000.0 * 9.81,
        "{}",
        h.stiffness[(3, 3)]
    );
    // The release of heave: linear theory's hemisphere, 1.958 s with its
    // peaks falling to 0.591 a cycle (the frequency-domain release of the
    // hemisphere's coefficients, tests/decay.rs, by the same measure).
    let dt = 0.01;
    let times: Vec<f64> = (0..1200).map(|n| n as f64 * dt).collect();
    let x = model.release(1, 0.05, &times).unwrap();
    let (period, ratio) = decay_measure(&x, dt).unwrap();
    eprintln!("heave release: period {period:.3} s, peak ratio {ratio:.3}");
    assert!((period / 1.958 - 1.0).abs() < 0.01, "{period}");
    assert!((ratio / 0.591 - 1.0).abs() < 0.02, "{ratio}");
    // In long waves the sphere rides the surface: heave RAO 1, its
    // excitation (Haskind's, here at KR 0.06) the long-wave limit
    // `C − ω² (ρV + A)`: the water-plane's stiffness less the inertia of
    // the water the body displaces and sets moving.
    let long = model.sweep().frequencies[0].omega;
    let rao = model.rao(1, long, 0.0).unwrap();
    let x = model.excitation(1, long, 0.0).unwrap().norm();
    let (a, _) = model.sweep().at(1, 1, long);
    let limit = h.stiffness[(1, 1)] - long * long * (1000.0 * h.volume + a);
    eprintln!("ω {long:.3} rad/s: heave RAO {rao:.4}, |X| {x:.0} N/m against {limit:.0}");
    assert!((rao - 1.0).abs() < 0.01, "{rao}");
    assert!((x / limit - 1.0).abs() < 0.01, "{x} vs {limit}");
    assert!(model.rao(1, 0.5 * long, 0.0).is_none());
    // A step resolves the body's motion up to its natural time √(L/g)
    // (L ≈ 1 m: 0.32 s).
    assert!(model.resolved_by(1.0 / 60.0) && model.resolved_by(0.3));
    assert!(!model.resolved_by(0.33) && !model.resolved_by(1.0));
    // Yaw radiates nothing: no states.
    assert!(model.kernel(4).poles.is_empty());
    assert!(model.release(0, 0.1, &times).is_none());
}

/// Bessel's J₁ by its integral, `(1/π) ∫₀^π cos(τ − x sin τ) dτ`.
fn bessel_j1(x: f64) -> f64 {
    let n = 4000;
    let h = PI / n as f64;
    (0..n)
        .map(|i| {
            let tau = (i as f64 + 0.5) * h;
            (tau - x * tau.sin()).cos()
        })
        .sum::<f64>()
        * h
        / PI
}

/// The hydrostatic columns' wave force is the water-plane's integral of
/// the wave, `ρ g ∫ e^{ikx} dA` (for a disc of radius R,
/// `ρ g π R² · 2 J₁(kR)/(kR)`), and linear theory's excitation is the
/// same in long waves and less in shorter ones (the pressure decays with
/// depth): what the time domain adds to the columns.
#[test]
fn the_columns_wave_force_is_the_water_planes_and_theory_adds_the_decay() {
    let model = sphere_model();
    let h = model.hydrostatics();
    let weight = 1000.0 * model.gravity();
    let radius = (h.waterplane_area / PI).sqrt();
    let frequencies = &model.sweep().frequencies;
    for heading in [0.0, 0.3, 2.0] {
        for c in frequencies.iter().step_by(6) {
            let k = c.omega * c.omega / model.gravity();
            let kr = k * radius;
            let disc = weight * h.waterplane_area * 2.0 * bessel_j1(kr) / kr;
            let columns = model.column_excitation(1, c.omega, heading).unwrap();
            let unit = weight * h.waterplane_area;
            assert!(
                (columns.re - disc).abs() < 0.01 * unit && columns.im.abs() < 1e-3 * unit,
                "kR {kr:.2}, heading {heading}: {columns} against {disc:.1}"
            );
            // Symmetric about the wave's direction: a wave along x rolls it
            // not at all (to the centroid rule's 0.5 % on facets cut
            // into triangles one way).
            if heading == 0.0 {
                let roll = model.column_excitation(3, c.omega, heading).unwrap();
                assert!(roll.norm() < 5e-3 * unit * radius, "{roll}");
            }
            let theory = model.excitation(1, c.omega, heading).unwrap();
            let beyond = model.excitation_beyond_columns(1, c.omega, heading);
            assert!((theory - columns - beyond).norm() < 1e-9 * unit);
            if heading == 0.0 {
                eprintln!(
                    "kR {kr:.2}: columns {:.0} N/m, disc {disc:.0}, theory |X| {:.0}",
                    columns.re,
                    theory.norm()
                );
            }
        }
    }
    // Long waves: theory adds to the columns' force the inertia of the
    // water the body displaces and sets moving, −ω² (ρV + A); at KR ≈ 1.8
    // it leaves under half of it.
    let first = frequencies[0].omega;
    let beyond = model.excitation_beyond_columns(1, first, 0.0);
    let (a, _) = model.sweep().at(1, 1, first);
    let inertia = first * first * (1000.0 * h.volume + a);
    eprintln!(
        "kR {:.2}: theory adds {beyond:.0} N/m against −{inertia:.0}",
        first * first / model.gravity() * radius
    );
    // (The imaginary part is the damping's, ω B, small in long waves.)
    assert!(
        (beyond.re / -inertia - 1.0).abs() < 0.03 && beyond.im.abs() < 0.1 * inertia,
        "{beyond}"
    );
    let short = (1.8 * model.gravity() / radius).sqrt();
    let ratio = model.excitation(1, short, 0.0).unwrap().norm()
        / model.column_excitation(1, short, 0.0).unwrap().norm();
    assert!(ratio < 0.5, "{ratio}");
    // Below the frequencies solved the addition falls away; above them it
    // stays finite; nothing for a frequency that is not one.
    assert!(
        model.excitation_beyond_columns(1, 0.1 * first, 0.0).norm()
            < 0.011 * model.excitation_beyond_columns(1, first, 0.0).norm() + 1e-9
    );
    let last = frequencies.last().unwrap().omega;
    assert!(
        model
            .excitation_beyond_columns(1, 2.0 * last, 0.0)
            .norm()
            .is_finite()
    );
    assert_eq!(model.excitation_beyond_columns(1, f64::NAN, 0.0).norm(), 0.0);
    assert_eq!(model.excitation_beyond_columns(7, first, 0.0).norm(), 0.0);
}

#[test]
fn the_memory_turns_with_the_body_and_refuses_what_is_not_finite() {
    let model = sphere_model();
    let mut state = RadiationState::new(&model);
    assert!(state.fits(&model));
    // Heave up at 0.1 m/s for a while: the memory pushes back down.
    for n in 0..50 {
        state.record(&model, [0.0, 0.1, 0.0, 0.0, 0.0, 0.0], n as f64 * 0.01);
    }
    let f = state.force(&model);
    assert!(f[1] < 0.0, "{f}");
    assert!(f[0].abs() < 1e-9 * f[1].abs());
    let before = state.clone();
    state.record(&model, [f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0], 0.5);
    state.record(&model, [0.0; 6], f64::INFINITY);
    assert_eq!(state, before);
    // Turned upside down, the body's heave force points the other way in the world.
    let flipped = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI);
    let (up, _) = state.world_force(&model, &UnitQuaternion::identity());
    let (down, _) = state.world_force(&model, &flipped);
    assert!((up + down).norm() < 1e-9 * up.norm());
    // Saved and restored bit for bit.
    let text = serde_json::to_string(&state).unwrap();
    let back: RadiationState = serde_json::from_str(&text).unwrap();
    assert_eq!(back, state);
}

#[test]
fn a_body_too_heavy_to_float_is_refused() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    let body = FloatingBody {
        mesh: &mesh,
        mass: 1100.0,
        center_of_mass: Point3::origin(),
        inertia: Matrix3::identity() * 180.0,
        rotation: UnitQuaternion::identity(),
    };
    let result = RadiationModel::bake(&body, &RadiationSettings::default());
    assert!(matches!(result, Err(SeakeepingError::Sinks { .. })), "{result:?}");
    // Neutral within 0.1 %: no water-plane to float on.
    let neutral = FloatingBody { mass: 999.5, ..body };
    let result = RadiationModel::bake(&neutral, &RadiationSettings::default());
    assert!(matches!(result, Err(SeakeepingError::Sinks { .. })), "{result:?}");
    let light = FloatingBody { mass: -1.0, ..body };
    assert!(matches!(
        RadiationModel::bake(&light, &RadiationSettings::default()),
        Err(SeakeepingError::BadParameter { name: "mass", .. })
    ));
}

#[test]
fn a_square_log_rolls_onto_an_edge_and_a_barge_stays_flat() {
    // 1 × 0.5 × 0.5 m at half the water's density: flat, its metacentre
    // lies below its centre of mass (BM = B²/12T = 0.083 m, KB = 0.125 m,
    // KG = 0.25 m); it floats on an edge, turned 45° about its length.
    let settled = |mesh: &soak_bake::Mesh| {
        let mass = 500.0 * volume(mesh);
        let body = FloatingBody {
            mesh,
            mass,
            center_of_mass: Point3::origin(),
            inertia: Matrix3::identity(),
            rotation: UnitQuaternion::identity(),
        };
        let settings = RadiationSettings {
            panels: 60,
            frequencies: 8,
            ..RadiationSettings::default()
        };
        *RadiationModel::bake(&body, &settings).unwrap().rotation()
    };
    let log = settled(&builtin::cuboid(1.0, 0.5, 0.5));
    let (axis, angle) = log.axis_angle().unwrap();
    eprintln!("log: {:.3}° about {axis:?}", angle.to_degrees());
    assert!((angle.to_degrees() - 45.0).abs() < 0.05, "{}", angle.to_degrees());
    assert!((axis.x.abs() - 1.0).abs() < 1e-6);
    let barge = settled(&builtin::cuboid(4.0, 1.0, 2.0));
    assert_eq!(barge, UnitQuaternion::identity());
}

/// A box barge's wave moments as its texels' hydrostatic pressure gives
/// them (no decay with depth, no diffraction), against their closed forms
/// at every frequency of its sweep: 4 × 1 × 2 m (x, y, z) at half the
/// water's density, floating 0.5 m deep with its centre of mass on the
/// water-plane. With `f = e^{i k s}` along the wave (s = z for a beam
/// wave, x for a head one) and the half-width `b` along it, the columns'
/// moment is `∓ρ g w 2i (sin kb / k² − b cos kb / k)` (w the width across
/// the wave) and the push of the sloping surface on the sides adds
/// `ρ g i k ∫_V f (y − h) dV = ±ρ g i w T² sin kb` (T the draft):
/// in long waves `−i k ρ g V GM` in roll and `+i k ρ g V GM_L` in pitch,
/// the restoring moments of the slope. The columns alone would give
/// `ρ g V BM`: 60 % more in roll.
#[test]
fn a_barges_wave_moments_are_its_columns_and_the_push_on_its_sides() {
    let mesh = builtin::cuboid(4.0, 1.0, 2.0);
    let mass = 500.0 * volume(&mesh);
    let body = FloatingBody {
        mesh: &mesh,
        mass,
        center_of_mass: Point3::origin(),
        inertia: Matrix3::identity() * mass,
        rotation: UnitQuaternion::identity(),
    };
    let settings = RadiationSettings {
        panels: 200,
        frequencies: 8,
        ..RadiationSettings::default()
    };
    let model = RadiationModel::bake(&body, &settings).unwrap();
    let weight = 1000.0 * model.gravity();
    let draft: f64 = 0.5;
    let h = model.hydrostatics();
    for c in &model.sweep().frequencies {
        let k = c.omega * c.omega / model.gravity();
        // (mode, heading, half-width along the wave, width across it, sign)
        for (mode, heading, b, w, sign) in [(3, 0.5 * PI, 1.0, 4.0, -1.0), (5, 0.0, 2.0, 2.0, 1.0)] {
            let b: f64 = b;
            let columns = w * 2.0 * ((k * b).sin() / (k * k) - b * (k * b).cos() / k);
            let push = w * 0.5 * draft * draft * 2.0 * (k * b).sin();
            let exact = sign * weight * (columns - push);
            let ours = model.column_excitation(mode, c.omega, heading).unwrap();
            // The scale: the long-wave moment of the water-plane alone.
            let unit = weight * k * w * (2.0 * b).powi(3) / 12.0;
            assert!(
                ours.re.abs() < 1e-3 * unit && (ours.im - exact).abs() < 5e-3 * unit,
                "mode {mode}, kb {:.2}: {ours:.1} against {exact:.1}i",
                k * b
            );
            // The push along the wave, `−i k ρ g ∫_V f dV = −2i ρ g w T
            // sin kb`; nothing across it, and no yaw.
            let along = if mode == 3 { 2 } else { 0 };
            let push = model.column_excitation(along, c.omega, heading).unwrap();
            let exact = -2.0 * weight * w * draft * (k * b).sin();
            let unit = weight * w * draft * 2.0 * b * k;
            assert!(
                push.re.abs() < 1e-3 * unit && (push.im - exact).abs() < 5e-3 * unit,
                "mode {along}, kb {:.2}: {push:.1} against {exact:.1}i",
                k * b
            );
            for other in [2 - along, 4] {
                let none = model.column_excitation(other, c.omega, heading).unwrap();
                assert!(none.norm() < 1e-4 * unit, "mode {other}: {none}");
            }
        }
    }
    // The long-wave limit is the restoring moment of the slope.
    let first = model.sweep().frequencies[0].omega;
    let k = first * first / model.gravity();
    let roll = model.column_excitation(3, first, 0.5 * PI).unwrap().im;
    let pitch = model.column_excitation(5, first, 0.0).unwrap().im;
    let (c44, c55) = (h.stiffness[(3, 3)], h.stiffness[(5, 5)]);
    eprintln!(
        "long waves (kb {:.3}): roll {roll:.1} against −k C44 {:.1}; pitch {pitch:.1} against k C55 {:.1}",
        k,
        -k * c44,
        k * c55
    );
    assert!(
        (roll / (-k * c44) - 1.0).abs() < 0.01,
        "{roll} against {}",
        -k * c44
    );
    assert!(
        (pitch / (k * c55) - 1.0).abs() < 0.02,
        "{pitch} against {}",
        k * c55
    );
    // GM = KB + BM − KG = 0.25 + 4/6 − 0.5 m across, 0.25 + 16/6 − 0.5 along.
    let rho_g_v = weight * 4.0;
    assert!(
        (c44 / (rho_g_v * (0.25 + 4.0 / 6.0 - 0.5)) - 1.0).abs() < 1e-6,
        "{c44}"
    );
    assert!(
        (c55 / (rho_g_v * (0.25 + 16.0 / 6.0 - 0.5)) - 1.0).abs() < 1e-6,
        "{c55}"
    );
}
