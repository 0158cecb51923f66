// Conservative return, per cell: whether any cell of its 3x3x3 block
// changed (else its texels keep their liquid exactly and are skipped).
// Writes factor[v] = (0, changed).

@group(0) @binding(0) var<storage, read> cellinfo: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> nstart: array<u32>;
@group(0) @binding(2) var<storage, read> neighbours: array<u32>;
@group(0) @binding(3) var<storage, read_write> factor: array<vec2<f32>>;
@group(0) @binding(4) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let v = voxel_index(wg, lid);
    if (v >= params.info.w) {
        return;
    }
    var changed = cellinfo[v].w != 0.0;
    for (var k = nstart[v]; k < nstart[v + 1u] && !changed; k++) {
        changed = cellinfo[neighbours[k]].w != 0.0;
    }
    factor[v] = vec2<f32>(0.0, select(0.0, 1.0, changed));
}
