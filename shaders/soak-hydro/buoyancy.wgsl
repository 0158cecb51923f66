// Buoyancy and drag sums per texel, reduced per work item (first pass).
//
// Composed after bindings.wgsl and water_surface.wgsl.
// Mirrors `BuoyancySums::add_texel` and `DragSums::add_texel` of
// hydrostatics.rs in f32, with positions relative to the atlas origin. One
// work item (WG * PER_THREAD texels of one body) makes one partial of SLOTS
// vec4s:
//   0: vol, wr.xyz          1: wd2, f.xyz           2: rxf.xyz, area
//   3: count, Kvv00, Kvv01, Kvv02                   4: Kvv11, Kvv12, Kvv22, b0
//   5: b1, b2, b3, b4       6: b5, Kvw00, Kvw01, Kvw02
//   7: Kvw10, Kvw11, Kvw12, Kvw20                   8: Kvw21, Kvw22, Kww00, Kww01
//   9: Kww02, Kww11, Kww12, Kww22
//  10: d2a.xyz, ayr                              11: wrs.xyz, shallow
// (K = [[Kvv, Kvw], [Kvwᵀ, Kww]] is symmetric; d2a = Σ (d²/2) A and
// wrs = Σ w ρ × s are Archimedes' torque sums, `BuoyancySums::d2a` and
// `SlopeSums` of hydrostatics.rs, as are ayr = Σ A_y r_y and
// shallow = Σ ln min(d/δ, 1), δ the mean thickness (widened to g dt²)
// at most the bounding radius (`deep_scale` of hydrostatics/frame.rs;
// the body's drag.w, the radius where it is 0); those three only in
// Archimedes mode under a surface that is not a plane.)

const SLOTS: u32 = 12u;

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read> bodies: array<Body>;
@group(0) @binding(2) var<storage, read> items: array<Item>;
@group(0) @binding(3) var<storage, read> waves: array<Wave>;
@group(0) @binding(4) var<storage, read> heights: array<f32>;
@group(0) @binding(5) var<storage, read> radii: array<u32>;
@group(0) @binding(6) var<storage, read_write> partials: array<vec4<f32>>;
@group(0) @binding(7) var<uniform> dispatch: Dispatch;

var<workgroup> scratch: array<vec4<f32>, 768>; // WG * SLOTS

fn rotate(b: Body, x: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(b.rot0.xyz, x), dot(b.rot1.xyz, x), dot(b.rot2.xyz, x));
}

// The matrix [r]x with [r]x v = r x v.
fn skew(r: vec3<f32>) -> mat3x3<f32> {
    return mat3x3<f32>(
        vec3<f32>(0.0, r.z, -r.y),
        vec3<f32>(-r.z, 0.0, r.x),
        vec3<f32>(r.y, -r.x, 0.0),
    );
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let index = flat_index(wg, dispatch);
    if (index >= dispatch.count) {
        return;
    }
    let item = items[dispatch.base + index];
    let b = bodies[item.body];
    let drag_on = b.drag.y > 0.5;
    let rho = b.linear_velocity.w;
    let cd = b.angular_velocity.w;
    let linear = b.drag.x;
    var delta = sqrt(bitcast<f32>(radii[b.slot.x]));
    if (b.drag.w > 0.0) {
        delta = min(delta, b.drag.w);
    }

    // Twelve accumulators indexed by constants only, so compilers keep them in registers.
    var acc: array<vec4<f32>, 12>;
    for (var k = 0u; k < PER_THREAD; k++) {
        let i = item.start + k * WG + lid;
        if (i >= item.end) {
            break;
        }
        let xl = texels[2u * i];
        let r = rotate(b, xl.xyz);
        let sp = surface_at(b, r);
        let d = sp.depth;
        if (d > 0.0) {
            let a = rotate(b, texels[2u * i + 1u].xyz);
            let area = xl.w;
            let w = -a.y * d;
            let f = -d * a;
            acc[0] += vec4<f32>(w, w * r);
            acc[1] += vec4<f32>(0.5 * w * d, f);
            acc[2] += vec4<f32>(cross(r, f), area);
            acc[3].x += 1.0;
            acc[10] += vec4<f32>(0.5 * d * d * a, 0.0);
            if (b.drag.z > 0.5) {
                let s2 = surface_slope(b, r, sp);
                let rho = r - b.com.xyz;
                var shallow = 0.0;
                if (d < delta) {
                    shallow = log(d / delta);
                }
                acc[10].w += a.y * r.y;
                acc[11] += vec4<f32>(w * cross(rho, vec3<f32>(s2.x, 0.0, s2.y)), shallow);
            }
            if (drag_on) {
                let rc = r - b.com.xyz;
                let u = fluid_velocity(b, r, sp);
                let v = b.linear_velocity.xyz + cross(b.angular_velocity.xyz, rc) - u;
                let facing = dot(a, v);
                var kq = 0.0;
                if (facing > 0.0) {
                    kq = 0.5 * rho * cd * facing;
                }
                if (kq != 0.0 || linear > 0.0) {
                    var ki = mat3x3<f32>(
                        vec3<f32>(kq, 0.0, 0.0),
                        vec3<f32>(0.0, kq, 0.0),
                        vec3<f32>(0.0, 0.0, kq),
                    );
                    let wet = length(a);
                    if (linear > 0.0 && wet > 0.0) {
                        let n = a / wet;
                        let s = linear * wet;
                        ki += mat3x3<f32>(
                            s * (vec3<f32>(1.0, 0.0, 0.0) - n * n.x),
                            s * (vec3<f32>(0.0, 1.0, 0.0) - n * n.y),
                            s * (vec3<f32>(0.0, 0.0, 1.0) - n * n.z),
                        );
                    }
                    let sk = skew(rc);
                    // Element (row i, column j) of a WGSL matrix m is m[j][i].
                    let kvw = (ki * sk) * -1.0;
                    let kww = (sk * ki * sk) * -1.0;
                    let fu = ki * u;
                    let tu = cross(rc, fu);
                    acc[3] += vec4<f32>(0.0, ki[0][0], ki[1][0], ki[2][0]);
                    acc[4] += vec4<f32>(ki[1][1], ki[2][1], ki[2][2], fu.x);
                    acc[5] += vec4<f32>(fu.y, fu.z, tu.x, tu.y);
                    acc[6] += vec4<f32>(tu.z, kvw[0][0], kvw[1][0], kvw[2][0]);
                    acc[7] += vec4<f32>(kvw[0][1], kvw[1][1], kvw[2][1], kvw[0][2]);
                    acc[8] += vec4<f32>(kvw[1][2], kvw[2][2], kww[0][0], kww[1][0]);
                    acc[9] += vec4<f32>(kww[2][0], kww[1][1], kww[2][1], kww[2][2]);
                }
            }
        }
    }

    let at = lid * SLOTS;
    scratch[at] = acc[0];
    scratch[at + 1u] = acc[1];
    scratch[at + 2u] = acc[2];
    scratch[at + 3u] = acc[3];
    scratch[at + 4u] = acc[4];
    scratch[at + 5u] = acc[5];
    scratch[at + 6u] = acc[6];
    scratch[at + 7u] = acc[7];
    scratch[at + 8u] = acc[8];
    scratch[at + 9u] = acc[9];
    scratch[at + 10u] = acc[10];
    scratch[at + 11u] = acc[11];
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
