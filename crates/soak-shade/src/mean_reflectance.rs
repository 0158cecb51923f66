//! Hemispherical mean reflectances of a flat dielectric interface.

use std::f64::consts::LN_2;

/// Below this `n − 1` the series branch is used (f64).
const SERIES_BELOW: f64 = 0.1;

/// Series coefficients `(b_k, a_k)` of `R̄(1+ε) = Σ_{k=1}^{16} (b_k + a_k ln ε) ε^k`,
/// derived symbolically (sympy) from Stern's closed form.
const SERIES: [(f64, f64); 16] = [
    (1.0 / 3.0, 0.0),
    (19.0 / 24.0 - LN_2 / 2.0, 1.0 / 2.0),
    (-79.0 / 60.0, 0.0),
    (37.0 / 160.0 + 5.0 * LN_2 / 8.0, -5.0 / 8.0),
    (275.0 / 224.0 - 5.0 * LN_2 / 8.0, 5.0 / 8.0),
    (-341.0 / 210.0 + LN_2 / 16.0, -1.0 / 16.0),
    (LN_2 / 2.0 + 1489.0 / 2016.0, -1.0 / 2.0),
    (22189.0 / 40320.0 - 5.0 * LN_2 / 8.0, 5.0 / 8.0),
    (-555019.0 / 443520.0 + 5.0 * LN_2 / 16.0, -5.0 / 16.0),
    (LN_2 / 8.0 + 2083877.0 / 2027520.0, -1.0 / 8.0),
    (-3.0 * LN_2 / 8.0 - 11581223.0 / 46126080.0, 3.0 / 8.0),
    (-22405057.0 / 49201152.0 + 43.0 * LN_2 / 128.0, -43.0 / 128.0),
    (513194771.0 / 738017280.0 - 15.0 * LN_2 / 128.0, 15.0 / 128.0),
    (-12758917.0 / 26836992.0 - 25.0 * LN_2 / 256.0, 25.0 / 256.0),
    (328663.0 / 4752384.0 + 3.0 * LN_2 / 16.0, -3.0 / 16.0),
    (82416451.0 / 350945280.0 - 37.0 * LN_2 / 256.0, 37.0 / 256.0),
];

/// Stern's closed form, accurate for `n − 1 ≳ 0.01`.
fn stern_closed_form(n: f64) -> f64 {
    let n2 = n * n;
    let np1 = n + 1.0;
    let n2p1 = n2 + 1.0;
    let n2m1 = n2 - 1.0;
    (3.0 * n2 + 2.0 * n + 1.0) / (3.0 * np1 * np1)
        - 2.0 * n2 * n * (n2 + 2.0 * n - 1.0) / (n2p1 * n2p1 * n2m1)
        + n2 * n2p1 / (n2m1 * n2m1) * n.ln()
        - n2 * n2m1 * n2m1 / (n2p1 * n2p1 * n2p1) * (n * np1 / (n - 1.0)).ln()
}

/// The series branch, for small `ε = n − 1 > 0`.
fn stern_series(eps: f64) -> f64 {
    let l = eps.ln();
    let mut acc = 0.0;
    for &(b, a) in SERIES.iter().rev() {
        acc = acc * eps + (b + a * l);
    }
    acc * eps
}

/// Stern's mean reflectance `R̄(n)` of a flat interface under isotropic
/// (diffuse) illumination, unpolarised, for light entering a medium of
/// relative refractive index `n` (dimensionless; e.g. 1.333 for water
/// relative to air).
///
/// Stern (1964) integrated Fresnel's equations for unpolarised light over a
/// hemisphere of *isotropic* (diffuse, cosine-weighted) incidence:
///
/// ```text
/// R̄(n) = 2 ∫₀^{π/2} R(θ, n) cos θ sin θ dθ
/// ```
///
/// and found the closed form (thesis Eq. 6.7), for a relative index `n > 1`
/// (light arriving from the optically thinner side, e.g. air → water):
///
/// ```text
/// R̄(n) = (3n² + 2n + 1) / (3(n+1)²)
///       − 2n³(n² + 2n − 1) / ((n²+1)²(n²−1))
///       + n²(n²+1) / (n²−1)² · ln n
///       − n²(n²−1)² / (n²+1)³ · ln(n(n+1)/(n−1))
/// ```
///
/// Light going the other way (liquid → air) is totally reflected beyond the
/// critical angle; by reciprocity its mean reflectance is
///
/// ```text
/// p = 1 − (1 − R̄(n)) / n²
/// ```
///
/// which Lekner & Dorf (1988) call the probability that diffusely scattered
/// light is reflected back at the liquid–air interface. The thesis writes the
/// same as `p = 1 − n²[1 − R̄(1/n)]` with `n = n_air/n_liquid < 1`
/// (Eq. 6.6); here `n` is always the liquid's index relative to air, `> 1`.
///
/// Returns a fraction in `[0, 1]`:
/// - `n > 1`: Stern's closed form (thesis Eq. 6.7), e.g. `R̄(1.333) ≈ 0.066406`;
/// - `n = 1`: 0 (no interface);
/// - `0 < n < 1` (light leaving the denser medium): `1 − n²(1 − R̄(1/n))`,
///   the same as [`internal_reflectance`]`(1/n)`;
/// - `n = +∞`: 1; `n ≤ 0` or NaN: NaN (never panics).
///
/// This is also the right `R_spec` for the wet albedo under diffuse (ambient)
/// lighting, being the cosine-weighted hemispherical average of Fresnel.
///
/// # Numerics
///
/// The closed form cancels catastrophically as `n → 1` (its terms grow like
/// `1/(n−1)` while the result shrinks like `(n−1)/3`): evaluated directly in
/// f64 it loses half its digits at `n = 1.0001` and is wrong in the first
/// digit at `n = 1.000001`. For `n − 1 < 0.1` this function uses instead the
/// series of the same closed form in `ε = n − 1`,
///
/// ```text
/// R̄(1+ε) = ε/3 + ε²(19/24 − ½ln 2 + ½ln ε) − 79ε³/60 + …   (16 terms)
/// ```
///
/// whose truncation error is below 2·10⁻¹⁸ there, while the closed form's
/// rounding error stays below 6·10⁻¹⁵ above it. Both branches agree with a
/// numerical integration of Fresnel's equations to ~1e-14 over `(1, 4]`.
///
/// # Example
/// ```
/// let r = soak_shade::stern_mean_reflectance(1.333);
/// assert!((r - 0.066406).abs() < 1e-6);
/// ```
pub fn stern_mean_reflectance(n: f64) -> f64 {
    if n.is_nan() || n <= 0.0 {
        f64::NAN
    } else if n == f64::INFINITY {
        1.0
    } else if n < 1.0 {
        internal_reflectance(1.0 / n)
    } else if n == 1.0 {
        0.0
    } else {
        let eps = n - 1.0;
        let r = if eps < SERIES_BELOW {
            stern_series(eps)
        } else {
            stern_closed_form(n)
        };
        r.clamp(0.0, 1.0)
    }
}

/// Internal diffuse reflectance `p = 1 − (1 − R̄(n))/n²`: the fraction of
/// light scattered diffusely (Lambertian) *inside* a liquid of relative index
/// `n > 1` that the liquid–air interface reflects back down, by total
/// internal reflection beyond the critical angle and Fresnel reflection
/// below it (Lekner & Dorf 1988; thesis Eq. 6.4–6.6).
///
/// Returns a fraction in `[0, 1)`, e.g. `p(1.333) ≈ 0.474591`,
/// `p(1.5) ≈ 0.596346`; 0 at `n = 1`. For `0 < n < 1` it returns the
/// external value `R̄(1/n)`; NaN for `n ≤ 0` or NaN.
///
/// # Example
/// ```
/// let p = soak_shade::internal_reflectance(1.5);
/// assert!((p - 0.596346).abs() < 1e-6);
/// ```
pub fn internal_reflectance(n: f64) -> f64 {
    if n > 1.0 {
        let p = 1.0 - (1.0 - stern_mean_reflectance(n)) / (n * n);
        p.clamp(0.0, 1.0)
    } else {
        stern_mean_reflectance(1.0 / n)
    }
}

/// f32 convenience for [`stern_mean_reflectance`] (evaluated in f64).
pub fn stern_mean_reflectance_f32(n: f32) -> f32 {
    stern_mean_reflectance(f64::from(n)) as f32
}

/// f32 convenience for [`internal_reflectance`] (evaluated in f64).
pub fn internal_reflectance_f32(n: f32) -> f32 {
    internal_reflectance(f64::from(n)) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branches_meet() {
        let n = 1.0 + SERIES_BELOW;
        let a = stern_closed_form(n);
        let b = stern_series(n - 1.0);
        assert!((a - b).abs() < 1e-14, "{a} vs {b}");
    }

    #[test]
    fn internal_is_reciprocal() {
        for n in [1.1, 1.333, 1.5, 2.4] {
            // p(n) is R̄ seen from inside: R̄(1/n) must give the same.
            let p = internal_reflectance(n);
            let inside = stern_mean_reflectance(1.0 / n);
            assert!((p - inside).abs() < 1e-15, "{p} vs {inside}");
        }
    }
}
