// After the substeps, per cell: conservative (start volume M, new volume
// M' clamped to [0, C], capacity C, fill change (M' − M) / C); thesis
// (the diffused Shepard value, 0, 0, 0).

@group(0) @binding(0) var<storage, read> initial: array<f32>;
@group(0) @binding(1) var<storage, read> current: array<f32>;
@group(0) @binding(2) var<storage, read> capacity: array<f32>;
@group(0) @binding(3) var<storage, read_write> cellinfo: array<vec4<f32>>;
@group(0) @binding(4) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let v = voxel_index(wg, lid);
    if (v >= params.info.w) {
        return;
    }
    if (params.info2.y == MODE_THESIS) {
        cellinfo[v] = vec4<f32>(current[v], 0.0, 0.0, 0.0);
    } else {
        let c = capacity[v];
        let m0 = initial[v];
        let m1 = clamp(current[v], 0.0, c);
        cellinfo[v] = vec4<f32>(m0, m1, c, (m1 - m0) / c);
    }
}
