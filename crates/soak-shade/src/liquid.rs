//! The liquid film: refractive index, colour (transmittance per pass, from
//! Beer–Lambert absorption) and surface roughness.

use crate::error::{
    ParameterError, check_non_negative, check_positive, check_refractive_index, check_unit, check_unit_rgb,
};

/// Refractive index of water relative to air (visible light, 20 °C).
pub const WATER_REFRACTIVE_INDEX: f64 = 1.333;

/// Beer–Lambert transmittance `σ = exp(−α h)` of one pass through a film.
///
/// - `absorption`: absorption coefficient `α` in 1/m (natural-log base;
///   pure water is ≈ 0.4 /m in red, ≈ 0.02 /m in blue, so clear at film
///   thicknesses);
/// - `thickness`: path length `h` through the liquid in m (the film
///   thickness at normal incidence).
///
/// Returns a fraction in `[0, 1]`: negative `α·h` is treated as 0 (σ = 1),
/// NaN gives 0. The Lekner–Dorf model uses one `σ` per pass; for a
/// Lambertian (diffuse) pass the mean path through a thin slab is `2h`, so
/// pass `2h` to account for obliquity.
///
/// # Example
/// ```
/// // 1 mm of a dye absorbing 500 /m transmits e^-0.5 per pass.
/// let s = soak_shade::beer_lambert(500.0, 1e-3);
/// assert!((s - (-0.5f64).exp()).abs() < 1e-15);
/// ```
pub fn beer_lambert(absorption: f64, thickness: f64) -> f64 {
    let optical_depth = (absorption * thickness).max(0.0);
    let s = (-optical_depth).exp();
    if s.is_nan() { 0.0 } else { s }
}

/// The absorption coefficient `α = −ln(c)/h_ref` in 1/m of a liquid whose
/// colour is `c` (transmittance, fraction in `[0, 1]`, linear not sRGB) seen
/// through a reference thickness `h_ref` in m. `c = 0` gives `+∞` (opaque),
/// `c = 1` gives 0 (clear); `h_ref ≤ 0` gives `+∞` or NaN.
pub fn absorption_from_colour(colour: f64, reference_thickness: f64) -> f64 {
    -colour.ln() / reference_thickness
}

/// A liquid film over the surface.
///
/// # Example
/// ```
/// use soak_shade::Liquid;
/// // Tea: transmits (0.8, 0.5, 0.2) through 1 cm; a 0.5 mm film on the surface.
/// let tea = Liquid::from_colour(1.34, [0.8, 0.5, 0.2], 1e-2, 5e-4);
/// tea.validate().unwrap();
/// assert!(tea.transmittance[2] < tea.transmittance[0]);
/// assert_eq!(Liquid::default().transmittance, [1.0; 3]); // clear water
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Liquid {
    /// Refractive index relative to air, dimensionless, `> 1`
    /// (water 1.333, ethanol 1.36, glycerol 1.47, oil ≈ 1.47).
    pub refractive_index: f64,
    /// Transmittance `σ` of one pass through the film, per RGB channel,
    /// fractions in `[0, 1]`; `[1, 1, 1]` for a clear liquid.
    pub transmittance: [f64; 3],
    /// Perceptual roughness of the liquid's free surface in `[0, 1]`
    /// (GGX `α = roughness²`); small, as surface tension smooths it.
    pub film_roughness: f64,
}

impl Default for Liquid {
    /// Clear water: `n = 1.333`, `σ = 1`, film roughness 0.1.
    fn default() -> Self {
        Self {
            refractive_index: WATER_REFRACTIVE_INDEX,
            transmittance: [1.0; 3],
            film_roughness: 0.1,
        }
    }
}

impl Liquid {
    /// Clear water, the same as [`Liquid::default`].
    pub fn water() -> Self {
        Self::default()
    }

    /// A liquid of relative index `refractive_index` with absorption
    /// coefficients `absorption` (1/m, per RGB channel) as a film of
    /// `thickness` m: `σ = exp(−α h)` per channel ([`beer_lambert`]).
    pub fn with_absorption(refractive_index: f64, absorption: [f64; 3], thickness: f64) -> Self {
        Self {
            refractive_index,
            transmittance: absorption.map(|a| beer_lambert(a, thickness)),
            ..Self::default()
        }
    }

    /// A liquid whose colour through `reference_thickness` m is `colour`
    /// (linear RGB transmittance in `[0, 1]`), as a film of `thickness` m:
    /// `σ = colour^(thickness / reference_thickness)` per channel.
    pub fn from_colour(
        refractive_index: f64,
        colour: [f64; 3],
        reference_thickness: f64,
        thickness: f64,
    ) -> Self {
        let absorption = colour.map(|c| absorption_from_colour(c, reference_thickness));
        Self::with_absorption(refractive_index, absorption, thickness)
    }

    /// Normal-incidence reflectance `F0` of the air–liquid interface
    /// ([`fresnel_f0`](crate::fresnel_f0)).
    pub fn f0(&self) -> f64 {
        crate::fresnel::fresnel_f0(self.refractive_index)
    }

    /// Internal diffuse reflectance `p` of the liquid–air interface
    /// ([`internal_reflectance`](crate::internal_reflectance)).
    pub fn internal_reflectance(&self) -> f64 {
        crate::mean_reflectance::internal_reflectance(self.refractive_index)
    }

    /// Checks every field: `refractive_index > 1` and finite, transmittance
    /// and film roughness in `[0, 1]`.
    pub fn validate(&self) -> Result<(), ParameterError> {
        check_refractive_index("liquid.refractive_index", self.refractive_index)?;
        check_unit_rgb(
            [
                "liquid.transmittance.r",
                "liquid.transmittance.g",
                "liquid.transmittance.b",
            ],
            self.transmittance,
        )?;
        check_unit("liquid.film_roughness", self.film_roughness)?;
        Ok(())
    }
}

/// Checks Beer–Lambert inputs: absorption coefficient (1/m) and thickness
/// (m) must be finite and non-negative; a reference thickness must be
/// positive. Convenience for callers building a [`Liquid`] from user data.
pub fn validate_absorption(
    absorption: [f64; 3],
    thickness: f64,
    reference_thickness: Option<f64>,
) -> Result<(), ParameterError> {
    for (name, a) in ["absorption.r", "absorption.g", "absorption.b"]
        .into_iter()
        .zip(absorption)
    {
        check_non_negative(name, a)?;
    }
    check_non_negative("thickness", thickness)?;
    if let Some(h) = reference_thickness {
        check_positive("reference_thickness", h)?;
    }
    Ok(())
}
