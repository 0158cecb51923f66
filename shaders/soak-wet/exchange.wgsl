// Absorption, rain and evaporation per texel: `exchange` of
// crates/soak-wet/src/exchange.rs in f32, positions relative to the atlas
// origin in world axes (r = R x).

@group(0) @binding(0) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> liquid: array<f32>;
@group(0) @binding(2) var<storage, read> permeability: array<f32>;
@group(0) @binding(3) var<storage, read> bodies: array<Body>;
@group(0) @binding(4) var<storage, read> waves: array<Wave>;
@group(0) @binding(5) var<storage, read> heights: array<f32>;
@group(0) @binding(6) var<storage, read> radii: array<u32>;
@group(0) @binding(7) var<uniform> params: Params;

fn rotate(b: Body, x: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(b.rot0.xyz, x), dot(b.rot1.xyz, x), dot(b.rot2.xyz, x));
}

fn in_rain(r: vec3<f32>) -> bool {
    switch params.info.z {
        case REGION_DISC: {
            let d = r.xz - params.region.xy;
            return dot(d, d) <= params.region.z;
        }
        case REGION_BOX: {
            return all(r >= params.region.xyz) && all(r <= params.region2.xyz);
        }
        default: {
            return true;
        }
    }
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let i = texel_index(wg, lid);
    if (i >= params.info.x) {
        return;
    }
    let b = bodies[0];
    let t0 = texels[2u * i];
    let r = rotate(b, t0.xyz);
    let a = t0.w;
    let hmax = params.rates.w;
    let dt = params.step.x;
    var h = liquid[i];
    var depth = -1.0;
    if ((params.info.y & FLAG_WET_POSSIBLE) != 0u && r.y <= params.step.z) {
        if (r.y < params.step.y && h >= hmax) {
            depth = params.step.y - r.y;
        } else {
            depth = surface_at(b, r).depth;
        }
    }
    let scale = permeability[i];
    if (depth > 0.0) {
        let gain = params.rates.x * scale * depth * dt;
        if (gain > 0.0 && h < hmax) {
            h = min(h + gain, hmax);
        }
    } else {
        if ((params.info.y & FLAG_RAINING) != 0u && a > 0.0) {
            let up = rotate(b, texels[2u * i + 1u].xyz).y / a;
            if (up > 0.0 && in_rain(r)) {
                let gain = params.rates.z * up * dt;
                if (gain > 0.0 && h < hmax) {
                    h = min(h + gain, hmax);
                }
            }
        }
        let loss = params.rates.y * scale * dt;
        if (loss > 0.0 && h > 0.0) {
            h = h - min(loss, h);
        }
    }
    liquid[i] = h;
}
