//! Which texels fall in which voxel: the binning of one or more atlases
//! into a [`VoxelGrid`], the defined cells and their neighbourhoods.
//!
//! A *cell* is a voxel seen by one atlas (segment): with one body, cells are
//! the defined voxels; where several bodies share a voxel each has its own
//! cell there, and the cells of one voxel are neighbours of each other (so
//! a wet sheet lying on a dry one passes liquid to it even where the two
//! share every voxel). Texels are binned by a stable counting sort, so each
//! cell lists its texels in increasing index order and every per-cell sum
//! has a fixed order: results do not depend on the number of threads.

use nalgebra::Isometry3;
use rayon::prelude::*;
use soak_bake::Atlas;

use crate::grid::VoxelGrid;

/// Marks a texel outside the field or a voxel that is not defined.
pub(crate) const NONE: u32 = u32::MAX;

/// Texels up to this many voxels outside a grid are clamped onto it.
const SLACK: f64 = 1e-3;

/// One atlas placed in a field.
pub(crate) struct Placement<'a> {
    pub atlas: &'a Atlas,
    /// Object space to the field's frame.
    pub transform: Isometry3<f64>,
    /// The material's saturation, m.
    pub saturation: f64,
}

/// A contiguous run of texels of one atlas in the concatenated arrays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Segment {
    pub start: usize,
    pub end: usize,
    pub saturation: f64,
}

/// The binning of texels into a grid (CSR lists both ways) and the
/// defined voxels' neighbourhoods, capacities and areas.
#[derive(Clone, Debug, Default)]
pub(crate) struct Layout {
    pub grid: Option<VoxelGrid>,
    pub segments: Vec<Segment>,
    /// Per texel: area, m² (concatenated over segments).
    pub areas: Vec<f32>,
    /// Per texel: compact id of its voxel, or [`NONE`].
    pub voxel_of: Vec<u32>,
    /// Per (grid voxel, segment), at `voxel · segments + segment`: compact
    /// cell id, or [`NONE`] when that body has no texel there.
    pub dense: Vec<u32>,
    /// Per cell: its voxel.
    pub cells: Vec<[u32; 3]>,
    /// Per cell: its segment (body).
    pub cell_segment: Vec<u32>,
    /// Texels of cell `v`: `members[start[v]..start[v+1]]`.
    pub start: Vec<u32>,
    pub members: Vec<u32>,
    /// Per member slot (in `members` order, so each cell's texels are
    /// contiguous): the texel's area, m², and its position in its cell,
    /// voxel units from the cell's lower corner (`grid coordinates − cell`,
    /// exact in `f32`: the difference of an `f32` and an integer below
    /// 2^24 that lies within about one voxel of it). The per-step passes
    /// read these in order instead of looking texels up.
    pub slot_area: Vec<f32>,
    pub slot_frac: Vec<[f32; 3]>,
    /// Neighbour cells of cell `v` (3×3×3 block, other bodies' cells of
    /// the same voxel included): `neighbours[nstart[v]..nstart[v+1]]`.
    pub nstart: Vec<u32>,
    pub neighbours: Vec<u32>,
    /// Per cell and octant of the voxel (bit k set: the upper half along
    /// axis k), the 8 cells of the same body around the octant's corner,
    /// `corners[64 v + 8 o + c]` for corner bits `c` = (x, y, z) from the
    /// lower one, or [`NONE`]: the "8 nearest voxels" of a texel.
    pub corners: Vec<u32>,
    /// Per cell: Σ a_i (m²) and capacity Σ a_i h_max,i (m³).
    pub area: Vec<f64>,
    pub capacity: Vec<f64>,
    /// Most neighbours of any cell (the `Count` of Eq. 5.12).
    pub count_max: u32,
    /// Texels that fell outside the grid.
    pub outside: usize,
}

/// The octant `o` of its cell that a texel at `g` (its [`Layout::slot_frac`])
/// lies in (index of its 8 nearest cells in `corners[64 v + 8 o..]`) and its
/// trilinear coordinates `t` ∈ [0, 1]³ from the lower of those 8 centres:
/// corner `c` has the weight `Π_k (t_k if bit k of c else 1 − t_k)`.
#[inline(always)]
pub(crate) fn octant(g: &[f32; 3]) -> (usize, [f64; 3]) {
    let mut o = 0;
    let mut t = [0.0; 3];
    for a in 0..3 {
        let f = g[a] as f64;
        let upper = f >= 0.5;
        o |= usize::from(upper) << a;
        // Lower corner at c - 1 + upper, centre 0.5 further.
        let base = if upper { 0.5 } else { -0.5 };
        t[a] = (f - base).clamp(0.0, 1.0);
    }
    (o, t)
}

impl Layout {
    /// Member slots of cell `v`.
    #[inline]
    pub fn slots(&self, v: usize) -> std::ops::Range<usize> {
        self.start[v] as usize..self.start[v + 1] as usize
    }

    /// Defined voxels.
    pub fn defined(&self) -> usize {
        self.cells.len()
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.areas.capacity() * 4
            + self.voxel_of.capacity() * 4
            + self.dense.capacity() * 4
            + self.cells.capacity() * 12
            + self.cell_segment.capacity() * 4
            + self.start.capacity() * 4
            + self.members.capacity() * 4
            + self.slot_area.capacity() * 4
            + self.slot_frac.capacity() * 12
            + self.nstart.capacity() * 4
            + self.neighbours.capacity() * 4
            + self.corners.capacity() * 4
            + self.area.capacity() * 8
            + self.capacity.capacity() * 8
    }

    /// Bins the texels of `placements` into `grid`, reusing the buffers.
    /// Texels with no area or no saturation hold no liquid that can move and
    /// stay out of the field.
    pub fn rebuild(&mut self, grid: VoxelGrid, placements: &[Placement<'_>]) {
        self.grid = Some(grid);
        let n: usize = placements.iter().map(|p| p.atlas.len()).sum();
        self.segments.clear();
        self.areas.clear();
        let mut grid_pos = vec![[0.0f32; 3]; n];
        self.voxel_of.clear();
        self.voxel_of.resize(n, NONE);
        let mut at = 0;
        for p in placements {
            let len = p.atlas.len();
            self.segments.push(Segment {
                start: at,
                end: at + len,
                saturation: p.saturation,
            });
            self.areas.extend_from_slice(p.atlas.areas());
            let origin = p.atlas.origin();
            let usable = p.saturation > 0.0;
            let local = p.atlas.local_positions();
            let areas = p.atlas.areas();
            grid_pos[at..at + len]
                .par_iter_mut()
                .zip(self.voxel_of[at..at + len].par_iter_mut())
                .enumerate()
                .for_each(|(i, (g, v))| {
                    let x = local.get(i);
                    let q = p.transform
                        * nalgebra::Point3::new(
                            origin.x + x[0] as f64,
                            origin.y + x[1] as f64,
                            origin.z + x[2] as f64,
                        );
                    let c = grid.grid_coords(&q);
                    *g = c.map(|x| x as f32);
                    // Dense index for now; compact ids below.
                    *v = match grid.cell(c, SLACK) {
                        Some(cell) if usable && areas[i] > 0.0 => grid.index(cell) as u32,
                        _ => NONE,
                    };
                });
            at += len;
        }

        // Counting sort of texels by cell (stable: increasing texel index).
        let segs = placements.len().max(1);
        for (k, seg) in self.segments.iter().enumerate() {
            for v in &mut self.voxel_of[seg.start..seg.end] {
                if *v != NONE {
                    *v = *v * segs as u32 + k as u32;
                }
            }
        }
        let keys = grid.voxel_count() * segs;
        self.dense.clear();
        self.dense.resize(keys, 0);
        let mut outside = 0;
        for &v in &self.voxel_of {
            if v == NONE {
                outside += 1;
            } else {
                self.dense[v as usize] += 1;
            }
        }
        self.outside = outside;
        self.cells.clear();
        self.cell_segment.clear();
        self.start.clear();
        let mut total = 0u32;
        let (dx, dy) = (grid.dims[0] as usize, grid.dims[1] as usize);
        for (key, slot) in self.dense.iter_mut().enumerate() {
            let count = *slot;
            if count == 0 {
                *slot = NONE;
            } else {
                *slot = self.cells.len() as u32;
                let d = key / segs;
                self.cell_segment.push((key % segs) as u32);
                self.cells
                    .push([(d % dx) as u32, ((d / dx) % dy) as u32, (d / (dx * dy)) as u32]);
                self.start.push(total);
                total += count;
            }
        }
        self.start.push(total);
        let mut fill: Vec<u32> = self.start[..self.start.len() - 1].to_vec();
        self.members.clear();
        self.members.resize(total as usize, 0);
        for (i, v) in self.voxel_of.iter_mut().enumerate() {
            if *v != NONE {
                let c = self.dense[*v as usize];
                *v = c;
                self.members[fill[c as usize] as usize] = i as u32;
                fill[c as usize] += 1;
            }
        }
        self.slot_area.clear();
        self.slot_area
            .extend(self.members.iter().map(|&i| self.areas[i as usize]));
        self.slot_frac.clear();
        self.slot_frac.resize(total as usize, [0.0; 3]);
        let (members, cells, start) = (&self.members, &self.cells, &self.start);
        self.slot_frac.par_iter_mut().enumerate().for_each(|(k, f)| {
            // The slot's cell: the last v with start[v] <= k.
            let v = start.partition_point(|&s| s as usize <= k) - 1;
            let g = grid_pos[members[k] as usize];
            let c = cells[v];
            *f = [0, 1, 2].map(|a| (g[a] as f64 - c[a] as f64) as f32);
        });

        // Areas and capacities per defined voxel, in member order.
        let defined = self.cells.len();
        let saturation_of = |i: usize| {
            self.segments
                .iter()
                .find(|s| i < s.end)
                .map_or(0.0, |s| s.saturation)
        };
        let sums: Vec<(f64, f64)> = (0..defined)
            .into_par_iter()
            .map(|v| {
                let (mut a, mut c) = (0.0, 0.0);
                for &i in &self.members[self.start[v] as usize..self.start[v + 1] as usize] {
                    let ai = self.areas[i as usize] as f64;
                    a += ai;
                    c += ai * saturation_of(i as usize);
                }
                (a, c)
            })
            .collect();
        self.area.clear();
        self.capacity.clear();
        for (a, c) in sums {
            self.area.push(a);
            self.capacity.push(c);
        }

        // Neighbour cells in the 3×3×3 block (other bodies' cells in the
        // same voxel included), in a fixed order.
        let lists: Vec<Vec<u32>> = (0..defined)
            .into_par_iter()
            .map(|v| {
                let c = self.cells[v];
                let own = self.cell_segment[v] as usize;
                let mut list = Vec::with_capacity(26);
                for dz in -1i64..=1 {
                    for dy in -1i64..=1 {
                        for dx in -1i64..=1 {
                            let q = [c[0] as i64 + dx, c[1] as i64 + dy, c[2] as i64 + dz];
                            if (0..3).any(|a| q[a] < 0 || q[a] >= grid.dims[a] as i64) {
                                continue;
                            }
                            let base = grid.index(q.map(|x| x as u32)) * segs;
                            for s in 0..segs {
                                if dx == 0 && dy == 0 && dz == 0 && s == own {
                                    continue;
                                }
                                let id = self.dense[base + s];
                                if id != NONE {
                                    list.push(id);
                                }
                            }
                        }
                    }
                }
                list
            })
            .collect();
        // The 8 nearest cells of each octant.
        self.corners.clear();
        self.corners.resize(defined * 64, NONE);
        let (cells, cell_segment, dense) = (&self.cells, &self.cell_segment, &self.dense);
        self.corners
            .par_chunks_mut(64)
            .enumerate()
            .for_each(|(v, table)| {
                let c = cells[v];
                let s = cell_segment[v] as usize;
                for o in 0..8 {
                    for corner in 0..8 {
                        let q = [0, 1, 2]
                            .map(|k| c[k] as i64 - 1 + ((o >> k) & 1) as i64 + ((corner >> k) & 1) as i64);
                        if (0..3).all(|k| q[k] >= 0 && q[k] < grid.dims[k] as i64) {
                            table[8 * o + corner] = dense[grid.index(q.map(|x| x as u32)) * segs + s];
                        }
                    }
                }
            });
        self.nstart.clear();
        self.neighbours.clear();
        self.count_max = 0;
        for list in &lists {
            self.nstart.push(self.neighbours.len() as u32);
            self.neighbours.extend_from_slice(list);
            self.count_max = self.count_max.max(list.len() as u32);
        }
        self.nstart.push(self.neighbours.len() as u32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use soak_bake::{BakeOptions, builtin};

    #[test]
    fn every_texel_of_a_body_is_binned_once() {
        let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64)).unwrap();
        let grid = VoxelGrid::covering(
            nalgebra::Point3::new(-0.5, -0.5, -0.5),
            nalgebra::Point3::new(0.5, 0.5, 0.5),
            0.25,
        )
        .unwrap();
        let mut layout = Layout::default();
        layout.rebuild(
            grid,
            &[Placement {
                atlas: &atlas,
                transform: Isometry3::identity(),
                saturation: 1.0,
            }],
        );
        assert_eq!(layout.outside, 0);
        assert_eq!(layout.members.len(), atlas.len());
        let mut seen = vec![false; atlas.len()];
        for v in 0..layout.defined() {
            let list = &layout.members[layout.start[v] as usize..layout.start[v + 1] as usize];
            assert!(list.windows(2).all(|w| w[0] < w[1]));
            for (k, &i) in layout.slots(v).zip(list) {
                assert_eq!(layout.voxel_of[i as usize], v as u32);
                seen[i as usize] = true;
                assert_eq!(layout.slot_area[k], layout.areas[i as usize]);
                // The slot's position in its cell, in voxels from its lower
                // corner: the texel lies in the cell (to the binning slack).
                let f = layout.slot_frac[k];
                assert!(
                    f.iter()
                        .all(|&x| (-SLACK as f32..=1.0 + SLACK as f32).contains(&x)),
                    "{f:?}"
                );
            }
        }
        assert!(seen.iter().all(|&s| s));
        // A 4³ grid over a cube's surface: all 56 boundary voxels are defined.
        assert_eq!(layout.defined(), 64 - 8);
        assert!((layout.area.iter().sum::<f64>() - 6.0).abs() < 1e-4);
        // A voxel on a face sees at least the 8 around it on that face.
        assert!((8..=26).contains(&layout.count_max), "{}", layout.count_max);
        for v in 0..layout.defined() {
            let nb = &layout.neighbours[layout.nstart[v] as usize..layout.nstart[v + 1] as usize];
            for &u in nb {
                let back = &layout.neighbours
                    [layout.nstart[u as usize] as usize..layout.nstart[u as usize + 1] as usize];
                assert!(back.contains(&(v as u32)), "neighbourhood is symmetric");
            }
        }
    }
}
