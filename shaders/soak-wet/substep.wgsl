// One application of the 3x3x3 kernel over the defined voxels (Eq. 5.12):
// thesis, on Shepard averages; conservative, in flux form on the fill
// fraction φ = M / C with pair weights min(C_v, C_u).

@group(0) @binding(0) var<storage, read> current: array<f32>;
@group(0) @binding(1) var<storage, read_write> next: array<f32>;
@group(0) @binding(2) var<storage, read> capacity: array<f32>;
@group(0) @binding(3) var<storage, read> nstart: array<u32>;
@group(0) @binding(4) var<storage, read> neighbours: array<u32>;
@group(0) @binding(5) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let v = voxel_index(wg, lid);
    if (v >= params.info.w) {
        return;
    }
    let w = params.step.w;
    let x = current[v];
    let first = nstart[v];
    let last = nstart[v + 1u];
    if (params.info2.y == MODE_THESIS) {
        var sum = 0.0;
        for (var k = first; k < last; k++) {
            sum += current[neighbours[k]];
        }
        next[v] = (1.0 - w * f32(last - first)) * x + w * sum;
    } else {
        let cv = capacity[v];
        let pv = x / cv;
        var flux = 0.0;
        for (var k = first; k < last; k++) {
            let u = neighbours[k];
            let cu = capacity[u];
            flux += min(cv, cu) * (current[u] / cu - pv);
        }
        next[v] = x + w * flux;
    }
}
