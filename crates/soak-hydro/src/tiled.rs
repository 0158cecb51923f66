//! The tiled path for planar water: same answer as the per-texel sums, far
//! less work.
//!
//! The tiles' moments for buoyancy and for drag are built in one pass over
//! the atlas and read by one classification of groups and tiles against
//! the waterline and the flow (here); the drag's walk over what that
//! classification finds is in `drag.rs`, the sea's tiles in `sea.rs`.

use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;
use soak_bake::Atlas;

use crate::error::HydroError;
use crate::hydrostatics::body_state::BodyState;
use crate::hydrostatics::drag_kernel::{
    Added, DragLanes, DragMoments, Facing, FacingBounds, HBox, LocalDrag, RangeList, add_drag_ranges,
    uniform_velocity,
};
use crate::hydrostatics::evaluation::{drag_sums, exact_sums, patch_sums, plane_of, sample_patch};
use crate::hydrostatics::finish::finish;
use crate::hydrostatics::forces::HydroForces;
use crate::hydrostatics::frame::{Frame, texel};
use crate::hydrostatics::options::{BuoyancyMode, HydroOptions};
use crate::hydrostatics::planar_kernel::{PlanarTexels, add_planar_ranges};
use crate::hydrostatics::sea_drag::SeaDragFrame;
use crate::hydrostatics::sums::{BuoyancySums, DragAcc, DragSums};
use crate::mass::MassProperties;
use crate::parallel::{par_fold, par_map};
use crate::scratch::Ranges;
use crate::water::{SurfacePatch, Water};

mod drag;
mod sea;

use self::drag::DragWalk;
pub use self::drag::{DragTexels, evaluate_with_drag};
pub use self::sea::SEA_TILE_TOLERANCE;

/// Texels (the body's and its drag texels' together) up to which
/// [`TiledAtlas::evaluate_with_drag`] runs its two evaluations one after
/// the other rather than side by side: a 128² body's two take a few
/// microseconds, about what handing one to another thread costs.
const SIDE_BY_SIDE: usize = 32_768;

/// Moments of one tile's texels, relative to the atlas origin: the
/// atlas' own ([`soak_bake::TexelMoments`], which it dereferences to:
/// `m.s0`, `m.radius`, ...) and where its texels lie in the atlas.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileMoments {
    /// The tile's moments, bounding sphere and box, as the atlas gives them.
    pub moments: soak_bake::TexelMoments,
    /// Texel range in the atlas.
    pub range: (u32, u32),
}

impl std::ops::Deref for TileMoments {
    type Target = soak_bake::TexelMoments;
    fn deref(&self) -> &Self::Target {
        &self.moments
    }
}

impl TileMoments {
    /// Where the tile lies: its bounding sphere and box.
    fn bounds(&self) -> Bounds {
        Bounds {
            centre: self.centre,
            radius: self.radius,
            half_extent: self.half_extent,
        }
    }
}

/// A bounding sphere and a bounding box about the same centre (object
/// axes, relative to the atlas origin), m.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    centre: Vector3<f64>,
    radius: f64,
    half_extent: Vector3<f64>,
}

impl Bounds {
    /// Bounds around `parts`' (at least one): the box around their boxes,
    /// the sphere about its centre around their spheres.
    fn around(parts: impl Iterator<Item = Bounds> + Clone) -> Self {
        let (mut lo, mut hi) = (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN));
        for b in parts.clone() {
            lo = lo.inf(&(b.centre - b.half_extent));
            hi = hi.sup(&(b.centre + b.half_extent));
        }
        let centre = (lo + hi) * 0.5;
        let radius = parts
            .map(|b| (b.centre - centre).norm() + b.radius)
            .fold(0.0, f64::max);
        Self {
            centre,
            radius,
            half_extent: (hi - lo) * 0.5,
        }
    }
}

/// What the walk over the tiles reads of each: where it lies and its
/// texels, one cache line a tile (the moments, six times as large, are
/// read only for the tiles a walk sums).
#[derive(Clone, Copy, Debug)]
struct Place {
    bounds: Bounds,
    range: (u32, u32),
}

/// The moments the closed form takes, summed over a set of texels (a run
/// of tiles): the closed form of a union of tiles is the closed form of
/// the sums of their moments.
#[derive(Clone, Copy, Debug, Default)]
struct Sums {
    /// Σ A, m².
    s0: Vector3<f64>,
    /// `s1[(j, k)] = Σ A_j x_k`, m³.
    s1: Matrix3<f64>,
    /// `s2[j][(k, l)] = Σ A_j x_k x_l`, m⁴.
    s2: [Matrix3<f64>; 3],
    /// Σ a, m².
    area: f64,
    /// Number of texels.
    texels: u64,
}

impl Sums {
    /// Adds `to − from`: the sums of the texels counted in `to` and not in
    /// `from` (two entries of a running sum).
    fn add_difference(&mut self, to: &Sums, from: &Sums) {
        self.s0 += to.s0 - from.s0;
        self.s1 += to.s1 - from.s1;
        for j in 0..3 {
            self.s2[j] += to.s2[j] - from.s2[j];
        }
        self.area += to.area - from.area;
        self.texels += to.texels - from.texels;
    }
}

/// Tiles `tiles` of the atlas' tile list, settled together.
#[derive(Clone, Debug)]
struct Group {
    bounds: Bounds,
    /// A box around the drag's `h = (A, x × A) / |A|` of the group's texels.
    facing: FacingBounds,
    tiles: std::ops::Range<usize>,
}

/// An atlas with per-tile moments, for fast hydrostatics under planar water:
/// same answer as the per-texel sums of [`crate::evaluate`], far less work.
///
/// Under a plane the depth is affine in object-space position,
/// `d(x) = α + β·x`, so a tile of texels that lies wholly under water
/// contributes a closed form of its precomputed moments `Σ A`, `Σ A⊗x` and
/// `Σ A⊗x⊗x`; a tile wholly above water contributes nothing (a bounding-sphere
/// and bounding-box test decides); only tiles cut by the waterline are
/// summed texel by texel. The closed form is linear in the moments, so
/// consecutive tiles under water take theirs from a running sum, two
/// entries for the whole run, and one closed form serves them all. A cut
/// tile whose centre is under water joins the run, and the planar kernel
/// takes its dry texels' sums back out: either way the kernel does full
/// work only on the smaller side of the waterline.
///
/// On a sampled sea (a [`SurfacePatch`](crate::SurfacePatch), handed in or
/// sampled as [`HydroOptions::sea`] asks) tiles wholly under the waves take
/// the same closed forms from the surface's second-order Taylor polynomial
/// over each tile, the error of its remainder held under
/// [`SEA_TILE_TOLERANCE`]; the rest goes through the
/// sea kernel texel by texel. Drag on a sea takes every texel of a tile in
/// closed form as submerged and the others as the sea kernel finds them,
/// each with the fluid's velocity where it is. Any other surface falls
/// back to the per-texel path.
///
/// Two levels: the atlas' tiles (`tile_size`² texels), and groups of
/// neighbouring tiles, consecutive in the tile list, with bounds around
/// them all: up to four tiles close together on the body where the atlas
/// has at most 512 tiles (a 128² body's), else the [`TiledAtlas::GROUP`]²
/// tiles of a block of the texture (see `spatial_groups`). A group wholly under or above water
/// is settled by one test; only the tiles of groups the waterline cuts are
/// looked at one by one. Running sums of the tiles' moments give any run
/// of consecutive tiles its moments from two entries.
#[derive(Clone, Debug)]
pub struct TiledAtlas {
    /// Tile moments, ordered group by group.
    tiles: Vec<TileMoments>,
    /// Each tile's bounds and texels, in the same order.
    places: Vec<Place>,
    /// Groups of consecutive tiles.
    groups: Vec<Group>,
    /// Groups per parallel task: a chunk of up to 512 tiles.
    group_chunk: usize,
    /// `prefix[i]` holds the sums of the moments of `tiles[..i]`: a run of
    /// tiles under water takes its sums from two entries, however long.
    prefix: Vec<Sums>,
    /// Per tile, a box around the drag's `h / |A| = (A, x × A) / |A|` of its texels:
    /// whether all of them face the flow, none does, or some may.
    facing: Vec<FacingBounds>,
    /// `drag_prefix[i]` holds the sums of the drag moments of `tiles[..i]`.
    drag_prefix: Vec<DragMoments>,
    /// Each tile's drag moments alone (two neighbouring entries of
    /// `drag_prefix` apart), made on the first evaluation with drag on a
    /// sampled sea, which takes them tile by tile: nothing where no body
    /// of this atlas meets drag on a sea.
    tile_drag: std::sync::OnceLock<Vec<DragMoments>>,
}

/// How many tiles of each kind the last evaluation met.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TileCounts {
    /// Tiles wholly under water (closed form).
    pub submerged: usize,
    /// Tiles wholly above water (skipped).
    pub dry: usize,
    /// Tiles cut by the waterline (per texel).
    pub cut: usize,
}

impl std::ops::AddAssign for TileCounts {
    /// Adds another part's counts, kind by kind.
    fn add_assign(&mut self, other: Self) {
        self.submerged += other.submerged;
        self.dry += other.dry;
        self.cut += other.cut;
    }
}

impl TiledAtlas {
    /// Precomputes the tile moments of `atlas` (once per bake or refresh).
    pub fn new(atlas: &Atlas) -> Self {
        let mut tiles = atlas
            .tiles()
            .par_iter()
            .zip(atlas.tile_moments())
            .map(|(t, a)| {
                let m = TileMoments {
                    moments: *a,
                    range: (t.start, t.end),
                };
                let (mut dm, mut hbox) = (DragMoments::default(), HBox::default());
                for i in t.range() {
                    let (x, a) = texel(atlas, i);
                    dm.add_texel(&x, &a);
                    hbox.add_texel(&x, &a);
                }
                (m, dm, hbox)
            })
            .collect::<Vec<_>>();
        // Group the tiles: by their place on the body where the atlas has
        // few of them, else by the block of GROUP × GROUP tiles their first
        // texel lies in (tiles are in row-major block order already); see
        // `spatial_groups`.
        let spans = if tiles.len() <= SPATIAL_TILES {
            let centres: Vec<Vector3<f64>> = tiles.iter().map(|(m, _, _)| m.centre).collect();
            let mut order: Vec<usize> = (0..tiles.len()).collect();
            let mut spans = Vec::new();
            spatial_groups(&centres, &mut order, 0, &mut spans);
            let mut slots: Vec<Option<_>> = tiles.into_iter().map(Some).collect();
            tiles = order
                .iter()
                .map(|&i| slots[i].take().expect("each tile once"))
                .collect();
            spans
        } else {
            let ts = atlas.tile_size().max(1);
            let group_of = |m: &TileMoments| {
                let [x, y] = atlas.texels().get(m.range.0 as usize).copied().unwrap_or([0, 0]);
                let span = ts * Self::GROUP;
                (u32::from(y) / span, u32::from(x) / span)
            };
            tiles.sort_by_key(|(m, _, _)| (group_of(m), m.range.0));
            let mut spans = Vec::new();
            let mut start = 0;
            while start < tiles.len() {
                let key = group_of(&tiles[start].0);
                let end = start
                    + tiles[start..]
                        .iter()
                        .take_while(|t| group_of(&t.0) == key)
                        .count();
                spans.push(start..end);
                start = end;
            }
            spans
        };
        let mut drag_prefix = Vec::with_capacity(tiles.len() + 1);
        let mut running = DragMoments::default();
        drag_prefix.push(running);
        for (_, dm, _) in &tiles {
            running.add(dm);
            drag_prefix.push(running);
        }
        let facing: Vec<HBox> = tiles.iter().map(|t| t.2).collect();
        let tiles: Vec<TileMoments> = tiles.into_iter().map(|t| t.0).collect();
        // The texture's blocks, 32 a task; an atlas grouped by place is
        // one task.
        let group_chunk = if tiles.len() <= SPATIAL_TILES {
            spans.len().max(1)
        } else {
            32
        };
        let mut groups = Vec::with_capacity(spans.len());
        for std::ops::Range { start, end } in spans {
            let mut group_facing = HBox::default();
            for b in &facing[start..end] {
                group_facing.add(b);
            }
            groups.push(Group {
                bounds: Bounds::around(tiles[start..end].iter().map(TileMoments::bounds)),
                facing: group_facing.bounds(),
                tiles: start..end,
            });
        }
        let mut prefix = Vec::with_capacity(tiles.len() + 1);
        let mut running = Sums::default();
        prefix.push(running);
        for m in &tiles {
            running.s0 += m.s0;
            running.s1 += m.s1;
            for j in 0..3 {
                running.s2[j] += m.s2[j];
            }
            running.area += m.area;
            running.texels += u64::from(m.range.1 - m.range.0);
            prefix.push(running);
        }
        Self {
            places: tiles
                .iter()
                .map(|m| Place {
                    bounds: m.bounds(),
                    range: m.range,
                })
                .collect(),
            tiles,
            groups,
            group_chunk,
            prefix,
            facing: facing.iter().map(HBox::bounds).collect(),
            drag_prefix,
            tile_drag: std::sync::OnceLock::new(),
        }
    }

    /// Tiles per side of a group of a large atlas: a group is a block of
    /// `GROUP`² tiles of the texture.
    pub const GROUP: u32 = 4;

    /// The tiles' moments, ordered group by group.
    pub fn tiles(&self) -> &[TileMoments] {
        &self.tiles
    }

    /// Each tile's drag moments, made on the first call.
    fn tile_drag(&self) -> &[DragMoments] {
        self.tile_drag.get_or_init(|| {
            (0..self.tiles.len())
                .map(|ti| DragMoments::of_tile(&self.drag_prefix, ti))
                .collect()
        })
    }

    /// Same as [`crate::evaluate`], using closed forms for tiles wholly under
    /// a planar surface or a sampled sea. Falls back to the per-texel path
    /// for other surfaces.
    /// `self` must come from this `atlas` (same bake or refresh).
    pub fn evaluate(
        &self,
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
        options: &HydroOptions,
    ) -> Result<HydroForces, HydroError> {
        self.evaluate_counted(atlas, water, state, mass, t, options)
            .map(|(f, _)| f)
    }

    /// [`TiledAtlas::evaluate`] that also reports how tiles were classified.
    pub fn evaluate_counted(
        &self,
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
        options: &HydroOptions,
    ) -> Result<(HydroForces, TileCounts), HydroError> {
        water.validate()?;
        state.check()?;
        // A sea read as one plane over the body: its tiles under that plane.
        if let Some(plane) = plane_of(atlas, water, state, t, options)? {
            return self.evaluate_counted(atlas, &plane, state, mass, t, options);
        }
        let e = self.evaluation(atlas, water, state, mass, t, options, true)?;
        let forces = finish(&e.frame, water, state, mass, &e.sums, e.drag.as_ref(), options);
        Ok((forces, e.counts))
    }

    /// [`TiledAtlas::evaluate`] with the drag summed over the texels of
    /// another bake of the same mesh (`drag`, typically coarser: a 64²
    /// bake of a 1024² body), the buoyancy over this atlas' own. Drag is a
    /// smooth surface integral whose coefficients are empirical; a coarse
    /// bake takes it to within a few parts in a thousand of the body's own
    /// texels (`soak accuracy` reports how close, per resolution) for a
    /// fraction of the work. Without [`HydroOptions::drag`] this is
    /// [`TiledAtlas::evaluate`]. A sampled sea is sampled once, for both.
    ///
    /// # Errors
    /// Those of [`TiledAtlas::evaluate`], and [`HydroError::DragTexels`]
    /// when `drag`'s atlas is not of this body's mesh (another origin).
    ///
    /// # Example
    /// ```
    /// use nalgebra::{Isometry3, Vector3};
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// use soak_hydro::{BodyState, Drag, DragTexels, HydroOptions, MassModel, TiledAtlas, Water};
    ///
    /// let mesh = builtin::sphere(0.5, 64, 32);
    /// let atlas = Atlas::bake(&mesh, BakeOptions::square(512))?;
    /// let tiled = TiledAtlas::new(&atlas);
    /// let coarse = DragTexels::bake(&mesh, 64)?;
    /// let mass = MassModel::Solid { density: 500.0 }.mass_properties(&atlas)?;
    /// let state = BodyState {
    ///     linear_velocity: Vector3::new(1.0, 0.0, 0.0),
    ///     ..BodyState::at_rest(Isometry3::identity())
    /// };
    /// let options = HydroOptions { drag: Some(Drag::default()), ..HydroOptions::default() };
    /// let water = Water::calm(0.0);
    /// let fine = tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &options)?;
    /// let fast = tiled.evaluate_with_drag(&atlas, &coarse, &water, &state, &mass, 0.0, &options)?;
    /// assert_eq!(fast.buoyancy, fine.buoyancy);
    /// let f = fine.drag_explicit.force;
    /// assert!((fast.drag_explicit.force - f).norm() < 1e-2 * f.norm());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate_with_drag(
        &self,
        atlas: &Atlas,
        drag: &DragTexels,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
        options: &HydroOptions,
    ) -> Result<HydroForces, HydroError> {
        if options.drag.is_none() {
            return self.evaluate(atlas, water, state, mass, t, options);
        }
        drag.check(atlas)?;
        // Validates the water and the state, and samples a sea once for both.
        let sampled = crate::sampled_water(atlas, water, state, t, options)?;
        let water = sampled.as_ref().unwrap_or(water);
        let still = HydroOptions {
            drag: None,
            ..*options
        };
        let run = |i: usize| match i {
            0 => self.evaluation(atlas, water, state, mass, t, &still, true),
            _ => drag
                .tiled
                .evaluation(&drag.atlas, water, state, mass, t, options, false),
        };
        // Two evaluations of a few thousand texels each cost less than
        // handing one to another thread; larger ones run side by side, the
        // body's buoyancy taking the threads the drag leaves it (each sums
        // in a fixed order whatever the threads).
        let (body, coarse) = if atlas.len() + drag.atlas.len() <= SIDE_BY_SIDE {
            let body = run(0)?;
            // Under a plane, the drag texels' sums read the body's frame
            // where it is theirs too (the same origin and plane): one frame
            // and one evaluation's records made and moved, not two.
            if body.frame.serves(atlas, &drag.atlas, water, t) {
                let (_, coarse, _) =
                    drag.tiled
                        .sums(&drag.atlas, water, state, &body.frame, t, options, false);
                return Ok(finish(
                    &body.frame,
                    water,
                    state,
                    mass,
                    &body.sums,
                    coarse.as_ref(),
                    options,
                ));
            }
            (Ok(body), run(1))
        } else {
            let mut both = par_map(2, run).into_iter();
            let (Some(body), Some(coarse)) = (both.next(), both.next()) else {
                unreachable!("two evaluations")
            };
            (body, coarse)
        };
        let (body, coarse) = (body?, coarse?);
        Ok(finish(
            &body.frame,
            water,
            state,
            mass,
            &body.sums,
            coarse.drag.as_ref(),
            options,
        ))
    }

    /// The sums of one evaluation (validated water and state), the
    /// buoyancy's only where `buoyancy` (with drag alone, a plane's tiles
    /// are classified for the drag and nothing else is summed).
    #[allow(clippy::too_many_arguments)]
    fn evaluation(
        &self,
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
        options: &HydroOptions,
        buoyancy: bool,
    ) -> Result<Evaluation, HydroError> {
        let frame = Frame::new(atlas, water, state, mass, t, options.dt);
        if frame.plane.is_none() {
            // A sampled sea (handed in, or sampled here as `evaluate` would):
            // tiles under the waves in closed form. Any other surface per
            // texel.
            let handed = water
                .surface
                .as_any()
                .and_then(|s| s.downcast_ref::<SurfacePatch>());
            let sampled = match handed {
                Some(_) => None,
                None => sample_patch(atlas, water, state, t, options)?,
            };
            let Some(patch) = handed.or(sampled.as_ref()) else {
                let (sums, drag) = exact_sums(atlas, water, state, &frame, t, options);
                return Ok(Evaluation {
                    frame,
                    sums,
                    drag,
                    counts: TileCounts::default(),
                });
            };
            let archimedes = options.buoyancy == BuoyancyMode::Archimedes;
            let drag_frame = options
                .drag
                .map(|drag| SeaDragFrame::of(&drag, water, state, &frame, patch));
            let (sums, drag, counts) = match self.sea_sums(
                atlas,
                &frame,
                patch,
                archimedes,
                buoyancy,
                drag_frame.as_ref().map(|(f, _)| f),
                options.sea_velocity,
            ) {
                Some((sums, drag, counts)) => (
                    sums,
                    drag.zip(drag_frame.as_ref())
                        .map(|(d, (_, c))| d.system(&frame.rot, c)),
                    counts,
                ),
                None => {
                    let (sums, drag) = patch_sums(atlas, water, state, &frame, t, options, patch);
                    (sums, drag, TileCounts::default())
                }
            };
            return Ok(Evaluation {
                frame,
                sums,
                drag,
                counts,
            });
        }
        let (sums, drag, counts) = self.sums(atlas, water, state, &frame, t, options, buoyancy);
        Ok(Evaluation {
            frame,
            sums,
            drag,
            counts,
        })
    }

    /// The buoyancy and drag sums of [`TiledAtlas::evaluate_counted`]
    /// under planar water (`frame.plane` is some); without `buoyancy`,
    /// the drag's alone (the buoyancy sums stay zero).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn sums(
        &self,
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        frame: &Frame,
        t: f64,
        options: &HydroOptions,
        buoyancy: bool,
    ) -> (BuoyancySums, Option<DragSums>, TileCounts) {
        let (n, offset) = frame.plane.expect("planar water");
        let rot = frame.rot;
        // d(x) = α + β·x in object coordinates relative to the atlas origin.
        let alpha = (offset - n.dot(&frame.ow)) / n.y;
        let beta = -(rot.transpose() * n) / n.y;
        let g = rot.transpose() * Vector3::y();
        // Drag in object axes about the atlas origin, where the fluid moves
        // at the same velocity everywhere; elsewhere per texel below.
        let c = rot.transpose() * (frame.com - frame.ow);
        let uniform = options
            .drag
            .and_then(|d| uniform_velocity(water).map(|u| (d, u)))
            .map(|(d, u)| {
                let p = LocalDrag::new(
                    &d,
                    water.density,
                    alpha,
                    &beta,
                    &rot,
                    &c,
                    &state.linear_velocity,
                    &state.angular_velocity,
                    &u,
                );
                (p, u)
            });
        let local_drag = uniform.map(|(p, _)| p).filter(|p| p.quadratic() || p.lin > 0.0);

        let sides = PlaneSides::new(alpha, &beta);
        let classify = |m: &Bounds| sides.side(m);
        let pressure = options.buoyancy == BuoyancyMode::Pressure;
        let n_chunks = self.groups.len().div_ceil(self.group_chunk);
        let work = |c: usize| {
            let mut drag = local_drag.map(|p| DragWalk::new(self, atlas, p));
            let mut counts = TileCounts::default();
            let mut local = BuoyancySums::default(); // object frame
            // Runs of consecutive tiles and groups wholly under water take
            // their moments from the running sums, and their sum takes one
            // closed form. A cut tile whose centre is under water joins
            // them, and the kernel then takes away its dry texels' sums;
            // the other cut tiles' wet texels go through the kernel.
            let mut under = Sums::default();
            let mut run: Option<std::ops::Range<usize>> = None;
            let mut submerge = |tiles: std::ops::Range<usize>, under: &mut Sums| match run.as_mut() {
                _ if !buoyancy => {}
                Some(open) if open.end == tiles.start => open.end = tiles.end,
                _ => {
                    if let Some(done) = run.replace(tiles) {
                        under.add_difference(&self.prefix[done.end], &self.prefix[done.start]);
                    }
                }
            };
            let (mut cut, mut cut_wet) = (Ranges::new(), Ranges::new());
            for group in
                &self.groups[c * self.group_chunk..((c + 1) * self.group_chunk).min(self.groups.len())]
            {
                let members = group.tiles.clone();
                match classify(&group.bounds) {
                    Side::Dry => {
                        counts.dry += members.len();
                        continue;
                    }
                    Side::Submerged => {
                        counts.submerged += members.len();
                        submerge(members.clone(), &mut under);
                        if let Some(d) = drag.as_mut() {
                            d.submerged(members.clone(), &group.facing);
                        }
                    }
                    Side::Cut { .. } => {
                        for ti in members.clone() {
                            let place = &self.places[ti];
                            match classify(&place.bounds) {
                                Side::Dry => counts.dry += 1,
                                Side::Submerged => {
                                    counts.submerged += 1;
                                    submerge(ti..ti + 1, &mut under);
                                    if let Some(d) = drag.as_mut() {
                                        d.submerged(ti..ti + 1, &self.facing[ti]);
                                    }
                                }
                                Side::Cut { centre_wet } => {
                                    counts.cut += 1;
                                    let (start, end) = place.range;
                                    if !buoyancy {
                                    } else if centre_wet {
                                        submerge(ti..ti + 1, &mut under);
                                        cut_wet.push(start as usize..end as usize);
                                    } else {
                                        cut.push(start as usize..end as usize);
                                    }
                                    if let Some(d) = drag.as_mut() {
                                        d.cut(ti, centre_wet);
                                    }
                                }
                            }
                        }
                    }
                }
            }
            if let Some(done) = run {
                under.add_difference(&self.prefix[done.end], &self.prefix[done.start]);
            }
            if under.texels > 0 {
                let _ = add_closed_form(&mut local, &under, alpha, &beta, &g);
            }
            for (ranges, side) in [(cut_wet, PlanarTexels::Dry), (cut, PlanarTexels::Wet)] {
                if !ranges.is_empty() {
                    add_planar_ranges(&mut local, atlas, &ranges, alpha, &beta, &g, pressure, side);
                }
            }
            (
                local.rotated(&rot),
                drag.as_mut().and_then(DragWalk::finish),
                counts,
            )
        };
        let (mut sums, mut acc, mut counts) =
            (BuoyancySums::default(), DragAcc::default(), TileCounts::default());
        let mut wet = false;
        let mut add = |(s, d, c): (BuoyancySums, Option<DragAcc>, TileCounts)| {
            if let Some(d) = d {
                acc += &d;
                wet = true;
            }
            counts += c;
            sums += s;
        };
        // One chunk (a body of up to 512 tiles) is added here as it comes
        // rather than through `par_fold`, whose fold took a 128² box's
        // evaluation from 1.79–1.81 to 1.86–1.95 µs in four A/B pairs.
        if n_chunks == 1 {
            add(work(0));
        } else {
            par_map(n_chunks, work).into_iter().for_each(add);
        }
        let drag = options.drag.map(|d| match uniform {
            Some((_, u)) if wet => acc.system(&rot, &c, &u),
            // No drag texel under water: no drag.
            Some(_) => DragSums::default(),
            // A current changing linearly under a plane: tile by tile.
            None => match water
                .surface
                .as_any()
                .and_then(|s| s.downcast_ref::<crate::FlowPlane>())
            {
                Some(flow) => self.flow_drag(atlas, frame, state, &d, water.density, flow),
                // The fluid's velocity varies otherwise: per texel, with it
                // where it is.
                None => drag_sums(atlas, water, state, frame, &d, t, 0..atlas.len()),
            },
        });
        (sums, drag, counts)
    }
}

/// The most tiles of an atlas whose tiles are grouped by their place on
/// the body ([`spatial_groups`]); a larger atlas' are grouped by the
/// texture's blocks of [`TiledAtlas::GROUP`]² tiles.
const SPATIAL_TILES: usize = 512;

/// The most tiles in a group made by [`spatial_groups`].
const SPATIAL_GROUP: usize = 4;

/// Orders `ids` (indices into `centres`, the tiles' centres) so that
/// tiles close together on the body are close together in the list, and
/// cuts it into groups of at most [`SPATIAL_GROUP`] tiles, pushed to
/// `groups` as ranges of the list (offset by `start`): the leaves of a
/// k-d split of the centres, each part halved at its median along its
/// widest extent. Ties keep the atlas' order, so that a bake always
/// gives the same list.
///
/// On a small atlas the texture's blocks of 16 tiles are as wide as the
/// body: they span a box's faces and a sphere's seams, and a plane across
/// a floating body cut most of them, leaving most tiles to be looked at
/// one by one. Over 100 poses of the bench's meshes at 128² afloat on calm
/// water (the box level or tilted, the sphere turned any way), the bounds
/// the walk tests, blocks against these groups: the box 167 → 116, the
/// sphere 113 → 91; runs of consecutive submerged tiles (a difference of
/// running sums each) for the box 25 → 10 (the test
/// `a_walk_over_groups_by_place_tests_fewer_bounds_than_over_texture_blocks`
/// prints them). On a large atlas the blocks are
/// small against the body and these groups do no better: at 1024² the
/// box's walk would test 4,432 bounds against the blocks' 1,830 (a
/// throwaway probe), and a k-d tree over the groups, which tests fewer
/// (989 from its root), took the sphere's evaluation
/// (`sphere_1024/tiled`) from 8.7 to 11 µs.
fn spatial_groups(
    centres: &[Vector3<f64>],
    ids: &mut [usize],
    start: usize,
    groups: &mut Vec<std::ops::Range<usize>>,
) {
    if ids.len() <= SPATIAL_GROUP {
        if !ids.is_empty() {
            // A group's tiles in the atlas' order: neighbouring texels
            // where they can be.
            ids.sort_unstable();
            groups.push(start..start + ids.len());
        }
        return;
    }
    let (mut lo, mut hi) = (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN));
    for &i in ids.iter() {
        lo = lo.inf(&centres[i]);
        hi = hi.sup(&centres[i]);
    }
    let axis = (hi - lo).imax();
    ids.sort_by(|&a, &b| centres[a][axis].total_cmp(&centres[b][axis]).then(a.cmp(&b)));
    let half = ids.len() / 2;
    let (left, right) = ids.split_at_mut(half);
    spatial_groups(centres, left, start, groups);
    spatial_groups(centres, right, start + half, groups);
}

/// The sums of one evaluation, before [`finish`].
struct Evaluation {
    frame: Frame,
    sums: BuoyancySums,
    drag: Option<DragSums>,
    counts: TileCounts,
}

/// Where tiles and groups lie against the water plane whose depth is
/// `d(x) = α + β·x` (object coordinates from the atlas origin).
struct PlaneSides {
    alpha: f64,
    beta: Vector3<f64>,
    beta_norm: f64,
    beta_abs: Vector3<f64>,
}

impl PlaneSides {
    fn new(alpha: f64, beta: &Vector3<f64>) -> Self {
        Self {
            alpha,
            beta: *beta,
            beta_norm: beta.norm(),
            beta_abs: beta.abs(),
        }
    }

    /// A tile (or group) lies wholly under water when its bounding sphere
    /// or box does, wholly above when either does: the depth varies over
    /// it by at most the smaller of |β| r and |β|·h.
    #[inline]
    fn side(&self, m: &Bounds) -> Side {
        let dc = self.alpha + self.beta.dot(&m.centre);
        let reach = (self.beta_norm * m.radius).min(self.beta_abs.dot(&m.half_extent));
        if dc + reach <= 0.0 {
            Side::Dry
        } else if dc - reach > 0.0 {
            Side::Submerged
        } else {
            Side::Cut { centre_wet: dc > 0.0 }
        }
    }
}

/// Where a tile or group lies against the water plane.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    Dry,
    Submerged,
    /// Cut by the waterline, its centre under water or not.
    Cut {
        centre_wet: bool,
    },
}

/// Adds texels wholly under water, of moments `m`, to object-frame sums
/// (`wr`, `f`, `rxf` in object axes; rotated by the caller).
/// The moments the closed form reads: a run's [`Sums`] or one tile's
/// [`TileMoments`], without a copy.
trait Moments {
    fn s0(&self) -> &Vector3<f64>;
    fn s1(&self) -> &Matrix3<f64>;
    fn s2(&self) -> &[Matrix3<f64>; 3];
    fn area(&self) -> f64;
    fn texels(&self) -> u64;
}

impl Moments for Sums {
    fn s0(&self) -> &Vector3<f64> {
        &self.s0
    }
    fn s1(&self) -> &Matrix3<f64> {
        &self.s1
    }
    fn s2(&self) -> &[Matrix3<f64>; 3] {
        &self.s2
    }
    fn area(&self) -> f64 {
        self.area
    }
    fn texels(&self) -> u64 {
        self.texels
    }
}

impl Moments for TileMoments {
    fn s0(&self) -> &Vector3<f64> {
        &self.s0
    }
    fn s1(&self) -> &Matrix3<f64> {
        &self.s1
    }
    fn s2(&self) -> &[Matrix3<f64>; 3] {
        &self.s2
    }
    fn area(&self) -> f64 {
        self.area
    }
    fn texels(&self) -> u64 {
        u64::from(self.range.1 - self.range.0)
    }
}

/// Adds the planar closed form of the tile with moments `m` under the
/// depth `α + β·x` (object axes) to `s`, and returns `S1ᵀ g` and
/// `Σ_j g_j S2_j` (the moments weighted by the area vectors' up component,
/// for callers that take the depth further).
fn add_closed_form<M: Moments>(
    s: &mut BuoyancySums,
    m: &M,
    alpha: f64,
    beta: &Vector3<f64>,
    g: &Vector3<f64>,
) -> (Vector3<f64>, Matrix3<f64>) {
    let (s0, s1, s2) = (*m.s0(), *m.s1(), m.s2());
    // Σ A d = α S0 + S1 β
    let ad = alpha * s0 + s1 * beta;
    // T1 = Σ (g·A) x = S1ᵀ g ; T2 = Σ (g·A) x xᵀ = Σ_j g_j S2_j
    let t1 = s1.transpose() * g;
    let t2 = s2[0] * g.x + s2[1] * g.y + s2[2] * g.z;
    // w = −(g·A) d
    s.vol += -g.dot(&ad);
    s.wr += -(alpha * t1 + t2 * beta);
    s.wd2 += -0.5 * (alpha * alpha * g.dot(&s0) + 2.0 * alpha * beta.dot(&t1) + beta.dot(&(t2 * beta)));
    s.f += -ad;
    // Σ x × A d = α Σ x × A + Σ (β·x) x × A
    let cross1 = Vector3::new(
        s1[(2, 1)] - s1[(1, 2)],
        s1[(0, 2)] - s1[(2, 0)],
        s1[(1, 0)] - s1[(0, 1)],
    );
    // Σ (β·x) x_k A_j = (S2_j β)_k
    let b0 = s2[0] * beta;
    let b1 = s2[1] * beta;
    let b2 = s2[2] * beta;
    let cross2 = Vector3::new(b2[1] - b1[2], b0[2] - b2[0], b1[0] - b0[1]);
    s.rxf += -(alpha * cross1 + cross2);
    // Σ (d²/2) A_j = (α² S0_j + 2α (S1 β)_j + βᵀ S2_j β) / 2
    let bsb = Vector3::new(beta.dot(&b0), beta.dot(&b1), beta.dot(&b2));
    s.d2a += 0.5 * (alpha * alpha * s0 + 2.0 * alpha * (s1 * beta) + bsb);
    s.area += m.area();
    s.count += m.texels() as usize;
    (t1, t2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MassModel;
    use nalgebra::{Isometry3, UnitQuaternion};
    use soak_bake::{BakeOptions, builtin};

    /// The bounds a walk under `sides` tests over `groups` (each group's,
    /// then each tile's in a cut group) and the runs of consecutive tiles
    /// it takes in closed form (a difference of running sums each), as
    /// [`TiledAtlas::sums`] walks.
    fn walk(
        places: &[Place],
        groups: &[(Bounds, std::ops::Range<usize>)],
        sides: &PlaneSides,
    ) -> (usize, usize) {
        let (mut tests, mut runs, mut open) = (0, 0, false);
        let mut join = |wet: bool, runs: &mut usize| {
            *runs += usize::from(wet && !open);
            open = wet;
        };
        for (bounds, tiles) in groups {
            tests += 1;
            match sides.side(bounds) {
                Side::Dry => join(false, &mut runs),
                Side::Submerged => join(true, &mut runs),
                Side::Cut { .. } => {
                    for ti in tiles.clone() {
                        tests += 1;
                        match sides.side(&places[ti].bounds) {
                            Side::Dry | Side::Cut { centre_wet: false } => join(false, &mut runs),
                            Side::Submerged | Side::Cut { centre_wet: true } => join(true, &mut runs),
                        }
                    }
                }
            }
        }
        (tests, runs)
    }

    /// Over 100 poses afloat on calm water (the bench box level or tilted
    /// by up to 0.1 rad and turned any way about the vertical, the bench
    /// sphere turned any way, both within 2.5 cm of their draft's
    /// height), the walk over the bench meshes' 128² tiles grouped by
    /// their place on the body tests fewer bounds, and takes the
    /// submerged tiles in fewer runs, than over the same tiles grouped
    /// by the texture's blocks of 4 × 4 tiles (in the atlas' order within
    /// a block), which they were before. Printed with `--nocapture`.
    #[test]
    fn a_walk_over_groups_by_place_tests_fewer_bounds_than_over_texture_blocks() {
        for (name, mesh) in [
            ("box", builtin::cuboid(1.0, 0.6, 0.8)),
            ("sphere", builtin::sphere(0.5, 64, 32)),
        ] {
            let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
            let tiled = TiledAtlas::new(&atlas);
            let mass = MassModel::Solid { density: 500.0 }
                .mass_properties(&atlas)
                .unwrap();
            let by_place: Vec<_> = tiled.groups.iter().map(|g| (g.bounds, g.tiles.clone())).collect();
            // The same tiles in the texture's blocks.
            let ts = atlas.tile_size();
            let block = |ti: usize| {
                let [x, y] = atlas.texels()[tiled.places[ti].range.0 as usize];
                let span = ts * TiledAtlas::GROUP;
                (u32::from(y) / span, u32::from(x) / span, tiled.places[ti].range.0)
            };
            let mut order: Vec<usize> = (0..tiled.places.len()).collect();
            order.sort_by_key(|&ti| block(ti));
            let places: Vec<Place> = order.iter().map(|&ti| tiled.places[ti]).collect();
            let mut by_block = Vec::new();
            let mut start = 0;
            while start < order.len() {
                let key = |k: usize| {
                    let (by, bx, _) = block(order[k]);
                    (by, bx)
                };
                let end = (start..order.len())
                    .find(|&k| key(k) != key(start))
                    .unwrap_or(order.len());
                by_block.push((Bounds::around((start..end).map(|k| places[k].bounds)), start..end));
                start = end;
            }
            let (mut place_sums, mut block_sums) = ((0, 0), (0, 0));
            let mut seed = 1u64;
            let mut uniform = || {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (seed >> 11) as f64 / (1u64 << 53) as f64
            };
            let water = Water::calm(0.0);
            for _ in 0..100 {
                let turn = std::f64::consts::TAU;
                let rotation = if name == "box" {
                    UnitQuaternion::from_euler_angles(
                        0.2 * (uniform() - 0.5),
                        turn * uniform(),
                        0.2 * (uniform() - 0.5),
                    )
                } else {
                    UnitQuaternion::from_euler_angles(turn * uniform(), turn * uniform(), turn * uniform())
                };
                let y = 0.05 * (uniform() - 0.5);
                let state =
                    BodyState::at_rest(Isometry3::from_parts(Vector3::new(0.0, y, 0.0).into(), rotation));
                let frame = Frame::new(&atlas, &water, &state, &mass, 0.0, 1.0 / 60.0);
                let (n, offset) = frame.plane.expect("a plane");
                let alpha = (offset - n.dot(&frame.ow)) / n.y;
                let beta = -(frame.rot.transpose() * n) / n.y;
                let sides = PlaneSides::new(alpha, &beta);
                let (t, r) = walk(&tiled.places, &by_place, &sides);
                place_sums = (place_sums.0 + t, place_sums.1 + r);
                let (t, r) = walk(&places, &by_block, &sides);
                block_sums = (block_sums.0 + t, block_sums.1 + r);
            }
            println!(
                "{name} at 128²: bounds tested {} by blocks, {} by place; runs {} by blocks, {} by place (means over 100 poses)",
                block_sums.0 / 100,
                place_sums.0 / 100,
                block_sums.1 / 100,
                place_sums.1 / 100
            );
            assert!(
                (place_sums.0 as f64) < 0.85 * block_sums.0 as f64,
                "{name}: {place_sums:?} against {block_sums:?}"
            );
            if name == "box" {
                assert!(
                    place_sums.1 * 2 < block_sums.1,
                    "{name}: {place_sums:?} against {block_sums:?}"
                );
            }
        }
    }

    /// The groups list every tile once, consecutive and in order, each
    /// group's bounds around its tiles' and each chunk a group range; a
    /// small atlas' groups are of at most four tiles close together on
    /// the body (the bench box's reach at most 0.3 m from their centres,
    /// its texture's blocks up to 0.73 m), a large one's the texture's
    /// blocks.
    #[test]
    fn groups_list_every_tile_once_within_their_bounds() {
        let cases = [
            ("box", builtin::cuboid(1.0, 0.6, 0.8), 128, true),
            ("sphere", builtin::sphere(0.5, 64, 32), 128, true),
            ("box", builtin::cuboid(1.0, 0.6, 0.8), 256, false),
        ];
        for (name, mesh, n, spatial) in cases {
            let atlas = Atlas::bake(&mesh, BakeOptions::square(n)).unwrap();
            let tiled = TiledAtlas::new(&atlas);
            assert_eq!(tiled.tiles.len() <= SPATIAL_TILES, spatial, "{name} at {n}²");
            // Every tile of the atlas once.
            let mut ranges: Vec<(u32, u32)> = tiled.tiles.iter().map(|m| m.range).collect();
            ranges.sort_unstable();
            let mut want: Vec<(u32, u32)> = atlas.tiles().iter().map(|t| (t.start, t.end)).collect();
            want.sort_unstable();
            assert_eq!(ranges, want, "{name} at {n}²");
            // The groups, consecutive, cover the list.
            let mut next = 0;
            let mut widest: f64 = 0.0;
            for g in &tiled.groups {
                assert_eq!(g.tiles.start, next, "{name} at {n}²");
                assert!(!g.tiles.is_empty());
                if spatial {
                    assert!(g.tiles.len() <= SPATIAL_GROUP, "{name}: {} tiles", g.tiles.len());
                }
                next = g.tiles.end;
                for m in &tiled.tiles[g.tiles.clone()] {
                    let d = m.centre - g.bounds.centre;
                    assert!(d.norm() + m.radius <= g.bounds.radius * (1.0 + 1e-12), "{name}");
                    for k in 0..3 {
                        assert!(
                            d[k].abs() + m.half_extent[k] <= g.bounds.half_extent[k] * (1.0 + 1e-12) + 1e-15
                        );
                    }
                }
                widest = widest.max(g.bounds.radius);
            }
            assert_eq!(next, tiled.tiles.len(), "{name} at {n}²");
            if spatial {
                assert_eq!(tiled.group_chunk, tiled.groups.len(), "{name}: one chunk");
                if name == "box" {
                    assert!(widest < 0.3, "the box's widest group reaches {widest} m");
                }
            } else {
                assert_eq!(tiled.group_chunk, 32);
            }
        }
    }
}
