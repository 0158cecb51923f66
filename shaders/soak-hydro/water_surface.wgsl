// soak: water surfaces on the GPU, mirroring crates/soak-hydro/src/water.
//
// Needs bindings.wgsl and, in the including module, the bindings
// `waves: array<Wave>`, `heights: array<f32>` and `radii: array<u32>`.
// Points are `r = p - o_w` (world axes, relative to the body's atlas origin).
//
// A spectral sea read exactly (SURFACE_SPECTRAL) reads its tile's fields,
// evaluated on the device in the same submission (sea_modes.wgsl,
// sea_unpack.wgsl), and inverts its choppy map at every point as
// `SpectralSurface` does on the CPU.
//
// A Gerstner sea comes in two forms: its waves (SURFACE_GERSTNER), whose
// map is inverted here at every point, or sampled once on the CPU
// (SURFACE_PATCH, `SurfacePatch` of water/patch.rs): per cell the bicubic
// coefficients of its height and, with drag, the trilinear coefficients of
// the fluid's velocity, read from `heights`.

// Fixed-point inversion of the Gerstner displacement: the CPU's iteration
// count, and its relative tolerance scaled to f32 (the CPU uses 1e-10 in f64).
const GERSTNER_ITERATIONS: u32 = 32u;
const GERSTNER_TOLERANCE: f32 = 4.8e-7;

struct SurfacePoint {
    // Depth below the surface, m (positive under water).
    depth: f32,
    // Gerstner: rest position (x0, z0) of the surface particle above the
    // point, relative to o_w; unused otherwise.
    rest: vec2<f32>,
    // Patch: slope (dh/dx, dh/dz) read with the height; unused otherwise.
    slope: vec2<f32>,
}

// Horizontal displacement (x, z) and height (y) of the particle at rest
// position x0 (relative to o_w), summed over the body's waves.
fn gerstner_displacement(b: Body, x0: vec2<f32>) -> vec3<f32> {
    var d = vec3<f32>(0.0);
    for (var i = b.info.y; i < b.info.y + b.info.z; i++) {
        let w = waves[i];
        let th = w.a.z * dot(w.a.xy, x0) + w.b.z;
        let s = sin(th);
        let c = cos(th);
        d.x -= w.b.x * w.a.x * s;
        d.z -= w.b.x * w.a.y * s;
        d.y += w.b.y * c;
    }
    return d;
}

fn gerstner_rest(b: Body, x: vec2<f32>) -> vec2<f32> {
    var x0 = x;
    let world = abs(b.surface2.xy + x);
    let tolerance = GERSTNER_TOLERANCE * (1.0 + world.x + world.y);
    for (var it = 0u; it < GERSTNER_ITERATIONS; it++) {
        let d = gerstner_displacement(b, x0);
        let dx = x0.x + d.x - x.x;
        let dz = x0.y + d.z - x.y;
        x0.x -= dx;
        x0.y -= dz;
        if (abs(dx) + abs(dz) < tolerance) {
            break;
        }
    }
    return x0;
}

fn height_sample(b: Body, i: u32, j: u32) -> f32 {
    return heights[b.info.y + j * b.info.z + i];
}

// A row of a patch cell's coefficients at `at`, in v: the value
// sum_q a_pq v^q and its derivative in v.
fn patch_row(at: u32, v: f32) -> vec2<f32> {
    let a0 = heights[at];
    let a1 = heights[at + 1u];
    let a2 = heights[at + 2u];
    let a3 = heights[at + 3u];
    return vec2<f32>(((a3 * v + a2) * v + a1) * v + a0, (3.0 * a3 * v + 2.0 * a2) * v + a1);
}

// Height (relative to the patch's reference, m) and slope (dh/dx, dh/dz)
// of the patch above r, `SurfacePatch::height_slope`: the cell's bicubic
// at the fractions (u, v) across it, clamped to the patch's rectangle.
fn patch_height_slope(b: Body, r: vec3<f32>) -> vec3<f32> {
    let cx = b.info.z;
    let cz = b.info.w;
    let gx = clamp(b.surface.x + r.x * b.surface.z, 0.0, f32(cx));
    let gz = clamp(b.surface.y + r.z * b.surface.w, 0.0, f32(cz));
    let i = min(u32(gx), cx - 1u);
    let j = min(u32(gz), cz - 1u);
    let u = gx - f32(i);
    let v = gz - f32(j);
    let at = b.info.y + 16u * (j * cx + i);
    let c0 = patch_row(at, v);
    let c1 = patch_row(at + 4u, v);
    let c2 = patch_row(at + 8u, v);
    let c3 = patch_row(at + 12u, v);
    let h = ((c3.x * u + c2.x) * u + c1.x) * u + c0.x;
    let hu = (3.0 * c3.x * u + 2.0 * c2.x) * u + c1.x;
    let hv = ((c3.y * u + c2.y) * u + c1.y) * u + c0.y;
    return vec3<f32>(h, hu * b.surface.z, hv * b.surface.z);
}

// The cell along one axis of a patch's velocity grid and the fraction
// across it, clamped to the grid.
struct PatchAxis {
    cell: u32,
    f: f32,
}

fn patch_axis(q: f32, nodes: u32, cells: u32) -> PatchAxis {
    let f = clamp(q, 0.0, f32(nodes - 1u));
    let i = min(u32(f), cells - 1u);
    return PatchAxis(i, f - f32(i));
}

fn patch_coefficient(at: u32, k: u32) -> vec3<f32> {
    let m = at + 3u * k;
    return vec3<f32>(heights[m], heights[m + 1u], heights[m + 2u]);
}

// Fluid velocity at r (m/s) from a patch's velocity grid, its
// `velocity_at`: trilinear in the cell's coefficients, clamped to the
// grid; zero when the patch has no velocities.
fn patch_velocity(b: Body, r: vec3<f32>) -> vec3<f32> {
    let ny = b.slot.z;
    if (ny == 0u) {
        return vec3<f32>(0.0);
    }
    let cx = b.info.z;
    let cz = b.info.w;
    let x = patch_axis(b.surface.x + r.x * b.surface.z, cx + 1u, cx);
    let y = patch_axis(b.surface2.y + r.y * b.surface.z, ny, max(ny, 2u) - 1u);
    let z = patch_axis(b.surface.y + r.z * b.surface.w, cz + 1u, cz);
    let at = b.slot.y + 24u * ((y.cell * cz + z.cell) * cx + x.cell);
    let a = patch_coefficient(at, 0u) + x.f * patch_coefficient(at, 1u);
    let bb = patch_coefficient(at, 2u) + x.f * patch_coefficient(at, 4u);
    let e = patch_coefficient(at, 3u) + x.f * patch_coefficient(at, 5u);
    let d = patch_coefficient(at, 6u) + x.f * patch_coefficient(at, 7u);
    return y.f * (z.f * d + e) + (z.f * bb + a);
}

// ---- spectral sea (SURFACE_SPECTRAL): `SpectralSurface`'s exact read.
// info.y: first float of the tile's fields in `heights` (16 per node, see
// sea_unpack.wgsl); info.z: cells per side n; info.w: the node at or below
// o_w, (ix | iz << 16). surface.xy: o_w's place across that node's cell,
// [0, 1); surface.z: 1 / cell side (1/m); surface.w: cell side (m).
// surface2.x: mean level - o_w.y (m); surface2.y: the energy-weighted mean
// wavenumber (1/m) of the velocity's decay. Rest positions are in cells
// from that node, so f32 keeps its precision anywhere on the tile.

// Newton's method on the choppy map: the CPU's iteration count, and a
// tolerance in cells at f32's precision (the CPU's is 1e-12 relative in f64).
const SPECTRAL_ITERATIONS: u32 = 16u;
const SPECTRAL_TOLERANCE: f32 = 2e-6;

// The first float of node (i, j) of the tile, counted from o_w's node and
// wrapped into the tile.
fn spectral_node(b: Body, i: i32, j: i32) -> u32 {
    let n = i32(b.info.z);
    let x = ((i32(b.info.w & 0xffffu) + i) % n + n) % n;
    let z = ((i32(b.info.w >> 16u) + j) % n + n) % n;
    return b.info.y + 16u * u32(z * n + x);
}

// The cubic Hermite basis at t (value at 0, value at 1, slope at 0, slope
// at 1) and its derivative, `hermite_basis` of water/spectrum.rs.
fn hermite_value(t: f32) -> vec4<f32> {
    let t2 = t * t;
    let t3 = t2 * t;
    return vec4<f32>(2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2, t3 - 2.0 * t2 + t, t3 - t2);
}

fn hermite_slope(t: f32) -> vec4<f32> {
    let t2 = t * t;
    return vec4<f32>(6.0 * t2 - 6.0 * t, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
}

fn spectral_data(at: u32) -> vec4<f32> {
    return vec4<f32>(heights[at], heights[at + 1u], heights[at + 2u], heights[at + 3u]);
}

// The surface particle at rest at `a` (cells from o_w's node), the
// bicubic Hermite interpolants of the tile's fields (`SeaFields::particle_at`).
struct SpectralJet {
    // Where it is, cells from o_w's node.
    position: vec2<f32>,
    // Its elevation above the mean level, m.
    height: f32,
    // The Jacobian of its position over its rest position:
    // (∂x/∂x₀, ∂x/∂z₀, ∂z/∂x₀, ∂z/∂z₀).
    jacobian: vec4<f32>,
    // Its elevation's gradient over its rest position, m per cell.
    gradient: vec2<f32>,
}

fn spectral_jet(b: Body, a: vec2<f32>) -> SpectralJet {
    let c = floor(a);
    let f = a - c;
    let bu = hermite_value(f.x);
    let du = hermite_slope(f.x);
    let bv = hermite_value(f.y);
    let dv = hermite_slope(f.y);
    // Per field (η, Dx, Dz): value, u-derivative, v-derivative.
    var h = vec3<f32>(0.0);
    var dx = vec3<f32>(0.0);
    var dz = vec3<f32>(0.0);
    for (var corner = 0u; corner < 4u; corner++) {
        let ca = corner & 1u;
        let cb = corner >> 1u;
        let at = spectral_node(b, i32(c.x) + i32(ca), i32(c.y) + i32(cb));
        let w = vec4<f32>(bu[ca] * bv[cb], bu[ca + 2u] * bv[cb], bu[ca] * bv[cb + 2u], bu[ca + 2u] * bv[cb + 2u]);
        let wu = vec4<f32>(du[ca] * bv[cb], du[ca + 2u] * bv[cb], du[ca] * bv[cb + 2u], du[ca + 2u] * bv[cb + 2u]);
        let wv = vec4<f32>(bu[ca] * dv[cb], bu[ca + 2u] * dv[cb], bu[ca] * dv[cb + 2u], bu[ca + 2u] * dv[cb + 2u]);
        let fh = spectral_data(at);
        let fx = spectral_data(at + 4u);
        let fz = spectral_data(at + 8u);
        h += vec3<f32>(dot(fh, w), dot(fh, wu), dot(fh, wv));
        dx += vec3<f32>(dot(fx, w), dot(fx, wu), dot(fx, wv));
        dz += vec3<f32>(dot(fz, w), dot(fz, wu), dot(fz, wv));
    }
    return SpectralJet(
        a + vec2<f32>(dx.x, dz.x),
        h.x,
        vec4<f32>(1.0 + dx.y, dx.z, dz.y, 1.0 + dz.z),
        h.yz,
    );
}

// The particle above `x` (cells from o_w's node), by Newton's method from
// the guess that it is not displaced (`SeaFields::invert`).
fn spectral_invert(x: vec2<f32>, b: Body) -> SpectralJet {
    var a = x;
    var jet = spectral_jet(b, a);
    let tolerance = SPECTRAL_TOLERANCE * (1.0 + abs(x.x) + abs(x.y));
    for (var it = 0u; it < SPECTRAL_ITERATIONS; it++) {
        let r = jet.position - x;
        if (abs(r.x) + abs(r.y) < tolerance) {
            break;
        }
        let j = jet.jacobian;
        let det = j.x * j.w - j.y * j.z;
        var step = r;
        if (det > 1e-3) {
            step = vec2<f32>(j.w * r.x - j.y * r.y, j.x * r.y - j.z * r.x) / det;
        }
        a -= step;
        jet = spectral_jet(b, a);
    }
    return jet;
}

// The slope `J⁻ᵀ ∇₀η` of the surface over the particle (per m; flat where
// the map folds), `slope_through` of water/spectral_surface.rs.
fn spectral_slope(b: Body, jet: SpectralJet) -> vec2<f32> {
    let j = jet.jacobian;
    let det = j.x * j.w - j.y * j.z;
    if (abs(det) < 1e-12) {
        return vec2<f32>(0.0);
    }
    let g = jet.gradient * b.surface.z;
    return vec2<f32>(j.w * g.x - j.z * g.y, j.x * g.y - j.y * g.x) / det;
}

// The water's velocity at r (m/s), `SpectralSurface::velocity_at`: the
// tile's velocity at the mean level bilinear between the nodes at the
// point's own place, decaying below the mean level as e^(k̄ (y - level))
// and continued linearly above it up to the surface.
fn spectral_velocity(b: Body, r: vec3<f32>, depth: f32) -> vec3<f32> {
    let x = b.surface.xy + r.xz * b.surface.z;
    let c = floor(x);
    let f = x - c;
    var v = vec3<f32>(0.0);
    for (var corner = 0u; corner < 4u; corner++) {
        let ca = corner & 1u;
        let cb = corner >> 1u;
        let at = spectral_node(b, i32(c.x) + i32(ca), i32(c.y) + i32(cb)) + 12u;
        let w = select(1.0 - f.x, f.x, ca == 1u) * select(1.0 - f.y, f.y, cb == 1u);
        v += w * vec3<f32>(heights[at], heights[at + 1u], heights[at + 2u]);
    }
    let z = b.surface2.y * (min(r.y, r.y + depth) - b.surface2.x);
    var decay = 1.0 + z;
    if (z <= 0.0) {
        decay = exp(z);
    }
    return v * decay;
}

fn surface_at(b: Body, r: vec3<f32>) -> SurfacePoint {
    var out = SurfacePoint(0.0, vec2<f32>(0.0), vec2<f32>(0.0));
    switch b.info.x {
        case SURFACE_GERSTNER: {
            let x0 = gerstner_rest(b, r.xz);
            out.rest = x0;
            out.depth = b.surface.x + gerstner_displacement(b, x0).y - r.y;
        }
        case SURFACE_HEIGHT_FIELD: {
            let nx = b.info.z;
            let nz = b.info.w;
            let fx = clamp(b.surface.x + r.x * b.surface.z, 0.0, f32(nx - 1u));
            let fz = clamp(b.surface.y + r.z * b.surface.w, 0.0, f32(nz - 1u));
            let ix = min(u32(fx), nx - 2u);
            let iz = min(u32(fz), nz - 2u);
            let u = fx - f32(ix);
            let v = fz - f32(iz);
            let h = (1.0 - v) * ((1.0 - u) * height_sample(b, ix, iz) + u * height_sample(b, ix + 1u, iz))
                + v * ((1.0 - u) * height_sample(b, ix, iz + 1u) + u * height_sample(b, ix + 1u, iz + 1u));
            out.depth = b.surface2.x + h - r.y;
        }
        case SURFACE_PATCH: {
            let hs = patch_height_slope(b, r);
            out.slope = hs.yz;
            out.depth = b.surface2.x + hs.x - r.y;
        }
        case SURFACE_SPECTRAL: {
            let jet = spectral_invert(b.surface.xy + r.xz * b.surface.z, b);
            out.slope = spectral_slope(b, jet);
            out.depth = b.surface2.x + jet.height - r.y;
        }
        case SURFACE_UNBOUNDED: {
            // The CPU's trick: a horizontal plane 1 m above the bounding sphere.
            let radius = sqrt(bitcast<f32>(radii[b.slot.x]));
            out.depth = radius + 1.0 - r.y;
        }
        default: {
            out.depth = (b.surface.w - dot(b.surface.xyz, r)) / b.surface.y;
        }
    }
    return out;
}

// Slope (dh/dx, dh/dz) of the surface above r, the CPU's `Surface::slope`:
// for Gerstner waves J^-1 grad(y) at the particle's rest position (J the
// Jacobian of its horizontal position), for a height field the bilinear
// interpolant's (zero across an axis outside the grid), for a patch the
// one `surface_at` read, for a plane -(n.x, n.z)/n.y, and none for an
// unbounded medium.
fn surface_slope(b: Body, r: vec3<f32>, sp: SurfacePoint) -> vec2<f32> {
    switch b.info.x {
        case SURFACE_PATCH, SURFACE_SPECTRAL: {
            return sp.slope;
        }
        case SURFACE_GERSTNER: {
            var j = vec3<f32>(1.0, 0.0, 1.0); // xx, xz, zz
            var g = vec2<f32>(0.0);
            for (var i = b.info.y; i < b.info.y + b.info.z; i++) {
                let w = waves[i];
                let th = w.a.z * dot(w.a.xy, sp.rest) + w.b.z;
                let f = w.b.x * w.a.z * cos(th);
                j -= f * vec3<f32>(w.a.x * w.a.x, w.a.x * w.a.y, w.a.y * w.a.y);
                g -= w.b.y * w.a.z * sin(th) * w.a.xy;
            }
            let det = j.x * j.z - j.y * j.y;
            if (abs(det) < 1e-12) {
                return vec2<f32>(0.0);
            }
            return vec2<f32>(j.z * g.x - j.y * g.y, j.x * g.y - j.y * g.x) / det;
        }
        case SURFACE_HEIGHT_FIELD: {
            let nx = b.info.z;
            let nz = b.info.w;
            let gx = b.surface.x + r.x * b.surface.z;
            let gz = b.surface.y + r.z * b.surface.w;
            let fx = clamp(gx, 0.0, f32(nx - 1u));
            let fz = clamp(gz, 0.0, f32(nz - 1u));
            let ix = min(u32(fx), nx - 2u);
            let iz = min(u32(fz), nz - 2u);
            let u = fx - f32(ix);
            let v = fz - f32(iz);
            let h00 = height_sample(b, ix, iz);
            let h10 = height_sample(b, ix + 1u, iz);
            let h01 = height_sample(b, ix, iz + 1u);
            let h11 = height_sample(b, ix + 1u, iz + 1u);
            var s = vec2<f32>(0.0);
            if (gx >= 0.0 && gx <= f32(nx - 1u)) {
                s.x = ((1.0 - v) * (h10 - h00) + v * (h11 - h01)) * b.surface.z;
            }
            if (gz >= 0.0 && gz <= f32(nz - 1u)) {
                s.y = ((1.0 - u) * (h01 - h00) + u * (h11 - h10)) * b.surface.w;
            }
            return s;
        }
        case SURFACE_UNBOUNDED: {
            return vec2<f32>(0.0);
        }
        default: {
            return -b.surface.xz / b.surface.y;
        }
    }
}

// Fluid velocity at r (m/s), the CPU's `Surface::velocity`: for Gerstner
// waves linear theory's, a w e^(k (y - level)) along each wave (upward a
// quarter period ahead) at the point's own phase, continued linearly above
// the mean level up to the surface and the surface's above it; the
// patch's sampled velocity; or the current, uniform or changing linearly.
fn fluid_velocity(b: Body, r: vec3<f32>, sp: SurfacePoint) -> vec3<f32> {
    if (b.info.x == SURFACE_PATCH) {
        return patch_velocity(b, r);
    }
    if (b.info.x == SURFACE_SPECTRAL) {
        return spectral_velocity(b, r, sp.depth);
    }
    if (b.info.x != SURFACE_GERSTNER) {
        return b.current.xyz + vec3<f32>(dot(b.flow0.xyz, r), dot(b.flow1.xyz, r), dot(b.flow2.xyz, r));
    }
    let y = min(r.y, r.y + sp.depth) - b.surface.x;
    var v = vec3<f32>(0.0);
    for (var i = b.info.y; i < b.info.y + b.info.z; i++) {
        let w = waves[i];
        let th = w.a.z * dot(w.a.xy, r.xz) + w.b.z;
        let s = sin(th);
        let c = cos(th);
        let z = w.a.z * y;
        var decay = 1.0 + z;
        if (z <= 0.0) {
            decay = exp(z);
        }
        let speed = w.b.y * w.a.w * decay;
        v.x += speed * c * w.a.x;
        v.z += speed * c * w.a.y;
        v.y += speed * s;
    }
    return v;
}
