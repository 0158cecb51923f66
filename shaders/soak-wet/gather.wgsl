// Texels to voxels: the liquid volume Σ a h (conservative) or the Shepard
// average of h (thesis, Eq. 5.9–5.10) of each defined voxel, in member
// order. Writes the value twice: the step's start and the substeps' input.

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> liquid: array<f32>;
@group(0) @binding(2) var<storage, read> start: array<u32>;
@group(0) @binding(3) var<storage, read> members: array<u32>;
@group(0) @binding(4) var<storage, read> cells: array<vec4<u32>>;
@group(0) @binding(5) var<storage, read_write> initial: array<f32>;
@group(0) @binding(6) var<storage, read_write> current: array<f32>;
@group(0) @binding(7) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let v = voxel_index(wg, lid);
    if (v >= params.info.w) {
        return;
    }
    var num = 0.0;
    var den = 0.0;
    let thesis = params.info2.y == MODE_THESIS;
    let centre = vec3<f32>(cells[v].xyz) + vec3<f32>(0.5);
    for (var k = start[v]; k < start[v + 1u]; k++) {
        let i = members[k];
        let t = texels[2u * i];
        if (thesis) {
            let g = t.xyz * params.grid.w + params.grid.xyz;
            let w = shepard(length(g - centre));
            num += w * liquid[i];
            den += w;
        } else {
            num += t.w * liquid[i];
        }
    }
    var value = num;
    if (thesis) {
        value = num / den;
    }
    initial[v] = value;
    current[v] = value;
}
