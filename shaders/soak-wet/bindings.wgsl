// soak-wet: buffer layouts of the wetting kernels (feature `gpu`).
//
// Composed after soak-hydro's bindings.wgsl (Body, Wave, SURFACE_*) and
// water_surface.wgsl. `Params` mirrors the `#[repr(C)]` bytemuck
// struct in crates/soak-wet/src/gpu/layout.rs field by field: vec4 fields
// only, so WGSL's alignment rules insert no hidden padding.

const NONE: u32 = 0xffffffffu;
const FLAG_WET_POSSIBLE: u32 = 1u;
const FLAG_RAINING: u32 = 2u;
const MODE_THESIS: u32 = 1u;
const REGION_DISC: u32 = 1u;
const REGION_BOX: u32 = 2u;
// Minimum Shepard distance in voxels (SHEPARD_MIN_DISTANCE).
const SHEPARD_MIN: f32 = 0.02;

struct Params {
    // absorption per metre of depth (1/s), evaporation (m/s), rain (m/s),
    // saturation h_max (m)
    rates: vec4<f32>,
    // dt (s), lowest trough and highest crest relative to o_w.y (m),
    // kernel weight w per substep
    step: vec4<f32>,
    // rain region relative to o_w: disc (cx, cz, r^2, 0) or box min (xyz)
    region: vec4<f32>,
    // rain region: box max (xyz), relative to o_w
    region2: vec4<f32>,
    // grid coordinates of the atlas origin (xyz), 1 / voxel size (1/m)
    grid: vec4<f32>,
    // texels, flags, rain region kind, defined voxels
    info: vec4<u32>,
    // grid dims (xyz), workgroups along x of the per-texel dispatches
    dims: vec4<u32>,
    // workgroups along x of the per-voxel dispatches, mode (0 conservative,
    // 1 thesis), unused, unused
    info2: vec4<u32>,
}

fn texel_index(wg: vec3<u32>, lid: u32) -> u32 {
    return (wg.y * params.dims.w + wg.x) * 64u + lid;
}

fn voxel_index(wg: vec3<u32>, lid: u32) -> u32 {
    return (wg.y * params.info2.x + wg.x) * 64u + lid;
}

fn shepard(d: f32) -> f32 {
    return 1.0 / max(d, SHEPARD_MIN);
}
