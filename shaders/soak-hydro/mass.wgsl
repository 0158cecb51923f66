// Mass-property sums per texel, reduced per work item (first pass).
//
// Composed after bindings.wgsl. Mirrors `volume_moments` and
// `shell` of mass.rs in f32 (positions relative to the atlas origin):
// dispatch.mode 0 is the solid (the ten divergence-theorem sums), 1 a shell
// of uniform areal density dispatch.param.x, 2 a shell with one areal density
// per texel (`densities`, indexed from item.body, the atlas-local index of
// item.start). Partial layout, SLOTS = 3 vec4s:
//   solid: (x.A, x²A_x/2, y²A_y/2, z²A_z/2), (x³A_x, y³A_y, z³A_z, x²yA_x/2), (y²zA_y/2, z²xA_z/2, 0, 0)
//   shell: (m, m x, m y, m z), (m x², m y², m z², m x y), (m y z, m z x, 0, 0)

const SLOTS: u32 = 3u;

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> items: array<Item>;
@group(0) @binding(2) var<storage, read> densities: array<f32>;
@group(0) @binding(3) var<storage, read_write> partials: array<vec4<f32>>;
@group(0) @binding(4) var<uniform> dispatch: Dispatch;

var<workgroup> scratch: array<vec4<f32>, 192>; // WG * SLOTS

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let index = flat_index(wg, dispatch);
    if (index >= dispatch.count) {
        return;
    }
    let item = items[dispatch.base + index];
    var acc0 = vec4<f32>(0.0);
    var acc1 = vec4<f32>(0.0);
    var acc2 = vec4<f32>(0.0);
    for (var k = 0u; k < PER_THREAD; k++) {
        let i = item.start + k * WG + lid;
        if (i >= item.end) {
            break;
        }
        let xw = texels[2u * i];
        let x = xw.xyz;
        let a = texels[2u * i + 1u].xyz;
        if (dispatch.mode == 0u) {
            acc0 += vec4<f32>(dot(x, a), 0.5 * x.x * x.x * a.x, 0.5 * x.y * x.y * a.y, 0.5 * x.z * x.z * a.z);
            acc1 += vec4<f32>(
                x.x * x.x * x.x * a.x,
                x.y * x.y * x.y * a.y,
                x.z * x.z * x.z * a.z,
                0.5 * x.x * x.x * x.y * a.x,
            );
            acc2 += vec4<f32>(0.5 * x.y * x.y * x.z * a.y, 0.5 * x.z * x.z * x.x * a.z, 0.0, 0.0);
        } else {
            var sigma = dispatch.param.x;
            if (dispatch.mode == 2u) {
                sigma = densities[item.body + (i - item.start)];
            }
            let m = sigma * xw.w;
            acc0 += vec4<f32>(m, m * x);
            acc1 += vec4<f32>(m * x * x, m * x.x * x.y);
            acc2 += vec4<f32>(m * x.y * x.z, m * x.z * x.x, 0.0, 0.0);
        }
    }
    scratch[lid * SLOTS] = acc0;
    scratch[lid * SLOTS + 1u] = acc1;
    scratch[lid * SLOTS + 2u] = acc2;
    for (var s = WG / 2u; s > 0u; s = s >> 1u) {
        workgroupBarrier();
        if (lid < s) {
            for (var j = 0u; j < SLOTS; j++) {
                scratch[lid * SLOTS + j] += scratch[(lid + s) * SLOTS + j];
            }
        }
    }
    workgroupBarrier();
    if (lid < SLOTS) {
        partials[item.partial * SLOTS + lid] = scratch[lid];
    }
}
