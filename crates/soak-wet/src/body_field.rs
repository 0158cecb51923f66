//! A body's own voxel field (its texels binned in object space) and the
//! atlas measures that size it.

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::Atlas;

use crate::diffusion::{Diffusion, Scratch};
use crate::error::WetError;
use crate::grid::VoxelGrid;
use crate::layout::{Layout, Placement};

/// A body's own field: the binning of its texels in object space, built
/// once (the texels do not move in object space) and reused every step.
#[derive(Clone, Debug, Default)]
pub(crate) struct BodyField {
    pub layout: Layout,
    pub scratch: Scratch,
}

impl BodyField {
    pub(crate) fn build(atlas: &Atlas, diffusion: &Diffusion, saturation: f64) -> Result<Self, WetError> {
        let (min, max) = atlas_bounds(atlas);
        let longest = (0..3).map(|k| max[k] - min[k]).fold(0.0, f64::max);
        let texel = mean_texel_edge(atlas);
        let size = diffusion
            .resolution
            .voxel_size(longest.max(texel.unwrap_or(0.0)), texel)?;
        let grid = VoxelGrid::covering(min, max, size)?;
        let mut layout = Layout::default();
        layout.rebuild(
            grid,
            &[Placement {
                atlas,
                transform: Isometry3::identity(),
                saturation,
            }],
        );
        Ok(Self {
            layout,
            scratch: Scratch::default(),
        })
    }
}

/// Object-space bounds of an atlas' texels, m.
pub(crate) fn atlas_bounds(atlas: &Atlas) -> (Point3<f64>, Point3<f64>) {
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in atlas.local_positions().iter() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let o = atlas.origin();
    (
        o + Vector3::new(lo[0] as f64, lo[1] as f64, lo[2] as f64),
        o + Vector3::new(hi[0] as f64, hi[1] as f64, hi[2] as f64),
    )
}

/// `√(Σ a_i / N)`, m: the mean texel edge.
pub(crate) fn mean_texel_edge(atlas: &Atlas) -> Option<f64> {
    (!atlas.is_empty()).then(|| (atlas.area() / atlas.len() as f64).sqrt())
}
