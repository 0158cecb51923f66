// The interactive waves' finish (see `GpuWaves`): the inverse transform's
// real parts scaled by 1/n², the sponge's decay along the border, the
// elevation and potential back as real layers (zero imaginary parts) for
// the next step, and the elevation alone for reading back.

struct Finish {
    n: u32,
    // Sponge width, cells (0: none).
    sponge: u32,
    // The sponge's deepest decay rate, 1/s.
    rate: f32,
    dt: f32,
}

@group(0) @binding(0) var<storage, read_write> spec: array<vec2<f32>>;
@group(0) @binding(1) var<storage, read_write> heights: array<f32>;
@group(0) @binding(2) var<uniform> fin: Finish;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.x + gid.y * groups.x * 64u;
    let nn = fin.n * fin.n;
    if (i >= nn) {
        return;
    }
    let ix = i % fin.n;
    let iz = i / fin.n;
    let edge = min(min(ix, iz), min(fin.n - 1u - ix, fin.n - 1u - iz));
    var factor = 1.0 / f32(nn);
    if (edge < fin.sponge) {
        let depth = f32(fin.sponge - edge) / f32(fin.sponge);
        factor = factor * exp(-fin.rate * depth * depth * fin.dt);
    }
    let h = spec[i].x * factor;
    let phi = spec[nn + i].x * factor;
    spec[i] = vec2<f32>(h, 0.0);
    spec[nn + i] = vec2<f32>(phi, 0.0);
    heights[i] = h;
}
