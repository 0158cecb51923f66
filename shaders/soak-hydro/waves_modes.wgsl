// The interactive waves' per-mode rotation (see `GpuWaves`): every mode of
// wavenumber k turns at ω = √(g k) about the depression −P/g the pressure
// holds over the step, exactly; the mean (k = 0) takes the pressure's push.

struct Modes {
    n: u32,
    _pad0: u32,
    // 2π / side, rad/m.
    base: f32,
    g: f32,
    dt: f32,
    _pad1: f32,
    _pad2: f32,
    _pad3: f32,
}

@group(0) @binding(0) var<storage, read_write> spec: array<vec2<f32>>;
@group(0) @binding(1) var<uniform> md: Modes;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.x + gid.y * groups.x * 64u;
    let nn = md.n * md.n;
    if (i >= nn) {
        return;
    }
    let half = md.n / 2u;
    let ix = i % md.n;
    let iz = i / md.n;
    let sx = select(f32(ix), f32(ix) - f32(md.n), ix >= half);
    let sz = select(f32(iz), f32(iz) - f32(md.n), iz >= half);
    let k = md.base * sqrt(sx * sx + sz * sz);
    let h = spec[i];
    let phi = spec[nn + i];
    let p = spec[2u * nn + i];
    if (k == 0.0) {
        spec[nn + i] = phi - (h * md.g + p) * md.dt;
        return;
    }
    let omega = sqrt(md.g * k);
    let c = cos(omega * md.dt);
    let s = sin(omega * md.dt);
    let rest = h + p / md.g;
    spec[i] = rest * c + phi * (k / omega * s) - p / md.g;
    spec[nn + i] = phi * c - rest * (md.g / omega * s);
}
