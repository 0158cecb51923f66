//! The drag's side of the tiled path: a coarser bake a body's drag is
//! summed over ([`DragTexels`]), and the walk over tiles that adds the
//! drag's closed forms and cut tiles' texels as the classification of
//! `super` meets them ([`DragWalk`]).

use super::*;

/// The texels a body's drag is summed over when they are not its own
/// atlas': another bake of the same mesh (same origin, same object
/// frame), typically coarser, with its tiles. See
/// [`TiledAtlas::evaluate_with_drag`].
#[derive(Clone, Debug)]
pub struct DragTexels {
    pub(super) atlas: Atlas,
    pub(super) tiled: TiledAtlas,
    /// For texels coarsened from a body's atlas: that atlas (a refresh
    /// refreshes it and coarsens it again) and the factor.
    source: Option<(std::sync::Arc<Atlas>, u32)>,
}

impl DragTexels {
    /// The drag texels of `atlas` (a bake of the body's mesh), with its
    /// tiles.
    pub fn new(atlas: Atlas) -> Self {
        let tiled = TiledAtlas::new(&atlas);
        Self {
            atlas,
            tiled,
            source: None,
        }
    }

    /// The default merging factor of [`DragTexels::coarsened`]: 4 × 4
    /// texels of a body's atlas per drag texel (a 128² body's drag over
    /// a 32² grid, a 1024² body's over 256²).
    pub const COARSENING: u32 = 4;

    /// The drag texels of `atlas` (the body's own, baked) coarsened by
    /// `factor`: each `factor`² block of its texels merged into one
    /// ([`Atlas::coarsened`]), in tiles of [`DragTexels::TILE_SIZE`]
    /// merged texels. Made from the atlas rather than the mesh, they are
    /// as few as the blocks whatever the mesh's triangle count (a bake of
    /// a mesh of `n` triangles keeps `n` texels or more), and follow the
    /// body's atlas through [`DragTexels::refresh`].
    ///
    /// # Errors
    /// Those of [`Atlas::coarsened`].
    pub fn coarsened(atlas: std::sync::Arc<Atlas>, factor: u32) -> Result<Self, soak_bake::BakeError> {
        let coarse = atlas.coarsened(factor, Self::TILE_SIZE)?;
        Ok(Self {
            source: Some((atlas, factor)),
            ..Self::new(coarse)
        })
    }

    /// The tile side of [`DragTexels::bake`], texels: half the default,
    /// as a coarse bake's tiles are wide on the surface (on a 1024² sphere
    /// with a 64² drag bake, 10 % less time than with 8² tiles).
    pub const TILE_SIZE: u32 = 4;

    /// `mesh` baked at `resolution`² (tiles of [`DragTexels::TILE_SIZE`])
    /// for its drag. A bake takes at least one texel per triangle: a mesh
    /// of `n` triangles has `n` drag texels or more at any resolution.
    ///
    /// # Errors
    /// Those of [`Atlas::bake`].
    pub fn bake(mesh: &soak_bake::Mesh, resolution: u32) -> Result<Self, soak_bake::BakeError> {
        let options = soak_bake::BakeOptions {
            tile_size: Self::TILE_SIZE,
            ..soak_bake::BakeOptions::square(resolution)
        };
        Atlas::bake(mesh, options).map(Self::new)
    }

    /// The atlas the drag is summed over.
    pub fn atlas(&self) -> &Atlas {
        &self.atlas
    }

    /// Follows a deforming mesh, as [`Atlas::refresh`] (new vertex
    /// positions, object frame, m, same topology); coarsened texels
    /// refresh the atlas they were made from and are coarsened again.
    ///
    /// # Errors
    /// Those of [`Atlas::refresh`].
    pub fn refresh(&mut self, positions: &[nalgebra::Point3<f64>]) -> Result<(), soak_bake::BakeError> {
        match &self.source {
            Some((source, factor)) => {
                let mut source = Atlas::clone(source);
                source.refresh(positions)?;
                *self = Self::coarsened(source.into(), *factor)?;
            }
            None => {
                self.atlas.refresh(positions)?;
                self.tiled = TiledAtlas::new(&self.atlas);
            }
        }
        Ok(())
    }

    /// Refuses drag texels of another mesh than `body`'s: their origins
    /// (each bake's bounding-box centre) must be the same.
    pub fn check(&self, body: &Atlas) -> Result<(), HydroError> {
        let (a, b) = (body.origin(), self.atlas.origin());
        let scale = body.bounding_radius().max(f64::MIN_POSITIVE);
        if (a - b).norm() > 1e-9 * scale {
            return Err(HydroError::DragTexels {
                body: a.coords.into(),
                drag: b.coords.into(),
            });
        }
        Ok(())
    }
}

/// [`evaluate`](crate::evaluate) (every texel) with the drag summed over
/// `drag`'s texels, every one of them too: the per-texel reference of
/// [`TiledAtlas::evaluate_with_drag`], which gives the same but for
/// rounding. Without [`HydroOptions::drag`] this is
/// [`evaluate`](crate::evaluate).
///
/// # Errors
/// Those of [`evaluate`](crate::evaluate), and [`HydroError::DragTexels`]
/// when `drag`'s atlas is not of this body's mesh.
pub fn evaluate_with_drag(
    atlas: &Atlas,
    drag: &DragTexels,
    water: &Water,
    state: &BodyState,
    mass: &MassProperties,
    t: f64,
    options: &HydroOptions,
) -> Result<HydroForces, HydroError> {
    if options.drag.is_none() {
        return crate::evaluate(atlas, water, state, mass, t, options);
    }
    drag.check(atlas)?;
    let sampled = crate::sampled_water(atlas, water, state, t, options)?;
    let water = sampled.as_ref().unwrap_or(water);
    let still = HydroOptions {
        drag: None,
        ..*options
    };
    let body = crate::evaluate(atlas, water, state, mass, t, &still)?;
    // The drag of an evaluation is its drag sums' alone (with the state,
    // the mass and the step): the coarse evaluation's, whatever its
    // buoyancy.
    let alone = HydroOptions {
        buoyancy: BuoyancyMode::Off,
        ..*options
    };
    let coarse = crate::evaluate(&drag.atlas, water, state, mass, t, &alone)?;
    Ok(HydroForces {
        drag: coarse.drag,
        drag_explicit: coarse.drag_explicit,
        ..body
    })
}

/// The drag of one chunk of the tiled path's groups (object axes about the
/// atlas origin): runs of tiles whose skin friction, or whose quadratic
/// drag, takes the closed form of their moments, and the per-texel kernel
/// for the rest: the tiles it takes are listed as they come, by what the
/// kernel is to do with them, and each list goes through the kernel in
/// one call at the end.
pub(super) struct DragWalk<'a> {
    pub(super) tiled: &'a TiledAtlas,
    pub(super) atlas: &'a Atlas,
    pub(super) p: LocalDrag,
    /// Texel ranges for the kernel, by [`DragWalk::list`].
    pub(super) texels: [Ranges; 8],
    /// Tiles whose every texel adds its skin friction.
    pub(super) linear: MomentRun<true>,
    /// Tiles whose every texel adds `k_q h·w`.
    pub(super) quadratic: MomentRun<false>,
}

impl<'a> DragWalk<'a> {
    pub(super) fn new(tiled: &'a TiledAtlas, atlas: &'a Atlas, p: LocalDrag) -> Self {
        Self {
            tiled,
            atlas,
            p,
            texels: Default::default(),
            linear: MomentRun::default(),
            quadratic: MomentRun::default(),
        }
    }

    /// Tiles wholly under water, `facing` a box around their `h`.
    pub(super) fn submerged(&mut self, tiles: std::ops::Range<usize>, facing: &FacingBounds) {
        if self.p.lin > 0.0 {
            self.linear.push(&self.tiled.drag_prefix, tiles.clone());
        }
        if self.p.quadratic() {
            self.submerged_quadratic(tiles, facing);
        }
    }

    /// The quadratic drag of tiles wholly under water.
    pub(super) fn submerged_quadratic(&mut self, tiles: std::ops::Range<usize>, facing: &FacingBounds) {
        let prefix = &self.tiled.drag_prefix;
        match facing.facing(&self.p.w) {
            Facing::All => self.quadratic.push(prefix, tiles),
            Facing::None => {}
            Facing::Mixed if tiles.len() > 1 => {
                for ti in tiles {
                    let facing = self.tiled.facing[ti];
                    self.submerged_quadratic(ti..ti + 1, &facing);
                }
            }
            Facing::Mixed => {
                // The kernel takes the smaller side: the texels facing the
                // flow, or where most of the tile does, the others out of
                // its closed form.
                // The tile's skin friction is in its closed form already.
                let ti = tiles.start;
                let quadratic = self.mostly_facing(ti);
                if quadratic {
                    self.quadratic.push(prefix, tiles);
                }
                let (start, end) = self.tiled.places[ti].range;
                let added = Added {
                    linear: true,
                    quadratic,
                };
                self.texels[Self::list(false, added)].push(start as usize..end as usize);
            }
        }
    }

    /// A tile cut by the waterline, its centre under water or not.
    pub(super) fn cut(&mut self, ti: usize, centre_wet: bool) {
        let prefix = &self.tiled.drag_prefix;
        if centre_wet && self.p.lin > 0.0 {
            self.linear.push(prefix, ti..ti + 1);
        }
        let quadratic = centre_wet
            && self.p.quadratic()
            && match self.tiled.facing[ti].facing(&self.p.w) {
                Facing::All => true,
                Facing::None => false,
                Facing::Mixed => self.mostly_facing(ti),
            };
        if quadratic {
            self.quadratic.push(prefix, ti..ti + 1);
        }
        self.texels(
            ti,
            Added {
                linear: centre_wet,
                quadratic,
            },
        );
    }

    /// Whether the texels of tile `ti` face the flow more than not.
    pub(super) fn mostly_facing(&self, ti: usize) -> bool {
        let prefix = &self.tiled.drag_prefix;
        let (to, from) = (&prefix[ti + 1].quadratic, &prefix[ti].quadratic);
        (0..6).map(|j| (to[j][0] - from[j][0]) * self.p.w[j]).sum::<f64>() > 0.0
    }

    /// The per-texel kernel over tile `ti`.
    pub(super) fn texels(&mut self, ti: usize, added: Added) {
        let (start, end) = self.tiled.places[ti].range;
        self.texels[Self::list(self.p.lin > 0.0, added)].push(start as usize..end as usize);
    }

    /// Which list of [`DragWalk::texels`] takes tiles whose kernel adds
    /// skin friction (`linear`, where there is any) and completes `added`.
    pub(super) fn list(linear: bool, added: Added) -> usize {
        usize::from(linear) * 4 + usize::from(added.linear) * 2 + usize::from(added.quadratic)
    }

    /// What the closed forms added to the tiles of list `j` (of either
    /// half): the inverse of [`DragWalk::list`]'s `added`.
    pub(super) fn added(j: usize) -> Added {
        Added {
            linear: j & 2 != 0,
            quadratic: j & 1 != 0,
        }
    }

    /// The chunk's sums; `None` when none of its texels is under water
    /// (every sum would add zeros to zeros).
    pub(super) fn finish(&mut self) -> Option<DragAcc> {
        let prefix = &self.tiled.drag_prefix;
        if self.texels.iter().all(|ranges| ranges.is_empty())
            && self.linear.is_empty()
            && self.quadratic.is_empty()
        {
            return None;
        }
        let mut acc = DragAcc::default();
        let mut lanes = DragLanes::default();
        // One kernel call for the lists without its skin friction, one for
        // those with: each list's ranges in turn.
        for (k, lists) in self.texels.chunks(4).enumerate() {
            let p = LocalDrag {
                lin: if k == 1 { self.p.lin } else { 0.0 },
                ..self.p
            };
            let lists: [RangeList; 4] = std::array::from_fn(|j| (&lists[j][..], Self::added(j)));
            add_drag_ranges(&mut lanes, self.atlas, &lists, &p);
        }
        lanes.add_to(&mut acc);
        self.linear.close(prefix).add_linear(&mut acc, &self.p);
        self.quadratic.close(prefix).add_quadratic(&mut acc, &self.p);
        Some(acc)
    }
}

impl TiledAtlas {
    /// The drag under a plane whose current changes linearly over space
    /// ([`crate::FlowPlane`]), as the system about the centre of mass in
    /// world axes: each tile wholly under water in closed form, in the
    /// fluid to first order about its centre (the linear current itself),
    /// where its texels all face the flow alike
    /// ([`SeaDragSums::add_tile`](crate::hydrostatics::sea_drag::SeaDragSums::add_tile));
    /// every other submerged texel through the sea's drag kernel in the
    /// same fluid. `frame` is the evaluation's, under the flow's plane.
    pub(super) fn flow_drag(
        &self,
        atlas: &Atlas,
        frame: &Frame,
        state: &BodyState,
        drag: &crate::Drag,
        density: f64,
        flow: &crate::FlowPlane,
    ) -> DragSums {
        use crate::hydrostatics::sea_drag::{LinearFluid, SeaDragLanes, SeaDragParams, SeaDragSums};
        let Some((alpha, beta, _)) = frame.local_plane else {
            return DragSums::default();
        };
        let rot = frame.rot;
        let c = rot.transpose() * (frame.com - frame.ow);
        let params = SeaDragParams::new(
            drag,
            density,
            &rot,
            &c,
            &state.linear_velocity,
            &state.angular_velocity,
        );
        let d = SeaDragFrame {
            params,
            rot,
            ow: frame.ow,
            patch: None,
        };
        // The fluid in object axes about the atlas origin: `u_o + U x`.
        let grad = rot.transpose() * flow.gradient * rot;
        let u_o = rot.transpose() * (flow.plane.current + flow.gradient * (frame.ow - flow.about.coords));
        let fluid = |centre: &Vector3<f64>| LinearFluid {
            u: u_o + grad * centre,
            grad,
            c: *centre,
        };
        let sides = PlaneSides::new(alpha, &beta);
        let classify = |m: &Bounds| sides.side(m);
        let xs = atlas.local_positions().columns(0..atlas.len());
        let chunk = |k: usize| {
            let groups =
                &self.groups[k * self.group_chunk..((k + 1) * self.group_chunk).min(self.groups.len())];
            let mut sums = SeaDragSums::default();
            let mut lanes = SeaDragLanes::default();
            let mut depths = Vec::new();
            for group in groups {
                if classify(&group.bounds) == Side::Dry {
                    continue;
                }
                for ti in group.tiles.clone() {
                    let m = &self.tiles[ti];
                    let range = m.range.0 as usize..m.range.1 as usize;
                    let side = classify(&m.bounds());
                    if side == Side::Dry {
                        continue;
                    }
                    let f = fluid(&m.centre);
                    match side {
                        Side::Dry => continue,
                        Side::Submerged => {
                            if self.add_tile_drag(&mut sums, ti, &d, &f) {
                                continue;
                            }
                            depths.clear();
                            depths.resize(range.len(), 1.0);
                        }
                        Side::Cut { .. } => {
                            depths.clear();
                            depths.extend(range.clone().map(|i| {
                                alpha
                                    + beta.x * f64::from(xs[0][i])
                                    + beta.y * f64::from(xs[1][i])
                                    + beta.z * f64::from(xs[2][i])
                            }));
                        }
                    }
                    lanes.add(atlas, range, &depths, &d, Some(&f));
                }
            }
            sums + lanes.finish()
        };
        let mut total = SeaDragSums::default();
        par_fold(
            self.groups.len().div_ceil(self.group_chunk),
            chunk,
            &mut total,
            |total, part| *total += part,
        );
        total.system(&rot, &c)
    }
}

/// Drag moments of runs of consecutive tiles, from the running sums: the
/// skin friction's (`LINEAR`, which [`DragMoments::add_linear`] reads) or
/// the quadratic part's (which [`DragMoments::add_quadratic`] reads), the
/// other part left at zero.
#[derive(Default)]
pub(super) struct MomentRun<const LINEAR: bool> {
    open: Option<std::ops::Range<usize>>,
    sum: DragMoments,
}

impl<const LINEAR: bool> MomentRun<LINEAR> {
    /// Whether no tile was pushed (a run, once open, stays open until
    /// [`MomentRun::close`]).
    fn is_empty(&self) -> bool {
        self.open.is_none()
    }

    /// Adds `tiles`, extending the open run where they follow it.
    fn push(&mut self, prefix: &[DragMoments], tiles: std::ops::Range<usize>) {
        match self.open.as_mut() {
            Some(open) if open.end == tiles.start => open.end = tiles.end,
            _ => {
                if let Some(done) = self.open.replace(tiles) {
                    self.add(prefix, done);
                }
            }
        }
    }

    /// Adds the moments of a finished run.
    fn add(&mut self, prefix: &[DragMoments], done: std::ops::Range<usize>) {
        let (to, from) = (&prefix[done.end], &prefix[done.start]);
        if LINEAR {
            self.sum.add_linear_difference(to, from);
        } else {
            self.sum.add_quadratic_difference(to, from);
        }
    }

    /// The sums of every tile pushed (the open run closed).
    fn close(&mut self, prefix: &[DragMoments]) -> &DragMoments {
        if let Some(done) = self.open.take() {
            self.add(prefix, done);
        }
        &self.sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hydrostatics::finish::finish;
    use crate::{Drag, MassModel, Unbounded};
    use nalgebra::{Isometry3, UnitQuaternion, Vector3};
    use soak_bake::{BakeOptions, builtin};

    /// Under a plane, the drag texels' sums taken in the body's frame (the
    /// same origin and plane) are the sums taken in their own, to the bit:
    /// afloat, wholly under, wholly above (nothing to sum), and in a medium
    /// with no free surface (whose plane above the body is placed by each
    /// atlas' own radius).
    #[test]
    fn the_drag_texels_read_the_bodys_frame_as_their_own() {
        let mesh = builtin::cuboid(1.0, 0.6, 0.8);
        let atlas = std::sync::Arc::new(Atlas::bake(&mesh, BakeOptions::square(128)).unwrap());
        let tiled = TiledAtlas::new(&atlas);
        let mass = MassModel::Solid { density: 500.0 }
            .mass_properties(&atlas)
            .unwrap();
        let options = HydroOptions {
            drag: Some(Drag {
                coefficient: 0.8,
                linear: 20.0,
            }),
            ..HydroOptions::default()
        };
        let still = HydroOptions {
            drag: None,
            ..options
        };
        let coarsened = DragTexels::coarsened(atlas.clone(), DragTexels::COARSENING).unwrap();
        let baked = DragTexels::bake(&mesh, 32).unwrap();
        let current = || {
            Water::new(Unbounded {
                current: [0.5, 0.0, -0.2],
            })
        };
        let mut served = 0;
        for drag in [&coarsened, &baked] {
            for (water, heights) in [(Water::calm(0.0), &[0.1, -2.0, 3.0][..]), (current(), &[0.0][..])] {
                for &y in heights {
                    let state = BodyState {
                        linear_velocity: Vector3::new(0.3, -0.4, 0.1),
                        angular_velocity: Vector3::new(0.2, 0.1, -0.3),
                        ..BodyState::at_rest(Isometry3::from_parts(
                            Vector3::new(0.2, y, -0.1).into(),
                            UnitQuaternion::from_euler_angles(0.3, -0.2, 0.5),
                        ))
                    };
                    let got = tiled
                        .evaluate_with_drag(&atlas, drag, &water, &state, &mass, 0.0, &options)
                        .unwrap();
                    let body = tiled
                        .evaluation(&atlas, &water, &state, &mass, 0.0, &still, true)
                        .unwrap();
                    let own = drag
                        .tiled
                        .evaluation(&drag.atlas, &water, &state, &mass, 0.0, &options, false)
                        .unwrap();
                    let want = finish(
                        &body.frame,
                        &water,
                        &state,
                        &mass,
                        &body.sums,
                        own.drag.as_ref(),
                        &options,
                    );
                    assert_eq!(got, want, "drag texels of {} at y = {y}", drag.atlas.len());
                    served += usize::from(body.frame.serves(&atlas, &drag.atlas, &water, 0.0));
                }
            }
        }
        assert!(served >= 3, "the body's frame served {served} times");
    }

    #[test]
    fn a_list_reads_back_what_it_was_chosen_by() {
        for linear in [false, true] {
            for (l, q) in [(false, false), (false, true), (true, false), (true, true)] {
                let added = Added {
                    linear: l,
                    quadratic: q,
                };
                let j = DragWalk::list(linear, added);
                assert_eq!(j / 4, usize::from(linear));
                assert_eq!(DragWalk::added(j % 4), added);
            }
        }
    }
}
