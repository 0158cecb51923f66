// soak-shade renderer: the background (sky, ground or distant sea, and a
// sun disk) behind everything. Needs the optics library and frame.wgsl.

struct SkyOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

@vertex
fn vs_sky(@builtin(vertex_index) i: u32) -> SkyOut {
    var out: SkyOut;
    out.clip = fullscreen_position(i);
    out.ndc = out.clip.xy;
    return out;
}

@fragment
fn fs_sky(in: SkyOut) -> @location(0) vec4<f32> {
    let near = frame.inv_view_proj * vec4<f32>(in.ndc, 0.0, 1.0);
    let far = frame.inv_view_proj * vec4<f32>(in.ndc, 1.0, 1.0);
    let d = normalize(far.xyz / far.w - near.xyz / near.w);
    var radiance = environment_radiance(d);
    if (frame.view.x == 0u && d.y > 0.0) {
        // The sun: a disk of 0.6° with a glow.
        let c = dot(d, frame.sun_direction.xyz);
        let disk = smoothstep(0.99994, 0.99996, c) * 60.0;
        let glow = pow(max(c, 0.0), 600.0) * 0.6;
        radiance += frame.sun_irradiance.rgb * (disk + glow);
    }
    return vec4<f32>(radiance, 1.0);
}
