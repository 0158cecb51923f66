// Conservative return, per texel: its smooth share of the change
// (`smooth_change`), zero where nothing in its voxel's block changed.

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> liquid: array<f32>;
@group(0) @binding(2) var<storage, read> voxel_of: array<u32>;
@group(0) @binding(3) var<storage, read> dense: array<u32>;
@group(0) @binding(4) var<storage, read> cellinfo: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> factor: array<vec2<f32>>;
@group(0) @binding(6) var<storage, read_write> delta: array<f32>;
@group(0) @binding(7) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let i = texel_index(wg, lid);
    if (i >= params.info.x) {
        return;
    }
    let v = voxel_of[i];
    var d = 0.0;
    if (v != NONE && factor[v].y != 0.0) {
        let t = texels[2u * i];
        d = smooth_change(t.xyz * params.grid.w + params.grid.xyz, liquid[i], params.rates.w);
    }
    delta[i] = d;
}
