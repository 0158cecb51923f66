//! The tiled path on a sampled sea: tiles wholly under the waves in closed
//! form, from the surface's second-order Taylor polynomial over each.
//!
//! Under a [`SurfacePatch`] a texel's depth is `h(X, Z) − Y`. Over a tile,
//! whose world footprint is a disc of radius `ρ` (its bounding sphere's)
//! about the point `P` its centre `c` is carried to, `h` is its Taylor
//! polynomial `h₀ + s·Δ + ½ Δᵀ H Δ` (`Δ` the horizontal offset from `P`,
//! `s` the slope and `H` the second derivatives read from the patch at `P`)
//! within `K ρ³ / 6`, `K` the patch's [`SurfacePatch::cubic_bound`]. Since
//! `Δ = L (x − c)` is affine in the texel's object position `x` (`L` the
//! horizontal rows of the rotation), the depth is then an affine part
//! `α + β·x`, which the tile's moments integrate in closed form as under a
//! plane, and a quadratic part `δ(x) = ½ (x − c)ᵀ Q (x − c)` with
//! `Q = Lᵀ H L`:
//!
//! - the sums linear in the depth (`Σ w`, `Σ d A`) take it exactly, from
//!   the tile's second moments: `Σ A_j δ = ½ tr(Q Σ A_j (x − c)(x − c)ᵀ)`;
//! - those with a further factor `x` or `d` (`Σ w x`, `Σ x × d A`, `Σ w d`,
//!   `Σ d² A`) take it at the tile's centre, an error of second order in
//!   the tile's size times `δ`, itself second order;
//! - Archimedes' slope sums `Σ w ρ × s` take the slope across the tile as
//!   `s + H Δ + ½ D³h[Δ, Δ]` (the third derivatives read from the patch
//!   too), with the weight's first moment exactly and its second with the
//!   depth at the centre; `Σ A_y r_y` exactly.
//!
//! A tile is taken in closed form only when the remainder `K ρ³ / 6` is
//! within [`SEA_TILE_TOLERANCE`] of the body's bounding radius and the
//! polynomial (with that remainder) is positive over the whole disc; a
//! tile the waterline may cut, or too large against the waves' curvature,
//! goes through the sea kernel texel by texel (a tile within the tolerance
//! reads the surface there from the same polynomial, to third order, a few
//! multiply-adds a texel; a larger one from the patch's cells), and a tile
//! wholly above the waves is skipped. For a 1024² atlas of a half-metre body on a metres-long
//! swell the remainder is below a micrometre and nearly every tile under
//! water takes the closed form.

use std::ops::Range;

use nalgebra::{Matrix2, Matrix2x3, Matrix3, Vector2, Vector3};
use soak_bake::Atlas;

use super::{TileCounts, TiledAtlas, add_closed_form};
use crate::hydrostatics::frame::Frame;
use crate::hydrostatics::options::SeaVelocity;
use crate::hydrostatics::sea_drag::{LinearFluid, SeaDragFrame, SeaDragLanes, SeaDragSums};
use crate::hydrostatics::sea_kernel::{self, SeaFrame, SeaRead, Taylor, add_sea_range};
use crate::hydrostatics::sums::{BuoyancySums, SlopeSums};
use crate::parallel::par_fold;
use crate::water::{Surface, SurfacePatch};

/// How far the tiled path on a sampled sea lets the surface depart from
/// its second-order Taylor polynomial over a tile taken in closed form, as
/// a fraction of the body's bounding radius; and, over a tile the kernel
/// reads texel by texel, how far its texels may read the surface from that
/// polynomial (to third order) rather than from the patch's cells.
///
/// Over a tile whose footprint is a disc of radius `ρ`, the polynomial
/// `h₀ + s·Δ + ½ Δᵀ H Δ` read from the patch at the disc's centre makes the
/// depth affine plus quadratic in the texel's object position, which the
/// tile's moments integrate in closed form. Its remainder is estimated
/// from the third derivatives there as `|D³h| ρ³ / 3` (twice the cubic
/// term's largest size, for their change across the disc); a tile whose
/// estimate is above this fraction of the bounding radius goes through the
/// texels. The cubic term is odd about the tile's centre, so what the sums
/// feel of it is far smaller than the estimate. The tolerance is set
/// against the patch's own error, which is what the tiles add to: at 128²
/// on the two-wave swell (a 1 × 0.6 × 0.8 m box and a 0.3 m ball, six
/// poses afloat each in both buoyancy modes, 16 nodes per shortest wave;
/// `cargo test -p soak-hydro --test tiled_sea -- --nocapture` prints them)
/// the tiled read departs from the per-texel read of the same patch by at
/// most 9e-7 of the volume, 1.3e-6 of the force (of the displaced water's
/// weight), 6e-6 of the centre of buoyancy (of the bounding radius) and
/// 6e-6 of the torque (of the weight times the radius), where the patch
/// itself is 1.3e-5 to 1.9e-5 of the volume and 2e-5 of the force from
/// the exact surface. A tenth of this tolerance (1e-4, as it was) took
/// those departures to 9e-8, 1e-7, 7e-7 and 1.2e-6, with a fifth as many
/// tiles in closed form: most of each body's tiles at 128² went through
/// the patch's cells. The same test holds a sphere at 384² and the boat at
/// 256² to the per-texel read (within 1e-6 of the volume and the centre,
/// 1e-5 of the force and the torque); `soak accuracy` puts each read
/// against the exact inversion.
pub const SEA_TILE_TOLERANCE: f64 = 1e-3;

/// How far a tile's texels may read the surface from its polynomial in a
/// pass for the drag alone, as a fraction of the body's bounding radius.
///
/// That pass takes nothing of a texel's depth but its sign (whether the
/// texel is under water), and its texels are coarse: a depth off by the
/// polynomial's remainder, a few millimetres on a half-metre body, moves
/// only the texels that close to the waterline, a few per cent of a drag
/// texel's size (on the bench's box on its JONSWAP sea, the remainders of
/// its cut drag tiles are 0.1 to 0.7 mm and its drag the same to 15
/// digits). The polynomial's read costs a few multiply-adds a texel, the
/// patch's cells far more.
const SEA_DRAG_DEPTH_TOLERANCE: f64 = 1e-2;

/// One evaluation's constants.
struct SeaTiles<'a> {
    rot: Matrix3<f64>,
    /// The world's up in object axes.
    g: Vector3<f64>,
    /// The horizontal rows of `rot`: `Δ = L (x − c)`.
    l: Matrix2x3<f64>,
    /// The same rows `l₀`, `l₂` as vectors.
    rows: [Vector3<f64>; 2],
    /// `l₀l₀ᵀ`, `l₀l₂ᵀ + l₂l₀ᵀ` and `l₂l₂ᵀ`: `Q = Lᵀ H L` from `H`.
    ll: [Sym; 3],
    ow: Vector3<f64>,
    /// The centre of mass from the atlas origin, world axes, m.
    com: Vector3<f64>,
    /// Highest height of the patch, m.
    top: f64,
    tolerance: f64,
    /// How far the texels of a tile the kernel reads may read the surface
    /// from its polynomial, m: the tolerance where the buoyancy is summed,
    /// [`SEA_DRAG_DEPTH_TOLERANCE`]'s where only the depths' signs count.
    texel_tolerance: f64,
    delta: f64,
    archimedes: bool,
    /// Whether the buoyancy is summed (else the tiles are classified for
    /// the drag alone).
    buoyancy: bool,
    patch: &'a SurfacePatch,
}

/// What one chunk of groups adds.
#[derive(Default)]
struct Part {
    /// Closed forms, object axes (rotated once at the end).
    local: BuoyancySums,
    /// The kernel's sums and the slope sums, world axes.
    world: BuoyancySums,
    counts: TileCounts,
    /// Whether a tile in closed form may come within `δ` of the surface
    /// (its share of `Σ ln min(d/δ, 1)` would then not be zero).
    shallow: bool,
    /// Drag sums (object axes), where drag is on.
    drag: SeaDragSums,
}

impl TiledAtlas {
    /// The buoyancy sums (world axes, as the sea kernel gives them) of a
    /// body under `patch`, tiles wholly under it in closed form, and with
    /// `drag` the sea's drag sums of its submerged texels (every texel of a
    /// tile in closed form, the others as the sea kernel finds them): `None`
    /// where the sea kernel is not available, or where every tile is under
    /// water and some in closed form lie within the depth scale of the
    /// surface (Archimedes' deep-volume weight then needs every texel's
    /// depth): take the per-texel path then. Without `buoyancy` the tiles
    /// are classified and the texels' depths read for the drag alone, and
    /// the buoyancy sums returned are zero.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn sea_sums(
        &self,
        atlas: &Atlas,
        frame: &Frame,
        patch: &SurfacePatch,
        archimedes: bool,
        buoyancy: bool,
        drag: Option<&SeaDragFrame>,
        detail: SeaVelocity,
    ) -> Option<(BuoyancySums, Option<SeaDragSums>, TileCounts)> {
        if !sea_kernel::available() {
            return None;
        }
        let rot = frame.rot;
        let top = patch
            .height_bounds(patch.time())
            .map_or(f64::INFINITY, |(_, hi)| hi);
        let c = SeaTiles {
            rot,
            g: rot.transpose() * Vector3::y(),
            l: Matrix2x3::from_rows(&[rot.row(0), rot.row(2)]),
            rows: [rot.row(0).transpose(), rot.row(2).transpose()],
            ll: {
                let (r0, r2) = (rot.row(0), rot.row(2));
                [
                    std::array::from_fn(|e| r0[SYM[e].0] * r0[SYM[e].1]),
                    std::array::from_fn(|e| r0[SYM[e].0] * r2[SYM[e].1] + r2[SYM[e].0] * r0[SYM[e].1]),
                    std::array::from_fn(|e| r2[SYM[e].0] * r2[SYM[e].1]),
                ]
            },
            ow: frame.ow,
            com: frame.com - frame.ow,
            top,
            tolerance: SEA_TILE_TOLERANCE * frame.depth_scale,
            texel_tolerance: if buoyancy {
                SEA_TILE_TOLERANCE
            } else {
                SEA_DRAG_DEPTH_TOLERANCE
            } * frame.depth_scale,
            delta: frame.deep_scale,
            archimedes,
            buoyancy,
            patch,
        };
        let read = if buoyancy { SeaRead::Sums } else { SeaRead::Depths };
        let sea = SeaFrame {
            rot,
            ow: frame.ow,
            com: c.com,
            top,
            delta: frame.deep_scale,
            patch,
            archimedes,
        };
        let n_chunks = self.groups.len().div_ceil(self.group_chunk);
        // Over tiles, a tile's texels take the fluid's velocity to first
        // order about its centre (object axes); texel by texel, each its
        // own.
        // A tile wider than the patch's spacing reads it at every texel:
        // the linear part is then no longer the patch's velocity to within
        // the interpolant's own error.
        let tile_fluid = |ti: usize| -> Option<TileFluid> {
            let d = drag.filter(|_| detail == SeaVelocity::PerTile)?;
            let patch = d.patch?;
            if self.tiles[ti].radius > 0.5 * patch.spacing() {
                return None;
            }
            let centre = self.tiles[ti].centre;
            let (u, grad) = patch.velocity_gradient_at(&(d.ow + d.rot * centre));
            let fluid = LinearFluid {
                u: d.rot.transpose() * u,
                grad: d.rot.transpose() * grad * d.rot,
                c: centre,
            };
            Some((ti, fluid))
        };
        let chunk = |k: usize| {
            let groups =
                &self.groups[k * self.group_chunk..((k + 1) * self.group_chunk).min(self.groups.len())];
            let mut part = Part::default();
            // Texel ranges for the sea kernel and, where drag is on, those
            // of tiles in closed form whose drag is summed texel by texel;
            // each with the fluid's velocity over it where it is one.
            let (mut texels, mut closed) = (Ranges::default(), Ranges::default());
            for group in groups {
                let b = &group.bounds;
                if (c.ow + rot * b.centre).y - b.radius >= c.top {
                    part.counts.dry += group.tiles.len();
                    continue;
                }
                for ti in group.tiles.clone() {
                    let m = &self.tiles[ti];
                    let range = m.range.0 as usize..m.range.1 as usize;
                    match self.sea_tile(&c, ti, &mut part) {
                        SeaTile::Dry => {}
                        SeaTile::Texels(taylor) => texels.push(range, tile_fluid(ti), taylor),
                        SeaTile::Closed => match (drag, tile_fluid(ti)) {
                            // The tile's drag in closed form where its
                            // texels all face the flow alike.
                            (Some(d), Some((_, fluid))) => {
                                if !self.add_tile_drag(&mut part.drag, ti, d, &fluid) {
                                    closed.push(range, Some((ti, fluid)), None);
                                }
                            }
                            (Some(_), None) => closed.push(range, None, None),
                            (None, _) => {}
                        },
                    }
                }
            }
            let Some(drag) = drag else {
                for (span, taylor, _) in texels.calls() {
                    add_sea_range(&mut part.world, atlas, span, &sea, taylor, read, None);
                }
                return part;
            };
            // The drag kernel takes the kernel's depths where it read them,
            // and every texel of a tile in closed form as submerged; its
            // ranges' sums stay in lanes until the chunk's end.
            let mut depths = Vec::new();
            let mut lanes = SeaDragLanes::default();
            // The kernel's calls as without drag (the same sums to the
            // bit); the drag over each range of a call, with its depths.
            for (span, taylor, members) in texels.calls() {
                depths.clear();
                depths.resize(span.len(), 0.0);
                add_sea_range(
                    &mut part.world,
                    atlas,
                    span.clone(),
                    &sea,
                    taylor,
                    read,
                    Some(&mut depths),
                );
                for (r, fluid, _) in members {
                    let depths = &depths[r.start - span.start..r.end - span.start];
                    // A tile the kernel finds wholly under water takes its
                    // drag in closed form as the others do.
                    if let Some((ti, fluid)) = fluid
                        && depths.iter().all(|&d| d > 0.0)
                        && self.add_tile_drag(&mut part.drag, *ti, drag, fluid)
                    {
                        continue;
                    }
                    let fluid = fluid.as_ref().map(|(_, f)| f);
                    lanes.add(atlas, r.clone(), depths, drag, fluid);
                }
            }
            for (r, fluid, _) in &closed.0 {
                depths.clear();
                depths.resize(r.len(), 1.0);
                let fluid = fluid.as_ref().map(|(_, f)| f);
                lanes.add(atlas, r.clone(), &depths, drag, fluid);
            }
            part.drag += lanes.finish();
            part
        };
        let mut sums = BuoyancySums::default();
        let mut drag_sums = SeaDragSums::default();
        let mut counts = TileCounts::default();
        let mut shallow = false;
        par_fold(
            n_chunks,
            chunk,
            &mut (&mut sums, &mut drag_sums, &mut counts, &mut shallow),
            |(sums, drag_sums, counts, shallow), p| {
                **counts += p.counts;
                **sums += p.local.rotated(&rot);
                **sums += p.world;
                **drag_sums += p.drag;
                **shallow |= p.shallow;
            },
        );
        if archimedes && shallow && sums.count == atlas.len() {
            return None;
        }
        Some((sums, drag.map(|_| drag_sums), counts))
    }

    /// Adds the drag of tile `ti`, wholly under water in `fluid`, in closed
    /// form; `false` (nothing added) where its texels may not all face the
    /// flow alike.
    pub(super) fn add_tile_drag(
        &self,
        sums: &mut SeaDragSums,
        ti: usize,
        d: &SeaDragFrame,
        fluid: &LinearFluid,
    ) -> bool {
        let m = &self.tiles[ti];
        sums.add_tile(
            &self.tile_drag()[ti],
            &self.facing[ti],
            &m.s1,
            &m.s2,
            m.radius,
            &d.params,
            fluid,
        )
    }

    /// Settles tile `ti`: skipped, in closed form into `part`, or left to
    /// the kernel.
    fn sea_tile(&self, c: &SeaTiles, ti: usize, part: &mut Part) -> SeaTile {
        let m = &self.tiles[ti];
        let (rho, centre) = (m.radius, m.centre);
        let p = c.ow + c.rot * centre;
        if p.y - rho >= c.top {
            part.counts.dry += 1;
            return SeaTile::Dry;
        }
        let taylor = Taylor::of(c.patch, p.x, p.z);
        let Taylor {
            h,
            slope: s,
            hess,
            third,
            ..
        } = taylor;
        let slope = Vector2::new(s[0], s[1]);
        // d(x) ≈ α + β·x + δ(x): the affine part from the tangent plane at P.
        let beta = c.l.transpose() * slope - c.g;
        let dc = h - p.y;
        let alpha = dc - beta.dot(&centre);
        let hm = Matrix2::new(hess[0], hess[1], hess[1], hess[2]);
        // The cubic term's largest size over the disc, twice over for the
        // change of the third derivatives across it.
        let cubic = third[0].abs() + 3.0 * third[1].abs() + 3.0 * third[2].abs() + third[3].abs();
        let remainder = cubic * rho * rho * rho / 3.0;
        // The affine part varies over the tile by at most the smaller of
        // |β| ρ and |β|·(half the box), as under a plane.
        let linear = (beta.norm() * rho).min(beta.abs().dot(&m.half_extent));
        let reach = linear + 0.5 * hm.norm() * rho * rho + remainder;
        if dc + reach <= 0.0 {
            part.counts.dry += 1;
            return SeaTile::Dry;
        }
        if dc - reach <= 0.0 || remainder > c.tolerance {
            part.counts.cut += 1;
            // A tile small against the waves reads them from the polynomial
            // the closed forms take, to third order: within the same
            // tolerance (a looser one for the drag alone), and a few
            // multiply-adds a texel.
            return SeaTile::Texels((remainder <= c.texel_tolerance).then_some(taylor));
        }
        part.counts.submerged += 1;
        if !c.buoyancy {
            return SeaTile::Closed;
        }
        part.shallow |= dc - reach < c.delta;
        let mut t = BuoyancySums::default();
        let (t1, t2) = add_closed_form(&mut t, m, alpha, &beta, &c.g);
        // The quadratic part: u_j = Σ A_j δ = ½ tr(Q M_j), with
        // M_j = Σ A_j (x − c)(x − c)ᵀ = S2_j − S1_j cᵀ − c S1_jᵀ + S0_j c cᵀ
        // from the moments (`Q` symmetric): ½ tr(Q S2_j) − cᵀQ S1_j + ½ S0_j cᵀQc.
        // Q = Lᵀ H L = H_xx l₀l₀ᵀ + H_xz (l₀l₂ᵀ + l₂l₀ᵀ) + H_zz l₂l₂ᵀ.
        let [hxx, hxz, hzz] = hess;
        let q: Sym = std::array::from_fn(|e| hxx * c.ll[0][e] + hxz * c.ll[1][e] + hzz * c.ll[2][e]);
        let qc = sym_mul(&q, &centre);
        let cqc = centre.dot(&qc);
        let s1qc = m.s1 * qc;
        let u = Vector3::from_fn(|j, _| 0.5 * sym_trace(&q, &m.s2[j]) - s1qc[j] + 0.5 * m.s0[j] * cqc);
        let gu = c.g.dot(&u);
        t.vol -= gu;
        t.wr -= gu * centre;
        t.wd2 -= dc * gu;
        t.f -= u;
        t.rxf -= centre.cross(&u);
        t.d2a += dc * u;
        if c.archimedes {
            // Σ w ρ × s with ρ = ρ_c + R y and s = s_c + P y (y = x − c,
            // P y = (H L y) laid in the horizontal plane): the weight W and
            // its first moment about the centre m exactly, its second
            // moment Σ w y yᵀ with the depth at the centre,
            // −d_c Σ (g·A) y yᵀ = −d_c M_g.
            let w = t.vol;
            let first = t.wr - centre * w;
            let rho_c = c.rot * centre - c.com;
            let s3 = Vector3::new(slope.x, 0.0, slope.y);
            let [r0, r2] = &c.rows;
            // The rows of H L.
            let hl = [hxx * r0 + hxz * r2, hxz * r0 + hzz * r2];
            let ds3 = Vector3::new(hl[0].dot(&first), 0.0, hl[1].dot(&first));
            // M_g = Σ_j g_j S2_j − T1 cᵀ − c T1ᵀ + (g·S0) c cᵀ, T1 = S1ᵀ g.
            let gs0 = c.g.dot(&m.s0);
            let mg: Sym = std::array::from_fn(|e| {
                let (k, l) = SYM[e];
                t2[(k, l)] - t1[k] * centre[l] - centre[k] * t1[l] + gs0 * centre[k] * centre[l]
            });
            // The rows of L M_g (M_g symmetric), of H L M_g, and
            // N = L M_g Lᵀ.
            let lm = [sym_mul(&mg, r0), sym_mul(&mg, r2)];
            let hlm = [hxx * lm[0] + hxz * lm[1], hxz * lm[0] + hzz * lm[1]];
            let (n00, n01, n11) = (lm[0].dot(r0), lm[0].dot(r2), lm[1].dot(r2));
            // Σ_kl M_kl R e_k × P e_l = Σ_k R e_k × (P M) e_k, with
            // (P M) e_k = (hlm₀ₖ, 0, hlm₁ₖ).
            let (p0, p1): ([f64; 3], [f64; 3]) = (hlm[0].into(), hlm[1].into());
            let mut second = Vector3::zeros();
            for (k, (vx, vz)) in p0.into_iter().zip(p1).enumerate() {
                let rk = c.rot.column(k);
                second += Vector3::new(rk[1] * vz, rk[2] * vx - rk[0] * vz, -rk[1] * vx);
            }
            // The slope's second-order part ½ D³h[Δ, Δ] against the same
            // second moment: ½ tr(T_i N) per slope component.
            let [xxx, xxz, xzz, zzz] = third;
            let ds2 = Vector3::new(
                0.5 * (xxx * n00 + 2.0 * xxz * n01 + xzz * n11),
                0.0,
                0.5 * (xxz * n00 + 2.0 * xzz * n01 + zzz * n11),
            );
            second += rho_c.cross(&ds2);
            part.world.slope += SlopeSums {
                wrs: w * rho_c.cross(&s3) + (c.rot * first).cross(&s3) + rho_c.cross(&ds3) - dc * second,
                ayr: c.g.dot(&(m.s1 * c.g)),
                shallow: 0.0,
            };
        }
        part.local += t;
        SeaTile::Closed
    }
}

/// A symmetric 3 × 3 matrix by its entries `SYM`.
type Sym = [f64; 6];

/// The entries of a [`Sym`]: the diagonal, then above it.
const SYM: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (0, 2)];

/// `a v`.
#[inline]
fn sym_mul(a: &Sym, v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(
        a[0] * v.x + a[3] * v.y + a[5] * v.z,
        a[3] * v.x + a[1] * v.y + a[4] * v.z,
        a[5] * v.x + a[4] * v.y + a[2] * v.z,
    )
}

/// `tr(a b)` for `b` symmetric.
#[inline]
fn sym_trace(a: &Sym, b: &Matrix3<f64>) -> f64 {
    a[0] * b[(0, 0)]
        + a[1] * b[(1, 1)]
        + a[2] * b[(2, 2)]
        + 2.0 * (a[3] * b[(0, 1)] + a[4] * b[(1, 2)] + a[5] * b[(0, 2)])
}

/// Where a tile lies under the sea.
enum SeaTile {
    /// Above the waves: skipped.
    Dry,
    /// In closed form.
    Closed,
    /// Through the sea kernel, texel by texel: reading the surface from its
    /// polynomial about the tile's centre where given, else from the
    /// patch's cells.
    Texels(Option<Taylor>),
}

/// Texel ranges, each with its tile and the fluid's velocity over it
/// (object axes) where the drag takes one per tile, and the polynomial
/// the kernel reads the surface from where it is one.
#[derive(Default)]
struct Ranges(Vec<Entry>);

/// A texel range, its tile and fluid, and its polynomial ([`Ranges`]).
type Entry = (Range<usize>, Option<TileFluid>, Option<Taylor>);

/// A tile and the fluid's velocity over it, to first order about its
/// centre (object axes).
type TileFluid = (usize, LinearFluid);

impl Ranges {
    /// Appends `range`, extending the last one where it follows it and
    /// neither has a velocity or a polynomial of its own.
    fn push(&mut self, range: Range<usize>, fluid: Option<TileFluid>, taylor: Option<Taylor>) {
        match self.0.last_mut() {
            Some((last, None, None)) if fluid.is_none() && taylor.is_none() && last.end == range.start => {
                last.end = range.end
            }
            _ => self.0.push((range, fluid, taylor)),
        }
    }

    /// The sea kernel's calls over the ranges, each with the ranges it
    /// covers: a range with a polynomial on its own, runs of consecutive
    /// ranges without one together.
    fn calls(&self) -> impl Iterator<Item = (Range<usize>, Option<&Taylor>, &[Entry])> {
        let mut rest = &self.0[..];
        std::iter::from_fn(move || {
            let (first, _, taylor) = rest.first()?;
            let len = match taylor {
                Some(_) => 1,
                None => {
                    1 + rest
                        .windows(2)
                        .take_while(|w| w[1].2.is_none() && w[0].0.end == w[1].0.start)
                        .count()
                }
            };
            let (members, next) = rest.split_at(len);
            rest = next;
            Some((first.start..members[len - 1].0.end, taylor.as_ref(), members))
        })
    }
}
