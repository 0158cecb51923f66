//! The square 2-D FFT the interactive waves and the spectral sea share.

use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

/// Forward and inverse 2-D transforms of an `n × n` grid stored row by row
/// (cell `(ix, iz)` at `iz · n + ix`), unnormalised: the rows, then the
/// columns as rows of the transpose, the rows in parallel (each row's
/// transform is the same on any number of threads, so the result is too).
#[derive(Clone)]
pub(crate) struct Fft2 {
    n: usize,
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
}

impl Fft2 {
    /// The transforms of an `n × n` grid.
    pub(crate) fn new(n: usize) -> Self {
        let mut planner = FftPlanner::new();
        Self {
            n,
            forward: planner.plan_fft_forward(n),
            inverse: planner.plan_fft_inverse(n),
        }
    }

    /// The transform of `data` in place (`forward`: `Σ x e^{−i k·x}`;
    /// otherwise `Σ X e^{+i k·x}`, not divided by `n²`); `scratch` holds
    /// `n²` values.
    pub(crate) fn process(&self, data: &mut [Complex<f64>], forward: bool, scratch: &mut [Complex<f64>]) {
        self.run(data, forward, scratch, true);
    }

    /// [`Fft2::process`] on the calling thread alone (for callers that run
    /// several transforms in parallel).
    pub(crate) fn process_serial(
        &self,
        data: &mut [Complex<f64>],
        forward: bool,
        scratch: &mut [Complex<f64>],
    ) {
        self.run(data, forward, scratch, false);
    }

    /// The rows, then the columns as rows of the transpose; the rows in
    /// parallel where `parallel`.
    fn run(&self, data: &mut [Complex<f64>], forward: bool, scratch: &mut [Complex<f64>], parallel: bool) {
        let n = self.n;
        let fft = if forward { &self.forward } else { &self.inverse };
        let rows = |data: &mut [Complex<f64>]| {
            if parallel {
                data.par_chunks_mut(n * 8).for_each(|c| fft.process(c));
            } else {
                data.chunks_mut(n * 8).for_each(|c| fft.process(c));
            }
        };
        rows(data);
        transpose(data, scratch, n);
        rows(scratch);
        transpose(scratch, data, n);
    }
}

/// `to = fromᵀ` for `n × n` grids, in blocks of 16 × 16 so that both
/// sides stay in cache.
fn transpose(from: &[Complex<f64>], to: &mut [Complex<f64>], n: usize) {
    const B: usize = 16;
    for r0 in (0..n).step_by(B) {
        for c0 in (0..n).step_by(B) {
            for r in r0..(r0 + B).min(n) {
                for c in c0..(c0 + B).min(n) {
                    to[c * n + r] = from[r * n + c];
                }
            }
        }
    }
}
