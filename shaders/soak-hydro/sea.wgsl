// A spectral sea's tile on the GPU: the uniform its kernels share
// (`SeaUniform` in src/gpu/sea.rs), composed before sea_modes.wgsl and
// sea_unpack.wgsl.

struct Sea {
    // Cells per side, first mode in `modes`, first float of the fields in
    // `heights` (sea_unpack.wgsl), unused.
    n: u32,
    modes_first: u32,
    fields_first: u32,
    _pad0: u32,
    // Wavenumber step 2π/L (1/m), choppiness, gravity (m/s²), cell side (m).
    dk: f32,
    lambda: f32,
    gravity: f32,
    cell: f32,
}
