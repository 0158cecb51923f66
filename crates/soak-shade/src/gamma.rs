//! Γ(h): how much of the wet look a texel with liquid saturation `h` shows.

use crate::artist_curve::ArtistCurve;
use crate::error::{ParameterError, check_positive};
use crate::fresnel::unit;

/// Below this shape parameter the log and arctan families are linear to
/// within rounding, and are evaluated as such.
const LINEAR_LIMIT: f64 = 1e-9;

/// Forces the contract: exact ends, values in `[0, 1]`, NaN to 0.
fn finish(h: f64, g: f64) -> f64 {
    if h <= 0.0 {
        0.0
    } else if h >= 1.0 {
        1.0
    } else {
        unit(g)
    }
}

/// Logarithmic Γ: `ln(1 + k h) / ln(1 + k)`, concave, for a shape
/// parameter `k > 0` (dimensionless). `k → 0` tends to linear (and `k ≤ 0`
/// or NaN is evaluated as linear).
pub fn gamma_log(h: f64, k: f64) -> f64 {
    let h = unit(h);
    let g = if k > LINEAR_LIMIT && k.is_finite() {
        (k * h).ln_1p() / k.ln_1p()
    } else if k == f64::INFINITY {
        1.0
    } else {
        h
    };
    finish(h, g)
}

/// Power Γ: `h^γ` for an exponent `γ > 0` (dimensionless). `γ ≤ 0` gives a
/// step (Γ = 1 for every `h > 0`); NaN gives 0 inside `(0, 1)`.
pub fn gamma_power(h: f64, exponent: f64) -> f64 {
    let h = unit(h);
    finish(h, h.powf(exponent))
}

/// Arctan sigmoid Γ (the thesis' preferred family):
/// `½(atan(r(h − ½)) / atan(r/2) + 1)`, normalised so Γ(0) = 0 and
/// Γ(1) = 1 exactly. The surface roughness `r ≥ 0` (dimensionless) sets the
/// steepness: `r → 0` tends to linear (smooth, polished materials), large
/// `r` to a step at `h = ½` (rough materials). Negative `r` acts as `|r|`.
pub fn gamma_arctan(h: f64, roughness: f64) -> f64 {
    let h = unit(h);
    let r = roughness.abs();
    let g = if r > LINEAR_LIMIT {
        0.5 * ((r * (h - 0.5)).atan() / (0.5 * r).atan() + 1.0)
    } else {
        h
    };
    finish(h, g)
}

/// Linear Γ: `h` clamped to `[0, 1]`.
pub fn gamma_linear(h: f64) -> f64 {
    unit(h)
}

/// The wet/dry blend `(1 − Γ)·dry + Γ·wet` for a weight `gamma` in `[0, 1]`
/// (clamped; NaN counts as 0, i.e. dry). Exactly `dry` at Γ = 0 and exactly
/// `wet` at Γ = 1. (The thesis prints the weights swapped.)
///
/// # Example
/// ```
/// use soak_shade::{blend, gamma_arctan};
/// assert_eq!(blend(0.5, 0.3, gamma_arctan(0.0, 8.0)), 0.5);
/// assert_eq!(blend(0.5, 0.3, gamma_arctan(1.0, 8.0)), 0.3);
/// ```
pub fn blend(dry: f64, wet: f64, gamma: f64) -> f64 {
    let g = unit(gamma);
    if g >= 1.0 { wet } else { (1.0 - g) * dry + g * wet }
}

/// [`blend`] per RGB channel with one weight.
pub fn blend_rgb(dry: [f64; 3], wet: [f64; 3], gamma: f64) -> [f64; 3] {
    std::array::from_fn(|i| blend(dry[i], wet[i], gamma))
}

/// A Γ family with its parameter.
///
/// The thesis blends the dry and the wet reflectance with a weight Γ(h) that
/// must satisfy Γ(0) = 0, Γ(1) = 1 and be non-decreasing (§6.1.1). Its printed
/// blend `Γ(h)·BRDF_dry + (1 − Γ(h))·BSSRDF_wet` has the two weights swapped
/// (it would make a dry texel look wet); the blend here is
/// `(1 − Γ(h))·dry + Γ(h)·wet`.
///
/// Families (all map `[0, 1]` onto `[0, 1]` with exact ends, for every
/// parameter value; `h` outside `[0, 1]` is clamped, NaN counts as 0):
///
/// | family | Γ(h) | parameter |
/// |---|---|---|
/// | linear | `h` | — |
/// | log | `ln(1 + k h) / ln(1 + k)` | `k > 0`: larger darkens sooner |
/// | power | `h^γ` | `γ > 0`: `< 1` darkens sooner |
/// | arctan sigmoid | `½(atan(r(h − ½))/atan(r/2) + 1)` | roughness `r > 0`: larger is more abrupt |
/// | artist | piecewise linear through a 1-D table | [`ArtistCurve`] |
///
/// # Example
/// ```
/// use soak_shade::Gamma;
/// let g = Gamma::Arctan { roughness: 8.0 };
/// g.validate().unwrap();
/// assert_eq!(g.eval(0.0), 0.0);
/// assert_eq!(g.eval(1.0), 1.0);
/// assert!(g.eval(0.25) < 0.25); // a sigmoid lags, then catches up
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
#[non_exhaustive]
pub enum Gamma {
    /// `Γ(h) = h`.
    Linear,
    /// `Γ(h) = ln(1 + k h)/ln(1 + k)`, see [`gamma_log`].
    Log {
        /// Shape `k > 0`, dimensionless.
        k: f64,
    },
    /// `Γ(h) = h^γ`, see [`gamma_power`].
    Power {
        /// Exponent `γ > 0`, dimensionless.
        exponent: f64,
    },
    /// Arctan sigmoid, see [`gamma_arctan`].
    Arctan {
        /// Surface roughness `r > 0`, dimensionless.
        roughness: f64,
    },
    /// Piecewise linear artist curve, see [`ArtistCurve`].
    Artist {
        /// The curve.
        curve: ArtistCurve,
    },
}

impl Default for Gamma {
    /// The arctan sigmoid with `r = 8`, the family the thesis found most
    /// convincing.
    fn default() -> Self {
        Gamma::Arctan { roughness: 8.0 }
    }
}

impl Gamma {
    /// Γ(h) for a saturation `h` in `[0, 1]` (clamped; NaN counts as 0).
    /// Always in `[0, 1]`, non-decreasing in `h`, exact at the ends.
    pub fn eval(&self, h: f64) -> f64 {
        match self {
            Gamma::Linear => gamma_linear(h),
            Gamma::Log { k } => gamma_log(h, *k),
            Gamma::Power { exponent } => gamma_power(h, *exponent),
            Gamma::Arctan { roughness } => gamma_arctan(h, *roughness),
            Gamma::Artist { curve } => curve.eval(h),
        }
    }

    /// Checks the shape parameter: `k`, `γ` and `r` must be finite and `> 0`.
    /// (An [`ArtistCurve`] is validated when it is built.)
    pub fn validate(&self) -> Result<(), ParameterError> {
        match self {
            Gamma::Linear | Gamma::Artist { .. } => Ok(()),
            Gamma::Log { k } => check_positive("gamma.k", *k).map(drop),
            Gamma::Power { exponent } => check_positive("gamma.exponent", *exponent).map(drop),
            Gamma::Arctan { roughness } => check_positive("gamma.roughness", *roughness).map(drop),
        }
    }

    /// The GPU encoding `(kind, parameter)` used by
    /// [`OpticsInput`](crate::OpticsInput): 0 linear, 1 log, 2 power,
    /// 3 arctan. `None` for an artist curve, which the GPU reads from an
    /// [`ArtistCurveGpu`](crate::ArtistCurveGpu) instead.
    pub fn gpu_code(&self) -> Option<(u32, f32)> {
        match self {
            Gamma::Linear => Some((GAMMA_LINEAR, 0.0)),
            Gamma::Log { k } => Some((GAMMA_LOG, *k as f32)),
            Gamma::Power { exponent } => Some((GAMMA_POWER, *exponent as f32)),
            Gamma::Arctan { roughness } => Some((GAMMA_ARCTAN, *roughness as f32)),
            Gamma::Artist { .. } => None,
        }
    }
}

/// GPU code of [`Gamma::Linear`] (and of any unknown code).
pub const GAMMA_LINEAR: u32 = 0;
/// GPU code of [`Gamma::Log`].
pub const GAMMA_LOG: u32 = 1;
/// GPU code of [`Gamma::Power`].
pub const GAMMA_POWER: u32 = 2;
/// GPU code of [`Gamma::Arctan`].
pub const GAMMA_ARCTAN: u32 = 3;

/// Γ from a GPU code (see [`Gamma::gpu_code`]); unknown codes are linear.
pub fn gamma_from_code(kind: u32, parameter: f64, h: f64) -> f64 {
    match kind {
        GAMMA_LOG => gamma_log(h, parameter),
        GAMMA_POWER => gamma_power(h, parameter),
        GAMMA_ARCTAN => gamma_arctan(h, parameter),
        _ => gamma_linear(h),
    }
}
