//! The panel method against exact and published references: a sphere in
//! unbounded water, the floating hemisphere's zero- and infinite-frequency
//! limits (by spherical harmonics, here), and Hulme's (1982) tabulated
//! added mass and damping of the surging hemisphere.

use nalgebra::Point3;
use soak_seakeeping::{Radiation, Surface};

mod common;
use common::{hemisphere, sphere_panels};
use std::f64::consts::PI;

const RHO: f64 = 1000.0;
const G: f64 = 9.81;

/// ρ (2/3) π a³ for a = 1: the hemisphere's displaced mass.
fn displaced() -> f64 {
    RHO * 2.0 / 3.0 * PI
}

/// Gauss–Legendre nodes and weights on [a, b].
fn gauss(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 0..n {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(n, x);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        let (_, dp) = legendre(n, x);
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((0.5 * (b - a) * x + 0.5 * (a + b), 0.5 * (b - a) * w));
    }
    out
}

/// P_n(x) and P_n'(x).
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for l in 1..n {
        let l = l as f64;
        let p2 = ((2.0 * l + 1.0) * x * p1 - l * p0) / (l + 1.0);
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// All P_l(x), l = 0..=n.
fn legendre_all(n: usize, x: f64) -> Vec<f64> {
    let mut p = vec![1.0, x];
    for l in 1..n {
        let l = l as f64;
        p.push(((2.0 * l + 1.0) * x * p[l as usize] - l * p[l as usize - 1]) / (l + 1.0));
    }
    p.truncate(n + 1);
    p
}

/// The hemisphere's heave added mass at zero frequency (rigid lid), by
/// the even extension: a unit sphere whose surface moves with normal
/// velocity −|μ| (μ the cosine from +y), solved by Legendre series.
fn heave_zero_frequency_reference() -> f64 {
    let lmax = 400;
    let nodes = gauss(600, 0.0, 1.0);
    // g_l = (2l+1)/2 ∫_{−1}^{1} −|μ| P_l dμ (even l only).
    let mut g = vec![0.0; lmax + 1];
    for &(mu, w) in &nodes {
        let p = legendre_all(lmax, mu);
        for l in (0..=lmax).step_by(2) {
            g[l] += (2.0 * l as f64 + 1.0) / 2.0 * 2.0 * (-mu) * p[l] * w;
        }
    }
    // φ(1, μ) = Σ c_l P_l(μ), c_l = −g_l/(l+1); A = −2πρ ∫_{−1}^{0} φ μ dμ.
    let mut integral = 0.0;
    for &(m, w) in &nodes {
        let mu = -m;
        let p = legendre_all(lmax, mu);
        let phi: f64 = (0..=lmax)
            .step_by(2)
            .map(|l| -g[l] / (l as f64 + 1.0) * p[l])
            .sum();
        integral += phi * mu * w;
    }
    -2.0 * PI * RHO * integral / displaced()
}

/// The hemisphere's surge added mass at infinite frequency (φ = 0 on the
/// surface), by the odd extension: normal velocity −sgn(μ) sin θ cos ϕ on
/// the unit sphere, solved by associated Legendre series P_l¹.
fn surge_infinite_frequency_reference() -> f64 {
    let lmax = 400;
    let nodes = gauss(600, 0.0, 1.0);
    // P_l¹(μ) = √(1−μ²) P_l'(μ); ∫ (P_l¹)² = 2l(l+1)/(2l+1).
    let assoc = |l: usize, mu: f64| {
        let (_, dp) = legendre(l, mu);
        (1.0 - mu * mu).sqrt() * dp
    };
    let mut g = vec![0.0; lmax + 1];
    for &(mu, w) in &nodes {
        let s = (1.0 - mu * mu).sqrt();
        for l in (2..=lmax).step_by(2) {
            let norm = (2.0 * l as f64 + 1.0) / (2.0 * (l * (l + 1)) as f64);
            // h(μ) = −sgn(μ) s is odd and P_l¹ is odd for even l: twice [0, 1].
            g[l] += norm * 2.0 * (-s) * assoc(l, mu) * w;
        }
    }
    // A = −ρ π ∫_{−1}^{0} φ(μ) √(1−μ²) dμ with φ = Σ c_l P_l¹, c_l = −g_l/(l+1).
    let mut integral = 0.0;
    for &(m, w) in &nodes {
        let mu = -m;
        let phi: f64 = (2..=lmax)
            .step_by(2)
            .map(|l| -g[l] / (l as f64 + 1.0) * assoc(l, mu))
            .sum();
        integral += phi * (1.0 - mu * mu).sqrt() * w;
    }
    -PI * RHO * integral / displaced()
}

#[test]
fn a_sphere_in_unbounded_water_has_half_its_displaced_mass() {
    // 1,152 panels.
    let panels = sphere_panels(1.0, Point3::new(0.0, -10.0, 0.0), PI, 24, 48).unwrap();
    let problem = Radiation::new(panels, Point3::new(0.0, -10.0, 0.0), RHO, G).unwrap();
    let c = problem.solve(Surface::Unbounded).unwrap();
    let expected = 0.5 * RHO * 4.0 / 3.0 * PI;
    for mode in 0..3 {
        let error = c.added_mass[(mode, mode)] / expected - 1.0;
        eprintln!(
            "mode {mode}: A = {:.2} kg, error {:.3} %",
            c.added_mass[(mode, mode)],
            error * 100.0
        );
        assert!(error.abs() < 0.006, "mode {mode}: {error}");
    }
    // Off the diagonal: nothing couples a sphere's translations.
    assert!(c.added_mass[(0, 1)].abs() < 1e-3 * expected);
}

#[test]
fn the_hemisphere_limits_match_spherical_harmonics() {
    // 576 panels.
    let problem = hemisphere(12, 48);
    let zero = problem.solve(Surface::ZeroFrequency).unwrap();
    let infinite = problem.solve(Surface::InfiniteFrequency).unwrap();
    let heave_zero = heave_zero_frequency_reference();
    let surge_infinite = surge_infinite_frequency_reference();
    eprintln!("references: heave(0) {heave_zero:.4}, surge(∞) {surge_infinite:.4}");
    let cases = [
        ("heave, ω = 0", zero.added_mass[(1, 1)] / displaced(), heave_zero),
        ("heave, ω = ∞", infinite.added_mass[(1, 1)] / displaced(), 0.5),
        ("surge, ω = 0", zero.added_mass[(0, 0)] / displaced(), 0.5),
        (
            "surge, ω = ∞",
            infinite.added_mass[(0, 0)] / displaced(),
            surge_infinite,
        ),
    ];
    for (name, ours, reference) in cases {
        eprintln!(
            "{name}: {ours:.4} vs {reference:.4} ({:+.2} %)",
            (ours / reference - 1.0) * 100.0
        );
        assert!(
            (ours / reference - 1.0).abs() < 0.015,
            "{name}: {ours} vs {reference}"
        );
    }
}

/// Over Ka 0.1–4, through the hemisphere's irregular frequencies (heave
/// near Ka 2.6, surge near 3.9: without the lid's equations the surge
/// added mass at Ka 4 is 18 % off).
#[test]
fn surge_matches_hulme() {
    // 576 panels.
    let problem = hemisphere(12, 48);
    let mut worst: f64 = 0.0;
    // Hulme (1982), Table 2 (`references::HULME_SURGE`): its added mass at
    // Ka 0.7 breaks the table's smooth curve; it is met within the 3 %.
    for (ka, a_ref, b_ref) in soak_seakeeping::references::HULME_SURGE {
        let c = problem.solve(Surface::Wavenumber(ka)).unwrap();
        let a = c.added_mass[(0, 0)] / displaced();
        let b = c.damping[(0, 0)] / (c.omega * displaced());
        eprintln!("Ka {ka}: A {a:.4} (Hulme {a_ref}), B {b:.4} (Hulme {b_ref})");
        worst = worst.max((a - a_ref).abs() / a_ref);
        assert!((a - a_ref).abs() < 0.03 * a_ref, "Ka {ka}: A {a} vs {a_ref}");
        // The damping within 3 %, or 2e-4 where it is itself that small
        // (the table's 4 decimals).
        if b_ref.is_finite() {
            assert!(
                (b - b_ref).abs() < (0.03 * b_ref).max(2e-4),
                "Ka {ka}: B {b} vs {b_ref}"
            );
        }
    }
    eprintln!("worst added-mass error {:.2} %", worst * 100.0);
}

/// The damping from the pressure on the hull against the energy the
/// radiated waves carry to infinity (the Kochin function): two
/// independent paths from the same potentials, for surge and heave.
#[test]
fn far_field_damping_matches_the_pressure() {
    let problem = hemisphere(12, 48);
    for ka in [0.3, 1.0, 2.0, 3.0] {
        let potentials = problem.potentials(Surface::Wavenumber(ka)).unwrap();
        let near = problem.coefficients(&potentials).damping;
        let far = problem.far_field_damping(&potentials).unwrap();
        for mode in [0, 1] {
            let (p, f) = (near[(mode, mode)], far[mode]);
            eprintln!("Ka {ka} mode {mode}: pressure {p:.3}, far field {f:.3}");
            assert!((p - f).abs() < 0.03 * p, "Ka {ka} mode {mode}: {p} vs {f}");
        }
    }
}

/// The excitation (Haskind) in long waves tends to the hydrostatic force
/// of the wave's elevation, ρ g A_wp per metre of amplitude in heave, and
/// a floating sphere's heave RAO to 1; waves from opposite headings push
/// it opposite ways in surge.
#[test]
fn long_waves_lift_the_hemisphere_hydrostatically() {
    let problem = hemisphere(12, 48);
    let hydrostatic = RHO * G * PI;
    for ka in [0.01, 0.05] {
        let potentials = problem.potentials(Surface::Wavenumber(ka)).unwrap();
        let x = problem.excitation(&potentials, 0.0).unwrap();
        let back = problem.excitation(&potentials, PI).unwrap();
        let c = problem.coefficients(&potentials);
        let mass = displaced();
        let omega = c.omega;
        let rao = x[1]
            / num_complex::Complex64::new(
                hydrostatic - omega * omega * (mass + c.added_mass[(1, 1)]),
                -omega * c.damping[(1, 1)],
            );
        eprintln!(
            "Ka {ka}: heave {:.1} ({:.4} of ρgA), RAO {:.4}, surge {:.1} / {:.1}",
            x[1].norm(),
            x[1].norm() / hydrostatic,
            rao.norm(),
            x[0],
            back[0]
        );
        // Within 2·Ka of the limit (the first correction is of order Ka).
        assert!(
            (x[1].norm() / hydrostatic - 1.0).abs() < 2.0 * ka + 0.01,
            "Ka {ka}: {}",
            x[1].norm() / hydrostatic
        );
        assert!(
            (rao.norm() - 1.0).abs() < 2.0 * ka + 0.01,
            "Ka {ka}: RAO {}",
            rao.norm()
        );
        assert!((x[0] + back[0]).norm() < 1e-6 * hydrostatic.max(x[0].norm()));
    }
}

/// Heave through its irregular frequency (Ka ≈ 2.6): smooth.
#[test]
fn heave_is_smooth_through_the_irregular_frequency() {
    let problem = hemisphere(12, 48);
    let a: Vec<f64> = [2.4, 2.5, 2.6, 2.7, 2.8]
        .iter()
        .map(|&ka| problem.solve(Surface::Wavenumber(ka)).unwrap().added_mass[(1, 1)] / displaced())
        .collect();
    for w in a.windows(3) {
        let curvature = (w[0] - 2.0 * w[1] + w[2]).abs();
        assert!(curvature < 2e-3, "heave added mass {a:?}");
    }
}
