//! Buoyancy and drag of a body from its texel atlas, per texel.
//!
//! For texel `i` at world position `p_i` with world area vector `A_i`,
//! depth `d_i = f(p_i) − p_i.y` and submerged set `S = {i : d_i > 0}`:
//! `V_s = Σ_S −A_{i,y} d_i` (signed columns, exact for non-convex bodies and
//! any surface `y = f(x, z)`), `C_B = (1/V_s) Σ_S −A_{i,y} d_i (p_x, p_y + d_i/2, p_z)`;
//! Archimedes mode applies `ρ g V_s` up at `C_B`; pressure mode sums
//! `−ρ g d_i A_i` and its torque (equal on a plane, and it also feels the
//! sideways push of a wave's slope). Drag is quadratic per submerged texel
//! facing its relative velocity, plus optional linear skin friction, and is
//! integrated implicitly over the step so it never reverses a velocity.

use nalgebra::{Isometry3, Matrix3, Matrix6, Point3, Vector3, Vector6};
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::error::HydroError;
use crate::mass::{CHUNK, MassProperties, chunked_sum};
use crate::water::{SurfaceKind, Water};

/// Which buoyancy force is reported as [`HydroForces::buoyancy`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BuoyancyMode {
    /// `ρ g V_s` straight up at the centre of buoyancy (the thesis' model).
    /// Where the surface over a floating body is not flat, its torque also
    /// takes the slope's part, so that force and torque together are the
    /// derivative of the water's potential and a body rocking over waves
    /// or a step neither gains nor loses energy by it; there is still no
    /// sideways force (no drift).
    #[default]
    Archimedes,
    /// Sum of hydrostatic pressure forces `−ρ g d_i A_i` and their torques.
    Pressure,
    /// No buoyancy.
    Off,
}

/// Drag coefficients.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Drag {
    /// Quadratic pressure-drag coefficient `C_d` (dimensionless); 1.0 is a
    /// flat plate, about 0.5 a sphere.
    pub coefficient: f64,
    /// Linear skin friction, N·s/m per m² of wetted surface, on the
    /// tangential relative velocity.
    #[serde(default)]
    pub linear: f64,
}

impl Default for Drag {
    fn default() -> Self {
        Self {
            coefficient: 1.0,
            linear: 0.0,
        }
    }
}

/// What to compute.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HydroOptions {
    /// Buoyancy model.
    pub buoyancy: BuoyancyMode,
    /// Drag, if any.
    pub drag: Option<Drag>,
    /// Time step over which drag is integrated implicitly, s. Zero reports
    /// the explicit drag force of the current velocity.
    pub dt: f64,
}

impl Default for HydroOptions {
    fn default() -> Self {
        Self {
            buoyancy: BuoyancyMode::Archimedes,
            drag: None,
            dt: 1.0 / 60.0,
        }
    }
}

/// Pose and velocity of a body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyState {
    /// Object-to-world transform (m).
    pub pose: Isometry3<f64>,
    /// Velocity of the centre of mass, world frame, m/s.
    pub linear_velocity: Vector3<f64>,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: Vector3<f64>,
}

impl BodyState {
    /// A body at rest at `pose`.
    pub fn at_rest(pose: Isometry3<f64>) -> Self {
        Self {
            pose,
            linear_velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
        }
    }

    pub(crate) fn check(&self) -> Result<(), HydroError> {
        let fin = |v: &[f64]| v.iter().all(|c| c.is_finite());
        if !fin(self.pose.translation.vector.as_slice()) || !fin(self.pose.rotation.coords.as_slice()) {
            return Err(HydroError::NonFiniteState { field: "pose" });
        }
        if !fin(self.linear_velocity.as_slice()) {
            return Err(HydroError::NonFiniteState {
                field: "linear_velocity",
            });
        }
        if !fin(self.angular_velocity.as_slice()) {
            return Err(HydroError::NonFiniteState {
                field: "angular_velocity",
            });
        }
        Ok(())
    }
}

/// A force and a torque, world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Wrench {
    /// Force, N.
    pub force: Vector3<f64>,
    /// Torque about the centre of mass, N·m.
    pub torque: Vector3<f64>,
}

impl std::ops::Add for Wrench {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            force: self.force + o.force,
            torque: self.torque + o.torque,
        }
    }
}

impl Wrench {
    /// Whether force and torque are finite.
    pub fn is_finite(&self) -> bool {
        self.force.iter().chain(self.torque.iter()).all(|c| c.is_finite())
    }
}

/// Everything the fluid does to a body in one evaluation, world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct HydroForces {
    /// Submerged volume `V_s`, m³: `Σ −A_y d` over the submerged texels,
    /// but in Archimedes mode, for a body wholly under a surface that is
    /// not a plane, moved towards the enclosed volume as it goes deeper
    /// (by the weight [`HydroForces::deep`]), which takes out the sampling
    /// error of `∮ h n_y dA = 0`.
    pub submerged_volume: f64,
    /// Centre of buoyancy, world, m (the body's centre of mass when dry).
    pub center_of_buoyancy: Point3<f64>,
    /// Wetted (submerged) surface area, m².
    pub wetted_area: f64,
    /// Submerged texels.
    pub submerged_texels: usize,
    /// The water columns' potential `ρ_w g Σ (−A_{i,y}) d_i²/2` over the
    /// submerged texels, J (zero dry; summed whatever the buoyancy mode).
    /// Minus its derivative along a vertical displacement is the vertical
    /// buoyancy, and in Archimedes mode minus its derivative along a turn
    /// is the torque wherever the body is partly dry, so that on calm water
    /// `½ m v² + ½ ωᵀIω + m g y_G + potential` is conserved. (0 when read
    /// from a saved state that predates it.)
    #[serde(default)]
    pub potential: f64,
    /// How deep the body is: 0 while any texel is dry, 1 once every texel
    /// is under water; but in Archimedes mode under a surface that is not
    /// a plane, `φ = Π min(d_i/r, 1)` over the texels (`r` the bounding
    /// radius), 1 only once every texel is deeper than `r`: the weight with
    /// which the force's volume has moved from `Σ −A_y d` to the enclosed
    /// volume (see [`HydroForces::submerged_volume`]). Below 1 the body is
    /// at the surface, where its buoyancy changes with its pose. (0 when
    /// read from a saved state that predates it.)
    #[serde(default)]
    pub deep: f64,
    /// The buoyancy of the mode [`HydroOptions::buoyancy`] selects, N and
    /// N·m about the centre of mass: in Archimedes mode `ρ g V_s` up at the
    /// centre of buoyancy (its torque with the terms that make it the
    /// derivative of the sampled potential), in pressure mode the pressure
    /// force `Σ −ρ g d_i A_i` and its moment, zero when off. Only the
    /// selected mode's sums are taken: to compare the two, evaluate twice.
    pub buoyancy: Wrench,
    /// Drag as applied: the implicit integral over the step divided by `dt`.
    pub drag: Wrench,
    /// Drag at the current velocity (explicit), for reporting.
    pub drag_explicit: Wrench,
}

impl HydroForces {
    /// Buoyancy plus drag: what to apply to the body.
    pub fn total(&self) -> Wrench {
        self.buoyancy + self.drag
    }
}

/// Buoyancy sums relative to the body's world reference point `o_w`
/// (the atlas origin carried by the pose).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BuoyancySums {
    /// Σ w, w = −A_y d.
    pub vol: f64,
    /// Σ w r, r = p − o_w.
    pub wr: Vector3<f64>,
    /// Σ w d / 2.
    pub wd2: f64,
    /// Σ −d A (the planar kernel sums it, and the next, only in
    /// pressure mode, and `d2a` only in Archimedes mode: see
    /// [`add_planar_ranges`]).
    pub f: Vector3<f64>,
    /// Σ r × (−d A).
    pub rxf: Vector3<f64>,
    /// Σ a over submerged texels.
    pub area: f64,
    /// Submerged texels.
    pub count: usize,
    /// Σ (d²/2) A: with the surface's slope, what makes Archimedes' torque
    /// the derivative of the columns' potential (see [`slope_torque`]).
    pub d2a: Vector3<f64>,
    /// Archimedes' slope term, where the surface is not a plane (see
    /// [`SlopeSums`]).
    pub slope: SlopeSums,
}

impl BuoyancySums {
    /// The sums with their vector parts rotated by `rot` (object → world).
    pub(crate) fn rotated(&self, rot: &Matrix3<f64>) -> Self {
        Self {
            wr: rot * self.wr,
            f: rot * self.f,
            rxf: rot * self.rxf,
            d2a: rot * self.d2a,
            ..*self
        }
    }
}

impl std::ops::Add for BuoyancySums {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            vol: self.vol + o.vol,
            wr: self.wr + o.wr,
            wd2: self.wd2 + o.wd2,
            f: self.f + o.f,
            rxf: self.rxf + o.rxf,
            area: self.area + o.area,
            count: self.count + o.count,
            d2a: self.d2a + o.d2a,
            slope: self.slope + o.slope,
        }
    }
}

impl BuoyancySums {
    #[inline]
    pub(crate) fn add_texel(&mut self, r: &Vector3<f64>, a: &Vector3<f64>, area: f64, d: f64) {
        self.add_local(r, a, a.y, area, d);
    }

    /// Adds a texel in any frame rotated from the world's: `r` and `a` in
    /// that frame, `ay` the world-vertical component of `a`. Rotate the sums
    /// back with [`BuoyancySums::rotated`].
    #[inline]
    pub(crate) fn add_local(&mut self, r: &Vector3<f64>, a: &Vector3<f64>, ay: f64, area: f64, d: f64) {
        let w = -ay * d;
        self.vol += w;
        self.wr += w * r;
        self.wd2 += w * d * 0.5;
        let f = -d * a;
        self.f += f;
        self.rxf += r.cross(&f);
        self.area += area;
        self.count += 1;
        self.d2a += (0.5 * d * d) * a;
    }
}

/// The sums Archimedes' buoyancy takes where the surface over a body is not
/// a plane, over the submerged texels: with [`BuoyancySums::d2a`], what
/// makes its torque the derivative of the water's potential (`wrs`, with
/// `s = (∂h/∂x, 0, ∂h/∂z)` the surface's slope over a texel, `w = −A_y d`,
/// and `ρ` the texel's position relative to the centre of mass; see
/// [`slope_torque`]), and what takes the sampling error out of the force on
/// a body deep under water (`ayr`, `shallow`; see [`deep_volume`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SlopeSums {
    /// Σ w ρ × s.
    pub wrs: Vector3<f64>,
    /// Σ A_y r_y, `r` the texel's position from the atlas origin: once
    /// every texel is under water, the enclosed volume the samples give.
    pub ayr: f64,
    /// Σ ln min(d/δ, 1), `δ` the body's bounding radius: `exp` of it is 1
    /// for a body whose every texel is deeper than `δ` and falls to 0 as
    /// any one of them comes up to the surface.
    pub shallow: f64,
}

impl std::ops::Add for SlopeSums {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            wrs: self.wrs + o.wrs,
            ayr: self.ayr + o.ayr,
            shallow: self.shallow + o.shallow,
        }
    }
}

impl SlopeSums {
    /// Adds a submerged texel (world axes): `rho` from the centre of mass,
    /// `ry` the vertical part of its offset from the atlas origin, `a` its
    /// area vector, `d` its depth, `slope` the surface's over it and
    /// `delta` the depth past which it counts as deep.
    #[inline]
    pub(crate) fn add(
        &mut self,
        rho: &Vector3<f64>,
        ry: f64,
        a: &Vector3<f64>,
        d: f64,
        slope: [f64; 2],
        delta: f64,
    ) {
        let s = Vector3::new(slope[0], 0.0, slope[1]);
        self.wrs += (-a.y * d) * rho.cross(&s);
        self.ayr += a.y * ry;
        if d < delta {
            self.shallow += (d / delta).ln();
        }
    }
}

/// Linear drag system about the centre of mass: wrench = −K q + b.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DragSums {
    pub k: Matrix6<f64>,
    pub b: Vector6<f64>,
}

impl Default for DragSums {
    fn default() -> Self {
        Self {
            k: Matrix6::zeros(),
            b: Vector6::zeros(),
        }
    }
}

impl std::ops::Add for DragSums {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            k: self.k + o.k,
            b: self.b + o.b,
        }
    }
}

#[inline]
fn skew(r: &Vector3<f64>) -> Matrix3<f64> {
    r.cross_matrix()
}

impl DragSums {
    /// Adds a submerged texel at `rc` from the centre of mass with world area
    /// vector `a`, relative velocity `vrel` and fluid velocity `u`.
    #[inline]
    pub(crate) fn add_texel(
        &mut self,
        drag: &Drag,
        rho: f64,
        rc: &Vector3<f64>,
        a: &Vector3<f64>,
        vrel: &Vector3<f64>,
        u: &Vector3<f64>,
    ) {
        let facing = a.dot(vrel);
        let kq = if facing > 0.0 {
            0.5 * rho * drag.coefficient * facing
        } else {
            0.0
        };
        let area = a.norm();
        let mut ki = Matrix3::identity() * kq;
        if drag.linear > 0.0 && area > 0.0 {
            let n = a / area;
            ki += (Matrix3::identity() - n * n.transpose()) * (drag.linear * area);
        }
        if kq == 0.0 && drag.linear <= 0.0 {
            return;
        }
        // Texel velocity = J q with J = [I, −[r]×]; K += Jᵀ K_i J, b += Jᵀ K_i u.
        let s = skew(rc);
        let kvv = ki;
        let kvw = -ki * s;
        let kwv = s * ki;
        let kww = -s * ki * s;
        {
            let mut v = self.k.fixed_view_mut::<3, 3>(0, 0);
            v += kvv;
        }
        {
            let mut v = self.k.fixed_view_mut::<3, 3>(0, 3);
            v += kvw;
        }
        {
            let mut v = self.k.fixed_view_mut::<3, 3>(3, 0);
            v += kwv;
        }
        {
            let mut v = self.k.fixed_view_mut::<3, 3>(3, 3);
            v += kww;
        }
        let f = ki * u;
        {
            let mut v = self.b.fixed_rows_mut::<3>(0);
            v += f;
        }
        {
            let mut v = self.b.fixed_rows_mut::<3>(3);
            v += rc.cross(&f);
        }
    }
}

/// Buoyancy and drag sums of one pass.
#[derive(Clone, Copy, Default)]
struct Both {
    b: BuoyancySums,
    d: DragSums,
}

impl std::ops::Add for Both {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            b: self.b + o.b,
            d: self.d + o.d,
        }
    }
}

/// Per-evaluation constants shared by the CPU paths.
pub(crate) struct Frame {
    /// For planar water, depth `d(x) = α + β·x` in object coordinates
    /// relative to the atlas origin, and the world up axis in object axes.
    pub local_plane: Option<(f64, Vector3<f64>, Vector3<f64>)>,
    pub rot: Matrix3<f64>,
    /// World position of the atlas origin.
    pub ow: Vector3<f64>,
    /// World centre of mass.
    pub com: Vector3<f64>,
    pub plane: Option<(Vector3<f64>, f64)>,
    pub texels: usize,
    /// Depth past which a texel counts as deep (the bounding radius), m:
    /// see [`deep_volume`].
    pub depth_scale: f64,
}

impl Frame {
    pub(crate) fn new(
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
    ) -> Self {
        let rot = state.pose.rotation.to_rotation_matrix().into_inner();
        let ow = (state.pose * atlas.origin()).coords;
        let com = (state.pose * mass.center_of_mass).coords;
        let plane = Self::surface_plane(water, t, &ow, atlas.bounding_radius());
        let local_plane = plane.map(|(n, c)| {
            let alpha = (c - n.dot(&ow)) / n.y;
            let beta = -(rot.transpose() * n) / n.y;
            (alpha, beta, rot.transpose() * Vector3::y())
        });
        Self {
            local_plane,
            rot,
            ow,
            com,
            plane,
            texels: atlas.len(),
            depth_scale: atlas.bounding_radius(),
        }
    }

    /// The water's surface as a plane `(normal, offset)` at time `t`, if it
    /// is one, for a body whose atlas origin is at `ow` within `radius`.
    pub(crate) fn surface_plane(
        water: &Water,
        t: f64,
        ow: &Vector3<f64>,
        radius: f64,
    ) -> Option<(Vector3<f64>, f64)> {
        match water.surface.kind(t) {
            SurfaceKind::Plane { normal, offset } => Some((normal, offset)),
            // No free surface: a horizontal plane above the whole body gives
            // the same sums (Σ A = 0 for a closed surface) with finite depths.
            SurfaceKind::Unbounded => Some((Vector3::y(), ow.y + radius + 1.0)),
            SurfaceKind::General => None,
        }
    }

    #[inline]
    pub(crate) fn depth(&self, water: &Water, p: &Vector3<f64>, t: f64) -> f64 {
        match self.plane {
            Some((n, c)) => (c - n.dot(p)) / n.y,
            None => water.surface.depth(&Point3::from(*p), t),
        }
    }
}

#[inline]
pub(crate) fn texel(atlas: &Atlas, i: usize) -> (Vector3<f64>, Vector3<f64>) {
    let x = atlas.local_positions().get(i);
    let a = atlas.area_vectors().get(i);
    (
        Vector3::new(x[0] as f64, x[1] as f64, x[2] as f64),
        Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64),
    )
}

/// Adds the submerged texels of `ranges` under planar water, `d(x) = α + β·x`
/// in object coordinates relative to the atlas origin, `g` the world's up in
/// object axes (object-frame sums).
///
/// Texels are taken [`LANES`] at a time: their coordinates widened to f64
/// and laid side by side (the last texels of a range in a group of their
/// own, its empty lanes masked), a group with no submerged texel costs one test,
/// and the others add to sums of [`LANES`] lanes each, a dry lane adding
/// zeros (its depth clamped to zero). Archimedes' buoyancy needs eight
/// (`Σ w`, `Σ w r`, `Σ d² a`, `Σ area`); the pressure force and its torque
/// eleven (`Σ d a`, `Σ r × d a`, and for the centre of buoyancy `Σ w r`,
/// `Σ w d`, `Σ area`, `Σ w` being `g · Σ d a`). `pressure` chooses; the
/// sums of [`BuoyancySums`] the other mode needs are left alone
/// ([`BuoyancySums::f`] and [`BuoyancySums::rxf`] in Archimedes mode,
/// [`BuoyancySums::d2a`] in pressure mode). Where the processor has AVX2
/// and FMA (chosen at run time) a group is a few vector instructions
/// written with intrinsics; elsewhere the same operations in portable code
/// without fused multiply-adds (the two differ in the last bits, 1e-16
/// relative). The lanes
/// are summed in a fixed order at the end, and the signs and the ½ of
/// [`BuoyancySums`] applied once, so on one machine the result is the same
/// bits run after run and for any thread count.
///
/// With [`PlanarTexels::Dry`] the kernel takes the other texels, those at
/// or above the surface (`d ≤ 0`), with their depths as they are, and
/// subtracts their sums: where the closed form of a tile's moments has
/// added the affine depth's sums over all its texels, this leaves the
/// submerged texels' sums, for the work of the dry ones.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn add_planar_ranges(
    s: &mut BuoyancySums,
    atlas: &Atlas,
    ranges: &[std::ops::Range<usize>],
    alpha: f64,
    beta: &Vector3<f64>,
    g: &Vector3<f64>,
    pressure: bool,
    texels_summed: PlanarTexels,
) {
    let n = atlas.len();
    let texels = TexelColumns {
        xs: atlas.local_positions().columns(0..n),
        avs: atlas.area_vectors().columns(0..n),
        areas: atlas.areas(),
    };
    let plane = PlaneLanes {
        alpha,
        beta: [beta.x, beta.y, beta.z],
        g: [g.x, g.y, g.z],
    };
    let dry = texels_summed == PlanarTexels::Dry;
    let lanes = planar_lanes(&plane, &texels, ranges, pressure, dry);
    // Σ ay d r and Σ area; Archimedes: Σ ay d and Σ d² a (Σ ay d² = g · Σ d² a);
    // pressure: Σ d a, Σ r × (d a) (Σ ay d = g · Σ d a) and Σ ay d².
    // The dry texels' sums are subtracted: every sign turns.
    let sign = if dry { -1.0 } else { 1.0 };
    let sum = |v: &Lanes| sign * ((v[0] + v[1]) + (v[2] + v[3]));
    s.wr -= Vector3::new(sum(&lanes.wr[0]), sum(&lanes.wr[1]), sum(&lanes.wr[2]));
    if pressure {
        let f = Vector3::new(sum(&lanes.f[0]), sum(&lanes.f[1]), sum(&lanes.f[2]));
        s.vol -= g.dot(&f);
        s.f -= f;
        s.rxf -= Vector3::new(sum(&lanes.rxf[0]), sum(&lanes.rxf[1]), sum(&lanes.rxf[2]));
        s.wd2 -= 0.5 * sum(&lanes.wd);
    } else {
        s.vol -= sum(&lanes.vol);
        let dda = Vector3::new(sum(&lanes.d2a[0]), sum(&lanes.d2a[1]), sum(&lanes.d2a[2]));
        s.wd2 -= 0.5 * g.dot(&dda);
        s.d2a += 0.5 * dda;
    }
    s.area += sum(&lanes.area);
    if dry {
        s.count -= lanes.count;
    } else {
        s.count += lanes.count;
    }
}

/// Which texels [`add_planar_ranges`] sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PlanarTexels {
    /// The submerged texels (`d > 0`), added.
    Wet,
    /// The others (`d ≤ 0`), subtracted: for ranges whose closed form has
    /// been added already, and which are mostly under water.
    Dry,
}

/// Texels the planar kernel takes side by side.
const LANES: usize = 4;

/// Lanes of f64, one per texel of a group.
type Lanes = [f64; LANES];

/// `a b + c` lane by lane, fused where the processor has FMA.
#[inline(always)]
fn lanes_madd<const FMA: bool>(a: &Lanes, b: &Lanes, c: &Lanes) -> Lanes {
    std::array::from_fn(|k| madd::<FMA>(a[k], b[k], c[k]))
}

/// `c − a b` lane by lane, fused where the processor has FMA.
#[inline(always)]
fn lanes_nmadd<const FMA: bool>(a: &Lanes, b: &Lanes, c: &Lanes) -> Lanes {
    std::array::from_fn(|k| madd::<FMA>(-a[k], b[k], c[k]))
}

/// `a b` lane by lane.
#[inline(always)]
fn lanes_mul(a: &Lanes, b: &Lanes) -> Lanes {
    std::array::from_fn(|k| a[k] * b[k])
}

/// `a + b` lane by lane.
#[inline(always)]
fn lanes_add(a: &Lanes, b: &Lanes) -> Lanes {
    std::array::from_fn(|k| a[k] + b[k])
}

/// The arrays of an atlas the planar kernel reads, each of the same length.
struct TexelColumns<'a> {
    xs: [&'a [f32]; 3],
    avs: [&'a [f32]; 3],
    areas: &'a [f32],
}

/// The planar water of [`add_planar_ranges`] as plain arrays.
struct PlaneLanes {
    alpha: f64,
    beta: [f64; 3],
    g: [f64; 3],
}

impl PlaneLanes {
    /// The depths `α + β·r` of a group's lanes.
    #[inline(always)]
    fn depths<const FMA: bool>(&self, r: &[Lanes; 3]) -> Lanes {
        let b = self.beta.map(|b| [b; LANES]);
        let d = lanes_madd::<FMA>(&b[0], &r[0], &[self.alpha; LANES]);
        let d = lanes_madd::<FMA>(&b[1], &r[1], &d);
        lanes_madd::<FMA>(&b[2], &r[2], &d)
    }
}

/// The planar kernel's sums, one per lane (see [`add_planar_ranges`]).
#[derive(Default)]
struct PlanarLanes {
    vol: Lanes,
    wd: Lanes,
    wr: [Lanes; 3],
    f: [Lanes; 3],
    rxf: [Lanes; 3],
    d2a: [Lanes; 3],
    area: Lanes,
    count: usize,
}

/// The planar kernel over `ranges`: the sums of the wet texels (`d > 0`),
/// or where `dry` of the others (`d ≤ 0`, their depths as they are).
fn planar_lanes(
    p: &PlaneLanes,
    t: &TexelColumns,
    ranges: &[std::ops::Range<usize>],
    pressure: bool,
    dry: bool,
) -> PlanarLanes {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
            // SAFETY: the processor has AVX2 and FMA, checked just above.
            #[allow(unsafe_code)]
            return unsafe {
                match (pressure, dry) {
                    (true, false) => planar_lanes_avx2::<true, false>(p, t, ranges),
                    (false, false) => planar_lanes_avx2::<false, false>(p, t, ranges),
                    (true, true) => planar_lanes_avx2::<true, true>(p, t, ranges),
                    (false, true) => planar_lanes_avx2::<false, true>(p, t, ranges),
                }
            };
        }
    }
    let mut acc = PlanarLanes::default();
    for r in ranges {
        let r = r.clone();
        match (pressure, dry) {
            (true, false) => planar_lanes_generic::<false, true, false>(&mut acc, p, t, r),
            (false, false) => planar_lanes_generic::<false, false, false>(&mut acc, p, t, r),
            (true, true) => planar_lanes_generic::<false, true, true>(&mut acc, p, t, r),
            (false, true) => planar_lanes_generic::<false, false, true>(&mut acc, p, t, r),
        }
    }
    acc
}

/// Lanes `i .. i + LANES` of one coordinate array, widened: one load of
/// consecutive floats (the atlas stores each coordinate in an array of its
/// own) and one conversion.
#[inline(always)]
fn load_lanes(v: &[f32], i: usize) -> Lanes {
    let v: &[f32; LANES] = v[i..i + LANES].try_into().expect("a slice of LANES floats");
    v.map(f64::from)
}

/// [`planar_lanes_generic`] with fused multiply-adds over several ranges,
/// written with AVX2 intrinsics: the same operations in the same order on
/// the same lanes (where the compiler left to itself vectorises the
/// generic code only in part). The last `len % LANES` texels of a range
/// make a group of their own, padded with zeros and its empty lanes
/// masked off like dry ones.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn planar_lanes_avx2<const PRESSURE: bool, const DRY: bool>(
    p: &PlaneLanes,
    t: &TexelColumns,
    ranges: &[std::ops::Range<usize>],
) -> PlanarLanes {
    use std::arch::x86_64::*;

    /// Lanes `i .. i + LANES` of `v`, widened.
    #[target_feature(enable = "avx2,fma")]
    fn load(v: &[f32], i: usize) -> __m256d {
        let v = &v[i..i + LANES];
        // SAFETY: `v` holds the four floats an unaligned 128-bit load reads.
        #[allow(unsafe_code)]
        _mm256_cvtps_pd(unsafe { _mm_loadu_ps(v.as_ptr()) })
    }
    /// The lanes of `v` as an array.
    #[target_feature(enable = "avx2,fma")]
    fn lanes(v: __m256d) -> Lanes {
        let mut out = [0.0; LANES];
        // SAFETY: `out` holds the four f64 an unaligned 256-bit store writes.
        #[allow(unsafe_code)]
        unsafe {
            _mm256_storeu_pd(out.as_mut_ptr(), v)
        };
        out
    }

    let zero = _mm256_setzero_pd();
    let one = _mm256_set1_pd(1.0);
    let alpha = _mm256_set1_pd(p.alpha);
    let b = p.beta.map(|b| _mm256_set1_pd(b));
    let g = p.g.map(|g| _mm256_set1_pd(g));
    let (mut vol, mut wd, mut area_sum, mut count) = (zero, zero, zero, zero);
    let (mut wr, mut f, mut rxf, mut d2a) = ([zero; 3], [zero; 3], [zero; 3], [zero; 3]);
    // One group from where `at` finds it (`xs`, `avs`, `areas`), `valid`
    // masking the lanes that hold texels.
    let mut group = |xs: [&[f32]; 3], avs: [&[f32]; 3], areas: &[f32], at: usize, valid: __m256d| {
        let r = [load(xs[0], at), load(xs[1], at), load(xs[2], at)];
        let d = _mm256_fmadd_pd(b[0], r[0], alpha);
        let d = _mm256_fmadd_pd(b[1], r[1], d);
        let d = _mm256_fmadd_pd(b[2], r[2], d);
        let side = if DRY {
            _mm256_cmp_pd::<_CMP_LE_OQ>(d, zero)
        } else {
            _mm256_cmp_pd::<_CMP_GT_OQ>(d, zero)
        };
        let taken = _mm256_and_pd(side, valid);
        if _mm256_movemask_pd(taken) == 0 {
            return;
        }
        // A lane not taken adds zeros: its depth and area masked to +0.
        let d = _mm256_and_pd(d, taken);
        let area = _mm256_and_pd(load(areas, at), taken);
        count = _mm256_add_pd(count, _mm256_and_pd(one, taken));
        let da = [
            _mm256_mul_pd(d, load(avs[0], at)),
            _mm256_mul_pd(d, load(avs[1], at)),
            _mm256_mul_pd(d, load(avs[2], at)),
        ];
        let w = _mm256_fmadd_pd(
            g[2],
            da[2],
            _mm256_fmadd_pd(g[1], da[1], _mm256_mul_pd(g[0], da[0])),
        );
        for c in 0..3 {
            wr[c] = _mm256_fmadd_pd(w, r[c], wr[c]);
        }
        if PRESSURE {
            for c in 0..3 {
                f[c] = _mm256_add_pd(f[c], da[c]);
            }
            rxf[0] = _mm256_fmadd_pd(r[1], da[2], _mm256_fnmadd_pd(r[2], da[1], rxf[0]));
            rxf[1] = _mm256_fmadd_pd(r[2], da[0], _mm256_fnmadd_pd(r[0], da[2], rxf[1]));
            rxf[2] = _mm256_fmadd_pd(r[0], da[1], _mm256_fnmadd_pd(r[1], da[0], rxf[2]));
            wd = _mm256_fmadd_pd(w, d, wd);
        } else {
            vol = _mm256_add_pd(vol, w);
            for c in 0..3 {
                d2a[c] = _mm256_fmadd_pd(d, da[c], d2a[c]);
            }
        }
        area_sum = _mm256_add_pd(area_sum, area);
    };
    let all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for range in ranges {
        let (start, end) = (range.start, range.end);
        let whole = end - (end - start) % LANES;
        for i in (start..whole).step_by(LANES) {
            group(t.xs, t.avs, t.areas, i, all);
        }
        if whole < end {
            let k = end - whole;
            let pad = |v: &[f32]| {
                let mut padded = [0.0f32; LANES];
                padded[..k].copy_from_slice(&v[whole..end]);
                padded
            };
            let (xs, avs, areas) = (t.xs.map(pad), t.avs.map(pad), pad(t.areas));
            let valid = _mm256_castsi256_pd(_mm256_setr_epi64x(
                -1,
                if k > 1 { -1 } else { 0 },
                if k > 2 { -1 } else { 0 },
                0,
            ));
            group(
                xs.each_ref().map(|v| &v[..]),
                avs.each_ref().map(|v| &v[..]),
                &areas,
                0,
                valid,
            );
        }
    }
    PlanarLanes {
        vol: lanes(vol),
        wd: lanes(wd),
        wr: wr.map(|v| lanes(v)),
        f: f.map(|v| lanes(v)),
        rxf: rxf.map(|v| lanes(v)),
        d2a: d2a.map(|v| lanes(v)),
        area: lanes(area_sum),
        count: lanes(count).iter().sum::<f64>() as usize,
    }
}

/// Adds the texels of `range` to `acc`, [`LANES`] at a time, the last
/// `len % LANES` each in a lane of its own.
#[inline(always)]
fn planar_lanes_generic<const FMA: bool, const PRESSURE: bool, const DRY: bool>(
    acc: &mut PlanarLanes,
    p: &PlaneLanes,
    t: &TexelColumns,
    range: std::ops::Range<usize>,
) {
    // Wet texels counted per lane in f64 (exact up to 2⁵³), a vector like
    // the sums.
    let mut count: Lanes = [0.0; LANES];
    let (start, end) = (range.start, range.end);
    let whole = end - (end - start) % LANES;
    for i in (start..whole).step_by(LANES) {
        let r = t.xs.map(|v| load_lanes(v, i));
        let d = p.depths::<FMA>(&r);
        let taken: [bool; LANES] = d.map(taken::<DRY>);
        if taken.iter().fold(false, |any, &w| any | w) {
            let a = t.avs.map(|v| load_lanes(v, i));
            let area = load_lanes(t.areas, i);
            count = lanes_add(&count, &taken.map(|w| if w { 1.0 } else { 0.0 }));
            add_lanes::<FMA, PRESSURE>(acc, p, &r, &a, &area, &d, &taken);
        }
    }
    for (k, i) in (whole..end).enumerate() {
        let mut r = [[0.0; LANES]; 3];
        let mut av = [[0.0; LANES]; 3];
        for c in 0..3 {
            r[c][k] = f64::from(t.xs[c][i]);
            av[c][k] = f64::from(t.avs[c][i]);
        }
        let d = p.depths::<FMA>(&r);
        let mut taken = [false; LANES];
        taken[k] = self::taken::<DRY>(d[k]);
        let mut ar = [0.0; LANES];
        ar[k] = f64::from(t.areas[i]);
        count[k] += if taken[k] { 1.0 } else { 0.0 };
        add_lanes::<FMA, PRESSURE>(acc, p, &r, &av, &ar, &d, &taken);
    }
    acc.count += count.iter().sum::<f64>() as usize;
}

/// Whether the planar kernel takes a texel at depth `d`: a wet one
/// (`d > 0`), or where `DRY` one at or above the surface.
#[inline(always)]
fn taken<const DRY: bool>(d: f64) -> bool {
    if DRY { d <= 0.0 } else { d > 0.0 }
}

/// `a b + c`, fused where the processor has FMA.
#[inline(always)]
fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA { a.mul_add(b, c) } else { a * b + c }
}

/// One group of texels; a lane not taken adds zeros. Eight running sums in
/// Archimedes mode, eleven where `PRESSURE` (see [`add_planar_ranges`]):
/// fewer than the processor's vector registers. Written as operations on
/// whole groups of lanes, each of which the compiler turns into one vector
/// instruction.
#[inline(always)]
fn add_lanes<const FMA: bool, const PRESSURE: bool>(
    acc: &mut PlanarLanes,
    p: &PlaneLanes,
    r: &[Lanes; 3],
    a: &[Lanes; 3],
    area: &Lanes,
    d: &Lanes,
    taken: &[bool; LANES],
) {
    let d: Lanes = std::array::from_fn(|k| if taken[k] { d[k] } else { 0.0 });
    let area: Lanes = std::array::from_fn(|k| if taken[k] { area[k] } else { 0.0 });
    let da = [lanes_mul(&d, &a[0]), lanes_mul(&d, &a[1]), lanes_mul(&d, &a[2])];
    let g = p.g.map(|g| [g; LANES]);
    let w = lanes_madd::<FMA>(
        &g[2],
        &da[2],
        &lanes_madd::<FMA>(&g[1], &da[1], &lanes_mul(&g[0], &da[0])),
    );
    acc.wr = std::array::from_fn(|c| lanes_madd::<FMA>(&w, &r[c], &acc.wr[c]));
    if PRESSURE {
        acc.f = std::array::from_fn(|c| lanes_add(&acc.f[c], &da[c]));
        let rxf = &mut acc.rxf;
        rxf[0] = lanes_madd::<FMA>(&r[1], &da[2], &lanes_nmadd::<FMA>(&r[2], &da[1], &rxf[0]));
        rxf[1] = lanes_madd::<FMA>(&r[2], &da[0], &lanes_nmadd::<FMA>(&r[0], &da[2], &rxf[1]));
        rxf[2] = lanes_madd::<FMA>(&r[0], &da[1], &lanes_nmadd::<FMA>(&r[1], &da[0], &rxf[2]));
        acc.wd = lanes_madd::<FMA>(&w, &d, &acc.wd);
    } else {
        acc.vol = lanes_add(&acc.vol, &w);
        acc.d2a = std::array::from_fn(|c| lanes_madd::<FMA>(&d, &da[c], &acc.d2a[c]));
    }
    acc.area = lanes_add(&acc.area, &area);
}

/// Reads every position, area vector and area of the atlas once and folds
/// their bits into a checksum, in the same chunks as [`evaluate`]: the
/// bytes a per-texel pass reads and nothing else, as fast as the memory
/// gives them, and so the floor under any such pass. Benchmarks compare
/// [`evaluate`]'s time against it.
///
/// The chunks go to rayon's pool alone, the calling thread waiting: of the
/// ways tried this reads fastest (handed out one by one to the calling
/// thread and a helper, as the passes' chunks are, the read took 1.4–1.6
/// times as long at 1024²), so the floor is the lowest one.
pub fn streaming_read(atlas: &Atlas) -> f64 {
    use rayon::prelude::*;
    let n = atlas.len();
    let chunk = |range: std::ops::Range<usize>| {
        let [x, y, z] = atlas.local_positions().columns(range.clone());
        let [ax, ay, az] = atlas.area_vectors().columns(range.clone());
        let areas = &atlas.areas()[range];
        // Wrapping integer sums of the bits, one array after the other: no
        // chain of dependent float additions, so the compiler reads with
        // SIMD and the time is the memory's, not an adder's latency.
        let bits = |v: &[f32]| v.iter().fold(0u32, |s, x| s.wrapping_add(x.to_bits()));
        let s = bits(x) ^ bits(y) ^ bits(z) ^ bits(ax) ^ bits(ay) ^ bits(az) ^ bits(areas);
        f64::from(s)
    };
    (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| chunk(c * CHUNK..((c + 1) * CHUNK).min(n)))
        .sum()
}

/// Buoyancy and drag on a body, summing over every texel (rayon, f64,
/// deterministic for any thread count).
///
/// `mass` are the body's mass properties (object frame): the centre of mass
/// is where torques are taken, and mass and inertia make the implicit drag.
///
/// # Example
/// ```
/// use nalgebra::{Isometry3, Vector3};
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_hydro::prelude::*;
///
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(128))?;
/// let mass = MassModel::Solid { density: 500.0 }.mass_properties(&atlas)?;
/// // Box centred 0.2 m below the surface at y = 0: 0.7 m³ submerged.
/// let state = BodyState::at_rest(Isometry3::translation(0.0, -0.2, 0.0));
/// let f = evaluate(&atlas, &Water::calm(0.0), &state, &mass, 0.0, &HydroOptions::default())?;
/// assert!((f.submerged_volume - 0.7).abs() < 1e-6);
/// assert!((f.buoyancy.force.y - 1000.0 * 9.80665 * 0.7).abs() < 1e-2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn evaluate(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    mass: &MassProperties,
    t: f64,
    options: &HydroOptions,
) -> Result<HydroForces, HydroError> {
    water.validate()?;
    state.check()?;
    let frame = Frame::new(atlas, water, state, mass, t);
    let pressure = options.buoyancy == BuoyancyMode::Pressure;
    let sums = match frame.local_plane {
        // Planar water: depth is affine in object coordinates, so sum there
        // and rotate once.
        Some((alpha, beta, g)) => chunked_sum(atlas.len(), BuoyancySums::default(), |range| {
            let mut s = BuoyancySums::default();
            add_planar_ranges(
                &mut s,
                atlas,
                &[range],
                alpha,
                &beta,
                &g,
                pressure,
                PlanarTexels::Wet,
            );
            s
        })
        .rotated(&frame.rot),
        None => {
            // Any surface: one probe per texel gives the depth and, for drag,
            // the fluid velocity; neighbouring texels warm-start each other.
            let both = chunked_sum(atlas.len(), Both::default(), |range| {
                let mut s = Both::default();
                let mut hint = [0.0; 2];
                for i in range {
                    let (x, a) = texel(atlas, i);
                    let r = frame.rot * x;
                    let p = frame.ow + r;
                    let (d, u) = water
                        .surface
                        .probe(&Point3::from(p), t, options.drag.is_some(), &mut hint);
                    if d > 0.0 {
                        let aw = frame.rot * a;
                        s.b.add_texel(&r, &aw, atlas.areas()[i] as f64, d);
                        if options.buoyancy == BuoyancyMode::Archimedes {
                            let slope = water.surface.slope(p.x, p.z, t, &hint);
                            s.b.slope
                                .add(&(p - frame.com), r.y, &aw, d, slope, frame.depth_scale);
                        }
                        if let Some(drag) = &options.drag {
                            let rc = p - frame.com;
                            let v = state.linear_velocity + state.angular_velocity.cross(&rc) - u;
                            s.d.add_texel(drag, water.density, &rc, &aw, &v, &u);
                        }
                    }
                }
                s
            });
            let drag = options.drag.map(|_| both.d);
            return Ok(finish(
                &frame,
                water,
                state,
                mass,
                &both.b,
                drag.as_ref(),
                options,
            ));
        }
    };
    let drag = options
        .drag
        .map(|drag| drag_sums(atlas, water, state, &frame, &drag, t, 0..atlas.len()));
    Ok(finish(&frame, water, state, mass, &sums, drag.as_ref(), options))
}

/// Drag sums over the submerged texels of `range`.
pub(crate) fn drag_sums(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    frame: &Frame,
    drag: &Drag,
    t: f64,
    range: std::ops::Range<usize>,
) -> DragSums {
    let start = range.start;
    chunked_sum(range.len(), DragSums::default(), |r| {
        let mut s = DragSums::default();
        for i in r.start + start..r.end + start {
            let (x, a) = texel(atlas, i);
            let rr = frame.rot * x;
            let p = frame.ow + rr;
            let d = frame.depth(water, &p, t);
            if d > 0.0 {
                let rc = p - frame.com;
                let u = water.surface.velocity(&Point3::from(p), t);
                let v = state.linear_velocity + state.angular_velocity.cross(&rc) - u;
                s.add_texel(drag, water.density, &rc, &(frame.rot * a), &v, &u);
            }
        }
        s
    })
}

/// What Archimedes' torque needs, over `ρ_w g`, beyond `ρ_w g V_s` at the
/// centre of buoyancy, to be the derivative of the water's potential as the
/// texels sample it.
///
/// Under a static surface `h(x, z)` the water's potential is the columns'
/// `U = ρ_w g Σ (−A_y) d²/2`. Archimedes' vertical force is `−∂U/∂y`; the
/// torque that makes the pair conserve energy is `−∂U/∂θ` about the centre
/// of mass, `ρ_w g Σ [(d²/2) A × ŷ + A_y d ρ × (s − ŷ)]`: the force at the
/// centre of buoyancy plus `ρ_w g (Σ (d²/2) A × ŷ − Σ w ρ × s)`. Without
/// the second term a floating body pitching over a slope takes in energy
/// every swing. Under flat water `s = 0`, and `Σ (d²/2) A` of the exact
/// surface is vertical (the divergence theorem: `−ŷ ∫ d dV`), so the term
/// vanishes in the limit; but a body's samples can leave it a torque the
/// potential does not have (a sliver triangle's few samples sit off its
/// middle line), and one about an axis of small inertia spins the body.
/// Summed from the same samples, the torque is the derivative of their
/// potential whatever their placement. A body wholly under water keeps
/// the classic torque of `ρ_w g V` at its centre of buoyancy: real pressure
/// forgets the surface's shape with depth, and the columns' terms would be
/// differences of numbers that grow with the depth squared. A tilted
/// plane's slope is the same everywhere: `Σ w ρ × s = (Σ w ρ) × s`.
fn slope_torque(frame: &Frame, s: &BuoyancySums) -> Vector3<f64> {
    if s.count >= frame.texels {
        return Vector3::zeros();
    }
    let columns = s.d2a.cross(&Vector3::y());
    match frame.plane {
        Some((n, _)) if n.x == 0.0 && n.z == 0.0 => columns,
        Some((n, _)) => {
            let slope = Vector3::new(-n.x / n.y, 0.0, -n.z / n.y);
            let wrho = s.wr - s.vol * (frame.com - frame.ow);
            columns - wrho.cross(&slope)
        }
        None => columns - s.slope.wrs,
    }
}

/// The submerged volume Archimedes' force takes, m³: `Σ −A_y d`, but for a
/// body wholly under a surface that is not a plane, where that sum carries
/// the sampling error of a zero integral, it tends to the enclosed volume
/// as the body goes deeper.
///
/// Wholly under water, `Σ −A_y d = Σ −A_y (h − Y) + Σ A_y (y − Y)` with `h`
/// the surface's height over each texel and `Y` the atlas origin's: the
/// second sum is the volume the samples enclose (`Σ A_y r_y`, exact for
/// samples whose first moments are their triangles'), the first samples
/// `−∮ (h − Y) n_y dA`, which is zero for any closed surface since `h`
/// does not depend on `y`. Under a plane the samples integrate the affine
/// `h` exactly; under waves or a height field whose features are no
/// larger than the spacing of the samples (a 200:1 rod's few samples
/// straddling a step) it is not zero, and a sinking or neutral body feels
/// it as a force the water's potential does not have, all the way down.
/// The volume taken is `Σ −A_y d − φ E`, `E` that error, with
/// `φ = Π min(d_i/δ, 1)` over the texels (`δ` the bounding radius): 0
/// while any texel is dry and continuous as the last one goes under,
/// 1 once every texel is deeper than `δ`. The force then differs from the
/// derivative of the columns' potential only within `δ` of the surface, by
/// at most `ρ_w g |E|`, so a body that sinks far gains at most
/// `ρ_w g |E| δ` from it.
///
/// Returns the volume and `φ` ([`HydroForces::deep`]).
fn deep_volume(frame: &Frame, s: &BuoyancySums, archimedes: bool) -> (f64, f64) {
    if frame.texels == 0 || s.count < frame.texels {
        return (s.vol, 0.0);
    }
    if frame.plane.is_some() || !archimedes {
        return (s.vol, 1.0);
    }
    let phi = s.slope.shallow.exp();
    let error = s.vol - s.slope.ayr;
    if !(phi > 0.0 && error.is_finite()) {
        // At the surface (φ = 0, or a sum that is not a number): the sum
        // as it is.
        return (s.vol, 0.0);
    }
    let phi = phi.min(1.0);
    (s.vol - phi * error, phi)
}

/// Turns the sums into forces.
pub(crate) fn finish(
    frame: &Frame,
    water: &Water,
    state: &BodyState,
    mass: &MassProperties,
    s: &BuoyancySums,
    drag: Option<&DragSums>,
    options: &HydroOptions,
) -> HydroForces {
    let rg = water.density * water.gravity;
    let com = frame.com;
    let ow = frame.ow;
    let (volume, deep) = deep_volume(frame, s, options.buoyancy == BuoyancyMode::Archimedes);
    let volume = volume.max(0.0);
    let cb = if s.vol > 0.0 {
        ow + (s.wr + Vector3::y() * s.wd2) / s.vol
    } else {
        com
    };
    let buoyancy = match options.buoyancy {
        BuoyancyMode::Archimedes => {
            let force = Vector3::new(0.0, rg * volume, 0.0);
            let slope_torque = rg * slope_torque(frame, s);
            Wrench {
                force,
                torque: (cb - com).cross(&force) + slope_torque,
            }
        }
        BuoyancyMode::Pressure => {
            let force = rg * s.f;
            // Σ (p − c) × F = Σ r × F − (c − o_w) × Σ F
            Wrench {
                force,
                torque: rg * s.rxf - (com - ow).cross(&force),
            }
        }
        BuoyancyMode::Off => Wrench::default(),
    };
    let (drag, drag_explicit) = match drag {
        Some(d) => implicit_drag(d, state, mass, options.dt),
        None => (Wrench::default(), Wrench::default()),
    };
    HydroForces {
        submerged_volume: volume,
        center_of_buoyancy: Point3::from(cb),
        wetted_area: s.area,
        submerged_texels: s.count,
        potential: rg * s.wd2,
        deep,
        buoyancy,
        drag,
        drag_explicit,
    }
}

/// `(applied, explicit)`: the applied drag is `M (q' − q)/dt` with
/// `q' = (M + dt K)⁻¹ (M q + dt b)`, which decays the relative velocity
/// without ever reversing it, for any `dt`.
fn implicit_drag(d: &DragSums, state: &BodyState, mass: &MassProperties, dt: f64) -> (Wrench, Wrench) {
    let q = Vector6::new(
        state.linear_velocity.x,
        state.linear_velocity.y,
        state.linear_velocity.z,
        state.angular_velocity.x,
        state.angular_velocity.y,
        state.angular_velocity.z,
    );
    let explicit = d.b - d.k * q;
    let wrench = |v: &Vector6<f64>| Wrench {
        force: Vector3::new(v[0], v[1], v[2]),
        torque: Vector3::new(v[3], v[4], v[5]),
    };
    if dt.is_nan() || dt <= 0.0 || mass.mass <= 0.0 {
        return (wrench(&explicit), wrench(&explicit));
    }
    let rot = state.pose.rotation.to_rotation_matrix().into_inner();
    let inertia = rot * mass.inertia * rot.transpose();
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(Matrix3::identity() * mass.mass));
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&inertia);
    // A massless rotational axis (point mass) gets no rotational drag.
    let sys = m + d.k * dt;
    let rhs = m * q + d.b * dt;
    let q_new = sys
        .cholesky()
        .map(|c| c.solve(&rhs))
        .or_else(|| sys.lu().solve(&rhs))
        .unwrap_or(q);
    let applied = m * (q_new - q) / dt;
    (wrench(&applied), wrench(&explicit))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;
    use soak_bake::{BakeOptions, builtin};

    /// The planar kernel, with and without fused multiply-adds, with and
    /// without the pressure sums, over the wet texels and over the dry ones,
    /// against the plain per-texel sums of the general path
    /// ([`BuoyancySums::add_local`]) at poses cutting the boat at the
    /// waterline, over ranges of every length modulo the lanes.
    #[test]
    fn the_planar_kernel_adds_what_the_plain_sums_add() {
        let atlas = Atlas::bake(&builtin::boat(4.0, 1.2, 0.6), BakeOptions::square(128)).unwrap();
        let n = atlas.len() - 3;
        assert_ne!(n % LANES, 0);
        for (k, y) in [-0.05, 0.0, 0.1, 0.3].into_iter().enumerate() {
            let rot = UnitQuaternion::from_euler_angles(0.3 * k as f64, 0.2, -0.1)
                .to_rotation_matrix()
                .into_inner();
            let g = rot.transpose() * Vector3::y();
            let (alpha, beta) = (y, -g);
            // The wet texels' sums, and the dry ones' with their depths as
            // they are (not clamped).
            let (mut wet, mut dry) = (BuoyancySums::default(), BuoyancySums::default());
            for i in 0..n {
                let (r, a) = texel(&atlas, i);
                let d = alpha + beta.dot(&r);
                let side = if d > 0.0 { &mut wet } else { &mut dry };
                side.add_local(&r, &a, a.dot(&g), f64::from(atlas.areas()[i]), d);
            }
            assert!(wet.count > 0 && dry.count > 0, "the waterline cuts the boat");
            let p = PlaneLanes {
                alpha,
                beta: beta.into(),
                g: g.into(),
            };
            let t = TexelColumns {
                xs: atlas.local_positions().columns(0..atlas.len()),
                avs: atlas.area_vectors().columns(0..atlas.len()),
                areas: atlas.areas(),
            };
            // Ranges of every length modulo the lanes, as the tiled path
            // hands them over, together covering `0..n`.
            let ranges = [0..5, 5..6, 6..37, 37..39, 39..n / 2, n / 2..n];
            fn generic<const FMA: bool, const PRESSURE: bool, const DRY: bool>(
                p: &PlaneLanes,
                t: &TexelColumns,
                ranges: &[std::ops::Range<usize>],
            ) -> (PlanarLanes, bool, bool) {
                let mut acc = PlanarLanes::default();
                for r in ranges {
                    planar_lanes_generic::<FMA, PRESSURE, DRY>(&mut acc, p, t, r.clone());
                }
                (acc, PRESSURE, DRY)
            }
            // Every variant, with and without the pressure sums, of either
            // side: plain or fused, and the AVX2 kernel where the processor
            // has it.
            #[allow(unused_mut)]
            let mut variants = vec![
                generic::<false, true, false>(&p, &t, &ranges),
                generic::<true, true, false>(&p, &t, &ranges),
                generic::<false, false, false>(&p, &t, &ranges),
                generic::<true, false, false>(&p, &t, &ranges),
                generic::<false, true, true>(&p, &t, &ranges),
                generic::<true, true, true>(&p, &t, &ranges),
                generic::<false, false, true>(&p, &t, &ranges),
                generic::<true, false, true>(&p, &t, &ranges),
            ];
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                // SAFETY: the processor has AVX2 and FMA, checked just above.
                #[allow(unsafe_code)]
                variants.extend(unsafe {
                    [
                        (planar_lanes_avx2::<true, false>(&p, &t, &ranges), true, false),
                        (planar_lanes_avx2::<false, false>(&p, &t, &ranges), false, false),
                        (planar_lanes_avx2::<true, true>(&p, &t, &ranges), true, true),
                        (planar_lanes_avx2::<false, true>(&p, &t, &ranges), false, true),
                    ]
                });
            }
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
            for (lanes, pressure, on_dry) in variants {
                let plain = if on_dry { &dry } else { &wet };
                let sum = |v: &[f64; LANES]| v.iter().sum::<f64>();
                assert_eq!(lanes.count, plain.count);
                assert!(close(sum(&lanes.area), plain.area));
                for c in 0..3 {
                    assert!(close(-sum(&lanes.wr[c]), plain.wr[c]), "wr {c}");
                    if pressure {
                        assert!(close(-sum(&lanes.f[c]), plain.f[c]), "f {c}");
                        assert!(close(-sum(&lanes.rxf[c]), plain.rxf[c]), "rxf {c}");
                        assert_eq!(lanes.d2a[c], [0.0; LANES], "d2a {c} is not summed");
                    } else {
                        assert!(close(0.5 * sum(&lanes.d2a[c]), plain.d2a[c]), "d2a {c}");
                        assert_eq!(lanes.f[c], [0.0; LANES], "f {c} is not summed");
                        assert_eq!(lanes.rxf[c], [0.0; LANES], "rxf {c} is not summed");
                    }
                }
                if pressure {
                    assert_eq!(lanes.vol, [0.0; LANES], "Σ w is g · Σ d a");
                    assert!(close(-0.5 * sum(&lanes.wd), plain.wd2));
                } else {
                    assert!(close(-sum(&lanes.vol), plain.vol));
                    assert_eq!(lanes.wd, [0.0; LANES], "Σ w d is g · Σ d² a");
                    let dda = Vector3::from(std::array::from_fn(|c| sum(&lanes.d2a[c])));
                    assert!(close(-0.5 * g.dot(&dda), plain.wd2));
                }
            }
            // The path this processor takes, with its own loads: the wet
            // texels added to nothing give their sums; the dry ones taken
            // from their sums leave nothing.
            for pressure in [false, true] {
                for side in [PlanarTexels::Wet, PlanarTexels::Dry] {
                    let (mut dispatched, expected) = match side {
                        PlanarTexels::Wet => (BuoyancySums::default(), wet),
                        PlanarTexels::Dry => (dry, BuoyancySums::default()),
                    };
                    add_planar_ranges(&mut dispatched, &atlas, &ranges, alpha, &beta, &g, pressure, side);
                    assert_eq!(dispatched.count, expected.count);
                    // Against the sums' own size: what is left of the dry
                    // sums is their rounding.
                    let check = |name: &str, get: &dyn Fn(&BuoyancySums) -> f64| {
                        let size = get(&wet).abs() + get(&dry).abs();
                        let (got, want) = (get(&dispatched), get(&expected));
                        assert!(
                            (got - want).abs() <= 1e-12 * (1.0 + size),
                            "{side:?} {name}: {got} against {want}"
                        );
                    };
                    check("area", &|s| s.area);
                    check("vol", &|s| s.vol);
                    check("wd2", &|s| s.wd2);
                    for c in 0..3 {
                        check("wr", &|s| s.wr[c]);
                        if pressure {
                            check("f", &|s| s.f[c]);
                            check("rxf", &|s| s.rxf[c]);
                        } else {
                            check("d2a", &|s| s.d2a[c]);
                        }
                    }
                }
            }
        }
    }
}
