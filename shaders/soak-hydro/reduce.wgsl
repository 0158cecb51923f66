// Second pass: sums each output's run of partials (one workgroup per
// output: a body of a batch, or an atlas for the mass properties).
//
// Composed after bindings.wgsl and a prelude that defines
// `const SLOTS: u32` (vec4s per partial) and `const COUNT_SLOT: u32` (the
// slot whose x holds a texel count, summed exactly in u32 and written as
// its bits; SLOTS when there is none).

@group(0) @binding(0) var<storage, read> partials: array<vec4<f32>>;
// Per output: first partial, number of partials.
@group(0) @binding(1) var<storage, read> ranges: array<vec2<u32>>;
@group(0) @binding(2) var<storage, read_write> results: array<vec4<f32>>;
@group(0) @binding(3) var<uniform> dispatch: Dispatch;

var<workgroup> scratch: array<vec4<f32>, WG * SLOTS>;
var<workgroup> counts: array<u32, WG>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let index = flat_index(wg, dispatch);
    if (index >= dispatch.count) {
        return;
    }
    let range = ranges[dispatch.base + index];
    var acc: array<vec4<f32>, SLOTS>;
    for (var j = 0u; j < SLOTS; j++) {
        acc[j] = vec4<f32>(0.0);
    }
    var n = 0u;
    for (var p = range.x + lid; p < range.x + range.y; p += WG) {
        for (var j = 0u; j < SLOTS; j++) {
            acc[j] += partials[p * SLOTS + j];
        }
        if (COUNT_SLOT < SLOTS) {
            n += u32(partials[p * SLOTS + COUNT_SLOT].x + 0.5);
        }
    }
    for (var j = 0u; j < SLOTS; j++) {
        scratch[lid * SLOTS + j] = acc[j];
    }
    counts[lid] = n;
    for (var s = WG / 2u; s > 0u; s = s >> 1u) {
        workgroupBarrier();
        if (lid < s) {
            for (var j = 0u; j < SLOTS; j++) {
                scratch[lid * SLOTS + j] += scratch[(lid + s) * SLOTS + j];
            }
            counts[lid] += counts[lid + s];
        }
    }
    workgroupBarrier();
    if (lid < SLOTS) {
        var v = scratch[lid];
        if (lid == COUNT_SLOT) {
            v.x = bitcast<f32>(counts[0]);
        }
        results[(dispatch.base + index) * SLOTS + lid] = v;
    }
}
