//! The Lekner–Dorf wet albedo: why absorbent things look darker when wet,
//! extended to coloured liquids (thesis Ch. 6, Eq. 6.1).

use crate::fresnel::unit;

/// The denominator `1 − p a σ²` of the bounce series, kept away from 0.
///
/// With all inputs in `[0, 1]` it is 0 only for `p = a = σ = 1`, which no
/// finite refractive index reaches (`p < 1`).
fn bounce_denominator(a: f64, sigma: f64, p: f64) -> f64 {
    (1.0 - p * a * sigma * sigma).max(f64::MIN_POSITIVE)
}

/// The Lekner–Dorf wet albedo `W = (1 − R_spec) σ² a (1 − p) / (1 − p a σ²)`:
/// the fraction of incident light a liquid-covered diffuse surface sends back
/// diffusely to the eye, for one wavelength band.
///
/// A thin liquid film of relative index `n` covers a diffuse surface of
/// albedo `a`. Of the light reaching the film, `R_spec` is reflected
/// specularly at the air–liquid interface; the rest crosses the film
/// (transmittance `σ` per pass), meets the surface (absorbed `1 − a`,
/// scattered diffusely `a`), crosses the film again (`σ`), and at the
/// liquid–air interface escapes with probability `1 − p` or is reflected back
/// down with probability `p` (the internal diffuse reflectance). Summing the
/// geometric series of bounces, with `D = 1 − p·a·σ²`:
///
/// ```text
/// absorbed by the surface  A = (1 − R_spec)(1 − a) σ / D
/// albedo seen by the eye   W = (1 − R_spec) σ² a (1 − p) / D
/// absorbed by the liquid   L = (1 − R_spec)(1 − σ)(1 + a σ) / D
/// and R_spec + W + A + L = 1 exactly.
/// ```
///
/// Every function here works per wavelength band: call it per RGB channel,
/// or use the `_rgb` variants, with `a` and `σ` as RGB triples.
///
/// - `albedo`: dry diffuse albedo `a`, fraction in `[0, 1]`;
/// - `transmittance`: liquid transmittance `σ` per pass through the film,
///   in `[0, 1]` (1 for clear water; see [`beer_lambert`](crate::beer_lambert));
/// - `r_spec`: specular reflectance of the air–liquid interface for the
///   incident light, in `[0, 1]` ([`schlick`](crate::schlick) at the light's
///   incidence angle, or [`stern_mean_reflectance`](crate::stern_mean_reflectance)
///   under diffuse light);
/// - `p`: internal diffuse reflectance, in `[0, 1)`
///   ([`internal_reflectance`](crate::internal_reflectance)).
///
/// Inputs are clamped to `[0, 1]` (NaN becomes 0), so the result is always a
/// fraction in `[0, a]`: wet is never brighter than dry.
///
/// # Example
/// Water (n = 1.33) at normal incidence darkens a 0.5 albedo to 0.3386:
/// ```
/// use soak_shade::{fresnel_f0, internal_reflectance, schlick, wet_albedo};
/// let n = 1.33;
/// let r_spec = schlick(1.0, fresnel_f0(n));
/// let w = wet_albedo(0.5, 1.0, r_spec, internal_reflectance(n));
/// assert!((w - 0.3386).abs() < 1e-4);
/// ```
pub fn wet_albedo(albedo: f64, transmittance: f64, r_spec: f64, p: f64) -> f64 {
    let (a, s, r, p) = (unit(albedo), unit(transmittance), unit(r_spec), unit(p));
    (1.0 - r) * s * s * a * (1.0 - p) / bounce_denominator(a, s, p)
}

/// Fraction of incident light absorbed by the wet *surface* (thesis Eq. 6.1),
/// `A = (1 − R_spec)(1 − a) σ / (1 − p a σ²)`. Arguments as for
/// [`wet_albedo`]; the result is a fraction in `[0, 1]`.
pub fn absorbed_fraction(albedo: f64, transmittance: f64, r_spec: f64, p: f64) -> f64 {
    let (a, s, r, p) = (unit(albedo), unit(transmittance), unit(r_spec), unit(p));
    (1.0 - r) * (1.0 - a) * s / bounce_denominator(a, s, p)
}

/// Fraction of incident light absorbed by the *liquid* on its way down and
/// up, `L = (1 − R_spec)(1 − σ)(1 + a σ) / (1 − p a σ²)`; 0 for a clear
/// liquid. Arguments as for [`wet_albedo`]; the result is in `[0, 1]`.
pub fn liquid_absorbed_fraction(albedo: f64, transmittance: f64, r_spec: f64, p: f64) -> f64 {
    let (a, s, r, p) = (unit(albedo), unit(transmittance), unit(r_spec), unit(p));
    (1.0 - r) * (1.0 - s) * (1.0 + a * s) / bounce_denominator(a, s, p)
}

/// [`wet_albedo`] per RGB channel, for a coloured liquid (`transmittance` per
/// channel) over a coloured surface.
pub fn wet_albedo_rgb(albedo: [f64; 3], transmittance: [f64; 3], r_spec: f64, p: f64) -> [f64; 3] {
    std::array::from_fn(|i| wet_albedo(albedo[i], transmittance[i], r_spec, p))
}

/// [`absorbed_fraction`] per RGB channel.
pub fn absorbed_fraction_rgb(albedo: [f64; 3], transmittance: [f64; 3], r_spec: f64, p: f64) -> [f64; 3] {
    std::array::from_fn(|i| absorbed_fraction(albedo[i], transmittance[i], r_spec, p))
}

/// f32 convenience for [`wet_albedo`] (evaluated in f64).
pub fn wet_albedo_f32(albedo: f32, transmittance: f32, r_spec: f32, p: f32) -> f32 {
    wet_albedo(
        f64::from(albedo),
        f64::from(transmittance),
        f64::from(r_spec),
        f64::from(p),
    ) as f32
}

/// Where the incident light goes, for one wavelength band: the four
/// fractions sum to 1 (to rounding) for inputs in `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnergyBudget {
    /// Reflected specularly at the air–liquid interface, `R_spec`.
    pub specular: f64,
    /// Scattered back out of the film diffusely: the wet albedo `W`.
    pub diffuse: f64,
    /// Absorbed by the surface, `A`.
    pub surface_absorbed: f64,
    /// Absorbed by the liquid, `L`.
    pub liquid_absorbed: f64,
}

impl EnergyBudget {
    /// The budget for albedo `a`, transmittance `σ`, specular reflectance
    /// `R_spec` and internal reflectance `p` (all fractions, clamped to
    /// `[0, 1]`), as in [`wet_albedo`].
    pub fn new(albedo: f64, transmittance: f64, r_spec: f64, p: f64) -> Self {
        Self {
            specular: unit(r_spec),
            diffuse: wet_albedo(albedo, transmittance, r_spec, p),
            surface_absorbed: absorbed_fraction(albedo, transmittance, r_spec, p),
            liquid_absorbed: liquid_absorbed_fraction(albedo, transmittance, r_spec, p),
        }
    }

    /// Sum of the four fractions; 1 up to rounding.
    pub fn total(&self) -> f64 {
        self.specular + self.diffuse + self.surface_absorbed + self.liquid_absorbed
    }
}
