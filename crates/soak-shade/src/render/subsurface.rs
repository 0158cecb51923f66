//! The texture-space subsurface term (d'Eon, Luebke & Enderton 2007, as the
//! thesis' §6.1.2 after Borshukov & Lewis 2003): light entering the wet
//! film at one point leaves it at another, so the wet diffuse term uses the
//! transmitted irradiance blurred over the surface by a sum of Gaussians.

use super::error::RenderError;

/// One Gaussian of a diffusion profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubsurfaceGaussian {
    /// Variance `v` of `G(r) = exp(−r²/2v)/(2πv)`, m².
    pub variance: f64,
    /// Weight per RGB channel; a profile's weights sum to 1 per channel.
    pub weight: [f64; 3],
}

/// The texture-space subsurface option of a [`RenderScene`](super::RenderScene).
///
/// Per object with UVs: the irradiance transmitted into the film,
/// `(1 − R_spec)·E_sun + (1 − R̄)·E_env`, is rasterised into its UV square
/// together with each texel's world area (so texels stretched by the UV map
/// weigh what they cover, and the kernel is in metres, not texels); each
/// Gaussian blurs it in two separable passes; the weighted sum replaces the
/// local irradiance of the wet term, `T·E_blurred/π` with the Lekner–Dorf
/// transmission `T = σ² a (1 − p)/(1 − p a σ²)`. The dry term stays local.
/// Where the blur sees constant irradiance it changes nothing: it only
/// moves light across edges (shadow boundaries, creases).
#[derive(Debug, Clone, PartialEq)]
pub struct Subsurface {
    /// The diffusion profile, a sum of Gaussians (at most 8).
    pub profile: Vec<SubsurfaceGaussian>,
    /// Side of each object's irradiance texture, texels (16..=4096).
    pub resolution: u32,
}

impl Default for Subsurface {
    /// [`Subsurface::wet_film`] at 256².
    fn default() -> Self {
        Self {
            profile: Self::wet_film(),
            resolution: 256,
        }
    }
}

impl Subsurface {
    /// A grey profile for a water film on a porous surface: σ = 0.5, 2 and
    /// 8 mm with weights 0.5, 0.3, 0.2. Light wanders millimetres, so the
    /// term only shows at close range.
    pub fn wet_film() -> Vec<SubsurfaceGaussian> {
        [(0.5e-3, 0.5), (2e-3, 0.3), (8e-3, 0.2)]
            .map(|(sigma, w): (f64, f64)| SubsurfaceGaussian {
                variance: sigma * sigma,
                weight: [w; 3],
            })
            .to_vec()
    }

    /// d'Eon et al.'s six-Gaussian fit of skin (variances 0.0064 to
    /// 7.41 mm²), for reference and comparison.
    pub fn skin() -> Vec<SubsurfaceGaussian> {
        [
            (0.0064, [0.233, 0.455, 0.649]),
            (0.0484, [0.100, 0.336, 0.344]),
            (0.187, [0.118, 0.198, 0.0]),
            (0.567, [0.113, 0.007, 0.007]),
            (1.99, [0.358, 0.004, 0.0]),
            (7.41, [0.078, 0.0, 0.0]),
        ]
        .map(|(v_mm2, weight)| SubsurfaceGaussian {
            variance: v_mm2 * 1e-6,
            weight,
        })
        .to_vec()
    }

    /// The same profile with every distance multiplied by `factor`
    /// (variances by `factor²`): to show the effect at the scale of a scene.
    pub fn scaled(mut self, factor: f64) -> Self {
        for g in &mut self.profile {
            g.variance *= factor * factor;
        }
        self
    }

    /// Checks the profile and resolution.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |detail: String| RenderError::Scene {
            what: "subsurface".into(),
            detail,
        };
        if self.profile.is_empty() || self.profile.len() > 8 {
            return Err(bad(format!(
                "the profile has {} Gaussians; use 1 to 8",
                self.profile.len()
            )));
        }
        for (i, g) in self.profile.iter().enumerate() {
            if !(g.variance.is_finite() && g.variance >= 0.0) {
                return Err(bad(format!("Gaussian {i} has variance {}", g.variance)));
            }
            if !g.weight.iter().all(|w| w.is_finite() && *w >= 0.0) {
                return Err(bad(format!("Gaussian {i} has weights {:?}", g.weight)));
            }
        }
        if !(16..=4096).contains(&self.resolution) {
            return Err(bad(format!(
                "resolution {} is outside 16..=4096",
                self.resolution
            )));
        }
        Ok(())
    }
}
