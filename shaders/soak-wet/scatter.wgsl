// Voxels to texels. Conservative: the smooth share of the change
// (`delta.wgsl`) plus the cell's rest (`residual.wgsl`), skipping cells
// whose block did not change.
// Thesis: the Shepard average of the defined voxels among the 8 nearest
// voxel centres (Eq. 5.13–5.14), clamped to [0, h_max].

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> liquid: array<f32>;
@group(0) @binding(2) var<storage, read> voxel_of: array<u32>;
@group(0) @binding(3) var<storage, read> dense: array<u32>;
@group(0) @binding(4) var<storage, read> cellinfo: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> factor: array<vec2<f32>>;
@group(0) @binding(6) var<storage, read> delta: array<f32>;
@group(0) @binding(7) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let i = texel_index(wg, lid);
    if (i >= params.info.x) {
        return;
    }
    let v = voxel_of[i];
    if (v == NONE) {
        return;
    }
    let hmax = params.rates.w;
    let g = texels[2u * i].xyz * params.grid.w + params.grid.xyz;
    var h = liquid[i];
    if (params.info2.y == MODE_THESIS) {
        let base = vec3<i32>(floor(g - vec3<f32>(0.5)));
        let dims = vec3<i32>(params.dims.xyz);
        var num = 0.0;
        var den = 0.0;
        for (var corner = 0u; corner < 8u; corner++) {
            let c = base + vec3<i32>(i32(corner & 1u), i32((corner >> 1u) & 1u), i32((corner >> 2u) & 1u));
            if (any(c < vec3<i32>(0)) || any(c >= dims)) {
                continue;
            }
            let id = dense[u32(c.x) + params.dims.x * (u32(c.y) + params.dims.y * u32(c.z))];
            if (id == NONE) {
                continue;
            }
            let w = shepard(length(g - (vec3<f32>(c) + vec3<f32>(0.5))));
            num += w * cellinfo[id].x;
            den += w;
        }
        if (den > 0.0) {
            h = clamp(num / den, 0.0, hmax);
        }
    } else {
        let f = factor[v];
        if (f.y == 0.0) {
            return;
        }
        h = h + delta[i];
        if (f.x < 0.0) {
            h = h * (1.0 + f.x);
        } else {
            h = h + f.x * (hmax - h);
        }
        h = clamp(h, 0.0, hmax);
    }
    liquid[i] = h;
}
