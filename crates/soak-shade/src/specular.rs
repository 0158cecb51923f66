//! The liquid film's specular lobe and the gloss change of a wetting surface.

use crate::fresnel::{clamp_nan_to_low, schlick, unit};

/// Smallest GGX `α` the lobe uses (perceptual roughness ≈ 0.045): below it
/// the peak `1/(π α²)` is dominated by the rounding of `n·h`, in f32 at least.
pub const MIN_ALPHA: f64 = 0.002;

/// GGX `α` from perceptual roughness in `[0, 1]`: `α = roughness²`, at least
/// [`MIN_ALPHA`].
pub fn alpha_from_roughness(roughness: f64) -> f64 {
    let r = unit(roughness);
    (r * r).max(MIN_ALPHA)
}

/// GGX / Trowbridge–Reitz normal distribution
/// `D = α² / (π ((n·h)²(α² − 1) + 1)²)` in 1/sr, for the cosine `n_dot_h`
/// between normal and half vector (clamped to `[0, 1]`) and GGX `alpha`
/// (clamped to `[MIN_ALPHA, 1]`).
pub fn ggx_distribution(n_dot_h: f64, alpha: f64) -> f64 {
    let c = unit(n_dot_h);
    let a2 = {
        let a = clamp_nan_to_low(alpha, MIN_ALPHA, 1.0);
        a * a
    };
    let d = c * c * (a2 - 1.0) + 1.0;
    a2 / (std::f64::consts::PI * d * d)
}

/// Height-correlated Smith visibility
/// `V = ½ / (n·l √((n·v)²(1 − α²) + α²) + n·v √((n·l)²(1 − α²) + α²))`
/// (dimensionless times 1/cos², so `D·V·F` is a BRDF). Cosines clamped to
/// `[0, 1]`; 0 when either is 0.
pub fn smith_visibility(n_dot_l: f64, n_dot_v: f64, alpha: f64) -> f64 {
    let (l, v) = (unit(n_dot_l), unit(n_dot_v));
    let a = clamp_nan_to_low(alpha, MIN_ALPHA, 1.0);
    let a2 = a * a;
    let gv = l * (v * v * (1.0 - a2) + a2).sqrt();
    let gl = v * (l * l * (1.0 - a2) + a2).sqrt();
    let s = gv + gl;
    if s > 0.0 { 0.5 / s } else { 0.0 }
}

/// The liquid film's specular BRDF `D · V · F` in 1/sr.
///
/// The film's free surface is smooth (surface tension), so a wet texel
/// reflects a sharp highlight with the liquid's Fresnel reflectance on top of
/// the darkened diffuse term of [`wet_albedo`](crate::wet_albedo). The lobe is
/// the usual microfacet BRDF
///
/// ```text
/// f_s = D(n·h; α) · V(n·l, n·v; α) · F(v·h)        [1/sr]
/// ```
///
/// with the GGX / Trowbridge–Reitz distribution `D`, the height-correlated
/// Smith visibility `V = G₂ / (4 (n·l)(n·v))` (Heitz 2014) and Schlick's `F`
/// with the liquid's `F0`. Roughness is *perceptual* in the structs
/// (`α = roughness²`) and GGX `α` in these functions.
///
/// - `n_dot_l`, `n_dot_v`, `n_dot_h`: cosines between the surface normal and
///   the light, view and half vectors; `v_dot_h` between view and half
///   vector (all clamped to `[0, 1]`);
/// - `alpha`: GGX roughness of the film, e.g.
///   [`alpha_from_roughness`]`(liquid.film_roughness)`;
/// - `f0`: the liquid's normal-incidence reflectance
///   ([`fresnel_f0`](crate::fresnel_f0)).
///
/// Returns 0 when the light or the eye is below the horizon.
///
/// # Example
/// ```
/// use soak_shade::{film_specular, fresnel_f0};
/// // Mirror configuration: the peak grows as the film gets smoother.
/// let f0 = fresnel_f0(1.333);
/// let rough = film_specular(1.0, 1.0, 1.0, 1.0, 0.3, f0);
/// let smooth = film_specular(1.0, 1.0, 1.0, 1.0, 0.05, f0);
/// assert!(smooth > rough);
/// ```
pub fn film_specular(n_dot_l: f64, n_dot_v: f64, n_dot_h: f64, v_dot_h: f64, alpha: f64, f0: f64) -> f64 {
    if !(n_dot_l > 0.0 && n_dot_v > 0.0) {
        return 0.0;
    }
    ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha) * schlick(v_dot_h, f0)
}

/// Perceptual roughness of a wetting surface: from the dry `dry_roughness`
/// towards the liquid film's `film_roughness` (both in `[0, 1]`) with the
/// wet weight `wetness = Γ(h)` in `[0, 1]`:
/// `lerp(dry, min(dry, film), Γ)`. Liquid fills the micro-cavities and its
/// free surface is smooth, so wetting never makes a surface rougher.
pub fn wet_roughness(dry_roughness: f64, film_roughness: f64, wetness: f64) -> f64 {
    let dry = unit(dry_roughness);
    let film = unit(film_roughness).min(dry);
    crate::gamma::blend(dry, film, wetness)
}
