//! A coarser atlas made from a baked one by merging its samples
//! ([`Atlas::coarsened`]): the sampling of smooth surface integrals
//! (drag) that need far fewer points than the buoyancy's.

use nalgebra::Vector3;

use crate::atlas::{Atlas, Tile};
use crate::columns::Columns;
use crate::error::BakeError;
use crate::pieces::{PIECE_LINK, pieces};

/// Samples whose normals differ by more than this (cosine: 30°) are not
/// merged: a block of texels folded over an edge of the mesh keeps one
/// sample per side.
const NORMAL_COS: f64 = 0.866_025_403_784_438_6;

/// Samples farther apart than this many times `factor` texel sides (the
/// larger sample's, `√a`) are not merged: a block that straddles two
/// charts of the UV map keeps one sample per chart.
const REACH: f64 = 1.5;

/// One merged sample while it is built.
struct Cluster {
    /// The first sample's unit normal (zero for a sample without area).
    normal: Vector3<f64>,
    /// The first sample's position (relative to the origin), m.
    seed: Vector3<f64>,
    /// The first sample's texel side `√a`, m.
    side: f64,
    /// Σ a_i p_i, m³.
    moment: Vector3<f64>,
    /// Σ p_i, m (for a cluster without area).
    positions: Vector3<f64>,
    /// Σ A_i, m².
    area_vector: Vector3<f64>,
    /// Σ a_i, m².
    area: f64,
    count: usize,
    /// The member of largest area (its triangle and barycentrics are the
    /// cluster's).
    representative: usize,
    representative_area: f64,
}

impl Cluster {
    fn new(atlas: &Atlas, i: usize) -> Self {
        let (p, a, area) = sample(atlas, i);
        let norm = a.norm();
        Self {
            normal: if norm > 0.0 { a / norm } else { Vector3::zeros() },
            seed: p,
            side: area.sqrt(),
            moment: Vector3::zeros(),
            positions: Vector3::zeros(),
            area_vector: Vector3::zeros(),
            area: 0.0,
            count: 0,
            representative: i,
            representative_area: -1.0,
        }
    }

    /// Whether sample `i` belongs with this cluster's seed.
    fn admits(&self, atlas: &Atlas, i: usize, factor: f64) -> bool {
        let (p, a, area) = sample(atlas, i);
        let norm = a.norm();
        let facing =
            norm == 0.0 || self.normal == Vector3::zeros() || a.dot(&self.normal) >= NORMAL_COS * norm;
        let reach = REACH * factor * self.side.max(area.sqrt());
        facing && (p - self.seed).norm() <= reach
    }

    fn add(&mut self, atlas: &Atlas, i: usize) {
        let (p, a, area) = sample(atlas, i);
        let norm = a.norm();
        if self.normal == Vector3::zeros() && norm > 0.0 {
            // A seed without area has no normal: the first member with
            // area seeds the cluster, so the fold rule applies to the rest.
            (self.normal, self.seed, self.side) = (a / norm, p, area.sqrt());
        }
        self.moment += area * p;
        self.positions += p;
        self.area_vector += a;
        self.area += area;
        self.count += 1;
        if area > self.representative_area {
            self.representative = i;
            self.representative_area = area;
        }
    }

    fn position(&self) -> Vector3<f64> {
        if self.area > 0.0 {
            self.moment / self.area
        } else {
            self.positions / self.count as f64
        }
    }
}

/// Sample `i`'s position (relative to the origin), area vector and area.
fn sample(atlas: &Atlas, i: usize) -> (Vector3<f64>, Vector3<f64>, f64) {
    let p = atlas.local_positions.get(i).map(f64::from);
    let a = atlas.area_vectors.get(i).map(f64::from);
    (p.into(), a.into(), atlas.areas[i] as f64)
}

impl Atlas {
    /// A coarser sampling of the same surface: the samples of each
    /// `factor`² block of texels merged into one, as a bake at `1/factor`
    /// of this atlas' resolution would place one, with tiles of
    /// `tile_size`² merged texels. A merged sample carries its members'
    /// summed area vector `Σ A_i` and summed area `Σ a_i` (so the total
    /// area and `Σ A_i` are this atlas'; on a curved block `a` is a little
    /// more than `|A|`) at their area-weighted mean position. A block's
    /// samples are kept apart where they are not one piece of surface:
    /// normals more than 30° apart (a fold over an edge of the mesh), more
    /// than 1.5 `factor` texel sides apart (two charts of the UV map side
    /// by side), or one on a cap of an opening and one on the walls.
    ///
    /// Unlike a bake of the mesh at a lower resolution, a coarsened atlas
    /// has as few samples as its blocks whatever the mesh's triangle count
    /// (a bake takes at least one sample per triangle): the sampling for
    /// smooth surface integrals such as drag, made once per mesh. Its
    /// samples are not on single triangles, so it does not follow a
    /// deforming mesh: [`Atlas::refresh`] the baked atlas and coarsen it
    /// again. Its texel coordinates are its blocks' (the baked texel's
    /// over `factor`), its width and height the baked ones over `factor`
    /// rounded up; each sample's triangle and barycentrics are those of
    /// its largest member, and [`Atlas::texels_per_triangle`] counts
    /// those. It is a sampling for surface integrals, not a body's atlas
    /// for wetting, flooding, export or a deforming GPU upload.
    ///
    /// # Errors
    /// [`BakeError::Coarsening`] for a `factor` of zero or more than 256,
    /// [`BakeError::TileSize`] for a `tile_size` outside `1..=256`.
    ///
    /// ```
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// // 4,096 triangles: a 128² bake has about 10,000 samples, and no
    /// // bake of this mesh fewer than 4,096.
    /// let mesh = builtin::sphere(0.5, 64, 32);
    /// let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    /// let coarse = atlas.coarsened(4, 4)?;
    /// assert!(coarse.len() * 8 < atlas.len());
    /// // The same surface: its area, and its volume to a fraction of a percent.
    /// assert!((coarse.area() - atlas.area()).abs() < 1e-6 * atlas.area());
    /// assert!((coarse.volume() - atlas.volume()).abs() < 5e-3 * atlas.volume());
    /// # Ok::<(), soak_bake::BakeError>(())
    /// ```
    pub fn coarsened(&self, factor: u32, tile_size: u32) -> Result<Atlas, BakeError> {
        if factor == 0 || factor > 256 {
            return Err(BakeError::Coarsening { factor });
        }
        if tile_size == 0 || tile_size > 256 {
            return Err(BakeError::TileSize(tile_size));
        }
        let coarse = |t: [u16; 2]| [t[0] as u32 / factor, t[1] as u32 / factor];
        // Samples ordered by merged tile, then merged texel (row by row),
        // then walls before caps, then as they were.
        let key = |i: usize| {
            let [x, y] = coarse(self.texels[i]);
            let tile = (((y / tile_size) as u64) << 16) | (x / tile_size) as u64;
            (
                (tile << 32) | ((y as u64) << 16) | x as u64,
                self.is_opening(i),
                i,
            )
        };
        let mut order: Vec<usize> = (0..self.len()).collect();
        order.sort_unstable_by_key(|&i| key(i));

        let (width, height) = (self.width.div_ceil(factor), self.height.div_ceil(factor));
        let mut atlas = Atlas {
            width,
            height,
            tile_size,
            origin: self.origin,
            local_positions: Columns::default(),
            area_vectors: Columns::default(),
            areas: Vec::new(),
            triangle_ids: Vec::new(),
            barycentrics: Vec::new(),
            texels: Vec::new(),
            centroid_samples: Vec::new(),
            tiles: Vec::new(),
            triangles: self.triangles.clone(),
            texels_per_triangle: vec![0; self.triangles.len()],
            vertex_count: self.vertex_count,
            bounding_radius: 0.0,
            first_opening: self.first_opening,
            mean_thickness: std::sync::OnceLock::new(),
            tile_moments: std::sync::OnceLock::new(),
            coarsening: Some(self.coarsening().unwrap_or(1).saturating_mul(factor)),
        };
        let mut radius2 = 0.0f64;
        let mut clusters: Vec<Cluster> = Vec::new();
        // The merged samples of the tile being laid, and its block.
        let mut pending: Vec<Merged> = Vec::new();
        let mut pending_tile = None;
        let mut block = 0;
        while block < order.len() {
            let (block_key, opening, _) = key(order[block]);
            let end = block
                + order[block..]
                    .iter()
                    .position(|&i| {
                        let (k, o, _) = key(i);
                        (k, o) != (block_key, opening)
                    })
                    .unwrap_or(order.len() - block);
            clusters.clear();
            for &i in &order[block..end] {
                match clusters.iter_mut().find(|c| c.admits(self, i, factor as f64)) {
                    Some(c) => c.add(self, i),
                    None => {
                        let mut c = Cluster::new(self, i);
                        c.add(self, i);
                        clusters.push(c);
                    }
                }
            }
            let tile = block_key >> 32;
            if pending_tile != Some(tile) {
                lay_tile(&mut atlas, self, &mut pending, &mut radius2);
                pending_tile = Some(tile);
            }
            let texel = [(block_key & 0xffff) as u16, ((block_key >> 16) & 0xffff) as u16];
            pending.extend(clusters.iter().map(|c| Merged {
                position: c.position(),
                area_vector: c.area_vector,
                area: c.area,
                representative: c.representative,
                texel,
            }));
            block = end;
        }
        lay_tile(&mut atlas, self, &mut pending, &mut radius2);
        atlas.bounding_radius = radius2.sqrt();
        Ok(atlas)
    }

    /// The factor this atlas was coarsened by ([`Atlas::coarsened`]; the
    /// product of the factors of nested coarsenings); `None` for a baked
    /// atlas. A coarsened atlas does not [`Atlas::refresh`], even by 1 (which
    /// merges a triangle's centroid sample with the sample sharing its
    /// texel).
    pub fn coarsening(&self) -> Option<u32> {
        self.coarsening
    }
}

/// A merged sample waiting for the pieces of its tile.
struct Merged {
    position: Vector3<f64>,
    area_vector: Vector3<f64>,
    area: f64,
    /// The source sample whose triangle and barycentrics it takes.
    representative: usize,
    /// Its block, in the coarse texture.
    texel: [u16; 2],
}

/// Lays the merged samples of one `tile_size`² block of the coarse texture
/// (`pending`, emptied) into `atlas`: one tile per piece of surface among
/// them ([`pieces`], chained within [`PIECE_LINK`] texel sides), each
/// piece's samples in their order, the pieces in the order of their first
/// sample.
fn lay_tile(atlas: &mut Atlas, source: &Atlas, pending: &mut Vec<Merged>, radius2: &mut f64) {
    let link = PIECE_LINK * pending.iter().map(|m| m.area.sqrt()).fold(0.0, f64::max);
    let points: Vec<Vector3<f64>> = pending.iter().map(|m| m.position).collect();
    let (order, ends) = pieces(&points, link);
    let mut begin = 0;
    for end in ends {
        let start = atlas.areas.len() as u32;
        for m in order[begin..end].iter().map(|&i| &pending[i]) {
            let p = m.position;
            *radius2 = radius2.max(p.norm_squared());
            atlas.local_positions.push([p.x as f32, p.y as f32, p.z as f32]);
            let a = m.area_vector;
            atlas.area_vectors.push([a.x as f32, a.y as f32, a.z as f32]);
            atlas.areas.push(m.area as f32);
            let t = source.triangle_ids[m.representative];
            atlas.triangle_ids.push(t);
            atlas.texels_per_triangle[t as usize] += 1;
            atlas.barycentrics.push(source.barycentrics[m.representative]);
            atlas.texels.push(m.texel);
        }
        atlas.tiles.push(Tile {
            start,
            end: atlas.areas.len() as u32,
        });
        begin = end;
    }
    pending.clear();
}

#[cfg(test)]
/// The merged tile a tile of a coarsened atlas lies in (from its first
/// texel).
fn tile_of(atlas: &Atlas, tile: &Tile) -> u64 {
    let [x, y] = atlas.texels[tile.start as usize];
    let t = atlas.tile_size;
    (((y as u32 / t) as u64) << 16) | (x as u32 / t) as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BakeOptions, builtin, cap_openings};

    fn baked(mesh: &crate::Mesh, n: u32) -> Atlas {
        Atlas::bake(mesh, BakeOptions::square(n)).unwrap()
    }

    /// Σ a_i p_i about the origin, m³.
    fn first_moment(a: &Atlas) -> Vector3<f64> {
        (0..a.len()).map(|i| a.areas[i] as f64 * sample(a, i).0).sum()
    }

    /// The sums a merged sample carries are its members': area, area
    /// vector and first moment to the f32 storage's rounding, at every
    /// factor; on a box, whose blocks are flat, the enclosed volume too.
    #[test]
    fn merging_keeps_the_surface_sums() {
        for (mesh, flat) in [
            (builtin::cuboid(1.0, 0.6, 0.8), true),
            (builtin::sphere(0.5, 64, 32), false),
            (builtin::torus(1.0, 0.3, 48, 24), false),
        ] {
            let fine = baked(&mesh, 128);
            for k in [1, 2, 4, 8, 16] {
                let coarse = fine.coarsened(k, 4).unwrap();
                assert!(coarse.len() <= fine.len());
                assert_eq!(coarse.coarsening(), Some(k));
                let area = fine.area();
                assert!((coarse.area() - area).abs() < 1e-6 * area, "k {k}");
                assert!((coarse.area_vector_sum() - fine.area_vector_sum()).norm() < 1e-6 * area);
                let r = fine.bounding_radius();
                assert!((first_moment(&coarse) - first_moment(&fine)).norm() < 1e-6 * area * r);
                if flat {
                    assert!(
                        (coarse.volume() - fine.volume()).abs() < 1e-6 * fine.volume(),
                        "k {k}"
                    );
                }
                assert!(coarse.bounding_radius() <= r * (1.0 + 1e-6));
            }
        }
    }

    /// Blocks of the box's UV map hold faces side by side: no merged sample
    /// mixes two faces (each face has its own normal, so the fold rule
    /// decides), so every one is flat (`|A| = a`) and lies on the box's
    /// surface.
    #[test]
    fn faces_are_not_merged_across_folds_or_charts() {
        let h = [0.5, 0.3, 0.4];
        let fine = baked(&builtin::cuboid(1.0, 0.6, 0.8), 128);
        for k in [4, 16, 64] {
            let coarse = fine.coarsened(k, 4).unwrap();
            for i in 0..coarse.len() {
                let (p, a, area) = sample(&coarse, i);
                assert!(
                    a.norm() > (1.0 - 1e-5) * area,
                    "k {k}, sample {i}: |A| {} < a {area}",
                    a.norm()
                );
                let on = (0..3).map(|j| p[j].abs() / h[j]).fold(0.0, f64::max);
                assert!((on - 1.0).abs() < 1e-5, "k {k}, sample {i} at {p:?}");
            }
        }
    }

    /// The coarsened caps' area is the baked caps' and the walls' the
    /// walls' (on this open box the cap faces away from every wall, so the
    /// fold rule keeps them apart as well as the caps' own rule).
    #[test]
    fn caps_stay_apart_from_the_walls() {
        let mesh = cap_openings(&builtin::open_box(1.0, 0.6, 0.8)).unwrap();
        let fine = baked(&mesh, 128);
        assert!(fine.has_openings());
        let caps = |a: &Atlas| {
            (0..a.len())
                .filter(|&i| a.is_opening(i))
                .map(|i| a.areas[i] as f64)
                .sum::<f64>()
        };
        let coarse = fine.coarsened(8, 4).unwrap();
        assert!(caps(&fine) > 0.1);
        assert!((caps(&coarse) - caps(&fine)).abs() < 1e-6 * caps(&fine));
        assert!((coarse.wall_area() - fine.wall_area()).abs() < 1e-6 * fine.wall_area());
    }

    /// Two pieces of surface facing alike in one block of texels but far
    /// apart on the mesh (as two charts of a UV map side by side) are not
    /// merged: every other column of a box's texels moved 50 m along x,
    /// every merged sample lies on the box or on its moved copy, none
    /// between.
    #[test]
    fn pieces_apart_on_the_mesh_are_not_merged() {
        let mut atlas = baked(&builtin::cuboid(1.0, 0.6, 0.8), 64);
        let [x, _, _] = atlas.local_positions.columns_mut();
        for (x, t) in x.iter_mut().zip(&atlas.texels) {
            if t[0] % 2 == 1 {
                *x += 50.0;
            }
        }
        let coarse = atlas.coarsened(8, 4).unwrap();
        assert!((coarse.area() - atlas.area()).abs() < 1e-6 * atlas.area());
        for i in 0..coarse.len() {
            let p = sample(&coarse, i).0;
            let on = |dx: f64| (p.x - dx).abs() <= 0.5 + 1e-4;
            assert!(on(0.0) || on(50.0), "sample {i} at {p:?}");
        }
    }

    /// A sample without area (a triangle collapsed by a refresh) seeding a
    /// block does not open the block to every normal: the first member
    /// with area seeds it. A thin plate in one block, its first sample
    /// made arealess: the top and the bottom, a millimetre apart, stay
    /// apart (every merged sample flat).
    #[test]
    fn an_arealess_seed_keeps_the_fold_rule() {
        let mut atlas = baked(&builtin::cuboid(1.0, 1e-3, 1.0), 64);
        for c in atlas.area_vectors.columns_mut() {
            c[0] = 0.0;
        }
        atlas.areas[0] = 0.0;
        let coarse = atlas.coarsened(64, 4).unwrap();
        for i in 0..coarse.len() {
            let (_, a, area) = sample(&coarse, i);
            assert!(
                a.norm() > (1.0 - 1e-5) * area,
                "sample {i}: |A| {} < a {area}",
                a.norm()
            );
        }
    }

    /// Tiles are runs of samples in one `tile_size`² block of the coarse
    /// texture, covering every sample once, a block's runs one after
    /// another.
    #[test]
    fn tiles_are_runs_of_one_block() {
        for mesh in [builtin::sphere(0.5, 64, 32), builtin::cuboid(1.0, 0.6, 0.8)] {
            let fine = baked(&mesh, 128);
            let coarse = fine.coarsened(4, 4).unwrap();
            assert_eq!((coarse.width(), coarse.height()), (32, 32));
            let mut next = 0;
            let mut seen = std::collections::HashSet::new();
            let mut last = None;
            for tile in coarse.tiles() {
                assert_eq!(tile.start, next);
                assert!(tile.end > tile.start);
                let block = tile_of(&coarse, tile);
                assert!(
                    last == Some(block) || seen.insert(block),
                    "block {block} in runs apart"
                );
                last = Some(block);
                for i in tile.range() {
                    let [x, y] = coarse.texels()[i];
                    assert_eq!(((y as u64 / 4) << 16) | (x as u64 / 4), block);
                }
                next = tile.end;
            }
            assert_eq!(next as usize, coarse.len());
        }
    }

    /// A block holding samples of charts laid side by side in the texture
    /// but apart on the mesh (the box's faces) lays one tile per piece:
    /// each tile's samples chained within `PIECE_LINK` sides, no two tiles
    /// of a block that close, and every tile as small as a block of one
    /// chart (a tile of the box spanned 1.4 m before: two faces).
    #[test]
    fn a_block_of_charts_apart_lays_a_tile_per_piece() {
        let coarse = baked(&builtin::cuboid(1.0, 0.6, 0.8), 128)
            .coarsened(4, 4)
            .unwrap();
        let position = |i: usize| Vector3::from(coarse.local_positions().get(i).map(f64::from));
        let side = (0..coarse.len())
            .map(|i| f64::from(coarse.areas()[i]).sqrt())
            .fold(0.0, f64::max);
        let tiles = coarse.tiles();
        let mut split = 0;
        for (k, tile) in tiles.iter().enumerate() {
            let r = tile.range();
            let centre = r.clone().map(position).sum::<Vector3<f64>>() / r.len() as f64;
            let radius = r
                .clone()
                .map(|i| (position(i) - centre).norm())
                .fold(0.0, f64::max);
            // A block is 4 × 4 merged samples of about `side` each.
            assert!(
                radius <= 3.0 * side,
                "tile {k}: radius {radius} against a side of {side}"
            );
            if let Some(next) = tiles
                .get(k + 1)
                .filter(|n| tile_of(&coarse, n) == tile_of(&coarse, tile))
            {
                split += 1;
                let link = r
                    .clone()
                    .flat_map(|i| next.range().map(move |j| (i, j)))
                    .map(|(i, j)| (position(i) - position(j)).norm())
                    .fold(f64::MAX, f64::min);
                assert!(link > PIECE_LINK * side * 0.5, "tiles {k} and {}: {link}", k + 1);
            }
        }
        assert!(split > 0, "no block of the box's atlas holds two charts");
    }

    /// Hard cases: an atlas of centroid samples only (4,096 triangles at
    /// 8²), 1000:1 slivers, and scales from a millimetre to a kilometre:
    /// every merged sample finite, the area and the area vector kept, a
    /// factor larger than the texture one sample per piece of surface.
    #[test]
    fn hard_cases_stay_finite_and_keep_the_area() {
        let cases = [
            (builtin::sphere(0.5, 64, 32), 8),
            (builtin::cuboid(100.0, 0.1, 0.1), 64),
            (builtin::cuboid(1e-3, 6e-4, 8e-4), 128),
            (builtin::cuboid(1e3, 6e2, 8e2), 128),
            (builtin::sphere(1e3, 32, 16), 128),
        ];
        for (mesh, n) in cases {
            let fine = baked(&mesh, n);
            for k in [2, 8, 256] {
                let coarse = fine.coarsened(k, 4).unwrap();
                assert!(!coarse.is_empty() && coarse.len() <= fine.len());
                for i in 0..coarse.len() {
                    let (p, a, area) = sample(&coarse, i);
                    assert!(p.iter().chain(a.iter()).all(|v| v.is_finite()) && area.is_finite());
                }
                let area = fine.area();
                assert!(
                    (coarse.area() - area).abs() < 1e-6 * area,
                    "{} at {n}² by {k}",
                    mesh.name
                );
                assert!((coarse.area_vector_sum() - fine.area_vector_sum()).norm() < 1e-6 * area);
            }
        }
    }

    /// Factors out of range and refreshing a coarsened atlas are refused.
    #[test]
    fn bad_factors_and_refreshes_are_refused() {
        let mesh = builtin::cuboid(1.0, 0.6, 0.8);
        let fine = baked(&mesh, 32);
        assert_eq!(fine.coarsening(), None);
        assert_eq!(
            fine.coarsened(0, 4).unwrap_err(),
            BakeError::Coarsening { factor: 0 }
        );
        assert_eq!(
            fine.coarsened(257, 4).unwrap_err(),
            BakeError::Coarsening { factor: 257 }
        );
        assert_eq!(fine.coarsened(2, 0).unwrap_err(), BakeError::TileSize(0));
        let mut coarse = fine.coarsened(2, 4).unwrap();
        assert_eq!(
            coarse.refresh(&mesh.positions).unwrap_err(),
            BakeError::CoarsenedRefresh { factor: 2 }
        );
        // Nested, the factors multiply; by 1, it is still coarsened.
        let mut nested = coarse.coarsened(1, 4).unwrap().coarsened(3, 4).unwrap();
        assert_eq!(nested.coarsening(), Some(6));
        assert_eq!(
            nested.refresh(&mesh.positions).unwrap_err(),
            BakeError::CoarsenedRefresh { factor: 6 }
        );
        let mut by_one = fine.coarsened(1, 4).unwrap();
        assert_eq!(
            by_one.refresh(&mesh.positions).unwrap_err(),
            BakeError::CoarsenedRefresh { factor: 1 }
        );
    }
}
