//! Buffer layouts shared with the kernels: `#[repr(C)]` bytemuck structs
//! mirrored field by field in WGSL: `Params` is `bindings.wgsl`'s. The
//! exchange kernel also reads soak-hydro's `Body` and `Wave`
//! ([`soak_hydro::gpu::wgsl`]). Only `[f32; 4]` and `[u32; 4]` fields, so no
//! WGSL alignment padding can hide.

use bytemuck::{Pod, Zeroable};

/// Invocations per workgroup of every kernel (`@workgroup_size(64)`).
pub(crate) const WG: u32 = 64;
/// Workgroups per dispatch dimension the WebGPU baseline allows.
pub(crate) const MAX_GROUPS_X: u32 = 65535;

pub(crate) const FLAG_WET_POSSIBLE: u32 = 1;
pub(crate) const FLAG_RAINING: u32 = 2;
pub(crate) const MODE_CONSERVATIVE: u32 = 0;
pub(crate) const MODE_THESIS: u32 = 1;
pub(crate) const REGION_EVERYWHERE: u32 = 0;
pub(crate) const REGION_DISC: u32 = 1;
pub(crate) const REGION_BOX: u32 = 2;

/// Per-step constants (WGSL `Params`, a uniform).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub(crate) struct Params {
    pub rates: [f32; 4],
    pub step: [f32; 4],
    pub region: [f32; 4],
    pub region2: [f32; 4],
    pub grid: [f32; 4],
    pub info: [u32; 4],
    pub dims: [u32; 4],
    pub info2: [u32; 4],
}

/// Workgroups `(x, y)` for one invocation per element of `count`, and the
/// `x` the kernels fold the flat index with.
pub(crate) fn groups(count: usize) -> [u32; 2] {
    let n = (count as u64).div_ceil(WG as u64).max(1);
    let x = n.min(MAX_GROUPS_X as u64);
    [x as u32, n.div_ceil(x) as u32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_match_the_wgsl() {
        assert_eq!(size_of::<Params>(), 8 * 16);
    }

    #[test]
    fn dispatches_fold_into_two_dimensions() {
        assert_eq!(groups(0), [1, 1]);
        assert_eq!(groups(64), [1, 1]);
        assert_eq!(groups(65), [2, 1]);
        let g = groups(64 * 200_000);
        assert_eq!(g[0], MAX_GROUPS_X);
        assert!(g[0] as u64 * g[1] as u64 * 64 >= 64 * 200_000);
    }
}
