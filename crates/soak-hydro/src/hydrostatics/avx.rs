//! The lane loads and stores of the AVX2 kernels (the planar, sea and drag
//! kernels take four texels side by side, in `f64` lanes read from the
//! atlas' `f32` columns).

use std::arch::x86_64::{
    __m256d, _mm_loadu_ps, _mm256_add_pd, _mm256_cvtps_pd, _mm256_fmadd_pd, _mm256_loadu_pd, _mm256_mul_pd,
    _mm256_storeu_pd, _mm256_sub_pd,
};

/// Texels side by side in an AVX2 kernel.
const LANES: usize = 4;

/// The last texels of a range, fewer than [`LANES`] (`v`, the tail of a
/// column), as a group padded with zeros: the tail group of every AVX2
/// kernel here (its empty lanes then masked off by the kernel).
#[inline(always)]
pub(super) fn padded<T: Copy + Default>(v: &[T]) -> [T; LANES] {
    debug_assert!(v.len() < LANES, "a tail of fewer than {LANES} texels");
    std::array::from_fn(|i| v.get(i).copied().unwrap_or_default())
}

/// Four floats, widened.
#[target_feature(enable = "avx2,fma")]
pub(super) fn widen(v: &[f32; LANES]) -> __m256d {
    // SAFETY: `v` holds the four floats an unaligned 128-bit load reads.
    #[allow(unsafe_code)]
    _mm256_cvtps_pd(unsafe { _mm_loadu_ps(v.as_ptr()) })
}

/// Lanes `i .. i + 4` of `v`, widened, checked against `v` (the sea's
/// drag kernel, whose groups cost far more than the check).
#[target_feature(enable = "avx2,fma")]
pub(super) fn widen_at(v: &[f32], i: usize) -> __m256d {
    let quad: &[f32; LANES] = v[i..i + LANES].try_into().expect("four floats");
    widen(quad)
}

/// The texels of `range` of `column`, [`LANES`] at a time (the last
/// `range.len() % LANES` left out), in exactly `range.len() / LANES`
/// quadruples: a kernel that reads its columns' quadruples by one index
/// below that length needs no bounds check (checking each load was a third
/// of the planar kernel's instructions).
pub(super) fn quads(column: &[f32], range: std::ops::Range<usize>) -> &[[f32; LANES]] {
    let n = range.len() / LANES;
    let floats = &column[range.start..range.start + n * LANES];
    // SAFETY: `[f32; LANES]` is `LANES` floats in a row, aligned as a
    // float, and `floats` holds `n` of them (what `<[T]>::as_chunks` does,
    // stable after this workspace's oldest supported Rust).
    #[allow(unsafe_code)]
    unsafe {
        std::slice::from_raw_parts(floats.as_ptr().cast::<[f32; LANES]>(), n)
    }
}

/// [`quads`] of three columns (a texel's coordinates, or its area
/// vector's), each exactly `range.len() / LANES` long.
pub(super) fn quads3(columns: [&[f32]; 3], range: std::ops::Range<usize>) -> [&[[f32; LANES]]; 3] {
    columns.map(|c| quads(c, range.clone()))
}

/// The first four of `v` as lanes.
#[target_feature(enable = "avx2,fma")]
pub(super) fn load(v: &[f64]) -> __m256d {
    let v = &v[..LANES];
    // SAFETY: `v` holds the four f64 an unaligned 256-bit load reads.
    #[allow(unsafe_code)]
    unsafe {
        _mm256_loadu_pd(v.as_ptr())
    }
}

/// The lanes of `v` as an array.
#[target_feature(enable = "avx2,fma")]
pub(super) fn store(v: __m256d) -> [f64; LANES] {
    let mut out = [0.0; LANES];
    // SAFETY: `out` holds the four f64 an unaligned 256-bit store writes.
    #[allow(unsafe_code)]
    unsafe {
        _mm256_storeu_pd(out.as_mut_ptr(), v)
    };
    out
}

/// Adds `s (1, x, x xᵀ)` lane by lane to the ten sums of
/// [`DragAcc::iso`](super::sums::DragAcc) (in its order): the drag
/// kernels' isotropic sums.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn add_iso(iso: &mut [__m256d; 10], s: __m256d, x: &[__m256d; 3]) {
    let sr = [0, 1, 2].map(|k| _mm256_mul_pd(s, x[k]));
    iso[0] = _mm256_add_pd(iso[0], s);
    iso[1] = _mm256_add_pd(iso[1], sr[0]);
    iso[2] = _mm256_add_pd(iso[2], sr[1]);
    iso[3] = _mm256_add_pd(iso[3], sr[2]);
    iso[4] = _mm256_fmadd_pd(sr[0], x[0], iso[4]);
    iso[5] = _mm256_fmadd_pd(sr[1], x[1], iso[5]);
    iso[6] = _mm256_fmadd_pd(sr[2], x[2], iso[6]);
    iso[7] = _mm256_fmadd_pd(sr[0], x[1], iso[7]);
    iso[8] = _mm256_fmadd_pd(sr[1], x[2], iso[8]);
    iso[9] = _mm256_fmadd_pd(sr[2], x[0], iso[9]);
}

/// Adds `w h hᵀ` lane by lane to the upper triangle (row by row) of
/// [`DragAcc::gg`](super::sums::DragAcc): the drag kernels' skin friction.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn add_rank1(gg: &mut [__m256d; 21], w: __m256d, h: &[__m256d; 6]) {
    let mut m = 0;
    for i in 0..6 {
        let wh = _mm256_mul_pd(w, h[i]);
        for hj in &h[i..] {
            gg[m] = _mm256_fmadd_pd(wh, *hj, gg[m]);
            m += 1;
        }
    }
}

/// `h = (A, x × A)` lane by lane: a texel's row of the drag's Jacobian.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn h_of(x: &[__m256d; 3], a: &[__m256d; 3]) -> [__m256d; 6] {
    [
        a[0],
        a[1],
        a[2],
        _mm256_sub_pd(_mm256_mul_pd(x[1], a[2]), _mm256_mul_pd(x[2], a[1])),
        _mm256_sub_pd(_mm256_mul_pd(x[2], a[0]), _mm256_mul_pd(x[0], a[2])),
        _mm256_sub_pd(_mm256_mul_pd(x[0], a[1]), _mm256_mul_pd(x[1], a[0])),
    ]
}
