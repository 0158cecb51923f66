//! Water: a surface `y = f(x, z, t)` in the world frame (y up), its velocity
//! field, and the fluid's density.

use nalgebra::{Point3, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::error::WaterError;

/// Density of fresh water, kg/m³.
pub const WATER_DENSITY: f64 = 1000.0;
/// Density of air at sea level and 20 °C, kg/m³.
pub const AIR_DENSITY: f64 = 1.2;
/// Standard gravity, m/s².
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// How the hydrostatics may treat a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfaceKind {
    /// A plane `n·p = offset` (unit `n` with `n.y > 0`): depth is affine in
    /// position, so the tiled closed forms apply.
    Plane {
        /// Unit normal pointing out of the fluid.
        normal: Vector3<f64>,
        /// Plane offset, m.
        offset: f64,
    },
    /// Any height field `y = f(x, z, t)`.
    General,
    /// No free surface: the body is wholly immersed (air around a balloon).
    Unbounded,
}

/// A fluid's free surface and velocity field, world frame, y up: the
/// surface is `y = f(x, z, t)`.
///
/// Four surfaces are provided: a [`Plane`] (horizontal or tilted), a sum of
/// [`Gerstner`] waves, a bilinear [`HeightField`], and an [`Unbounded`]
/// medium (a balloon in air: everything is immersed). Implement [`Surface`]
/// for your own.
pub trait Surface: Send + Sync {
    /// Surface height `f(x, z, t)` at horizontal position `(x, z)` (m) and time `t` (s), m.
    fn height(&self, x: f64, z: f64, t: f64) -> f64;

    /// Fluid velocity at world point `p` (m) and time `t` (s), m/s.
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        Vector3::zeros()
    }

    /// The surface's kind at time `t`; the default is [`SurfaceKind::General`].
    fn kind(&self, _t: f64) -> SurfaceKind {
        SurfaceKind::General
    }

    /// Lowest and highest surface height over all `(x, z)` at time `t`, m,
    /// if known: a body whose lowest point is above the highest crest is dry
    /// and needs no texel work. `None` (the default) means unknown.
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        None
    }

    /// The concrete surface, for backends that handle known surfaces
    /// natively (the GPU evaluates [`Plane`], [`Gerstner`], [`HeightField`]
    /// and [`Unbounded`] itself). `None` for other surfaces.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        None
    }

    /// Depth of `p` below the surface (m) and, when `with_velocity`, the
    /// fluid velocity there (m/s), in one call. `hint` carries state between
    /// calls at nearby points (it starts zeroed); surfaces that solve for the
    /// height iteratively use it to warm-start.
    fn probe(
        &self,
        p: &Point3<f64>,
        t: f64,
        with_velocity: bool,
        hint: &mut [f64; 2],
    ) -> (f64, Vector3<f64>) {
        let _ = hint;
        let v = if with_velocity {
            self.velocity(p, t)
        } else {
            Vector3::zeros()
        };
        (self.depth(p, t), v)
    }

    /// Slope `(∂f/∂x, ∂f/∂z)` of the surface above `(x, z)` (m) at time `t`
    /// (s), dimensionless. Archimedes buoyancy needs it where the surface is
    /// not flat, so that its torque is the derivative of the water's
    /// potential. `hint` is [`Surface::probe`]'s, left by a probe at the
    /// same point. The default takes central differences of
    /// [`Surface::height`] 10⁻⁵ (1 + |x| + |z|) m apart.
    fn slope(&self, x: f64, z: f64, t: f64, hint: &[f64; 2]) -> [f64; 2] {
        let _ = hint;
        let h = 1e-5 * (1.0 + x.abs() + z.abs());
        [
            (self.height(x + h, z, t) - self.height(x - h, z, t)) / (2.0 * h),
            (self.height(x, z + h, t) - self.height(x, z - h, t)) / (2.0 * h),
        ]
    }

    /// Depth of `p` below the surface, m (positive under water, measured vertically).
    fn depth(&self, p: &Point3<f64>, t: f64) -> f64 {
        self.height(p.x, p.z, t) - p.y
    }
}

/// A plane surface `normal·p = offset`, horizontal unless tilted.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    /// Unit normal pointing up out of the water (`normal.y > 0`).
    pub normal: Vector3<f64>,
    /// `normal·p` on the surface, m.
    pub offset: f64,
    /// Uniform current, m/s.
    pub current: Vector3<f64>,
}

impl Plane {
    /// The horizontal plane `y = level` (m), still water.
    pub fn horizontal(level: f64) -> Self {
        Self {
            normal: Vector3::y(),
            offset: level,
            current: Vector3::zeros(),
        }
    }

    /// A plane through `point` (m) with the given up normal (normalised here).
    pub fn tilted(point: Point3<f64>, normal: Vector3<f64>) -> Result<Self, WaterError> {
        let n = normal.try_normalize(1e-12).ok_or(WaterError::PlaneNormal {
            normal: normal.into(),
        })?;
        if n.y <= 1e-6 || !n.iter().all(|c| c.is_finite()) || !point.iter().all(|c| c.is_finite()) {
            return Err(WaterError::PlaneNormal {
                normal: normal.into(),
            });
        }
        Ok(Self {
            normal: n,
            offset: n.dot(&point.coords),
            current: Vector3::zeros(),
        })
    }

    /// The same plane with a uniform current (m/s).
    pub fn with_current(mut self, current: Vector3<f64>) -> Self {
        self.current = current;
        self
    }
}

impl Surface for Plane {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        (self.normal.x == 0.0 && self.normal.z == 0.0).then_some((self.offset, self.offset))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        (self.offset - self.normal.x * x - self.normal.z * z) / self.normal.y
    }
    fn slope(&self, _x: f64, _z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        [-self.normal.x / self.normal.y, -self.normal.z / self.normal.y]
    }
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        self.current
    }
    fn kind(&self, _t: f64) -> SurfaceKind {
        SurfaceKind::Plane {
            normal: self.normal,
            offset: self.offset,
        }
    }
}

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
            if rx.abs() + rz.abs() < 1e-12 * (1.0 + x.abs() + z.abs()) {
                break;
            }
        }
        (x0, z0)
    }

    /// The horizontal position of the particle at rest position `(x0, z0)`,
    /// its Jacobian over the rest position and the gradient of its height.
    fn jet(&self, x0: f64, z0: f64, t: f64) -> Jet {
        let (mut px, mut pz) = (x0, z0);
        let (mut jxx, mut jxz, mut jzz) = (1.0, 0.0, 1.0);
        let (mut gx, mut gz) = (0.0, 0.0);
        for w in &self.cache {
            let th = w.k * (w.dir.x * x0 + w.dir.y * z0) - w.omega * t + w.phase;
            let (s, c) = th.sin_cos();
            px -= w.qa * w.dir.x * s;
            pz -= w.qa * w.dir.y * s;
            let f = w.qa * w.k * c;
            jxx -= f * w.dir.x * w.dir.x;
            jxz -= f * w.dir.x * w.dir.y;
            jzz -= f * w.dir.y * w.dir.y;
            let e = w.a * w.k * s;
            gx -= e * w.dir.x;
            gz -= e * w.dir.y;
        }
        Jet {
            position: [px, pz],
            jacobian: [jxx, jxz, jzz],
            height_gradient: [gx, gz],
        }
    }
}

/// A Gerstner particle's horizontal position (m), the symmetric Jacobian
/// `[xx, xz, zz]` of that position over its rest position, and the gradient
/// of its height over its rest position.
struct Jet {
    position: [f64; 2],
    jacobian: [f64; 3],
    height_gradient: [f64; 2],
}

impl Surface for Gerstner {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        let a: f64 = self.waves.iter().map(|w| w.amplitude).sum();
        Some((self.level - a, self.level + a))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
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
            self.velocity_at_rest(x0, z0, p.y, t)
        } else {
            Vector3::zeros()
        };
        (height - p.y, v)
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
        let [jxx, jxz, jzz] = jet.jacobian;
        let [gx, gz] = jet.height_gradient;
        let det = jxx * jzz - jxz * jxz;
        if det.abs() < 1e-12 {
            return [0.0, 0.0];
        }
        [(jzz * gx - jxz * gz) / det, (jxx * gz - jxz * gx) / det]
    }

    /// Orbital velocity of the surface particle above `p`, decaying as
    /// `e^{k·(y − level)}` below the mean level (Airy theory).
    fn velocity(&self, p: &Point3<f64>, t: f64) -> Vector3<f64> {
        let (x0, z0) = self.rest_position(p.x, p.z, t);
        self.velocity_at_rest(x0, z0, p.y, t)
    }
}

impl Gerstner {
    fn velocity_at_rest(&self, x0: f64, z0: f64, y: f64, t: f64) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        for w in &self.cache {
            let th = w.k * (w.dir.x * x0 + w.dir.y * z0) - w.omega * t + w.phase;
            let (s, c) = th.sin_cos();
            let decay = (w.k * (y - self.level).min(0.0)).exp();
            v.x += w.qa * w.dir.x * w.omega * c * decay;
            v.z += w.qa * w.dir.y * w.omega * c * decay;
            v.y += w.a * w.omega * s * decay;
        }
        v
    }
}

/// Heights sampled on a regular grid, bilinearly interpolated; outside the
/// grid the nearest edge value holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeightField {
    /// World `(x, z)` of sample `(0, 0)`, m.
    pub origin: [f64; 2],
    /// Spacing between samples along x and z, m.
    pub spacing: [f64; 2],
    /// Samples along x.
    pub nx: usize,
    /// Samples along z.
    pub nz: usize,
    /// Heights, m, row-major with x fastest: `heights[iz * nx + ix]`.
    pub heights: Vec<f64>,
    /// Uniform current, m/s.
    #[serde(default)]
    pub current: [f64; 3],
}

impl HeightField {
    /// A validated height field.
    pub fn new(
        origin: [f64; 2],
        spacing: [f64; 2],
        nx: usize,
        nz: usize,
        heights: Vec<f64>,
    ) -> Result<Self, WaterError> {
        if nx < 2 || nz < 2 || heights.len() != nx * nz {
            return Err(WaterError::HeightFieldShape {
                nx,
                nz,
                len: heights.len(),
            });
        }
        for (name, v) in [("spacing x", spacing[0]), ("spacing z", spacing[1])] {
            if !(v.is_finite() && v > 0.0) {
                return Err(WaterError::Parameter { name, value: v });
            }
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(WaterError::HeightFieldSample {
                index: i,
                value: heights[i],
            });
        }
        Ok(Self {
            origin,
            spacing,
            nx,
            nz,
            heights,
            current: [0.0; 3],
        })
    }
}

/// The grid cell under a point: its corner heights `[h00, h10, h01, h11]`,
/// the point's fractions `(u, v)` across it, and whether the point is
/// inside the grid along x and z (outside, the edge value holds).
struct Cell {
    corners: [f64; 4],
    u: f64,
    v: f64,
    inside: [bool; 2],
}

impl HeightField {
    fn cell(&self, x: f64, z: f64) -> Cell {
        let gx = (x - self.origin[0]) / self.spacing[0];
        let gz = (z - self.origin[1]) / self.spacing[1];
        let (nx, nz) = ((self.nx - 1) as f64, (self.nz - 1) as f64);
        let (fx, fz) = (gx.clamp(0.0, nx), gz.clamp(0.0, nz));
        let (ix, iz) = ((fx as usize).min(self.nx - 2), (fz as usize).min(self.nz - 2));
        let h = |i: usize, j: usize| self.heights[j * self.nx + i];
        Cell {
            corners: [h(ix, iz), h(ix + 1, iz), h(ix, iz + 1), h(ix + 1, iz + 1)],
            u: fx - ix as f64,
            v: fz - iz as f64,
            inside: [(0.0..=nx).contains(&gx), (0.0..=nz).contains(&gz)],
        }
    }
}

impl Surface for HeightField {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        let lo = self.heights.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = self.heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Some((lo, hi))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        let c = self.cell(x, z);
        let [h00, h10, h01, h11] = c.corners;
        (1.0 - c.v) * ((1.0 - c.u) * h00 + c.u * h10) + c.v * ((1.0 - c.u) * h01 + c.u * h11)
    }
    /// The bilinear interpolant's slope; zero across an axis outside the
    /// grid, where the edge value holds.
    fn slope(&self, x: f64, z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        let c = self.cell(x, z);
        let [h00, h10, h01, h11] = c.corners;
        let sx = if c.inside[0] {
            ((1.0 - c.v) * (h10 - h00) + c.v * (h11 - h01)) / self.spacing[0]
        } else {
            0.0
        };
        let sz = if c.inside[1] {
            ((1.0 - c.u) * (h01 - h00) + c.u * (h11 - h10)) / self.spacing[1]
        } else {
            0.0
        };
        [sx, sz]
    }
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        Vector3::from(self.current)
    }
}

/// A fluid without a free surface: bodies are wholly immersed (air).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Unbounded {
    /// Uniform wind or current, m/s.
    pub current: [f64; 3],
}

impl Surface for Unbounded {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        Some((f64::INFINITY, f64::INFINITY))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, _x: f64, _z: f64, _t: f64) -> f64 {
        f64::INFINITY
    }
    fn slope(&self, _x: f64, _z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        [0.0, 0.0]
    }
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        Vector3::from(self.current)
    }
    fn kind(&self, _t: f64) -> SurfaceKind {
        SurfaceKind::Unbounded
    }
}

/// A fluid: its surface, density and the gravity that makes its pressure.
pub struct Water {
    /// The free surface and velocity field.
    pub surface: Box<dyn Surface>,
    /// Density, kg/m³.
    pub density: f64,
    /// Magnitude of gravity for hydrostatic pressure, m/s² (acting along −y).
    pub gravity: f64,
}

impl Water {
    /// Still fresh water with its surface at `y = level` (m).
    pub fn calm(level: f64) -> Self {
        Self::new(Plane::horizontal(level))
    }

    /// Fresh water (1000 kg/m³, standard gravity) with the given surface.
    pub fn new(surface: impl Surface + 'static) -> Self {
        Self {
            surface: Box::new(surface),
            density: WATER_DENSITY,
            gravity: STANDARD_GRAVITY,
        }
    }

    /// Air (1.2 kg/m³) everywhere: no free surface.
    pub fn air() -> Self {
        Self {
            surface: Box::new(Unbounded::default()),
            density: AIR_DENSITY,
            gravity: STANDARD_GRAVITY,
        }
    }

    /// The same water with another density (kg/m³).
    pub fn with_density(mut self, density: f64) -> Self {
        self.density = density;
        self
    }

    /// The same water with another gravity magnitude (m/s²).
    pub fn with_gravity(mut self, gravity: f64) -> Self {
        self.gravity = gravity;
        self
    }

    /// Checks density and gravity are finite and positive.
    pub fn validate(&self) -> Result<(), WaterError> {
        if !(self.density.is_finite() && self.density > 0.0) {
            return Err(WaterError::Parameter {
                name: "density",
                value: self.density,
            });
        }
        if !(self.gravity.is_finite() && self.gravity >= 0.0) {
            return Err(WaterError::Parameter {
                name: "gravity",
                value: self.gravity,
            });
        }
        Ok(())
    }
}

impl std::fmt::Debug for Water {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Water")
            .field("density", &self.density)
            .field("gravity", &self.gravity)
            .finish_non_exhaustive()
    }
}
