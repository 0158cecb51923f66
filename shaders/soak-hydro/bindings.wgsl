// soak: buffer layouts of the hydrostatics kernels (soak-hydro's `gpu` feature).
//
// Every struct mirrors a `#[repr(C)]` bytemuck struct in
// crates/soak-hydro/src/gpu/layout.rs field by field. Only vec4 and scalar
// u32 fields, in multiples of 16 bytes, so WGSL's alignment rules (vec3 has
// 16-byte alignment) never insert hidden padding.

const SURFACE_PLANE: u32 = 0u;
const SURFACE_GERSTNER: u32 = 1u;
const SURFACE_HEIGHT_FIELD: u32 = 2u;
const SURFACE_UNBOUNDED: u32 = 3u;
const SURFACE_PATCH: u32 = 4u;
const SURFACE_SPECTRAL: u32 = 5u;

// Invocations per workgroup and texels per invocation of the per-texel
// kernels: one work item is WG * PER_THREAD consecutive texels.
const WG: u32 = 64u;
const PER_THREAD: u32 = 64u;

// One body of a batch. Positions are relative to the body's atlas origin in
// world axes (`r = R x`), so f32 keeps its precision at any distance from the
// world origin.
struct Body {
    // Rows of the rotation object -> world (w unused).
    rot0: vec4<f32>,
    rot1: vec4<f32>,
    rot2: vec4<f32>,
    // Plane / unbounded: unit normal xyz, w = offset - n.o_w (m).
    // Gerstner: x = mean level - o_w.y (m). Height field and sampled
    // surface (patch): x, y = grid coordinates (x, z) of o_w, z, w =
    // 1/spacing (1/m).
    surface: vec4<f32>,
    // Gerstner: x, y = world x, z of o_w (m, for the convergence test).
    // Height field and patch: x = reference height - o_w.y (m); patch: y =
    // the velocity grid's coordinate along y of o_w.
    surface2: vec4<f32>,
    // Fluid velocity (plane, height field, unbounded), m/s, at o_w where
    // it changes linearly (flow0..flow2).
    current: vec4<f32>,
    // Centre of mass - o_w, world axes, m.
    com: vec4<f32>,
    // xyz: velocity of the centre of mass (m/s); w: fluid density (kg/m^3).
    linear_velocity: vec4<f32>,
    // xyz: angular velocity (rad/s); w: quadratic drag coefficient.
    angular_velocity: vec4<f32>,
    // x: linear skin friction (N s/m per m^2); y: 1 when drag is wanted;
    // z: 1 when Archimedes' slope sum is wanted (a surface that is not a plane);
    // w: the atlas' mean thickness 3V/A (m, 0 where it encloses no volume).
    drag: vec4<f32>,
    // x: surface kind; y: first wave / first height sample / first patch
    // coefficient; z: wave count / samples along x / patch cells along x;
    // w: samples / patch cells along z.
    info: vec4<u32>,
    // x: atlas slot (bounding radius for the unbounded medium). Patch: y =
    // first velocity coefficient, z = velocity nodes along y (0: none).
    slot: vec4<u32>,
    // Rows of the current's gradient du_i/dp_j (1/s, world axes): the fluid
    // moves at current + G r at r from o_w (zero but under a FlowPlane).
    flow0: vec4<f32>,
    flow1: vec4<f32>,
    flow2: vec4<f32>,
}

// One Gerstner wave, with its phase at the body's origin and time folded in.
struct Wave {
    // direction x, direction z, wavenumber k (1/m), angular frequency (rad/s)
    a: vec4<f32>,
    // Q A (m), amplitude (m), phase k d.o_w - w t + phase (rad), unused
    b: vec4<f32>,
}

// A run of at most WG * PER_THREAD consecutive texels of one page.
struct Item {
    // Body index (hydrostatics), atlas-local index of `start` (mass), unused
    // (deformation).
    body: u32,
    start: u32,
    end: u32,
    // Where this item's partial sums go.
    partial: u32,
}

// Per-dispatch constants (uniform, dynamic offset).
struct Dispatch {
    // First item (or output) of this dispatch and how many.
    base: u32,
    count: u32,
    // Workgroups along x: the flat index is y * groups_x + x.
    groups_x: u32,
    // Kernel-specific: mass model (mass) or atlas slot (deformation).
    mode: u32,
    // Kernel-specific: x = uniform areal density (mass).
    param: vec4<f32>,
}

fn flat_index(wg: vec3<u32>, d: Dispatch) -> u32 {
    return wg.y * d.groups_x + wg.x;
}
