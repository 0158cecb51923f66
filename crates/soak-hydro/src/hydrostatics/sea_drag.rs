//! Drag under a sampled sea, where the fluid's velocity differs from texel
//! to texel: the texels of a chunk are taken four side by side, each
//! submerged one with the fluid's velocity where it is, and summed in
//! object axes about the atlas origin (AVX2 and FMA where the processor
//! has them).
//!
//! A texel at `x` (object axes, from the atlas origin) with area vector
//! `A` in fluid moving at `u` moves through it at `W + ω × x − u`, so its
//! facing is `h·w − A·u`, with `h = (A, x × A)` and `w = (W, ω)` the body's
//! own velocity (see [`LocalDrag`](super::drag_kernel::LocalDrag), which
//! is this with one `u` for every texel). The texel adds [`DragAcc`]'s
//! sums, `s (1, x, x xᵀ)` and `w h hᵀ`, and its part of the right-hand side
//! `b = Σ J_iᵀ K_i u_i = Σ (s u, s x × u) − w (A·u) h`.

use std::ops::Range;

use nalgebra::{Matrix3, Vector3, Vector6};
use soak_bake::Atlas;

use super::body_state::BodyState;
use super::drag_kernel::{
    DragMoments, Facing, FacingBounds, LANES, Lanes, add_iso_lanes, add_rank1_lanes, lanes, madd,
};
use super::frame::Frame;
use super::options::Drag;
use super::sums::upper6;
use super::sums::{DragAcc, DragSums};
use crate::water::{SurfacePatch, Water};

/// What every texel of an evaluation shares.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SeaDragParams {
    /// `(W, ω)`: the atlas origin's velocity and the angular velocity,
    /// object axes, m/s and rad/s.
    w: [f64; 6],
    /// `½ ρ C_d`.
    kq: f64,
    /// Skin friction where it counts (positive), else zero.
    lin: f64,
}

impl SeaDragParams {
    /// The drag of a body whose object axes `rot` turns into the world's,
    /// with its centre of mass at `c` (object axes, from the atlas origin)
    /// moving at `v` and `omega` (world), in fluid of density `rho`.
    pub(crate) fn new(
        drag: &Drag,
        rho: f64,
        rot: &Matrix3<f64>,
        c: &Vector3<f64>,
        v: &Vector3<f64>,
        omega: &Vector3<f64>,
    ) -> Self {
        let om = rot.transpose() * omega;
        let w0 = rot.transpose() * v - om.cross(c);
        Self {
            w: [w0.x, w0.y, w0.z, om.x, om.y, om.z],
            kq: 0.5 * rho * drag.coefficient,
            lin: if drag.linear > 0.0 { drag.linear } else { 0.0 },
        }
    }
}

/// The sums of submerged texels in object axes about the atlas origin:
/// [`DragAcc`]'s and `b`'s. [`SeaDragSums::system`] turns them into the
/// drag system once.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SeaDragSums {
    acc: DragAcc,
    /// `Σ (s u, s x × u) − w (A·u) h`.
    b: [f64; 6],
}

impl std::ops::Add for SeaDragSums {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        self.acc += &o.acc;
        for (x, y) in self.b.iter_mut().zip(&o.b) {
            *x += y;
        }
        self
    }
}

impl SeaDragSums {
    /// The drag system about the centre of mass in world axes (`rot` and
    /// `c` as in [`SeaDragParams::new`]): `K` by [`DragAcc::system`], and
    /// `b` turned about the centre of mass, `(F, τ − c × F)`, and into the
    /// world's axes.
    pub(crate) fn system(&self, rot: &Matrix3<f64>, c: &Vector3<f64>) -> DragSums {
        let k = self.acc.system(rot, c, &Vector3::zeros()).k;
        let f = Vector3::new(self.b[0], self.b[1], self.b[2]);
        let tau = Vector3::new(self.b[3], self.b[4], self.b[5]) - c.cross(&f);
        let (f, tau) = (rot * f, rot * tau);
        DragSums {
            k,
            b: Vector6::new(f.x, f.y, f.z, tau.x, tau.y, tau.z),
        }
    }
}

/// The fluid's velocity over a tile to first order about a point `c`:
/// `u + U (x − c)` at `x` (object axes, from the atlas origin).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LinearFluid {
    /// The velocity at `c`, m/s.
    pub u: Vector3<f64>,
    /// Its derivatives `∂u_i/∂x_j`, 1/s.
    pub grad: Matrix3<f64>,
    /// Where it is taken, m.
    pub c: Vector3<f64>,
}

impl LinearFluid {
    /// The velocity at `x`.
    #[inline]
    fn at(&self, x: &Vector3<f64>) -> Vector3<f64> {
        self.u + self.grad * (x - self.c)
    }
}

impl SeaDragSums {
    /// Adds a tile wholly under water in fluid moving at `fluid`, in
    /// closed form from its drag moments `m`, its facing box `facing` and
    /// its area moments `s1` (`Σ A_j x_k`) and `s2` (`Σ A_j x_k x_l`),
    /// all within `radius` of `fluid.c`.
    ///
    /// A texel at `x` moves through the fluid at `W₀ + ω × x − U x` with
    /// `W₀ = W − u + U c`, so its facing is `h·w₀ − Aᵀ U x`: the planar
    /// closed forms with `w₀`, less `Σ (Aᵀ U x) (1, x, x xᵀ)`, whose first
    /// two moments are `s1`'s and `s2`'s contractions with `U` and whose
    /// third is taken to first order about `c`. The right-hand side is
    /// `(Σ s u(x), Σ s x × u(x))` from the tile's `Σ s`, `Σ s x` and
    /// `Σ s x xᵀ`, less the skin friction's `λ Σ (A·u) h / a` with the
    /// velocity at the tile's area-weighted centroid (the velocity's
    /// change across the tile in that term, odd about the centroid, is
    /// left out). Uniform fluid
    /// (`U = 0`): the texels' sums exactly. `false` (and nothing added)
    /// where some of its texels may face the flow and some not: the
    /// caller sums those texel by texel.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn add_tile(
        &mut self,
        m: &DragMoments,
        facing: &FacingBounds,
        s1: &Matrix3<f64>,
        s2: &[Matrix3<f64>; 3],
        radius: f64,
        p: &SeaDragParams,
        fluid: &LinearFluid,
    ) -> bool {
        let (u, grad, c) = (&fluid.u, &fluid.grad, &fluid.c);
        // Facing `h·(W − u, ω) − Aᵀ U (x − c)`: the box's with the
        // velocity at c, give or take |U| times the tile's radius.
        let wc = [p.w[0] - u.x, p.w[1] - u.y, p.w[2] - u.z, p.w[3], p.w[4], p.w[5]];
        let w0 = Vector3::new(p.w[0], p.w[1], p.w[2]) - u + grad * c;
        let w = [w0.x, w0.y, w0.z, p.w[3], p.w[4], p.w[5]];
        let quadratic = p.kq != 0.0
            && match facing.facing_within(&wc, grad.norm() * radius) {
                Facing::All => true,
                Facing::None => false,
                Facing::Mixed => return false,
            };
        // The tile's own iso sums Σ s (1, x, x xᵀ), for the right-hand side.
        let mut iso = [0.0; 10];
        if p.lin > 0.0 {
            let (l_iso, gg) = m.linear.split_at(10);
            for (a, v) in iso.iter_mut().zip(l_iso) {
                *a += p.lin * v;
            }
            for (a, v) in self.acc.gg.iter_mut().zip(gg) {
                *a += p.lin * v;
            }
            // λ Σ (A·u(x)) h / a ≈ λ (Σ h hᵀ / a)[:, 0..3] u(x̄), the
            // velocity at the tile's area-weighted centroid x̄, about which
            // the change of u is odd.
            let bar = if l_iso[0] > 0.0 {
                fluid.at(&(Vector3::new(l_iso[1], l_iso[2], l_iso[3]) / l_iso[0]))
            } else {
                *u
            };
            for (i, b) in self.b.iter_mut().enumerate() {
                let gu: f64 = (0..3).map(|j| gg[upper6(i.min(j), i.max(j))] * bar[j]).sum();
                *b -= p.lin * gu;
            }
        }
        if quadratic {
            // Σ (Aᵀ U x), Σ (Aᵀ U x) x, and Σ (Aᵀ U x) x xᵀ to first order
            // about c.
            let e0 = grad.component_mul(s1).sum();
            let e1 = Vector3::from_fn(|l, _| (0..3).map(|j| (grad.row(j) * s2[j].column(l))[0]).sum::<f64>());
            let e2 = c * e1.transpose() + e1 * c.transpose() - c * c.transpose() * e0;
            let e = [
                e0,
                e1.x,
                e1.y,
                e1.z,
                e2[(0, 0)],
                e2[(1, 1)],
                e2[(2, 2)],
                e2[(0, 1)],
                e2[(1, 2)],
                e2[(2, 0)],
            ];
            for (k, a) in iso.iter_mut().enumerate() {
                let f: f64 = (0..6).map(|j| m.quadratic[j][k] * w[j]).sum();
                *a += p.kq * (f - e[k]);
            }
        }
        for (a, v) in self.acc.iso.iter_mut().zip(&iso) {
            *a += v;
        }
        // Σ s u(x) = S u + U (S₁ − S c); Σ s x × u(x) = S₁ × (u − U c) + Σ s x × U x.
        let (s0, s1x) = (iso[0], Vector3::new(iso[1], iso[2], iso[3]));
        let s2x = Matrix3::new(
            iso[4], iso[7], iso[9], iso[7], iso[5], iso[8], iso[9], iso[8], iso[6],
        );
        let f = s0 * u + grad * (s1x - s0 * c);
        // (Σ s x × U x)_p = ε_pqr (U S₂)_rq.
        let us2 = grad * s2x;
        let curl = Vector3::new(
            us2[(2, 1)] - us2[(1, 2)],
            us2[(0, 2)] - us2[(2, 0)],
            us2[(1, 0)] - us2[(0, 1)],
        );
        let t = s1x.cross(&(u - grad * c)) + curl;
        for (b, v) in self.b.iter_mut().zip(f.iter().chain(t.iter())) {
            *b += v;
        }
        true
    }
}

/// Running sums per lane.
#[derive(Clone, Copy)]
struct SumLanes {
    /// `Σ s`, `Σ s x` (3), `Σ s x xᵀ` (xx, yy, zz, xy, yz, zx), as
    /// [`DragAcc::iso`].
    iso: [Lanes; 10],
    /// `Σ w h hᵀ`, its upper triangle row by row, as [`DragAcc::gg`].
    gg: [Lanes; 21],
    /// `Σ s u`, `Σ s x × u`.
    su: [Lanes; 6],
    /// `Σ w (A·u) h`.
    wh: [Lanes; 6],
}

impl Default for SumLanes {
    fn default() -> Self {
        Self {
            iso: [[0.0; LANES]; 10],
            gg: [[0.0; LANES]; 21],
            su: [[0.0; LANES]; 6],
            wh: [[0.0; LANES]; 6],
        }
    }
}

impl SumLanes {
    /// The sums of the lanes, added in a fixed order.
    fn finish(&self) -> SeaDragSums {
        let sum = |v: &Lanes| (v[0] + v[1]) + (v[2] + v[3]);
        let mut out = SeaDragSums::default();
        for (s, v) in out.acc.iso.iter_mut().zip(&self.iso) {
            *s = sum(v);
        }
        for (s, v) in out.acc.gg.iter_mut().zip(&self.gg) {
            *s = sum(v);
        }
        for (j, b) in out.b.iter_mut().enumerate() {
            *b = sum(&self.su[j]) - sum(&self.wh[j]);
        }
        out
    }
}

/// What the texels of one evaluation under a sampled sea share.
pub(crate) struct SeaDragFrame<'a> {
    pub params: SeaDragParams,
    /// Object axes into the world's.
    pub rot: Matrix3<f64>,
    /// The atlas origin, world, m.
    pub ow: Vector3<f64>,
    /// The sampled sea, with its velocities.
    pub patch: &'a SurfacePatch,
}

impl<'a> SeaDragFrame<'a> {
    /// The frame of one evaluation of a body at `state` under `patch` in
    /// `water`, with `drag`; and the centre of mass from the atlas origin in
    /// object axes, which [`SeaDragSums::system`] takes.
    pub(crate) fn of(
        drag: &Drag,
        water: &Water,
        state: &BodyState,
        frame: &Frame,
        patch: &'a SurfacePatch,
    ) -> (Self, Vector3<f64>) {
        let c = frame.rot.transpose() * (frame.com - frame.ow);
        let params = SeaDragParams::new(
            drag,
            water.density,
            &frame.rot,
            &c,
            &state.linear_velocity,
            &state.angular_velocity,
        );
        (
            Self {
                params,
                rot: frame.rot,
                ow: frame.ow,
                patch,
            },
            c,
        )
    }
}

/// The drag sums of the texels of `range` whose depth (`depths`, one per
/// texel of the range) is positive, each in the fluid's velocity where it
/// is (read from the patch).
pub(crate) fn sea_drag_range(
    atlas: &Atlas,
    range: Range<usize>,
    depths: &[f64],
    frame: &SeaDragFrame,
    fluid: Option<&LinearFluid>,
) -> SeaDragSums {
    let mut sums = SumLanes::default();
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
            // SAFETY: the processor has AVX2 and FMA, checked just above.
            #[allow(unsafe_code)]
            unsafe {
                sea_drag_avx2(&mut sums, atlas, range, depths, frame, fluid)
            };
            return sums.finish();
        }
    }
    sea_drag_lanes::<false>(&mut sums, atlas, range, depths, frame, fluid);
    sums.finish()
}

/// [`sea_drag_lanes`] compiled for AVX2, multiply-adds fused.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn sea_drag_avx2(
    sums: &mut SumLanes,
    atlas: &Atlas,
    range: Range<usize>,
    depths: &[f64],
    frame: &SeaDragFrame,
    fluid: Option<&LinearFluid>,
) {
    sea_drag_lanes::<true>(sums, atlas, range, depths, frame, fluid);
}

/// The texels of `range`, [`LANES`] at a time (the last group padded with
/// texels of no area); a group none of whose texels is submerged is
/// skipped, a dry texel of a group adds zeros.
#[inline(always)]
fn sea_drag_lanes<const FMA: bool>(
    sums: &mut SumLanes,
    atlas: &Atlas,
    range: Range<usize>,
    depths: &[f64],
    frame: &SeaDragFrame,
    fluid: Option<&LinearFluid>,
) {
    let n = atlas.len();
    let xs = atlas.local_positions().columns(0..n);
    let avs = atlas.area_vectors().columns(0..n);
    let (rot, ow) = (&frame.rot, &frame.ow);
    for g in range.clone().step_by(LANES) {
        let wet: [bool; LANES] =
            std::array::from_fn(|k| g + k < range.end && depths[g + k - range.start] > 0.0);
        if !wet.iter().any(|&w| w) {
            continue;
        }
        let at = |v: &[f32], k: usize| if wet[k] { f64::from(v[g + k]) } else { 0.0 };
        let x: [Lanes; 3] = std::array::from_fn(|c| lanes(|k| at(xs[c], k)));
        let a: [Lanes; 3] = std::array::from_fn(|c| lanes(|k| at(avs[c], k)));
        if let Some(fluid) = fluid {
            // The velocity to first order over the range, object axes.
            let at: [Vector3<f64>; LANES] = std::array::from_fn(|k| {
                if wet[k] {
                    fluid.at(&Vector3::new(x[0][k], x[1][k], x[2][k]))
                } else {
                    Vector3::zeros()
                }
            });
            let u: [Lanes; 3] = std::array::from_fn(|c| lanes(|k| at[k][c]));
            add_group::<FMA>(sums, &frame.params, &x, &a, &u);
            continue;
        }
        // The fluid's velocity at each texel's place (world), then in
        // object axes.
        let mut uw = [[0.0; LANES]; 3];
        for k in 0..LANES {
            if wet[k] {
                let p = Vector3::from_fn(|c, _| {
                    let v = madd::<FMA>(rot[(c, 0)], x[0][k], ow[c]);
                    let v = madd::<FMA>(rot[(c, 1)], x[1][k], v);
                    madd::<FMA>(rot[(c, 2)], x[2][k], v)
                });
                let v = frame.patch.velocity_lanes::<FMA>(&p);
                for c in 0..3 {
                    uw[c][k] = v[c];
                }
            }
        }
        let u: [Lanes; 3] = std::array::from_fn(|c| {
            lanes(|k| {
                let v = rot[(0, c)] * uw[0][k];
                let v = madd::<FMA>(rot[(1, c)], uw[1][k], v);
                madd::<FMA>(rot[(2, c)], uw[2][k], v)
            })
        });
        add_group::<FMA>(sums, &frame.params, &x, &a, &u);
    }
}

/// The sums of texels given one by one (position, area vector and fluid
/// velocity, object axes), with the kernel's own arithmetic: for the
/// tests.
#[cfg(test)]
pub(crate) fn sea_drag_texels(p: &SeaDragParams, texels: &[[Vector3<f64>; 3]]) -> SeaDragSums {
    let mut sums = SumLanes::default();
    for group in texels.chunks(LANES) {
        let lane = |m: usize| -> [Lanes; 3] {
            std::array::from_fn(|c| lanes(|k| group.get(k).map_or(0.0, |t| t[m][c])))
        };
        add_group::<false>(&mut sums, p, &lane(0), &lane(1), &lane(2));
    }
    sums.finish()
}

/// Adds one group of texels side by side (position, area vector, fluid
/// velocity, object axes; a texel of no area adds zeros).
#[inline(always)]
fn add_group<const FMA: bool>(
    sums: &mut SumLanes,
    p: &SeaDragParams,
    x: &[Lanes; 3],
    a: &[Lanes; 3],
    u: &[Lanes; 3],
) {
    let w = &p.w;
    {
        let h = [
            a[0],
            a[1],
            a[2],
            lanes(|k| x[1][k] * a[2][k] - x[2][k] * a[1][k]),
            lanes(|k| x[2][k] * a[0][k] - x[0][k] * a[2][k]),
            lanes(|k| x[0][k] * a[1][k] - x[1][k] * a[0][k]),
        ];
        // A·u and the facing h·w − A·u.
        let au = lanes(|k| madd::<FMA>(a[2][k], u[2][k], madd::<FMA>(a[1][k], u[1][k], a[0][k] * u[0][k])));
        let f = lanes(|k| {
            let mut f = h[0][k] * w[0];
            for j in 1..6 {
                f = madd::<FMA>(h[j][k], w[j], f);
            }
            f - au[k]
        });
        let mut s = lanes(|k| p.kq * f[k].max(0.0));
        let mut wl = [0.0; LANES];
        if p.lin > 0.0 {
            let area = lanes(|k| {
                madd::<FMA>(a[2][k], a[2][k], madd::<FMA>(a[1][k], a[1][k], a[0][k] * a[0][k])).sqrt()
            });
            for k in 0..LANES {
                let some = area[k] > 0.0;
                s[k] += if some { p.lin * area[k] } else { 0.0 };
                wl[k] = if some { p.lin / area[k] } else { 0.0 };
            }
        }
        add_iso_lanes::<FMA>(&mut sums.iso, &s, x);
        // s u and s x × u.
        let su = [
            lanes(|k| s[k] * u[0][k]),
            lanes(|k| s[k] * u[1][k]),
            lanes(|k| s[k] * u[2][k]),
        ];
        let b = &mut sums.su;
        for k in 0..LANES {
            b[0][k] += su[0][k];
            b[1][k] += su[1][k];
            b[2][k] += su[2][k];
            b[3][k] += x[1][k] * su[2][k] - x[2][k] * su[1][k];
            b[4][k] += x[2][k] * su[0][k] - x[0][k] * su[2][k];
            b[5][k] += x[0][k] * su[1][k] - x[1][k] * su[0][k];
        }
        if p.lin > 0.0 {
            add_rank1_lanes::<FMA>(&mut sums.gg, &wl, &h);
            let wau = lanes(|k| wl[k] * au[k]);
            for (j, hj) in h.iter().enumerate() {
                for k in 0..LANES {
                    sums.wh[j][k] = madd::<FMA>(wau[k], hj[k], sums.wh[j][k]);
                }
            }
        }
    }
}
