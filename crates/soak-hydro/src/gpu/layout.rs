//! Buffer layouts shared with the kernels: `#[repr(C)]` bytemuck structs
//! mirrored field by field in `bindings.wgsl`. Only `[f32; 4]`,
//! `[u32; 4]` and `u32` fields, so no WGSL alignment padding can hide.

use bytemuck::{Pod, Zeroable};

/// Invocations per workgroup (`WG` in the WGSL).
pub(crate) const WG: u32 = 64;
/// Texels per invocation (`PER_THREAD` in the WGSL).
pub(crate) const PER_THREAD: u32 = 64;
/// Texels per work item (one workgroup, one partial).
pub(crate) const ITEM_TEXELS: u32 = WG * PER_THREAD;
/// vec4s per hydrostatics partial (`SLOTS` in buoyancy.wgsl).
pub(crate) const HYDRO_SLOTS: u32 = 12;
/// vec4s per mass partial (`SLOTS` in mass.wgsl).
pub(crate) const MASS_SLOTS: u32 = 3;
/// Bytes per texel in a page: position and area vector, two vec4s.
pub(crate) const TEXEL_BYTES: u64 = 32;
/// Bytes per texel of the triangle id and barycentrics.
pub(crate) const TRIBARY_BYTES: u64 = 16;
/// Stride of the per-dispatch uniforms (dynamic offsets).
pub(crate) const DISPATCH_STRIDE: u64 = 256;
/// Workgroups per dispatch dimension the WebGPU baseline allows.
pub(crate) const MAX_GROUPS_X: u32 = 65535;
/// Refuses `floats` f32 a kernel indexes with a `u32` when they are more
/// than it reaches, naming `what` they are.
pub(crate) fn u32_indexed(what: &'static str, floats: u64) -> Result<(), soak_gpu::GpuError> {
    if floats > u64::from(u32::MAX) {
        return Err(soak_gpu::GpuError::TooLarge {
            what,
            needed: floats * 4,
            limit: u64::from(u32::MAX) * 4,
        });
    }
    Ok(())
}

/// Threads per workgroup of every kernel (`@workgroup_size(64)`).
pub(crate) const GROUP_THREADS: u32 = 64;

/// Workgroups `[x, y]` for one thread per element of `threads` elements,
/// at most [`MAX_GROUPS_X`] along x (a kernel counts its element as
/// `(y · x_groups + x) · 64 + local`, and skips those past the end).
pub(crate) fn thread_groups(threads: u32) -> [u32; 2] {
    let count = threads.div_ceil(GROUP_THREADS);
    let x = count.clamp(1, MAX_GROUPS_X);
    [x, count.div_ceil(x)]
}

pub(crate) const SURFACE_PLANE: u32 = 0;
pub(crate) const SURFACE_GERSTNER: u32 = 1;
pub(crate) const SURFACE_HEIGHT_FIELD: u32 = 2;
pub(crate) const SURFACE_UNBOUNDED: u32 = 3;
pub(crate) const SURFACE_PATCH: u32 = 4;
/// A spectral sea read exactly from its tile's fields on the device.
pub(crate) const SURFACE_SPECTRAL: u32 = 5;
/// Floats per node of a spectral sea's fields in the `heights` binding.
pub(crate) const SEA_NODE_FLOATS: usize = 16;
/// Floats per cell of a patch's bicubic coefficients in the `heights` binding.
pub(crate) const PATCH_CELL_FLOATS: usize = 16;
/// Floats per cell of a patch's velocity coefficients in the `heights` binding.
pub(crate) const PATCH_VELOCITY_CELL_FLOATS: usize = 24;

/// One body of a batch (WGSL `Body`): its pose and its water surface, seen
/// from the body's atlas origin `o_w` in world axes, so f32 keeps its
/// precision anywhere in the world.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct Body {
    /// First row of the rotation object → world (w unused).
    pub rot0: [f32; 4],
    /// Second row of the rotation object → world (w unused).
    pub rot1: [f32; 4],
    /// Third row of the rotation object → world (w unused).
    pub rot2: [f32; 4],
    /// Plane or unbounded medium: unit normal xyz, w = offset − n·o_w (m).
    /// Gerstner: x = mean level − o_w.y (m). Height field and sampled
    /// surface (patch): x, y = grid coordinates (x, z) of o_w, z, w =
    /// 1/spacing (1/m).
    pub surface: [f32; 4],
    /// Gerstner: x, y = world x, z of o_w (m). Height field and patch: x =
    /// reference height − o_w.y (m); patch: y = the velocity grid's
    /// coordinate along y of o_w.
    pub surface2: [f32; 4],
    /// Fluid velocity (plane, height field, unbounded), m/s: uniform, or
    /// at o_w where the current changes linearly (`flow0`..`flow2`).
    pub current: [f32; 4],
    /// Centre of mass − o_w, world axes, m.
    pub com: [f32; 4],
    /// xyz: velocity of the centre of mass (m/s); w: fluid density (kg/m³).
    pub linear_velocity: [f32; 4],
    /// xyz: angular velocity (rad/s); w: quadratic drag coefficient.
    pub angular_velocity: [f32; 4],
    /// x: linear skin friction (N s/m per m²); y: 1 when drag is wanted;
    /// z: 1 when Archimedes' slope sum is wanted; w: the atlas' mean
    /// thickness (m, 0 where it encloses no volume).
    pub drag: [f32; 4],
    /// x: surface kind (`SURFACE_*`); y: first wave, first height sample
    /// or first patch coefficient; z: wave count, samples along x or patch
    /// cells along x; w: samples or patch cells along z.
    pub info: [u32; 4],
    /// x: atlas slot (bounding radius for the unbounded medium). Patch:
    /// y = first velocity coefficient, z = velocity nodes along y (0 when
    /// the patch has no velocities).
    pub slot: [u32; 4],
    /// Rows of the current's gradient `∂u_i/∂p_j` (1/s, world axes; w
    /// unused): the fluid moves at `current + G r` at `r` from o_w. Zero
    /// but under a [`FlowPlane`](crate::FlowPlane).
    pub flow0: [f32; 4],
    /// Second row of the current's gradient.
    pub flow1: [f32; 4],
    /// Third row of the current's gradient.
    pub flow2: [f32; 4],
}

/// An atlas's texels as the kernels read them: two vec4s per texel, the
/// position relative to the atlas origin with the texel's area `(x − o, |A|)`
/// (m, m²), then its area vector `(A, 0)` (m²).
pub fn texel_vec4s(atlas: &soak_bake::Atlas) -> Vec<[f32; 4]> {
    let mut texels = Vec::with_capacity(2 * atlas.len());
    for ((x, a), &area) in atlas
        .local_positions()
        .iter()
        .zip(atlas.area_vectors().iter())
        .zip(atlas.areas())
    {
        texels.push([x[0], x[1], x[2], area]);
        texels.push([a[0], a[1], a[2], 0.0]);
    }
    texels
}

/// One Gerstner wave (WGSL `Wave`), its phase at the body's origin and time
/// folded in.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct Wave {
    /// Direction x, direction z, wavenumber k (1/m), angular frequency (rad/s).
    pub a: [f32; 4],
    /// Q·A (m), amplitude (m), phase k d·o_w − ω t + φ (rad), unused.
    pub b: [f32; 4],
}

/// A run of texels of one page (WGSL `Item`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub(crate) struct Item {
    pub body: u32,
    pub start: u32,
    pub end: u32,
    pub partial: u32,
}

/// Per-dispatch constants (WGSL `Dispatch`), at a 256-byte stride.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub(crate) struct Dispatch {
    pub base: u32,
    pub count: u32,
    pub groups_x: u32,
    pub mode: u32,
    pub param: [f32; 4],
}

impl Dispatch {
    /// Constants and workgroup counts `(x, y)` for `count` workgroups from `base`.
    pub(crate) fn new(base: u32, count: u32, mode: u32, param: [f32; 4]) -> (Self, [u32; 2]) {
        let x = count.clamp(1, MAX_GROUPS_X);
        let y = count.div_ceil(x).max(1);
        (
            Self {
                base,
                count,
                groups_x: x,
                mode,
                param,
            },
            [x, y],
        )
    }
}

/// Packs dispatch constants at [`DISPATCH_STRIDE`] for dynamic offsets.
pub(crate) fn dispatch_bytes(dispatches: &[Dispatch]) -> Vec<u8> {
    let mut out = vec![0u8; dispatches.len().max(1) * DISPATCH_STRIDE as usize];
    for (i, d) in dispatches.iter().enumerate() {
        let at = i * DISPATCH_STRIDE as usize;
        out[at..at + size_of::<Dispatch>()].copy_from_slice(bytemuck::bytes_of(d));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_match_the_wgsl() {
        assert_eq!(size_of::<Body>(), 15 * 16);
        assert_eq!(size_of::<Wave>(), 32);
        assert_eq!(size_of::<Item>(), 16);
        assert_eq!(size_of::<Dispatch>(), 32);
    }

    #[test]
    fn dispatches_fold_into_two_dimensions() {
        let (d, g) = Dispatch::new(0, 200_000, 0, [0.0; 4]);
        assert_eq!(g[0], MAX_GROUPS_X);
        assert!(g[0] as u64 * g[1] as u64 >= 200_000);
        assert_eq!(d.groups_x, MAX_GROUPS_X);
        assert_eq!(Dispatch::new(0, 0, 0, [0.0; 4]).1, [1, 1]);
    }
}
