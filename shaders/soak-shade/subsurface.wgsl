// soak-shade renderer: texture-space subsurface scattering (d'Eon et al.
// 2007): the transmitted irradiance (w·E, w), w the texel's world area over
// the mean, blurred by a sum of Gaussians in world units. Each Gaussian is
// two separable passes: pass 0 sums along u; pass 1 sums along v, divides
// by the summed area and adds weight·E (and 1/K coverage) to the result.
// `Blur` mirrors `BlurUniform`.

struct Blur {
    // xy texel step, z σ in m, w mean texel area in m².
    direction: vec4<f32>,
    // rgb weight of this Gaussian; w 1/K.
    weight: vec4<f32>,
    // x pass (0 or 1).
    mode: vec4<u32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var irradiance: texture_2d<f32>;
@group(0) @binding(2) var<uniform> blur: Blur;

// Taps on each side, at most.
const MAX_TAPS: i32 = 24;

@vertex
fn vs_blur(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_blur(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let size = vec2<i32>(textureDimensions(source));
    let x = vec2<i32>(position.xy);
    let own = textureLoad(irradiance, x, 0);
    let mean_area = blur.direction.w;
    // The texel's side in metres sets the kernel's width in texels.
    var side = sqrt(mean_area);
    if (own.a > 0.0) {
        side = sqrt(own.a * mean_area);
    }
    let sigma = blur.direction.z / max(side, 1e-12);
    let step_dir = vec2<i32>(blur.direction.xy);
    var sum = vec4<f32>(0.0);
    if (sigma < 0.2) {
        sum = textureLoad(source, x, 0);
    } else {
        let radius = i32(ceil(3.0 * sigma));
        let stride = max(1, (radius + MAX_TAPS - 1) / MAX_TAPS);
        for (var k = -radius; k <= radius; k += stride) {
            let q = x + step_dir * k;
            if (all(q >= vec2<i32>(0)) && all(q < size)) {
                let t = f32(k) / sigma;
                sum += exp(-0.5 * t * t) * textureLoad(source, q, 0);
            }
        }
    }
    if (blur.mode.x == 0u) {
        return sum;
    }
    if (own.a <= 0.0 || sum.a <= 0.0) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(blur.weight.rgb * (sum.rgb / sum.a), blur.weight.w);
}
