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

/// `to = fromᵀ` for `n × n` grids, a block of `B × B` at a time through a
/// local copy, so that both sides are read and written along their rows
/// (written straight down a column, the rows of a power-of-two grid fall
/// on the same cache sets and evict one another).
// `j` walks the block's columns: no iterator over `block` gives them.
#[allow(clippy::needless_range_loop)]
fn transpose(from: &[Complex<f64>], to: &mut [Complex<f64>], n: usize) {
    const B: usize = 8;
    let mut block = [[Complex::new(0.0, 0.0); B]; B];
    for r0 in (0..n).step_by(B) {
        let rows = B.min(n - r0);
        for c0 in (0..n).step_by(B) {
            let columns = B.min(n - c0);
            if rows == B && columns == B {
                // A whole block: fixed lengths the compiler unrolls.
                for (i, row) in block.iter_mut().enumerate() {
                    let start = (r0 + i) * n + c0;
                    row.copy_from_slice(&from[start..start + B]);
                }
                for j in 0..B {
                    let start = (c0 + j) * n + r0;
                    let out: &mut [Complex<f64>; B] =
                        (&mut to[start..start + B]).try_into().expect("B values");
                    for (i, o) in out.iter_mut().enumerate() {
                        *o = block[i][j];
                    }
                }
                continue;
            }
            for (i, row) in block.iter_mut().enumerate().take(rows) {
                let start = (r0 + i) * n + c0;
                row[..columns].copy_from_slice(&from[start..start + columns]);
            }
            for j in 0..columns {
                let start = (c0 + j) * n + r0;
                for (i, out) in to[start..start + rows].iter_mut().enumerate() {
                    *out = block[i][j];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the definition: sizes below a block, of whole blocks and
    /// of blocks and a remainder (the waves' regions need only be even).
    #[test]
    fn the_transpose_is_the_definitions() {
        for n in [1, 2, 4, 8, 10, 16, 30, 64, 100, 256] {
            let from: Vec<Complex<f64>> = (0..n * n)
                .map(|k| Complex::new(k as f64, -(k as f64) / 3.0))
                .collect();
            let mut to = vec![Complex::new(f64::NAN, 0.0); n * n];
            transpose(&from, &mut to, n);
            for r in 0..n {
                for c in 0..n {
                    assert_eq!(to[c * n + r], from[r * n + c], "n = {n}, ({r}, {c})");
                }
            }
        }
    }
}
