// Parity kernel: evaluates the WGSL optics library (prepended) on a table of
// inputs, as `soak_shade::evaluate_table` does on the CPU, plus an artist Γ
// curve at each row's saturation.

@group(0) @binding(0) var<storage, read> inputs: array<OpticsInput>;
@group(0) @binding(1) var<storage, read_write> outputs: array<OpticsOutput>;
@group(0) @binding(2) var<uniform> curve: ArtistCurveGpu;
@group(0) @binding(3) var<storage, read_write> artist: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x < arrayLength(&inputs)) {
        outputs[id.x] = evaluate_optics(inputs[id.x]);
        artist[id.x] = gamma_artist(inputs[id.x].saturation, curve);
    }
}
