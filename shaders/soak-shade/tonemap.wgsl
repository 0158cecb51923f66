// soak-shade renderer: linear radiance to 8-bit sRGB (exposure, tone map,
// sRGB encoding, optional dither). `Post` mirrors `PostUniform`.

struct Post {
    // x exposure.
    exposure: vec4<f32>,
    // x 0 Khronos PBR Neutral, 1 linear; y dither.
    mode: vec4<u32>,
}

@group(0) @binding(0) var hdr: texture_2d<f32>;
@group(0) @binding(1) var<uniform> post: Post;

@vertex
fn vs_post(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

// Khronos PBR Neutral tone mapping (2024).
fn neutral(c_in: vec3<f32>) -> vec3<f32> {
    let start = 0.8 - 0.04;
    let desaturation = 0.15;
    var c = c_in;
    let x = min(c.r, min(c.g, c.b));
    var offset = 0.04;
    if (x < 0.08) {
        offset = x - 6.25 * x * x;
    }
    c -= vec3<f32>(offset);
    let peak = max(c.r, max(c.g, c.b));
    if (peak < start) {
        return c;
    }
    let d = 1.0 - start;
    let new_peak = 1.0 - d * d / (peak + d - start);
    c *= new_peak / peak;
    let g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(c, vec3<f32>(new_peak), g);
}

fn srgb_encode(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - vec3<f32>(0.055);
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

// Interleaved gradient noise in [0, 1) (Jimenez 2014).
fn ign(p: vec2<f32>) -> f32 {
    return fract(52.9829189 * fract(dot(p, vec2<f32>(0.06711056, 0.00583715))));
}

@fragment
fn fs_post(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let radiance = max(textureLoad(hdr, vec2<i32>(position.xy), 0).rgb, vec3<f32>(0.0));
    var c = radiance * post.exposure.x;
    if (post.mode.x == 0u) {
        c = neutral(c);
    }
    var e = srgb_encode(clamp(c, vec3<f32>(0.0), vec3<f32>(1.0)));
    if (post.mode.y == 1u) {
        e += vec3<f32>((ign(position.xy) - 0.5) / 255.0);
    }
    return vec4<f32>(clamp(e, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}
