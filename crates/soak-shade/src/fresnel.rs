//! Fresnel reflectance at the air–liquid interface: Schlick's approximation
//! (used for shading, thesis Eq. 6.2) and the exact unpolarised dielectric
//! formula (for reference and comparison).

/// Normal-incidence reflectance `F0 = ((n − 1)/(n + 1))²` of a dielectric of
/// relative refractive index `n` (dimensionless). Water (`n = 1.333`):
/// `F0 ≈ 0.0204`; `n = 1.33`: `0.02006`. A fraction in `[0, 1]` for `n ≥ 0`.
pub fn fresnel_f0(n: f64) -> f64 {
    let r = (n - 1.0) / (n + 1.0);
    r * r
}

/// Schlick's approximation of unpolarised Fresnel reflectance,
/// `R(θ) = F0 + (1 − F0)(1 − cos θ)⁵` (Schlick 1994; thesis Eq. 6.2).
///
/// `cos_theta` is the cosine of the incidence angle (clamped to `[0, 1]`,
/// NaN treated as 0, i.e. grazing); `f0` the normal-incidence reflectance
/// from [`fresnel_f0`]. Returns a fraction in `[0, 1]` when `f0` is.
///
/// # Example
/// ```
/// use soak_shade::{fresnel_f0, schlick};
/// let r = schlick(1.0, fresnel_f0(1.33)); // normal incidence
/// assert!((r - 0.0201).abs() < 1e-4);
/// assert_eq!(schlick(0.0, 0.02), 1.0); // grazing
/// ```
pub fn schlick(cos_theta: f64, f0: f64) -> f64 {
    let c = unit(cos_theta);
    let m = 1.0 - c;
    let m2 = m * m;
    f0 + (1.0 - f0) * m2 * m2 * m
}

/// f32 convenience for [`schlick`].
pub fn schlick_f32(cos_theta: f32, f0: f32) -> f32 {
    schlick(f64::from(cos_theta), f64::from(f0)) as f32
}

/// Exact Fresnel reflectance for unpolarised light, the mean of the s and p
/// reflectances, incident from the medium of index 1 onto one of relative
/// index `n` at an angle with cosine `cos_theta` (clamped to `[0, 1]`).
///
/// For `n < 1` (light leaving the denser medium) it returns 1 beyond the
/// critical angle. Returns a fraction in `[0, 1]`.
pub fn fresnel_dielectric(cos_theta: f64, n: f64) -> f64 {
    let ci = unit(cos_theta);
    let sin_t2 = (1.0 - ci * ci) / (n * n);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - sin_t2).sqrt();
    let rs = (ci - n * ct) / (ci + n * ct);
    let rp = (n * ci - ct) / (n * ci + ct);
    (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0)
}

/// Clamps to `[0, 1]`, mapping NaN to 0.
pub(crate) fn unit(x: f64) -> f64 {
    clamp_nan_to_low(x, 0.0, 1.0)
}

/// Clamps `x` to `[lo, hi]` (`lo ≤ hi`, not NaN), mapping NaN to `lo`:
/// `f64::max` drops a NaN operand, whereas `f64::clamp` would return NaN.
#[allow(clippy::manual_clamp)]
pub(crate) fn clamp_nan_to_low(x: f64, lo: f64, hi: f64) -> f64 {
    x.max(lo).min(hi)
}
