//! The sea kernel: the buoyancy sums of a body under a sampled surface
//! ([`SurfacePatch`]), texels taken four at a time with AVX2 and FMA.
//!
//! The same sums as the per-texel loop of the general path reading the
//! patch (`general_sums` in `evaluation`), which is the portable form and
//! the reference: world-frame sums (the texel's offset `r = R x` from the
//! atlas origin, its area vector `R a`), the depth `h(X, Z) − Y` read from
//! the bicubic polynomial of the patch's cell. Neighbouring texels of the
//! atlas lie close together on the body, so the four of a group nearly
//! always fall in one cell of the patch: its sixteen coefficients are then
//! read once for the group, and a group spread over several cells reads
//! each lane's on its own. The lanes are summed in a fixed order at the
//! end: on one machine the same bits run after run, for any thread count;
//! against the portable loop the sums differ in their last bits (fused
//! multiply-adds, another order of additions, and Archimedes' depth weight
//! `Σ ln min(d/δ, 1)` taken as the logarithm of a running product,
//! renormalised before it could underflow).
//!
//! A texel range that lies within a disc small against the waves (a tile
//! of the tiled path) may read the surface from one [`Taylor`] polynomial
//! about the disc's centre instead of the patch's cells: the cell's
//! bicubic to third order, a few multiply-adds a texel where the cell's
//! read gathers and evaluates sixteen coefficients.

use std::ops::Range;

use nalgebra::{Matrix3, Vector3};
use soak_bake::Atlas;

use super::sums::BuoyancySums;
use crate::water::SurfacePatch;

/// Whether this processor runs [`add_sea_range`].
pub(crate) fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// One evaluation's constants for the kernel (world frame).
pub(crate) struct SeaFrame<'a> {
    /// Object → world rotation.
    pub rot: Matrix3<f64>,
    /// World position of the atlas origin, m.
    pub ow: Vector3<f64>,
    /// The centre of mass's offset from the atlas origin, world axes, m.
    pub com: Vector3<f64>,
    /// A texel at or above this height is dry without a read, m.
    pub top: f64,
    /// Depth past which a texel counts as deep, m.
    pub delta: f64,
    /// The sampled surface.
    pub patch: &'a SurfacePatch,
    /// Archimedes' slope sums (`wrs`, `ayr`, `shallow`) and `d2a`.
    pub archimedes: bool,
}

/// The patch's surface about one world point `(x₀, z₀)` to third order:
/// `h₀ + s·Δ + ½ Δᵀ H Δ + ⅙ D³h[Δ, Δ, Δ]` with `Δ = (x − x₀, z − z₀)`,
/// and its slope `s + H Δ + ½ D³h[Δ, Δ]` (the derivatives those of
/// [`SurfacePatch::taylor`] at the point).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Taylor {
    /// The point `(x₀, z₀)`, world, m.
    pub at: [f64; 2],
    /// Height there, m.
    pub h: f64,
    /// Slope `(∂f/∂x, ∂f/∂z)`.
    pub slope: [f64; 2],
    /// `(f_xx, f_xz, f_zz)`, 1/m.
    pub hess: [f64; 3],
    /// `(f_xxx, f_xxz, f_xzz, f_zzz)`, 1/m².
    pub third: [f64; 4],
}

impl Taylor {
    /// The polynomial of `patch` about `(x, z)`.
    pub fn of(patch: &SurfacePatch, x: f64, z: f64) -> Self {
        let (h, slope, hess, third) = patch.taylor(x, z);
        Self {
            at: [x, z],
            h,
            slope,
            hess,
            third,
        }
    }

    /// Height (m) and slope at `(x, z)`, world: the portable form of what
    /// the kernel reads, and its reference.
    #[cfg(test)]
    pub fn height_slope(&self, x: f64, z: f64) -> (f64, [f64; 2]) {
        let (dx, dz) = (x - self.at[0], z - self.at[1]);
        let [hxx, hxz, hzz] = self.hess;
        let [xxx, xxz, xzz, zzz] = self.third;
        // ½ D³h[Δ, Δ], component by component.
        let (xx, xz, zz) = (dx * dx, dx * dz, dz * dz);
        let cx = 0.5 * xxx * xx + xxz * xz + 0.5 * xzz * zz;
        let cz = 0.5 * xxz * xx + xzz * xz + 0.5 * zzz * zz;
        let (hx, hz) = (hxx * dx + hxz * dz, hxz * dx + hzz * dz);
        let [sx, sz] = self.slope;
        let h = self.h + dx * (sx + 0.5 * hx + cx / 3.0) + dz * (sz + 0.5 * hz + cz / 3.0);
        (h, [sx + hx + cx, sz + hz + cz])
    }
}

/// What [`add_sea_range`] takes of each texel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SeaRead {
    /// The buoyancy sums (and the depths where asked).
    Sums,
    /// The depths alone: nothing is added to the sums.
    Depths,
}

/// Adds the submerged texels of `range` to `s`, as the general path adds
/// them (`add_texel`, and in Archimedes mode the slope sums), the surface
/// read from the patch's cells or, where `taylor` is given, from that
/// polynomial; where `depths` is given (as long as `range`) it receives
/// every texel's depth, `≤ 0` for a dry one; with [`SeaRead::Depths`]
/// nothing else. Call only where [`available`].
pub(crate) fn add_sea_range(
    s: &mut BuoyancySums,
    atlas: &Atlas,
    range: Range<usize>,
    frame: &SeaFrame,
    taylor: Option<&Taylor>,
    read: SeaRead,
    depths: Option<&mut [f64]>,
) {
    #[cfg(target_arch = "x86_64")]
    {
        if available() {
            // SAFETY: the processor has AVX2 and FMA, checked just above.
            #[allow(unsafe_code)]
            unsafe {
                match (read, frame.archimedes, taylor) {
                    (SeaRead::Depths, _, None) => {
                        avx2::add::<false, false, false>(s, atlas, range, frame, None, depths)
                    }
                    (SeaRead::Depths, _, t) => {
                        avx2::add::<false, false, true>(s, atlas, range, frame, t, depths)
                    }
                    (SeaRead::Sums, true, None) => {
                        avx2::add::<true, true, false>(s, atlas, range, frame, None, depths)
                    }
                    (SeaRead::Sums, true, t) => {
                        avx2::add::<true, true, true>(s, atlas, range, frame, t, depths)
                    }
                    (SeaRead::Sums, false, None) => {
                        avx2::add::<true, false, false>(s, atlas, range, frame, None, depths)
                    }
                    (SeaRead::Sums, false, t) => {
                        avx2::add::<true, false, true>(s, atlas, range, frame, t, depths)
                    }
                }
            }
            return;
        }
    }
    let _ = (s, atlas, range, frame, taylor, read, depths);
    unreachable!("add_sea_range called where AVX2 and FMA are not available");
}

/// Running products of `min(d/δ, 1)` are folded into the sum of their
/// logarithms before they fall below this.
const RENORMALISE: f64 = 1e-200;

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64::*;
    use std::ops::Range;

    use nalgebra::Vector3;
    use soak_bake::Atlas;

    use super::{RENORMALISE, SeaFrame, Taylor};
    use crate::hydrostatics::avx::{load as vector_of, padded, quads, quads3, store as lanes, widen as load};
    use crate::hydrostatics::sums::BuoyancySums;

    const LANES: usize = 4;

    /// The running sums, one per lane.
    struct Acc {
        vol: __m256d,
        wr: [__m256d; 3],
        wd: __m256d,
        area: __m256d,
        count: __m256d,
        f: [__m256d; 3],
        rxf: [__m256d; 3],
        d2a: [__m256d; 3],
        wrs: [__m256d; 3],
        ayr: __m256d,
        product: __m256d,
        shallow: [f64; LANES],
    }

    /// `SUMS`: add the sums (else the depths alone); `TAYLOR`: read the
    /// surface from `taylor` (given) rather than the patch's cells.
    #[target_feature(enable = "avx2,fma")]
    pub(super) fn add<const SUMS: bool, const ARCHIMEDES: bool, const TAYLOR: bool>(
        s: &mut BuoyancySums,
        atlas: &Atlas,
        range: Range<usize>,
        frame: &SeaFrame,
        taylor: Option<&Taylor>,
        mut depths: Option<&mut [f64]>,
    ) {
        let xs = atlas.local_positions().columns(0..atlas.len());
        let avs = atlas.area_vectors().columns(0..atlas.len());
        let areas = atlas.areas();
        let crate::water::PatchGrid {
            origin,
            spacing,
            cells,
            coefficients,
        } = frame.patch.grid();
        let inv = 1.0 / spacing;

        let zero = _mm256_setzero_pd();
        let one = _mm256_set1_pd(1.0);
        let rot: [[__m256d; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| _mm256_set1_pd(frame.rot[(i, j)])));
        let ow = [0, 1, 2].map(|c| _mm256_set1_pd(frame.ow[c]));
        let com = [0, 1, 2].map(|c| _mm256_set1_pd(frame.com[c]));
        let top = _mm256_set1_pd(frame.top);
        let ox = _mm256_set1_pd(origin[0]);
        let oz = _mm256_set1_pd(origin[1]);
        let inv_v = _mm256_set1_pd(inv);
        let max_x = _mm256_set1_pd(cells[0] as f64);
        let max_z = _mm256_set1_pd(cells[1] as f64);
        let last_x = _mm256_set1_pd((cells[0] - 1) as f64);
        let last_z = _mm256_set1_pd((cells[1] - 1) as f64);
        let cx = _mm256_set1_pd(cells[0] as f64);
        let inv_delta = _mm256_set1_pd(1.0 / frame.delta);
        let renormalise = _mm256_set1_pd(RENORMALISE);
        let three = _mm256_set1_pd(3.0);
        let two = _mm256_set1_pd(2.0);

        let mut acc = Acc {
            vol: zero,
            wr: [zero; 3],
            wd: zero,
            area: zero,
            count: zero,
            f: [zero; 3],
            rxf: [zero; 3],
            d2a: [zero; 3],
            wrs: [zero; 3],
            ayr: zero,
            product: one,
            shallow: [0.0; LANES],
        };

        // Height and slope of the patch at four points `(x, z)` (world).
        let surface = |x: __m256d, z: __m256d| -> (__m256d, __m256d, __m256d) {
            let gx = _mm256_min_pd(
                _mm256_max_pd(_mm256_mul_pd(_mm256_sub_pd(x, ox), inv_v), zero),
                max_x,
            );
            let gz = _mm256_min_pd(
                _mm256_max_pd(_mm256_mul_pd(_mm256_sub_pd(z, oz), inv_v), zero),
                max_z,
            );
            let ix = _mm256_min_pd(_mm256_floor_pd(gx), last_x);
            let iz = _mm256_min_pd(_mm256_floor_pd(gz), last_z);
            let u = _mm256_sub_pd(gx, ix);
            let v = _mm256_sub_pd(gz, iz);
            let cell = _mm256_fmadd_pd(iz, cx, ix);
            let first = _mm256_permute4x64_pd::<0>(cell);
            let same = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_EQ_OQ>(cell, first)) == 0b1111;
            // The coefficient a[p][q] of every lane: broadcast from the one
            // cell, or gathered lane by lane.
            let cells_of = lanes(cell).map(|c| c as usize);
            let coefficient = |p: usize, q: usize| -> __m256d {
                if same {
                    _mm256_set1_pd(coefficients[cells_of[0]][p][q])
                } else {
                    vector_of(&cells_of.map(|c| coefficients[c][p][q]))
                }
            };
            let mut c = [zero; 4];
            let mut dc = [zero; 4];
            for (p, (cp, dcp)) in c.iter_mut().zip(dc.iter_mut()).enumerate() {
                let (a0, a1, a2, a3) = (
                    coefficient(p, 0),
                    coefficient(p, 1),
                    coefficient(p, 2),
                    coefficient(p, 3),
                );
                *cp = _mm256_fmadd_pd(_mm256_fmadd_pd(_mm256_fmadd_pd(a3, v, a2), v, a1), v, a0);
                *dcp = _mm256_fmadd_pd(
                    _mm256_fmadd_pd(_mm256_mul_pd(three, a3), v, _mm256_mul_pd(two, a2)),
                    v,
                    a1,
                );
            }
            let h = _mm256_fmadd_pd(_mm256_fmadd_pd(_mm256_fmadd_pd(c[3], u, c[2]), u, c[1]), u, c[0]);
            let hu = _mm256_fmadd_pd(
                _mm256_fmadd_pd(_mm256_mul_pd(three, c[3]), u, _mm256_mul_pd(two, c[2])),
                u,
                c[1],
            );
            let hv = _mm256_fmadd_pd(
                _mm256_fmadd_pd(_mm256_fmadd_pd(dc[3], u, dc[2]), u, dc[1]),
                u,
                dc[0],
            );
            (h, _mm256_mul_pd(hu, inv_v), _mm256_mul_pd(hv, inv_v))
        };

        // The same from the polynomial about one point (`Taylor`), its
        // coefficients broadcast once.
        let t = taylor.copied().unwrap_or(Taylor {
            at: [0.0; 2],
            h: 0.0,
            slope: [0.0; 2],
            hess: [0.0; 3],
            third: [0.0; 4],
        });
        let [tx, tz, th] = [t.at[0], t.at[1], t.h].map(|v| _mm256_set1_pd(v));
        let [tsx, tsz] = t.slope.map(|v| _mm256_set1_pd(v));
        let [hxx, hxz, hzz] = t.hess.map(|v| _mm256_set1_pd(v));
        let [xxx, xxz, xzz, zzz] = t.third;
        let [cxx, cxz, czz] = [0.5 * xxx, xxz, 0.5 * xzz].map(|v| _mm256_set1_pd(v));
        let [dxx, dxz, dzz] = [0.5 * xxz, xzz, 0.5 * zzz].map(|v| _mm256_set1_pd(v));
        let half = _mm256_set1_pd(0.5);
        let third = _mm256_set1_pd(1.0 / 3.0);
        let polynomial = |x: __m256d, z: __m256d| -> (__m256d, __m256d, __m256d) {
            let dx = _mm256_sub_pd(x, tx);
            let dz = _mm256_sub_pd(z, tz);
            let (xx, xz, zz) = (
                _mm256_mul_pd(dx, dx),
                _mm256_mul_pd(dx, dz),
                _mm256_mul_pd(dz, dz),
            );
            // ½ D³h[Δ, Δ] and H Δ, component by component.
            let cx = _mm256_fmadd_pd(czz, zz, _mm256_fmadd_pd(cxz, xz, _mm256_mul_pd(cxx, xx)));
            let cz = _mm256_fmadd_pd(dzz, zz, _mm256_fmadd_pd(dxz, xz, _mm256_mul_pd(dxx, xx)));
            let hx = _mm256_fmadd_pd(hxz, dz, _mm256_mul_pd(hxx, dx));
            let hz = _mm256_fmadd_pd(hzz, dz, _mm256_mul_pd(hxz, dx));
            let ex = _mm256_fmadd_pd(third, cx, _mm256_fmadd_pd(half, hx, tsx));
            let ez = _mm256_fmadd_pd(third, cz, _mm256_fmadd_pd(half, hz, tsz));
            let h = _mm256_fmadd_pd(dz, ez, _mm256_fmadd_pd(dx, ex, th));
            (
                h,
                _mm256_add_pd(tsx, _mm256_add_pd(hx, cx)),
                _mm256_add_pd(tsz, _mm256_add_pd(hz, cz)),
            )
        };

        // A vector of the body's axes in the world's: `rot v`, lane by lane.
        let turn = |v: [__m256d; 3]| -> [__m256d; 3] {
            std::array::from_fn(|i| {
                _mm256_fmadd_pd(
                    rot[i][2],
                    v[2],
                    _mm256_fmadd_pd(rot[i][1], v[1], _mm256_mul_pd(rot[i][0], v[0])),
                )
            })
        };
        // One group of texels; `valid` masks the lanes that hold texels;
        // the depths of the lanes are returned.
        type Quad<'a> = &'a [f32; LANES];
        let mut group = |xs: [Quad; 3], avs: [Quad; 3], areas: Quad, valid: __m256d| -> [f64; LANES] {
            let r = turn(xs.map(|v| load(v)));
            let p = [
                _mm256_add_pd(ow[0], r[0]),
                _mm256_add_pd(ow[1], r[1]),
                _mm256_add_pd(ow[2], r[2]),
            ];
            let below = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(p[1], top), valid);
            if _mm256_movemask_pd(below) == 0 {
                return [-1.0; LANES];
            }
            let (h, sx, sz) = if TAYLOR {
                polynomial(p[0], p[2])
            } else {
                surface(p[0], p[2])
            };
            let depth = _mm256_sub_pd(h, p[1]);
            let taken = _mm256_and_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(depth, zero), below);
            // A dry lane reports a depth ≤ 0 (above the top: its height over it).
            let reported = lanes(_mm256_blendv_pd(_mm256_min_pd(depth, zero), depth, taken));
            if !SUMS || _mm256_movemask_pd(taken) == 0 {
                return reported;
            }
            let d = _mm256_and_pd(depth, taken);
            let area = _mm256_and_pd(load(areas), taken);
            acc.count = _mm256_add_pd(acc.count, _mm256_and_pd(one, taken));
            acc.area = _mm256_add_pd(acc.area, area);
            let aw = turn(avs.map(|v| load(v)));
            // w = −A_y d (zero on lanes not taken).
            let w = _mm256_mul_pd(_mm256_sub_pd(zero, aw[1]), d);
            acc.vol = _mm256_add_pd(acc.vol, w);
            acc.wr = std::array::from_fn(|c| _mm256_fmadd_pd(w, r[c], acc.wr[c]));
            acc.wd = _mm256_fmadd_pd(w, d, acc.wd);
            if ARCHIMEDES {
                let dd = _mm256_mul_pd(d, d);
                acc.d2a = std::array::from_fn(|c| _mm256_fmadd_pd(dd, aw[c], acc.d2a[c]));
                // ρ × s with ρ = r − (c − o), s = (s_x, 0, s_z):
                // (ρ_y s_z, ρ_z s_x − ρ_x s_z, −ρ_y s_x).
                let rho = [
                    _mm256_sub_pd(r[0], com[0]),
                    _mm256_sub_pd(r[1], com[1]),
                    _mm256_sub_pd(r[2], com[2]),
                ];
                let wy = _mm256_mul_pd(w, rho[1]);
                acc.wrs[0] = _mm256_fmadd_pd(wy, sz, acc.wrs[0]);
                acc.wrs[1] = _mm256_fmadd_pd(
                    w,
                    _mm256_fmsub_pd(rho[2], sx, _mm256_mul_pd(rho[0], sz)),
                    acc.wrs[1],
                );
                acc.wrs[2] = _mm256_fnmadd_pd(wy, sx, acc.wrs[2]);
                acc.ayr = _mm256_fmadd_pd(_mm256_and_pd(aw[1], taken), r[1], acc.ayr);
                // Π min(d/δ, 1) over the taken lanes.
                let factor =
                    _mm256_blendv_pd(one, _mm256_min_pd(_mm256_mul_pd(depth, inv_delta), one), taken);
                acc.product = _mm256_mul_pd(acc.product, factor);
                if _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(acc.product, renormalise)) != 0 {
                    let mut product = lanes(acc.product);
                    for (k, pk) in product.iter_mut().enumerate() {
                        if *pk < RENORMALISE {
                            acc.shallow[k] += pk.ln();
                            *pk = 1.0;
                        }
                    }
                    acc.product = vector_of(&product);
                }
            } else {
                // Σ −d A and Σ r × (−d A), the signs applied at the end.
                let da = [
                    _mm256_mul_pd(d, aw[0]),
                    _mm256_mul_pd(d, aw[1]),
                    _mm256_mul_pd(d, aw[2]),
                ];
                acc.f = std::array::from_fn(|c| _mm256_add_pd(acc.f[c], da[c]));
                acc.rxf[0] = _mm256_fmadd_pd(r[1], da[2], _mm256_fnmadd_pd(r[2], da[1], acc.rxf[0]));
                acc.rxf[1] = _mm256_fmadd_pd(r[2], da[0], _mm256_fnmadd_pd(r[0], da[2], acc.rxf[1]));
                acc.rxf[2] = _mm256_fmadd_pd(r[0], da[1], _mm256_fnmadd_pd(r[1], da[0], acc.rxf[2]));
            }
            reported
        };

        let all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
        let (start, end) = (range.start, range.end);
        // One call of `group` in the loop (the last texels of the range, a
        // group of their own, read from padded copies): the compiler then
        // keeps the running sums in registers.
        let (x, a) = (quads3(xs, start..end), quads3(avs, start..end));
        let ar = quads(areas, start..end);
        let groups = ar.len() + usize::from(ar.len() * LANES < end - start);
        for q in 0..groups {
            let i = start + q * LANES;
            let k = (end - i).min(LANES);
            let (pxs, pavs, pareas);
            let (gx, ga, gar, valid) = if q < ar.len() {
                (
                    [&x[0][q], &x[1][q], &x[2][q]],
                    [&a[0][q], &a[1][q], &a[2][q]],
                    &ar[q],
                    all,
                )
            } else {
                let pad = |v: &[f32]| padded(&v[i..end]);
                (pxs, pavs, pareas) = (xs.map(pad), avs.map(pad), pad(areas));
                let valid = _mm256_castsi256_pd(_mm256_setr_epi64x(
                    -1,
                    if k > 1 { -1 } else { 0 },
                    if k > 2 { -1 } else { 0 },
                    0,
                ));
                (pxs.each_ref(), pavs.each_ref(), &pareas, valid)
            };
            let d = group(gx, ga, gar, valid);
            if let Some(out) = depths.as_deref_mut() {
                out[i - start..i - start + k].copy_from_slice(&d[..k]);
            }
        }

        if !SUMS {
            return;
        }
        let sum = |v: __m256d| {
            let l = lanes(v);
            (l[0] + l[1]) + (l[2] + l[3])
        };
        let sum3 = |v: &[__m256d; 3]| Vector3::new(sum(v[0]), sum(v[1]), sum(v[2]));
        s.vol += sum(acc.vol);
        s.wr += sum3(&acc.wr);
        s.wd2 += 0.5 * sum(acc.wd);
        s.area += sum(acc.area);
        s.count += sum(acc.count) as usize;
        if ARCHIMEDES {
            s.d2a += 0.5 * sum3(&acc.d2a);
            s.slope.wrs += sum3(&acc.wrs);
            s.slope.ayr += sum(acc.ayr);
            let product = lanes(acc.product);
            s.slope.shallow += (0..LANES)
                .map(|k| acc.shallow[k] + product[k].ln())
                .fold(0.0, |a, b| a + b);
        } else {
            s.f -= sum3(&acc.f);
            s.rxf -= sum3(&acc.rxf);
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Isometry3, UnitQuaternion, Vector3};
    use soak_bake::{Atlas, BakeOptions, builtin};

    use super::*;
    use crate::hydrostatics::frame::texel;
    use crate::water::{Gerstner, GerstnerWave, Surface};

    fn sea() -> Gerstner {
        Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.81).unwrap()
    }

    /// The plain per-texel sums the general path adds, over `range`, the
    /// surface read from the patch or from `taylor`.
    fn plain(
        atlas: &Atlas,
        frame: &SeaFrame,
        range: Range<usize>,
        taylor: Option<&Taylor>,
        depths: &mut Vec<f64>,
    ) -> BuoyancySums {
        let mut s = BuoyancySums::default();
        for i in range {
            let (x, a) = texel(atlas, i);
            let r = frame.rot * x;
            let p = frame.ow + r;
            let (h, slope) = match taylor {
                Some(t) => t.height_slope(p.x, p.z),
                None => frame.patch.height_slope(p.x, p.z),
            };
            let d = h - p.y;
            depths.push(d);
            if p.y < frame.top && d > 0.0 {
                let aw = frame.rot * a;
                s.add_texel(&r, &aw, atlas.areas()[i] as f64, d);
                if frame.archimedes {
                    s.slope.add(&(r - frame.com), r.y, &aw, d, slope, frame.delta);
                }
            }
        }
        s
    }

    /// The kernel against the plain sums, for the boat cut by the swell,
    /// wholly under it and in the air, in both modes, the surface read
    /// from the patch's cells and from a polynomial about a point near the
    /// boat, over ranges of every length modulo the lanes (a short last
    /// group); and reading the depths alone, the same depths and nothing
    /// added.
    #[test]
    fn the_sea_kernel_adds_what_the_plain_sums_add() {
        if !available() {
            eprintln!("no AVX2 and FMA here: the sea kernel is not used, nothing to check");
            return;
        }
        let atlas = Atlas::bake(&builtin::boat(4.0, 1.2, 0.6), BakeOptions::square(96)).unwrap();
        let sea = sea();
        for (y, tilt) in [(0.0, 0.2), (-0.15, -0.3), (-2.0, 0.1), (3.0, 0.0)] {
            let pose = Isometry3::from_parts(
                Vector3::new(0.7, y, -0.4).into(),
                UnitQuaternion::from_euler_angles(tilt, 0.6, 0.1),
            );
            let rot = pose.rotation.to_rotation_matrix().into_inner();
            let ow = (pose * atlas.origin()).coords;
            let r = atlas.bounding_radius();
            let patch = SurfacePatch::sample(
                &sea,
                1.3,
                [ow.x - r - 0.3, ow.z - r - 0.3],
                [ow.x + r + 0.3, ow.z + r + 0.3],
                0.25,
                None,
            )
            .unwrap();
            let top = patch.height_bounds(0.0).unwrap().1;
            for archimedes in [true, false] {
                let frame = SeaFrame {
                    rot,
                    ow,
                    com: Vector3::new(0.1, -0.05, 0.02),
                    top,
                    delta: r,
                    patch: &patch,
                    archimedes,
                };
                let near = Taylor::of(&patch, ow.x + 0.3, ow.z - 0.2);
                for (len, taylor) in [
                    (atlas.len(), None),
                    (atlas.len() - 1, None),
                    (atlas.len() - 2, Some(&near)),
                    (atlas.len() - 3, Some(&near)),
                ] {
                    let mut want_depths = Vec::new();
                    let want = plain(&atlas, &frame, 0..len, taylor, &mut want_depths);
                    let mut alone = BuoyancySums::default();
                    let mut alone_depths = vec![0.0; len];
                    add_sea_range(
                        &mut alone,
                        &atlas,
                        0..len,
                        &frame,
                        taylor,
                        SeaRead::Depths,
                        Some(&mut alone_depths),
                    );
                    assert_eq!(alone.count, 0, "the depths alone add nothing");
                    assert_eq!(alone.vol, 0.0, "the depths alone add nothing");
                    let mut got = BuoyancySums::default();
                    let mut depths = vec![0.0; len];
                    add_sea_range(
                        &mut got,
                        &atlas,
                        0..len,
                        &frame,
                        taylor,
                        SeaRead::Sums,
                        Some(&mut depths),
                    );
                    assert_eq!(depths, alone_depths, "the same depths, summed or not");
                    assert_eq!(got.count, want.count, "y {y}");
                    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale.max(1e-300);
                    let vs = |a: &Vector3<f64>, b: &Vector3<f64>, scale: f64| {
                        (a - b).norm() <= 1e-12 * scale.max(1e-300)
                    };
                    let scale = want.area.max(1e-9);
                    assert!(close(got.vol, want.vol, scale), "vol {} vs {}", got.vol, want.vol);
                    assert!(vs(&got.wr, &want.wr, scale), "wr {} vs {}", got.wr, want.wr);
                    assert!(close(got.wd2, want.wd2, scale), "wd2");
                    assert!(close(got.area, want.area, scale), "area");
                    if archimedes {
                        assert!(vs(&got.d2a, &want.d2a, scale), "d2a {} vs {}", got.d2a, want.d2a);
                        assert!(vs(&got.slope.wrs, &want.slope.wrs, scale), "wrs");
                        assert!(close(got.slope.ayr, want.slope.ayr, scale), "ayr");
                        let sh = want.slope.shallow.abs().max(1.0);
                        assert!(
                            close(got.slope.shallow, want.slope.shallow, sh),
                            "shallow {} vs {}",
                            got.slope.shallow,
                            want.slope.shallow
                        );
                    } else {
                        assert!(vs(&got.f, &want.f, scale), "f {} vs {}", got.f, want.f);
                        assert!(vs(&got.rxf, &want.rxf, scale), "rxf {} vs {}", got.rxf, want.rxf);
                    }
                    for (k, (g, w)) in depths.iter().zip(&want_depths).enumerate() {
                        if *w > 0.0 {
                            assert!((g - w).abs() < 1e-12, "depth {k}: {g} vs {w}");
                        } else {
                            assert!(*g <= 0.0, "depth {k}: {g} for a dry texel");
                        }
                    }
                }
            }
        }
    }
}
