//! A spectral sea: a directional wave spectrum (JONSWAP or
//! Pierson–Moskowitz by significant height and peak period, cos-2s
//! spreading) realised on a periodic tile by the inverse FFT, with the
//! surface particles' choppy horizontal displacement and orbital velocity.
//!
//! Every mode of the tile's wavenumber grid `k = 2π (n, l) / L` is one
//! linear deep-water wave travelling along `k` at `ω = √(g |k|)`, with a
//! complex amplitude `A_k` drawn from the spectrum (a complex Gaussian of
//! variance `2 S(k) Δk²`, so that the elevation's variance is the
//! spectrum's `m₀ = H_s² / 16` in expectation). The surface particle at
//! rest on the node `x₀` is, at time `t`, at
//!
//! - height `η = Re Σ A_k e^{i(k·x₀ − ωt)}`,
//! - horizontal displacement `D = λ Re Σ i k̂ A_k e^{i(k·x₀ − ωt)}`
//!   (`λ` the choppiness: 1 is linear theory's particle orbit),
//!
//! so that one mode of amplitude `a` is exactly the [`Gerstner`](super::Gerstner)
//! wave of that amplitude with steepness `λ k a`.

use std::borrow::Cow;

use nalgebra::Vector2;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use rustfft::num_complex::Complex;
use serde::{Deserialize, Serialize};

use crate::error::WaterError;
use crate::fft2::Fft2;

/// The shape of a sea's frequency spectrum `S(ω)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SpectrumShape {
    /// Pierson–Moskowitz: a fully developed sea,
    /// `S(ω) = (5/16) H_s² ω_p⁴ ω⁻⁵ exp(−5/4 (ω_p/ω)⁴)`.
    PiersonMoskowitz,
    /// JONSWAP: a fetch-limited sea, Pierson–Moskowitz's shape with its peak
    /// raised by `gamma^r`, `r = exp(−(ω − ω_p)² / (2 σ² ω_p²))`,
    /// `σ = 0.07` below the peak and `0.09` above it; `gamma` 1 is
    /// Pierson–Moskowitz, 3.3 the mean of the JONSWAP measurements.
    Jonswap {
        /// Peak enhancement `γ`, at least 1.
        gamma: f64,
    },
}

/// A directional wave spectrum: a sea state by its significant height and
/// peak period, the direction it travels and how widely it spreads.
///
/// `S(ω, θ) = S(ω) D(θ)`, `S(ω)` scaled so that `∫ S dω = H_s² / 16`
/// exactly (JONSWAP's usual factor `1 − 0.287 ln γ` is that scaling's
/// approximation), and `D(θ) ∝ cos^{2s}((θ − θ_m)/2)` with `∫ D dθ = 1`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeaSpectrum {
    /// The spectrum's shape.
    pub shape: SpectrumShape,
    /// Significant wave height `H_s = 4 √m₀`, m.
    pub significant_height: f64,
    /// Peak period `T_p = 2π / ω_p`, s.
    pub peak_period: f64,
    /// Mean direction of travel, degrees from +x towards +z.
    pub direction_deg: f64,
    /// The cos-2s spreading exponent `s` (0: waves from every direction
    /// alike; 1 wide; 10 a wind sea; 75 a swell).
    pub spreading: f64,
}

/// Points of the numerical integrals of the spectrum's and the spreading's
/// normalisations (composite Simpson).
const QUADRATURE: usize = 20_000;

impl SeaSpectrum {
    /// A JONSWAP sea of significant height `hs` (m) and peak period `tp`
    /// (s) with `γ` = 3.3, travelling along +x with spreading `s` = 10.
    pub fn jonswap(hs: f64, tp: f64) -> Self {
        Self {
            shape: SpectrumShape::Jonswap { gamma: 3.3 },
            significant_height: hs,
            peak_period: tp,
            direction_deg: 0.0,
            spreading: 10.0,
        }
    }

    /// Checks every field: finite, `H_s` and `T_p` > 0, `γ` ≥ 1, `s` ≥ 0
    /// (and at most 1,000).
    pub fn validate(&self) -> Result<(), WaterError> {
        let gamma = match self.shape {
            SpectrumShape::PiersonMoskowitz => 1.0,
            SpectrumShape::Jonswap { gamma } => gamma,
        };
        let checks = [
            (
                "significant_height",
                self.significant_height,
                self.significant_height > 0.0,
            ),
            ("peak_period", self.peak_period, self.peak_period > 0.0),
            ("gamma", gamma, gamma >= 1.0),
            ("direction_deg", self.direction_deg, true),
            (
                "spreading",
                self.spreading,
                (0.0..=1000.0).contains(&self.spreading),
            ),
        ];
        for (name, value, ok) in checks {
            if !(value.is_finite() && ok) {
                return Err(WaterError::Parameter { name, value });
            }
        }
        Ok(())
    }

    /// Peak angular frequency `ω_p = 2π / T_p`, rad/s.
    pub fn peak_frequency(&self) -> f64 {
        std::f64::consts::TAU / self.peak_period
    }

    /// Deep-water wavelength of the peak, `g T_p² / (2π)`, m.
    pub fn peak_wavelength(&self, gravity: f64) -> f64 {
        gravity * self.peak_period.powi(2) / std::f64::consts::TAU
    }

    /// The tile a sea of this spectrum is realised on by default: eight
    /// peak wavelengths (m), so that the peak is the tile's eighth mode and
    /// its neighbours resolve it (at four, JONSWAP's narrow peak falls
    /// between modes and the realised `H_s` is 1.7 % high on average).
    /// With [`DEFAULT_SEA_CELLS`] (128) the shortest wave is an eighth of
    /// the peak's, at 2.8 times its frequency (the spectrum's tail beyond
    /// holds 2 % of its energy); 256 cells reach four times the peak's
    /// frequency (0.5 %) at four times the cost.
    pub fn default_tile(&self, gravity: f64) -> f64 {
        8.0 * self.peak_wavelength(gravity)
    }

    /// The shape before scaling, at `x = ω / ω_p`.
    fn unscaled(&self, x: f64) -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        let pm = x.powi(-5) * (-1.25 * x.powi(-4)).exp();
        match self.shape {
            SpectrumShape::PiersonMoskowitz => pm,
            SpectrumShape::Jonswap { gamma } => {
                let sigma = if x <= 1.0 { 0.07 } else { 0.09 };
                pm * gamma.powf((-(x - 1.0).powi(2) / (2.0 * sigma * sigma)).exp())
            }
        }
    }

    /// The factor that takes [`Self::unscaled`] (in `x = ω/ω_p`) to
    /// `S(ω)`: `m₀ / (ω_p ∫ unscaled dx)`.
    fn scale(&self) -> f64 {
        // The shape is below 1e-40 of its peak under x = 0.1 and falls as
        // x⁻⁵ above; the tail beyond x = 40 (a 4·10⁻⁷ share) is added in
        // closed form.
        let (a, b) = (0.1, 40.0);
        let integral = simpson(|x| self.unscaled(x), a, b, QUADRATURE) + 0.25 * self.unscaled(b) * b;
        let m0 = self.significant_height.powi(2) / 16.0;
        m0 / (self.peak_frequency() * integral)
    }

    /// The frequency spectrum `S(ω)` at each of `omegas` (rad/s), m²·s:
    /// `∫₀^∞ S dω = H_s² / 16`.
    pub fn densities(&self, omegas: &[f64]) -> Vec<f64> {
        let (scale, wp) = (self.scale(), self.peak_frequency());
        omegas.iter().map(|&w| scale * self.unscaled(w / wp)).collect()
    }

    /// The frequency spectrum `S(ω)` at one `omega` (rad/s), m²·s (the
    /// scaling is computed on each call: for many frequencies use
    /// [`Self::densities`]).
    pub fn density(&self, omega: f64) -> f64 {
        self.densities(&[omega])[0]
    }

    /// The spreading `D(θ)` (1/rad) at each direction of travel `thetas`
    /// (radians from +x towards +z): `∫_{−π}^{π} D dθ = 1`.
    pub fn spreading_densities(&self, thetas: &[f64]) -> Vec<f64> {
        let spreading = self.spreading_function();
        thetas.iter().map(|&t| spreading(t)).collect()
    }

    /// `D(θ)` as a function, its normalisation computed once.
    fn spreading_function(&self) -> impl Fn(f64) -> f64 + use<> {
        let s = self.spreading;
        let norm = simpson(
            |a| (0.5 * a).cos().powf(2.0 * s),
            -std::f64::consts::PI,
            std::f64::consts::PI,
            QUADRATURE,
        );
        let mean = self.direction_deg.to_radians();
        move |t| (0.5 * wrap_angle(t - mean)).cos().abs().powf(2.0 * s) / norm
    }
}

/// `a` taken into (−π, π].
fn wrap_angle(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let r = a.rem_euclid(tau);
    if r > std::f64::consts::PI { r - tau } else { r }
}

/// Composite Simpson's rule over `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let n = n + n % 2;
    let h = (b - a) / n as f64;
    let mut sum = f(a) + f(b);
    for i in 1..n {
        sum += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// One wave of a sea given mode by mode ([`SpectralSea::from_modes`]):
/// the tile's mode `(n, l)` (wavenumber `2π (n, l) / L`), its amplitude and
/// phase.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeaMode {
    /// Wavenumber index along x, within `−cells/2 < n < cells/2`.
    pub n: i32,
    /// Wavenumber index along z, within `−cells/2 < l < cells/2`.
    pub l: i32,
    /// Amplitude, m.
    pub amplitude: f64,
    /// Phase, radians: the wave's elevation is `a cos(k·x − ωt + phase)`.
    pub phase: f64,
}

/// The cells a side of a sea's tile by default.
pub const DEFAULT_SEA_CELLS: usize = 128;

/// The smallest and largest tile side in cells.
pub const SEA_CELLS: std::ops::RangeInclusive<usize> = 8..=2048;

/// A sea realised on a periodic square tile: the complex amplitude of
/// every mode of its FFT grid, drawn from a [`SeaSpectrum`] by a seed
/// (the same seed, the same sea, on any machine), or given mode by mode.
/// [`SpectralSea::fields`] evaluates the whole tile at a time `t` with a
/// few inverse FFTs.
#[derive(Clone)]
pub struct SpectralSea {
    /// Mean water level, m.
    pub level: f64,
    /// The tile's side, m (the sea repeats with this period along x and z).
    pub size: f64,
    /// Cells along each side (a power of two).
    pub cells: usize,
    /// Choppiness `λ`: the horizontal displacement's factor (0: heights
    /// only; 1: linear theory's orbits).
    pub choppiness: f64,
    /// Gravity for the dispersion relation, m/s².
    pub gravity: f64,
    /// `A_k` per mode in the transform's order (`l` row, `n` column, each
    /// index `i < cells/2` as itself, otherwise `i − cells`), m.
    amplitudes: Vec<Complex<f64>>,
    fft: Fft2,
    /// What of each mode with an amplitude does not change with time
    /// (its `k`, `k̂` and `ω`), made on the first evaluation for the tile's
    /// size and gravity then ([`Stationary`]).
    stationary: std::sync::OnceLock<Stationary>,
}

/// The modes of a [`SpectralSea`] that have an amplitude, each with its
/// index and what [`SpectralSea::fields`] needs of it that does not change
/// with time (`a` its amplitude at `t = 0`), row by row; made for the
/// tile's `size` and `gravity` it records.
#[derive(Clone)]
struct Stationary {
    size: f64,
    gravity: f64,
    /// Each mode's index in its row and the mode.
    modes: Vec<(usize, Turned)>,
    /// `rows[l]..rows[l + 1]`: row `l`'s modes in `modes`.
    rows: Vec<usize>,
}

impl Stationary {
    /// The modes of `sea` with an amplitude (neither the mean nor of no
    /// amplitude), at `t = 0`.
    fn of(sea: &SpectralSea) -> Self {
        let n = sea.cells;
        let dk = std::f64::consts::TAU / sea.size;
        let mut modes = Vec::new();
        let mut rows = Vec::with_capacity(n + 1);
        for lz in 0..n {
            rows.push(modes.len());
            let kz = signed(lz, n) as f64 * dk;
            for lx in 0..n {
                let a = sea.amplitudes[lz * n + lx];
                let k = [signed(lx, n) as f64 * dk, kz];
                let kk = k[0].hypot(k[1]);
                if kk == 0.0 || a.norm_sqr() == 0.0 {
                    continue;
                }
                let omega = (sea.gravity * kk).sqrt();
                modes.push((
                    lx,
                    Turned {
                        a,
                        k,
                        unit: [k[0] / kk, k[1] / kk],
                        omega,
                    },
                ));
            }
        }
        rows.push(modes.len());
        Self {
            size: sea.size,
            gravity: sea.gravity,
            modes,
            rows,
        }
    }

    /// Whether it was made for `sea`'s size and gravity as they are now.
    fn fits(&self, sea: &SpectralSea) -> bool {
        self.size.to_bits() == sea.size.to_bits() && self.gravity.to_bits() == sea.gravity.to_bits()
    }
}

impl std::fmt::Debug for SpectralSea {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpectralSea")
            .field("level", &self.level)
            .field("size", &self.size)
            .field("cells", &self.cells)
            .field("choppiness", &self.choppiness)
            .field("gravity", &self.gravity)
            .finish_non_exhaustive()
    }
}

/// A tile's fields at one time, every array `cells²` long in row order
/// (node `(ix, iz)` at `iz · cells + ix`, at rest at `(ix, iz) · size /
/// cells`): the surface particle resting on each node, where it is and how
/// it moves.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaFields {
    /// The time, s.
    pub time: f64,
    /// Mean water level, m.
    pub level: f64,
    /// The tile's side, m.
    pub size: f64,
    /// Cells along each side.
    pub cells: usize,
    /// Elevation above the mean level, m.
    pub height: Vec<f64>,
    /// Horizontal displacement along x and z, m.
    pub displacement: [Vec<f64>; 2],
    /// The elevation's gradient over the rest position `(∂η/∂x₀, ∂η/∂z₀)`.
    pub height_gradient: [Vec<f64>; 2],
    /// The displacement's gradient over the rest position
    /// `[∂Dx/∂x₀, ∂Dx/∂z₀ = ∂Dz/∂x₀, ∂Dz/∂z₀]`.
    pub displacement_gradient: [Vec<f64>; 3],
    /// The cross derivatives `∂²/∂x₀∂z₀` of the elevation and of the
    /// displacement along x and z (the twists bicubic interpolation needs).
    pub twist: [Vec<f64>; 3],
    /// Linear theory's water velocity `(x, y, z)` at the node, m/s: on the
    /// mean level at the node's rest position as a fixed point, and the
    /// velocity of the particle resting there at choppiness 1 (its
    /// horizontal part does not scale with the choppiness).
    pub velocity: [Vec<f64>; 3],
}

/// A surface particle as [`SeaFields::particle_at`] gives it: its
/// position (m), the Jacobian of its horizontal position over its rest
/// position, and its elevation's gradient over its rest position.
pub type ParticleJet = ([f64; 3], [[f64; 2]; 2], [f64; 2]);

impl SeaFields {
    /// The surface particle resting on node `(ix, iz)`: its position, m.
    pub fn particle(&self, ix: usize, iz: usize) -> [f64; 3] {
        let i = iz * self.cells + ix;
        let d = self.size / self.cells as f64;
        [
            ix as f64 * d + self.displacement[0][i],
            self.level + self.height[i],
            iz as f64 * d + self.displacement[1][i],
        ]
    }

    /// The cell of the tile rest position `(x0, z0)` (m, taken into the
    /// tile) lies in, `(ix, iz)`, and the fractions `(u, v)` across it.
    pub(crate) fn cell(&self, x0: f64, z0: f64) -> ([usize; 2], [f64; 2]) {
        let n = self.cells;
        let d = self.size / n as f64;
        // The cell and fraction along one axis: the fraction exact
        // (`g − ⌊g⌋`), the index wrapped into the tile.
        let axis = |g: f64| {
            let f = g.floor();
            let i = if f.abs() < 9.0e15 {
                (f as i64).rem_euclid(n as i64) as usize
            } else {
                0
            };
            (i.min(n - 1), (g - f).clamp(0.0, 1.0))
        };
        let (ix, u) = axis(x0 / d);
        let (iz, v) = axis(z0 / d);
        ([ix, iz], [u, v])
    }

    /// The fields the bicubic Hermite interpolants are made of: per
    /// interpolated field (the elevation, the displacement along x and
    /// along z) its values, its gradient along x and z and its twist at
    /// the nodes.
    fn interpolated(&self) -> [[&[f64]; 4]; 3] {
        let [hx, hz] = &self.height_gradient;
        let [dxx, dxz, dzz] = &self.displacement_gradient;
        let [txz, tdx, tdz] = &self.twist;
        [
            [&self.height, hx, hz, txz],
            [&self.displacement[0], dxx, dxz, tdx],
            [&self.displacement[1], dxz, dzz, tdz],
        ]
    }

    /// The bicubic Hermite interpolants of the elevation and of the
    /// displacement along x and z (their values, gradients and twists at
    /// the nodes) at rest position `(x0, z0)` (m, taken into the tile):
    /// per field its value and its gradient over the rest position, the
    /// cell and its basis found once for the three.
    fn hermite3(&self, x0: f64, z0: f64) -> [(f64, [f64; 2]); 3] {
        let n = self.cells;
        let d = self.size / n as f64;
        let ([ix, iz], [u, v]) = self.cell(x0, z0);
        let ((bu, du, _), (bv, dv, _)) = (hermite_basis(u), hermite_basis(v));
        let fields = self.interpolated();
        let mut out = [(0.0, [0.0; 2]); 3];
        let corner = corners(ix, iz, n);
        for (k, (a, b)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
            let i = corner[k];
            // The corner's four basis products, and their u- and
            // v-derivatives.
            let w = [
                bu[a] * bv[b],
                bu[a + 2] * bv[b],
                bu[a] * bv[b + 2],
                bu[a + 2] * bv[b + 2],
            ];
            let wu = [
                du[a] * bv[b],
                du[a + 2] * bv[b],
                du[a] * bv[b + 2],
                du[a + 2] * bv[b + 2],
            ];
            let wv = [
                bu[a] * dv[b],
                bu[a + 2] * dv[b],
                bu[a] * dv[b + 2],
                bu[a + 2] * dv[b + 2],
            ];
            for ([f, fx, fz, fxz], (value, [ddu, ddv])) in fields.iter().zip(out.iter_mut()) {
                // Derivatives over the rest position, in cells.
                let c = [f[i], fx[i] * d, fz[i] * d, fxz[i] * d * d];
                *value += c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3];
                *ddu += c[0] * wu[0] + c[1] * wu[1] + c[2] * wu[2] + c[3] * wu[3];
                *ddv += c[0] * wv[0] + c[1] * wv[1] + c[2] * wv[2] + c[3] * wv[3];
            }
        }
        out.map(|(value, [ddu, ddv])| (value, [ddu / d, ddv / d]))
    }

    /// The second derivatives over the rest position `[∂²/∂x₀², ∂²/∂x₀∂z₀,
    /// ∂²/∂z₀²]` (1/m for the elevation's, likewise the displacements') of
    /// the bicubic Hermite interpolants of the elevation and of the
    /// displacement along x and z at rest position `(x0, z0)` (m).
    pub(crate) fn second_derivatives(&self, x0: f64, z0: f64) -> [[f64; 3]; 3] {
        let n = self.cells;
        let d = self.size / n as f64;
        let ([ix, iz], [u, v]) = self.cell(x0, z0);
        let ((bu, du, eu), (bv, dv, ev)) = (hermite_basis(u), hermite_basis(v));
        let fields = self.interpolated();
        let mut out = [[0.0; 3]; 3];
        let corner = corners(ix, iz, n);
        for (k, (a, b)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
            let i = corner[k];
            // The corner's four basis products' uu, uv and vv derivatives.
            let pair = |p: &[f64; 4], q: &[f64; 4]| {
                [p[a] * q[b], p[a + 2] * q[b], p[a] * q[b + 2], p[a + 2] * q[b + 2]]
            };
            let (wuu, wuv, wvv) = (pair(&eu, &bv), pair(&du, &dv), pair(&bu, &ev));
            for ([f, fx, fz, fxz], o) in fields.iter().zip(out.iter_mut()) {
                // Derivatives over the rest position, in cells.
                let c = [f[i], fx[i] * d, fz[i] * d, fxz[i] * d * d];
                let dot = |w: &[f64; 4]| c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3];
                o[0] += dot(&wuu);
                o[1] += dot(&wuv);
                o[2] += dot(&wvv);
            }
        }
        let d2 = d * d;
        out.map(|o| o.map(|x| x / d2))
    }

    /// The surface particle at rest at any `(x0, z0)` (m; the fields'
    /// bicubic Hermite interpolants between the nodes): where it is (m),
    /// the Jacobian `[[∂x/∂x₀, ∂x/∂z₀], [∂z/∂x₀, ∂z/∂z₀]]` of its
    /// horizontal position over its rest position, and the gradient of its
    /// elevation over its rest position.
    pub fn particle_at(&self, x0: f64, z0: f64) -> ParticleJet {
        let [(h, gh), (dx, gdx), (dz, gdz)] = self.hermite3(x0, z0);
        (
            [x0 + dx, self.level + h, z0 + dz],
            [[1.0 + gdx[0], gdx[1]], [gdz[0], 1.0 + gdz[1]]],
            gh,
        )
    }

    /// The rest position of the surface particle above world `(x, z)` (m),
    /// by Newton's method on the interpolated displacement from the guess
    /// that the particle is displaced by `shift` (m).
    pub fn rest_position(&self, x: f64, z: f64, shift: [f64; 2]) -> [f64; 2] {
        self.invert(x, z, shift).0
    }

    /// [`SeaFields::rest_position`] with the particle there
    /// ([`SeaFields::particle_at`]'s answer at the rest position found).
    pub fn invert(&self, x: f64, z: f64, shift: [f64; 2]) -> ([f64; 2], ParticleJet) {
        let (mut x0, mut z0) = (x - shift[0], z - shift[1]);
        for _ in 0..16 {
            let jet = self.particle_at(x0, z0);
            let (p, j) = (jet.0, jet.1);
            let (rx, rz) = (p[0] - x, p[2] - z);
            if rx.abs() + rz.abs() < 1e-12 * (1.0 + x.abs() + z.abs()) {
                return ([x0, z0], jet);
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let (dx, dz) = if det > 1e-3 {
                (
                    (j[1][1] * rx - j[0][1] * rz) / det,
                    (j[0][0] * rz - j[1][0] * rx) / det,
                )
            } else {
                (rx, rz)
            };
            x0 -= dx;
            z0 -= dz;
        }
        ([x0, z0], self.particle_at(x0, z0))
    }

    /// The realised significant height `4 √⟨η²⟩` over the tile's nodes, m.
    pub fn significant_height(&self) -> f64 {
        let m0 = self.height.iter().map(|h| h * h).sum::<f64>() / self.height.len() as f64;
        4.0 * m0.sqrt()
    }
}

impl SpectralSea {
    /// The sea `spectrum` realised on a tile `size` m across of `cells`
    /// nodes a side, from `seed`, at mean `level` (m), choppiness 1, under
    /// `gravity` (m/s²).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for an invalid spectrum, level, size or
    /// gravity, or `cells` not a power of two within [`SEA_CELLS`].
    pub fn realize(
        spectrum: &SeaSpectrum,
        level: f64,
        size: f64,
        cells: usize,
        seed: u64,
        gravity: f64,
    ) -> Result<Self, WaterError> {
        spectrum.validate()?;
        check_tile(level, size, cells, gravity)?;
        let n = cells;
        let dk = std::f64::consts::TAU / size;
        let (scale, wp) = (spectrum.scale(), spectrum.peak_frequency());
        let spreading = spectrum.spreading_function();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut amplitudes = vec![Complex::default(); n * n];
        for (i, a) in amplitudes.iter_mut().enumerate() {
            // Two normal deviates per mode, drawn for every mode in order
            // (the Nyquist row and column and k = 0 included) so that the
            // sea of a seed does not depend on which modes carry energy.
            let (u1, u2): (f64, f64) = (rng.random(), rng.random());
            let r = (-2.0 * (1.0 - u1).ln()).sqrt();
            let (sn, cs) = (std::f64::consts::TAU * u2).sin_cos();
            let (nx, nz) = (signed(i % n, n), signed(i / n, n));
            if nx == -(n as i64) / 2 || nz == -(n as i64) / 2 || (nx == 0 && nz == 0) {
                continue;
            }
            let k = Vector2::new(nx as f64, nz as f64) * dk;
            let kk = k.norm();
            let omega = (gravity * kk).sqrt();
            // S(kx, kz) = S(ω) D(θ) (dω/dk) / k, dω/dk = g / (2ω).
            let d = spreading(k.y.atan2(k.x));
            let density = scale * spectrum.unscaled(omega / wp) * d * gravity / (2.0 * omega * kk);
            // E|A|² = 2 S Δk²: each of the two parts has variance S Δk².
            let sigma = (density * dk * dk).sqrt();
            *a = Complex::new(sigma * r * cs, sigma * r * sn);
        }
        Ok(Self::of_amplitudes(level, size, cells, gravity, amplitudes))
    }

    /// A sea given mode by mode on a tile `size` m across of `cells` nodes
    /// a side, at mean `level` (m), choppiness 1, under `gravity` (m/s²).
    ///
    /// # Errors
    /// As [`SpectralSea::realize`], and [`WaterError::Mode`] naming a mode
    /// outside the grid (or its Nyquist row or column), the mean `n = l =
    /// 0` (no wave: the mean height is `level`), or with an amplitude or
    /// phase that is not finite (or a negative amplitude).
    pub fn from_modes(
        level: f64,
        size: f64,
        cells: usize,
        modes: &[SeaMode],
        gravity: f64,
    ) -> Result<Self, WaterError> {
        check_tile(level, size, cells, gravity)?;
        let half = (cells / 2) as i32;
        let mut amplitudes = vec![Complex::default(); cells * cells];
        for (index, m) in modes.iter().enumerate() {
            let bad = |field, value| WaterError::Mode { index, field, value };
            if m.n.abs() >= half {
                return Err(bad("n", m.n as f64));
            }
            if m.l.abs() >= half {
                return Err(bad("l", m.l as f64));
            }
            if m.n == 0 && m.l == 0 {
                return Err(bad("n and l (the mean; set the level instead)", 0.0));
            }
            if !(m.amplitude.is_finite() && m.amplitude >= 0.0) {
                return Err(bad("amplitude", m.amplitude));
            }
            if !m.phase.is_finite() {
                return Err(bad("phase", m.phase));
            }
            let ix = m.n.rem_euclid(cells as i32) as usize;
            let iz = m.l.rem_euclid(cells as i32) as usize;
            amplitudes[iz * cells + ix] += Complex::from_polar(m.amplitude, m.phase);
        }
        Ok(Self::of_amplitudes(level, size, cells, gravity, amplitudes))
    }

    /// The sea of `amplitudes` (checked tile), choppiness 1.
    fn of_amplitudes(
        level: f64,
        size: f64,
        cells: usize,
        gravity: f64,
        amplitudes: Vec<Complex<f64>>,
    ) -> Self {
        Self {
            level,
            size,
            cells,
            choppiness: 1.0,
            gravity,
            amplitudes,
            fft: Fft2::new(cells),
            stationary: std::sync::OnceLock::new(),
        }
    }

    /// The same sea with choppiness `lambda` (0 to 1 keeps most seas from
    /// folding over; a fold is where the displacement's Jacobian
    /// `det(I + ∇D)` falls to 0).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] for a negative or non-finite `lambda`.
    pub fn with_choppiness(mut self, lambda: f64) -> Result<Self, WaterError> {
        if !(lambda.is_finite() && lambda >= 0.0) {
            return Err(WaterError::Parameter {
                name: "choppiness",
                value: lambda,
            });
        }
        self.choppiness = lambda;
        Ok(self)
    }

    /// The same sea without its waves of two cells of a `cells` grid or
    /// shorter: the modes of wavenumber `|k| < π cells / size` (wavelength
    /// longer than `2 size / cells`), each with its amplitude and phase,
    /// realised on a tile of `cells` nodes a side (the coarsest grid that
    /// holds them). A body over which the shorter waves average out reads
    /// it at a fraction of the cost ([`SeaBand`](crate::SeaBand)).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] (`"band cells"`) when `cells` is not a
    /// power of two within [`SEA_CELLS`] or is more than the sea's own.
    pub fn low_pass(&self, cells: usize) -> Result<Self, WaterError> {
        if !(cells.is_power_of_two() && SEA_CELLS.contains(&cells) && cells <= self.cells) {
            return Err(WaterError::Parameter {
                name: "band cells",
                value: cells as f64,
            });
        }
        let (n, c) = (self.cells, cells);
        // |k| < π c / size ⇔ n² + l² < (c/2)², in units of 2π/size.
        let limit = (c / 2) as i64 * (c / 2) as i64;
        let mut amplitudes = vec![Complex::default(); c * c];
        for (i, a) in self.amplitudes.iter().enumerate() {
            let (nx, nz) = (signed(i % n, n), signed(i / n, n));
            if nx * nx + nz * nz < limit {
                let (ix, iz) = (nx.rem_euclid(c as i64) as usize, nz.rem_euclid(c as i64) as usize);
                amplitudes[iz * c + ix] = *a;
            }
        }
        let mut sea = Self::of_amplitudes(self.level, self.size, c, self.gravity, amplitudes);
        sea.choppiness = self.choppiness;
        Ok(sea)
    }

    /// The complex amplitude of mode `(n, l)`, m (0 outside the grid).
    pub fn amplitude(&self, n: i64, l: i64) -> Complex<f64> {
        let c = self.cells as i64;
        if n.abs() >= c / 2 || l.abs() >= c / 2 {
            return Complex::default();
        }
        self.amplitudes[(l.rem_euclid(c) * c + n.rem_euclid(c)) as usize]
    }

    /// Every mode with energy as a [`SeaMode`] (its indices, amplitude and
    /// phase): [`SpectralSea::from_modes`] of them on a finer grid is the
    /// same sea evaluated at more nodes.
    pub fn sea_modes(&self) -> Vec<SeaMode> {
        let n = self.cells;
        self.amplitudes
            .iter()
            .enumerate()
            .filter(|(_, a)| a.norm_sqr() > 0.0)
            .map(|(i, a)| SeaMode {
                n: signed(i % n, n) as i32,
                l: signed(i / n, n) as i32,
                amplitude: a.norm(),
                phase: a.arg(),
            })
            .collect()
    }

    /// The tile's frequency resolution at `omega` (rad/s): how far apart
    /// in frequency its neighbouring wavenumbers are there, `dω/dk · Δk =
    /// g/(2ω) · 2π/size` (deep water).
    pub fn frequency_resolution(&self, omega: f64) -> f64 {
        self.gravity / (2.0 * omega) * std::f64::consts::TAU / self.size
    }

    /// The realised sea's frequency spectrum, m²·s/rad (as
    /// [`SeaSpectrum::density`]): its modes' variance `|A|²/2` summed in
    /// `bins` bins `bin` rad/s wide from ω = 0, over the bin's width.
    /// Averaged over seeds it is the target's density averaged over each
    /// bin (with one seed, a periodogram: each bin scattered about it).
    pub fn frequency_spectrum(&self, bin: f64, bins: usize) -> Vec<f64> {
        let mut density = vec![0.0; bins];
        for (_, omega, a2) in self.modes() {
            let b = (omega / bin) as usize;
            if b < bins {
                density[b] += 0.5 * a2 / bin;
            }
        }
        density
    }

    /// Every wave with energy: its wavenumber `(kx, kz)` (rad/m), its
    /// angular frequency (rad/s) and `|A|²` (m²), row by row; the modes
    /// [`SpectralSea::fields`] transforms (not the mean, `k = 0`, which
    /// moves no water).
    pub fn modes(&self) -> impl Iterator<Item = ([f64; 2], f64, f64)> + '_ {
        let stationary = self.stationary();
        (0..stationary.modes.len()).map(move |j| {
            let m = &stationary.modes[j].1;
            (m.k, m.omega, m.a.norm_sqr())
        })
    }

    /// What of each mode with an amplitude does not change with time:
    /// the kept one where it fits the tile's size and gravity as they are
    /// now, else made anew.
    fn stationary(&self) -> Cow<'_, Stationary> {
        match self.stationary.get_or_init(|| Stationary::of(self)) {
            s if s.fits(self) => Cow::Borrowed(s),
            _ => Cow::Owned(Stationary::of(self)),
        }
    }

    /// The whole tile at time `t` (s): seven inverse transforms of
    /// `cells²`, two real fields each (the elevation, the displacement,
    /// their gradients and twists, and the particles' velocity).
    pub fn fields(&self, t: f64) -> SeaFields {
        let n = self.cells;
        let lambda = self.choppiness;
        let turned = self.turned(t);
        let i = Complex::i();
        let turned = &turned[..];
        // The seven transforms, two real fields each, in parallel: each
        // on one thread, so that the result does not depend on how many.
        let transform = |which: usize| {
            let mut data = match which {
                0 => hermitian_pair(turned, n, |m| m.a, |m| -i * m.omega * m.a),
                1 => hermitian_pair(
                    turned,
                    n,
                    |m| i * lambda * m.unit[0] * m.a,
                    |m| i * lambda * m.unit[1] * m.a,
                ),
                2 => hermitian_pair(turned, n, |m| i * m.k[0] * m.a, |m| i * m.k[1] * m.a),
                3 => hermitian_pair(
                    turned,
                    n,
                    |m| -lambda * m.unit[0] * m.k[0] * m.a,
                    |m| -lambda * m.unit[1] * m.k[1] * m.a,
                ),
                4 => hermitian_pair(
                    turned,
                    n,
                    |m| -lambda * m.unit[0] * m.k[1] * m.a,
                    |m| -m.k[0] * m.k[1] * m.a,
                ),
                5 => hermitian_pair(
                    turned,
                    n,
                    |m| -i * lambda * m.unit[0] * m.k[0] * m.k[1] * m.a,
                    |m| -i * lambda * m.unit[1] * m.k[0] * m.k[1] * m.a,
                ),
                // Linear theory's water velocity at the node as a fixed
                // point (the particle's at choppiness 1), whatever the
                // choppiness.
                _ => hermitian_pair(
                    turned,
                    n,
                    |m| m.omega * m.unit[0] * m.a,
                    |m| m.omega * m.unit[1] * m.a,
                ),
            };
            let mut scratch = vec![Complex::default(); n * n];
            self.fft.process_serial(&mut data, false, &mut scratch);
            data.into_iter()
                .map(|c| (c.re, c.im))
                .unzip::<f64, f64, Vec<f64>, Vec<f64>>()
        };
        let mut out: Vec<(Vec<f64>, Vec<f64>)> = (0..7).into_par_iter().map(transform).collect();
        let mut next = || out.remove(0);
        let (height, vy) = next();
        let (dx, dz) = next();
        let (hx, hz) = next();
        let (dxx, dzz) = next();
        let (dxz, hxz) = next();
        let (dx_xz, dz_xz) = next();
        let (vx, vz) = next();
        SeaFields {
            time: t,
            level: self.level,
            size: self.size,
            cells: n,
            height,
            displacement: [dx, dz],
            height_gradient: [hx, hz],
            displacement_gradient: [dxx, dxz, dzz],
            twist: [hxz, dx_xz, dz_xz],
            velocity: [vx, vy, vz],
        }
    }

    /// Every mode at time `t` (s), at its index: `A e^{−iωt}`, `k`, `k̂`
    /// and `ω` (all zero for the mean and for modes of no amplitude).
    fn turned(&self, t: f64) -> Vec<Turned> {
        let n = self.cells;
        // What does not change with time is made once (again, should the
        // tile's size or gravity have been changed since): per mode with
        // an amplitude, only `A e^{−iωt}` is made here, the rows in
        // parallel.
        let stationary = self.stationary();
        let mut turned = vec![Turned::default(); n * n];
        turned.par_chunks_mut(n).enumerate().for_each(|(lz, row)| {
            let modes = &stationary.modes[stationary.rows[lz]..stationary.rows[lz + 1]];
            for &(lx, m) in modes {
                row[lx] = Turned {
                    a: m.a * Complex::from_polar(1.0, -m.omega * t),
                    ..m
                };
            }
        });
        turned
    }

    /// Every mode's amplitude turned to time `t` (s), `A e^{−iωt}` (m), at
    /// its index: what [`SpectralSea::fields`] transforms (the GPU's read
    /// of the sea transforms it on the device).
    #[cfg(feature = "gpu")]
    pub(crate) fn turned_amplitudes(&self, t: f64) -> Vec<Complex<f64>> {
        self.turned(t).into_iter().map(|m| m.a).collect()
    }
}

/// The nodes at the corners `(0, 0)`, `(1, 0)`, `(0, 1)` and `(1, 1)` of
/// cell `(ix, iz)` of a tile of `n` cells a side, wrapped into it.
pub(super) fn corners(ix: usize, iz: usize, n: usize) -> [usize; 4] {
    let (ix1, iz1) = (
        if ix + 1 == n { 0 } else { ix + 1 },
        if iz + 1 == n { 0 } else { iz + 1 },
    );
    [iz * n + ix, iz * n + ix1, iz1 * n + ix, iz1 * n + ix1]
}

/// The cubic Hermite basis on [0, 1] at `t` (value at 0, value at 1,
/// slope at 0, slope at 1), its first and its second derivatives.
fn hermite_basis(t: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    (
        [
            2.0 * t3 - 3.0 * t2 + 1.0,
            -2.0 * t3 + 3.0 * t2,
            t3 - 2.0 * t2 + t,
            t3 - t2,
        ],
        [
            6.0 * t2 - 6.0 * t,
            -6.0 * t2 + 6.0 * t,
            3.0 * t2 - 4.0 * t + 1.0,
            3.0 * t2 - 2.0 * t,
        ],
        [12.0 * t - 6.0, -12.0 * t + 6.0, 6.0 * t - 4.0, 6.0 * t - 2.0],
    )
}

/// One mode at the time of [`SpectralSea::fields`]: `A e^{−iωt}` (m), `k`
/// (rad/m), `k̂` and `ω` (rad/s).
#[derive(Clone, Copy, Default)]
struct Turned {
    a: Complex<f64>,
    k: [f64; 2],
    unit: [f64; 2],
    omega: f64,
}

/// The coefficients whose transform is `F + i G`, `F` and `G` the real
/// fields of the modes' coefficients `f` and `g`: `F = Re Σ c_k e^{ik·x}`
/// has the Hermitian coefficients `½ (c_k + conj(c_{−k}))`, so `F + i G`
/// is the transform of `F̂ + i Ĝ` (no energy on the Nyquist row and
/// column, so `−k` of every mode is on the grid). Row by row: the mode
/// opposite `(lx, lz)` is `(−lx, −lz)` taken into the tile, found without
/// a division.
fn hermitian_pair<F, G>(turned: &[Turned], n: usize, f: F, g: G) -> Vec<Complex<f64>>
where
    F: Fn(&Turned) -> Complex<f64>,
    G: Fn(&Turned) -> Complex<f64>,
{
    let i = Complex::<f64>::i();
    let mut data = vec![Complex::new(0.0, 0.0); n * n];
    for lz in 0..n {
        let row = lz * n;
        let opposite_row = ((n - lz) % n) * n;
        for lx in 0..n {
            let opposite = if lx == 0 { 0 } else { n - lx };
            let (k, ko) = (row + lx, opposite_row + opposite);
            // The opposite mode's coefficients are the conjugates of this
            // one's: each pair is evaluated once, from its first mode.
            if ko < k {
                continue;
            }
            let (m, o) = (&turned[k], &turned[ko]);
            let (fm, fo, gm, go) = (f(m), f(o), g(m), g(o));
            let (a, b) = (0.5 * (fm + fo.conj()), 0.5 * (gm + go.conj()));
            data[k] = a + i * b;
            if ko != k {
                data[ko] = a.conj() + i * b.conj();
            }
        }
    }
    data
}

/// Transform index `i` of `n` as a signed wavenumber index.
fn signed(i: usize, n: usize) -> i64 {
    if i < n / 2 { i as i64 } else { i as i64 - n as i64 }
}

fn check_tile(level: f64, size: f64, cells: usize, gravity: f64) -> Result<(), WaterError> {
    let checks = [
        ("level", level, true),
        ("tile", size, size > 0.0),
        ("gravity", gravity, gravity > 0.0),
        (
            "cells",
            cells as f64,
            cells.is_power_of_two() && SEA_CELLS.contains(&cells),
        ),
    ];
    for (name, value, ok) in checks {
        if !(value.is_finite() && ok) {
            return Err(WaterError::Parameter { name, value });
        }
    }
    Ok(())
}
