//! The per-texel sums every path adds to: buoyancy, Archimedes' slope terms
//! and the linear drag system, each with the texel it adds.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

use super::options::Drag;

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
    /// [`add_planar_ranges`](super::planar_kernel::add_planar_ranges)).
    pub f: Vector3<f64>,
    /// Σ r × (−d A).
    pub rxf: Vector3<f64>,
    /// Σ a over submerged texels.
    pub area: f64,
    /// Submerged texels.
    pub count: usize,
    /// Σ (d²/2) A: with the surface's slope, what makes Archimedes' torque
    /// the derivative of the columns' potential (see [`slope_torque`](super::slope_torque::slope_torque)).
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
/// [`slope_torque`](super::slope_torque::slope_torque)), and what takes the
/// sampling error out of the force on a body deep under water (`ayr`,
/// `shallow`; see [`deep_volume`](super::deep_volume::deep_volume)).
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
