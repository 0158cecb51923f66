//! Rasterising a mesh's UV map into a texel atlas.

use nalgebra::{Point2, Point3, Vector3};
use rayon::prelude::*;

use crate::atlas::{Atlas, Tile};
use crate::columns::Columns;
use crate::error::BakeError;
use crate::mesh::Mesh;
use crate::pieces::{PIECE_LINK, pieces};
use crate::validate;

/// Largest texture side soak bakes, texels.
pub const MAX_RESOLUTION: u32 = 16384;
/// Default tile side, texels.
pub const DEFAULT_TILE_SIZE: u32 = 8;

/// Resolution and layout of a bake.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BakeOptions {
    /// Texture width in texels (1..=[`MAX_RESOLUTION`]).
    pub width: u32,
    /// Texture height in texels (1..=[`MAX_RESOLUTION`]).
    pub height: u32,
    /// Side of the square blocks the samples are grouped in (1..=256).
    pub tile_size: u32,
    /// Nudge each triangle's samples so their mean and covariance equal the
    /// triangle's (see [`Atlas`]); `false` keeps them at texel centres as in
    /// the thesis.
    pub moment_matching: bool,
}

impl BakeOptions {
    /// A square `n`×`n` texture with the default tile size.
    pub fn square(n: u32) -> Self {
        Self {
            width: n,
            height: n,
            tile_size: DEFAULT_TILE_SIZE,
            moment_matching: true,
        }
    }
}

impl Default for BakeOptions {
    fn default() -> Self {
        Self::square(256)
    }
}

struct Sample {
    key: u64,
    texel: [u16; 2],
    triangle: u32,
    bary: [f64; 2],
    centroid: bool,
}

/// Edge function of `c` against the directed edge `p → q`, computed with the
/// endpoints in a canonical order so both triangles sharing an edge get
/// bit-identical values of opposite sign.
#[inline]
fn edge(p: Point2<f64>, q: Point2<f64>, c: Point2<f64>) -> f64 {
    let e = |p: Point2<f64>, q: Point2<f64>| (q.x - p.x) * (c.y - p.y) - (q.y - p.y) * (c.x - p.x);
    if (p.x, p.y) <= (q.x, q.y) {
        e(p, q)
    } else {
        -e(q, p)
    }
}

/// Top-left ownership of points exactly on an edge with direction `d`
/// (counter-clockwise traversal): exactly one of `d` and `−d` owns them.
#[inline]
fn owns(d: nalgebra::Vector2<f64>) -> bool {
    d.y < 0.0 || (d.y == 0.0 && d.x < 0.0)
}

impl Atlas {
    /// Validates `mesh` (closed, manifold, outward, bijective UVs) and bakes it.
    ///
    /// # Example
    /// ```
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// let mesh = builtin::sphere(0.5, 48, 24);
    /// let atlas = Atlas::bake(&mesh, BakeOptions::square(256))?;
    /// let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    /// assert!((atlas.volume() - exact).abs() / exact < 0.01);
    /// # Ok::<(), soak_bake::BakeError>(())
    /// ```
    pub fn bake(mesh: &Mesh, options: BakeOptions) -> Result<Self, BakeError> {
        check_options(&options)?;
        validate::validate(mesh)?;
        Ok(bake_unchecked(mesh, options))
    }
}

fn check_options(o: &BakeOptions) -> Result<(), BakeError> {
    if o.width == 0 || o.height == 0 {
        return Err(BakeError::ZeroResolution {
            width: o.width,
            height: o.height,
        });
    }
    if o.width > MAX_RESOLUTION || o.height > MAX_RESOLUTION {
        return Err(BakeError::ResolutionTooLarge {
            width: o.width,
            height: o.height,
            max: MAX_RESOLUTION,
        });
    }
    if o.tile_size == 0 || o.tile_size > 256 {
        return Err(BakeError::TileSize(o.tile_size));
    }
    Ok(())
}

fn rasterise(mesh: &Mesh, t: usize, o: &BakeOptions, out: &mut Vec<Sample>) {
    let (w, h) = (o.width as f64, o.height as f64);
    let uv = mesh.triangle_uvs(t).expect("validated");
    let p = uv.map(|q| Point2::new(q.x * w, q.y * h));
    let area2 = edge(p[0], p[1], p[2]);
    let s = area2.signum();
    // Edge k is opposite vertex k; its direction in counter-clockwise order.
    let dirs = [p[2] - p[1], p[0] - p[2], p[1] - p[0]].map(|d| d * s);
    let lo = p[0].inf(&p[1]).inf(&p[2]);
    let hi = p[0].sup(&p[1]).sup(&p[2]);
    let x0 = ((lo.x - 0.5).ceil().max(0.0)) as u32;
    let y0 = ((lo.y - 0.5).ceil().max(0.0)) as u32;
    let x1 = ((hi.x - 0.5).floor().min(w - 1.0)) as i64;
    let y1 = ((hi.y - 0.5).floor().min(h - 1.0)) as i64;
    let ts = o.tile_size;
    let tiles_x = o.width.div_ceil(ts) as u64;
    let before = out.len();
    for y in y0 as i64..=y1 {
        for x in x0 as i64..=x1 {
            let c = Point2::new(x as f64 + 0.5, y as f64 + 0.5);
            let e = [edge(p[1], p[2], c), edge(p[2], p[0], c), edge(p[0], p[1], c)];
            let inside = (0..3).all(|k| {
                let v = e[k] * s;
                v > 0.0 || (v == 0.0 && owns(dirs[k]))
            });
            if inside {
                out.push(sample(
                    x as u32,
                    y as u32,
                    t,
                    [e[1] / area2, e[2] / area2],
                    ts,
                    tiles_x,
                ));
            }
        }
    }
    if out.len() == before {
        // No texel centre inside: one sample at the centroid carries the area.
        let c = Point2::from((p[0].coords + p[1].coords + p[2].coords) / 3.0);
        let x = (c.x.floor().max(0.0) as u32).min(o.width - 1);
        let y = (c.y.floor().max(0.0) as u32).min(o.height - 1);
        let mut s = sample(x, y, t, [1.0 / 3.0, 1.0 / 3.0], ts, tiles_x);
        s.centroid = true;
        out.push(s);
    }
}

#[inline]
fn sample(x: u32, y: u32, t: usize, bary: [f64; 2], ts: u32, tiles_x: u64) -> Sample {
    let tile = (y / ts) as u64 * tiles_x + (x / ts) as u64;
    let within = ((y % ts) * ts + (x % ts)) as u64;
    Sample {
        key: (tile << 16) | within,
        texel: [x as u16, y as u16],
        triangle: t as u32,
        bary,
        centroid: false,
    }
}

/// Bakes without validating. The mesh must satisfy [`validate::validate`].
pub(crate) fn bake_unchecked(mesh: &Mesh, options: BakeOptions) -> Atlas {
    let mut samples: Vec<Sample> = (0..mesh.triangles.len())
        .into_par_iter()
        .fold(Vec::new, |mut v, t| {
            rasterise(mesh, t, &options, &mut v);
            v
        })
        .flatten_iter()
        .collect();
    samples.par_sort_unstable_by_key(|s| (s.key, s.triangle));

    let (lo, hi) = mesh.bounds();
    let origin = nalgebra::center(&lo, &hi);
    let n_tri = mesh.triangles.len();
    let mut texels_per_triangle = vec![0u32; n_tri];
    for s in &samples {
        texels_per_triangle[s.triangle as usize] += 1;
    }
    if options.moment_matching {
        match_moments(&mut samples, n_tri);
    }
    let per_triangle: Vec<(Vector3<f64>, [Vector3<f64>; 3])> = (0..n_tri)
        .map(|t| {
            let pts = mesh.triangle_points(t).map(|p: Point3<f64>| p - origin);
            (mesh.triangle_area_vector(t) / texels_per_triangle[t] as f64, pts)
        })
        .collect();

    let position = |s: &Sample| {
        let (_, [p0, p1, p2]) = &per_triangle[s.triangle as usize];
        let [l1, l2] = s.bary;
        p0 * (1.0 - l1 - l2) + p1 * l1 + p2 * l2
    };
    // Each block's samples piece by piece, a tile per piece (`pieces`).
    let mut blocks = Vec::new();
    let mut start = 0;
    while start < samples.len() {
        let block = samples[start].key >> 16;
        let len = samples[start..]
            .iter()
            .take_while(|s| s.key >> 16 == block)
            .count();
        blocks.push(start..start + len);
        start += len;
    }
    let laid: Vec<(Vec<usize>, Vec<usize>)> = blocks
        .par_iter()
        .map(|r| {
            let points: Vec<Vector3<f64>> = samples[r.clone()].iter().map(position).collect();
            let side = samples[r.clone()]
                .iter()
                .map(|s| per_triangle[s.triangle as usize].0.norm().sqrt())
                .fold(0.0, f64::max);
            let (order, ends) = pieces(&points, PIECE_LINK * side);
            (order.into_iter().map(|i| r.start + i).collect(), ends)
        })
        .collect();

    let n = samples.len();
    let mut local_positions = Columns::with_capacity(n);
    let mut area_vectors = Columns::with_capacity(n);
    let mut areas = Vec::with_capacity(n);
    let mut triangle_ids = Vec::with_capacity(n);
    let mut barycentrics = Vec::with_capacity(n);
    let mut texels = Vec::with_capacity(n);
    let mut centroid_samples = Vec::new();
    let mut tiles: Vec<Tile> = Vec::new();
    let mut radius2 = 0.0f64;
    for (order, ends) in &laid {
        let mut begin = 0;
        for &end in ends {
            let first = areas.len() as u32;
            for s in order[begin..end].iter().map(|&k| &samples[k]) {
                let i = areas.len();
                let av = per_triangle[s.triangle as usize].0;
                let p = position(s);
                radius2 = radius2.max(p.norm_squared());
                local_positions.push([p.x as f32, p.y as f32, p.z as f32]);
                area_vectors.push([av.x as f32, av.y as f32, av.z as f32]);
                areas.push(av.norm() as f32);
                triangle_ids.push(s.triangle);
                barycentrics.push(s.bary.map(|l| l as f32));
                texels.push(s.texel);
                if s.centroid {
                    centroid_samples.push(i as u32);
                }
            }
            tiles.push(Tile {
                start: first,
                end: areas.len() as u32,
            });
            begin = end;
        }
    }
    Atlas {
        width: options.width,
        height: options.height,
        tile_size: options.tile_size,
        origin: [origin.x, origin.y, origin.z],
        local_positions,
        area_vectors,
        areas,
        triangle_ids,
        barycentrics,
        texels,
        centroid_samples,
        tiles,
        triangles: mesh.triangles.clone(),
        texels_per_triangle,
        vertex_count: mesh.positions.len(),
        bounding_radius: radius2.sqrt(),
        first_opening: mesh.first_opening_triangle(),
        mean_thickness: std::sync::OnceLock::new(),
        tile_moments: std::sync::OnceLock::new(),
        coarsening: None,
    }
}

/// Moves each triangle's samples, in barycentric space, so their mean is the
/// triangle's centroid `(1/3, 1/3)` and their covariance the uniform
/// triangle's (`Var λ = 1/18`, `Cov(λ1, λ2) = −1/36`). Positions are affine in
/// the barycentrics, so every integral of a polynomial up to degree two over a
/// whole triangle becomes exact. Texel-centre sampling has a first-order error
/// from partly covered texels along the edges; this removes it at bake time,
/// at no run-time cost. Triangles with fewer than 16 samples (or whose
/// covariance map would distort them by more than half) only get the mean
/// shifted; centroid samples are already exact. With very few samples per
/// triangle (textures far too small for the mesh) the shift can move a
/// triangle's few samples across a waterline together, so `soak accuracy`
/// reports both samplings.
fn match_moments(samples: &mut [Sample], n_tri: usize) {
    #[derive(Clone, Copy, Default)]
    struct Acc {
        n: f64,
        m: [f64; 2],
        c: [f64; 3],
    }
    let mut acc = vec![Acc::default(); n_tri];
    for s in samples.iter() {
        let a = &mut acc[s.triangle as usize];
        let [x, y] = s.bary;
        a.n += 1.0;
        a.m[0] += x;
        a.m[1] += y;
        a.c[0] += x * x;
        a.c[1] += x * y;
        a.c[2] += y * y;
    }
    // Per triangle: mean and the map L with L C_s Lᵀ = C_e (Cholesky factors).
    let exact = nalgebra::Matrix2::new(1.0 / 18.0, -1.0 / 36.0, -1.0 / 36.0, 1.0 / 18.0);
    let le = exact.cholesky().expect("positive definite").l();
    let maps: Vec<([f64; 2], nalgebra::Matrix2<f64>)> = acc
        .iter()
        .map(|a| {
            if a.n == 0.0 {
                return ([1.0 / 3.0; 2], nalgebra::Matrix2::identity());
            }
            let m = [a.m[0] / a.n, a.m[1] / a.n];
            let cov = nalgebra::Matrix2::new(
                a.c[0] / a.n - m[0] * m[0],
                a.c[1] / a.n - m[0] * m[1],
                a.c[1] / a.n - m[0] * m[1],
                a.c[2] / a.n - m[1] * m[1],
            );
            let l = if a.n >= 16.0 {
                cov.cholesky()
                    .and_then(|c| c.l().try_inverse())
                    .map(|inv| le * inv)
                    .filter(|l| (l - nalgebra::Matrix2::identity()).norm() < 0.5)
                    .unwrap_or_else(nalgebra::Matrix2::identity)
            } else {
                nalgebra::Matrix2::identity()
            };
            (m, l)
        })
        .collect();
    for s in samples.iter_mut() {
        if s.centroid {
            continue;
        }
        let (m, l) = &maps[s.triangle as usize];
        let d = l * nalgebra::Vector2::new(s.bary[0] - m[0], s.bary[1] - m[1]);
        s.bary = [1.0 / 3.0 + d.x, 1.0 / 3.0 + d.y];
    }
}
