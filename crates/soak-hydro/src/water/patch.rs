//! The water surface sampled once over a region: heights and slopes at the
//! nodes of a square grid, bicubic Hermite between them, and optionally the
//! fluid velocity on a three-dimensional grid, trilinear between its nodes.
//!
//! A Gerstner sea has no closed form for its height above a point: each
//! read inverts the Gerstner map (Newton's method over every wave). Read
//! per texel that is most of an evaluation's time. A patch pays the
//! inversion once per node instead, a few dozen nodes over a body's
//! footprint, and every texel then reads a polynomial. Its error is that of
//! bicubic Hermite interpolation, `O(Δ⁴)` in the node spacing `Δ`: the
//! spacing is an accuracy knob like the atlas resolution
//! ([`SeaSampling`](crate::SeaSampling)).

use nalgebra::{Matrix3, Point3, Vector3};

use super::{Surface, SurfaceNode};
use crate::error::WaterError;

/// Most nodes along one side of a patch's grid; a region that would need
/// more is sampled more coarsely (see [`SurfacePatch::sample`]).
pub const MAX_PATCH_NODES: usize = 256;

/// A surface sampled at one time over a rectangle of the horizontal plane.
///
/// Inside the rectangle [`Surface::height`] and [`Surface::slope`] are those
/// of the bicubic Hermite interpolant of the sampled heights, slopes and
/// twists (`∂²f/∂x∂z`: the surface's own where it gives them, otherwise
/// central differences of the slopes); outside it the
/// nearest edge cell's polynomial is read at the nearest point of the
/// rectangle. The time argument of the [`Surface`] methods is ignored: the
/// patch is the surface at the time it was sampled.
///
/// [`Surface::velocity`] is the trilinear interpolant of velocities sampled
/// on a grid over `[y_min, y_max]` as well, when the patch was sampled
/// with velocities; otherwise it is zero.
#[derive(Clone, Debug)]
pub struct SurfacePatch {
    /// World `(x, z)` of node `(0, 0)`, m.
    origin: [f64; 2],
    /// Node spacing, m.
    spacing: f64,
    /// Cells along x and z.
    cells: [usize; 2],
    /// Bicubic coefficients per cell, `a[p][q]` of `u^p v^q` (`u`, `v` the
    /// position across the cell along x and z, in cells), row-major cells
    /// with x fastest.
    coefficients: Vec<[[f64; 4]; 4]>,
    /// Lowest and highest value the interpolant can take, m.
    bounds: (f64, f64),
    /// The time the surface was sampled at, s.
    time: f64,
    velocity: Option<VelocityGrid>,
}

/// A patch's grid as a kernel reads it (see [`SurfacePatch::grid`]).
pub(crate) struct PatchGrid<'a> {
    /// World `(x, z)` of node `(0, 0)`, m.
    pub origin: [f64; 2],
    /// Node spacing, m.
    pub spacing: f64,
    /// Cells along x and z.
    pub cells: [usize; 2],
    /// Bicubic coefficients per cell, x fastest.
    pub coefficients: &'a [[[f64; 4]; 4]],
}

/// A patch's velocity grid as a kernel reads it (see
/// [`SurfacePatch::velocity_grid`]); its x and z run over the patch's
/// nodes, from the patch's origin.
#[cfg(feature = "gpu")]
pub(crate) struct PatchVelocityGrid<'a> {
    /// Lowest height of the grid, m.
    pub y0: f64,
    /// Nodes along x, y and z.
    pub nodes: [usize; 3],
    /// Cells along x, y and z (at least one each).
    pub cells: [usize; 3],
    /// Per cell, x fastest, then z, then y: the trilinear coefficients
    /// `c0..c7` (m/s, the fourth lane zero; see `VelocityGrid::at`).
    pub coefficients: &'a [[[f64; 4]; 8]],
}

/// Fluid velocities on a grid over the patch's rectangle and a height
/// range, kept per cell as the coefficients of the trilinear interpolant.
#[derive(Clone, Debug)]
struct VelocityGrid {
    /// Lowest height of the grid, m.
    y0: f64,
    /// The reciprocal of the spacing (horizontal and vertical alike), 1/m.
    inv_spacing: f64,
    /// Nodes along x, y and z.
    nodes: [usize; 3],
    /// Cells along x, y and z: one fewer than the nodes, and at least one
    /// (a single node makes a cell of no extent).
    cells: [usize; 3],
    /// Per cell, x fastest, then z, then y: `c[k]` of the trilinear
    /// `c0 + x c1 + z c2 + y c3 + x z c4 + x y c5 + z y c6 + x z y c7` in
    /// the fractions across the cell, each a velocity (m/s, the fourth
    /// lane zero).
    coefficients: Vec<[[f64; 4]; 8]>,
}

impl VelocityGrid {
    /// The grid of velocities `values` (m/s, at `nodes` nodes, x fastest,
    /// then z, then y), lowest at `y0`, `spacing` apart.
    fn new(y0: f64, spacing: f64, nodes: [usize; 3], values: &[[f64; 3]]) -> Self {
        let [nx, ny, nz] = nodes;
        let cells = nodes.map(|n| n.saturating_sub(1).max(1));
        let node = |i: usize, l: usize, k: usize| {
            let v = values[(l.min(ny - 1) * nz + k.min(nz - 1)) * nx + i.min(nx - 1)];
            [v[0], v[1], v[2], 0.0]
        };
        let mut coefficients = Vec::with_capacity(cells.iter().product());
        for l in 0..cells[1] {
            for k in 0..cells[2] {
                for i in 0..cells[0] {
                    let c = |di: usize, dl: usize, dk: usize| node(i + di, l + dl, k + dk);
                    let (c000, c100, c010, c110) = (c(0, 0, 0), c(1, 0, 0), c(0, 0, 1), c(1, 0, 1));
                    let (c001, c101, c011, c111) = (c(0, 1, 0), c(1, 1, 0), c(0, 1, 1), c(1, 1, 1));
                    // Corners named x z y; the coefficients of the
                    // products of the fractions.
                    let lane = |f: &dyn Fn(usize) -> f64| -> [f64; 4] { std::array::from_fn(f) };
                    coefficients.push([
                        c000,
                        lane(&|m| c100[m] - c000[m]),
                        lane(&|m| c010[m] - c000[m]),
                        lane(&|m| c001[m] - c000[m]),
                        lane(&|m| c110[m] - c010[m] - c100[m] + c000[m]),
                        lane(&|m| c101[m] - c001[m] - c100[m] + c000[m]),
                        lane(&|m| c011[m] - c001[m] - c010[m] + c000[m]),
                        lane(&|m| {
                            c111[m] - c011[m] - c101[m] - c110[m] + c100[m] + c010[m] + c001[m] - c000[m]
                        }),
                    ]);
                }
            }
        }
        Self {
            y0,
            inv_spacing: 1.0 / spacing,
            nodes,
            cells,
            coefficients,
        }
    }

    /// The velocity at `p` (world, m) and its derivatives `∂u_i/∂p_j`
    /// (1/s), those of the trilinear interpolant of the cell `p` lies in
    /// (clamped to the grid; no derivative along an axis it is clamped on).
    fn gradient(&self, origin: &[f64; 2], p: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        let inv = self.inv_spacing;
        // The cell along an axis, the fraction across it, and whether `q`
        // lies within the grid along it.
        let axis = |q: f64, nodes: usize, cells: usize| {
            let f = q.clamp(0.0, (nodes - 1) as f64);
            let i = (f as usize).min(cells - 1);
            (i, f - i as f64, q == f && nodes > 1)
        };
        let (i, fx, ix) = axis((p.x - origin[0]) * inv, self.nodes[0], self.cells[0]);
        let (l, fy, iy) = axis((p.y - self.y0) * inv, self.nodes[1], self.cells[1]);
        let (k, fz, iz) = axis((p.z - origin[1]) * inv, self.nodes[2], self.cells[2]);
        let c = &self.coefficients[(l * self.cells[2] + k) * self.cells[0] + i];
        let at = |m: usize| {
            c[0][m]
                + fx * c[1][m]
                + fz * c[2][m]
                + fy * c[3][m]
                + fx * fz * c[4][m]
                + fx * fy * c[5][m]
                + fz * fy * c[6][m]
                + fx * fz * fy * c[7][m]
        };
        let dx = |m: usize| c[1][m] + fz * c[4][m] + fy * c[5][m] + fz * fy * c[7][m];
        let dy = |m: usize| c[3][m] + fx * c[5][m] + fz * c[6][m] + fx * fz * c[7][m];
        let dz = |m: usize| c[2][m] + fx * c[4][m] + fy * c[6][m] + fx * fy * c[7][m];
        let on = |inside: bool| if inside { inv } else { 0.0 };
        let (sx, sy, sz) = (on(ix), on(iy), on(iz));
        (
            Vector3::from_fn(|m, _| at(m)),
            Matrix3::from_fn(|m, j| match j {
                0 => sx * dx(m),
                1 => sy * dy(m),
                _ => sz * dz(m),
            }),
        )
    }

    /// The velocity at `p` (world, m), clamped to the grid, multiply-adds
    /// fused where `FMA`.
    #[inline(always)]
    fn at<const FMA: bool>(&self, origin: &[f64; 2], p: &Vector3<f64>) -> [f64; 4] {
        #[inline(always)]
        fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
            if FMA { a.mul_add(b, c) } else { a * b + c }
        }
        // The cell along an axis and the fraction across it.
        #[inline(always)]
        fn axis(q: f64, nodes: usize, cells: usize) -> (usize, f64) {
            let f = q.clamp(0.0, (nodes - 1) as f64);
            let i = (f as usize).min(cells - 1);
            (i, f - i as f64)
        }
        let inv = self.inv_spacing;
        let (i, fx) = axis((p.x - origin[0]) * inv, self.nodes[0], self.cells[0]);
        let (l, fy) = axis((p.y - self.y0) * inv, self.nodes[1], self.cells[1]);
        let (k, fz) = axis((p.z - origin[1]) * inv, self.nodes[2], self.cells[2]);
        let c = &self.coefficients[(l * self.cells[2] + k) * self.cells[0] + i];
        std::array::from_fn(|m| {
            let a = madd::<FMA>(fx, c[1][m], c[0][m]);
            let b = madd::<FMA>(fx, c[4][m], c[2][m]);
            let e = madd::<FMA>(fx, c[5][m], c[3][m]);
            let d = madd::<FMA>(fx, c[7][m], c[6][m]);
            madd::<FMA>(fy, madd::<FMA>(fz, d, e), madd::<FMA>(fz, b, a))
        })
    }
}

/// Where a horizontal position falls in the patch: its cell and its
/// fractions `(u, v)` across it, clamped to the rectangle.
#[derive(Clone, Copy)]
struct Place {
    cell: usize,
    u: f64,
    v: f64,
}

/// The bicubic Hermite basis in matrix form: `p(u) = [1 u u² u³] M [f0 f1 f0' f1']ᵀ`.
const HERMITE: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [-3.0, 3.0, -2.0, -1.0],
    [2.0, -2.0, 1.0, 1.0],
];

impl SurfacePatch {
    /// Samples `surface` at time `t` (s) over the rectangle from `min` to
    /// `max` (world `(x, z)`, m), with nodes `spacing` m apart (widened so
    /// that neither side has more than [`MAX_PATCH_NODES`] nodes); with
    /// `velocity = Some((y_min, y_max))` also the fluid velocity between
    /// those heights (m), on a grid as fine vertically.
    ///
    /// The rectangle is rounded out to whole cells. Errors when a bound or
    /// the spacing is not finite, or the spacing not positive.
    pub fn sample(
        surface: &dyn Surface,
        t: f64,
        min: [f64; 2],
        max: [f64; 2],
        spacing: f64,
        velocity: Option<(f64, f64)>,
    ) -> Result<Self, WaterError> {
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(WaterError::Parameter {
                name: "patch spacing",
                value: spacing,
            });
        }
        for (name, value) in [
            ("patch min x", min[0]),
            ("patch min z", min[1]),
            ("patch max x", max[0]),
            ("patch max z", max[1]),
            ("patch time", t),
        ] {
            if !value.is_finite() {
                return Err(WaterError::Parameter { name, value });
            }
        }
        let extent = [(max[0] - min[0]).max(0.0), (max[1] - min[1]).max(0.0)];
        let widest = extent[0].max(extent[1]);
        let spacing = spacing.max(widest / (MAX_PATCH_NODES - 1) as f64);
        let cells = extent.map(|e| ((e / spacing).ceil() as usize).max(1));
        let nodes = [cells[0] + 1, cells[1] + 1];
        let origin = min;

        // Heights and slopes at the nodes, each with its probe's hint:
        // where the velocities are sampled above and below it, the surface
        // starts from there.
        let n = nodes[0] * nodes[1];
        let mut sampled = vec![SurfaceNode::default(); n];
        surface.sample_nodes(t, origin, spacing, nodes, &mut sampled);
        let h: Vec<f64> = sampled.iter().map(|s| s.height).collect();
        let sx: Vec<f64> = sampled.iter().map(|s| s.slope[0]).collect();
        let sz: Vec<f64> = sampled.iter().map(|s| s.slope[1]).collect();
        // Twists `∂²f/∂x∂z`: the surface's own where it gives them at
        // every node, otherwise central differences of the slopes
        // (one-sided at the edges), the mean of the two mixed derivatives.
        let diff = |f: &[f64], k: usize, i: usize, count: usize, stride: usize| -> f64 {
            match (i > 0, i + 1 < count) {
                (true, true) => (f[k + stride] - f[k - stride]) / (2.0 * spacing),
                (false, true) => (f[k + stride] - f[k]) / spacing,
                (true, false) => (f[k] - f[k - stride]) / spacing,
                (false, false) => 0.0,
            }
        };
        let twist: Vec<f64> = match sampled.iter().map(|s| s.twist).collect::<Option<Vec<f64>>>() {
            Some(exact) => exact,
            None => (0..n)
                .map(|k| {
                    let (i, j) = (k % nodes[0], k / nodes[0]);
                    0.5 * (diff(&sx, k, j, nodes[1], nodes[0]) + diff(&sz, k, i, nodes[0], 1))
                })
                .collect(),
        };
        for (name, values) in [
            ("patch height", &h),
            ("patch slope", &sx),
            ("patch slope", &sz),
            ("patch twist", &twist),
        ] {
            if let Some(v) = values.iter().find(|v| !v.is_finite()) {
                return Err(WaterError::Parameter { name, value: *v });
            }
        }

        let mut coefficients = Vec::with_capacity(cells[0] * cells[1]);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for j in 0..cells[1] {
            for i in 0..cells[0] {
                let k = [j * nodes[0] + i, j * nodes[0] + i + 1];
                let k1 = [k[0] + nodes[0], k[1] + nodes[0]];
                // F[a][b]: value (a, b < 2), u-derivative (a ≥ 2), v-derivative
                // (b ≥ 2) and twist, in cell units, at corner (a mod 2, b mod 2).
                let d = spacing;
                let f = [
                    [h[k[0]], h[k1[0]], d * sz[k[0]], d * sz[k1[0]]],
                    [h[k[1]], h[k1[1]], d * sz[k[1]], d * sz[k1[1]]],
                    [
                        d * sx[k[0]],
                        d * sx[k1[0]],
                        d * d * twist[k[0]],
                        d * d * twist[k1[0]],
                    ],
                    [
                        d * sx[k[1]],
                        d * sx[k1[1]],
                        d * d * twist[k[1]],
                        d * d * twist[k1[1]],
                    ],
                ];
                // A = M F Mᵀ.
                let mut mf = [[0.0; 4]; 4];
                for (r, row) in mf.iter_mut().enumerate() {
                    for (c, out) in row.iter_mut().enumerate() {
                        *out = (0..4).map(|m| HERMITE[r][m] * f[m][c]).sum();
                    }
                }
                let mut a = [[0.0; 4]; 4];
                for (r, row) in a.iter_mut().enumerate() {
                    for (c, out) in row.iter_mut().enumerate() {
                        *out = (0..4).map(|m| mf[r][m] * HERMITE[c][m]).sum();
                    }
                }
                // |p(u, v) − a00| ≤ Σ |a_pq| over the other terms on [0, 1]².
                let reach: f64 = a.iter().flatten().skip(1).map(|c| c.abs()).sum();
                lo = lo.min(a[0][0] - reach);
                hi = hi.max(a[0][0] + reach);
                coefficients.push(a);
            }
        }

        let velocity = match velocity {
            None => None,
            Some((y_min, y_max)) => Some(Self::sample_velocity(
                surface, t, origin, spacing, nodes, &sampled, y_min, y_max,
            )?),
        };
        Ok(Self {
            origin,
            spacing,
            cells,
            coefficients,
            bounds: (lo, hi),
            time: t,
            velocity,
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn sample_velocity(
        surface: &dyn Surface,
        t: f64,
        origin: [f64; 2],
        spacing: f64,
        nodes: [usize; 2],
        columns: &[SurfaceNode],
        y_min: f64,
        y_max: f64,
    ) -> Result<VelocityGrid, WaterError> {
        for (name, value) in [("patch velocity y min", y_min), ("patch velocity y max", y_max)] {
            if !value.is_finite() {
                return Err(WaterError::Parameter { name, value });
            }
        }
        let dy = spacing;
        let ny = (((y_max - y_min).max(0.0) / dy).ceil() as usize + 1).min(MAX_PATCH_NODES);
        let ys: Vec<f64> = (0..ny).map(|l| y_min + l as f64 * dy).collect();
        let mut sampled = vec![Vector3::zeros(); nodes[0] * nodes[1] * ny];
        surface.sample_velocities(t, origin, spacing, nodes, columns, &ys, &mut sampled);
        if let Some(c) = sampled.iter().flat_map(|v| v.iter()).find(|c| !c.is_finite()) {
            return Err(WaterError::Parameter {
                name: "patch velocity",
                value: *c,
            });
        }
        let values: Vec<[f64; 3]> = sampled.iter().map(|v| [v.x, v.y, v.z]).collect();
        Ok(VelocityGrid::new(y_min, dy, [nodes[0], ny, nodes[1]], &values))
    }

    /// Node spacing, m.
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// Nodes along x and z.
    pub fn nodes(&self) -> [usize; 2] {
        [self.cells[0] + 1, self.cells[1] + 1]
    }

    /// The time the surface was sampled at, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Whether velocities were sampled.
    pub fn has_velocity(&self) -> bool {
        self.velocity.is_some()
    }

    /// What a kernel needs to read the heights itself: the origin, the
    /// cells along x and z, and the bicubic coefficients per cell (see
    /// [`SurfacePatch::height_slope`] for their use).
    pub(crate) fn grid(&self) -> PatchGrid<'_> {
        PatchGrid {
            origin: self.origin,
            spacing: self.spacing,
            cells: self.cells,
            coefficients: &self.coefficients,
        }
    }

    /// What a kernel needs to read the velocities itself, when they were
    /// sampled; the grid's spacing is the patch's.
    #[cfg(feature = "gpu")]
    pub(crate) fn velocity_grid(&self) -> Option<PatchVelocityGrid<'_>> {
        self.velocity.as_ref().map(|g| PatchVelocityGrid {
            y0: g.y0,
            nodes: g.nodes,
            cells: g.cells,
            coefficients: &g.coefficients,
        })
    }

    #[inline]
    fn place(&self, x: f64, z: f64) -> Place {
        let gx = ((x - self.origin[0]) / self.spacing).clamp(0.0, self.cells[0] as f64);
        let gz = ((z - self.origin[1]) / self.spacing).clamp(0.0, self.cells[1] as f64);
        let (i, j) = (
            (gx as usize).min(self.cells[0] - 1),
            (gz as usize).min(self.cells[1] - 1),
        );
        Place {
            cell: j * self.cells[0] + i,
            u: gx - i as f64,
            v: gz - j as f64,
        }
    }

    /// The interpolant's Taylor coefficients at `(x, z)`, in one read:
    /// height (m), slope `(∂f/∂x, ∂f/∂z)`, second derivatives
    /// `(∂²f/∂x², ∂²f/∂x∂z, ∂²f/∂z²)` (1/m) and third derivatives
    /// `(f_xxx, f_xxz, f_xzz, f_zzz)` (1/m²), those of the cell's bicubic.
    pub fn taylor(&self, x: f64, z: f64) -> (f64, [f64; 2], [f64; 3], [f64; 4]) {
        let Place { cell, u, v } = self.place(x, z);
        let a = &self.coefficients[cell];
        // c_p(v) = Σ_q a_pq v^q and its derivatives, once each, then the
        // polynomials in u and their derivatives.
        let c: [f64; 4] = std::array::from_fn(|p| ((a[p][3] * v + a[p][2]) * v + a[p][1]) * v + a[p][0]);
        let dc: [f64; 4] = std::array::from_fn(|p| (3.0 * a[p][3] * v + 2.0 * a[p][2]) * v + a[p][1]);
        let ddc: [f64; 4] = std::array::from_fn(|p| 6.0 * a[p][3] * v + 2.0 * a[p][2]);
        let dddc: [f64; 4] = std::array::from_fn(|p| 6.0 * a[p][3]);
        let poly = |k: &[f64; 4]| ((k[3] * u + k[2]) * u + k[1]) * u + k[0];
        let du = |k: &[f64; 4]| (3.0 * k[3] * u + 2.0 * k[2]) * u + k[1];
        let duu = |k: &[f64; 4]| 6.0 * k[3] * u + 2.0 * k[2];
        let inv = 1.0 / self.spacing;
        let (inv2, inv3) = (inv * inv, inv * inv * inv);
        (
            poly(&c),
            [du(&c) * inv, poly(&dc) * inv],
            [duu(&c) * inv2, du(&dc) * inv2, poly(&ddc) * inv2],
            [
                6.0 * c[3] * inv3,
                duu(&dc) * inv3,
                du(&ddc) * inv3,
                poly(&dddc) * inv3,
            ],
        )
    }

    /// Height (m) and slope `(∂f/∂x, ∂f/∂z)` at `(x, z)`, in one read.
    #[inline]
    pub fn height_slope(&self, x: f64, z: f64) -> (f64, [f64; 2]) {
        let Place { cell, u, v } = self.place(x, z);
        let a = &self.coefficients[cell];
        // c_p(v) = Σ_q a_pq v^q and its derivative, then Horner in u.
        let c = |p: usize| ((a[p][3] * v + a[p][2]) * v + a[p][1]) * v + a[p][0];
        let dc = |p: usize| (3.0 * a[p][3] * v + 2.0 * a[p][2]) * v + a[p][1];
        let (c0, c1, c2, c3) = (c(0), c(1), c(2), c(3));
        let h = ((c3 * u + c2) * u + c1) * u + c0;
        let hu = (3.0 * c3 * u + 2.0 * c2) * u + c1;
        let hv = ((dc(3) * u + dc(2)) * u + dc(1)) * u + dc(0);
        let inv = 1.0 / self.spacing;
        (h, [hu * inv, hv * inv])
    }

    /// Fluid velocity at `p` (m/s): trilinear in the sampled grid, clamped
    /// to it; zero when velocities were not sampled.
    #[inline]
    pub fn velocity_at(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let [x, y, z, _] = self.velocity_lanes::<false>(p);
        Vector3::new(x, y, z)
    }

    /// [`SurfacePatch::velocity_at`] and its derivatives `∂u_i/∂p_j` (1/s)
    /// at `p`: the trilinear interpolant's, in the cell `p` lies in.
    pub fn velocity_gradient_at(&self, p: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        match &self.velocity {
            Some(g) => g.gradient(&self.origin, p),
            None => (Vector3::zeros(), Matrix3::zeros()),
        }
    }

    /// [`SurfacePatch::velocity_at`] as four lanes (the last zero),
    /// multiply-adds fused where `FMA` (for callers compiled with it).
    #[inline(always)]
    pub(crate) fn velocity_lanes<const FMA: bool>(&self, p: &Vector3<f64>) -> [f64; 4] {
        match &self.velocity {
            Some(g) => g.at::<FMA>(&self.origin, p),
            None => [0.0; 4],
        }
    }
}

impl Surface for SurfacePatch {
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        self.height_slope(x, z).0
    }
    fn velocity(&self, p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        self.velocity_at(&p.coords)
    }
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        Some(self.bounds)
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn slope(&self, x: f64, z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        self.height_slope(x, z).1
    }
}
