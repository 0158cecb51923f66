//! Stern's closed form for the mean diffuse reflectance, and the internal
//! reflectance built on it, against an independent numerical integration of
//! Fresnel's equations written here (not the crate's `fresnel_dielectric`).

use soak_shade::{internal_reflectance, stern_mean_reflectance};
use std::f64::consts::FRAC_PI_2;

/// Unpolarised Fresnel reflectance for light going from index 1 into
/// relative index `m` at incidence angle `theta` (radians); total internal
/// reflection beyond the critical angle when `m < 1`.
fn fresnel(theta: f64, m: f64) -> f64 {
    let (si, ci) = theta.sin_cos();
    let st = si / m; // Snell
    if st >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - st * st).sqrt();
    let rs = (ci - m * ct) / (ci + m * ct);
    let rp = (m * ci - ct) / (m * ci + ct);
    0.5 * (rs * rs + rp * rp)
}

/// Composite Simpson rule of `f` over `[a, b]` with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * f(a + i as f64 * h);
    }
    s * h / 3.0
}

/// `2 ∫₀^{π/2} R(θ, m) cos θ sin θ dθ`. For `m < 1` the integral is split
/// at the critical angle θc, beyond which R = 1, and below it the variable
/// change θ = θc(1 − (1 − t)²) removes the square-root singularity of R's
/// slope at θc, so Simpson converges at its usual rate.
fn hemispherical_mean(m: f64) -> f64 {
    let f = |t: f64| 2.0 * fresnel(t, m) * t.cos() * t.sin();
    if m < 1.0 {
        let tc = m.asin();
        let below = |t: f64| {
            let u = 1.0 - t;
            f(tc * (1.0 - u * u)) * 2.0 * tc * u
        };
        simpson(below, 0.0, 1.0, 200_000) + simpson(f, tc, FRAC_PI_2, 2_000)
    } else {
        simpson(f, 0.0, FRAC_PI_2, 200_000)
    }
}

#[test]
fn thesis_oracles_hold() {
    // Independent numerical integrations quoted in DESIGN.md.
    for (n, r_bar, p) in [(1.333, 0.066406, 0.474591), (1.5, 0.091778, 0.596346)] {
        let r = stern_mean_reflectance(n);
        let q = internal_reflectance(n);
        assert!((r - r_bar).abs() < 1e-6, "R̄({n}) = {r}, expected {r_bar}");
        assert!((q - p).abs() < 1e-6, "p({n}) = {q}, expected {p}");
    }
}

#[test]
fn closed_form_matches_fresnel_integral() {
    for n in [
        1.001, 1.01, 1.03, 1.05, 1.1, 1.2, 1.31, 1.333, 1.4, 1.5, 1.7, 2.0, 2.42, 3.0, 4.0,
    ] {
        let numeric = hemispherical_mean(n);
        let closed = stern_mean_reflectance(n);
        assert!(
            (numeric - closed).abs() < 1e-11,
            "n = {n}: closed form {closed}, integral {numeric}, diff {:e}",
            numeric - closed
        );
    }
}

#[test]
fn internal_reflectance_matches_fresnel_integral_from_inside() {
    // p is the same hemispherical mean, seen from inside the liquid.
    for n in [1.01, 1.1, 1.2, 1.333, 1.5, 2.0, 3.0] {
        let numeric = hemispherical_mean(1.0 / n);
        let p = internal_reflectance(n);
        assert!(
            (numeric - p).abs() < 1e-11,
            "n = {n}: p = {p}, integral from inside {numeric}"
        );
    }
}

#[test]
fn stern_extends_to_light_leaving_the_liquid() {
    for n in [1.1, 1.333, 2.0] {
        assert!((stern_mean_reflectance(1.0 / n) - internal_reflectance(n)).abs() < 1e-15);
    }
    assert_eq!(stern_mean_reflectance(1.0), 0.0);
    assert_eq!(internal_reflectance(1.0), 0.0);
    assert_eq!(stern_mean_reflectance(f64::INFINITY), 1.0);
    assert!(stern_mean_reflectance(0.0).is_nan());
    assert!(stern_mean_reflectance(-1.5).is_nan());
    assert!(stern_mean_reflectance(f64::NAN).is_nan());
}

#[test]
fn increases_with_the_index() {
    let mut last = (0.0, 0.0);
    for i in 1..=4000 {
        let n = 1.0 + i as f64 * 0.00075; // up to n = 4
        let now = (stern_mean_reflectance(n), internal_reflectance(n));
        assert!(now.0 > last.0 && now.1 > last.1, "not increasing at n = {n}");
        assert!(now.0 < 1.0 && now.1 < 1.0);
        last = now;
    }
}
