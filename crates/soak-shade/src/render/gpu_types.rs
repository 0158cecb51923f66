//! `#[repr(C)]` vertex and uniform layouts, mirrored field by field by the
//! WGSL structs of the same names in this module's shaders.

use crate::artist_curve::ArtistCurveGpu;

/// A mesh corner: object-space position and normal, UV, face (segment) id.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct MeshVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub face: u32,
}

/// A water vertex, world space.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct WaterVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
}

/// An arrow vertex, world space, with its linear colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ArrowVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub colour: [f32; 3],
}

/// Per-frame constants (`Frame` in `frame.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct FrameUniform {
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    pub light_view_proj: [[f32; 4]; 4],
    /// xyz eye; w = 1 for an orthographic camera.
    pub eye: [f32; 4],
    /// xyz unit view direction.
    pub forward: [f32; 4],
    /// xyz unit vector towards the sun.
    pub sun_direction: [f32; 4],
    /// rgb sun irradiance.
    pub sun_irradiance: [f32; 4],
    pub zenith: [f32; 4],
    pub horizon: [f32; 4],
    pub ground: [f32; 4],
    pub sky_mean: [f32; 4],
    /// rgb water scattering colour; w water F0, 0 without water.
    pub water: [f32; 4],
    /// x shadows on (1/0), y shadow-map texel size in UV, z normal offset
    /// in m, w depth bias in light NDC.
    pub shadow: [f32; 4],
    /// x debug view code.
    pub view: [u32; 4],
}

/// Per-object constants (`Object` in `surface.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ObjectUniform {
    pub model: [[f32; 4]; 4],
    /// rgb linear albedo (times the texture, if any).
    pub albedo: [f32; 4],
    /// rgb liquid transmittance σ; w refractive index.
    pub transmittance: [f32; 4],
    /// x R̄(n), y p(n) (both f64 on the CPU), z F0, w film GGX α.
    pub optics: [f32; 4],
    /// x Γ parameter, y mean world area per subsurface texel (m²).
    pub gamma: [f32; 4],
    /// x Γ kind (0–3 as `Gamma::gpu_code`, 4 artist curve), y albedo
    /// texture, z liquid texture, w subsurface texture.
    pub flags: [u32; 4],
    pub curve: ArtistCurveGpu,
}

/// Water look (`Water` in `water.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct WaterUniform {
    /// rgb scattering colour; w opacity.
    pub colour: [f32; 4],
    /// x F0, y GGX α, z fade-out start distance (m), w fade-out end (m).
    pub params: [f32; 4],
    /// xz centre of the drawn square.
    pub centre: [f32; 4],
}

/// One separable blur pass of the subsurface term (`Blur` in
/// `subsurface.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct BlurUniform {
    /// xy texel step direction, z Gaussian σ in m, w mean texel area in m².
    pub direction: [f32; 4],
    /// rgb weight of this Gaussian; w 1/(number of Gaussians).
    pub weight: [f32; 4],
    /// x 1 for the second (accumulating) pass.
    pub mode: [u32; 4],
}

/// Tone mapping constants (`Post` in `tonemap.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct PostUniform {
    /// x exposure.
    pub exposure: [f32; 4],
    /// x tone map (0 neutral, 1 linear), y dither (1/0).
    pub mode: [u32; 4],
}

const _: () = assert!(size_of::<MeshVertex>() == 36);
const _: () = assert!(size_of::<FrameUniform>() == 3 * 64 + 11 * 16);
const _: () = assert!(size_of::<ObjectUniform>() == 64 + 5 * 16 + 272);

/// An RGB triple and a fourth lane as a `vec4<f32>`.
pub(crate) fn rgba(v: [f64; 3], w: f64) -> [f32; 4] {
    [v[0] as f32, v[1] as f32, v[2] as f32, w as f32]
}

/// A vector and a fourth lane as a `vec4<f32>`.
pub(crate) fn vec4(v: &nalgebra::Vector3<f64>, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}
