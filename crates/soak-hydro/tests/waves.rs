//! The interactive wave surface against deep-water theory: the ring a
//! disturbance spreads into puts each wavelength where the group velocity
//! has carried it (Cauchy–Poisson); a pressure patch towed at constant speed
//! leaves a Kelvin wake of half-angle arcsin(1/3) = 19.47° at two speeds;
//! without pressure the energy is kept, and the work a pressure does is the
//! energy in the waves plus what the sponge took.

use soak_hydro::{InteractiveWaves, WaveRegion};

const G: f64 = 9.81;

fn region(size: f64, cells: usize) -> WaveRegion {
    WaveRegion {
        centre: [0.0, 0.0],
        size,
        cells,
    }
}

/// A Gaussian hump spreads into a ring whose waves obey stationary phase:
/// the wave of wavenumber `k` is at `r = c_g t = ½ √(g/k) t`, so the phase
/// `g t² / (4 r)` grows by 2π from one crest to the next one inwards.
#[test]
fn a_rings_crests_are_where_the_group_velocity_carries_them() {
    let (size, cells) = (64.0, 256);
    let mut waves = InteractiveWaves::new(region(size, cells), G, 1000.0, 16).unwrap();
    let n = cells;
    let sigma: f64 = 0.4;
    let h: Vec<f64> = (0..n * n)
        .map(|i| {
            let [x, z] = waves.cell_centre(i % n, i / n);
            0.05 * (-(x * x + z * z) / (2.0 * sigma * sigma)).exp()
        })
        .collect();
    waves.set_state(&h, &vec![0.0; n * n]).unwrap();
    let dt = 1.0 / 30.0;
    println!("| t (s) | crest r (m) | next crest r (m) | Δ(g t²/4r) / 2π |");
    println!("|---|---|---|---|");
    let mut checked = 0;
    for (steps, t) in [(180, 6.0), (60, 8.0), (60, 10.0), (60, 12.0)] {
        for _ in 0..steps {
            waves.step(dt).unwrap();
        }
        // Crests along +x, between 2 m and 24 m from the centre (the
        // sponge starts at 28 m), found as local maxima of the profile
        // read every tenth of a cell.
        let crests = waves.crests([0.0, 0.0], 0.0, 2.0, 24.0);
        // Pairs of crests whose waves have at least six cells a
        // wavelength, where stationary phase holds (far enough out along
        // the ring, at least a wavelength and a half of it).
        for (r1, r2, ratio) in InteractiveWaves::phase_steps(&crests, t, G, 6.0 * size / cells as f64) {
            println!("| {t} | {r1:.2} | {r2:.2} | {ratio:.3} |");
            assert!(
                (ratio - 1.0).abs() < 0.1,
                "t {t}: crests at {r1} and {r2}: {ratio}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 6, "{checked} crest pairs");
}

/// A round pressure patch (a hull of draft 5 cm, σ = 0.3 m, its draft
/// eased in over 4 s) towed 40 m across still deep water at 1.5 and
/// 2.5 m/s: the wake's half-angle 11 to 20 m behind it is Kelvin's 19.47°
/// at both speeds.
#[test]
fn a_towed_source_leaves_a_kelvin_wake_of_19_5_degrees_at_two_speeds() {
    println!("| speed (m/s) | 11 m behind | 14 m | 17 m | 20 m | mean (°) | Kelvin (°) |");
    println!("|---|---|---|---|---|---|---|");
    for speed in [1.5, 2.5] {
        let mut waves = InteractiveWaves::new(region(64.0, 256), G, 1000.0, 16).unwrap();
        let dt = 1.0 / 30.0;
        let start = -24.0;
        let steps = (40.0 / speed / dt) as usize;
        for k in 0..steps {
            let t = (k as f64 + 0.5) * dt;
            let ease = (t / 4.0).min(1.0);
            waves.clear_pressure();
            waves.add_gaussian(
                start + speed * t,
                0.0,
                0.3,
                0.05 * ease * ease * (3.0 - 2.0 * ease),
            );
            waves.step(dt).unwrap();
        }
        let source = start + speed * steps as f64 * dt;
        let angles: Vec<f64> = [11.0, 14.0, 17.0, 20.0]
            .iter()
            .map(|&s| waves.wake_half_angle([source, 0.0], 0.0, s))
            .collect();
        let mean = angles.iter().sum::<f64>() / angles.len() as f64;
        println!(
            "| {speed} | {:.1} | {:.1} | {:.1} | {:.1} | {mean:.2} | 19.47 |",
            angles[0], angles[1], angles[2], angles[3]
        );
        assert!((mean - 19.47).abs() < 2.0, "{speed} m/s: {mean}°");
        assert!(
            angles.iter().all(|a| (a - 19.47).abs() < 3.0),
            "{speed} m/s: {angles:?}"
        );
    }
}

/// Without pressure the waves keep their energy exactly; with a patch
/// pushed down and let go, the energy in the waves plus what the sponge
/// took equals the work the pressure did, `−∫ p ∂h/∂t dA dt`.
#[test]
fn the_pressures_work_is_the_waves_energy() {
    let (size, cells) = (32.0, 128);
    let mut waves = InteractiveWaves::new(region(size, cells), G, 1000.0, 8).unwrap();
    let n = cells;
    let area = (size / cells as f64).powi(2);
    let dt = 1.0 / 60.0;
    let mut work = 0.0;
    for k in 0..600 {
        waves.clear_pressure();
        // A buoy of radius ~1 m heaving 5 cm for two seconds, then gone.
        if k < 120 {
            let draft = 0.05 * (1.0 - (2.0 * std::f64::consts::PI * k as f64 * dt).cos());
            waves.add_gaussian(0.0, 0.0, 0.5, draft);
        }
        let before = waves.heights().to_vec();
        let p: Vec<f64> = waves.pressure_mut().to_vec();
        waves.step(dt).unwrap();
        // −∫ p ∂h/∂t dA over the step (p held, ∂h/∂t ≈ Δh/dt): ρ (p/ρ) Δh.
        work -= 1000.0
            * (0..n * n)
                .map(|i| p[i] * (waves.heights()[i] - before[i]))
                .sum::<f64>()
            * area;
    }
    let energy = waves.energy();
    let total = energy + waves.absorbed();
    println!(
        "work done by the pressure {work:.4} J; waves {energy:.4} J + absorbed {:.4} J = {total:.4} J",
        waves.absorbed()
    );
    assert!(
        work > 0.0 && (total / work - 1.0).abs() < 0.02,
        "{total} vs {work}"
    );
    // Then free: nothing changes the energy but the sponge.
    let mut free = InteractiveWaves::new(region(size, cells), G, 1000.0, 0).unwrap();
    free.set_state(waves.heights(), &vec![0.0; n * n]).unwrap();
    let e0 = free.energy();
    for _ in 0..100 {
        free.step(dt).unwrap();
    }
    assert!((free.energy() / e0 - 1.0).abs() < 1e-9);
}

/// A floating cube pressing on the surface: each cell under it holds its
/// draft, and the cells' columns add up to its submerged volume; a sphere
/// wholly under water presses with its whole volume.
#[test]
fn a_hull_presses_with_its_submerged_columns() {
    use nalgebra::Isometry3;
    use soak_bake::{Atlas, BakeOptions, builtin};
    use soak_hydro::{BodyState, Water};

    let mut waves = InteractiveWaves::new(region(16.0, 64), G, 1000.0, 0).unwrap();
    let cell_area = 0.25 * 0.25;
    let cube = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(256)).unwrap();
    let floating = BodyState::at_rest(Isometry3::translation(0.0, 0.0, 0.0));
    let pressed = waves.press(&cube, &Water::calm(0.0), &floating, 0.0).unwrap();
    // The walls' texels on the cells' edges press nothing (their area is
    // all horizontal) but touch the cells beside.
    let under: Vec<&(usize, f64)> = pressed.iter().filter(|p| p.1.abs() > 1e-9).collect();
    assert_eq!(under.len(), 16, "the 4 × 4 cells under a 1 m cube at 0.25 m");
    for &&(cell, depth) in &under {
        // Each texel falls into one cell: a cell's share is its draft to
        // about a row of texels either side (a face of the 256² bake is
        // about 85 texels across, a 0.25 m cell about 21).
        assert!((depth - 0.5).abs() < 0.04, "cell {cell}: {depth} m");
        assert!((waves.pressure_mut()[cell] - G * depth).abs() < 1e-12);
    }
    let volume: f64 = pressed.iter().map(|p| p.1).sum::<f64>() * cell_area;
    assert!((volume - 0.5).abs() < 0.005, "{volume} m³");
    waves.clear_pressure();
    let sphere = Atlas::bake(&builtin::sphere(0.5, 48, 24), BakeOptions::square(256)).unwrap();
    let under = BodyState::at_rest(Isometry3::translation(1.1, -2.0, -0.7));
    let pressed = waves.press(&sphere, &Water::calm(0.0), &under, 0.0).unwrap();
    let volume: f64 = pressed.iter().map(|p| p.1).sum::<f64>() * cell_area;
    assert!(
        (volume / sphere.volume() - 1.0).abs() < 1e-6,
        "{volume} vs {}",
        sphere.volume()
    );
}

/// Moving the region keeps the surface where it is in the world.
#[test]
fn the_region_follows_without_moving_the_waves() {
    let mut waves = InteractiveWaves::new(region(16.0, 64), G, 1000.0, 0).unwrap();
    waves.add_gaussian(3.0, 2.0, 0.6, 0.1);
    for _ in 0..10 {
        waves.step(1.0 / 30.0).unwrap();
    }
    waves.clear_pressure();
    let probe = [(3.0, 2.0), (2.2, 1.4), (4.1, 2.9)];
    let before: Vec<f64> = probe.iter().map(|&(x, z)| waves.height(x, z)).collect();
    let shift = waves.recentre([1.0, -0.5]);
    assert_eq!(shift, (4, -2));
    assert_eq!(waves.region().centre, [1.0, -0.5]);
    for (k, &(x, z)) in probe.iter().enumerate() {
        assert!((waves.height(x, z) - before[k]).abs() < 1e-12, "at ({x}, {z})");
    }
}

/// A body on the waves over a sea floats on the sum of the two: at every
/// node of the patch it reads (the cells' centres), the height is the
/// sea's (found by inverting its choppy map, for the spectral sea) plus
/// the waves', on a Gerstner sea and on a spectral one alike.
#[test]
fn the_waves_ride_on_a_gerstner_and_a_spectral_sea() {
    use nalgebra::Isometry3;
    use soak_bake::{Atlas, BakeOptions, builtin};
    use soak_hydro::{BodyState, Gerstner, GerstnerWave, SeaSpectrum, SpectralSea, SpectralSurface, Water};

    let mut waves = InteractiveWaves::new(region(16.0, 64), G, 1000.0, 0).unwrap();
    waves.add_gaussian(1.0, -0.5, 0.8, 0.1);
    for _ in 0..15 {
        waves.step(1.0 / 30.0).unwrap();
    }
    let sphere = Atlas::bake(&builtin::sphere(0.5, 24, 12), BakeOptions::square(64)).unwrap();
    let state = BodyState::at_rest(Isometry3::translation(0.6, 0.0, -0.2));
    let spectrum = SeaSpectrum::jonswap(0.5, 3.0);
    let seas = [
        (
            "gerstner",
            Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), G).unwrap()),
        ),
        (
            "spectral",
            Water::new(SpectralSurface::new(
                SpectralSea::realize(&spectrum, 0.0, 56.0, 64, 4, G).unwrap(),
            )),
        ),
    ];
    let t = 1.3;
    for (name, sea) in &seas {
        let water = waves
            .water_for(sea, &sphere, &state, &[], t, false)
            .unwrap()
            .unwrap();
        let mut checked = 0;
        for iz in 0..64 {
            for ix in 0..64 {
                let [x, z] = waves.cell_centre(ix, iz);
                if (x - 0.6).hypot(z + 0.2) > 0.9 {
                    continue;
                }
                let expected = sea.surface.height(x, z, t) + waves.height(x, z);
                let read = water.surface.height(x, z, t);
                assert!(
                    (read - expected).abs() < 1e-9,
                    "{name} at ({x}, {z}): {read} vs {expected}"
                );
                checked += 1;
            }
        }
        assert!(checked > 30, "{name}: {checked} nodes");
        println!("{name}: {checked} nodes of the patch are the sea's height plus the waves'");
    }
}
