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

/// Below the mean level the water's velocity is linear theory's: without
/// divergence (the water incompressible) and without curl (the flow
/// irrotational), by central differences; above the surface the
/// surface's. And the drift it carries is `Σ a² ω k` at the surface.
#[test]
fn gerstner_water_is_incompressible_and_irrotational() {
    let sea = sea(0.7);
    let drift = sea.stokes_drift(sea.level + 1.0);
    let expected: Vector3<f64> = sea
        .waves
        .iter()
        .map(|w| {
            let k = std::f64::consts::TAU / w.wavelength;
            let (s, c) = w.direction_deg.to_radians().sin_cos();
            Vector3::new(c, 0.0, s) * w.amplitude * w.amplitude * (9.81 * k).sqrt() * k
        })
        .sum();
    assert!((drift - expected).norm() < 1e-12, "{drift} vs {expected}");
    for k in 0..50 {
        let (x, z, t) = (k as f64 * 0.37, -(k as f64) * 0.21, 3.0 + k as f64 * 0.1);
        let surface = sea.height(x, z, t);
        let p = Point3::new(x, surface.min(sea.level) - 0.05 - 0.02 * k as f64, z);
        let h = 1e-5;
        let d = |axis: usize| {
            let mut e = Vector3::zeros();
            e[axis] = h;
            (sea.velocity(&(p + e), t) - sea.velocity(&(p - e), t)) / (2.0 * h)
        };
        let (dx, dy, dz) = (d(0), d(1), d(2));
        let scale = dx.norm() + dy.norm() + dz.norm();
        let divergence = dx.x + dy.y + dz.z;
        let curl = Vector3::new(dy.z - dz.y, dz.x - dx.z, dx.y - dy.x);
        assert!(divergence.abs() < 1e-6 * scale, "div {divergence} at {p}");
        assert!(curl.norm() < 1e-6 * scale, "curl {curl} at {p}");
        let at = sea.velocity(&Point3::new(x, surface, z), t);
        let above = sea.velocity(&Point3::new(x, surface + 0.3, z), t);
        assert!((above - at).norm() < 1e-12, "{above} vs {at}");
    }
}

/// One wave, 0.25 m over 9 m: a tracer carried by the water's velocity
/// along the surface drifts forward at the Stokes drift `a² ω k` (the
/// least-squares slope of its path over 60 s, RK4): within 5 % on a sine
/// wave (1.3 % faster: the next order in `(kA)² = 0.03` and the orbit's
/// Doppler shift), within 10 % under the sharpest crests of steepness 0.6
/// (9 % slower: the trochoid's horizontal displacement, 0.86 m, lowers
/// its mean surface by 7.5 cm and the tracer with it). At
/// a fixed point 2 m down, below every trough, the mean current over a
/// period is nothing (it was a return current of about the drift's size
/// against the waves when the water moved as the Gerstner surface's
/// closed orbits).
#[test]
fn gerstner_water_drifts_with_the_waves_and_has_no_current_below_them() {
    for (steepness, tolerance) in [(0.0, 0.05), (0.6, 0.10)] {
        let (a, wavelength) = (0.25, 9.0);
        let sea = Gerstner::new(
            0.0,
            vec![GerstnerWave {
                amplitude: a,
                wavelength,
                direction_deg: 0.0,
                steepness,
                phase: 0.0,
            }],
            9.81,
        )
        .unwrap();
        let k = std::f64::consts::TAU / wavelength;
        let omega = (9.81 * k).sqrt();
        let drift = a * a * omega * k;
        assert!((sea.stokes_drift(0.0) - Vector3::x() * drift).norm() < 1e-15);
        // A tracer on the surface: (x, z), its height the surface's.
        let on_surface = |x: f64, z: f64, t: f64| {
            let y = sea.height(x, z, t);
            let v = sea.velocity(&Point3::new(x, y, z), t);
            (v.x, v.z)
        };
        let (seconds, dt) = (60.0, 0.005);
        let (mut x, mut z, mut t) = (0.0, 0.0, 0.0);
        // The least-squares slope of x(t): the mean speed, the orbit's
        // own excursion averaged out.
        let (mut st, mut sx, mut stt, mut stx, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for _ in 0..(seconds / dt) as usize {
            st += t;
            sx += x;
            stt += t * t;
            stx += t * x;
            n += 1.0;
            let k1 = on_surface(x, z, t);
            let k2 = on_surface(x + 0.5 * dt * k1.0, z + 0.5 * dt * k1.1, t + 0.5 * dt);
            let k3 = on_surface(x + 0.5 * dt * k2.0, z + 0.5 * dt * k2.1, t + 0.5 * dt);
            let k4 = on_surface(x + dt * k3.0, z + dt * k3.1, t + dt);
            x += dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            z += dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            t += dt;
        }
        let speed = (n * stx - st * sx) / (n * stt - st * st);
        assert!(
            (speed / drift - 1.0).abs() < tolerance,
            "steepness {steepness}: tracer {speed} m/s, drift {drift} m/s"
        );
        assert!(z.abs() < 1e-9);
        let period = std::f64::consts::TAU / omega;
        let below = Point3::new(1.3, -2.0, 0.0);
        let n = 2000;
        let mean: Vector3<f64> = (0..n)
            .map(|i| sea.velocity(&below, i as f64 * period / n as f64))
            .sum::<Vector3<f64>>()
            / n as f64;
        let there = sea.stokes_drift(-2.0).x;
        assert!((there - drift * (-4.0 * k).exp()).abs() < 1e-15);
        assert!(
            mean.norm() < 1e-3 * there,
            "mean current {mean} m/s, drift there {there} m/s"
        );
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
