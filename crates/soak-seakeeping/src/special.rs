//! Special functions of the free-surface Green function: the exponential
//! integral of a complex argument and a tanh–sinh quadrature rule.

use num_complex::Complex64;

/// Euler–Mascheroni constant.
const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// `e^w E₁(w)` for a complex `w` off the negative real axis (principal
/// branch, the cut along the negative real axis; on the cut, the mean of
/// its two sides, `−Ei(−w)`).
///
/// The power series is used where it loses few digits (where
/// `|w| + Re w` is small: the terms grow as `e^|w|` while the result is of
/// order `e^{−Re w}/|w|`), the continued fraction elsewhere.
pub(crate) fn exp_e1(w: Complex64) -> Complex64 {
    if w.norm() + w.re < 14.0 {
        let (e1, on_cut) = e1_series(w);
        let value = w.exp() * e1;
        if on_cut {
            Complex64::new(value.re, 0.0)
        } else {
            value
        }
    } else {
        exp_e1_continued_fraction(w)
    }
}

/// `E₁(w)` by its power series, `−γ − ln w − Σ (−w)ⁿ/(n·n!)`, and whether
/// `w` lies on the cut (negative real), where the real part is the mean of
/// the two sides.
fn e1_series(w: Complex64) -> (Complex64, bool) {
    let on_cut = w.im == 0.0 && w.re < 0.0;
    let log = if on_cut {
        Complex64::new((-w.re).ln(), 0.0)
    } else {
        w.ln()
    };
    let mut term = Complex64::new(1.0, 0.0);
    let mut sum = Complex64::new(0.0, 0.0);
    for n in 1..600 {
        let n = f64::from(n);
        term *= -w / n;
        let add = term / n;
        sum += add;
        if add.norm() <= 0.5 * f64::EPSILON * sum.norm() {
            break;
        }
    }
    (-EULER_GAMMA - log - sum, on_cut)
}

/// `e^w E₁(w)` by the continued fraction
/// `1/(w+1− 1/(w+3− 4/(w+5− …)))` (modified Lentz), valid off the negative
/// real axis and fast for large `|w|`.
fn exp_e1_continued_fraction(w: Complex64) -> Complex64 {
    let tiny = Complex64::new(1e-300, 0.0);
    let mut b = w + 1.0;
    let mut c = Complex64::new(1.0 / 1e-300, 0.0);
    let mut d = Complex64::new(1.0, 0.0) / b;
    let mut h = d;
    for i in 1..2000 {
        let a = -f64::from(i) * f64::from(i);
        b += 2.0;
        d = a * d + b;
        if d.norm() < 1e-300 {
            d = tiny;
        }
        c = b + a / c;
        if c.norm() < 1e-300 {
            c = tiny;
        }
        d = Complex64::new(1.0, 0.0) / d;
        let delta = c * d;
        h *= delta;
        if (delta - 1.0).norm() < 4.0 * f64::EPSILON {
            break;
        }
    }
    h
}

/// A tanh–sinh (double exponential) rule on `[0, 1]`: nodes as
/// `(s, 1 − s, weight)` with both distances to the ends exact, so that
/// integrands singular at either end keep their precision.
pub(crate) fn tanh_sinh_unit(levels: u32) -> Vec<(f64, f64, f64)> {
    let h = 1.0 / f64::from(1u32 << levels);
    let half_pi = std::f64::consts::FRAC_PI_2;
    let mut nodes = Vec::new();
    let mut k: i32 = 0;
    loop {
        let t = f64::from(k) * h;
        let u = half_pi * t.sinh();
        // x = (1 + tanh u)/2; 1 − x = 1/(1 + e^{2u}); x = 1/(1 + e^{−2u}).
        let to_one = 1.0 / (1.0 + (2.0 * u).exp());
        let s = 1.0 / (1.0 + (-2.0 * u).exp());
        let weight = h * half_pi * t.cosh() / (2.0 * u.cosh() * u.cosh());
        if weight < 1e-18 || to_one == 0.0 {
            break;
        }
        nodes.push((s, to_one, weight));
        if k > 0 {
            nodes.push((to_one, s, weight));
        }
        k += 1;
    }
    nodes
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `E₁(x)` for real x > 0 by composite Simpson of `e^{−x t}/t` over
    /// `t ∈ [1, ∞)` mapped to `u = 1/t ∈ (0, 1]`: `∫₀¹ e^{−x/u}/u du`.
    fn e1_real_reference(x: f64) -> f64 {
        let n = 200_000;
        let h = 1.0 / f64::from(n);
        let f = |u: f64| if u == 0.0 { 0.0 } else { (-x / u).exp() / u };
        let mut sum = f(0.0) + f(1.0);
        for i in 1..n {
            let u = f64::from(i) * h;
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(u);
        }
        sum * h / 3.0
    }

    #[test]
    fn e1_matches_direct_integration_on_the_positive_axis() {
        for x in [0.05, 0.3, 1.0, 2.5, 7.0, 13.0, 20.0, 40.0] {
            let reference = e1_real_reference(x) * x.exp();
            let ours = exp_e1(Complex64::new(x, 0.0));
            assert!(
                (ours.re - reference).abs() < 1e-9 * reference.abs().max(1.0),
                "x {x}: {ours} vs {reference}"
            );
            assert!(ours.im.abs() < 1e-12);
        }
    }

    #[test]
    fn series_and_continued_fraction_agree_where_both_hold() {
        for (r, deg) in [
            (8.0, 0.0),
            (8.0, 60.0),
            (8.0, 120.0),
            (10.0, 170.0),
            (12.0, 90.0),
            (9.0, -135.0),
        ] {
            let w = Complex64::from_polar(r, f64::to_radians(deg));
            let series = w.exp() * e1_series(w).0;
            let fraction = exp_e1_continued_fraction(w);
            assert!(
                (series - fraction).norm() < 1e-9 * fraction.norm(),
                "w {w}: {series} vs {fraction}"
            );
        }
    }

    #[test]
    fn ei_on_the_cut_is_the_principal_value() {
        // −Ei(x) e^{−x} at x = 1: Ei(1) = 1.8951178163559368.
        let value = exp_e1(Complex64::new(-1.0, 0.0));
        let expected = -(-1.0f64).exp() * 1.895_117_816_355_936_8;
        assert!((value.re - expected).abs() < 1e-13, "{value} vs {expected}");
        assert_eq!(value.im, 0.0);
    }

    #[test]
    fn tanh_sinh_integrates_a_log_singularity() {
        // ∫₀¹ ln s ds = −1; ∫₀¹ s^{−1/2} ds = 2.
        let rule = tanh_sinh_unit(6);
        let log: f64 = rule.iter().map(|&(s, _, w)| w * s.ln()).sum();
        let root: f64 = rule.iter().map(|&(s, _, w)| w / s.sqrt()).sum();
        assert!((log + 1.0).abs() < 1e-12, "{log}");
        assert!((root - 2.0).abs() < 1e-8, "{root}");
    }
}
