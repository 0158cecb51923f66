#![doc = include_str!("../README.md")]

mod artist_curve;
mod error;
mod fresnel;
mod gamma;
mod lekner_dorf;
mod liquid;
mod mean_reflectance;
mod optics_table;
mod porosity_shortcut;
#[cfg(feature = "render")]
pub mod render;
mod specular;
mod wet_material;

pub use artist_curve::{ARTIST_CURVE_GPU_SAMPLES, ArtistCurve, ArtistCurveGpu};
pub use error::{
    CurveError, ParameterError, check_finite, check_non_negative, check_positive, check_refractive_index,
    check_unit, check_unit_rgb,
};
pub use fresnel::{fresnel_dielectric, fresnel_f0, schlick, schlick_f32};
pub use gamma::{
    GAMMA_ARCTAN, GAMMA_LINEAR, GAMMA_LOG, GAMMA_POWER, Gamma, blend, blend_rgb, gamma_arctan,
    gamma_from_code, gamma_linear, gamma_log, gamma_power,
};
pub use lekner_dorf::{
    EnergyBudget, absorbed_fraction, absorbed_fraction_rgb, liquid_absorbed_fraction, wet_albedo,
    wet_albedo_f32, wet_albedo_rgb,
};
pub use liquid::{Liquid, WATER_REFRACTIVE_INDEX, absorption_from_colour, beer_lambert, validate_absorption};
pub use mean_reflectance::{
    internal_reflectance, internal_reflectance_f32, stern_mean_reflectance, stern_mean_reflectance_f32,
};
pub use optics_table::{OpticsInput, OpticsOutput, WET_OPTICS_WGSL, evaluate, evaluate_table};
pub use porosity_shortcut::{lagarde_factor, lagarde_wet_diffuse, lagarde_wet_gloss};
pub use specular::{
    MIN_ALPHA, alpha_from_roughness, film_specular, ggx_distribution, smith_visibility, wet_roughness,
};
pub use wet_material::{WetMaterial, validate_albedo, validate_saturation};

/// The types and functions most shading code needs.
pub mod prelude {
    pub use crate::{
        ArtistCurve, Gamma, Liquid, ParameterError, WET_OPTICS_WGSL, WetMaterial, blend, film_specular,
        internal_reflectance, schlick, stern_mean_reflectance, wet_albedo, wet_albedo_rgb,
    };
}
