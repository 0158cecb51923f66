//! The time-domain radiation model (Cummins' equation with a fitted
//! kernel) against the frequency domain: the kernel's transform against
//! B(ω) and, by Kramers–Kronig, against A(ω) − A∞; a floating sphere's
//! free heave decay against the decay the frequency-domain coefficients
//! predict.

use num_complex::Complex64;
use soak_seakeeping::{Kernel, Memory, Sweep, decay_measure};

mod common;
use common::hemisphere;
use std::f64::consts::PI;

const RHO: f64 = 1000.0;
const G: f64 = 9.81;

/// The hemisphere's heave and surge over ω 0.25–10 rad/s (Ka 0.006–10),
/// solved once for both tests.
fn sweep() -> &'static Sweep {
    static SWEEP: std::sync::OnceLock<Sweep> = std::sync::OnceLock::new();
    SWEEP.get_or_init(|| {
        let omegas: Vec<f64> = (1..=40).map(|n| 0.25 * n as f64).collect();
        hemisphere(10, 40).sweep(&omegas).unwrap()
    })
}

const DT: f64 = 0.04;

fn kernel(sweep: &Sweep) -> (Vec<f64>, Kernel) {
    let times: Vec<f64> = (0..=250).map(|n| n as f64 * DT).collect();
    let samples = sweep.kernel(1, 1, &times);
    let fit = Kernel::fit(&samples, DT, 10);
    (samples, fit)
}

#[test]
fn the_fitted_kernel_reproduces_damping_and_added_mass() {
    let sweep = sweep();
    let (samples, fit) = kernel(sweep);
    let peak = samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = samples
        .iter()
        .enumerate()
        .map(|(n, k)| (fit.value(n as f64 * DT) - k).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "{} poles; kernel peak {peak:.1}, worst misfit {worst:.3}",
        fit.poles.len()
    );
    assert!(worst < 0.01 * peak, "misfit {worst} of {peak}");
    let a_inf = sweep.infinite[(1, 1)];
    let b_peak = sweep
        .frequencies
        .iter()
        .map(|c| c.damping[(1, 1)])
        .fold(0.0, f64::max);
    let mut worst_a: f64 = 0.0;
    let mut worst_b: f64 = 0.0;
    for c in sweep
        .frequencies
        .iter()
        .filter(|c| c.omega >= 1.0 && c.omega <= 8.0)
    {
        let transform = fit.transform(c.omega);
        let b = transform.re;
        // Kramers–Kronig: A(ω) − A∞ = −Im K̂(ω)/ω, from B alone.
        let a = a_inf - transform.im / c.omega;
        let (a_panel, b_panel) = (c.added_mass[(1, 1)], c.damping[(1, 1)]);
        eprintln!(
            "ω {:.2}: B {b:.1} (panels {b_panel:.1}), A {a:.1} (panels {a_panel:.1})",
            c.omega
        );
        worst_b = worst_b.max((b - b_panel).abs() / b_peak);
        worst_a = worst_a.max((a - a_panel).abs() / a_panel);
    }
    eprintln!(
        "worst: B {:.2} % of its peak, A {:.2} %",
        worst_b * 100.0,
        worst_a * 100.0
    );
    assert!(worst_b < 0.02, "B misfit {worst_b}");
    assert!(worst_a < 0.03, "A (Kramers–Kronig) misfit {worst_a}");
}

/// Free decay of one mode released from `x0`: Cummins' equation with the
/// fitted kernel in the time domain against the release response of the
/// frequency-domain coefficients; (period, peak ratio) of each.
fn free_decay(sweep: &Sweep, mode: usize, inertia: f64, stiffness: f64, x0: f64) -> ((f64, f64), (f64, f64)) {
    let times: Vec<f64> = (0..=250).map(|n| n as f64 * DT).collect();
    let fit = Kernel::fit(&sweep.kernel(mode, mode, &times), DT, 10);
    let a_inf = sweep.infinite[(mode, mode)];
    let (dt, steps) = (0.002, 6000);

    // Time domain: the kernel's states advanced exactly for a velocity
    // linear over each step, the motion by a predictor–corrector
    // (trapezoidal in the velocity).
    let mut memory = Memory::new(&fit);
    let (mut x, mut v) = (x0, 0.0);
    let mut time_domain = vec![x];
    for _ in 0..steps {
        let force = |x: f64, memory: &Memory| -stiffness * x - memory.force(&fit);
        let a0 = force(x, &memory) / (inertia + a_inf);
        let v_pred = v + dt * a0;
        let x_new = x + dt * 0.5 * (v + v_pred);
        let mut m_new = memory.clone();
        m_new.advance(&fit, v, v_pred, dt);
        let a1 = force(x_new, &m_new) / (inertia + a_inf);
        let v_new = v + dt * 0.5 * (a0 + a1);
        memory.advance(&fit, v, v_new, dt);
        x += dt * 0.5 * (v + v_new);
        v = v_new;
        time_domain.push(x);
    }

    // Frequency domain: x(t) = x0 (1 − C s(t)), s the step response,
    // s(t) = (2/π) ∫₀^∞ Re H(ω) sin(ωt)/ω dω, H = 1/(C − ω²(M + A) − iωB).
    let d_omega = 0.001;
    let response: Vec<(f64, f64)> = (1..=30_000)
        .map(|n| {
            let omega = n as f64 * d_omega;
            let (a, b) = sweep.at(mode, mode, omega);
            let h = 1.0 / Complex64::new(stiffness - omega * omega * (inertia + a), -omega * b);
            (omega, h.re)
        })
        .collect();
    let frequency_domain: Vec<f64> = (0..=steps)
        .step_by(5)
        .map(|n| {
            let t = n as f64 * dt;
            let s: f64 = response
                .iter()
                .map(|&(w, re)| re * (w * t).sin() / w)
                .sum::<f64>()
                * d_omega
                * 2.0
                / PI;
            x0 * (1.0 - stiffness * s)
        })
        .collect();
    let sampled: Vec<f64> = time_domain.iter().step_by(5).copied().collect();
    (
        decay_measure(&sampled, 5.0 * dt).unwrap(),
        decay_measure(&frequency_domain, 5.0 * dt).unwrap(),
    )
}

/// Releases `mode` and asserts that the time domain agrees with the
/// frequency domain: period within 2 %, peak ratio within 5 %.
fn assert_decay_agrees(name: &str, sweep: &Sweep, mode: usize, inertia: f64, stiffness: f64, x0: f64) {
    let ((period_t, decay_t), (period_f, decay_f)) = free_decay(sweep, mode, inertia, stiffness, x0);
    eprintln!(
        "{name}: time domain {period_t:.3} s, peak ratio {decay_t:.3}; frequency domain {period_f:.3} s, {decay_f:.3}"
    );
    assert!(
        (period_t / period_f - 1.0).abs() < 0.02,
        "{name}: period {period_t} vs {period_f}"
    );
    assert!(
        (decay_t / decay_f - 1.0).abs() < 0.05,
        "{name}: decay {decay_t} vs {decay_f}"
    );
}

#[test]
fn free_heave_decay_matches_the_frequency_domain() {
    // A sphere of radius 1 m and density 500 kg/m³ floats with its centre
    // at the surface: mass ρ ⅔ π, waterplane stiffness ρ g π.
    assert_decay_agrees(
        "sphere heave",
        sweep(),
        1,
        RHO * 2.0 / 3.0 * PI,
        RHO * G * PI,
        0.05,
    );
}

/// A box barge 4 m long (x), 2 m wide (z), 1 m high, floating half
/// immersed (density 500 kg/m³, centre of gravity at the waterline):
/// heave and roll (about its length) released from rest.
#[test]
fn a_box_barges_heave_and_roll_decay_match_the_frequency_domain() {
    let barge = soak_bake::builtin::cuboid(4.0, 1.0, 2.0);
    let panels = soak_seakeeping::wetted_panels(&barge, &nalgebra::Isometry3::identity(), 0.7).unwrap();
    let problem = soak_seakeeping::Radiation::new(panels, nalgebra::Point3::origin(), RHO, G).unwrap();
    let omegas: Vec<f64> = (1..=40).map(|n| 0.25 * n as f64).collect();
    let sweep = problem.sweep(&omegas).unwrap();
    let mass = RHO * 4.0;
    // Heave: ρ g A_wp. Roll: ρ g V GM with GM = I_wp/V + z_B − z_G =
    // (4·2³/12)/4 − 0.25; the box's own roll inertia m (1² + 2²)/12.
    assert_decay_agrees("barge heave", &sweep, 1, mass, RHO * G * 8.0, 0.05);
    let gm = (4.0 * 8.0 / 12.0) / 4.0 - 0.25;
    assert_decay_agrees(
        "barge roll",
        &sweep,
        3,
        mass * 5.0 / 12.0,
        RHO * G * 4.0 * gm,
        0.05,
    );
}

/// A classical oscillator of natural period `period` (s) damped `zeta` of
/// critical, released from rest at 1: its displacement at `t` (s), its
/// damped period and its peak ratio per cycle.
fn oscillator(period: f64, zeta: f64, t: f64) -> (f64, f64, f64) {
    let omega = 2.0 * PI / period;
    let damped = omega * (1.0 - zeta * zeta).sqrt();
    let x = (-zeta * omega * t).exp() * ((damped * t).cos() + zeta * omega / damped * (damped * t).sin());
    (x, 2.0 * PI / damped, (-zeta * omega * 2.0 * PI / damped).exp())
}

#[test]
fn the_decay_measure_reads_light_and_heavy_damping_and_stops_at_a_tenth() {
    let dt = 1.0 / 60.0;
    // Lightly damped (a barge's roll): four crossings, two peak pairs.
    let (_, period, ratio) = oscillator(2.5, 0.02, 0.0);
    let x: Vec<f64> = (0..900).map(|n| oscillator(2.5, 0.02, n as f64 * dt).0).collect();
    let (p, r) = decay_measure(&x, dt).unwrap();
    assert!((p / period - 1.0).abs() < 1e-3, "{p} against {period}");
    assert!((r / ratio - 1.0).abs() < 1e-3, "{r} against {ratio}");
    // Damped a quarter of critical (a boat's heave), with a slow wobble a
    // two-hundredth of the release on top (a kernel fit's residual, the
    // last millimetre of a rest): the peaks fall to a fifth a cycle, and
    // the third and fourth crossings, at a hundredth of the release and
    // less, would move with the wobble. The measure stops at the first
    // peak below a tenth: the period from the two crossings before it,
    // the ratio from the first pair.
    let (_, period, ratio) = oscillator(1.4, 0.25, 0.0);
    for wobble in [0.0, 0.005, -0.005] {
        let x: Vec<f64> = (0..600)
            .map(|n| {
                let t = n as f64 * dt;
                oscillator(1.4, 0.25, t).0 + wobble * (0.7 * t).sin()
            })
            .collect();
        let (p, r) = decay_measure(&x, dt).unwrap();
        assert!(
            (p / period - 1.0).abs() < 0.01,
            "wobble {wobble}: {p} against {period}"
        );
        assert!(
            (r / ratio - 1.0).abs() < 0.05,
            "wobble {wobble}: {r} against {ratio}"
        );
    }
    // Over-damped: no crossing, no measure.
    let x: Vec<f64> = (0..600).map(|n| (-3.0 * n as f64 * dt).exp()).collect();
    assert_eq!(decay_measure(&x, dt), None);
}
