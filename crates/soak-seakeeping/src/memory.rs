//! From the frequency domain to the time domain: the radiation force's
//! memory (Cummins 1962) as a few exponential states.
//!
//! The radiation force of a body moving arbitrarily is
//! `−A∞ ẍ(t) − ∫₀ᵗ K(t − τ) ẋ(τ) dτ`, with the retardation kernel
//! `K(t) = (2/π) ∫₀^∞ B(ω) cos ωt dω`. A [`Sweep`] holds A(ω), B(ω) over
//! frequencies and gives K; [`Kernel::fit`] realises K as a sum of damped
//! complex exponentials `K(t) ≈ Re Σ c_k e^{λ_k t}` (poles by the
//! eigensystem realisation algorithm, a Hankel SVD of K's samples;
//! residues by least squares), so that the convolution costs one
//! complex multiply-add per pole per step: each pole's state
//! `s_k = ∫ e^{λ_k (t − τ)} ẋ(τ) dτ` advances exactly over a step in which
//! the velocity varies linearly.

use nalgebra::{DMatrix, DVector, Matrix6};
use num_complex::Complex64;

use crate::error::SeakeepingError;
use crate::green::catmull_rom;
use crate::radiation::{Coefficients, Radiation, Surface};

/// Added mass and damping over frequencies, and their infinite-frequency
/// limit.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// A∞: kg, kg·m, kg·m² by block.
    pub infinite: Matrix6<f64>,
    /// The coefficients at each frequency, in increasing ω.
    pub frequencies: Vec<Coefficients>,
}

impl Radiation {
    /// Solves the radiation problem at each of `omegas` (rad/s, positive)
    /// and at infinite frequency.
    pub fn sweep(&self, omegas: &[f64]) -> Result<Sweep, SeakeepingError> {
        let infinite = self.solve(Surface::InfiniteFrequency)?.added_mass;
        let mut omegas = omegas.to_vec();
        omegas.sort_by(f64::total_cmp);
        let mut frequencies = Vec::with_capacity(omegas.len());
        for omega in omegas {
            if !omega.is_finite() || omega <= 0.0 {
                return Err(SeakeepingError::BadParameter {
                    name: "omega",
                    value: omega,
                });
            }
            frequencies.push(self.solve(Surface::Wavenumber(omega * omega / self.gravity()))?);
        }
        Ok(Sweep {
            infinite,
            frequencies,
        })
    }
}

impl Sweep {
    /// A(ω) and B(ω) of modes (i, j), interpolated: Catmull–Rom between
    /// the computed frequencies; below the first, A held and B falling
    /// linearly to 0 at ω = 0; beyond the last, A going to A∞ as ω⁻² and B
    /// to 0 as ω⁻⁶ from their last values (best where B has died out).
    pub fn at(&self, i: usize, j: usize, omega: f64) -> (f64, f64) {
        let f = &self.frequencies;
        let n = f.len();
        if n == 0 {
            return (self.infinite[(i, j)], 0.0);
        }
        if omega <= f[0].omega {
            // B grows from 0 at ω = 0 (as ω⁴ or faster for a surface body:
            // a straight line to the first point is close enough there).
            let t = (omega / f[0].omega).max(0.0);
            return (f[0].added_mass[(i, j)], t * f[0].damping[(i, j)]);
        }
        if omega >= f[n - 1].omega {
            // A tail that joins the last frequency: A to A∞ as ω⁻², B to
            // zero as ω⁻⁶ (a truncated B would ring in the kernel).
            let last = &f[n - 1];
            let r = last.omega / omega;
            let a_inf = self.infinite[(i, j)];
            return (
                a_inf + (last.added_mass[(i, j)] - a_inf) * r * r,
                last.damping[(i, j)] * r.powi(6),
            );
        }
        let k = f.partition_point(|c| c.omega <= omega) - 1;
        let value = |index: isize, which: usize| {
            let index = index.clamp(0, n as isize - 1) as usize;
            if which == 0 {
                f[index].added_mass[(i, j)]
            } else {
                f[index].damping[(i, j)]
            }
        };
        let t = (omega - f[k].omega) / (f[k + 1].omega - f[k].omega);
        let w = catmull_rom(t);
        let mut a = 0.0;
        let mut b = 0.0;
        for (o, weight) in w.iter().enumerate() {
            let index = k as isize - 1 + o as isize;
            a += weight * value(index, 0);
            b += weight * value(index, 1);
        }
        (a, b)
    }

    /// The retardation kernel `K_ij(t) = (2/π) ∫₀^∞ B_ij(ω) cos ωt dω`
    /// (kg/s², or per m and m² by block) at each of `times` (s), by the
    /// trapezoidal rule on a grid fine enough for the largest time.
    pub fn kernel(&self, i: usize, j: usize, times: &[f64]) -> Vec<f64> {
        let Some(last) = self.frequencies.last() else {
            return vec![0.0; times.len()];
        };
        let t_max = times.iter().copied().fold(0.0, f64::max);
        let spacing = self
            .frequencies
            .windows(2)
            .map(|w| w[1].omega - w[0].omega)
            .fold(last.omega, f64::min);
        let step = (spacing / 8.0).min(std::f64::consts::PI / (16.0 * t_max.max(1e-9)));
        // The tail beyond the last frequency to 3×, where it is 0.14 % of
        // the last B.
        let top = 3.0 * last.omega;
        let count = (top / step).ceil() as usize;
        let step = top / count as f64;
        let samples: Vec<(f64, f64)> = (0..=count)
            .map(|n| (n as f64 * step, self.at(i, j, n as f64 * step).1))
            .collect();
        times
            .iter()
            .map(|&t| {
                let mut sum = 0.0;
                for (n, &(omega, b)) in samples.iter().enumerate() {
                    let weight = if n == 0 || n == count { 0.5 } else { 1.0 };
                    sum += weight * b * (omega * t).cos();
                }
                2.0 / std::f64::consts::PI * sum * step
            })
            .collect()
    }
}

/// A retardation kernel as a sum of damped complex exponentials,
/// `K(t) ≈ Re Σ c_k e^{λ_k t}`.
#[derive(Clone, Debug, PartialEq)]
pub struct Kernel {
    /// The poles λ_k (1/s, negative real parts).
    pub poles: Vec<Complex64>,
    /// The residues c_k (the kernel's units).
    pub residues: Vec<Complex64>,
}

impl Kernel {
    /// Fits `samples` (K at t = 0, dt, 2 dt, …) with at most `order`
    /// poles: the eigensystem realisation algorithm on the Hankel matrix
    /// of the samples (poles: the eigenvalues of the realised state
    /// matrix, the unstable ones dropped), then the residues by least
    /// squares over every sample.
    pub fn fit(samples: &[f64], dt: f64, order: usize) -> Kernel {
        let half = samples.len().saturating_sub(1) / 2;
        if half < 2 || order == 0 {
            return Kernel {
                poles: Vec::new(),
                residues: Vec::new(),
            };
        }
        let h0 = DMatrix::from_fn(half, half, |i, j| samples[i + j]);
        let h1 = DMatrix::from_fn(half, half, |i, j| samples[i + j + 1]);
        let svd = h0.svd(true, true);
        let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
            return Kernel {
                poles: Vec::new(),
                residues: Vec::new(),
            };
        };
        let largest = svd.singular_values[0];
        let rank = svd
            .singular_values
            .iter()
            .take(order)
            .filter(|&&s| s > 1e-10 * largest)
            .count();
        if rank == 0 {
            return Kernel {
                poles: Vec::new(),
                residues: Vec::new(),
            };
        }
        let root: Vec<f64> = (0..rank).map(|k| 1.0 / svd.singular_values[k].sqrt()).collect();
        let u_r = u.columns(0, rank);
        let v_r = v_t.rows(0, rank).transpose();
        let mut state = u_r.transpose() * h1 * v_r;
        for i in 0..rank {
            for j in 0..rank {
                state[(i, j)] *= root[i] * root[j];
            }
        }
        let poles: Vec<Complex64> = state
            .complex_eigenvalues()
            .iter()
            .filter(|z| z.norm() < 1.0 && z.norm() > 0.0)
            .map(|z| z.ln() / dt)
            .collect();
        let residues = residues(samples, dt, &poles);
        Kernel { poles, residues }
    }

    /// The same poles with residues refitted, by least squares, to a
    /// frequency response: at each `(ω, T)` of `response`, the kernel's
    /// transform [`Kernel::transform`] should be `T = B(ω) − i ω (A(ω) −
    /// A∞)`, or B alone where T's imaginary part is NaN; rows with a
    /// `weight` (relative, 1 for a computed frequency) count that much. Held, as [`Kernel::fit`] holds it, to a zero
    /// integral (`B(0) = 0`). Fitted to the time samples alone, the
    /// kernel's residues follow B over every frequency, its extrapolated
    /// tail included, and the added mass Kramers–Kronig makes of them
    /// missed the computed one wherever that tail was wrong; fitted here,
    /// both A and B are the computed ones over the sweep.
    pub fn refit(&self, response: &[(f64, Complex64, f64)]) -> Kernel {
        let n = self.poles.len();
        if n == 0 || response.is_empty() {
            return self.clone();
        }
        // Unknowns: Re c_k and Im c_k. With u = 1/(λ + iω), v = 1/(λ̄ +
        // iω), the transform of Re(c e^{λt}) is −½ (x (u + v) + i y (u − v)).
        let rows = 2 * response.len() + 1;
        // Nothing to fit to (a response of zeros): the kernel as it is.
        let largest = response.iter().fold(0.0f64, |m, r| m.max(r.1.re.abs()));
        if largest == 0.0 {
            return self.clone();
        }
        let mut design = DMatrix::<f64>::zeros(rows, 2 * n);
        let mut target = DVector::<f64>::zeros(rows);
        for (r, &(omega, t, weight)) in response.iter().enumerate() {
            let s = Complex64::new(0.0, omega);
            for (k, p) in self.poles.iter().enumerate() {
                let u = 1.0 / (p + s);
                let v = 1.0 / (p.conj() + s);
                let on_x = -0.5 * (u + v);
                let on_y = -0.5 * Complex64::new(0.0, 1.0) * (u - v);
                design[(2 * r, 2 * k)] = weight * on_x.re;
                design[(2 * r, 2 * k + 1)] = weight * on_y.re;
                design[(2 * r + 1, 2 * k)] = weight * on_x.im;
                design[(2 * r + 1, 2 * k + 1)] = weight * on_y.im;
            }
            target[2 * r] = weight * t.re;
            // An unknown added mass (NaN): B alone.
            if t.im.is_nan() {
                for k in 0..2 * n {
                    design[(2 * r + 1, k)] = 0.0;
                }
            } else {
                target[2 * r + 1] = weight * t.im;
            }
        }
        // The integral: Re Σ −c/λ = 0, weighted STEADY_WEIGHT.
        for (k, p) in self.poles.iter().enumerate() {
            let q = 1.0 / p;
            design[(rows - 1, 2 * k)] = -STEADY_WEIGHT * q.re;
            design[(rows - 1, 2 * k + 1)] = STEADY_WEIGHT * q.im;
        }
        let svd = design.svd(true, true);
        let Ok(x) = svd.solve(&target, 1e-12 * svd.singular_values.max()) else {
            return self.clone();
        };
        Kernel {
            poles: self.poles.clone(),
            residues: (0..n).map(|k| Complex64::new(x[2 * k], x[2 * k + 1])).collect(),
        }
    }

    /// K(t) of the fit.
    pub fn value(&self, t: f64) -> f64 {
        self.poles
            .iter()
            .zip(&self.residues)
            .map(|(p, c)| (c * (p * t).exp()).re)
            .sum()
    }

    /// The fit's transform `∫₀^∞ K(t) e^{iωt} dt`, whose real part is
    /// B(ω) and whose imaginary part is `−ω (A(ω) − A∞)`.
    pub fn transform(&self, omega: f64) -> Complex64 {
        self.poles
            .iter()
            .zip(&self.residues)
            .map(|(p, c)| {
                // Re Σ c e^{λt}: both c e^{λt} and its conjugate halves.
                let s = Complex64::new(0.0, omega);
                0.5 * (-c / (p + s) - c.conj() / (p.conj() + s))
            })
            .sum()
    }
}

/// Least-squares residues of `poles` over the samples, held to a fit
/// whose integral `∫₀^∞ K dt = B(0)` is zero as the kernel's is (a last
/// row, weighted [`STEADY_WEIGHT`], asks `Σ c_k / p_k = 0`). Left free,
/// the fit's integral came out a fraction of a percent off zero either
/// way: where it was negative, a body turning steadily in a mode without
/// stiffness (a rod about its own length) was pushed faster and faster.
fn residues(samples: &[f64], dt: f64, poles: &[Complex64]) -> Vec<Complex64> {
    if poles.is_empty() {
        return Vec::new();
    }
    let n = samples.len();
    // The steady row in the samples' units: `Σ c/p / dt` is the fit's
    // integral over the sample spacing, what `Σ K(t_i)` sums.
    let design = DMatrix::from_fn(n + 1, poles.len(), |i, k| {
        if i < n {
            (poles[k] * (i as f64 * dt)).exp()
        } else {
            STEADY_WEIGHT / (poles[k] * dt)
        }
    });
    let target = DVector::from_fn(n + 1, |i, _| {
        Complex64::new(if i < n { samples[i] } else { 0.0 }, 0.0)
    });
    let qr = design.qr();
    let projected = qr.q().adjoint() * target;
    qr.r()
        .solve_upper_triangular(&projected)
        .map(|c| c.iter().copied().collect())
        .unwrap_or_else(|| vec![Complex64::new(0.0, 0.0); poles.len()])
}

/// The weight of the fit's steady row against each sample's: the fit's
/// integral is held to zero to about 1e-4 of the samples' sum.
const STEADY_WEIGHT: f64 = 1e4;

/// The states of a [`Kernel`]'s convolution with a velocity history
/// (saved and restored bit for bit with serde).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Memory {
    states: Vec<Complex64>,
}

impl Memory {
    /// At rest (no history).
    pub fn new(kernel: &Kernel) -> Memory {
        Memory {
            states: vec![Complex64::new(0.0, 0.0); kernel.poles.len()],
        }
    }

    /// How many states it holds (its kernel's poles).
    pub fn len(&self) -> usize {
        self.states.len()
    }

    /// Whether it holds none (a kernel without poles).
    pub fn is_empty(&self) -> bool {
        self.states.is_empty()
    }

    /// `∫₀ᵗ K(t − τ) ẋ(τ) dτ` now (the force's units).
    pub fn force(&self, kernel: &Kernel) -> f64 {
        self.states
            .iter()
            .zip(&kernel.residues)
            .map(|(s, c)| (c * s).re)
            .sum()
    }

    /// Advances by `dt` over which the velocity goes linearly from `v0` to
    /// `v1` (exact for that history).
    pub fn advance(&mut self, kernel: &Kernel, v0: f64, v1: f64, dt: f64) {
        self.advance_by(&kernel.step(dt), v0, v1);
    }

    /// `∫ K(t − τ) ẋ(τ) dτ` at the end of a step of `step`'s length over
    /// which the velocity goes linearly from `v0` to `v1`, the states
    /// left as they are: one real product per pole (the residues folded
    /// into the step's [`KernelStep::weights`]).
    pub fn force_after(&self, step: &KernelStep, v0: f64, v1: f64) -> f64 {
        let held: f64 = self
            .states
            .iter()
            .zip(&step.weights)
            .map(|(s, w)| w.re * s.re - w.im * s.im)
            .sum();
        held + step.constant * v0 + step.ramp * (v1 - v0)
    }

    /// [`Memory::advance`] with the step's factors already computed
    /// ([`Kernel::step`]: the same for every body and step of one `dt`).
    pub fn advance_by(&mut self, step: &KernelStep, v0: f64, v1: f64) {
        for (s, f) in self.states.iter_mut().zip(&step.poles) {
            *s = f.decay * *s + f.constant * v0 + f.ramp * (v1 - v0);
        }
    }
}

/// A step of one length for one [`Kernel`]: each pole's [`StepFactors`]
/// (to advance a [`Memory`]), and the same folded with the kernel's
/// residues (for the force at the step's end, [`Memory::force_after`]).
#[derive(Clone, Debug, PartialEq)]
pub struct KernelStep {
    /// Each pole's factors, in order.
    pub poles: Vec<StepFactors>,
    /// Each pole's residue times its decay, `c e^{p dt}` (the force per
    /// unit state).
    pub weights: Vec<Complex64>,
    /// `Σ Re(c · constant)` over the poles: the force per unit of the
    /// velocity held over the step (N·s/m and their like).
    pub constant: f64,
    /// `Σ Re(c · ramp)`: the force per unit of the velocity's change
    /// over the step.
    pub ramp: f64,
}

/// What one step of `dt` does to one state of a [`Memory`]: for a pole
/// `p`, `decay = e^{p dt}`, `constant = ∫₀^dt e^{p(dt−τ)} dτ` and
/// `ramp = ∫₀^dt e^{p(dt−τ)} τ/dt dτ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepFactors {
    /// `e^{p dt}`.
    pub decay: Complex64,
    /// The constant velocity's part, s.
    pub constant: Complex64,
    /// The velocity's ramp's part, s.
    pub ramp: Complex64,
}

impl Kernel {
    /// The factors of a step of `dt` (s): each pole's, in order, and
    /// folded with the residues.
    pub fn step(&self, dt: f64) -> KernelStep {
        let poles = self.pole_factors(dt);
        let weights = poles
            .iter()
            .zip(&self.residues)
            .map(|(f, c)| c * f.decay)
            .collect();
        let part = |factor: fn(&StepFactors) -> Complex64| -> f64 {
            poles
                .iter()
                .zip(&self.residues)
                .map(|(f, c)| (c * factor(f)).re)
                .sum()
        };
        KernelStep {
            constant: part(|f| f.constant),
            ramp: part(|f| f.ramp),
            weights,
            poles,
        }
    }

    /// Each pole's factors of a step of `dt` (s), in order.
    fn pole_factors(&self, dt: f64) -> Vec<StepFactors> {
        self.poles
            .iter()
            .map(|&p| {
                let e = (p * dt).exp();
                let pd = p * dt;
                let (constant, ramp) = if pd.norm() < 1e-4 {
                    (
                        Complex64::new(dt, 0.0) * (1.0 + pd / 2.0),
                        Complex64::new(dt / 2.0, 0.0) * (1.0 + pd / 3.0),
                    )
                } else {
                    ((e - 1.0) / p, ((e - 1.0) / pd - 1.0) / p)
                };
                StepFactors {
                    decay: e,
                    constant,
                    ramp,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `K(t) = (1 − 2t²) e^{−t²}`: zero integral over t ≥ 0 (its `B(0)`),
    /// and no finite sum of exponentials, so a fit of a few poles misses
    /// it somewhere.
    fn gaussian_kernel(t: f64) -> f64 {
        (1.0 - 2.0 * t * t) * (-t * t).exp()
    }

    #[test]
    fn a_fitted_kernel_has_no_steady_damping() {
        let dt = 0.05;
        let samples: Vec<f64> = (0..=250).map(|n| gaussian_kernel(n as f64 * dt)).collect();
        let scale: f64 = samples.iter().map(|k| k.abs()).sum::<f64>() * dt;
        for order in [4, 6, 8] {
            let fit = Kernel::fit(&samples, dt, order);
            assert!(!fit.poles.is_empty(), "order {order}: no poles");
            // B(0) of the fit: its integral.
            let steady = fit.transform(0.0).re;
            let worst = samples
                .iter()
                .enumerate()
                .map(|(n, k)| (fit.value(n as f64 * dt) - k).abs())
                .fold(0.0, f64::max);
            assert!(
                steady.abs() <= 1e-3 * scale,
                "order {order}: B(0) = {steady:.3e} (∫|K| = {scale:.3e})"
            );
            assert!(worst <= 0.05, "order {order}: misfit {worst:.3e}");
        }
    }
}
