// soak-shade renderer: per-frame constants and the lighting helpers every
// pass shares (sky, environment irradiance, sun shadow). Mirrors
// `FrameUniform` field by field.

struct Frame {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    light_view_proj: mat4x4<f32>,
    // xyz eye; w = 1 for an orthographic camera.
    eye: vec4<f32>,
    forward: vec4<f32>,
    // Unit vector towards the sun.
    sun_direction: vec4<f32>,
    sun_irradiance: vec4<f32>,
    zenith: vec4<f32>,
    horizon: vec4<f32>,
    ground: vec4<f32>,
    sky_mean: vec4<f32>,
    // rgb water colour; w water F0 (0: no water).
    water: vec4<f32>,
    // x on, y texel size (UV), z normal offset (m), w depth bias.
    shadow: vec4<f32>,
    // x debug view: 0 shaded, 1 liquid, 2 segments, 3 normals.
    view: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var shadow_map: texture_depth_2d;
@group(0) @binding(2) var shadow_sampler: sampler_comparison;

const PI: f32 = 3.14159265358979;

// Radiance of the sky dome (above the horizon) in unit direction d.
fn sky_dome(d: vec3<f32>) -> vec3<f32> {
    return mix(frame.horizon.rgb, frame.zenith.rgb, sqrt(clamp(d.y, 0.0, 1.0)));
}

// Radiance arriving from unit direction d: the sky above the horizon; below
// it the ground, or, with water in the scene, a distant flat sea (Fresnel
// reflection of the sky over the water's body colour).
fn environment_radiance(d: vec3<f32>) -> vec3<f32> {
    if (d.y >= 0.0) {
        return sky_dome(d);
    }
    if (frame.water.w > 0.0) {
        let f = schlick(-d.y, frame.water.w);
        let body = frame.water.rgb * (frame.sun_irradiance.rgb * max(frame.sun_direction.y, 0.0)
            + PI * frame.sky_mean.rgb) / PI;
        return f * sky_dome(vec3<f32>(d.x, -d.y, d.z)) + (1.0 - f) * body;
    }
    return mix(frame.horizon.rgb, frame.ground.rgb, clamp(-d.y * 12.0, 0.0, 1.0));
}

// Irradiance from the environment on a surface with unit normal n: sky
// (cosine-weighted mean) above, ground below, by view factor.
fn ambient_irradiance(n: vec3<f32>) -> vec3<f32> {
    return PI * mix(frame.ground.rgb, frame.sky_mean.rgb, 0.5 + 0.5 * n.y);
}

// Unit vector from world point p towards the eye.
fn view_vector(p: vec3<f32>) -> vec3<f32> {
    if (frame.eye.w > 0.5) {
        return -frame.forward.xyz;
    }
    return normalize(frame.eye.xyz - p);
}

// Fraction of the sun reaching world point p with unit normal n: 3×3
// percentage-closer filtering of the shadow map.
fn sun_visibility(p: vec3<f32>, n: vec3<f32>) -> f32 {
    if (frame.shadow.x < 0.5) {
        return 1.0;
    }
    let q = p + n * frame.shadow.z;
    let c = frame.light_view_proj * vec4<f32>(q, 1.0);
    let ndc = c.xyz / c.w;
    let uv = vec2<f32>(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y);
    if (any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || ndc.z > 1.0 || ndc.z < 0.0) {
        return 1.0;
    }
    let depth = ndc.z - frame.shadow.w;
    var sum = 0.0;
    for (var j = -1; j <= 1; j++) {
        for (var i = -1; i <= 1; i++) {
            let o = vec2<f32>(f32(i), f32(j)) * frame.shadow.y;
            sum += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + o, depth);
        }
    }
    return sum / 9.0;
}

// A full-screen triangle: vertex i of 3.
fn fullscreen_position(i: u32) -> vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}
