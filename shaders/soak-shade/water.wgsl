// soak-shade renderer: the water surface, Fresnel-shaded and
// semi-transparent (premultiplied alpha). Needs the optics library and
// frame.wgsl prepended. `Water` mirrors `WaterUniform`.

struct Water {
    // rgb scattering colour; w opacity at normal incidence.
    colour: vec4<f32>,
    // x F0, y GGX α of the glint, z fade start (m), w fade end (m).
    params: vec4<f32>,
    // xz centre of the drawn square.
    centre: vec4<f32>,
}

@group(1) @binding(0) var<uniform> water: Water;

struct WaterOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

@vertex
fn vs_water(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> WaterOut {
    var out: WaterOut;
    out.world = position;
    out.normal = normal;
    out.clip = frame.view_proj * vec4<f32>(position, 1.0);
    return out;
}

@fragment
fn fs_water(in: WaterOut) -> @location(0) vec4<f32> {
    let v = view_vector(in.world);
    var n = normalize(in.normal);
    if (dot(n, v) < 0.0) {
        // A wave face turned away from the eye: shade as if grazing.
        n = normalize(n - v * dot(n, v) * 1.001);
    }
    let nv = max(dot(n, v), 1e-4);
    let f0 = water.params.x;
    let f = schlick(nv, f0);
    let l = frame.sun_direction.xyz;
    let nl = max(dot(n, l), 0.0);
    let vis = sun_visibility(in.world, n);
    let reflected = environment_radiance(reflect(-v, n));
    let hv = normalize(l + v);
    let glint = film_specular(nl, nv, max(dot(n, hv), 0.0), max(dot(v, hv), 0.0), water.params.y, f0)
        * frame.sun_irradiance.rgb * (nl * vis);
    let body = water.colour.rgb * (frame.sun_irradiance.rgb * (nl * vis) + ambient_irradiance(n)) / PI;
    let opacity = water.colour.a;
    var radiance = f * reflected + glint + (1.0 - f) * opacity * body;
    var alpha = 1.0 - (1.0 - f) * (1.0 - opacity);
    // Towards the edge of the drawn square, fade into the distant sea of
    // the background.
    let t = smoothstep(water.params.z, water.params.w, length(in.world.xz - water.centre.xz));
    radiance = mix(radiance, environment_radiance(-v), t);
    alpha = mix(alpha, 1.0, t);
    return vec4<f32>(radiance, alpha);
}
