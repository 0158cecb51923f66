//! Drag under planar water with a uniform current, in object axes about
//! the atlas origin: the per-texel kernel of the per-texel and tiled paths,
//! and the moments that let the tiled path skip texels.
//!
//! Everything here sums [`DragAcc`]; [`DragAcc::system`] turns the sums
//! into the world-axes system about the centre of mass once.

use nalgebra::{Matrix3, Vector3};
use soak_bake::Atlas;

use super::options::Drag;
use super::sums::DragAcc;
use crate::water::{Plane, Unbounded, Water};

/// The fluid's velocity if it is the same everywhere (a [`Plane`]'s or an
/// [`Unbounded`] fluid's current); `None` for any other surface.
pub(crate) fn uniform_velocity(water: &Water) -> Option<Vector3<f64>> {
    let any = water.surface.as_any()?;
    if let Some(p) = any.downcast_ref::<Plane>() {
        Some(p.current)
    } else {
        any.downcast_ref::<Unbounded>().map(|u| Vector3::from(u.current))
    }
}

/// Drag of one evaluation in object axes about the atlas origin.
///
/// A texel at `x` with area vector `A` moves through the fluid at
/// `v = W + ω × x` (`W` the atlas origin's velocity relative to the fluid,
/// `ω` the angular velocity, both in object axes), so its facing
/// `A·v = h·w` with `h = (A, x × A)` and `w = (W, ω)`: linear in `h`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LocalDrag {
    /// Depth `α + β·x` (planar water).
    pub alpha: f64,
    pub beta: [f64; 3],
    /// `(W, ω)`.
    pub w: [f64; 6],
    /// `½ ρ C_d`.
    pub kq: f64,
    /// Skin friction where it counts (positive), else zero.
    pub lin: f64,
}

impl LocalDrag {
    /// The drag of a body whose atlas origin (object frame `rot`, world
    /// velocities) has the centre of mass at `c` (object axes, from the
    /// atlas origin), moving at `v` and `omega` about it, in fluid of
    /// density `rho` moving at `u`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        drag: &Drag,
        rho: f64,
        alpha: f64,
        beta: &Vector3<f64>,
        rot: &Matrix3<f64>,
        c: &Vector3<f64>,
        v: &Vector3<f64>,
        omega: &Vector3<f64>,
        u: &Vector3<f64>,
    ) -> Self {
        let om = rot.transpose() * omega;
        let w0 = rot.transpose() * (v - u) - om.cross(c);
        Self {
            alpha,
            beta: [beta.x, beta.y, beta.z],
            w: [w0.x, w0.y, w0.z, om.x, om.y, om.z],
            kq: 0.5 * rho * drag.coefficient,
            lin: if drag.linear > 0.0 { drag.linear } else { 0.0 },
        }
    }

    /// Whether any texel can face the flow (a quadratic drag at all).
    pub(crate) fn quadratic(&self) -> bool {
        self.kq != 0.0
    }
}

/// What the tiled path has added for a tile in closed form already, which
/// the per-texel kernel completes: the linear part of all its texels, the
/// quadratic part `k_q h·w` of all its texels (facing the flow or not).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Added {
    pub linear: bool,
    pub quadratic: bool,
}

/// `h = (A, x × A)` of a texel.
#[inline(always)]
fn h_of(x: &[f64; 3], a: &[f64; 3]) -> [f64; 6] {
    [
        a[0],
        a[1],
        a[2],
        x[1] * a[2] - x[2] * a[1],
        x[2] * a[0] - x[0] * a[2],
        x[0] * a[1] - x[1] * a[0],
    ]
}

/// Adds the drag of the texels of `range` to `acc` (object axes about the
/// atlas origin), each submerged texel (`α + β·x > 0`) with its quadratic
/// part where it faces the flow and its skin friction, less what `added`
/// says the closed forms have added for them already: the result is the
/// submerged texels' sums, with the closed forms.
pub(crate) fn add_drag_texels(
    acc: &mut DragAcc,
    atlas: &Atlas,
    range: std::ops::Range<usize>,
    p: &LocalDrag,
    added: Added,
) {
    let [xs, ys, zs] = atlas.local_positions().columns(range.clone());
    let [axs, ays, azs] = atlas.area_vectors().columns(range);
    let quadratic = p.quadratic();
    for i in 0..xs.len() {
        let x = [f64::from(xs[i]), f64::from(ys[i]), f64::from(zs[i])];
        let d = p.alpha + p.beta[0] * x[0] + p.beta[1] * x[1] + p.beta[2] * x[2];
        let wet = d > 0.0;
        let a = [f64::from(axs[i]), f64::from(ays[i]), f64::from(azs[i])];
        let h = h_of(&x, &a);
        let mut s = 0.0;
        if quadratic {
            let f = h.iter().zip(&p.w).map(|(h, w)| h * w).sum::<f64>();
            let taken = wet && f > 0.0;
            if taken != added.quadratic {
                s = if taken { p.kq * f } else { -(p.kq * f) };
            }
        }
        let mut w = 0.0;
        if p.lin > 0.0 && wet != added.linear {
            let area = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            if area > 0.0 {
                let sign = if wet { 1.0 } else { -1.0 };
                s += sign * (p.lin * area);
                w = sign * (p.lin / area);
            }
        }
        if s != 0.0 {
            acc.add_iso(s, &x);
        }
        if w != 0.0 {
            acc.add_rank1(w, &h);
        }
    }
}

/// Per-tile drag moments about the atlas origin, object axes: the linear
/// part's and the quadratic part's (see [`DragMoments::add_texel`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DragMoments {
    /// `Σ a (1, x, x xᵀ)` (the layout of [`DragAcc::iso`]) and `Σ h hᵀ / a`
    /// (upper triangle, as [`DragAcc::gg`]), over texels of nonzero area.
    pub linear: [f64; 31],
    /// For each component `h_j` of `h`: `Σ h_j (1, x, x xᵀ)`.
    pub quadratic: [[f64; 10]; 6],
}

impl Default for DragMoments {
    fn default() -> Self {
        Self {
            linear: [0.0; 31],
            quadratic: [[0.0; 10]; 6],
        }
    }
}

impl DragMoments {
    /// Adds a texel at `x` with area vector `a`.
    pub(crate) fn add_texel(&mut self, x: &Vector3<f64>, a: &Vector3<f64>) {
        let x = [x.x, x.y, x.z];
        let a = [a.x, a.y, a.z];
        let h = h_of(&x, &a);
        let mut acc = DragAcc::default();
        let area = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        if area > 0.0 {
            acc.add_iso(area, &x);
            acc.add_rank1(1.0 / area, &h);
            for (m, v) in self.linear.iter_mut().zip(acc.iso.iter().chain(&acc.gg)) {
                *m += v;
            }
        }
        for (j, hj) in h.iter().enumerate() {
            let mut acc = DragAcc::default();
            acc.add_iso(*hj, &x);
            for (m, v) in self.quadratic[j].iter_mut().zip(&acc.iso) {
                *m += v;
            }
        }
    }

    /// `self += to − from`.
    pub(crate) fn add_difference(&mut self, to: &Self, from: &Self) {
        for ((m, t), f) in self.linear.iter_mut().zip(&to.linear).zip(&from.linear) {
            *m += t - f;
        }
        for j in 0..6 {
            for ((m, t), f) in self.quadratic[j]
                .iter_mut()
                .zip(&to.quadratic[j])
                .zip(&from.quadratic[j])
            {
                *m += t - f;
            }
        }
    }

    /// `self += o`.
    pub(crate) fn add(&mut self, o: &Self) {
        self.add_difference(o, &Self::default());
    }

    /// `Σ h·w` over the texels (positive where most of the area faces the
    /// flow).
    pub(crate) fn facing(&self, p: &LocalDrag) -> f64 {
        (0..6).map(|j| self.quadratic[j][0] * p.w[j]).sum()
    }

    /// Adds the linear part of all the texels (the caller checks there is one).
    pub(crate) fn add_linear(&self, acc: &mut DragAcc, p: &LocalDrag) {
        for (s, m) in acc.iso.iter_mut().zip(&self.linear[..10]) {
            *s += p.lin * m;
        }
        for (s, m) in acc.gg.iter_mut().zip(&self.linear[10..]) {
            *s += p.lin * m;
        }
    }

    /// Adds the quadratic part `k_q h·w` of all the texels, facing the flow
    /// or not.
    pub(crate) fn add_quadratic(&self, acc: &mut DragAcc, p: &LocalDrag) {
        for (k, s) in acc.iso.iter_mut().enumerate() {
            let f: f64 = (0..6).map(|j| self.quadratic[j][k] * p.w[j]).sum();
            *s += p.kq * f;
        }
    }
}

/// Where the facing `h·w` of a set of texels lies, from a box around
/// their `h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Facing {
    /// Every texel faces the flow (`h·w > 0`).
    All,
    /// None does (`h·w ≤ 0`).
    None,
    /// Some may, some may not.
    Mixed,
}

/// A box around the `h` of a set of texels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct HBox {
    pub lo: [f64; 6],
    pub hi: [f64; 6],
}

impl Default for HBox {
    fn default() -> Self {
        Self {
            lo: [f64::INFINITY; 6],
            hi: [f64::NEG_INFINITY; 6],
        }
    }
}

impl HBox {
    /// Grows the box around a texel at `x` with area vector `a`.
    pub(crate) fn add_texel(&mut self, x: &Vector3<f64>, a: &Vector3<f64>) {
        let h = h_of(&[x.x, x.y, x.z], &[a.x, a.y, a.z]);
        for j in 0..6 {
            self.lo[j] = self.lo[j].min(h[j]);
            self.hi[j] = self.hi[j].max(h[j]);
        }
    }

    /// Grows the box around another.
    pub(crate) fn add(&mut self, o: &HBox) {
        for j in 0..6 {
            self.lo[j] = self.lo[j].min(o.lo[j]);
            self.hi[j] = self.hi[j].max(o.hi[j]);
        }
    }

    /// Where `h·w` lies over the box. The bounds are widened by a relative
    /// 1e-12 so that a texel whose own facing rounds the other way is not
    /// misplaced.
    pub(crate) fn facing(&self, w: &[f64; 6]) -> Facing {
        let (mut lo, mut hi, mut size) = (0.0, 0.0, 0.0);
        for j in 0..6 {
            let (p, q) = (self.lo[j] * w[j], self.hi[j] * w[j]);
            lo += p.min(q);
            hi += p.max(q);
            size += p.abs().max(q.abs());
        }
        let margin = 1e-12 * size;
        if lo > margin {
            Facing::All
        } else if hi <= -margin {
            Facing::None
        } else {
            Facing::Mixed
        }
    }
}
