//! Deterministic parallel sums: fixed chunks summed in parallel, the chunk
//! sums added in order. Results do not depend on the thread count or on
//! rayon's work stealing.

use rayon::prelude::*;

/// Whether the processor has 256-bit vectors (AVX2). The per-texel
/// passes written in lanes then run a copy of their code compiled for them:
/// the same operations in the same order (no fused multiply-adds), so the
/// same bits.
pub(crate) fn wide_vectors() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Texels per chunk of the per-texel loops.
pub(crate) const CHUNK: usize = 4096;

/// Number of chunks for `n` texels.
#[inline]
pub(crate) fn chunks(n: usize) -> usize {
    n.div_ceil(CHUNK)
}

/// `Σ a_i h_i` (m³) over all texels, in a fixed order; `partials` is
/// reused scratch.
pub(crate) fn liquid_volume(h: &[f64], areas: &[f32], partials: &mut Vec<f64>) -> f64 {
    partials.clear();
    partials.resize(chunks(h.len()), 0.0);
    h.par_chunks(CHUNK)
        .zip(areas.par_chunks(CHUNK))
        .zip(partials.par_iter_mut())
        .for_each(|((h, a), p)| {
            *p = h.iter().zip(a).map(|(&h, &a)| h * a as f64).sum();
        });
    partials.iter().sum()
}
