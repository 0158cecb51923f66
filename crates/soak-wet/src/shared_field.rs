//! One liquid density field in world space shared by several bodies, so
//! liquid diffuses from one to another where they touch (thesis Fig. 7.13).

use nalgebra::{Isometry3, Point3};
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::body_field::atlas_bounds;
use crate::diffusion::{self, Diffusion, DiffusionMode, DiffusionReport, Scratch};
use crate::error::WetError;
use crate::grid::VoxelGrid;
use crate::layout::{Layout, Placement};
use crate::reduce::liquid_volume;
use crate::wetting::{Wetting, check_pose};

/// A body taking part in a [`SharedField`] step.
pub struct FieldMember<'a> {
    /// Its liquid (give it no diffusion of its own, or it diffuses twice).
    pub wetting: &'a mut Wetting,
    /// Its atlas.
    pub atlas: &'a Atlas,
    /// Object → world, m.
    pub pose: &'a Isometry3<f64>,
}

/// What a [`SharedField::diffuse`] step did.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SharedReport {
    /// The diffusion over all members.
    pub diffusion: DiffusionReport,
    /// Net liquid each member gained, m³, in member order (sums to zero to
    /// rounding in the conservative mode).
    pub gained: Vec<f64>,
    /// Whether the binning was rebuilt (a member moved, or the members changed).
    pub rebinned: bool,
}

#[derive(Clone, Debug, Default)]
struct Cache {
    layout: Layout,
    scratch: Scratch,
    key: Vec<u64>,
    h: Vec<f64>,
    sums: Vec<f64>,
}

/// A voxel field in world space over which several bodies' liquid diffuses
/// together: where two bodies' texels share or neighbour a voxel, liquid
/// passes between them (from the fuller to the emptier, relative to each
/// material's saturation); a body a voxel or more away exchanges nothing.
///
/// Each step, call every member's [`Wetting::step`] (absorption,
/// evaporation; members should have no diffusion of their own), then
/// [`SharedField::diffuse`] with all members. The binning is rebuilt only
/// when a member moved or the member list changed. Texels outside the
/// field's box do not diffuse. CPU only.
///
/// # Example
/// ```
/// use nalgebra::Isometry3;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_wet::prelude::*;
///
/// let atlas = Atlas::bake(&builtin::cuboid(0.2, 0.2, 0.2), BakeOptions::square(64))?;
/// let (left, right) = (Isometry3::translation(-0.1, 0.0, 0.0), Isometry3::translation(0.1, 0.0, 0.0));
/// let mut wet = Wetting::new(&atlas, Material::cotton(), Liquid::water())?;
/// wet.fill(&atlas, 1.0)?;
/// let mut dry = Wetting::new(&atlas, Material::cotton(), Liquid::water())?;
/// let diffusion = Diffusion::new(1e-4).with_resolution(FieldResolution::VoxelSize(0.02));
/// let mut field = SharedField::around(&[(&atlas, &left), (&atlas, &right)], 0.05, diffusion)?;
/// for _ in 0..20 {
///     field.diffuse(
///         &mut [
///             FieldMember { wetting: &mut wet, atlas: &atlas, pose: &left },
///             FieldMember { wetting: &mut dry, atlas: &atlas, pose: &right },
///         ],
///         0.1,
///     )?;
/// }
/// assert!(dry.total_liquid(&atlas) > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SharedField {
    grid: VoxelGrid,
    diffusion: Diffusion,
    #[serde(skip)]
    cache: Cache,
}

impl SharedField {
    /// A field over the world box `[min, max]` (m). The resolution must be
    /// [`crate::FieldResolution::VoxelSize`] or
    /// [`crate::FieldResolution::Cells`] (along the longest side).
    pub fn new(min: Point3<f64>, max: Point3<f64>, diffusion: Diffusion) -> Result<Self, WetError> {
        diffusion.validate()?;
        let longest = (0..3).map(|k| max[k] - min[k]).fold(0.0, f64::max);
        let size = diffusion.resolution.voxel_size(longest, None)?;
        Ok(Self {
            grid: VoxelGrid::covering(min, max, size)?,
            diffusion,
            cache: Cache::default(),
        })
    }

    /// A field over the world box holding the texels of `bodies` (atlas and
    /// pose each) grown by `margin` (m) on every side, for bodies that move
    /// within it. [`crate::FieldResolution::Auto`] and `TexelSpan` size the
    /// voxels from the bodies' mean texel edge.
    pub fn around(
        bodies: &[(&Atlas, &Isometry3<f64>)],
        margin: f64,
        diffusion: Diffusion,
    ) -> Result<Self, WetError> {
        diffusion.validate()?;
        if !(margin.is_finite() && margin >= 0.0) {
            return Err(WetError::parameter("field.margin", margin, "finite and >= 0 m"));
        }
        let mut lo = Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY);
        let mut hi = -lo;
        let (mut area, mut texels) = (0.0, 0usize);
        for (k, (atlas, pose)) in bodies.iter().enumerate() {
            check_pose(pose, &format!("field member {k}"))?;
            if atlas.is_empty() {
                return Err(WetError::EmptyAtlas);
            }
            let (a, b) = atlas_bounds(atlas);
            for x in [a.x, b.x] {
                for y in [a.y, b.y] {
                    for z in [a.z, b.z] {
                        let p = *pose * Point3::new(x, y, z);
                        lo = lo.inf(&p);
                        hi = hi.sup(&p);
                    }
                }
            }
            area += atlas.area();
            texels += atlas.len();
        }
        if texels == 0 {
            return Err(WetError::EmptyAtlas);
        }
        let m = nalgebra::Vector3::repeat(margin);
        let (lo, hi) = (lo - m, hi + m);
        let longest = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let texel = (area / texels as f64).sqrt();
        let size = diffusion.resolution.voxel_size(longest, Some(texel))?;
        Ok(Self {
            grid: VoxelGrid::covering(lo, hi, size)?,
            diffusion,
            cache: Cache::default(),
        })
    }

    /// The grid, world space.
    pub fn grid(&self) -> &VoxelGrid {
        &self.grid
    }

    /// The diffusion settings.
    pub fn diffusion(&self) -> &Diffusion {
        &self.diffusion
    }

    /// Replaces the coefficient, mode or step limit (validated). The
    /// resolution of an existing field does not change.
    pub fn set_diffusion(&mut self, diffusion: Diffusion) -> Result<(), WetError> {
        diffusion.validate()?;
        self.diffusion = diffusion;
        Ok(())
    }

    /// Diffuses the members' liquid together over `dt` (s).
    ///
    /// Each member has its own cells in the voxels it occupies (a field of
    /// V voxels and S members indexes V·S cells, at most 4 × 2^24).
    ///
    /// In the conservative mode each member's change is booked in its
    /// [`crate::Ledger::exchanged`]; in the thesis mode (not conservative)
    /// in its [`crate::Ledger::drift`].
    pub fn diffuse(&mut self, members: &mut [FieldMember<'_>], dt: f64) -> Result<SharedReport, WetError> {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(WetError::TimeStep { dt });
        }
        let mut key = Vec::with_capacity(members.len() * 10);
        for (k, m) in members.iter().enumerate() {
            check_pose(m.pose, &format!("field member {k}"))?;
            if m.atlas.len() != m.wetting.texels() {
                return Err(WetError::AtlasMismatch {
                    state: m.wetting.texels(),
                    atlas: m.atlas.len(),
                });
            }
            key.push(m.atlas as *const Atlas as usize as u64);
            key.push(m.atlas.len() as u64);
            key.push(m.wetting.material().saturation.to_bits());
            key.extend(m.pose.translation.vector.iter().map(|c| c.to_bits()));
            key.extend(m.pose.rotation.coords.iter().map(|c| c.to_bits()));
        }
        let c = &mut self.cache;
        let rebinned = key != c.key || c.layout.grid.is_none();
        if rebinned {
            let keys = self.grid.voxel_count() as u64 * members.len().max(1) as u64;
            if keys > 4 * crate::grid::MAX_VOXELS {
                return Err(WetError::FieldTooLarge {
                    dims: self.grid.dims.map(|d| d as u64),
                    voxels: keys,
                    limit: 4 * crate::grid::MAX_VOXELS,
                });
            }
            let placements: Vec<Placement<'_>> = members
                .iter()
                .map(|m| Placement {
                    atlas: m.atlas,
                    transform: *m.pose,
                    saturation: m.wetting.material().saturation,
                })
                .collect();
            c.layout.rebuild(self.grid, &placements);
            c.key = key;
        }
        let plan = self.diffusion.plan(dt, self.grid.voxel_size, c.layout.count_max);
        let mut report = SharedReport {
            diffusion: DiffusionReport {
                plan,
                voxels: c.layout.defined(),
                count_max: c.layout.count_max,
                outside: c.layout.outside,
                drift: 0.0,
            },
            gained: vec![0.0; members.len()],
            rebinned,
        };
        if plan.substeps == 0 {
            return Ok(report);
        }
        c.h.clear();
        for m in members.iter() {
            c.h.extend_from_slice(m.wetting.liquid());
        }
        let drift = diffusion::run(&c.layout, &mut c.h, self.diffusion.mode, &plan, &mut c.scratch);
        report.diffusion.drift = drift;
        for (k, (m, seg)) in members.iter_mut().zip(&c.layout.segments).enumerate() {
            let (h, ledger) = m.wetting.parts_mut();
            let before = liquid_volume(h, m.atlas.areas(), &mut c.sums);
            h.copy_from_slice(&c.h[seg.start..seg.end]);
            let gained = liquid_volume(h, m.atlas.areas(), &mut c.sums) - before;
            report.gained[k] = gained;
            match self.diffusion.mode {
                DiffusionMode::Conservative => ledger.exchanged += gained,
                DiffusionMode::Thesis => ledger.drift += gained,
            }
        }
        Ok(report)
    }
}
