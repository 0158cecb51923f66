//! The surface trait every fluid implements, the fluid itself ([`Water`]:
//! a surface, a density and a gravity), and the standard constants.

use nalgebra::{Point3, Vector3};

use super::{DEFAULT_SEA_CELLS, Plane, SeaSpectrum, SpectralSea, SpectralSurface, Unbounded};
use crate::error::WaterError;

/// Density of fresh water, kg/m³.
pub const WATER_DENSITY: f64 = 1000.0;
/// Density of air at sea level and 20 °C, kg/m³.
pub const AIR_DENSITY: f64 = 1.2;
/// Standard gravity, m/s².
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Fills `out` with `node(x, z, hint)` at the nodes of the grid of
/// [`Surface::sample_nodes`], row by row, `hint` (zeroed at the start)
/// carried from each node to the next.
pub(crate) fn fill_nodes(
    origin: [f64; 2],
    spacing: f64,
    nodes: [usize; 2],
    out: &mut [SurfaceNode],
    mut node: impl FnMut(f64, f64, &mut [f64; 2]) -> SurfaceNode,
) {
    let mut hint = [0.0; 2];
    for (k, slot) in out.iter_mut().enumerate().take(nodes[0] * nodes[1]) {
        let [x, z] = node_at(origin, spacing, nodes, k);
        *slot = node(x, z, &mut hint);
    }
}

/// Where node `k` of the grid of [`Surface::sample_nodes`] is, `(x, z)`
/// (m): node `(k mod nodes[0], k div nodes[0])`.
pub(crate) fn node_at(origin: [f64; 2], spacing: f64, nodes: [usize; 2], k: usize) -> [f64; 2] {
    let (i, j) = (k % nodes[0], k / nodes[0]);
    [origin[0] + i as f64 * spacing, origin[1] + j as f64 * spacing]
}

/// The surface at one node of a grid ([`Surface::sample_nodes`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceNode {
    /// The surface's height above the node, m.
    pub height: f64,
    /// Its slope `(∂f/∂x, ∂f/∂z)`, dimensionless.
    pub slope: [f64; 2],
    /// The hint a [`Surface::probe`] at the node leaves.
    pub hint: [f64; 2],
    /// The surface's twist `∂²f/∂x∂z` at the node (1/m), where the
    /// surface gives it ([`Surface::node_twists`]); `None` and a
    /// [`SurfacePatch`](super::SurfacePatch) takes differences of its
    /// nodes' slopes.
    pub twist: Option<f64>,
}

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
/// Five surfaces are provided: a [`Plane`] (horizontal or tilted), a sum of
/// [`Gerstner`](super::Gerstner) waves, a spectral sea
/// ([`SpectralSurface`](super::SpectralSurface)), a bilinear
/// [`HeightField`](super::HeightField), and an [`Unbounded`] medium (a
/// balloon in air: everything is immersed). Implement [`Surface`] for your
/// own.
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

    /// The length over which the surface's height changes shape at time
    /// `t`, m (the shortest wavelength of a sea), if it has one: evaluations
    /// sample the surface on a grid this fine or finer
    /// ([`SeaSampling`](crate::SeaSampling)) instead of reading it at every
    /// texel. `None` (the default) reads it at every texel.
    fn sampling_length(&self, _t: f64) -> Option<f64> {
        None
    }

    /// The surface without some of its waves shorter than `wavelength` (m),
    /// for a body over whose hull they average out
    /// ([`SeaBand`](crate::SeaBand)): never without a wave at least that
    /// long. `None` (the default) when the surface drops none: read it
    /// whole. A [`SpectralSurface`](super::SpectralSurface) answers with
    /// its sea on a coarser grid.
    fn band_limited(&self, wavelength: f64) -> Option<&dyn Surface> {
        let _ = wavelength;
        None
    }

    /// The concrete surface, for backends that handle known surfaces
    /// natively (the GPU evaluates [`Plane`], [`Gerstner`](super::Gerstner),
    /// [`HeightField`](super::HeightField) and [`Unbounded`] itself). `None`
    /// for other surfaces.
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

    /// The surface's heights above the points `(x, z)` of `points` (m) at
    /// time `t` (s), m, written to `out` (as long as `points`). `hint` is
    /// [`Surface::probe`]'s, carried from each point to the next. The
    /// default probes point by point; a surface that evaluates something
    /// per time (a spectral sea's tile) looks it up once.
    fn heights_at(&self, points: &[[f64; 2]], t: f64, hint: &mut [f64; 2], out: &mut [f64]) {
        for (&[x, z], h) in points.iter().zip(out.iter_mut()) {
            *h = self.probe(&Point3::new(x, 0.0, z), t, false, hint).0;
        }
    }

    /// [`Surface::heights_at`] for points near `centre` (m, within a
    /// body's reach), `hint` being [`Surface::probe`]'s at `centre`: the
    /// heights the plane read ([`SeaSampling::Plane`](crate::SeaSampling::Plane))
    /// fits its plane to. The default is [`Surface::heights_at`]. A surface
    /// whose height at a point is found by inverting a map may instead
    /// carry the height of a particle near the point to it along the
    /// surface's slope, after one step from the centre's particle: a
    /// spectral sea misses each point by about `½ |D''| ρ²` (`D''` the
    /// second derivatives of its horizontal displacement, `ρ` the point's
    /// distance from the centre; read again a step on where that is over
    /// a centimetre) and its heights by `½ |f''|` times that squared, far
    /// below the plane read's own error `|f''| ρ²/8`: within 1e-6 m for
    /// bodies up to 5 m across on a JONSWAP sea of significant height 2 m
    /// and peak period 8 s, 5e-5 m on one of 4 s (`tests/sea_plane.rs`).
    fn heights_near(
        &self,
        centre: [f64; 2],
        points: &[[f64; 2]],
        t: f64,
        hint: &mut [f64; 2],
        out: &mut [f64],
    ) {
        let _ = centre;
        self.heights_at(points, t, hint, out);
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

    /// Readies the surface for reads at time `t` (s) from many threads at
    /// once: a surface that evaluates something for every reader at a
    /// time (a spectral sea's tile) does it here, with every thread,
    /// rather than in the first read while the others wait for it. The
    /// default does nothing; reads are correct without it.
    fn prepare(&self, t: f64) {
        let _ = t;
    }

    /// Whether [`Surface::sample_nodes`] gives every node its twist
    /// ([`SurfaceNode::twist`]): a patch of such a surface then needs no
    /// nodes beyond the region it covers (the twists at its edges are
    /// not differences of slopes across them). The default is `false`.
    fn node_twists(&self) -> bool {
        false
    }

    /// Heights and slopes at the nodes of a square grid at time `t` (s):
    /// node `(i, j)` at `(origin[0] + i spacing, origin[1] + j spacing)`
    /// (m), stored at `j nodes[0] + i` of `out` (its length
    /// `nodes[0] nodes[1]`), each with the hint a [`Surface::probe`] there
    /// leaves. The default probes and takes the slope node by node, each
    /// probe warm-starting the next; a surface that can share work across
    /// the nodes (a spectral sea looks its tile up once) overrides it.
    fn sample_nodes(
        &self,
        t: f64,
        origin: [f64; 2],
        spacing: f64,
        nodes: [usize; 2],
        out: &mut [SurfaceNode],
    ) {
        fill_nodes(origin, spacing, nodes, out, |x, z, hint| {
            let (height, _) = self.probe(&Point3::new(x, 0.0, z), t, false, hint);
            SurfaceNode {
                height,
                slope: self.slope(x, z, t, hint),
                hint: *hint,
                twist: None,
            }
        });
    }

    /// The fluid's velocity at time `t` (s) at the nodes of a box grid,
    /// m/s: the columns of [`Surface::sample_nodes`]' grid (`origin`,
    /// `spacing`, `nodes`) whose surface `columns` holds as `sample_nodes`
    /// filled it, at the heights `ys` (m); the velocity at height `ys[l]`
    /// of column `(i, j)` is stored at `(l nodes[1] + j) nodes[0] + i` of
    /// `out` (its length `ys.len() nodes[0] nodes[1]`). Above a column's
    /// surface the velocity is the surface's own. The default reads
    /// [`Surface::velocity_under`] at each node under its column's surface
    /// and once for all of a column's nodes above it; a surface that can
    /// share work across the grid (a spectral sea looks its tile up once
    /// and interpolates each column once) overrides it.
    #[allow(clippy::too_many_arguments)]
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
        let mut at_surface: Vec<Option<Vector3<f64>>> = vec![None; n];
        for (l, &y) in ys.iter().enumerate() {
            for (k, column) in columns.iter().enumerate().take(n) {
                let above = y >= column.height;
                let v = match at_surface[k] {
                    Some(v) if above => v,
                    _ => {
                        let [x, z] = node_at(origin, spacing, nodes, k);
                        let p = Point3::new(x, y.min(column.height), z);
                        let v = self.velocity_under(&p, t, column.height, &column.hint);
                        if above {
                            at_surface[k] = Some(v);
                        }
                        v
                    }
                };
                out[l * n + k] = v;
            }
        }
    }

    /// The fluid's velocity at `p` (m) and time `t` (s), m/s, where the
    /// surface above `p` is known to be at `height` (m) and `hint` is a
    /// probe's there. The default probes again; surfaces whose velocity
    /// needs no inversion of the surface override it.
    fn velocity_under(&self, p: &Point3<f64>, t: f64, height: f64, hint: &[f64; 2]) -> Vector3<f64> {
        let _ = height;
        let mut hint = *hint;
        self.probe(p, t, true, &mut hint).1
    }

    /// Depth of `p` below the surface, m (positive under water, measured vertically).
    fn depth(&self, p: &Point3<f64>, t: f64) -> f64 {
        self.height(p.x, p.z, t) - p.y
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

    /// Fresh water (1000 kg/m³, standard gravity) whose surface is the sea
    /// `spectrum` realised from `seed` at mean level 0 on the spectrum's
    /// default tile ([`SeaSpectrum::default_tile`]: eight peak wavelengths
    /// across) of [`DEFAULT_SEA_CELLS`] nodes a side, choppiness 1. For
    /// another tile, level or choppiness, realise a [`SpectralSea`] and hand
    /// it to [`Water::new`] through a [`SpectralSurface`].
    ///
    /// ```
    /// use soak_hydro::{SeaSpectrum, Water};
    /// // A JONSWAP sea of significant height 2 m and peak period 8 s.
    /// let water = Water::spectral(&SeaSpectrum::jonswap(2.0, 8.0), 7)?;
    /// assert!(water.surface.height(0.0, 0.0, 0.0).abs() < 5.0);
    /// # Ok::<(), soak_hydro::WaterError>(())
    /// ```
    ///
    /// # Errors
    /// [`WaterError::Parameter`] naming what is invalid in `spectrum`.
    pub fn spectral(spectrum: &SeaSpectrum, seed: u64) -> Result<Self, WaterError> {
        let sea = SpectralSea::realize(
            spectrum,
            0.0,
            spectrum.default_tile(STANDARD_GRAVITY),
            DEFAULT_SEA_CELLS,
            seed,
            STANDARD_GRAVITY,
        )?;
        Ok(Self::new(SpectralSurface::new(sea)))
    }

    /// The same fluid (its density and gravity) under another surface: a
    /// sea as one body reads it (sampled over its footprint, or one plane
    /// over it).
    pub fn under(&self, surface: impl Surface + 'static) -> Self {
        Self {
            surface: Box::new(surface),
            density: self.density,
            gravity: self.gravity,
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
