//! The texel atlas: a compact structure of arrays over the covered texels.

use nalgebra::{Matrix3, Point3, Vector3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::columns::Columns;
use crate::error::BakeError;

/// A run of consecutive texels that lie in one `tile_size`² block of the
/// texture and on one piece of the surface: a block holding texels of
/// charts laid side by side in the texture but apart on the mesh lays one
/// tile per piece, one after another (samples within two texel sides of
/// each other are of one piece).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Tile {
    /// Index of the tile's first texel in the atlas arrays.
    pub start: u32,
    /// One past the tile's last texel.
    pub end: u32,
}

impl Tile {
    /// The texel indices of this tile.
    #[inline]
    pub fn range(&self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// The moments of one [`Tile`]'s texels (object axes, positions relative
/// to [`Atlas::origin`]), from which closed forms over the tile are made:
/// under a plane the depth is affine in the position, and what a tile
/// under water adds to the buoyancy is linear in these; the area vectors'
/// component along any direction `u` weighted by `1`, `x` and `x xᵀ`
/// (`Σ_j u_j s0_j`, `s1ᵀ u`, `Σ_j u_j s2_j`) give the tile's share of a
/// section across the body ([`Atlas::tile_moments`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelMoments {
    /// Σ A, m².
    pub s0: Vector3<f64>,
    /// `s1[(j, k)] = Σ A_j x_k`, m³.
    pub s1: Matrix3<f64>,
    /// `s2[j][(k, l)] = Σ A_j x_k x_l`, m⁴.
    pub s2: [Matrix3<f64>; 3],
    /// Σ a, m².
    pub area: f64,
    /// Centre of the box around its texels, m.
    pub centre: Vector3<f64>,
    /// Half the sides of that box (object axes), m.
    pub half_extent: Vector3<f64>,
    /// Radius of the sphere about `centre` that holds its texels, m.
    pub radius: f64,
}

/// The sums of [`TexelMoments`]' `s0`, `s1` and `s2` over a run of tiles
/// ([`Atlas::tile_moment_sums`]): the moments of any run of consecutive
/// tiles are the difference of two running sums.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MomentSums {
    /// Σ A, m².
    pub s0: Vector3<f64>,
    /// `s1[(j, k)] = Σ A_j x_k`, m³.
    pub s1: Matrix3<f64>,
    /// `s2[j][(k, l)] = Σ A_j x_k x_l`, m⁴.
    pub s2: [Matrix3<f64>; 3],
    /// Σ a, m².
    pub area: f64,
}

impl std::ops::Sub for MomentSums {
    type Output = Self;
    /// The moments of the tiles counted in `self` and not in `rhs`.
    fn sub(self, rhs: Self) -> Self {
        Self {
            s0: self.s0 - rhs.s0,
            s1: self.s1 - rhs.s1,
            s2: std::array::from_fn(|j| self.s2[j] - rhs.s2[j]),
            area: self.area - rhs.area,
        }
    }
}

impl std::ops::AddAssign<&MomentSums> for MomentSums {
    fn add_assign(&mut self, rhs: &MomentSums) {
        self.s0 += rhs.s0;
        self.s1 += rhs.s1;
        for j in 0..3 {
            self.s2[j] += rhs.s2[j];
        }
        self.area += rhs.area;
    }
}

impl std::ops::SubAssign<&MomentSums> for MomentSums {
    fn sub_assign(&mut self, rhs: &MomentSums) {
        self.s0 -= rhs.s0;
        self.s1 -= rhs.s1;
        for j in 0..3 {
            self.s2[j] -= rhs.s2[j];
        }
        self.area -= rhs.area;
    }
}

impl std::ops::AddAssign for MomentSums {
    fn add_assign(&mut self, rhs: Self) {
        *self += &rhs;
    }
}

/// [`Atlas::tile_moments`], [`Atlas::tile_centres`] and
/// [`Atlas::tile_moment_sums`], made together.
#[derive(Clone, Debug)]
pub(crate) struct MomentTables {
    tiles: Vec<TexelMoments>,
    centres: Vec<Vector3<f64>>,
    sums: Vec<MomentSums>,
}

/// Surface samples of a mesh, one per covered texel of its UV map, stored as a
/// structure of arrays in tile order.
///
/// Texel `i` sits at object-space position [`Atlas::position`]`(i)` and
/// carries the oriented area [`Atlas::area_vectors`]`[i]` (m², along the
/// outward face normal): the area of its triangle divided by the number of
/// texels the triangle covers. A triangle too small to cover any texel centre
/// gets one sample at its centroid carrying its whole area, so sums over
/// texels integrate over the whole surface at every resolution.
///
/// Samples start at texel centres; by default each triangle's samples are then
/// nudged by a fraction of a texel so their mean and covariance equal the
/// triangle's (moment matching, [`crate::BakeOptions::moment_matching`]): every
/// integral of a polynomial up to degree two over a whole triangle is then
/// exact, which removes the first-order error that partly covered texels along
/// triangle edges give to centres, inertias and torques.
///
/// Positions are stored in f32 relative to [`Atlas::origin`] (the bounding-box
/// centre), which keeps their precision at any distance from the object
/// origin; accumulate sums in f64.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Atlas {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) tile_size: u32,
    pub(crate) origin: [f64; 3],
    pub(crate) local_positions: Columns,
    pub(crate) area_vectors: Columns,
    pub(crate) areas: Vec<f32>,
    pub(crate) triangle_ids: Vec<u32>,
    pub(crate) barycentrics: Vec<[f32; 2]>,
    pub(crate) texels: Vec<[u16; 2]>,
    pub(crate) centroid_samples: Vec<u32>,
    pub(crate) tiles: Vec<Tile>,
    pub(crate) triangles: Vec<[u32; 3]>,
    pub(crate) texels_per_triangle: Vec<u32>,
    pub(crate) vertex_count: usize,
    pub(crate) bounding_radius: f64,
    /// The first triangle of the caps of an open mesh ([`crate::cap_openings`]).
    #[serde(default)]
    pub(crate) first_opening: Option<u32>,
    /// [`Atlas::mean_thickness`], computed when first asked for (and again
    /// after a [`Atlas::refresh`]); not stored.
    #[serde(skip)]
    pub(crate) mean_thickness: std::sync::OnceLock<f64>,
    /// [`Atlas::tile_moments`], computed when first asked for (and again
    /// after a [`Atlas::refresh`]); not stored.
    #[serde(skip)]
    pub(crate) tile_moments: std::sync::OnceLock<MomentTables>,
    /// The factor of [`Atlas::coarsened`] (the product over nested
    /// coarsenings); `None` for a baked atlas.
    #[serde(default)]
    pub(crate) coarsening: Option<u32>,
}

/// Rounded-free summary of an atlas: counts and the integral invariants.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AtlasSummary {
    /// Texture width in texels.
    pub width: u32,
    /// Texture height in texels.
    pub height: u32,
    /// Number of samples (covered texels plus centroid samples).
    pub texels: usize,
    /// Number of mesh triangles.
    pub triangles: usize,
    /// Triangles represented by a single centroid sample.
    pub centroid_samples: usize,
    /// Number of non-empty tiles.
    pub tiles: usize,
    /// Σ a_i, m².
    pub area: f64,
    /// (1/3) Σ x_i·A_i, m³.
    pub volume: f64,
    /// |Σ A_i| / Σ a_i: zero for a closed mesh.
    pub closure: f64,
    /// Radius of the bounding sphere about the origin, m.
    pub bounding_radius: f64,
}

impl Atlas {
    /// Whether sample `i` lies on a cap that closes an opening of an open
    /// mesh ([`crate::cap_openings`]): part of the closed shape that
    /// displaces water, but not of the body's walls.
    #[inline]
    pub fn is_opening(&self, i: usize) -> bool {
        self.first_opening.is_some_and(|f| self.triangle_ids[i] >= f)
    }

    /// The first cap triangle, if the mesh was open (see [`Atlas::is_opening`]).
    pub fn first_opening_triangle(&self) -> Option<u32> {
        self.first_opening
    }

    /// Whether the baked mesh had openings closed by caps.
    pub fn has_openings(&self) -> bool {
        self.first_opening.is_some()
    }

    /// The samples on caps, in order (see [`Atlas::is_opening`]).
    pub fn opening_samples(&self) -> Vec<u32> {
        (0..self.len())
            .filter(|&i| self.is_opening(i))
            .map(|i| i as u32)
            .collect()
    }

    /// Area of the walls (every sample but the caps'), m²: the whole
    /// [`Atlas::area`] for a closed mesh.
    pub fn wall_area(&self) -> f64 {
        (0..self.len())
            .filter(|&i| !self.is_opening(i))
            .map(|i| self.areas[i] as f64)
            .sum()
    }

    /// Number of samples.
    #[inline]
    pub fn len(&self) -> usize {
        self.area_vectors.len()
    }

    /// Whether the atlas holds no sample (never true for a baked atlas).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.area_vectors.is_empty()
    }

    /// Texture width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Texture height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Side of the square texel blocks that [`Atlas::tiles`] group.
    pub fn tile_size(&self) -> u32 {
        self.tile_size
    }

    /// The reference point the positions are stored relative to (the mesh's
    /// bounding-box centre at bake time), object space, m.
    pub fn origin(&self) -> Point3<f64> {
        Point3::from(self.origin)
    }

    /// Sample positions relative to [`Atlas::origin`], m, one array per
    /// coordinate.
    pub fn local_positions(&self) -> &Columns {
        &self.local_positions
    }

    /// Object-space position of sample `i`, m.
    #[inline]
    pub fn position(&self, i: usize) -> Point3<f64> {
        let p = self.local_positions.get(i);
        Point3::new(
            self.origin[0] + p[0] as f64,
            self.origin[1] + p[1] as f64,
            self.origin[2] + p[2] as f64,
        )
    }

    /// Area vectors `A_i = a_i n_i`, m², with the outward face normal, one
    /// array per coordinate.
    pub fn area_vectors(&self) -> &Columns {
        &self.area_vectors
    }

    /// Texel areas `a_i = |A_i|`, m².
    pub fn areas(&self) -> &[f32] {
        &self.areas
    }

    /// Triangle each sample lies on.
    pub fn triangle_ids(&self) -> &[u32] {
        &self.triangle_ids
    }

    /// Barycentric coordinates `(λ1, λ2)` of each sample in its triangle
    /// (`λ0 = 1 − λ1 − λ2`).
    pub fn barycentrics(&self) -> &[[f32; 2]] {
        &self.barycentrics
    }

    /// Texel coordinates `(x, y)` of each sample, `x = ⌊u·W⌋`, `y = ⌊v·H⌋`.
    pub fn texels(&self) -> &[[u16; 2]] {
        &self.texels
    }

    /// Indices of the samples placed at the centroid of a triangle that covers no texel centre.
    pub fn centroid_samples(&self) -> &[u32] {
        &self.centroid_samples
    }

    /// Runs of samples per texture tile and piece of surface ([`Tile`]),
    /// in storage order.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// Triangles (vertex indices) of the mesh the atlas was baked from.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Number of triangles of the mesh the atlas was baked from.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices of the mesh the atlas was baked from.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Number of samples on each triangle.
    pub fn texels_per_triangle(&self) -> &[u32] {
        &self.texels_per_triangle
    }

    /// Radius of a sphere about [`Atlas::origin`] that holds every sample, m.
    pub fn bounding_radius(&self) -> f64 {
        self.bounding_radius
    }

    /// Σ a_i in m² (f64 accumulation).
    pub fn area(&self) -> f64 {
        self.areas.iter().map(|&a| a as f64).sum()
    }

    /// Σ A_i in m² (f64 accumulation); zero for a closed mesh.
    pub fn area_vector_sum(&self) -> Vector3<f64> {
        self.area_vectors
            .iter()
            .map(|a| Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64))
            .sum()
    }

    /// Mean thickness `3 V / A`, m: the enclosed volume over a third of the
    /// area (a sphere's radius; a slab's or a rod's width, however long),
    /// computed once (O(texels)) and kept until a [`Atlas::refresh`]. Zero
    /// where the samples enclose no volume (`V ≤ 0`, or no area).
    ///
    /// ```
    /// use nalgebra::Point3;
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// let mesh = builtin::cuboid(100.0, 1.0, 1.0);
    /// let mut rod = Atlas::bake(&mesh, BakeOptions::square(64))?;
    /// // 3 · 100 m³ / 402 m²: the rod's width, not its length.
    /// assert!((rod.mean_thickness() - 300.0 / 402.0).abs() < 1e-3);
    /// // Twice as wide and tall: 3 · 400 m³ / 808 m², once refreshed.
    /// let wider: Vec<_> = mesh.positions.iter().map(|p| Point3::new(p.x, 2.0 * p.y, 2.0 * p.z)).collect();
    /// rod.refresh(&wider)?;
    /// assert!((rod.mean_thickness() - 1200.0 / 808.0).abs() < 1e-3);
    /// # Ok::<(), soak_bake::BakeError>(())
    /// ```
    pub fn mean_thickness(&self) -> f64 {
        *self.mean_thickness.get_or_init(|| {
            let (volume, area) = (self.volume(), self.area());
            let t = 3.0 * volume / area;
            if volume > 0.0 && t.is_finite() { t } else { 0.0 }
        })
    }

    /// The moments of each tile's texels, in [`Atlas::tiles`]' order,
    /// computed once (O(texels), in parallel) and kept until a
    /// [`Atlas::refresh`].
    ///
    /// ```
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// let atlas = Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(64))?;
    /// // The tiles' area vectors close, and their areas are the box's.
    /// let (closure, area) = atlas.tile_moments().iter().fold((nalgebra::Vector3::zeros(), 0.0), |(c, a), m| (c + m.s0, a + m.area));
    /// assert!(closure.norm() < 1e-6 && (area - 3.76).abs() < 1e-5);
    /// // The running sums' last entry is the whole atlas' moments.
    /// let sums = atlas.tile_moment_sums();
    /// assert_eq!(sums.len(), atlas.tiles().len() + 1);
    /// assert!((sums[sums.len() - 1].s0 - closure).norm() < 1e-9);
    /// # Ok::<(), soak_bake::BakeError>(())
    /// ```
    pub fn tile_moments(&self) -> &[TexelMoments] {
        &self.moment_tables().tiles
    }

    /// Each tile's [`TexelMoments::centre`], in one array (for passes that
    /// look at where the tiles are, and at the moments of only some).
    pub fn tile_centres(&self) -> &[Vector3<f64>] {
        &self.moment_tables().centres
    }

    /// The running sums of [`Atlas::tile_moments`]: entry `k` holds the sums
    /// over the first `k` tiles (one more entry than tiles), so a run of
    /// tiles `a..b` has the moments `sums[b] − sums[a]`. Made with the
    /// moments, kept as they are.
    pub fn tile_moment_sums(&self) -> &[MomentSums] {
        &self.moment_tables().sums
    }

    /// The tiles' moments and their running sums, made on the first call.
    fn moment_tables(&self) -> &MomentTables {
        self.tile_moments.get_or_init(|| {
            let tiles: Vec<TexelMoments> = self
                .tiles
                .par_iter()
                .map(|t| {
                    let mut m = TexelMoments {
                        s0: Vector3::zeros(),
                        s1: Matrix3::zeros(),
                        s2: [Matrix3::zeros(); 3],
                        area: 0.0,
                        centre: Vector3::zeros(),
                        half_extent: Vector3::zeros(),
                        radius: 0.0,
                    };
                    let texel = |i: usize| {
                        let x = self.local_positions.get(i);
                        let a = self.area_vectors.get(i);
                        (
                            Vector3::new(x[0] as f64, x[1] as f64, x[2] as f64),
                            Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64),
                        )
                    };
                    let (mut lo, mut hi) = (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN));
                    for i in t.range() {
                        let (x, a) = texel(i);
                        lo = lo.inf(&x);
                        hi = hi.sup(&x);
                        m.s0 += a;
                        m.s1 += a * x.transpose();
                        let xx = x * x.transpose();
                        for j in 0..3 {
                            m.s2[j] += xx * a[j];
                        }
                        m.area += self.areas[i] as f64;
                    }
                    m.centre = (lo + hi) * 0.5;
                    m.half_extent = (hi - lo) * 0.5;
                    m.radius = t
                        .range()
                        .map(|i| (texel(i).0 - m.centre).norm())
                        .fold(0.0, f64::max);
                    m
                })
                .collect();
            let mut sums = Vec::with_capacity(tiles.len() + 1);
            let mut running = MomentSums::default();
            sums.push(running);
            for m in &tiles {
                running += MomentSums {
                    s0: m.s0,
                    s1: m.s1,
                    s2: m.s2,
                    area: m.area,
                };
                sums.push(running);
            }
            MomentTables {
                centres: tiles.iter().map(|m| m.centre).collect(),
                tiles,
                sums,
            }
        })
    }

    /// Enclosed volume by the divergence theorem, `(1/3) Σ x_i·A_i`, m³.
    pub fn volume(&self) -> f64 {
        self.local_positions
            .iter()
            .zip(self.area_vectors.iter())
            .map(|(x, a)| x[0] as f64 * a[0] as f64 + x[1] as f64 * a[1] as f64 + x[2] as f64 * a[2] as f64)
            .sum::<f64>()
            / 3.0
    }

    /// Counts and integral invariants.
    pub fn summary(&self) -> AtlasSummary {
        let area = self.area();
        AtlasSummary {
            width: self.width,
            height: self.height,
            texels: self.len(),
            triangles: self.triangles.len(),
            centroid_samples: self.centroid_samples.len(),
            tiles: self.tiles.len(),
            area,
            volume: self.volume(),
            closure: if area > 0.0 {
                self.area_vector_sum().norm() / area
            } else {
                0.0
            },
            bounding_radius: self.bounding_radius,
        }
    }

    /// Moves the samples with the mesh after it deformed (same triangles, new
    /// vertex positions, object space, m): positions from the stored
    /// barycentrics and area vectors from the new triangle areas. O(texels),
    /// no rasterisation. UV coverage, and so the texel count per triangle,
    /// stays that of the bake.
    ///
    /// # Errors
    /// [`BakeError::VertexCountMismatch`], [`BakeError::NonFiniteRefresh`],
    /// and [`BakeError::CoarsenedRefresh`] for a coarsened atlas (whose
    /// samples are not on single triangles: refresh the baked atlas and
    /// coarsen it again).
    pub fn refresh(&mut self, positions: &[Point3<f64>]) -> Result<(), BakeError> {
        if let Some(factor) = self.coarsening {
            return Err(BakeError::CoarsenedRefresh { factor });
        }
        if positions.len() != self.vertex_count {
            return Err(BakeError::VertexCountMismatch {
                given: positions.len(),
                expected: self.vertex_count,
            });
        }
        if let Some(vertex) = positions
            .iter()
            .position(|p| !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()))
        {
            return Err(BakeError::NonFiniteRefresh { vertex });
        }
        let o = Vector3::from(self.origin);
        let per_triangle: Vec<(Vector3<f64>, [Vector3<f64>; 3])> = self
            .triangles
            .iter()
            .zip(&self.texels_per_triangle)
            .map(|(t, &n)| {
                let [a, b, c] = t.map(|v| positions[v as usize].coords - o);
                (0.5 * (b - a).cross(&(c - a)) / n.max(1) as f64, [a, b, c])
            })
            .collect();
        use rayon::prelude::*;
        let [x, y, z] = self.local_positions.columns_mut();
        let [ax, ay, az] = self.area_vectors.columns_mut();
        let radius2 = (
            x.par_iter_mut(),
            y.par_iter_mut(),
            z.par_iter_mut(),
            ax.par_iter_mut(),
            ay.par_iter_mut(),
            az.par_iter_mut(),
            self.areas.par_iter_mut(),
            self.triangle_ids.par_iter(),
            self.barycentrics.par_iter(),
        )
            .into_par_iter()
            .map(|(x, y, z, ax, ay, az, area, &t, b)| {
                let (av, [p0, p1, p2]) = &per_triangle[t as usize];
                let (l1, l2) = (b[0] as f64, b[1] as f64);
                let p = p0 * (1.0 - l1 - l2) + p1 * l1 + p2 * l2;
                (*x, *y, *z) = (p.x as f32, p.y as f32, p.z as f32);
                (*ax, *ay, *az) = (av.x as f32, av.y as f32, av.z as f32);
                *area = av.norm() as f32;
                p.norm_squared()
            })
            .reduce(|| 0.0, f64::max);
        self.bounding_radius = radius2.sqrt();
        self.mean_thickness = std::sync::OnceLock::new();
        self.tile_moments = std::sync::OnceLock::new();
        Ok(())
    }

    /// Per-sample values of a W×H single-channel image laid over the UV square
    /// (row `y` holds texels with `v·H` in `[y, y+1)`), nearest texel. The image
    /// may have another resolution than the atlas; it is sampled at each
    /// sample's texel centre.
    ///
    /// # Panics
    /// If `image.len() != width * height` or a side is zero.
    pub fn sample_image(&self, image: &[f32], width: u32, height: u32) -> Vec<f32> {
        assert!(width > 0 && height > 0 && image.len() == (width * height) as usize);
        self.texels
            .iter()
            .map(|t| {
                let u = (t[0] as f64 + 0.5) / self.width as f64;
                let v = (t[1] as f64 + 0.5) / self.height as f64;
                let x = ((u * width as f64) as u32).min(width - 1);
                let y = ((v * height as f64) as u32).min(height - 1);
                image[(y * width + x) as usize]
            })
            .collect()
    }
}
