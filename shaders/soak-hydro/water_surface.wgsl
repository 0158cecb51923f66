// soak: water surfaces on the GPU, mirroring crates/soak-hydro/src/water.
//
// Needs bindings.wgsl and, in the including module, the bindings
// `waves: array<Wave>`, `heights: array<f32>` and `radii: array<u32>`.
// Points are `r = p - o_w` (world axes, relative to the body's atlas origin).
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
        case SURFACE_PATCH: {
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
// patch's sampled velocity; or the uniform current.
fn fluid_velocity(b: Body, r: vec3<f32>, sp: SurfacePoint) -> vec3<f32> {
    if (b.info.x == SURFACE_PATCH) {
        return patch_velocity(b, r);
    }
    if (b.info.x != SURFACE_GERSTNER) {
        return b.current.xyz;
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
