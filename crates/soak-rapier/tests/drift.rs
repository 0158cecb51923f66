//! Flotsam drifts with the waves: small bodies with drag on a sea move
//! along the waves' direction at about the Stokes drift, as linear theory's
//! water carries them (the Gerstner surface's own closed orbits, read as
//! the water's velocity, carried them backwards at 0.09–0.14 m/s).

use soak_hydro::{Gerstner, GerstnerWave};
use soak_rapier::{LoadedScene, Simulation};

const G: f64 = 9.80665;

/// The least-squares slope of each body's x and z over `from`..`seconds`
/// (m/s): its mean drift, the orbit's own excursion averaged out.
fn drifts(text: &str, seconds: f64, from: f64) -> Vec<(String, f64, f64)> {
    let loaded = LoadedScene::from_str(text, std::path::Path::new(".")).unwrap();
    let mut sim = Simulation::from_scene(&loaded).unwrap();
    let dt = loaded.scene.dt;
    let n = sim.bodies.len();
    // Per body: Σt, Σx, Σz, Σt², Σtx, Σtz, count.
    let mut sums = vec![[0.0f64; 7]; n];
    let steps = (seconds / dt).round() as usize;
    for _ in 0..steps {
        sim.step().unwrap();
        let t = sim.time();
        if t < from {
            continue;
        }
        for (i, s) in sums.iter_mut().enumerate() {
            let p = sim.world.bodies[sim.bodies[i].handle].translation();
            let (x, z) = (p.x as f64, p.z as f64);
            for (k, v) in [t, x, z, t * t, t * x, t * z, 1.0].into_iter().enumerate() {
                s[k] += v;
            }
        }
    }
    sums.iter()
        .enumerate()
        .map(|(i, s)| {
            let slope = |sy: f64, sty: f64| (s[6] * sty - s[0] * sy) / (s[6] * s[3] - s[0] * s[0]);
            (sim.bodies[i].name.clone(), slope(s[1], s[4]), slope(s[2], s[5]))
        })
        .collect()
}

fn ball(name: &str, radius: f64, z: f64, extra: &str) -> String {
    format!(
        "[[bodies]]\nname = \"{name}\"\nmesh = \"builtin:sphere:{radius}:24\"\nresolution = 32\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.0, {z}]\n\
         drag = {{ coefficient = 1.0, linear = 50.0 }}\n{extra}\n"
    )
}

/// A regular sea, one sine wave 0.25 m high over 9 m along +x: balls of
/// 5 and 10 cm radius with drag, their pressure on the hull integrated
/// (so that the wave moves them back and forth as it moves the water),
/// drift along +x within 20 % of the Stokes drift at the surface,
/// `a² ω k` = 0.114 m/s (0.997 and 1.009 of it measured: their radiation
/// damps their orbit and the diffraction linear theory adds drives it), and
/// not sideways.
#[test]
fn small_balls_drift_with_a_regular_sea_at_the_stokes_drift() {
    balls_drift_on_the_regular_sea("");
}

/// The balls of the regular sea's tests, the sea read as `sampling` says
/// (a line of the scene's `[water]`, empty for the default): each drifts
/// along +x within 20 % of the Stokes drift, and not sideways.
fn balls_drift_on_the_regular_sea(sampling: &str) {
    let wave = GerstnerWave {
        amplitude: 0.25,
        wavelength: 9.0,
        direction_deg: 0.0,
        steepness: 0.0,
        phase: 0.0,
    };
    let drift = Gerstner::new(0.0, vec![wave], G).unwrap().stokes_drift(0.0).x;
    let text = format!(
        "dt = 0.0166667\nduration = 70.0\n[water]\nkind = \"gerstner\"\nlevel = 0.0\n{sampling}\nwaves = [\n\
         {{ amplitude = 0.25, wavelength = 9.0, direction_deg = 0.0, steepness = 0.0 }},\n]\n{}{}",
        ball("small", 0.05, 0.0, "buoyancy = \"pressure\""),
        ball("ball", 0.1, 3.0, "buoyancy = \"pressure\""),
    );
    for (name, vx, vz) in drifts(&text, 70.0, 10.0) {
        let ratio = vx / drift;
        println!("{name}: {vx:.4} m/s along the wave ({ratio:.3} of the drift), {vz:.4} across");
        assert!((ratio - 1.0).abs() < 0.2, "{name}: {vx} m/s against {drift}");
        assert!(vz.abs() < 0.2 * drift, "{name}: {vz} m/s across the wave");
    }
}

/// The two-wave swell of the `buoy_on_waves` scene, with default settings
/// (Archimedes' vertical buoyancy, radiation on): the crate and the ball
/// the issue tried, and a ball of 10 cm, with its drag, drift along the
/// waves (0.61, 0.71 and 0.86 of the surface drift, 0.165 m/s along +x,
/// measured), no longer against them. Vertical buoyancy leaves the
/// bodies' back-and-forth to the drag alone: they lag the water's orbit,
/// and drift slower than it.
#[test]
fn flotsam_drifts_along_the_swell_not_against_it() {
    flotsam_drifts_on_the_swell("");
}

/// The flotsam above with the swell read as one plane over each body
/// (`sampling = "plane"`): the crate, more than an eighth of the swell's
/// 4 m waves across, reads a current changing linearly over it, the balls
/// (within an eighth) one current each; all drift along the waves as the
/// sampled read has them drift.
#[test]
fn flotsam_reading_the_swell_as_planes_drifts_along_it() {
    flotsam_drifts_on_the_swell("sampling = \"plane\"\n");
}

/// The flotsam of the swell's tests, the sea read as `sampling` says (a
/// line of the scene's `[water]`, empty for the default).
fn flotsam_drifts_on_the_swell(sampling: &str) {
    let sea = Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), G).unwrap();
    let drift = sea.stokes_drift(0.0);
    let text = format!(
        "dt = 0.0166667\nduration = 70.0\n[water]\nkind = \"gerstner\"\nlevel = 0.0\n{sampling}waves = [\n\
         {{ amplitude = 0.25, wavelength = 9.0, direction_deg = 0.0, steepness = 0.6 }},\n\
         {{ amplitude = 0.10, wavelength = 4.0, direction_deg = 35.0, steepness = 0.4, phase = 1.0 }},\n]\n\
         [[bodies]]\nname = \"crate\"\nmesh = \"builtin:box:1x0.5x0.5\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.0, 0.0]\n\
         drag = {{ coefficient = 1.0, linear = 50.0 }}\n\
         [[bodies]]\nname = \"ball\"\nmesh = \"builtin:sphere:0.25:32\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.0, 5.0]\n\
         drag = {{ coefficient = 1.0, linear = 50.0 }}\n{}",
        ball("small", 0.1, -5.0, ""),
    );
    for (name, vx, vz) in drifts(&text, 70.0, 10.0) {
        let ratio = vx / drift.x;
        println!("{name}: {vx:.4} m/s along +x ({ratio:.3} of the drift), {vz:.4} along +z");
        assert!(
            (0.4..1.1).contains(&ratio),
            "{name}: {vx} m/s against {}",
            drift.x
        );
        assert!(vz.abs() < drift.x, "{name}: {vz} m/s along z");
    }
}

/// A spectral sea (JONSWAP, Hs 0.35 m, Tp 2.4 s: its peak wave 9 m long,
/// as the sine wave above; spreading 20 about +x): a ball of 5 cm with
/// drag and pressure buoyancy drifts along the sea within 20 % of its
/// Stokes drift at the surface (`SpectralSurface::stokes_drift`, 0.055
/// m/s; 0.86 of it measured), averaged over 60 s; a ball of 10 cm drifts
/// along it faster (1.5 times: the pressure of the sea's short waves on
/// its hull, a wave drift force, pushes it on), within a factor 2.
#[test]
fn small_balls_drift_with_a_spectral_sea_at_the_stokes_drift() {
    let text = format!(
        "dt = 0.0166667\nduration = 70.0\n[water]\nkind = \"spectrum\"\nsignificant_height = 0.35\n\
         peak_period = 2.4\nspreading = 20.0\nseed = 3\n{}{}",
        ball("small", 0.05, 0.0, "buoyancy = \"pressure\""),
        ball("ball", 0.1, 3.0, "buoyancy = \"pressure\""),
    );
    let loaded = LoadedScene::from_str(&text, std::path::Path::new(".")).unwrap();
    let sea = loaded.scene.water.spectral_sea(G).unwrap();
    let drift = soak_hydro::SpectralSurface::new(sea).stokes_drift(0.0);
    for (name, vx, vz) in drifts(&text, 70.0, 10.0) {
        let ratio = vx / drift.x;
        println!(
            "{name}: {vx:.4} m/s along +x ({ratio:.3} of the drift {:.4}), {vz:.4} along +z (drift {:.4})",
            drift.x, drift.z
        );
        let allowed = if name == "small" { 0.8..1.2 } else { 0.5..2.0 };
        assert!(allowed.contains(&ratio), "{name}: {vx} m/s against {}", drift.x);
        assert!(vz.abs() < 0.3 * drift.x, "{name}: {vz} m/s across the sea");
    }
}

/// The regular sea above read as one plane over each ball (`sampling =
/// "plane"`: the plane fitted over the ball, the water's velocity at its
/// centre as the current): the balls still drift along +x within 20 % of
/// the Stokes drift, and not sideways.
#[test]
fn small_balls_reading_the_sea_as_a_plane_drift_at_the_stokes_drift() {
    balls_drift_on_the_regular_sea("sampling = \"plane\"");
}
