// The interactive waves' step on the GPU (see `GpuWaves`): a radix-2
// Stockham FFT stage, the exact per-mode rotation, and the finish (scale,
// sponge, real parts out). The spectrum buffer holds three layers of n²
// complex values: the elevation, the potential and the pressure.

struct Stage {
    n: u32,
    // Half the span of this stage's butterflies (1, 2, 4, …, n/2).
    p: u32,
    // Element stride between lines and along a line (rows: n, 1; columns: 1, n).
    line_stride: u32,
    pos_stride: u32,
    // −1 forward, +1 inverse.
    sign: f32,
    layers: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<storage, read> src: array<vec2<f32>>;
@group(0) @binding(1) var<storage, read_write> dst: array<vec2<f32>>;
@group(0) @binding(2) var<uniform> st: Stage;

const PI: f32 = 3.14159265358979;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * 64u;
    let half = st.n / 2u;
    let per_layer = st.n * half;
    if (t >= st.layers * per_layer) {
        return;
    }
    let layer = t / per_layer;
    let rem = t % per_layer;
    let line = rem / half;
    let i = rem % half;
    let base = layer * st.n * st.n + line * st.line_stride;
    let k = i & (st.p - 1u);
    let u0 = src[base + i * st.pos_stride];
    let u1 = src[base + (i + half) * st.pos_stride];
    let angle = st.sign * PI * f32(k) / f32(st.p);
    let w = vec2<f32>(cos(angle), sin(angle));
    let v = vec2<f32>(u1.x * w.x - u1.y * w.y, u1.x * w.y + u1.y * w.x);
    let j = 2u * i - k;
    dst[base + j * st.pos_stride] = u0 + v;
    dst[base + (j + st.p) * st.pos_stride] = u0 - v;
}
