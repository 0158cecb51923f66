//! A wet material: the liquid, the Γ curve, and the shading they imply for
//! a texel of given dry albedo and saturation.

use crate::error::{ParameterError, check_unit, check_unit_rgb};
use crate::fresnel::schlick;
use crate::gamma::{Gamma, blend_rgb};
use crate::lekner_dorf::wet_albedo_rgb;
use crate::liquid::Liquid;
use crate::mean_reflectance::stern_mean_reflectance;
use crate::specular::{alpha_from_roughness, film_specular, wet_roughness};

/// How a material looks as it wets: the liquid that soaks it and the Γ
/// curve that maps liquid saturation to wet weight. The dry albedo and
/// roughness come per texel (textures), so they are arguments, not fields.
///
/// Defaults: clear water (`n = 1.333`, `σ = 1`), arctan Γ with `r = 8`.
///
/// # Example
/// ```
/// use soak_shade::WetMaterial;
/// let m = WetMaterial::default();
/// m.validate().unwrap();
/// let dry = [0.5, 0.4, 0.3];
/// assert_eq!(m.albedo(dry, 0.0, 1.0), dry); // dry texel
/// let soaked = m.albedo(dry, 1.0, 1.0);     // saturated texel
/// assert!(soaked.iter().zip(dry).all(|(w, d)| *w < d));
/// ```
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct WetMaterial {
    /// The liquid film.
    pub liquid: Liquid,
    /// The blend weight Γ(h).
    pub gamma: Gamma,
}

impl WetMaterial {
    /// Checks the liquid and the Γ parameters.
    pub fn validate(&self) -> Result<(), ParameterError> {
        self.liquid.validate()?;
        self.gamma.validate()
    }

    /// The fully wet albedo (Lekner–Dorf) of a texel with dry albedo `dry`
    /// (linear RGB in `[0, 1]`), lit at incidence cosine `cos_theta`
    /// (`R_spec` by Schlick).
    pub fn wet_albedo(&self, dry: [f64; 3], cos_theta: f64) -> [f64; 3] {
        let r_spec = schlick(cos_theta, self.liquid.f0());
        wet_albedo_rgb(
            dry,
            self.liquid.transmittance,
            r_spec,
            self.liquid.internal_reflectance(),
        )
    }

    /// The fully wet albedo under diffuse (uniform hemispherical) light:
    /// `R_spec` is then Stern's mean reflectance `R̄(n)`.
    pub fn wet_albedo_diffuse_light(&self, dry: [f64; 3]) -> [f64; 3] {
        let n = self.liquid.refractive_index;
        wet_albedo_rgb(
            dry,
            self.liquid.transmittance,
            stern_mean_reflectance(n),
            self.liquid.internal_reflectance(),
        )
    }

    /// The albedo of a texel with dry albedo `dry`, liquid saturation `h` in
    /// `[0, 1]` and light incidence cosine `cos_theta`:
    /// `(1 − Γ(h))·dry + Γ(h)·wet`. Exactly `dry` at `h = 0`.
    pub fn albedo(&self, dry: [f64; 3], saturation: f64, cos_theta: f64) -> [f64; 3] {
        let g = self.gamma.eval(saturation);
        if g <= 0.0 {
            return dry;
        }
        blend_rgb(dry, self.wet_albedo(dry, cos_theta), g)
    }

    /// Perceptual roughness of a texel with dry roughness `dry_roughness`
    /// in `[0, 1]` at saturation `h`: see [`wet_roughness`].
    pub fn roughness(&self, dry_roughness: f64, saturation: f64) -> f64 {
        wet_roughness(
            dry_roughness,
            self.liquid.film_roughness,
            self.gamma.eval(saturation),
        )
    }

    /// The film's specular BRDF in 1/sr at saturation `h`, weighted by
    /// Γ(h) (no film, no film highlight). Cosines as in [`film_specular`].
    pub fn film_specular(
        &self,
        n_dot_l: f64,
        n_dot_v: f64,
        n_dot_h: f64,
        v_dot_h: f64,
        saturation: f64,
    ) -> f64 {
        let g = self.gamma.eval(saturation);
        g * film_specular(
            n_dot_l,
            n_dot_v,
            n_dot_h,
            v_dot_h,
            alpha_from_roughness(self.liquid.film_roughness),
            self.liquid.f0(),
        )
    }
}

/// Checks a dry albedo: every channel finite and in `[0, 1]`.
pub fn validate_albedo(albedo: [f64; 3]) -> Result<(), ParameterError> {
    check_unit_rgb(["albedo.r", "albedo.g", "albedo.b"], albedo).map(drop)
}

/// Checks a liquid saturation: finite and in `[0, 1]`.
pub fn validate_saturation(saturation: f64) -> Result<(), ParameterError> {
    check_unit("saturation", saturation).map(drop)
}
