//! The industry shortcut for wet surfaces, for comparison only.

use crate::fresnel::unit;

/// `a(1 − t) + b t`, exact at both ends (WGSL's `mix`).
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a * (1.0 - t) + b * t
}

/// Lagarde's porosity darkening factor `lerp(1, 0.2, porosity)` at full
/// wetness; `porosity` in `[0, 1]` (clamped).
///
/// Lagarde ("Water drop 3b – Physically based wet surfaces", 2013, as used in
/// *Remember Me*) darkens the diffuse colour by a constant factor that depends
/// on the material's porosity and raises its gloss:
///
/// ```text
/// factor  = lerp(1, 0.2, porosity)
/// diffuse = diffuse · lerp(1, factor, wet)
/// gloss   = lerp(1, gloss, lerp(1, factor, wet / 2))
/// ```
///
/// so a fully wet, fully porous surface keeps 20 % of its albedo whatever that
/// albedo is. The Lekner–Dorf albedo of [`wet_albedo`](crate::wet_albedo)
/// instead follows from the liquid's refractive index: a 0.5 albedo under
/// water keeps 68 % (0.3386), a 0.1 albedo keeps 54 %, a 0.8 albedo 83 %;
/// dark materials darken relatively more, as observed. These functions exist so
/// renders and tests can compare the two; soak's shading does not use it.
pub fn lagarde_factor(porosity: f64) -> f64 {
    lerp(1.0, 0.2, unit(porosity))
}

/// Lagarde's wet diffuse albedo: `dry · lerp(1, lagarde_factor(porosity), wetness)`
/// for a dry albedo in `[0, 1]`, porosity and wetness (wet level, e.g. Γ(h))
/// in `[0, 1]` (clamped). Comparison only; see [`lagarde_factor`].
pub fn lagarde_wet_diffuse(dry: f64, porosity: f64, wetness: f64) -> f64 {
    dry * lerp(1.0, lagarde_factor(porosity), unit(wetness))
}

/// Lagarde's wet gloss (`gloss = 1 − perceptual roughness`, in `[0, 1]`):
/// `lerp(1, gloss, lerp(1, lagarde_factor(porosity), wetness/2))`. Raised
/// towards 1 as the surface wets, more for porous surfaces. Comparison only.
pub fn lagarde_wet_gloss(gloss: f64, porosity: f64, wetness: f64) -> f64 {
    let f = lagarde_factor(porosity);
    lerp(1.0, unit(gloss), lerp(1.0, f, 0.5 * unit(wetness)))
}
