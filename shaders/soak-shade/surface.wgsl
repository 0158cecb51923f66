// soak-shade renderer: wetting meshes. The dry/wet blend
// (1 − Γ(h))·dry + Γ(h)·wet of a Lambertian dry surface and the
// Lekner–Dorf wet surface with its liquid-film specular lobe, under a sun
// and an environment. Needs the optics library and frame.wgsl prepended.
// `Object` mirrors `ObjectUniform`.

struct Object {
    model: mat4x4<f32>,
    // Linear albedo (times the texture).
    albedo: vec4<f32>,
    // rgb σ per pass; w refractive index.
    transmittance: vec4<f32>,
    // x R̄(n), y p(n), z F0, w film GGX α.
    optics: vec4<f32>,
    // x Γ parameter, y mean world area of a subsurface texel (m²).
    gamma: vec4<f32>,
    // x Γ kind (4: artist curve), y albedo texture, z liquid, w subsurface.
    flags: vec4<u32>,
    curve: ArtistCurveGpu,
}

@group(1) @binding(0) var<uniform> object: Object;
@group(1) @binding(1) var albedo_texture: texture_2d<f32>;
@group(1) @binding(2) var liquid_texture: texture_2d<f32>;
@group(1) @binding(3) var subsurface_texture: texture_2d<f32>;
@group(1) @binding(4) var linear_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) face: u32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) @interpolate(flat) face: u32,
}

fn transform(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    let world = object.model * vec4<f32>(v.position, 1.0);
    out.world = world.xyz;
    out.normal = (object.model * vec4<f32>(v.normal, 0.0)).xyz;
    out.uv = v.uv;
    out.face = v.face;
    out.clip = frame.view_proj * world;
    return out;
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return transform(v);
}

// The same surface laid out in its UV square (row 0 = v 0 at the top), for
// the texture-space irradiance of the subsurface term.
@vertex
fn vs_texture_space(v: VertexIn) -> VertexOut {
    var out = transform(v);
    out.clip = vec4<f32>(v.uv.x * 2.0 - 1.0, 1.0 - v.uv.y * 2.0, 0.5, 1.0);
    return out;
}

fn wet_weight(h: f32) -> f32 {
    if (object.flags.x == 4u) {
        return gamma_artist(h, object.curve);
    }
    return gamma_eval(object.flags.x, object.gamma.x, h);
}

// Google's Turbo colour map (polynomial fit), returned in linear RGB.
fn turbo(x_in: f32) -> vec3<f32> {
    let x = clamp(x_in, 0.0, 1.0);
    let v4 = vec4<f32>(1.0, x, x * x, x * x * x);
    let v2 = v4.zw * v4.z;
    let c = vec3<f32>(
        dot(v4, vec4<f32>(0.13572138, 4.61539260, -42.66032258, 132.13108234))
            + dot(v2, vec2<f32>(-152.94239396, 59.28637943)),
        dot(v4, vec4<f32>(0.09140261, 2.19418839, 4.84296658, -14.18503333))
            + dot(v2, vec2<f32>(4.27729857, 2.82956604)),
        dot(v4, vec4<f32>(0.10667330, 12.64194608, -60.58204836, 110.36276771))
            + dot(v2, vec2<f32>(-89.90310912, 27.34824973)),
    );
    return pow(clamp(c, vec3<f32>(0.0), vec3<f32>(1.0)), vec3<f32>(2.2));
}

// A distinct, stable colour per id, linear RGB: hues step by the golden
// ratio (consecutive ids far apart), saturation and value alternate.
fn id_colour(id: u32) -> vec3<f32> {
    let hue = fract(f32(id % 4096u) * 0.618033988749 + 0.07);
    let k = fract(vec3<f32>(hue) + vec3<f32>(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0;
    let rgb = clamp(abs(k - vec3<f32>(3.0)) - vec3<f32>(1.0), vec3<f32>(0.0), vec3<f32>(1.0));
    let saturation = select(0.55, 0.85, (id & 1u) == 0u);
    let value = select(0.7, 0.95, ((id >> 1u) & 1u) == 0u);
    return pow(mix(vec3<f32>(1.0), rgb, saturation) * value, vec3<f32>(2.2));
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = normalize(in.normal);
    if (!front) {
        n = -n;
    }
    let texel = textureSample(albedo_texture, linear_sampler, in.uv).rgb;
    let h = clamp(textureSample(liquid_texture, linear_sampler, in.uv).r, 0.0, 1.0);
    let subsurface = textureSample(subsurface_texture, linear_sampler, in.uv);
    let v = view_vector(in.world);
    let nv = max(dot(n, v), 0.0);

    switch frame.view.x {
        case 1u: {
            // Dry is the blue end, saturated the red end (not Turbo's dark tips).
            return vec4<f32>(turbo(0.1 + 0.85 * h) * (0.4 + 0.6 * nv), 1.0);
        }
        case 2u: {
            return vec4<f32>(id_colour(in.face) * (0.4 + 0.6 * nv), 1.0);
        }
        case 3u: {
            return vec4<f32>(pow(0.5 + 0.5 * n, vec3<f32>(2.2)), 1.0);
        }
        default: {}
    }

    let dry = clamp(object.albedo.rgb * texel, vec3<f32>(0.0), vec3<f32>(1.0));
    let g = wet_weight(h);
    let l = frame.sun_direction.xyz;
    let nl = max(dot(n, l), 0.0);
    let e_sun = frame.sun_irradiance.rgb * (nl * sun_visibility(in.world, n));
    let e_env = ambient_irradiance(n);

    let sigma = object.transmittance.rgb;
    let r_mean = object.optics.x;
    let p = object.optics.y;
    let f0 = object.optics.z;

    // Dry: Lambertian.
    let dry_radiance = dry * (e_sun + e_env) / PI;

    // Wet: Lekner–Dorf albedo (R_spec by Schlick for the sun, R̄ for the
    // diffuse environment), or the blurred transmitted irradiance of the
    // subsurface term, plus the smooth film's specular lobe and its
    // reflection of the environment.
    var wet_diffuse = (wet_albedo(dry, sigma, schlick(nl, f0), p) * e_sun
        + wet_albedo(dry, sigma, r_mean, p) * e_env) / PI;
    if (object.flags.w == 1u && subsurface.a > 1e-3) {
        wet_diffuse = wet_albedo(dry, sigma, 0.0, p) * (subsurface.rgb / subsurface.a) / PI;
    }
    let hv = normalize(l + v);
    let lobe = film_specular(nl, nv, max(dot(n, hv), 0.0), max(dot(v, hv), 0.0), object.optics.w, f0);
    let mirror = schlick(nv, f0) * environment_radiance(reflect(-v, n));
    let wet_radiance = wet_diffuse + lobe * e_sun + mirror;

    return vec4<f32>(blend(dry_radiance, wet_radiance, g), 1.0);
}

// Transmitted irradiance (1 − R_spec)·E in the UV square, premultiplied by
// the texel's world area relative to the mean: (w·E, w).
@fragment
fn fs_irradiance(in: VertexOut) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    let l = frame.sun_direction.xyz;
    let nl = max(dot(n, l), 0.0);
    let e_sun = frame.sun_irradiance.rgb * (nl * sun_visibility(in.world, n));
    let e_env = ambient_irradiance(n);
    let e_t = (1.0 - schlick(nl, object.optics.z)) * e_sun + (1.0 - object.optics.x) * e_env;
    let area = length(cross(dpdx(in.world), dpdy(in.world)));
    let w = area / max(object.gamma.y, 1e-30);
    return vec4<f32>(e_t * w, w);
}

// An open container's caps: into the depth buffer only (the pipeline writes
// no colour), so the sea is hidden inside the container.
@fragment
fn fs_mask() -> @location(0) vec4<f32> {
    return vec4<f32>(0.0);
}
