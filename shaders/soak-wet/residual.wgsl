// Conservative return, per changed cell: what its texels' smooth shares
// (`delta.wgsl`) leave over of the cell's change M' − M, as a factor:
// f > 0 fills that fraction of the room left, f < 0 takes that fraction of
// the liquid left. Writes factor[v] = (f, changed).

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> start: array<u32>;
@group(0) @binding(2) var<storage, read> members: array<u32>;
@group(0) @binding(3) var<storage, read> delta: array<f32>;
@group(0) @binding(4) var<storage, read> cellinfo: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> factor: array<vec2<f32>>;
@group(0) @binding(6) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let v = voxel_index(wg, lid);
    if (v >= params.info.w || factor[v].y == 0.0) {
        return;
    }
    var spread = 0.0;
    for (var k = start[v]; k < start[v + 1u]; k++) {
        let i = members[k];
        spread += texels[2u * i].w * delta[i];
    }
    let info = cellinfo[v];
    let rest = (info.y - info.x) - spread;
    let room = info.z - info.x - spread;
    let content = info.x + spread;
    var f = 0.0;
    if (rest > 0.0 && room > 0.0) {
        f = min(rest / room, 1.0);
    } else if (rest < 0.0 && content > 0.0) {
        f = max(rest / content, -1.0);
    }
    factor[v] = vec2<f32>(f, 1.0);
}
