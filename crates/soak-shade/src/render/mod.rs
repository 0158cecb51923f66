//! An offscreen wgpu renderer for soak scenes (feature `render`): frames a
//! person can look at, showing wetness the way the optics of this crate say
//! it looks.
//!
//! - **Surfaces**: meshes ([`soak_bake::Mesh`]) with a pose, an albedo
//!   (constant or an sRGB texture) and an optional *liquid texture* (W×H
//!   saturations in `[0, 1]` over the UV square, row 0 at `v = 0`). Each
//!   pixel shows `(1 − Γ(h))·dry + Γ(h)·wet` of a [`WetMaterial`](crate::WetMaterial):
//!   dry is Lambertian; wet is the Lekner–Dorf albedo (Schlick `R_spec`
//!   for the sun, Stern's `R̄` for the environment) plus the smooth film's
//!   GGX lobe and its Fresnel reflection of the sky. The shaders call the
//!   WGSL optics library ([`WET_OPTICS_WGSL`](crate::WET_OPTICS_WGSL)); `R̄`
//!   and `p` come in as uniforms computed in f64.
//! - **Light**: a directional sun with a shadow map (3×3 PCF) and a
//!   sky/ground environment that lights, is reflected, and is the
//!   background.
//! - **Water**: a plane, a Gerstner sea ([`soak_hydro::Gerstner`]) or a
//!   spectral sea's tile ([`soak_hydro::SeaFields`]) as a displaced grid, Fresnel-shaded and semi-transparent, fading into a
//!   distant sea at the horizon.
//! - **Subsurface** (off by default): the texture-space sum-of-Gaussians
//!   irradiance blur of d'Eon et al. (2007), weighted by texel area
//!   ([`Subsurface`]).
//! - **Debug views**: liquid saturation in pseudo-colour, per-segment
//!   colours, normals ([`DebugView`]); force arrows ([`Arrow`]) on top.
//! - **Output**: an 8-bit sRGB [`image::RgbaImage`] (Khronos PBR Neutral
//!   tone mapping, or linear for measurements).
//!
//! The renderer takes a device ([`Renderer::new`]); [`headless_device`]
//! makes one for tools and tests. [`evaluate_table_gpu`] runs the WGSL
//! optics on a table for the CPU/GPU parity check, and [`material_sweep()`]
//! draws the thesis' Fig. 6.3.

mod camera;
mod colour;
mod error;
mod frame;
mod geometry;
mod gpu_types;
mod liquid_texture;
mod material_sweep;
mod optics_gpu;
mod passes;
mod pipelines;
mod procedural;
mod readback;
mod renderer;
mod scene;
mod subsurface;
mod targets;
mod text;
mod upload;
mod validation;

/// The font type of [`MaterialSweep::font`] (ab_glyph's).
pub use ab_glyph::FontArc as Font;
pub use camera::{Camera, Projection};
pub use colour::{
    hue_degrees, hue_distance, linear_to_pixel, linear_to_srgb, luminance, mean_linear, pixel_to_linear,
    srgb_to_linear,
};
pub use error::RenderError;
pub use liquid_texture::liquid_image_from_texels;
pub use material_sweep::{MaterialSweep, SweepColumn, SweepRow, SweepWetness, material_sweep};
pub use optics_gpu::{GpuOpticsTable, evaluate_table_gpu, optics_kernel_source};
pub use pipelines::shader_sources;
pub use procedural::{blotches, fractal_noise, speckled, value_noise, wood_planks};
pub use renderer::{Renderer, RendererOptions};
pub use scene::{
    Albedo, Arrow, DebugView, DirectionalLight, Environment, INTERACTIVE_RESOLUTION, LiquidImage,
    RenderObject, RenderScene, RenderWater, ToneMap, WaterShape,
};
/// The device helpers every GPU path of soak shares, re-exported from soak-gpu.
pub use soak_gpu::{GpuError, adapter_label, headless_device, is_software, test_device};
pub use subsurface::{Subsurface, SubsurfaceGaussian};
pub use text::{TextLayout, layout_text};
