//! The tiled path for planar water: same answer as the per-texel sums, far
//! less work.
//!
//! Under a plane the depth is affine in object-space position,
//! `d(x) = α + β·x`, so a tile of texels that lies wholly under water
//! contributes a closed form of its precomputed moments `Σ A`, `Σ A⊗x` and
//! `Σ A⊗x⊗x`; a tile wholly above water contributes nothing (a bounding-sphere
//! test decides); only tiles cut by the waterline are summed texel by texel.
//! Any other surface falls back to the per-texel path.

use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;
use soak_bake::Atlas;

use crate::error::HydroError;
use crate::hydrostatics::{
    BodyState, BuoyancyMode, BuoyancySums, DragSums, Frame, HydroForces, HydroOptions, add_planar_ranges,
    evaluate, finish, texel,
};
use crate::mass::{MassProperties, par_map};
use crate::water::Water;

/// Moments of one tile's texels, relative to the atlas origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileMoments {
    /// Σ A, m².
    pub s0: Vector3<f64>,
    /// `s1[(j, k)] = Σ A_j x_k`, m³.
    pub s1: Matrix3<f64>,
    /// `s2[j][(k, l)] = Σ A_j x_k x_l`, m⁴.
    pub s2: [Matrix3<f64>; 3],
    /// Σ a, m².
    pub area: f64,
    /// Bounding-sphere centre (relative to the atlas origin), m.
    pub centre: Vector3<f64>,
    /// Bounding-sphere radius, m.
    pub radius: f64,
    /// Half the sides of the bounding box about `centre` (object axes), m.
    pub half_extent: Vector3<f64>,
    /// Texel range in the atlas.
    pub range: (u32, u32),
}

impl TileMoments {
    /// Adds the moments of `other` (not its bounds): the sums of the two
    /// sets of texels, whose closed form is the sum of the two closed forms.
    fn add_moments(&mut self, other: &TileMoments) {
        self.s0 += other.s0;
        self.s1 += other.s1;
        for j in 0..3 {
            self.s2[j] += other.s2[j];
        }
        self.area += other.area;
    }

    /// No texels yet: zero sums over `range`.
    fn empty(range: (u32, u32)) -> Self {
        Self {
            s0: Vector3::zeros(),
            s1: Matrix3::zeros(),
            s2: [Matrix3::zeros(); 3],
            area: 0.0,
            centre: Vector3::zeros(),
            radius: 0.0,
            half_extent: Vector3::zeros(),
            range,
        }
    }
}

/// An atlas with per-tile moments, for fast hydrostatics under planar water.
///
/// Two levels: the atlas' tiles (`tile_size`² texels), and groups of
/// [`TiledAtlas::GROUP`]² neighbouring tiles with the sums of their moments.
/// A group wholly under or above water is settled by one test; only the
/// tiles of groups the waterline cuts are looked at one by one.
#[derive(Clone, Debug)]
pub struct TiledAtlas {
    /// Tile moments, ordered group by group.
    tiles: Vec<TileMoments>,
    /// Group moments (their `range` is the group's range in `tiles`).
    groups: Vec<TileMoments>,
    /// Texels per group.
    group_texels: Vec<u64>,
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

impl TiledAtlas {
    /// Precomputes the tile moments of `atlas` (once per bake or refresh).
    pub fn new(atlas: &Atlas) -> Self {
        let tiles = atlas
            .tiles()
            .par_iter()
            .map(|t| {
                let r = t.range();
                let mut m = TileMoments::empty((t.start, t.end));
                let (mut lo, mut hi) = (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN));
                for i in r.clone() {
                    let (x, a) = texel(atlas, i);
                    lo = lo.inf(&x);
                    hi = hi.sup(&x);
                    m.s0 += a;
                    m.s1 += a * x.transpose();
                    let xx = x * x.transpose();
                    for j in 0..3 {
                        m.s2[j] += xx * a[j];
                    }
                    m.area += atlas.areas()[i] as f64;
                }
                m.centre = (lo + hi) * 0.5;
                m.half_extent = (hi - lo) * 0.5;
                m.radius = r
                    .map(|i| (texel(atlas, i).0 - m.centre).norm())
                    .fold(0.0, f64::max);
                m
            })
            .collect::<Vec<_>>();
        // Group the tiles by the block of GROUP × GROUP tiles their first
        // texel lies in (tiles are in row-major block order already).
        let ts = atlas.tile_size().max(1);
        let group_of = |m: &TileMoments| {
            let [x, y] = atlas.texels().get(m.range.0 as usize).copied().unwrap_or([0, 0]);
            let span = ts * Self::GROUP;
            (u32::from(y) / span, u32::from(x) / span)
        };
        let mut tiles = tiles;
        tiles.sort_by_key(|m| (group_of(m), m.range.0));
        let mut groups = Vec::new();
        let mut group_texels = Vec::new();
        let mut start = 0;
        while start < tiles.len() {
            let key = group_of(&tiles[start]);
            let end = start + tiles[start..].iter().take_while(|m| group_of(m) == key).count();
            let members = &tiles[start..end];
            let mut g = TileMoments::empty((start as u32, end as u32));
            let (mut lo, mut hi) = (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN));
            for m in members {
                g.add_moments(m);
                lo = lo.inf(&(m.centre - m.half_extent));
                hi = hi.sup(&(m.centre + m.half_extent));
            }
            g.centre = (lo + hi) * 0.5;
            g.half_extent = (hi - lo) * 0.5;
            g.radius = members
                .iter()
                .map(|m| (m.centre - g.centre).norm() + m.radius)
                .fold(0.0, f64::max);
            groups.push(g);
            group_texels.push(members.iter().map(|m| u64::from(m.range.1 - m.range.0)).sum());
            start = end;
        }
        Self {
            tiles,
            groups,
            group_texels,
        }
    }

    /// Tiles per side of a group: a group is `GROUP`² tiles.
    pub const GROUP: u32 = 4;

    /// The tiles' moments, ordered group by group.
    pub fn tiles(&self) -> &[TileMoments] {
        &self.tiles
    }

    /// Same as [`crate::evaluate`], using closed forms for tiles wholly under
    /// a planar surface. Falls back to the per-texel path for other surfaces.
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
        let frame = Frame::new(atlas, water, state, mass, t);
        let Some((n, offset)) = frame.plane else {
            return evaluate(atlas, water, state, mass, t, options).map(|f| (f, TileCounts::default()));
        };
        let rot = frame.rot;
        // d(x) = α + β·x in object coordinates relative to the atlas origin.
        let alpha = (offset - n.dot(&frame.ow)) / n.y;
        let beta = -(rot.transpose() * n) / n.y;
        let bn = beta.norm();
        let g = rot.transpose() * Vector3::y();

        // A tile (or group) lies wholly under water when its bounding
        // sphere or box does, wholly above when either does: the depth
        // varies over it by at most the smaller of |β| r and |β|·h.
        let beta_abs = beta.abs();
        let classify = |m: &TileMoments| {
            let dc = alpha + beta.dot(&m.centre);
            let reach = (bn * m.radius).min(beta_abs.dot(&m.half_extent));
            if dc + reach <= 0.0 {
                Side::Dry
            } else if dc - reach > 0.0 {
                Side::Submerged
            } else {
                Side::Cut
            }
        };
        const GROUP_CHUNK: usize = 32;
        let pressure = options.buoyancy == BuoyancyMode::Pressure;
        let n_chunks = self.groups.len().div_ceil(GROUP_CHUNK);
        let parts: Vec<(BuoyancySums, Option<DragSums>, TileCounts)> = par_map(n_chunks, |c| {
            let mut drag = options.drag.map(|_| DragSums::default());
            let mut counts = TileCounts::default();
            let mut local = BuoyancySums::default(); // object frame
            let add_drag = |start: usize, end: usize, ds: &mut DragSums| {
                let Some(coefficients) = options.drag.as_ref() else {
                    return;
                };
                for i in start..end {
                    let (x, a) = texel(atlas, i);
                    let d = alpha + beta.dot(&x);
                    if d > 0.0 {
                        let p = frame.ow + rot * x;
                        let rc = p - frame.com;
                        let u = water.surface.velocity(&nalgebra::Point3::from(p), t);
                        let v = state.linear_velocity + state.angular_velocity.cross(&rc) - u;
                        ds.add_texel(coefficients, water.density, &rc, &(rot * a), &v, &u);
                    }
                }
            };
            // Tiles and groups wholly under water add their moments up,
            // and the sum takes one closed form; the cut tiles' texels go
            // through the planar kernel together.
            let mut under = TileMoments::empty((0, 0));
            let mut under_texels = 0u64;
            let mut cut = Vec::with_capacity(64);
            let range = c * GROUP_CHUNK..((c + 1) * GROUP_CHUNK).min(self.groups.len());
            for (gi, &texels) in range.clone().zip(&self.group_texels[range]) {
                let group = &self.groups[gi];
                let members = group.range.0 as usize..group.range.1 as usize;
                match classify(group) {
                    Side::Dry => {
                        counts.dry += members.len();
                        continue;
                    }
                    Side::Submerged => {
                        counts.submerged += members.len();
                        under.add_moments(group);
                        under_texels += texels;
                    }
                    Side::Cut => {
                        for ti in members.clone() {
                            let tile = &self.tiles[ti];
                            let (start, end) = (tile.range.0 as usize, tile.range.1 as usize);
                            match classify(tile) {
                                Side::Dry => counts.dry += 1,
                                Side::Submerged => {
                                    counts.submerged += 1;
                                    under.add_moments(tile);
                                    under_texels += (end - start) as u64;
                                }
                                Side::Cut => {
                                    counts.cut += 1;
                                    cut.push(start..end);
                                }
                            }
                        }
                    }
                }
                // Drag is per texel wherever the group is wet.
                if let Some(ds) = drag.as_mut() {
                    for tile in &self.tiles[members] {
                        add_drag(tile.range.0 as usize, tile.range.1 as usize, ds);
                    }
                }
            }
            if under_texels > 0 {
                add_closed_form(&mut local, &under, under_texels, alpha, &beta, &g);
            }
            if !cut.is_empty() {
                add_planar_ranges(&mut local, atlas, &cut, alpha, &beta, &g, pressure);
            }
            (local.rotated(&rot), drag, counts)
        });
        let mut sums = BuoyancySums::default();
        let mut drag = options.drag.map(|_| DragSums::default());
        let mut counts = TileCounts::default();
        for (s, d, c) in parts {
            sums = sums + s;
            if let (Some(acc), Some(d)) = (drag.as_mut(), d) {
                *acc = *acc + d;
            }
            counts.submerged += c.submerged;
            counts.dry += c.dry;
            counts.cut += c.cut;
        }
        Ok((
            finish(&frame, water, state, mass, &sums, drag.as_ref(), options),
            counts,
        ))
    }
}

/// Where a tile or group lies against the water plane.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    Dry,
    Submerged,
    Cut,
}

/// Adds a wholly submerged tile (or group) of `texels` samples to
/// object-frame sums (`wr`, `f`, `rxf` in object axes; rotated by the caller).
fn add_closed_form(
    s: &mut BuoyancySums,
    m: &TileMoments,
    texels: u64,
    alpha: f64,
    beta: &Vector3<f64>,
    g: &Vector3<f64>,
) {
    // Σ A d = α S0 + S1 β
    let ad = alpha * m.s0 + m.s1 * beta;
    // T1 = Σ (g·A) x = S1ᵀ g ; T2 = Σ (g·A) x xᵀ = Σ_j g_j S2_j
    let t1 = m.s1.transpose() * g;
    let t2 = m.s2[0] * g.x + m.s2[1] * g.y + m.s2[2] * g.z;
    // w = −(g·A) d
    s.vol += -g.dot(&ad);
    s.wr += -(alpha * t1 + t2 * beta);
    s.wd2 += -0.5 * (alpha * alpha * g.dot(&m.s0) + 2.0 * alpha * beta.dot(&t1) + beta.dot(&(t2 * beta)));
    s.f += -ad;
    // Σ x × A d = α Σ x × A + Σ (β·x) x × A
    let cross1 = Vector3::new(
        m.s1[(2, 1)] - m.s1[(1, 2)],
        m.s1[(0, 2)] - m.s1[(2, 0)],
        m.s1[(1, 0)] - m.s1[(0, 1)],
    );
    // Σ (β·x) x_k A_j = (S2_j β)_k
    let b0 = m.s2[0] * beta;
    let b1 = m.s2[1] * beta;
    let b2 = m.s2[2] * beta;
    let cross2 = Vector3::new(b2[1] - b1[2], b0[2] - b2[0], b1[0] - b0[1]);
    s.rxf += -(alpha * cross1 + cross2);
    // Σ (d²/2) A_j = (α² S0_j + 2α (S1 β)_j + βᵀ S2_j β) / 2
    let bsb = Vector3::new(beta.dot(&b0), beta.dot(&b1), beta.dot(&b2));
    s.d2a += 0.5 * (alpha * alpha * m.s0 + 2.0 * alpha * (m.s1 * beta) + bsb);
    s.area += m.area;
    s.count += texels as usize;
}
