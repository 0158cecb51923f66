//! A [`SpectralSea`] as a water surface: the tile evaluated once per time
//! for every reader, the choppy map inverted between its nodes.

use std::sync::{Arc, OnceLock, RwLock};

use nalgebra::{Point3, Vector3};

use super::surface::{fill_nodes, node_at};
use super::{SEA_CELLS, SeaFields, SpectralSea, Surface, SurfaceNode};

/// How far (m, the sum of the horizontal distances) the particle read by
/// [`Surface::heights_near`] may miss its point before it is read again a
/// Newton step on: its height carried along the slope is then off by
/// `½ |f''|` times this squared at most (`f''` the surface's second
/// derivatives): a few tenths of a micrometre on the bench's sea.
const NEAR_MISS: f64 = 1e-2;

/// A spectral sea as a [`Surface`], repeating with its tile's period.
///
/// The tile's fields are evaluated once per time (seven inverse FFTs)
/// and kept until a read at another time: every body of a step reads the
/// same evaluation. Above a horizontal point the surface is the particle
/// whose rest position the choppy map takes there, found by Newton's
/// method on the bicubic Hermite interpolants of the displacement and
/// elevation between the tile's nodes (from their exact gradients and
/// twists); the interpolation's error falls as the fourth power of the
/// node spacing against a wavelength, and is measured against the exact
/// sum over the modes in the tests.
///
/// The fluid's velocity at a point is linear theory's, as on a Gerstner
/// sea: the sum over the modes at the point's own (Eulerian) phase — the
/// tile's velocity field read at the point itself, not at the rest
/// position of the particle above it — decaying below the mean level as
/// `e^{k̄ (y − level)}` with `k̄` the sea's energy-weighted mean wavenumber
/// (each mode decays with its own `k` in linear theory: this is the
/// one-wavenumber approximation of that sum), continued linearly above the
/// mean level up to the surface (`1 + k̄ (y − level)`), and above the
/// surface the surface's. Its mean at a point below the troughs is zero,
/// and what it carries drifts forward at about the sea's Stokes drift
/// ([`SpectralSurface::stokes_drift`]).
pub struct SpectralSurface {
    sea: SpectralSea,
    /// The energy-weighted mean wavenumber, rad/m.
    mean_wavenumber: f64,
    /// The fields of the last times read, oldest first.
    fields: RwLock<Vec<Arc<SeaFields>>>,
    /// The sea without its shorter waves, built on the first read that
    /// asks for it ([`Surface::band_limited`]): entry `L − 1` on a grid of
    /// `cells / 2^L` nodes a side, down to 8.
    bands: Vec<OnceLock<SpectralSurface>>,
}

impl Clone for SpectralSurface {
    fn clone(&self) -> Self {
        Self::new(self.sea.clone())
    }
}

impl std::fmt::Debug for SpectralSurface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpectralSurface")
            .field("sea", &self.sea)
            .finish_non_exhaustive()
    }
}

impl SpectralSurface {
    /// The surface of `sea`.
    pub fn new(sea: SpectralSea) -> Self {
        let (mut energy, mut weighted) = (0.0, 0.0);
        for (k, _, a2) in sea.modes() {
            energy += a2;
            weighted += a2 * k[0].hypot(k[1]);
        }
        let levels = (sea.cells / *SEA_CELLS.start()).max(1).ilog2() as usize;
        Self {
            mean_wavenumber: if energy > 0.0 { weighted / energy } else { 0.0 },
            sea,
            fields: RwLock::new(Vec::new()),
            bands: (0..levels).map(|_| OnceLock::new()).collect(),
        }
    }

    /// The sea without its waves of `2^level` cells of its tile or shorter
    /// ([`SpectralSea::low_pass`] to `cells / 2^level` nodes a side), as a
    /// surface, built on the first call and kept; `None` for level 0 (the
    /// sea itself) or past the coarsest grid (8 nodes a side).
    pub fn band(&self, level: usize) -> Option<&SpectralSurface> {
        let slot = self.bands.get(level.checked_sub(1)?)?;
        Some(slot.get_or_init(|| {
            let sea = self
                .sea
                .low_pass(self.sea.cells >> level)
                .expect("a band's grid is a power of two within the sea's");
            SpectralSurface::new(sea)
        }))
    }

    /// The band [`Surface::band_limited`] reads for waves at least
    /// `wavelength` (m) long: the coarsest level whose shortest wave
    /// (`2^level` times the tile's, two of its cells) is at most
    /// `wavelength`; 0 (the whole sea) when even the first level's is
    /// longer.
    pub fn band_level(&self, wavelength: f64) -> usize {
        let shortest = 2.0 * self.sea.size / self.sea.cells as f64;
        let mut level = 0;
        while level < self.bands.len() && shortest * (1u64 << (level + 1)) as f64 <= wavelength {
            level += 1;
        }
        level
    }

    /// The sea.
    pub fn sea(&self) -> &SpectralSea {
        &self.sea
    }

    /// The energy-weighted mean wavenumber (1/m) the fluid's velocity
    /// decays with below the mean level.
    #[cfg(feature = "gpu")]
    pub(crate) fn mean_wavenumber(&self) -> f64 {
        self.mean_wavenumber
    }

    /// The tile's fields at time `t` (s): evaluated on the first read at
    /// `t` and shared by every later read at `t`, the last
    /// [`SpectralSurface::KEPT`] times kept (a step reads its own time, and
    /// a time-centred derivative two more).
    pub fn fields(&self, t: f64) -> Arc<SeaFields> {
        let find = |kept: &[Arc<SeaFields>]| kept.iter().find(|f| f.time == t).map(Arc::clone);
        if let Some(f) = find(&self.fields.read().unwrap_or_else(|e| e.into_inner())) {
            return f;
        }
        // Evaluated outside the lock: the transforms run on the thread
        // pool, and a thread waiting for them may take up another read of
        // this surface, which must not find the lock held. Two first reads
        // at once may both evaluate it; the first kept is shared.
        let f = Arc::new(self.sea.fields(t));
        let mut kept = self.fields.write().unwrap_or_else(|e| e.into_inner());
        if let Some(f) = find(&kept) {
            return f;
        }
        if kept.len() >= Self::KEPT {
            kept.remove(0);
        }
        kept.push(Arc::clone(&f));
        f
    }

    /// How many times' fields are kept.
    pub const KEPT: usize = 4;

    /// The sea's Stokes drift at mean height `y` (m), m/s: `Σ a² ω k
    /// e^{2k (y − level)}` along each mode's direction, over its modes
    /// (deep water; at the mean level and above, `Σ a² ω k`).
    pub fn stokes_drift(&self, y: f64) -> Vector3<f64> {
        let below = (y - self.sea.level).min(0.0);
        let mut v = Vector3::zeros();
        for (k, omega, a2) in self.sea.modes() {
            let kk = k[0].hypot(k[1]);
            let speed = a2 * omega * (2.0 * kk * below).exp();
            v.x += speed * k[0];
            v.z += speed * k[1];
        }
        v
    }

    /// The water's velocity at `(point, y)`, `point` its horizontal
    /// position (m) and `y` its height, taken at most the surface's.
    fn velocity_at(&self, f: &SeaFields, point: [f64; 2], y: f64) -> Vector3<f64> {
        Self::orbital(f, point) * self.decay(f, y)
    }

    /// The velocity at the mean level under `point`, bilinear between the
    /// tile's nodes.
    fn orbital(f: &SeaFields, point: [f64; 2]) -> Vector3<f64> {
        let [vx, vy, vz] = &f.velocity;
        let n = f.cells;
        let ([ix, iz], [u, v]) = f.cell(point[0], point[1]);
        let [c00, c10, c01, c11] = super::spectrum::corners(ix, iz, n);
        let at =
            |c: &[f64]| (1.0 - v) * ((1.0 - u) * c[c00] + u * c[c10]) + v * ((1.0 - u) * c[c01] + u * c[c11]);
        Vector3::new(at(vx), at(vy), at(vz))
    }

    /// The velocity's factor at height `y` (m) against the mean level's.
    fn decay(&self, f: &SeaFields, y: f64) -> f64 {
        let z = self.mean_wavenumber * (y - f.level);
        if z > 0.0 { 1.0 + z } else { z.exp() }
    }
}

impl Surface for SpectralSurface {
    fn height(&self, x: f64, z: f64, t: f64) -> f64 {
        let f = self.fields(t);
        f.invert(x, z, [0.0, 0.0]).1.0[1]
    }

    fn probe(
        &self,
        p: &Point3<f64>,
        t: f64,
        with_velocity: bool,
        hint: &mut [f64; 2],
    ) -> (f64, Vector3<f64>) {
        let f = self.fields(t);
        let (rest, particle) = f.invert(p.x, p.z, *hint);
        *hint = [p.x - rest[0], p.z - rest[1]];
        let height = particle.0[1];
        let v = if with_velocity {
            self.velocity_at(&f, [p.x, p.z], p.y.min(height))
        } else {
            Vector3::zeros()
        };
        (height - p.y, v)
    }

    /// The tile looked up once for every point.
    fn heights_at(&self, points: &[[f64; 2]], t: f64, hint: &mut [f64; 2], out: &mut [f64]) {
        let f = self.fields(t);
        for (&[x, z], h) in points.iter().zip(out.iter_mut()) {
            let (rest, particle) = f.invert(x, z, *hint);
            *hint = [x - rest[0], z - rest[1]];
            *h = particle.0[1];
        }
    }

    /// Each point's particle guessed from the centre's (its rest position
    /// moved by the centre's Jacobian inverted times the point's offset),
    /// read once (twice, a Newton step on, where the first read misses the
    /// point by more than a centimetre), and its height carried to the
    /// point along its slope: one read of the tile's interpolants a point
    /// for a body of a metre where its inversion takes about three. A
    /// point the guess misses by more than a quarter of its offset (a
    /// choppy map near folding) is inverted.
    fn heights_near(
        &self,
        centre: [f64; 2],
        points: &[[f64; 2]],
        t: f64,
        hint: &mut [f64; 2],
        out: &mut [f64],
    ) {
        let f = self.fields(t);
        let rest = [centre[0] - hint[0], centre[1] - hint[1]];
        let (p, j, _) = f.particle_at(rest[0], rest[1]);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        for (&[x, z], h) in points.iter().zip(out.iter_mut()) {
            let (dx, dz) = (x - p[0], z - p[2]);
            let near = (det > 1e-3)
                .then(|| {
                    let mut guess = [
                        rest[0] + (j[1][1] * dx - j[0][1] * dz) / det,
                        rest[1] + (j[0][0] * dz - j[1][0] * dx) / det,
                    ];
                    // A second read, a Newton step on, where the first
                    // missed by more than a centimetre (a large body).
                    for _ in 0..2 {
                        let (q, jq, gq) = f.particle_at(guess[0], guess[1]);
                        let miss = [x - q[0], z - q[2]];
                        let off = miss[0].abs() + miss[1].abs();
                        if off > 0.25 * (dx.abs() + dz.abs()) {
                            return None;
                        }
                        let dq = jq[0][0] * jq[1][1] - jq[0][1] * jq[1][0];
                        if off <= NEAR_MISS || dq <= 1e-3 {
                            let s = slope_through(&jq, &gq);
                            return Some(q[1] + s[0] * miss[0] + s[1] * miss[1]);
                        }
                        guess[0] += (jq[1][1] * miss[0] - jq[0][1] * miss[1]) / dq;
                        guess[1] += (jq[0][0] * miss[1] - jq[1][0] * miss[0]) / dq;
                    }
                    None
                })
                .flatten();
            *h = near.unwrap_or_else(|| f.invert(x, z, *hint).1.0[1]);
        }
    }

    /// Every node's twist, from the tile's interpolants.
    fn node_twists(&self) -> bool {
        true
    }

    /// The tile looked up once for every node; each node's inversion
    /// starts from the displacement of the one before it, and gives the
    /// slope with the height.
    fn sample_nodes(
        &self,
        t: f64,
        origin: [f64; 2],
        spacing: f64,
        nodes: [usize; 2],
        out: &mut [SurfaceNode],
    ) {
        let f = self.fields(t);
        fill_nodes(origin, spacing, nodes, out, |x, z, hint| {
            let (rest, (p, jac, g)) = f.invert(x, z, *hint);
            *hint = [x - rest[0], z - rest[1]];
            let slope = slope_through(&jac, &g);
            SurfaceNode {
                height: p[1],
                slope,
                hint: *hint,
                twist: Some(twist_through(
                    &jac,
                    slope,
                    &f.second_derivatives(rest[0], rest[1]),
                )),
            }
        });
    }

    /// Evaluates the tile at `t` (its seven transforms in parallel), and
    /// those of the bands read before.
    fn prepare(&self, t: f64) {
        let _ = self.fields(t);
        for band in self.bands.iter().filter_map(OnceLock::get) {
            band.prepare(t);
        }
    }

    /// The sea on the coarsest grid whose shortest wave is at most
    /// `wavelength` ([`SpectralSurface::band_level`]): the modes shorter
    /// than two of its cells dropped, the rest as they are.
    fn band_limited(&self, wavelength: f64) -> Option<&dyn Surface> {
        if !wavelength.is_finite() {
            return None;
        }
        self.band(self.band_level(wavelength)).map(|b| b as &dyn Surface)
    }

    fn velocity_under(&self, p: &Point3<f64>, t: f64, height: f64, _hint: &[f64; 2]) -> Vector3<f64> {
        self.velocity_at(&self.fields(t), [p.x, p.z], p.y.min(height))
    }

    /// The tile looked up once for the grid, each column's velocity at the
    /// mean level interpolated once.
    fn sample_velocities(
        &self,
        t: f64,
        origin: [f64; 2],
        spacing: f64,
        nodes: [usize; 2],
        columns: &[SurfaceNode],
        ys: &[f64],
        out: &mut [Vector3<f64>],
    ) {
        let f = self.fields(t);
        let n = nodes[0] * nodes[1];
        for (k, column) in columns.iter().enumerate().take(n) {
            let orbital = Self::orbital(&f, node_at(origin, spacing, nodes, k));
            for (l, &y) in ys.iter().enumerate() {
                out[l * n + k] = orbital * self.decay(&f, y.min(column.height));
            }
        }
    }

    fn velocity(&self, p: &Point3<f64>, t: f64) -> Vector3<f64> {
        let f = self.fields(t);
        let height = f.invert(p.x, p.z, [0.0, 0.0]).1.0[1];
        self.velocity_at(&f, [p.x, p.z], p.y.min(height))
    }

    /// `(∂f/∂x, ∂f/∂z) = J⁻ᵀ ∇₀η`: the elevation's gradient over the rest
    /// position through the choppy map's Jacobian.
    fn slope(&self, x: f64, z: f64, t: f64, hint: &[f64; 2]) -> [f64; 2] {
        let f = self.fields(t);
        // After a probe at the same point the hint holds the particle's
        // displacement: its first guess is the rest position, and the
        // inversion's first evaluation there gives the Jacobian.
        let (_, (_, j, g)) = f.invert(x, z, *hint);
        slope_through(&j, &g)
    }

    /// The nodes' lowest and highest elevation, widened by the most the
    /// bicubic interpolant can rise above its corners: within a cell of
    /// side `Δ` a cubic Hermite piece exceeds its ends by at most
    /// `4/27 Δ` times its end slopes, twice over in two dimensions, plus
    /// `(4/27)² Δ²` times the twists.
    fn height_bounds(&self, t: f64) -> Option<(f64, f64)> {
        let f = self.fields(t);
        let (lo, hi) = f
            .height
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| {
                (lo.min(h), hi.max(h))
            });
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let d = f.size / f.cells as f64;
        let c = 4.0 / 27.0;
        let pad = 2.0 * c * d * (largest(&f.height_gradient[0]) + largest(&f.height_gradient[1]))
            + 4.0 * c * c * d * d * largest(&f.twist[0]);
        Some((f.level + lo - pad, f.level + hi + pad))
    }

    /// The tile's shortest wave: two cells.
    fn sampling_length(&self, _t: f64) -> Option<f64> {
        Some(2.0 * self.sea.size / self.sea.cells as f64)
    }

    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
}

/// The surface's twist `∂²f/∂x∂z` (1/m) where the choppy map's Jacobian
/// is `j` (`j[r][c] = ∂x_r/∂a_c`, `a` the rest position) and the surface's
/// slope `s`, from the second derivatives over the rest position of the
/// elevation and the displacements along x and z (`[aa_xx, aa_xz, aa_zz]`
/// each): `s = J⁻ᵀ g`, so the surface's second derivatives are
/// `J⁻ᵀ M J⁻¹` with `M_rk = ∂²η/∂a_r∂a_k − Σ_c s_c ∂²D_c/∂a_r∂a_k` (flat
/// where the map folds).
fn twist_through(j: &[[f64; 2]; 2], s: [f64; 2], second: &[[f64; 3]; 3]) -> f64 {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det.abs() < 1e-12 {
        return 0.0;
    }
    let inv = [[j[1][1] / det, -j[0][1] / det], [-j[1][0] / det, j[0][0] / det]];
    let sym = |h: &[f64; 3]| [[h[0], h[1]], [h[1], h[2]]];
    let (eta, dx, dz) = (sym(&second[0]), sym(&second[1]), sym(&second[2]));
    let m: [[f64; 2]; 2] =
        std::array::from_fn(|r| std::array::from_fn(|k| eta[r][k] - s[0] * dx[r][k] - s[1] * dz[r][k]));
    // H = J⁻ᵀ M J⁻¹: (J⁻ᵀ)[r][c] = inv[c][r].
    let h: [[f64; 2]; 2] = std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            (0..2)
                .map(|p| (0..2).map(|q| inv[p][r] * m[p][q] * inv[q][c]).sum::<f64>())
                .sum()
        })
    });
    0.5 * (h[0][1] + h[1][0])
}

/// The surface's slope `s = J⁻ᵀ g` from the choppy map's Jacobian `j` and
/// the elevation's gradient `g` over the rest position (flat where the map
/// folds).
fn slope_through(j: &[[f64; 2]; 2], g: &[f64; 2]) -> [f64; 2] {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det.abs() < 1e-12 {
        return [0.0, 0.0];
    }
    // Solve Jᵀ s = g.
    [
        (j[1][1] * g[0] - j[1][0] * g[1]) / det,
        (j[0][0] * g[1] - j[0][1] * g[0]) / det,
    ]
}
