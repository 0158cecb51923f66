//! Stern's closed form cancels catastrophically as n → 1: in f64 it lost
//! half its digits at n = 1.0001 and returned 0.25 (instead of 3.3e-9) at
//! n = 1 + 1e-8. Near 1 the crate switches to a series; R̄ must stay
//! accurate, positive, continuous at the switch and ≈ (n − 1)/3.

use soak_shade::{internal_reflectance, stern_mean_reflectance};

#[test]
fn tends_to_a_third_of_the_index_excess() {
    for eps in [1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let r = stern_mean_reflectance(1.0 + eps);
        // R̄(1+ε) = ε/3 + O(ε² ln ε)
        let rel = (r / eps - 1.0 / 3.0).abs();
        assert!(rel < 10.0 * eps * eps.ln().abs() + 1e-3, "ε = {eps}: R̄ = {r}");
        assert!(r > 0.0);
    }
}

#[test]
fn values_near_one_match_high_precision_reference() {
    // 50-digit mpmath evaluations of Stern's closed form at the f64 value
    // of 1 + ε.
    for (eps, expected) in [
        (1e-1, 0.02515735735287707),
        (1e-2, 0.003146302682353434),
        (1e-3, 0.0003303232370818162),
        (1e-4, 3.3291731246209035e-05),
        (1e-5, 3.332802195072966e-06),
        (1e-6, 3.3332687064239287e-07),
        (1e-8, 3.3333324365503762e-09),
    ] {
        let r = stern_mean_reflectance(1.0 + eps);
        assert!(
            (r - expected).abs() <= 1e-13 * expected,
            "ε = {eps}: {r} vs {expected}"
        );
    }
}

#[test]
fn continuous_across_the_branch_switch() {
    // The series takes over below n = 1.1; steps of 1e-12 across the
    // switch must each rise by the slope times the step, without a jump.
    let at = 1.1;
    let slope = (stern_mean_reflectance(at + 1e-4) - stern_mean_reflectance(at - 1e-4)) / 2e-4;
    for k in -20..=20 {
        let a = at + k as f64 * 1e-12;
        let b = a + 1e-12;
        let (ra, rb) = (stern_mean_reflectance(a), stern_mean_reflectance(b));
        let jump = (rb - ra) - slope * (b - a);
        assert!(jump.abs() < 2e-14, "jump of {jump:e} at n = {a}: {ra} → {rb}");
    }
    assert!(internal_reflectance(1.0 + 1e-9) > 0.0);
}
