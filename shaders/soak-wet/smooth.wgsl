// The smooth share of a texel's change in the conservative return
// (`smooth_change` in diffusion.rs): the cells' fill changes (cellinfo.w)
// interpolated trilinearly at grid position g over the defined cells among
// the 8 nearest, times h_max, clamped to keep h in [0, h_max]. Needs the
// bindings `dense` and `cellinfo` in the including module.
fn smooth_change(g: vec3<f32>, h: f32, hmax: f32) -> f32 {
    let q = g - vec3<f32>(0.5);
    let base = floor(q);
    let t = q - base;
    let b = vec3<i32>(base);
    let dims = vec3<i32>(params.dims.xyz);
    var num = 0.0;
    var den = 0.0;
    for (var corner = 0u; corner < 8u; corner++) {
        let d = vec3<u32>(corner & 1u, (corner >> 1u) & 1u, (corner >> 2u) & 1u);
        let c = b + vec3<i32>(d);
        if (any(c < vec3<i32>(0)) || any(c >= dims)) {
            continue;
        }
        let id = dense[u32(c.x) + params.dims.x * (u32(c.y) + params.dims.y * u32(c.z))];
        if (id == NONE) {
            continue;
        }
        let wv = select(vec3<f32>(1.0) - t, t, d == vec3<u32>(1u));
        let w = wv.x * wv.y * wv.z;
        num += w * cellinfo[id].w;
        den += w;
    }
    if (den > 0.0) {
        return clamp(num / den * hmax, -h, hmax - h);
    }
    return 0.0;
}
