// Moves the texels with a deformed mesh, on the GPU: mirrors `Atlas::refresh`
// of soak-bake. Positions from the stored barycentrics, area vectors from the
// new triangle area over the triangle's texel count, and the bounding radius
// (its square's bits, atomically maxed into radii[dispatch.mode]).
//
// Composed after bindings.wgsl. Page layout: texels[2i] =
// (position - origin, |A|), texels[2i + 1] = (A, 0); tribary[i] =
// (bits of the triangle id, λ1, λ2, 0).

@group(0) @binding(0) var<storage, read_write> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> tribary: array<vec4<f32>>;
// Per triangle: vertex indices and the triangle's texel count.
@group(0) @binding(2) var<storage, read> triangles: array<vec4<u32>>;
// Vertex positions relative to the atlas origin, m.
@group(0) @binding(3) var<storage, read> vertices: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> radii: array<atomic<u32>>;
@group(0) @binding(5) var<storage, read> items: array<Item>;
@group(0) @binding(6) var<uniform> dispatch: Dispatch;

var<workgroup> largest: array<f32, WG>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let index = flat_index(wg, dispatch);
    if (index >= dispatch.count) {
        return;
    }
    let item = items[dispatch.base + index];
    var r2 = 0.0;
    for (var k = 0u; k < PER_THREAD; k++) {
        let i = item.start + k * WG + lid;
        if (i >= item.end) {
            break;
        }
        let tb = tribary[i];
        let t = triangles[bitcast<u32>(tb.x)];
        let p0 = vertices[t.x].xyz;
        let p1 = vertices[t.y].xyz;
        let p2 = vertices[t.z].xyz;
        let av = 0.5 * cross(p1 - p0, p2 - p0) / f32(max(t.w, 1u));
        let p = p0 * (1.0 - tb.y - tb.z) + p1 * tb.y + p2 * tb.z;
        texels[2u * i] = vec4<f32>(p, length(av));
        texels[2u * i + 1u] = vec4<f32>(av, 0.0);
        r2 = max(r2, dot(p, p));
    }
    largest[lid] = r2;
    for (var s = WG / 2u; s > 0u; s = s >> 1u) {
        workgroupBarrier();
        if (lid < s) {
            largest[lid] = max(largest[lid], largest[lid + s]);
        }
    }
    workgroupBarrier();
    if (lid == 0u) {
        // Non-negative floats order like their bits.
        atomicMax(&radii[dispatch.mode], bitcast<u32>(largest[0]));
    }
}
