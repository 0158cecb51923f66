//! The planar kernel: the buoyancy sums of a body under planar water, texels
//! taken four at a time, in portable code and in an AVX2 form.
//!
//! Longer than the other files on purpose: the portable and the AVX2 forms
//! must do the same operations in the same order on the same lanes, and the
//! test that holds them to each other and to the plain per-texel sums sits
//! with them.

use nalgebra::Vector3;
use soak_bake::Atlas;

use super::sums::BuoyancySums;

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
#[derive(Default, Debug, PartialEq)]
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

    use super::avx::{padded, quads, quads3, store as lanes, widen as load};

    let zero = _mm256_setzero_pd();
    let one = _mm256_set1_pd(1.0);
    let alpha = _mm256_set1_pd(p.alpha);
    let b = p.beta.map(|b| _mm256_set1_pd(b));
    let g = p.g.map(|g| _mm256_set1_pd(g));
    let (mut vol, mut wd, mut area_sum, mut count) = (zero, zero, zero, zero);
    let (mut wr, mut f, mut rxf, mut d2a) = ([zero; 3], [zero; 3], [zero; 3], [zero; 3]);
    // One group of texels (`xs`, `avs`, `areas`), `valid` masking the
    // lanes that hold texels.
    type Quad<'a> = &'a [f32; LANES];
    let mut group = |xs: [Quad; 3], avs: [Quad; 3], areas: Quad, valid: __m256d| {
        let r = xs.map(|v| load(v));
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
        let area = _mm256_and_pd(load(areas), taken);
        count = _mm256_add_pd(count, _mm256_and_pd(one, taken));
        let da = [
            _mm256_mul_pd(d, load(avs[0])),
            _mm256_mul_pd(d, load(avs[1])),
            _mm256_mul_pd(d, load(avs[2])),
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
        let (x, a) = (quads3(t.xs, start..whole), quads3(t.avs, start..whole));
        let areas = quads(t.areas, start..whole);
        for k in 0..areas.len() {
            group(
                [&x[0][k], &x[1][k], &x[2][k]],
                [&a[0][k], &a[1][k], &a[2][k]],
                &areas[k],
                all,
            );
        }
        if whole < end {
            let k = end - whole;
            let pad = |v: &[f32]| padded(&v[whole..end]);
            let (xs, avs, areas) = (t.xs.map(pad), t.avs.map(pad), pad(t.areas));
            let valid = _mm256_castsi256_pd(_mm256_setr_epi64x(
                -1,
                if k > 1 { -1 } else { 0 },
                if k > 2 { -1 } else { 0 },
                0,
            ));
            group(xs.each_ref(), avs.each_ref(), &areas, valid);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hydrostatics::frame::texel;
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
                // The same bits as the fused generic code.
                // SAFETY: the processor has AVX2 and FMA, checked just above.
                #[allow(unsafe_code)]
                let same = unsafe {
                    [
                        planar_lanes_avx2::<true, false>(&p, &t, &ranges)
                            == generic::<true, true, false>(&p, &t, &ranges).0,
                        planar_lanes_avx2::<false, false>(&p, &t, &ranges)
                            == generic::<true, false, false>(&p, &t, &ranges).0,
                        planar_lanes_avx2::<true, true>(&p, &t, &ranges)
                            == generic::<true, true, true>(&p, &t, &ranges).0,
                        planar_lanes_avx2::<false, true>(&p, &t, &ranges)
                            == generic::<true, false, true>(&p, &t, &ranges).0,
                    ]
                };
                assert_eq!(same, [true; 4], "AVX2 against fused generic at level {y}");
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
