//! Radiation on scene bodies: its model is baked when the scene
//! is built (once for bodies of one mesh, mass and orientation), and a
//! buoy released above its draft on calm water decays as linear theory
//! says instead of bobbing forever.

use soak_rapier::{LoadedScene, Simulation};

fn scene(radiation: bool) -> String {
    format!(
        "dt = 0.0166667\nduration = 6.0\n[water]\nkind = \"plane\"\n\
         [[bodies]]\nname = \"a\"\nmesh = \"builtin:sphere:0.5\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.05, 0.0]\nradiation = {radiation}\n\
         [[bodies]]\nname = \"b\"\nmesh = \"builtin:sphere:0.5\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [5.0, 0.05, 0.0]\nradiation = {radiation}\n"
    )
}

/// Heights of body 0's centre every step for `seconds`.
fn heave(radiation: bool, seconds: f64) -> (Vec<f64>, Simulation) {
    let loaded = LoadedScene::from_str(&scene(radiation), std::path::Path::new(".")).unwrap();
    let mut sim = Simulation::from_scene(&loaded).unwrap();
    let handle = sim.bodies[0].handle;
    let steps = (seconds / 0.0166667) as usize;
    let mut y = Vec::with_capacity(steps);
    for _ in 0..steps {
        sim.step().unwrap();
        y.push(sim.world.bodies[handle].translation().y as f64);
    }
    (y, sim)
}

/// Positive peaks of `x` after its start.
fn peaks(x: &[f64]) -> Vec<f64> {
    x.windows(3)
        .filter(|w| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.0)
        .map(|w| w[1])
        .collect()
}

#[test]
fn a_buoy_with_radiation_decays_and_one_without_bobs_on() {
    let (with, sim) = heave(true, 6.0);
    let (without, _) = heave(false, 6.0);
    // One model for the two bodies of one mesh, mass and orientation.
    let a = sim
        .soak
        .body(sim.bodies[0].id.unwrap())
        .unwrap()
        .effects()
        .radiation
        .clone()
        .unwrap();
    let b = sim
        .soak
        .body(sim.bodies[1].id.unwrap())
        .unwrap()
        .effects()
        .radiation
        .clone()
        .unwrap();
    assert!(std::sync::Arc::ptr_eq(&a, &b));
    let (p_with, p_without) = (peaks(&with), peaks(&without));
    eprintln!("peaks with radiation {p_with:.4?}, without {p_without:.4?}");
    // A sphere half under water: its bob falls to about 0.58 a cycle
    // (radius 0.5 m: period about 1.4 s); without radiation it keeps
    // nearly all of it.
    assert!(p_with[1] / p_with[0] < 0.7, "{p_with:?}");
    assert!(p_with[2] < 0.3 * 0.05, "{p_with:?}");
    assert!(p_without[2] > 0.8 * 0.05 - 0.01, "{p_without:?}");
}

/// The crate and ball of a first scene on a sea (density 500, the
/// two-wave swell of `data/scenes/buoy_on_waves.toml`), with the default
/// settings (radiation on, as for every body floating on a sea): ten
/// minutes of simulated time. Without radiation they are pumped
/// between −3 and +3 m; with it each follows linear theory: its heave at
/// each wave's frequency (demodulated against the wave's phase at the
/// body, which drifts) within 20 % of the model's RAO × the amplitude.
#[test]
fn a_crate_and_a_ball_on_the_swell_heave_as_linear_theory_says() {
    use soak_hydro::GerstnerWave;
    let seconds = 600.0;
    let text = format!(
        "dt = 0.0166667\nduration = {seconds}\n[water]\nkind = \"gerstner\"\nlevel = 0.0\nwaves = [\n\
         {{ amplitude = 0.25, wavelength = 9.0, direction_deg = 0.0, steepness = 0.6 }},\n\
         {{ amplitude = 0.10, wavelength = 4.0, direction_deg = 35.0, steepness = 0.4, phase = 1.0 }},\n]\n\
         [[bodies]]\nname = \"crate\"\nmesh = \"builtin:box:1x0.5x0.5\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.0, 0.0]\n\
         [[bodies]]\nname = \"ball\"\nmesh = \"builtin:sphere:0.25:32\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.0, 5.0]\n"
    );
    let loaded = LoadedScene::from_str(&text, std::path::Path::new(".")).unwrap();
    let mut sim = Simulation::from_scene(&loaded).unwrap();
    let dt = 0.0166667;
    let steps = (seconds / dt) as usize;
    let waves = GerstnerWave::SWELL;
    let g = 9.80665;
    for (i, name) in ["crate", "ball"].into_iter().enumerate() {
        assert_eq!(sim.bodies[i].name, name);
    }
    // Per body, per wave: Σ y e^{−iθ} over the last nine minutes, with θ
    // the wave's phase at the body; and the heights' range.
    let mut sums = [[(0.0f64, 0.0f64); 2]; 2];
    let mut mean = [0.0f64; 2];
    let mut heights = [(f64::INFINITY, f64::NEG_INFINITY); 2];
    let start = (60.0 / dt) as usize;
    let mut samples: [Vec<(f64, f64, f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for n in 0..steps {
        sim.step().unwrap();
        if n < start {
            continue;
        }
        let t = (n + 1) as f64 * dt;
        for (b, body) in sim.bodies.iter().enumerate() {
            let p = sim.world.bodies[body.handle].translation();
            let (x, y, z) = (p.x as f64, p.y as f64, p.z as f64);
            assert!(y.is_finite());
            heights[b] = (heights[b].0.min(y), heights[b].1.max(y));
            mean[b] += y;
            samples[b].push((t, x, y, z));
        }
    }
    for (b, body) in sim.bodies.iter().enumerate() {
        let count = samples[b].len() as f64;
        let level = mean[b] / count;
        for (w, wave) in waves.iter().enumerate() {
            let k = wave.wavenumber();
            let omega = (g * k).sqrt();
            let (s, c) = wave.direction_deg.to_radians().sin_cos();
            for &(t, x, y, z) in &samples[b] {
                let theta = k * (c * x + s * z) - omega * t + wave.phase;
                sums[b][w].0 += (y - level) * theta.cos();
                sums[b][w].1 -= (y - level) * theta.sin();
            }
            let measured = 2.0 * sums[b][w].0.hypot(sums[b][w].1) / count;
            let model = sim
                .soak
                .body(body.id.unwrap())
                .unwrap()
                .effects()
                .radiation
                .clone()
                .unwrap();
            // The wave's heading in the body's axes at rest, as it lies now.
            let rotation = sim.world.bodies[body.handle].rotation();
            let rotation = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                rotation.w as f64,
                rotation.x as f64,
                rotation.y as f64,
                rotation.z as f64,
            ));
            let frame = model.heading(&rotation) * model.rotation().inverse();
            let along = frame.inverse() * nalgebra::Vector3::new(c, 0.0, s);
            let predicted = model.rao(1, omega, along.z.atan2(along.x)).unwrap() * wave.amplitude;
            eprintln!(
                "{}: heights {:+.3} to {:+.3} m; ω {omega:.3} rad/s: heave {measured:.4} m, linear theory {predicted:.4} m",
                body.name, heights[b].0, heights[b].1
            );
            assert!(
                (measured / predicted - 1.0).abs() < 0.2,
                "{} at ω {omega}: {measured} against {predicted}",
                body.name
            );
        }
        // No pump: within the crest and trough and a body's size.
        assert!(heights[b].0 > -0.8 && heights[b].1 < 0.8, "{:?}", heights[b]);
    }
}

/// Whether a scene body radiates when the scene does not say: on for a
/// body floating on a Gerstner sea, off on calm water, with interactive
/// waves (bodies make their waves there), for a body told `false`, one
/// with `added_mass`, and one too heavy to float (no error: it sinks
/// without); `true` for a body too heavy to float is an error naming it.
#[test]
fn radiation_is_on_by_default_for_bodies_floating_on_a_sea_only() {
    let sea = "[water]\nkind = \"gerstner\"\nwaves = [{ amplitude = 0.1, wavelength = 6.0, direction_deg = 0.0, steepness = 0.0 }]\n";
    let calm = "[water]\nkind = \"plane\"\n";
    let body = |extra: &str| {
        format!(
            "[[bodies]]\nname = \"b\"\nmesh = \"builtin:box:0.6x0.4x0.5\"\nresolution = 32\n\
             mass = {{ model = \"solid\", density = 500.0 }}\n{extra}\n"
        )
    };
    let radiates = |text: String| -> Result<bool, String> {
        let text = format!("dt = 0.0166667\nduration = 1.0\n{text}");
        let loaded = LoadedScene::from_str(&text, std::path::Path::new(".")).map_err(|e| e.to_string())?;
        let sim = Simulation::from_scene(&loaded).map_err(|e| e.to_string())?;
        let id = sim.bodies[0].id.unwrap();
        Ok(sim.soak.body(id).unwrap().effects().radiation.is_some())
    };
    assert!(radiates(format!("{sea}{}", body(""))).unwrap());
    assert!(!radiates(format!("{calm}{}", body(""))).unwrap());
    assert!(radiates(format!("{calm}{}", body("radiation = true"))).unwrap());
    assert!(!radiates(format!("{sea}{}", body("radiation = false"))).unwrap());
    assert!(!radiates(format!("{sea}{}", body("added_mass = true"))).unwrap());
    let waves = "[waves]\nsize = 64.0\ncells = 64\n";
    assert!(!radiates(format!("{sea}{waves}{}", body(""))).unwrap());
    let heavy = |extra: &str| {
        format!(
            "[[bodies]]\nname = \"anchor\"\nmesh = \"builtin:box:0.3x0.3x0.3\"\nresolution = 32\n\
             mass = {{ model = \"solid\", density = 3000.0 }}\n{extra}\n"
        )
    };
    assert!(!radiates(format!("{sea}{}", heavy(""))).unwrap());
    let refused = radiates(format!("{sea}{}", heavy("radiation = true"))).unwrap_err();
    assert!(
        refused.contains("anchor") && refused.contains("radiation"),
        "{refused}"
    );
}
