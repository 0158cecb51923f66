//! A sea of Gerstner (trochoidal) waves, and the inversion of the Gerstner
//! map that finds the particle above a horizontal position.

use nalgebra::{Point3, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use super::Surface;
use super::surface::{SurfaceNode, node_at};
use crate::error::WaterError;

/// One Gerstner (trochoidal) wave on deep water.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GerstnerWave {
    /// Amplitude, m.
    pub amplitude: f64,
    /// Wavelength, m.
    pub wavelength: f64,
    /// Direction of travel in the horizontal plane, degrees from +x towards +z.
    pub direction_deg: f64,
    /// Steepness `Q` in [0, 1]: 0 is a sine wave, 1 the sharpest crest
    /// without loops (scaled by `1/(k A N)` over the `N` waves of a sea).
    pub steepness: f64,
    /// Phase offset, radians.
    #[serde(default)]
    pub phase: f64,
}

impl GerstnerWave {
    /// A moderate two-wave swell: 0.25 m over 9 m along +x and 0.10 m over
    /// 4 m at 35° to it, steepness 0.6 and 0.4. The sea of the
    /// `buoy_on_waves` scene, and of soak's sea benches and tests:
    /// `Gerstner::new(level, GerstnerWave::SWELL.to_vec(), gravity)`.
    pub const SWELL: [GerstnerWave; 2] = [
        GerstnerWave {
            amplitude: 0.25,
            wavelength: 9.0,
            direction_deg: 0.0,
            steepness: 0.6,
            phase: 0.0,
        },
        GerstnerWave {
            amplitude: 0.10,
            wavelength: 4.0,
            direction_deg: 35.0,
            steepness: 0.4,
            phase: 1.0,
        },
    ];

    /// Wavenumber `k = 2π/λ`, 1/m.
    pub fn wavenumber(&self) -> f64 {
        std::f64::consts::TAU / self.wavelength
    }
    fn direction(&self) -> Vector2<f64> {
        let a = self.direction_deg.to_radians();
        Vector2::new(a.cos(), a.sin())
    }
}

/// A sea made of Gerstner waves over a mean level, with deep-water
/// dispersion `ω = √(g k)`. Horizontal particle displacement makes crests
/// sharp; [`Surface::height`] inverts it by fixed-point iteration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Gerstner {
    /// Mean water level, m.
    pub level: f64,
    /// The waves.
    pub waves: Vec<GerstnerWave>,
    /// Gravity for the dispersion relation, m/s².
    pub gravity: f64,
    // Precomputed per wave: (k, ω, direction, Q·A scaled).
    #[serde(skip)]
    cache: Vec<WaveCache>,
}

#[derive(Clone, Copy, Debug, PartialEq, Default)]
struct WaveCache {
    k: f64,
    omega: f64,
    dir: Vector2<f64>,
    qa: f64,
    a: f64,
    phase: f64,
}

impl WaveCache {
    /// Linear theory's velocity of this wave (m/s) at height `y` (m) above
    /// the mean level, where its phase has the sine and cosine `(s, c)`.
    #[inline(always)]
    fn velocity(&self, phase: (f64, f64), y: f64) -> Vector3<f64> {
        self.velocity_at_speed(phase, self.speed(y))
    }

    /// The orbital speed of this wave (m/s) at height `y` (m) above the
    /// mean level: `a ω e^{k y}` below it, continued linearly above it (the
    /// exponential's growth to the crests of steep waves is not linear
    /// theory's).
    #[inline(always)]
    fn speed(&self, y: f64) -> f64 {
        let z = self.k * y;
        let decay = if z > 0.0 { 1.0 + z } else { z.exp() };
        self.a * self.omega * decay
    }

    /// [`WaveCache::velocity`] at a known [`WaveCache::speed`].
    #[inline(always)]
    fn velocity_at_speed(&self, (s, c): (f64, f64), speed: f64) -> Vector3<f64> {
        Vector3::new(speed * c * self.dir.x, speed * s, speed * c * self.dir.y)
    }
}

impl Gerstner {
    /// A sea at mean `level` (m) with the given waves, validated.
    pub fn new(level: f64, waves: Vec<GerstnerWave>, gravity: f64) -> Result<Self, WaterError> {
        if !level.is_finite() {
            return Err(WaterError::Parameter {
                name: "level",
                value: level,
            });
        }
        if !(gravity.is_finite() && gravity > 0.0) {
            return Err(WaterError::Parameter {
                name: "gravity",
                value: gravity,
            });
        }
        for (i, w) in waves.iter().enumerate() {
            let checks = [
                ("amplitude", w.amplitude, w.amplitude >= 0.0),
                ("wavelength", w.wavelength, w.wavelength > 0.0),
                ("steepness", w.steepness, (0.0..=1.0).contains(&w.steepness)),
                ("direction_deg", w.direction_deg, true),
                ("phase", w.phase, true),
            ];
            for (field, value, ok) in checks {
                if !(value.is_finite() && ok) {
                    return Err(WaterError::Wave {
                        index: i,
                        field,
                        value,
                    });
                }
            }
        }
        let n = waves.len().max(1) as f64;
        let cache = waves
            .iter()
            .map(|w| {
                let k = w.wavenumber();
                // Scale steepness so the sum never loops: Σ Q_i k_i A_i ≤ 1.
                let q = if w.amplitude > 0.0 {
                    w.steepness / (k * w.amplitude * n)
                } else {
                    0.0
                };
                WaveCache {
                    k,
                    omega: (gravity * k).sqrt(),
                    dir: w.direction(),
                    qa: q * w.amplitude,
                    a: w.amplitude,
                    phase: w.phase,
                }
            })
            .collect();
        Ok(Self {
            level,
            waves,
            gravity,
            cache,
        })
    }

    /// Rebuilds the cache after deserialisation or edits to `waves`.
    pub fn rebuild(self) -> Result<Self, WaterError> {
        Self::new(self.level, self.waves, self.gravity)
    }

    /// Position of the surface particle whose rest position is `(x0, z0)`, m.
    pub fn particle(&self, x0: f64, z0: f64, t: f64) -> Point3<f64> {
        let mut p = Point3::new(x0, self.level, z0);
        for w in &self.cache {
            let th = w.k * (w.dir.x * x0 + w.dir.y * z0) - w.omega * t + w.phase;
            let (s, c) = th.sin_cos();
            p.x -= w.qa * w.dir.x * s;
            p.z -= w.qa * w.dir.y * s;
            p.y += w.a * c;
        }
        p
    }

    fn rest_position(&self, x: f64, z: f64, t: f64) -> (f64, f64) {
        self.rest_position_from(x, z, t, [0.0, 0.0])
    }

    /// Rest position of the particle above `(x, z)`, starting from the guess
    /// that its horizontal displacement is `shift`.
    fn rest_position_from(&self, x: f64, z: f64, t: f64, shift: [f64; 2]) -> (f64, f64) {
        let (x0, z0, _) = self.invert(x, z, t, shift);
        (x0, z0)
    }

    /// [`Self::rest_position_from`], with the jet of the last of Newton's
    /// iterations: taken where the residual was below its tolerance, at
    /// most that far from the rest position returned (`None` when the
    /// iterations ran out first).
    fn invert(&self, x: f64, z: f64, t: f64, shift: [f64; 2]) -> (f64, f64, Option<Jet>) {
        self.invert_within(x, z, t, shift, 0.0)
    }

    /// [`Self::invert`] stopping once the residual `|r_x| + |r_z|` is
    /// below `within` (m) or below `1e-12 (1 + |x| + |z|)`, whichever is
    /// larger.
    fn invert_within(&self, x: f64, z: f64, t: f64, shift: [f64; 2], within: f64) -> (f64, f64, Option<Jet>) {
        let tolerance = within.max(1e-12 * (1.0 + x.abs() + z.abs()));
        // Newton's method on P(x0) = (x, z), with the Jacobian
        // J = I − Σ Q A k cos θ d dᵀ; a fixed-point step where J is near
        // singular (the sharpest crests). Converges in a few iterations.
        let (mut x0, mut z0) = (x - shift[0], z - shift[1]);
        for _ in 0..16 {
            let jet = self.jet(x0, z0, t);
            let [jxx, jxz, jzz] = jet.jacobian;
            let (rx, rz) = (jet.position[0] - x, jet.position[1] - z);
            let det = jxx * jzz - jxz * jxz;
            let (dx, dz) = if det > 1e-3 {
                ((jzz * rx - jxz * rz) / det, (jxx * rz - jxz * rx) / det)
            } else {
                (rx, rz)
            };
            x0 -= dx;
            z0 -= dz;
            if rx.abs() + rz.abs() < tolerance {
                return (x0, z0, Some(jet));
            }
        }
        (x0, z0, None)
    }

    /// The horizontal position of the particle at rest position `(x0, z0)`,
    /// its Jacobian over the rest position, the gradient of its height, and
    /// the sums [`Self::hessian`] reads: one pass over the
    /// waves, one sine and cosine each.
    fn jet(&self, x0: f64, z0: f64, t: f64) -> Jet {
        let (mut px, mut pz) = (x0, z0);
        let (mut jxx, mut jxz, mut jzz) = (1.0, 0.0, 1.0);
        let (mut gx, mut gz) = (0.0, 0.0);
        let mut height = self.level;
        let mut curvature = [0.0; 3];
        let mut warp = [0.0; 4];
        for w in &self.cache {
            let th = w.k * (w.dir.x * x0 + w.dir.y * z0) - w.omega * t + w.phase;
            let (s, c) = th.sin_cos();
            let [dx, dz] = [w.dir.x, w.dir.y];
            px -= w.qa * dx * s;
            pz -= w.qa * dz * s;
            height += w.a * c;
            let f = w.qa * w.k * c;
            jxx -= f * dx * dx;
            jxz -= f * dx * dz;
            jzz -= f * dz * dz;
            let e = w.a * w.k * s;
            gx -= e * dx;
            gz -= e * dz;
            // ∂g/∂a_k = −A k² cos θ d d_k and ∂J/∂a_k = Q A k² sin θ d dᵀ d_k:
            // their sums over the waves, for the twist.
            let kk = w.k * w.k;
            let (ck, sk) = (w.a * kk * c, w.qa * kk * s);
            curvature[0] += ck * dx * dx;
            curvature[1] += ck * dx * dz;
            curvature[2] += ck * dz * dz;
            warp[0] += sk * dx * dx * dx;
            warp[1] += sk * dx * dx * dz;
            warp[2] += sk * dx * dz * dz;
            warp[3] += sk * dz * dz * dz;
        }
        Jet {
            position: [px, pz],
            height,
            jacobian: [jxx, jxz, jzz],
            height_gradient: [gx, gz],
            curvature,
            warp,
        }
    }
}

impl Gerstner {
    /// The surface's second derivatives `[[f_xx, f_xz], [f_zx, f_zz]]`
    /// (1/m) above the particle whose `jet` and surface slope `s` are
    /// known.
    ///
    /// With `J` the Jacobian of the particle's horizontal position over its
    /// rest position and `g` its height's gradient, `s = J⁻¹ g`, so the
    /// surface's second derivatives are `J⁻¹ B J⁻¹` with the columns of `B`
    /// `∂g/∂a_k − (∂J/∂a_k) s` (`a` the rest position), which the jet's
    /// sums give without another pass over the waves.
    fn hessian(jet: &Jet, s: [f64; 2]) -> [[f64; 2]; 2] {
        let [jxx, jxz, jzz] = jet.jacobian;
        let det = jxx * jzz - jxz * jxz;
        if det.abs() < 1e-12 {
            return [[0.0; 2]; 2];
        }
        // B = −Σ A k² cos θ d dᵀ − Σ Q A k² sin θ (d·s) d dᵀ.
        let [cxx, cxz, czz] = jet.curvature;
        let [txxx, txxz, txzz, tzzz] = jet.warp;
        let b = [
            [
                -cxx - (txxx * s[0] + txxz * s[1]),
                -cxz - (txxz * s[0] + txzz * s[1]),
            ],
            [
                -cxz - (txxz * s[0] + txzz * s[1]),
                -czz - (txzz * s[0] + tzzz * s[1]),
            ],
        ];
        // J⁻¹ (symmetric).
        let inv = [[jzz / det, -jxz / det], [-jxz / det, jxx / det]];
        let mul = |p: &[[f64; 2]; 2], q: &[[f64; 2]; 2]| -> [[f64; 2]; 2] {
            std::array::from_fn(|r| std::array::from_fn(|c| p[r][0] * q[0][c] + p[r][1] * q[1][c]))
        };
        mul(&mul(&inv, &b), &inv)
    }
}

/// Where [`Gerstner`]'s node sampling stops Newton's method: a residual
/// below this fraction of the shortest wave's length.
const NODE_RESIDUAL: f64 = 1e-7;

/// A Gerstner particle's horizontal position (m), the symmetric Jacobian
/// `[xx, xz, zz]` of that position over its rest position, and the gradient
/// of its height over its rest position.
struct Jet {
    position: [f64; 2],
    /// The particle's height, m.
    height: f64,
    jacobian: [f64; 3],
    height_gradient: [f64; 2],
    /// `Σ A k² cos θ d dᵀ` over the waves, `[xx, xz, zz]` (1/m).
    curvature: [f64; 3],
    /// `Σ Q A k² sin θ d ⊗ d ⊗ d` over the waves, `[xxx, xxz, xzz, zzz]` (1/m).
    warp: [f64; 4],
}

impl Jet {
    /// The surface's slope `(∂f/∂x, ∂f/∂z) = J⁻¹ ∇y` where the particle
    /// is (zero where `J` is singular).
    fn slope(&self) -> [f64; 2] {
        let [jxx, jxz, jzz] = self.jacobian;
        let [gx, gz] = self.height_gradient;
        let det = jxx * jzz - jxz * jxz;
        if det.abs() < 1e-12 {
            return [0.0, 0.0];
        }
        [(jzz * gx - jxz * gz) / det, (jxx * gz - jxz * gx) / det]
    }
}

impl Surface for Gerstner {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        let a: f64 = self.waves.iter().map(|w| w.amplitude).sum();
        Some((self.level - a, self.level + a))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    /// The shortest wavelength of a wave with a non-zero amplitude.
    fn sampling_length(&self, _t: f64) -> Option<f64> {
        self.waves
            .iter()
            .filter(|w| w.amplitude > 0.0)
            .map(|w| w.wavelength)
            .min_by(f64::total_cmp)
    }
    fn height(&self, x: f64, z: f64, t: f64) -> f64 {
        let (x0, z0) = self.rest_position(x, z, t);
        self.particle(x0, z0, t).y
    }

    fn probe(
        &self,
        p: &Point3<f64>,
        t: f64,
        with_velocity: bool,
        hint: &mut [f64; 2],
    ) -> (f64, Vector3<f64>) {
        let (x0, z0) = self.rest_position_from(p.x, p.z, t, *hint);
        *hint = [p.x - x0, p.z - z0];
        let height = self.particle(x0, z0, t).y;
        let v = if with_velocity {
            self.velocity_below(p.x, p.z, p.y.min(height), t)
        } else {
            Vector3::zeros()
        };
        (height - p.y, v)
    }

    /// The velocity needs no inversion: read where it is.
    fn velocity_under(&self, p: &Point3<f64>, t: f64, height: f64, _hint: &[f64; 2]) -> Vector3<f64> {
        self.velocity_below(p.x, p.z, p.y.min(height), t)
    }

    /// `(∂f/∂x, ∂f/∂z) = J⁻¹ ∇y` at the particle's rest position, with `J`
    /// the Jacobian of its horizontal position and `∇y` the gradient of its
    /// height, both over the rest position.
    fn slope(&self, x: f64, z: f64, t: f64, hint: &[f64; 2]) -> [f64; 2] {
        // After a probe at the same point the hint holds the particle's
        // displacement, so the first guess is its rest position: the same
        // pass over the waves checks it and takes J and ∇y.
        let mut jet = self.jet(x - hint[0], z - hint[1], t);
        let off = (jet.position[0] - x).abs() + (jet.position[1] - z).abs();
        if off > 1e-9 * (1.0 + x.abs() + z.abs()) {
            let (x0, z0) = self.rest_position_from(x, z, t, *hint);
            jet = self.jet(x0, z0, t);
        }
        jet.slope()
    }

    /// Every node's twist, in closed form.
    fn node_twists(&self) -> bool {
        true
    }

    /// One inversion per node: the last of Newton's iterations, within
    /// its tolerance of the rest position, gives the height, the slope and
    /// the twist there, one pass over the waves for each iteration and
    /// none more. Each node's Newton starts where the node before it (the
    /// one to its left, or for a row's first the one below) says its
    /// particle is: that node's rest position moved by its inverse
    /// Jacobian times the step between them, the first Newton step taken
    /// from what that node's last iteration knew, so that most nodes
    /// converge an iteration sooner than from its displacement alone.
    fn sample_nodes(
        &self,
        t: f64,
        origin: [f64; 2],
        spacing: f64,
        nodes: [usize; 2],
        out: &mut [SurfaceNode],
    ) {
        // A solved node: its rest position and the inverse of its
        // Jacobian (`None` where it is near singular or the iterations ran
        // out), from which a neighbour's start is predicted.
        type Solved = ([f64; 2], Option<[f64; 3]>);
        let predict = |from: &Solved, step: [f64; 2]| -> Option<[f64; 2]> {
            let ([x0, z0], inv) = *from;
            let [ixx, ixz, izz] = inv?;
            Some([
                x0 + ixx * step[0] + ixz * step[1],
                z0 + ixz * step[0] + izz * step[1],
            ])
        };
        let (mut left, mut below): (Option<Solved>, Option<Solved>) = (None, None);
        let mut hint = [0.0; 2];
        // Newton stops within a ten-millionth of the shortest wave: the
        // first-order step back to the node leaves errors of the
        // order of the residual squared (2e-13 m in height on a 4 m wave
        // of 0.1 m), and in the twist of the residual (2e-7 1/m there).
        let k_max = self.cache.iter().map(|w| w.k).fold(0.0, f64::max);
        let tol = if k_max > 0.0 {
            NODE_RESIDUAL * std::f64::consts::TAU / k_max
        } else {
            0.0
        };
        for (k, slot) in out.iter_mut().enumerate().take(nodes[0] * nodes[1]) {
            let [x, z] = node_at(origin, spacing, nodes, k);
            let first = k % nodes[0] == 0;
            let start = if first {
                below.as_ref().and_then(|b| predict(b, [0.0, spacing]))
            } else {
                left.as_ref().and_then(|l| predict(l, [spacing, 0.0]))
            };
            if let Some([x0, z0]) = start {
                hint = [x - x0, z - z0];
            }
            let (x0, z0, jet) = self.invert_within(x, z, t, hint, tol);
            hint = [x - x0, z - z0];
            let solved = jet.is_some();
            let jet = jet.unwrap_or_else(|| self.jet(x0, z0, t));
            let [jxx, jxz, jzz] = jet.jacobian;
            let det = jxx * jzz - jxz * jxz;
            let inv = (solved && det > 1e-3).then(|| [jzz / det, -jxz / det, jxx / det]);
            left = Some(([x0, z0], inv));
            if first {
                below = left;
            }
            // The jet is of the particle at `(x, z) + r`, `r` its residual:
            // its height and slope taken back to the node to first order.
            // Where the iterations ran out (the sharpest crests), the last
            // iterate's own, as it is.
            let r = if solved {
                [jet.position[0] - x, jet.position[1] - z]
            } else {
                [0.0, 0.0]
            };
            let s = jet.slope();
            let h = Self::hessian(&jet, s);
            *slot = SurfaceNode {
                height: jet.height - (s[0] * r[0] + s[1] * r[1]),
                slope: [
                    s[0] - (h[0][0] * r[0] + h[0][1] * r[1]),
                    s[1] - (h[1][0] * r[0] + h[1][1] * r[1]),
                ],
                hint,
                twist: Some(0.5 * (h[0][1] + h[1][0])),
            };
        }
    }

    /// Each column's phases taken once for all its nodes, each layer's
    /// decays once for all its columns: a wave's velocity at a node is its
    /// phase's sine and cosine (the same down the column) times its speed
    /// at the node's height (the same across the layer, where the node is
    /// under the surface), so a grid of `c` columns and `l` layers costs
    /// `c` sines and cosines and `l` exponentials per wave, not `c l` of
    /// each; the layers above a column's surface, which all take the
    /// surface's velocity, take it once. The same values as [`Surface::velocity_under`] at every node,
    /// to the bit.
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
        let n = nodes[0] * nodes[1];
        let waves = self.cache.len();
        let mut phases = vec![(0.0, 0.0); waves];
        // speeds[l * waves + i]: wave i's speed at layer l.
        let speeds: Vec<f64> = ys
            .iter()
            .flat_map(|&y| self.cache.iter().map(move |w| w.speed(y - self.level)))
            .collect();
        for (k, column) in columns.iter().enumerate().take(n) {
            let [x, z] = node_at(origin, spacing, nodes, k);
            for (phase, w) in phases.iter_mut().zip(&self.cache) {
                *phase = (w.k * (w.dir.x * x + w.dir.y * z) - w.omega * t + w.phase).sin_cos();
            }
            // Above the surface every layer takes the surface's velocity:
            // taken once for the column, at its first layer above it.
            let mut surface = None;
            for (l, &y) in ys.iter().enumerate() {
                out[l * n + k] = if y <= column.height {
                    let layer = &speeds[l * waves..(l + 1) * waves];
                    let mut v = Vector3::zeros();
                    for ((&phase, w), &speed) in phases.iter().zip(&self.cache).zip(layer) {
                        v += w.velocity_at_speed(phase, speed);
                    }
                    v
                } else {
                    *surface.get_or_insert_with(|| self.velocity_with(&phases, column.height))
                };
            }
        }
    }

    /// The water's velocity at `p`, m/s: linear (Airy) theory's for each
    /// wave, `a ω e^{k (y − level)}` along the wave's direction in phase
    /// with its height and the same upward a quarter period ahead, at the
    /// Eulerian phase `k d·x − ω t` of `p` itself; continued linearly above
    /// the mean level up to the surface (`a ω (1 + k (y − level))`, as
    /// offshore practice extrapolates it: the exponential grows too fast
    /// to the crests of steep waves), and above the surface the surface's.
    ///
    /// Its mean at any point below the troughs is zero (no current), and a
    /// particle carried by it drifts forward at the Stokes drift
    /// ([`Gerstner::stokes_drift`], `Σ a² ω k e^{2k z}`): the water moves
    /// faster forward under the crests than back under the troughs, and
    /// forward where it has already moved forward. So a small body with
    /// drag drifts along with the waves, as flotsam does. (The Gerstner
    /// surface particle's own velocity, read where it is, was a closed
    /// orbit carrying nothing forward, and read at a fixed place a return
    /// current of about the drift's size against the waves.) The surface
    /// is the Gerstner one, sharpened by the steepness; the water under it
    /// moves as linear theory says of a wave of its amplitude and length,
    /// whatever the steepness.
    fn velocity(&self, p: &Point3<f64>, t: f64) -> Vector3<f64> {
        let surface = self.height(p.x, p.z, t);
        self.velocity_below(p.x, p.z, p.y.min(surface), t)
    }
}

impl Gerstner {
    /// Linear theory's velocity at `(x, y, z)` (m/s), under the surface.
    fn velocity_below(&self, x: f64, z: f64, y: f64, t: f64) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        for w in &self.cache {
            let th = w.k * (w.dir.x * x + w.dir.y * z) - w.omega * t + w.phase;
            v += w.velocity(th.sin_cos(), y - self.level);
        }
        v
    }

    /// [`Self::velocity_below`] at height `y` (m) of a column whose waves'
    /// phases have the sines and cosines `phases` (in the waves' order).
    fn velocity_with(&self, phases: &[(f64, f64)], y: f64) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        for (&phase, w) in phases.iter().zip(&self.cache) {
            v += w.velocity(phase, y - self.level);
        }
        v
    }

    /// The Stokes drift at mean height `y` (m), m/s: the mean velocity at
    /// which the waves carry the water's particles forward, `Σ a² ω k
    /// e^{2k·(y − level)}` along each wave's direction (deep water, second
    /// order in the steepness; at the mean level and above, `Σ a² ω k`).
    /// The mean velocity of a particle carried by [`Surface::velocity`]:
    /// what a small body with drag drifts at.
    pub fn stokes_drift(&self, y: f64) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        for w in &self.cache {
            let decay = (2.0 * w.k * (y - self.level).min(0.0)).exp();
            let speed = w.a * w.a * w.omega * w.k * decay;
            v.x += speed * w.dir.x;
            v.z += speed * w.dir.y;
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid's velocities, each column's phases taken once, are the
    /// velocity read node by node under the surface (and the surface's own
    /// above it), to the bit, and the velocity read afresh: layers from
    /// below the troughs, where the decay is exponential, to above the
    /// crests.
    #[test]
    fn a_columns_velocities_are_its_nodes_own() {
        let sea = Gerstner::new(0.1, GerstnerWave::SWELL.to_vec(), 9.81).unwrap();
        let (origin, spacing, nodes) = ([-1.3, 0.7], 0.25, [9, 7]);
        let ys: Vec<f64> = (0..12).map(|l| -1.2 + 0.15 * l as f64).collect();
        let n = nodes[0] * nodes[1];
        for t in [0.0, 1.7, 4.2] {
            let mut columns = vec![SurfaceNode::default(); n];
            sea.sample_nodes(t, origin, spacing, nodes, &mut columns);
            let mut out = vec![Vector3::zeros(); n * ys.len()];
            sea.sample_velocities(t, origin, spacing, nodes, &columns, &ys, &mut out);
            let mut above = 0;
            for (l, &y) in ys.iter().enumerate() {
                for (k, column) in columns.iter().enumerate() {
                    let [x, z] = node_at(origin, spacing, nodes, k);
                    above += usize::from(y > column.height);
                    let p = Point3::new(x, y.min(column.height), z);
                    let want = sea.velocity_under(&p, t, column.height, &column.hint);
                    assert_eq!(out[l * n + k], want, "node {k}, layer {l}, t = {t}");
                    // The velocity read afresh (the surface's height found
                    // by another inversion, within its tolerance).
                    let fresh = sea.velocity(&Point3::new(x, y, z), t);
                    assert!(
                        (want - fresh).norm() < 1e-12,
                        "node {k}, layer {l}: {want} against {fresh}"
                    );
                }
            }
            assert!(
                above > 0 && above < n * ys.len(),
                "{above} nodes above the surface"
            );
        }
    }

    /// The nodes, sampled with Newton stopped early and taken back to
    /// the node to first order, against a full inversion at each node
    /// (residual below 1e-12 of its coordinates, its height taken back to
    /// the node by it) and the second derivatives from it, on seas whose waves are 4 m to 0.4 m long: the height
    /// within 1e-13 of the shortest wave's length, the slope within 1e-10,
    /// the twist within 1e-5 times the steepest wave's `A k²` (the
    /// stopping residual, 1e-7 of that length, times the surface's third
    /// derivatives).
    #[test]
    fn nodes_stopped_early_agree_with_a_full_inversion() {
        for scale in [1.0, 0.1] {
            let waves: Vec<GerstnerWave> = GerstnerWave::SWELL
                .iter()
                .map(|w| GerstnerWave {
                    amplitude: w.amplitude * scale,
                    wavelength: w.wavelength * scale,
                    ..*w
                })
                .collect();
            let sea = Gerstner::new(0.1, waves, 9.81).unwrap();
            let shortest = sea.waves.iter().map(|w| w.wavelength).fold(f64::MAX, f64::min);
            let curvature = sea.cache.iter().map(|w| w.a * w.k * w.k).fold(0.0, f64::max);
            let spacing = shortest / 16.0;
            let (origin, nodes) = ([-13.0 * scale, 40.0 * scale], [12, 9]);
            for t in [0.0, 1.7, 4.2] {
                let mut out = vec![SurfaceNode::default(); nodes[0] * nodes[1]];
                sea.sample_nodes(t, origin, spacing, nodes, &mut out);
                let (mut dh, mut ds, mut dt) = (0.0f64, 0.0f64, 0.0f64);
                for (k, node) in out.iter().enumerate() {
                    let [x, z] = node_at(origin, spacing, nodes, k);
                    let (x0, z0, jet) = sea.invert(x, z, t, [0.0, 0.0]);
                    let jet = jet.unwrap_or_else(|| sea.jet(x0, z0, t));
                    let s = jet.slope();
                    let h = Gerstner::hessian(&jet, s);
                    // The full inversion's own residual (below 1e-12 of the
                    // coordinates, 5e-11 m here) taken back to the node.
                    let r = [jet.position[0] - x, jet.position[1] - z];
                    let height = jet.height - (s[0] * r[0] + s[1] * r[1]);
                    dh = dh.max((node.height - height).abs());
                    ds = ds.max((node.slope[0] - s[0]).abs() + (node.slope[1] - s[1]).abs());
                    dt = dt.max((node.twist.unwrap() - h[0][1]).abs());
                }
                eprintln!(
                    "scale {scale} t {t}: height {dh:.1e} slope {ds:.1e} twist {dt:.1e} (A k^2 {curvature:.2})"
                );
                assert!(dh < 1e-13 * shortest, "height off by {dh} at t = {t}");
                assert!(ds < 1e-10, "slope off by {ds} at t = {t}");
                assert!(dt < 1e-5 * curvature, "twist off by {dt} at t = {t}");
            }
        }
    }

    /// Crests as sharp as a Gerstner sea makes them (steepness 1, a cusp
    /// where the map's Jacobian is singular): every node finite, its
    /// height within the waves' reach of the level, wherever Newton's
    /// iterations end.
    #[test]
    fn nodes_at_cusped_crests_stay_finite() {
        let waves = vec![
            GerstnerWave {
                amplitude: 0.4,
                wavelength: 6.0,
                direction_deg: 0.0,
                steepness: 1.0,
                phase: 0.0,
            },
            GerstnerWave {
                amplitude: 0.1,
                wavelength: 2.5,
                direction_deg: 50.0,
                steepness: 1.0,
                phase: 0.3,
            },
        ];
        let sea = Gerstner::new(0.0, waves, 9.81).unwrap();
        let nodes = [40, 30];
        for t in [0.0, 0.9, 2.3] {
            let mut out = vec![SurfaceNode::default(); nodes[0] * nodes[1]];
            sea.sample_nodes(t, [-5.0, -3.0], 2.5 / 16.0, nodes, &mut out);
            for (k, node) in out.iter().enumerate() {
                let values = [node.height, node.slope[0], node.slope[1], node.twist.unwrap()];
                assert!(
                    values.iter().all(|v| v.is_finite()),
                    "node {k} at t = {t}: {node:?}"
                );
                assert!(node.height.abs() <= 0.5 + 1e-9, "node {k} at t = {t}: {node:?}");
            }
        }
    }

    /// The nodes sampled in one inversion each against the exact read of
    /// the surface: the height of the particle whose rest position the
    /// node's hint names, and that height's central differences.
    #[test]
    fn nodes_sampled_in_one_inversion_match_the_exact_surface() {
        let sea = Gerstner::new(0.1, GerstnerWave::SWELL.to_vec(), 9.81).unwrap();
        let (origin, spacing, nodes) = ([-1.3, 0.7], 0.25, [9, 7]);
        for t in [0.0, 1.7, 4.2] {
            let mut out = vec![SurfaceNode::default(); nodes[0] * nodes[1]];
            sea.sample_nodes(t, origin, spacing, nodes, &mut out);
            for (k, node) in out.iter().enumerate() {
                let [x, z] = super::super::surface::node_at(origin, spacing, nodes, k);
                // The hint is the displacement of the particle over the node.
                let p = sea.particle(x - node.hint[0], z - node.hint[1], t);
                assert!(
                    (p.x - x).abs() + (p.z - z).abs() < 1e-10,
                    "node {k} at t = {t}: {p}"
                );
                assert!((node.height - p.y).abs() < 1e-10, "node {k} at t = {t}");
                assert!(
                    (node.height - sea.height(x, z, t)).abs() < 1e-10,
                    "node {k} at t = {t}"
                );
                let e = 1e-5;
                let dx = (sea.height(x + e, z, t) - sea.height(x - e, z, t)) / (2.0 * e);
                let dz = (sea.height(x, z + e, t) - sea.height(x, z - e, t)) / (2.0 * e);
                assert!(
                    (node.slope[0] - dx).abs() < 1e-8 && (node.slope[1] - dz).abs() < 1e-8,
                    "node {k} at t = {t}: {:?} against {:?}",
                    node.slope,
                    [dx, dz]
                );
                // The twist against differences of the exact slope, both
                // ways round.
                let h = [0.0, 0.0];
                let sxz = (sea.slope(x, z + e, t, &h)[0] - sea.slope(x, z - e, t, &h)[0]) / (2.0 * e);
                let szx = (sea.slope(x + e, z, t, &h)[1] - sea.slope(x - e, z, t, &h)[1]) / (2.0 * e);
                let twist = node.twist.expect("a Gerstner sea gives its nodes' twists");
                assert!(
                    (twist - sxz).abs() < 1e-6 && (twist - szx).abs() < 1e-6,
                    "node {k} at t = {t}: twist {twist} against {sxz} and {szx}"
                );
            }
        }
    }
}
