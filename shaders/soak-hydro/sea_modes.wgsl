// A spectral sea's tile on the GPU, first half: from each mode's amplitude
// turned to the time (`A e^{-iωt}`, turned on the CPU in f64) the seven
// layers of coefficients whose inverse transforms are the tile's fields,
// two real fields per layer (`hermitian_pair` and `SpectralSea::fields` of
// water/spectrum.rs):
//
//   0: elevation, vertical velocity     4: ∂Dx/∂z, ∂²η/∂x∂z
//   1: displacement x, z                5: ∂²Dx/∂x∂z, ∂²Dz/∂x∂z
//   2: ∂η/∂x, ∂η/∂z                     6: horizontal velocity x, z
//   3: ∂Dx/∂x, ∂Dz/∂z
//
// Layer L of node k holds `F + i G` with `F = ½ (f(m) + conj f(o))`, `G` the
// same of `g`, `m` the mode at k and `o` the one opposite it. After sea.wgsl.

@group(0) @binding(0) var<storage, read> modes: array<vec2<f32>>;
@group(0) @binding(1) var<storage, read_write> spec: array<vec2<f32>>;
@group(0) @binding(2) var<uniform> sea: Sea;

const LAYERS: u32 = 7u;

fn signed_index(i: u32, n: u32) -> f32 {
    if (i < n / 2u) {
        return f32(i);
    }
    return f32(i) - f32(n);
}

fn mul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn conj(a: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x, -a.y);
}

// The factors f and g of layer `layer` for the mode of wavenumber k (its
// amplitude multiplies both), as complex numbers (x real, y imaginary).
struct Factors {
    f: vec2<f32>,
    g: vec2<f32>,
}

fn factors(layer: u32, k: vec2<f32>) -> Factors {
    let kk = length(k);
    if (kk == 0.0) {
        return Factors(vec2<f32>(0.0), vec2<f32>(0.0));
    }
    let u = k / kk;
    let omega = sqrt(sea.gravity * kk);
    let l = sea.lambda;
    switch layer {
        case 0u: {
            return Factors(vec2<f32>(1.0, 0.0), vec2<f32>(0.0, -omega));
        }
        case 1u: {
            return Factors(vec2<f32>(0.0, l * u.x), vec2<f32>(0.0, l * u.y));
        }
        case 2u: {
            return Factors(vec2<f32>(0.0, k.x), vec2<f32>(0.0, k.y));
        }
        case 3u: {
            return Factors(vec2<f32>(-l * u.x * k.x, 0.0), vec2<f32>(-l * u.y * k.y, 0.0));
        }
        case 4u: {
            return Factors(vec2<f32>(-l * u.x * k.y, 0.0), vec2<f32>(-k.x * k.y, 0.0));
        }
        case 5u: {
            return Factors(vec2<f32>(0.0, -l * u.x * k.x * k.y), vec2<f32>(0.0, -l * u.y * k.x * k.y));
        }
        default: {
            return Factors(vec2<f32>(omega * u.x, 0.0), vec2<f32>(omega * u.y, 0.0));
        }
    }
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * 64u;
    let n = sea.n;
    let nn = n * n;
    if (t >= nn) {
        return;
    }
    let lx = t % n;
    let lz = t / n;
    let ox = (n - lx) % n;
    let oz = (n - lz) % n;
    let km = vec2<f32>(signed_index(lx, n), signed_index(lz, n)) * sea.dk;
    let ko = vec2<f32>(signed_index(ox, n), signed_index(oz, n)) * sea.dk;
    let am = modes[sea.modes_first + t];
    let ao = modes[sea.modes_first + oz * n + ox];
    for (var layer = 0u; layer < LAYERS; layer++) {
        let m = factors(layer, km);
        let o = factors(layer, ko);
        let a = 0.5 * (mul(m.f, am) + conj(mul(o.f, ao)));
        let b = 0.5 * (mul(m.g, am) + conj(mul(o.g, ao)));
        // a + i b
        spec[layer * nn + t] = vec2<f32>(a.x - b.y, a.y + b.x);
    }
}
