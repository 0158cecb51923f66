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
        self += o;
        self
    }
}

impl std::ops::AddAssign for SeaDragSums {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        self.acc += &o.acc;
        for (x, y) in self.b.iter_mut().zip(&o.b) {
            *x += y;
        }
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

/// Running sums per lane of the sea's drag kernel: texel ranges added one
/// after another ([`SeaDragLanes::add`]) stay in lanes, summed once at the
/// end ([`SeaDragLanes::finish`]).
#[derive(Clone, Copy)]
pub(crate) struct SeaDragLanes {
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

impl Default for SeaDragLanes {
    fn default() -> Self {
        Self {
            iso: [[0.0; LANES]; 10],
            gg: [[0.0; LANES]; 21],
            su: [[0.0; LANES]; 6],
            wh: [[0.0; LANES]; 6],
        }
    }
}

impl SeaDragLanes {
    /// The sums of the lanes, added in a fixed order.
    pub(crate) fn finish(&self) -> SeaDragSums {
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
    /// The sampled sea, with its velocities; `None` under a plane whose
    /// current changes linearly ([`crate::FlowPlane`]), whose every range
    /// comes with its fluid (a range without one would read still water).
    pub patch: Option<&'a SurfacePatch>,
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
                patch: Some(patch),
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
    let mut sums = SeaDragLanes::default();
    sums.add(atlas, range, depths, frame, fluid);
    sums.finish()
}

impl SeaDragLanes {
    /// Adds the texels of `range` as [`sea_drag_range`] sums them, in the
    /// fluid's velocity over the range (`fluid`) or, without one, in the
    /// patch's at every texel.
    pub(crate) fn add(
        &mut self,
        atlas: &Atlas,
        range: Range<usize>,
        depths: &[f64],
        frame: &SeaDragFrame,
        fluid: Option<&LinearFluid>,
    ) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                // SAFETY: the processor has AVX2 and FMA, checked just above.
                #[allow(unsafe_code)]
                unsafe {
                    sea_drag_avx2(self, atlas, range, depths, frame, fluid)
                };
                return;
            }
        }
        sea_drag_lanes::<false>(self, atlas, range, depths, frame, fluid);
    }
}

/// [`sea_drag_lanes`] compiled for AVX2, multiply-adds fused.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn sea_drag_avx2(
    sums: &mut SeaDragLanes,
    atlas: &Atlas,
    range: Range<usize>,
    depths: &[f64],
    frame: &SeaDragFrame,
    fluid: Option<&LinearFluid>,
) {
    use super::avx::{load, store};
    use std::arch::x86_64::*;
    match fluid {
        Some(fluid) => {
            // u + U (x − c), as nalgebra sums a matrix times a vector.
            let u0 = [fluid.u.x, fluid.u.y, fluid.u.z].map(|v| _mm256_set1_pd(v));
            let c = [fluid.c.x, fluid.c.y, fluid.c.z].map(|v| _mm256_set1_pd(v));
            let grad: [[__m256d; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|j| _mm256_set1_pd(fluid.grad[(i, j)])));
            sea_drag_lanes_avx2(sums, atlas, range, depths, &frame.params, |x, wet| {
                let dx = [0, 1, 2].map(|k| _mm256_sub_pd(x[k], c[k]));
                std::array::from_fn(|i| {
                    let g = &grad[i];
                    let r = _mm256_add_pd(
                        _mm256_add_pd(_mm256_mul_pd(g[0], dx[0]), _mm256_mul_pd(g[1], dx[1])),
                        _mm256_mul_pd(g[2], dx[2]),
                    );
                    _mm256_and_pd(_mm256_add_pd(u0[i], r), wet)
                })
            });
        }
        // No patch and no fluid: still water.
        None if frame.patch.is_none() => {
            sea_drag_lanes_avx2(sums, atlas, range, depths, &frame.params, |_, _| {
                [_mm256_setzero_pd(); 3]
            });
        }
        None => {
            let (rot, ow) = (&frame.rot, &frame.ow);
            let Some(patch) = frame.patch else { return };
            let r: [[__m256d; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|j| _mm256_set1_pd(rot[(i, j)])));
            sea_drag_lanes_avx2(sums, atlas, range, depths, &frame.params, |x, wet| {
                // The fluid's velocity at each wet texel's place (world),
                // then in object axes.
                let (x, wet) = (x.map(|v| store(v)), _mm256_movemask_pd(wet));
                let mut uw = [[0.0; LANES]; 3];
                for k in (0..LANES).filter(|k| wet & (1 << k) != 0) {
                    let p = Vector3::from_fn(|c, _| {
                        let v = rot[(c, 0)].mul_add(x[0][k], ow[c]);
                        let v = rot[(c, 1)].mul_add(x[1][k], v);
                        rot[(c, 2)].mul_add(x[2][k], v)
                    });
                    let v = patch.velocity_lanes::<true>(&p);
                    for c in 0..3 {
                        uw[c][k] = v[c];
                    }
                }
                let uw = uw.map(|v| load(&v));
                std::array::from_fn(|c| {
                    let v = _mm256_mul_pd(r[0][c], uw[0]);
                    let v = _mm256_fmadd_pd(r[1][c], uw[1], v);
                    _mm256_fmadd_pd(r[2][c], uw[2], v)
                })
            });
        }
    }
}

/// [`sea_drag_lanes`] written with AVX2 intrinsics, the fluid's velocity
/// over a group's lanes from `velocity` (given their positions, zero
/// where dry, and the mask of the wet ones; zero where dry): the same
/// operations in the same order on the same lanes as [`add_group`] with
/// fused multiply-adds, so the same bits, its running sums in registers
/// rather than lane arrays. The last `len % LANES` texels make a group of
/// their own, read from padded copies, their empty lanes dry.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn sea_drag_lanes_avx2<V>(
    sums: &mut SeaDragLanes,
    atlas: &Atlas,
    range: Range<usize>,
    depths: &[f64],
    p: &SeaDragParams,
    mut velocity: V,
) where
    V: FnMut(&[std::arch::x86_64::__m256d; 3], std::arch::x86_64::__m256d) -> [std::arch::x86_64::__m256d; 3],
{
    use super::avx::{add_iso, add_rank1, h_of, load, padded, store, widen_at as widen};
    use std::arch::x86_64::*;

    let n = atlas.len();
    let xs = atlas.local_positions().columns(0..n);
    let avs = atlas.area_vectors().columns(0..n);
    let zero = _mm256_setzero_pd();
    let w = p.w.map(|v| _mm256_set1_pd(v));
    let (kq, lin) = (_mm256_set1_pd(p.kq), _mm256_set1_pd(p.lin));
    let linear = p.lin > 0.0;
    let mut iso = sums.iso.each_ref().map(|v| load(v));
    let mut gg = sums.gg.each_ref().map(|v| load(v));
    let mut su = sums.su.each_ref().map(|v| load(v));
    let mut wh = sums.wh.each_ref().map(|v| load(v));

    let mut group = |xs: [&[f32]; 3], avs: [&[f32]; 3], depths: &[f64], at: usize, d0: usize| {
        let wet = _mm256_cmp_pd::<_CMP_GT_OQ>(load(&depths[d0..]), zero);
        if _mm256_movemask_pd(wet) == 0 {
            return;
        }
        // A dry lane's position and area vector read as zeros, and its
        // fluid's velocity too: it adds zeros.
        let x = [0, 1, 2].map(|k| _mm256_and_pd(widen(xs[k], at), wet));
        let a = [0, 1, 2].map(|k| _mm256_and_pd(widen(avs[k], at), wet));
        let u = velocity(&x, wet);
        let h = h_of(&x, &a);
        // A·u and the facing h·w − A·u.
        let au = _mm256_fmadd_pd(a[2], u[2], _mm256_fmadd_pd(a[1], u[1], _mm256_mul_pd(a[0], u[0])));
        let mut f = _mm256_mul_pd(h[0], w[0]);
        for j in 1..6 {
            f = _mm256_fmadd_pd(h[j], w[j], f);
        }
        let f = _mm256_sub_pd(f, au);
        // `f64::max(f, 0)`: zero where `f` is not a number, as `max_pd`
        // gives its second operand then.
        let mut s = _mm256_mul_pd(kq, _mm256_max_pd(f, zero));
        let mut wl = zero;
        if linear {
            let aa = _mm256_fmadd_pd(a[2], a[2], _mm256_fmadd_pd(a[1], a[1], _mm256_mul_pd(a[0], a[0])));
            let area = _mm256_sqrt_pd(aa);
            let some = _mm256_cmp_pd::<_CMP_GT_OQ>(area, zero);
            s = _mm256_add_pd(s, _mm256_and_pd(_mm256_mul_pd(lin, area), some));
            wl = _mm256_and_pd(_mm256_div_pd(lin, area), some);
        }
        add_iso(&mut iso, s, &x);
        // s u and s x × u.
        let s_u = [0, 1, 2].map(|k| _mm256_mul_pd(s, u[k]));
        su[0] = _mm256_add_pd(su[0], s_u[0]);
        su[1] = _mm256_add_pd(su[1], s_u[1]);
        su[2] = _mm256_add_pd(su[2], s_u[2]);
        su[3] = _mm256_add_pd(
            su[3],
            _mm256_sub_pd(_mm256_mul_pd(x[1], s_u[2]), _mm256_mul_pd(x[2], s_u[1])),
        );
        su[4] = _mm256_add_pd(
            su[4],
            _mm256_sub_pd(_mm256_mul_pd(x[2], s_u[0]), _mm256_mul_pd(x[0], s_u[2])),
        );
        su[5] = _mm256_add_pd(
            su[5],
            _mm256_sub_pd(_mm256_mul_pd(x[0], s_u[1]), _mm256_mul_pd(x[1], s_u[0])),
        );
        if linear {
            add_rank1(&mut gg, wl, &h);
            let wau = _mm256_mul_pd(wl, au);
            for (j, hj) in h.iter().enumerate() {
                wh[j] = _mm256_fmadd_pd(wau, *hj, wh[j]);
            }
        }
    };

    // One call of `group` in the loop (the last texels of the range, a
    // group of their own, read from padded copies): the compiler then
    // inlines it, its running sums no longer stored and loaded each call.
    let (start, end) = (range.start, range.end);
    let mut i = start;
    while i < end {
        let k = (end - i).min(LANES);
        let (pxs, pavs, pd);
        let (gx, ga, gd, at, d0) = if k == LANES {
            (xs, avs, depths, i, i - start)
        } else {
            let pad = |v: &[f32]| padded(&v[i..end]);
            (pxs, pavs) = (xs.map(pad), avs.map(pad));
            pd = padded(&depths[i - start..]);
            (
                pxs.each_ref().map(|v| &v[..]),
                pavs.each_ref().map(|v| &v[..]),
                &pd[..],
                0,
                0,
            )
        };
        group(gx, ga, gd, at, d0);
        i += k;
    }
    for (out, v) in sums.iso.iter_mut().zip(iso) {
        *out = store(v);
    }
    for (out, v) in sums.su.iter_mut().zip(su) {
        *out = store(v);
    }
    if linear {
        for (out, v) in sums.gg.iter_mut().zip(gg) {
            *out = store(v);
        }
        for (out, v) in sums.wh.iter_mut().zip(wh) {
            *out = store(v);
        }
    }
}

/// The texels of `range`, [`LANES`] at a time (the last group padded with
/// texels of no area); a group none of whose texels is submerged is
/// skipped, a dry texel of a group adds zeros.
#[inline(always)]
fn sea_drag_lanes<const FMA: bool>(
    sums: &mut SeaDragLanes,
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
                let v = frame
                    .patch
                    .map_or([0.0; 4], |patch| patch.velocity_lanes::<FMA>(&p));
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
    let mut sums = SeaDragLanes::default();
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
    sums: &mut SeaDragLanes,
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

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use nalgebra::{Isometry3, Matrix3, UnitQuaternion, Vector3};
    use soak_bake::{Atlas, BakeOptions, builtin};

    use super::*;
    use crate::hydrostatics::body_state::BodyState;
    use crate::hydrostatics::options::HydroOptions;
    use crate::water::{Gerstner, GerstnerWave, Water};

    /// The intrinsics' kernel adds the same bits as the lanes' code it was
    /// written from, compiled for AVX2, in one fluid velocity over the
    /// range and in the patch's at every texel: over ranges of every
    /// length modulo the lanes, texels wet and dry, with skin friction and
    /// without, facing the flow and not.
    #[test]
    fn the_fluid_kernel_adds_the_lanes_bits() {
        if !(std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")) {
            eprintln!("skipped: the processor has no AVX2 and FMA");
            return;
        }
        let atlas = Atlas::bake(&builtin::sphere(0.5, 24, 12), BakeOptions::square(32)).unwrap();
        let swell = Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.81).unwrap());
        let state = BodyState::at_rest(Isometry3::from_parts(
            Vector3::new(0.3, 0.1, -0.2).into(),
            UnitQuaternion::from_euler_angles(0.3, -0.5, 0.2),
        ));
        // Sampled for drag, with the waves' velocities.
        let options = HydroOptions {
            drag: Some(Drag {
                coefficient: 1.0,
                linear: 0.0,
            }),
            ..HydroOptions::default()
        };
        let sampled = crate::sampled_water(&atlas, &swell, &state, 0.7, &options)
            .unwrap()
            .expect("the swell is sampled by default");
        let patch = sampled
            .surface
            .as_any()
            .and_then(|s| s.downcast_ref::<SurfacePatch>())
            .expect("a patch");
        let fluid = LinearFluid {
            u: Vector3::new(0.4, -0.2, 0.3),
            grad: Matrix3::new(0.3, -0.1, 0.05, 0.2, -0.4, 0.1, -0.15, 0.25, 0.1),
            c: Vector3::new(0.1, -0.2, 0.05),
        };
        // Depths of both signs, and zero, in a fixed pseudo-random order.
        let depths: Vec<f64> = (0..atlas.len())
            .map(|i| match (i * 7919) % 5 {
                0 => 0.0,
                1 | 3 => 0.01 * ((i % 13) as f64 + 1.0),
                _ => -0.02,
            })
            .collect();
        let mut compared = 0;
        for (linear, omega) in [(20.0, 0.8), (0.0, -1.5)] {
            let drag = Drag {
                coefficient: 0.9,
                linear,
            };
            let rot = *state.pose.rotation.to_rotation_matrix().matrix();
            let params = SeaDragParams::new(
                &drag,
                1025.0,
                &rot,
                &Vector3::new(0.02, 0.0, -0.01),
                &Vector3::new(0.5, -0.7, 0.3),
                &Vector3::new(0.2, omega, -0.4),
            );
            let frame = SeaDragFrame {
                params,
                rot,
                ow: state.pose.translation.vector,
                patch: Some(patch),
            };
            for start in [0, 1, 5, 6, 7] {
                for len in [1, 2, 3, 4, 5, 15, 16, 17, 63, 64] {
                    let range = start..(start + len).min(atlas.len());
                    let d = &depths[range.clone()];
                    // SAFETY: the processor has AVX2 and FMA, checked above.
                    #[allow(unsafe_code)]
                    for fluid in [Some(&fluid), None] {
                        let mut want = SeaDragLanes::default();
                        // SAFETY: the processor has AVX2 and FMA, checked above.
                        #[allow(unsafe_code)]
                        let got = unsafe {
                            let mut got = SeaDragLanes::default();
                            sea_drag_avx2(&mut got, &atlas, range.clone(), d, &frame, fluid);
                            lanes_avx2(&mut want, &atlas, range.clone(), d, &frame, fluid);
                            got
                        };
                        let (got, want) = (got.finish(), want.finish());
                        assert_eq!(got, want, "range {range:?}, skin friction {linear}, {fluid:?}");
                        assert!(got.acc.iso[0] != 0.0 || d.iter().all(|&d| d <= 0.0));
                        assert!(got.b.iter().any(|&b| b != 0.0) || d.iter().all(|&d| d <= 0.0));
                        compared += 1;
                    }
                }
            }
        }
        assert_eq!(compared, 200);
    }

    /// The lanes' code, compiled for AVX2.
    #[target_feature(enable = "avx2,fma")]
    fn lanes_avx2(
        sums: &mut SeaDragLanes,
        atlas: &Atlas,
        range: Range<usize>,
        depths: &[f64],
        frame: &SeaDragFrame,
        fluid: Option<&LinearFluid>,
    ) {
        sea_drag_lanes::<true>(sums, atlas, range, depths, frame, fluid);
    }
}
