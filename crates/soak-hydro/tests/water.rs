//! Water surfaces: heights and velocities against their definitions.

use nalgebra::{Point3, Vector3};
use soak_hydro::{Gerstner, GerstnerWave, HeightField, Plane, Surface};

fn sea(steepness: f64) -> Gerstner {
    Gerstner::new(
        0.2,
        vec![
            GerstnerWave {
                amplitude: 0.5,
                wavelength: 10.0,
                direction_deg: 10.0,
                steepness,
                phase: 0.0,
            },
            GerstnerWave {
                amplitude: 0.2,
                wavelength: 3.7,
                direction_deg: 75.0,
                steepness,
                phase: 2.0,
            },
            GerstnerWave {
                amplitude: 0.1,
                wavelength: 1.3,
                direction_deg: -40.0,
                steepness,
                phase: 0.5,
            },
        ],
        9.81,
    )
    .unwrap()
}

#[test]
fn gerstner_height_is_the_height_of_the_particle_above_that_point() {
    for steepness in [0.0, 0.5, 0.9, 0.99] {
        let sea = sea(steepness);
        for k in 0..200 {
            let (x0, z0, t) = (k as f64 * 0.173 - 17.0, k as f64 * 0.311 - 30.0, k as f64 * 0.05);
            let p = sea.particle(x0, z0, t);
            let h = sea.height(p.x, p.z, t);
            assert!((h - p.y).abs() < 1e-9, "steepness {steepness}: {h} vs {}", p.y);
        }
    }
}

#[test]
fn gerstner_velocity_is_the_particle_velocity_at_the_surface() {
    let sea = sea(0.7);
    for k in 0..50 {
        let (x0, z0, t) = (k as f64 * 0.37, -(k as f64) * 0.21, 3.0 + k as f64 * 0.1);
        let p = sea.particle(x0, z0, t);
        let e = 1e-6;
        let d = (sea.particle(x0, z0, t + e) - sea.particle(x0, z0, t - e)) / (2.0 * e);
        // At or above the mean level the orbital velocity has no decay.
        let probe = Point3::new(p.x, p.y.max(sea.level), p.z);
        let v = sea.velocity(&probe, t);
        if p.y >= sea.level {
            assert!((v - d).norm() < 1e-5 * (1.0 + d.norm()), "{v} vs {d}");
        }
        let bounds = sea.height_bounds(t).unwrap();
        assert!(p.y >= bounds.0 - 1e-12 && p.y <= bounds.1 + 1e-12);
    }
}

#[test]
fn a_sine_wave_travels_at_the_deep_water_phase_speed() {
    let sea = Gerstner::new(
        0.0,
        vec![GerstnerWave {
            amplitude: 0.1,
            wavelength: 20.0,
            direction_deg: 0.0,
            steepness: 0.0,
            phase: 0.0,
        }],
        9.81,
    )
    .unwrap();
    // c = √(g λ / 2π): a crest at x = 0 at t = 0 is at x = c t later.
    let c = (9.81 * 20.0 / std::f64::consts::TAU).sqrt();
    let t = 1.3;
    assert!((sea.height(c * t, 0.0, t) - 0.1).abs() < 1e-9);
}

#[test]
fn planes_and_height_fields() {
    let p = Plane::tilted(Point3::new(1.0, 2.0, 3.0), Vector3::new(0.0, 1.0, 1.0)).unwrap();
    assert!((p.height(1.0, 3.0, 0.0) - 2.0).abs() < 1e-12);
    assert!((p.height(1.0, 4.0, 0.0) - 1.0).abs() < 1e-12);
    assert_eq!(p.height_bounds(0.0), None);
    assert_eq!(Plane::horizontal(0.5).height_bounds(0.0), Some((0.5, 0.5)));
    let hf = HeightField::new([0.0, 0.0], [1.0, 2.0], 2, 2, vec![0.0, 1.0, 2.0, 3.0]).unwrap();
    assert!((hf.height(0.5, 1.0, 0.0) - 1.5).abs() < 1e-12);
    assert_eq!(hf.height(-5.0, -5.0, 0.0), 0.0);
    assert_eq!(hf.height(9.0, 9.0, 0.0), 3.0);
    assert!(HeightField::new([0.0, 0.0], [1.0, 1.0], 2, 2, vec![0.0; 3]).is_err());
    assert!(HeightField::new([0.0, 0.0], [1.0, 1.0], 2, 2, vec![0.0, f64::NAN, 0.0, 0.0]).is_err());
}

/// A surface that gives only its heights: `Surface::slope` differentiates it.
struct Ripple;
impl Surface for Ripple {
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        0.3 * (x.sin() * (0.5 * z).cos())
    }
}

#[test]
fn slopes_are_the_derivatives_of_the_heights() {
    let central = |s: &dyn Surface, x: f64, z: f64, t: f64| {
        let h = 1e-6;
        [
            (s.height(x + h, z, t) - s.height(x - h, z, t)) / (2.0 * h),
            (s.height(x, z + h, t) - s.height(x, z - h, t)) / (2.0 * h),
        ]
    };
    for steepness in [0.0, 0.5, 0.9] {
        let sea = sea(steepness);
        for (x, z, t) in [(0.3, -1.2, 0.0), (2.7, 0.4, 1.7), (-4.1, 3.3, 5.2)] {
            let s = sea.slope(x, z, t, &[0.0, 0.0]);
            let c = central(&sea, x, z, t);
            for k in 0..2 {
                assert!(
                    (s[k] - c[k]).abs() < 1e-6,
                    "steepness {steepness} at ({x}, {z}, {t}): {s:?} vs {c:?}"
                );
            }
        }
    }
    // The default: central differences of the heights.
    for (x, z) in [(0.2, 0.1), (1.4, -2.0)] {
        let s = Ripple.slope(x, z, 0.0, &[0.0, 0.0]);
        let exact = [0.3 * x.cos() * (0.5 * z).cos(), -0.15 * x.sin() * (0.5 * z).sin()];
        assert!(
            (s[0] - exact[0]).abs() < 1e-8 && (s[1] - exact[1]).abs() < 1e-8,
            "{s:?} vs {exact:?}"
        );
    }
    // h = x + z on this grid (spacing 1 by 2, heights 0, 1, 2, 3); flat
    // outside it, where the edge value holds.
    let hf = HeightField::new([0.0, 0.0], [1.0, 2.0], 2, 2, vec![0.0, 1.0, 2.0, 3.0]).unwrap();
    assert_eq!(hf.slope(0.5, 1.0, 0.0, &[0.0, 0.0]), [1.0, 1.0]);
    assert_eq!(hf.slope(-3.0, 1.0, 0.0, &[0.0, 0.0]), [0.0, 1.0]);
    assert_eq!(hf.slope(9.0, 9.0, 0.0, &[0.0, 0.0]), [0.0, 0.0]);
    let p = Plane::tilted(Point3::new(1.0, 2.0, 3.0), Vector3::new(0.0, 1.0, 1.0)).unwrap();
    let s = p.slope(5.0, -7.0, 0.0, &[0.0, 0.0]);
    assert!(s[0].abs() < 1e-15 && (s[1] + 1.0).abs() < 1e-12, "{s:?}");
}
