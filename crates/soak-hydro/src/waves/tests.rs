//! The interactive waves' unit tests.

use super::*;

fn waves(cells: usize, size: f64, sponge: usize) -> InteractiveWaves {
    InteractiveWaves::new(
        WaveRegion {
            centre: [0.0, 0.0],
            size,
            cells,
        },
        9.81,
        1000.0,
        sponge,
    )
    .unwrap()
}

/// A body's water over a Gerstner sea: at every cell centre under its
/// footprint the sea's height plus the waves' elevation plus the body's
/// own depression (nodes on the cell centres: the patch is exact
/// there), and nothing of the waves outside the region.
#[test]
fn a_bodys_water_is_the_sea_plus_the_waves_less_its_hollow() {
    let mut w = waves(32, 16.0, 0);
    let n = 32;
    let h: Vec<f64> = (0..n * n).map(|i| 0.01 * ((i * 7) % 13) as f64).collect();
    w.set_state(&h, &vec![0.0; n * n]).unwrap();
    let sea = crate::Gerstner::new(
        0.2,
        vec![crate::GerstnerWave {
            amplitude: 0.3,
            wavelength: 12.0,
            direction_deg: 20.0,
            steepness: 0.5,
            phase: 0.4,
        }],
        9.81,
    )
    .unwrap();
    let base = crate::Water::new(sea.clone());
    let atlas = soak_bake::Atlas::bake(
        &soak_bake::builtin::sphere(0.6, 24, 12),
        soak_bake::BakeOptions::square(32),
    )
    .unwrap();
    let state = crate::BodyState::at_rest(nalgebra::Isometry3::translation(1.3, 0.0, -2.1));
    let own = vec![(16 * n + 18, 0.25), (17 * n + 18, 0.5)];
    let t = 3.0;
    let water = w
        .water_for(&base, &atlas, &state, &own, t, false)
        .unwrap()
        .unwrap();
    let mut checked = 0;
    for iz in 0..n {
        for ix in 0..n {
            let [x, z] = w.cell_centre(ix, iz);
            if (x - 1.3).abs() > 1.4 || (z + 2.1).abs() > 1.4 {
                continue;
            }
            let mine = own.iter().find(|c| c.0 == iz * n + ix).map_or(0.0, |c| c.1);
            let want = crate::Surface::height(&sea, x, z, t) + h[iz * n + ix] + mine;
            let got = water.surface.height(x, z, t);
            assert!((got - want).abs() < 1e-9, "cell ({ix}, {iz}): {got} vs {want}");
            checked += 1;
        }
    }
    assert!(checked >= 25, "{checked}");
    let far = crate::BodyState::at_rest(nalgebra::Isometry3::translation(100.0, 0.0, 0.0));
    assert!(w.water_for(&base, &atlas, &far, &[], t, false).unwrap().is_none());
}

/// One Fourier mode: it oscillates at `ω = √(g k)` and keeps its
/// energy, whatever the step.
#[test]
fn a_mode_turns_at_the_deep_water_frequency_and_keeps_its_energy() {
    let (n, size) = (32, 16.0);
    let mut w = waves(n, size, 0);
    let k = 2.0 * std::f64::consts::PI * 3.0 / size;
    let h: Vec<f64> = (0..n * n)
        .map(|i| 0.1 * (k * w.cell_centre(i % n, i / n)[0]).cos())
        .collect();
    w.set_state(&h, &vec![0.0; n * n]).unwrap();
    let e0 = w.energy();
    let omega = (9.81 * k).sqrt();
    let dt = 0.37;
    for _ in 0..10 {
        w.step(dt).unwrap();
    }
    let want = 0.1 * (omega * 10.0 * dt).cos();
    let [x, _] = w.cell_centre(0, 0);
    let got = w.heights()[0] / (k * x).cos();
    assert!((got - want).abs() < 1e-9, "{got} vs {want}");
    assert!((w.energy() / e0 - 1.0).abs() < 1e-9);
}

#[test]
fn bad_settings_are_typed_errors() {
    let region = WaveRegion {
        centre: [0.0, 0.0],
        size: 10.0,
        cells: 7,
    };
    assert!(InteractiveWaves::new(region, 9.81, 1000.0, 0).is_err());
    let mut w = waves(16, 8.0, 2);
    assert!(w.step(f64::NAN).is_err());
    w.pressure_mut()[3] = f64::INFINITY;
    assert!(w.step(0.1).is_err());
    assert!(w.set_state(&[0.0; 3], &[0.0; 3]).is_err());
}
