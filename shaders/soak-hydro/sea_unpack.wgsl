// A spectral sea's tile on the GPU, last half: the seven transformed layers
// (sea_modes.wgsl, then the inverse FFT of waves.wgsl) laid out per node in
// `heights` for water_surface.wgsl's read (SURFACE_SPECTRAL), sixteen floats
// a node from `fields_first`, node (ix, iz) at iz n + ix:
//
//   0..4    η (m) and its x-slope, z-slope and twist, each per cell
//           (times the cell side d, d, d²): the Hermite data of η
//   4..8    Dx / d and its derivatives over the rest position in cells
//           (∂Dx/∂x, ∂Dx/∂z, d ∂²Dx/∂x∂z): the Hermite data of Dx in cells
//   8..12   the same of Dz
//   12..15  the water's velocity at the node (m/s); 15 unused
//
// After sea.wgsl.

@group(0) @binding(0) var<storage, read> spec: array<vec2<f32>>;
@group(0) @binding(1) var<storage, read_write> heights: array<f32>;
@group(0) @binding(2) var<uniform> sea: Sea;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * 64u;
    let nn = sea.n * sea.n;
    if (t >= nn) {
        return;
    }
    let d = sea.cell;
    let height_vy = spec[t];
    let disp = spec[nn + t];
    let grad = spec[2u * nn + t];
    let dxx_dzz = spec[3u * nn + t];
    let dxz_hxz = spec[4u * nn + t];
    let twists = spec[5u * nn + t];
    let v = spec[6u * nn + t];
    let at = sea.fields_first + 16u * t;
    heights[at] = height_vy.x;
    heights[at + 1u] = grad.x * d;
    heights[at + 2u] = grad.y * d;
    heights[at + 3u] = dxz_hxz.y * d * d;
    heights[at + 4u] = disp.x / d;
    heights[at + 5u] = dxx_dzz.x;
    heights[at + 6u] = dxz_hxz.x;
    heights[at + 7u] = twists.x * d;
    heights[at + 8u] = disp.y / d;
    heights[at + 9u] = dxz_hxz.x;
    heights[at + 10u] = dxx_dzz.y;
    heights[at + 11u] = twists.y * d;
    heights[at + 12u] = v.x;
    heights[at + 13u] = height_vy.y;
    heights[at + 14u] = v.y;
    heights[at + 15u] = 0.0;
}
