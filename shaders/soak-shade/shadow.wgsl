// soak-shade renderer: depth of the meshes seen from the sun. Binds only the
// leading matrices of `Frame` and `Object` (the buffers are larger).

struct FrameMatrices {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    light_view_proj: mat4x4<f32>,
}

struct ObjectMatrix {
    model: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> frame: FrameMatrices;
@group(1) @binding(0) var<uniform> object: ObjectMatrix;

@vertex
fn vs_shadow(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.light_view_proj * (object.model * vec4<f32>(position, 1.0));
}
