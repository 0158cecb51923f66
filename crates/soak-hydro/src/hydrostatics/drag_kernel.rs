//! Drag under planar water with a uniform current, in object axes about
//! the atlas origin: the per-texel kernel of the per-texel and tiled paths,
//! and the moments that let the tiled path skip texels.
//!
//! Everything here sums [`DragAcc`]; [`DragAcc::system`] turns the sums
//! into the world-axes system about the centre of mass once.
//!
//! Longer than the other files on purpose: the portable and the AVX2 forms
//! of the kernel must do the same operations in the same order on the same
//! lanes (the tests hold them to the same bits), and the per-tile moments
//! and facing bounds are the kernel's own sums over a tile, closed form for
//! closed form.

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
///
/// See [`add_drag_ranges`], which this is for one range, summed at once.
pub(crate) fn add_drag_texels(
    acc: &mut DragAcc,
    atlas: &Atlas,
    range: std::ops::Range<usize>,
    p: &LocalDrag,
    added: Added,
) {
    let mut lanes = DragLanes::default();
    add_drag_ranges(&mut lanes, atlas, &[(&[range][..], added)], p);
    lanes.add_to(acc);
}

/// [`add_drag_texels`] over several ranges into per-lane sums, which stay
/// in registers from one range to the next; [`DragLanes::add_to`] sums the
/// lanes once at the end.
///
/// Texels are taken [`LANES`] at a time side by side, like the planar
/// kernel's (the last of a range in a group of their own, its empty lanes
/// masked), a lane that adds nothing adding zeros, and a group none of
/// whose lanes adds anything skipped after its tests; with AVX2 and FMA
/// where the processor has them (the same operations, multiply-adds fused
/// as the portable code's `mul_add`, so the same bits as it).
pub(crate) fn add_drag_ranges(lanes: &mut DragLanes, atlas: &Atlas, lists: &[RangeList], p: &LocalDrag) {
    if lists.iter().all(|(ranges, _)| ranges.is_empty()) {
        return;
    }
    let n = atlas.len();
    let t = DragColumns {
        xs: atlas.local_positions().columns(0..n),
        avs: atlas.area_vectors().columns(0..n),
    };
    match (p.lin > 0.0, p.quadratic()) {
        (true, true) => drag_lanes::<true, true>(lanes, &t, lists, p),
        (true, false) => drag_lanes::<true, false>(lanes, &t, lists, p),
        (false, true) => drag_lanes::<false, true>(lanes, &t, lists, p),
        (false, false) => {}
    }
}

/// Texel ranges the drag kernel takes one after the other, with what the
/// closed forms have added for them already.
pub(crate) type RangeList<'a> = (&'a [std::ops::Range<usize>], Added);

/// Texels the drag kernel takes side by side.
pub(super) const LANES: usize = 4;

/// Lanes of f64, one per texel of a group.
pub(super) type Lanes = [f64; LANES];

/// The positions and area vectors of the atlas' texels.
struct DragColumns<'a> {
    xs: [&'a [f32]; 3],
    avs: [&'a [f32]; 3],
}

/// [`DragAcc`]'s sums, one per lane.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct DragLanes {
    iso: [Lanes; 10],
    gg: [Lanes; 21],
}

impl Default for DragLanes {
    fn default() -> Self {
        Self {
            iso: [[0.0; LANES]; 10],
            gg: [[0.0; LANES]; 21],
        }
    }
}

impl DragLanes {
    /// Adds the sums of the lanes, in a fixed order, to `acc`.
    pub(crate) fn add_to(&self, acc: &mut DragAcc) {
        let sum = |v: &Lanes| (v[0] + v[1]) + (v[2] + v[3]);
        for (s, v) in acc.iso.iter_mut().zip(&self.iso) {
            *s += sum(v);
        }
        for (s, v) in acc.gg.iter_mut().zip(&self.gg) {
            *s += sum(v);
        }
    }
}

/// The kernel over the ranges, with AVX2 where the processor has it.
fn drag_lanes<const LINEAR: bool, const QUADRATIC: bool>(
    acc: &mut DragLanes,
    t: &DragColumns,
    lists: &[RangeList],
    p: &LocalDrag,
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
            // SAFETY: the processor has AVX2 and FMA, checked just above.
            #[allow(unsafe_code)]
            unsafe {
                drag_lanes_avx2::<LINEAR, QUADRATIC>(acc, t, lists, p)
            };
            return;
        }
    }
    for (ranges, added) in lists {
        for r in ranges.iter() {
            drag_lanes_generic::<false, LINEAR, QUADRATIC>(acc, t, r.clone(), p, *added);
        }
    }
}

/// [`drag_lanes_generic`] with fused multiply-adds, written with AVX2
/// intrinsics: the same operations in the same order on the same lanes,
/// so the same bits. The last `len % LANES` texels of a range make a
/// group of their own, padded with zeros and its empty lanes masked off.
/// Every list's ranges in one call, the running sums in registers
/// throughout.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn drag_lanes_avx2<const LINEAR: bool, const QUADRATIC: bool>(
    acc: &mut DragLanes,
    t: &DragColumns,
    lists: &[RangeList],
    p: &LocalDrag,
) {
    use std::arch::x86_64::*;

    use super::avx::{add_iso, add_rank1, h_of, load as get, padded, quads3, store, widen as load};

    /// All lanes set where `on`, else none.
    #[target_feature(enable = "avx2,fma")]
    fn mask(on: bool) -> __m256d {
        _mm256_castsi256_pd(_mm256_set1_epi64x(if on { -1 } else { 0 }))
    }

    let zero = _mm256_setzero_pd();
    let neg = _mm256_set1_pd(-0.0);
    let alpha = _mm256_set1_pd(p.alpha);
    let beta = p.beta.map(|b| _mm256_set1_pd(b));
    let w = p.w.map(|w| _mm256_set1_pd(w));
    let (kq, lin) = (_mm256_set1_pd(p.kq), _mm256_set1_pd(p.lin));
    let mut iso = acc.iso.each_ref().map(|v| get(v));
    let mut gg = [zero; 21];
    if LINEAR {
        gg = acc.gg.each_ref().map(|v| get(v));
    }
    // What the closed forms added for a list's texels: the quadratic and
    // linear parts' masks, and whether either.
    type Quad<'a> = &'a [f32; LANES];
    let mut group = |xs: [Quad; 3], avs: [Quad; 3], valid: __m256d, added: (__m256d, __m256d, bool)| {
        let (added_q, added_l, anything_added) = added;
        let x = xs.map(|v| load(v));
        let d = _mm256_add_pd(alpha, _mm256_mul_pd(beta[0], x[0]));
        let d = _mm256_add_pd(d, _mm256_mul_pd(beta[1], x[1]));
        let d = _mm256_add_pd(d, _mm256_mul_pd(beta[2], x[2]));
        let wet = _mm256_and_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(d, zero), valid);
        if !anything_added && _mm256_movemask_pd(wet) == 0 {
            return;
        }
        let a = avs.map(|v| load(v));
        let h = h_of(&x, &a);
        let mut s = zero;
        let mut any = zero;
        if QUADRATIC {
            let mut f = _mm256_mul_pd(h[0], w[0]);
            for j in 1..6 {
                f = _mm256_fmadd_pd(h[j], w[j], f);
            }
            let taken = _mm256_and_pd(wet, _mm256_cmp_pd::<_CMP_GT_OQ>(f, zero));
            let kf = _mm256_mul_pd(kq, f);
            let signed = _mm256_blendv_pd(_mm256_xor_pd(kf, neg), kf, taken);
            let counted = _mm256_and_pd(_mm256_xor_pd(taken, added_q), valid);
            s = _mm256_and_pd(signed, counted);
            any = counted;
        }
        let mut wl = zero;
        if LINEAR {
            let counted = _mm256_and_pd(_mm256_xor_pd(wet, added_l), valid);
            any = _mm256_or_pd(any, counted);
            if _mm256_movemask_pd(any) == 0 {
                return;
            }
            let aa = _mm256_fmadd_pd(a[2], a[2], _mm256_fmadd_pd(a[1], a[1], _mm256_mul_pd(a[0], a[0])));
            let area = _mm256_sqrt_pd(aa);
            let counted = _mm256_and_pd(counted, _mm256_cmp_pd::<_CMP_GT_OQ>(area, zero));
            let ds = _mm256_mul_pd(lin, area);
            let dw = _mm256_div_pd(lin, area);
            let ds = _mm256_blendv_pd(_mm256_xor_pd(ds, neg), ds, wet);
            let dw = _mm256_blendv_pd(_mm256_xor_pd(dw, neg), dw, wet);
            s = _mm256_add_pd(s, _mm256_and_pd(ds, counted));
            wl = _mm256_and_pd(dw, counted);
        } else if _mm256_movemask_pd(any) == 0 {
            return;
        }
        add_iso(&mut iso, s, &x);
        if LINEAR {
            add_rank1(&mut gg, wl, &h);
        }
    };
    let all = mask(true);
    for (range, added) in lists.iter().flat_map(|(ranges, added)| {
        let masks = (
            mask(added.quadratic),
            mask(added.linear),
            added.quadratic || added.linear,
        );
        ranges.iter().map(move |r| (r, masks))
    }) {
        let (start, end) = (range.start, range.end);
        let whole = end - (end - start) % LANES;
        let (x, a) = (quads3(t.xs, start..whole), quads3(t.avs, start..whole));
        for k in 0..x[0].len() {
            group(
                [&x[0][k], &x[1][k], &x[2][k]],
                [&a[0][k], &a[1][k], &a[2][k]],
                all,
                added,
            );
        }
        if whole < end {
            let k = end - whole;
            let pad = |v: &[f32]| padded(&v[whole..end]);
            let (xs, avs) = (t.xs.map(pad), t.avs.map(pad));
            let valid = _mm256_castsi256_pd(_mm256_setr_epi64x(
                -1,
                if k > 1 { -1 } else { 0 },
                if k > 2 { -1 } else { 0 },
                0,
            ));
            group(xs.each_ref(), avs.each_ref(), valid, added);
        }
    }
    for (out, v) in acc.iso.iter_mut().zip(iso) {
        *out = store(v);
    }
    if LINEAR {
        for (out, v) in acc.gg.iter_mut().zip(gg) {
            *out = store(v);
        }
    }
}

/// The kernel over the texels of `range`, [`LANES`] at a time, multiply-adds
/// fused where `FMA`.
#[inline(always)]
fn drag_lanes_generic<const FMA: bool, const LINEAR: bool, const QUADRATIC: bool>(
    acc: &mut DragLanes,
    t: &DragColumns,
    range: std::ops::Range<usize>,
    p: &LocalDrag,
    added: Added,
) {
    let (start, n) = (range.start, range.end);
    let whole = n - (n - start) % LANES;
    let load = |v: &[f32], i: usize| -> Lanes {
        let v: &[f32; LANES] = v[i..i + LANES].try_into().expect("a slice of LANES floats");
        v.map(f64::from)
    };
    for i in (start..whole).step_by(LANES) {
        let x = t.xs.map(|v| load(v, i));
        let a = t.avs.map(|v| load(v, i));
        drag_group::<FMA, LINEAR, QUADRATIC>(acc, p, added, &x, &a, &[true; LANES]);
    }
    if whole < n {
        let mut x = [[0.0; LANES]; 3];
        let mut a = [[0.0; LANES]; 3];
        let mut valid = [false; LANES];
        for (k, i) in (whole..n).enumerate() {
            for c in 0..3 {
                x[c][k] = f64::from(t.xs[c][i]);
                a[c][k] = f64::from(t.avs[c][i]);
            }
            valid[k] = true;
        }
        drag_group::<FMA, LINEAR, QUADRATIC>(acc, p, added, &x, &a, &valid);
    }
}

/// Lanes from a function of the lane.
#[inline(always)]
pub(super) fn lanes(f: impl FnMut(usize) -> f64) -> Lanes {
    std::array::from_fn(f)
}

/// `a b + c`, fused where `FMA`.
#[inline(always)]
pub(super) fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA { a.mul_add(b, c) } else { a * b + c }
}

/// One group of texels (see [`add_drag_ranges`]).
#[inline(always)]
fn drag_group<const FMA: bool, const LINEAR: bool, const QUADRATIC: bool>(
    acc: &mut DragLanes,
    p: &LocalDrag,
    added: Added,
    x: &[Lanes; 3],
    a: &[Lanes; 3],
    valid: &[bool; LANES],
) {
    let d = lanes(|k| p.alpha + p.beta[0] * x[0][k] + p.beta[1] * x[1][k] + p.beta[2] * x[2][k]);
    let wet: [bool; LANES] = std::array::from_fn(|k| valid[k] && d[k] > 0.0);
    if !added.linear && !added.quadratic && !wet.iter().fold(false, |any, &w| any | w) {
        return;
    }
    let h = [
        a[0],
        a[1],
        a[2],
        lanes(|k| x[1][k] * a[2][k] - x[2][k] * a[1][k]),
        lanes(|k| x[2][k] * a[0][k] - x[0][k] * a[2][k]),
        lanes(|k| x[0][k] * a[1][k] - x[1][k] * a[0][k]),
    ];
    let mut s = [0.0; LANES];
    let mut any = false;
    if QUADRATIC {
        let w = &p.w;
        let f = lanes(|k| {
            let mut f = h[0][k] * w[0];
            for j in 1..6 {
                f = madd::<FMA>(h[j][k], w[j], f);
            }
            f
        });
        s = std::array::from_fn(|k| {
            let taken = wet[k] && f[k] > 0.0;
            let kf = p.kq * f[k];
            if !valid[k] || taken == added.quadratic {
                0.0
            } else if taken {
                kf
            } else {
                -kf
            }
        });
        any = (0..LANES).any(|k| valid[k] && (wet[k] && f[k] > 0.0) != added.quadratic);
    }
    let mut w = [0.0; LANES];
    if LINEAR {
        let counted: [bool; LANES] = std::array::from_fn(|k| valid[k] && wet[k] != added.linear);
        if !any && !counted.iter().any(|&c| c) {
            return;
        }
        let area =
            lanes(|k| madd::<FMA>(a[2][k], a[2][k], madd::<FMA>(a[1][k], a[1][k], a[0][k] * a[0][k])).sqrt());
        for k in 0..LANES {
            let counted = counted[k] && area[k] > 0.0;
            let sign = if wet[k] { 1.0 } else { -1.0 };
            let (ds, dw) = (sign * (p.lin * area[k]), sign * (p.lin / area[k]));
            s[k] += if counted { ds } else { 0.0 };
            w[k] = if counted { dw } else { 0.0 };
        }
    } else if !any {
        return;
    }
    add_iso_lanes::<FMA>(&mut acc.iso, &s, x);
    if LINEAR {
        add_rank1_lanes::<FMA>(&mut acc.gg, &w, &h);
    }
}

/// Adds `s (1, x, x xᵀ)` lane by lane to [`DragAcc::iso`]'s sums (in its
/// order), multiply-adds fused where `FMA`.
#[inline(always)]
pub(super) fn add_iso_lanes<const FMA: bool>(iso: &mut [Lanes; 10], s: &Lanes, x: &[Lanes; 3]) {
    let sr = [
        lanes(|k| s[k] * x[0][k]),
        lanes(|k| s[k] * x[1][k]),
        lanes(|k| s[k] * x[2][k]),
    ];
    for k in 0..LANES {
        iso[0][k] += s[k];
        iso[1][k] += sr[0][k];
        iso[2][k] += sr[1][k];
        iso[3][k] += sr[2][k];
        iso[4][k] = madd::<FMA>(sr[0][k], x[0][k], iso[4][k]);
        iso[5][k] = madd::<FMA>(sr[1][k], x[1][k], iso[5][k]);
        iso[6][k] = madd::<FMA>(sr[2][k], x[2][k], iso[6][k]);
        iso[7][k] = madd::<FMA>(sr[0][k], x[1][k], iso[7][k]);
        iso[8][k] = madd::<FMA>(sr[1][k], x[2][k], iso[8][k]);
        iso[9][k] = madd::<FMA>(sr[2][k], x[0][k], iso[9][k]);
    }
}

/// Adds `w h hᵀ` lane by lane to [`DragAcc::gg`]'s upper triangle (row by
/// row), multiply-adds fused where `FMA`.
#[inline(always)]
pub(super) fn add_rank1_lanes<const FMA: bool>(gg: &mut [Lanes; 21], w: &Lanes, h: &[Lanes; 6]) {
    let mut m = 0;
    for i in 0..6 {
        let wh = lanes(|k| w[k] * h[i][k]);
        for hj in &h[i..] {
            for k in 0..LANES {
                gg[m][k] = madd::<FMA>(wh[k], hj[k], gg[m][k]);
            }
            m += 1;
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
        self.add_linear_difference(to, from);
        self.add_quadratic_difference(to, from);
    }

    /// [`DragMoments::add_difference`] of the skin friction's moments
    /// alone (`linear`), for sums only [`DragMoments::add_linear`] reads.
    pub(crate) fn add_linear_difference(&mut self, to: &Self, from: &Self) {
        for ((m, t), f) in self.linear.iter_mut().zip(&to.linear).zip(&from.linear) {
            *m += t - f;
        }
    }

    /// [`DragMoments::add_difference`] of the quadratic part's moments
    /// alone (`quadratic`), for sums only [`DragMoments::add_quadratic`]
    /// reads.
    pub(crate) fn add_quadratic_difference(&mut self, to: &Self, from: &Self) {
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

    /// The moments of tile `ti` from the running sums `prefix`.
    pub(crate) fn of_tile(prefix: &[Self], ti: usize) -> Self {
        let mut m = Self::default();
        m.add_difference(&prefix[ti + 1], &prefix[ti]);
        m
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
    /// Grows the box around a texel at `x` with area vector `a`: around
    /// its `h / |A|`, whose facing has the sign of `h`'s and which varies
    /// over a tile far less than `h` (texels cut by a chart's edge have
    /// small areas). A texel of no area never faces the flow and adds
    /// nothing to any closed form: it is left out.
    pub(crate) fn add_texel(&mut self, x: &Vector3<f64>, a: &Vector3<f64>) {
        let area = a.norm();
        if area <= 0.0 {
            return;
        }
        let h = h_of(&[x.x, x.y, x.z], &[a.x, a.y, a.z]).map(|h| h / area);
        for ((lo, hi), h) in self.lo.iter_mut().zip(&mut self.hi).zip(h) {
            *lo = lo.min(h);
            *hi = hi.max(h);
        }
    }

    /// Grows the box around another.
    pub(crate) fn add(&mut self, o: &HBox) {
        for j in 0..6 {
            self.lo[j] = self.lo[j].min(o.lo[j]);
            self.hi[j] = self.hi[j].max(o.hi[j]);
        }
    }

    /// The box as its centre and half-widths, for [`FacingBounds::facing`].
    pub(crate) fn bounds(&self) -> FacingBounds {
        FacingBounds {
            mid: std::array::from_fn(|j| 0.5 * (self.lo[j] + self.hi[j])),
            half: std::array::from_fn(|j| 0.5 * (self.hi[j] - self.lo[j])),
        }
    }
}

/// An [`HBox`] as its centre and half-widths: `h·w` over it lies within
/// `mid·w ± half·|w|`, a few multiply-adds on six lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FacingBounds {
    mid: [f64; 6],
    half: [f64; 6],
}

impl FacingBounds {
    /// Where `h·w` lies over the box. The bounds are widened by a relative
    /// 1e-12 so that a texel whose own facing rounds the other way (or a
    /// centre and half-width rounded off the box's faces) is not
    /// misplaced. An empty box (no texel of any area) is mixed.
    #[inline]
    pub(crate) fn facing(&self, w: &[f64; 6]) -> Facing {
        self.facing_within(w, 0.0)
    }

    /// [`FacingBounds::facing`] with each texel's facing per unit area
    /// (`h·w / |A|`) free to differ from the box's by up to `spread` more
    /// (m/s): for a fluid whose velocity varies over the texels.
    #[inline]
    pub(crate) fn facing_within(&self, w: &[f64; 6], spread: f64) -> Facing {
        // Each sum of six in pairs (three additions deep, not six: the
        // walk over a body's tiles waits on this test for each of them).
        let c: [f64; 6] = std::array::from_fn(|j| self.mid[j] * w[j]);
        let r: [f64; 6] = std::array::from_fn(|j| self.half[j] * w[j].abs());
        let sum = |v: [f64; 6]| ((v[0] + v[1]) + (v[2] + v[3])) + (v[4] + v[5]);
        let (centre, reach) = (sum(c), sum(r));
        let size = sum(c.map(f64::abs)) + reach;
        let margin = 1e-12 * size;
        let reach = reach + spread;
        if centre - reach > margin {
            Facing::All
        } else if centre + reach <= -margin {
            Facing::None
        } else {
            Facing::Mixed
        }
    }
}

#[cfg(test)]
mod tests;
