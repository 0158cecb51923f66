// soak-shade renderer: solid arrows (forces) drawn over the scene. Needs
// frame.wgsl prepended.

struct ArrowOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec3<f32>,
}

@vertex
fn vs_arrow(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec3<f32>,
) -> ArrowOut {
    var out: ArrowOut;
    out.world = position;
    out.normal = normal;
    out.colour = colour;
    out.clip = frame.view_proj * vec4<f32>(position, 1.0);
    return out;
}

@fragment
fn fs_arrow(in: ArrowOut) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    let v = view_vector(in.world);
    // A headlight plus a little sun: readable in any lighting.
    let shade = 0.35 + 0.5 * max(dot(n, v), 0.0) + 0.25 * max(dot(n, frame.sun_direction.xyz), 0.0);
    return vec4<f32>(in.colour * shade, 1.0);
}
