//! The time-domain radiation model (Cummins' equation with a fitted
//! kernel) against the frequency domain: the kernel's transform against
//! B(ω) and, by Kramers–Kronig, against A(ω) − A∞; a floating sphere's
//! free heave decay against the decay the frequency-domain coefficients
//! predict.

use num_complex::Complex64;
use soak_seakeeping::{Kernel, Memory, Sweep};

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

/// Period (s) and mean ratio of successive positive peaks of `x`.
fn period_and_decay(x: &[f64], dt: f64) -> (f64, f64) {
    let crossings: Vec<f64> = x
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0] > 0.0 && w[1] <= 0.0)
        .map(|(n, w)| (n as f64 + w[0] / (w[0] - w[1])) * dt)
        .collect();
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let peaks: Vec<f64> = x
        .windows(3)
        .filter(|w| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.0)
        .map(|w| w[1])
        .collect();
    let ratios: Vec<f64> = peaks.windows(2).take(3).map(|p| p[1] / p[0]).collect();
    (period, ratios.iter().sum::<f64>() / ratios.len() as f64)
}

#[test]
fn free_heave_decay_matches_the_frequency_domain() {
    let sweep = sweep();
    let (_, fit) = kernel(sweep);
    // A sphere of radius 1 m and density 500 kg/m³ floats with its centre
    // at the surface: mass ρ ⅔ π, waterplane stiffness ρ g π.
    let mass = RHO * 2.0 / 3.0 * PI;
    let stiffness = RHO * G * PI;
    let a_inf = sweep.infinite[(1, 1)];
    let x0 = 0.05;
    let (dt, steps) = (0.002, 6000);

    // Time domain: Cummins' equation, the kernel's states advanced exactly
    // for a velocity linear over each step, the motion by a
    // velocity-Verlet-like predictor (the memory force lags by half a step
    // at most: dt is small).
    let mut memory = Memory::new(&fit);
    let (mut x, mut v) = (x0, 0.0);
    let mut time_domain = vec![x];
    for _ in 0..steps {
        let force = |x: f64, memory: &Memory| -stiffness * x - memory.force(&fit);
        let a0 = force(x, &memory) / (mass + a_inf);
        // Predict the step's end velocity, advance the memory with it, then
        // correct (trapezoidal in the velocity).
        let v_pred = v + dt * a0;
        let x_new = x + dt * 0.5 * (v + v_pred);
        let mut m_new = memory.clone();
        m_new.advance(&fit, v, v_pred, dt);
        let a1 = force(x_new, &m_new) / (mass + a_inf);
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
            let (a, b) = sweep.at(1, 1, omega);
            let h = 1.0 / Complex64::new(stiffness - omega * omega * (mass + a), -omega * b);
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
    let (period_t, decay_t) = period_and_decay(&sampled, 5.0 * dt);
    let (period_f, decay_f) = period_and_decay(&frequency_domain, 5.0 * dt);
    eprintln!(
        "time domain: period {period_t:.3} s, peak ratio {decay_t:.3}; frequency domain: {period_f:.3} s, {decay_f:.3}"
    );
    assert!(
        (period_t / period_f - 1.0).abs() < 0.02,
        "period {period_t} vs {period_f}"
    );
    assert!(
        (decay_t / decay_f - 1.0).abs() < 0.05,
        "decay {decay_t} vs {decay_f}"
    );
}
