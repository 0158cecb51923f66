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
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self += o;
        self
    }
}

/// In place (a tile's sums added to a chunk's without moving the chunk's
/// out and back); [`Add`](std::ops::Add) is written through it.
impl std::ops::AddAssign for BuoyancySums {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        self.vol += o.vol;
        self.wr += o.wr;
        self.wd2 += o.wd2;
        self.f += o.f;
        self.rxf += o.rxf;
        self.area += o.area;
        self.count += o.count;
        self.d2a += o.d2a;
        self.slope += o.slope;
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
    /// Σ ln min(d/δ, 1), `δ` the depth past which a texel is deep (the
    /// frame's `deep_scale`): `exp` of it is 1 for a body whose every
    /// texel is deeper than `δ` and falls to 0 as any one of them comes up
    /// to the surface.
    pub shallow: f64,
}

impl std::ops::Add for SlopeSums {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self += o;
        self
    }
}

impl std::ops::AddAssign for SlopeSums {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        self.wrs += o.wrs;
        self.ayr += o.ayr;
        self.shallow += o.shallow;
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

impl DragSums {
    /// Whether the system is all zeros (nothing under water): no drag,
    /// whatever the velocity.
    pub(crate) fn is_zero(&self) -> bool {
        self.k.iter().all(|x| *x == 0.0) && self.b.iter().all(|x| *x == 0.0)
    }
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

/// Index of entry `(i, j)`, `i ≤ j`, of a symmetric 6×6 matrix stored as
/// its upper triangle row by row (21 entries).
pub(crate) const fn upper6(i: usize, j: usize) -> usize {
    i * 6 - i * (i + 1) / 2 + j
}

/// The drag system of a set of texels in symmetric running sums, in any
/// frame and about any origin (the frame the texels' `r` and `a` are
/// taken in).
///
/// Per texel, `K_i = s I − w a aᵀ` with `s = k_q + λ a`, `w = λ / a` (`k_q`
/// the quadratic drag's `½ ρ C_d max(a·v, 0)`, `λ` the skin friction, `a`
/// the area `|A|`), and the texel's velocity is `J q` with
/// `J = [I, −[r]×]`, so `Jᵀ K_i J = s [[I, −[r]×], [[r]×, |r|² I − r rᵀ]]
/// − w g gᵀ` with `g = Jᵀ A = (A, r × A)`: the whole system takes the ten
/// sums `Σ s`, `Σ s r`, `Σ s r rᵀ` and the 21 of the symmetric `Σ w g gᵀ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DragAcc {
    /// `Σ s`, `Σ s r` (3), `Σ s r rᵀ` (xx, yy, zz, xy, yz, zx).
    pub iso: [f64; 10],
    /// `Σ w g gᵀ`, its upper triangle by [`upper6`].
    pub gg: [f64; 21],
}

impl Default for DragAcc {
    fn default() -> Self {
        Self {
            iso: [0.0; 10],
            gg: [0.0; 21],
        }
    }
}

impl std::ops::Add for DragAcc {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        self += &o;
        self
    }
}

impl std::ops::AddAssign<&DragAcc> for DragAcc {
    fn add_assign(&mut self, o: &DragAcc) {
        for (x, y) in self.iso.iter_mut().zip(&o.iso) {
            *x += y;
        }
        for (x, y) in self.gg.iter_mut().zip(&o.gg) {
            *x += y;
        }
    }
}

impl DragAcc {
    /// Adds `s (1, r, r rᵀ)`.
    #[inline(always)]
    pub(crate) fn add_iso(&mut self, s: f64, r: &[f64; 3]) {
        let sr = [s * r[0], s * r[1], s * r[2]];
        let t = &mut self.iso;
        t[0] += s;
        t[1] += sr[0];
        t[2] += sr[1];
        t[3] += sr[2];
        t[4] += sr[0] * r[0];
        t[5] += sr[1] * r[1];
        t[6] += sr[2] * r[2];
        t[7] += sr[0] * r[1];
        t[8] += sr[1] * r[2];
        t[9] += sr[2] * r[0];
    }

    /// Adds `w g gᵀ`.
    #[inline(always)]
    pub(crate) fn add_rank1(&mut self, w: f64, g: &[f64; 6]) {
        let mut k = 0;
        for i in 0..6 {
            let wg = w * g[i];
            for gj in &g[i..] {
                self.gg[k] += wg * gj;
                k += 1;
            }
        }
    }

    /// `K = Σ Jᵀ K_i J` about the origin of the texels' frame: the blocks
    /// of [`DragAcc::k_blocks`], `[[A, B], [Bᵀ, D]]`, symmetric to the last
    /// bit.
    pub(crate) fn k(&self) -> Matrix6<f64> {
        let [a, b, d] = self.k_blocks();
        block_matrix(&a, &b, &d)
    }

    /// The blocks `A`, `B` and `D` of `K = [[A, B], [Bᵀ, D]]` from the
    /// sums: with `G = Σ w g gᵀ` in blocks `[[G_tt, G_tr], [·, G_rr]]`,
    /// `A = (Σ s) I − G_tt`, `B = −G_tr − [Σ s r]×` and
    /// `D = tr(Σ s r rᵀ) I − Σ s r rᵀ − G_rr`; `A` and `D` symmetric to the
    /// last bit.
    fn k_blocks(&self) -> [Matrix3<f64>; 3] {
        let [s, sx, sy, sz, xx, yy, zz, xy, yz, zx] = self.iso;
        let g = |i: usize, j: usize| -self.gg[upper6(i.min(j), i.max(j))];
        let sr = Vector3::new(sx, sy, sz).cross_matrix();
        let rr = Matrix3::new(xx, xy, zx, xy, yy, yz, zx, yz, zz);
        let trace = xx + yy + zz;
        let eye = |i: usize, j: usize, x: f64| if i == j { x } else { 0.0 * x };
        [
            Matrix3::from_fn(|i, j| g(i, j) + eye(i, j, s)),
            Matrix3::from_fn(|i, j| g(i, j + 3) - sr[(i, j)]),
            Matrix3::from_fn(|i, j| g(i + 3, j + 3) + (eye(i, j, trace) - rr[(i, j)])),
        ]
    }

    /// The drag system about the centre of mass in world axes, of sums
    /// taken in object axes about the atlas origin: `rot` turns object
    /// axes into the world's, `c` is the centre of mass from the atlas
    /// origin (object axes), and the fluid moves at `u` (world, m/s)
    /// everywhere, so that `b = Σ Jᵀ K_i u = K (u, 0)`.
    ///
    /// With `J` about the centre of mass `J_o [[I, [c]×], [0, I]]`, the
    /// system about it is `T K_o Tᵀ` with `T = [[I, 0], [−[c]×, I]]`, and
    /// in world axes `Q T K_o Tᵀ Qᵀ` with `Q = diag(rot, rot)`.
    pub(crate) fn system(&self, rot: &Matrix3<f64>, c: &Vector3<f64>, u: &Vector3<f64>) -> DragSums {
        // In 3 × 3 blocks, K_o = [[A, B], [Bᵀ, D]] and [c]× = C (Cᵀ = −C):
        // T K_o Tᵀ = [[A, A C + B], [·, D − C B − (C B)ᵀ − C A C]], each block
        // then turned, R X Rᵀ (a third of the 6 × 6 products' work). The
        // diagonal blocks are symmetric: of them (and of C A C) only the
        // entries on and above the diagonal are made, and mirrored, so
        // that the matrix is the same to the last bit on either side.
        let [a, b, d] = self.k_blocks();
        let cx = c.cross_matrix();
        let ac = product(&a, &cx);
        let b_c = ac + b;
        let cb = product(&cx, &b);
        let d_c = symmetric(|i, j| d[(i, j)] - cb[(i, j)] - cb[(j, i)] - dot_row_column(&cx, i, &ac, j));
        let rt = rot.transpose();
        let turn_symmetric = |x: &Matrix3<f64>| {
            let y = product(x, &rt);
            symmetric(|i, j| dot_row_column(rot, i, &y, j))
        };
        let (a_w, b_w, d_w) = (
            turn_symmetric(&a),
            product(&product(rot, &b_c), &rt),
            turn_symmetric(&d_c),
        );
        let k = block_matrix(&a_w, &b_w, &d_w);
        let b = k.fixed_view::<6, 3>(0, 0) * u;
        DragSums { k, b }
    }
}

/// `[[a, b], [bᵀ, d]]`.
#[inline(always)]
fn block_matrix(a: &Matrix3<f64>, b: &Matrix3<f64>, d: &Matrix3<f64>) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| match (i < 3, j < 3) {
        (true, true) => a[(i, j)],
        (true, false) => b[(i, j - 3)],
        (false, true) => b[(j, i - 3)],
        (false, false) => d[(i - 3, j - 3)],
    })
}

/// `x y`, entry by entry (three multiply-adds each).
#[inline(always)]
fn product(x: &Matrix3<f64>, y: &Matrix3<f64>) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| dot_row_column(x, i, y, j))
}

/// Row `i` of `x` by column `j` of `y`.
#[inline(always)]
fn dot_row_column(x: &Matrix3<f64>, i: usize, y: &Matrix3<f64>, j: usize) -> f64 {
    x[(i, 0)] * y[(0, j)] + x[(i, 1)] * y[(1, j)] + x[(i, 2)] * y[(2, j)]
}

/// The symmetric 3 × 3 matrix whose entries on and above the diagonal
/// are `f(i, j)` (`i ≤ j`), each made once.
#[inline(always)]
fn symmetric(f: impl Fn(usize, usize) -> f64) -> Matrix3<f64> {
    let (xx, yy, zz, xy, yz, xz) = (f(0, 0), f(1, 1), f(2, 2), f(0, 1), f(1, 2), f(0, 2));
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// The drag of submerged texels taken one by one, each in its own fluid
/// velocity (any surface), in world axes about the centre of mass: the
/// sums of [`DragAcc`] (per texel `s (1, r, r rᵀ)` and `w g gᵀ`), and
/// `b = Σ Jᵀ K_i u_i`, which a fluid velocity that varies from texel to
/// texel keeps from being `K (u, 0)`. [`TexelDrag::sums`] turns them into
/// a [`DragSums`] once.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct TexelDrag {
    acc: DragAcc,
    /// Σ K_i u_i and Σ r × K_i u_i.
    f: Vector3<f64>,
    rf: Vector3<f64>,
}

impl TexelDrag {
    /// Adds a submerged texel at `r` from the centre of mass with world
    /// area vector `a`, relative velocity `vrel` and fluid velocity `u`.
    #[inline]
    pub(crate) fn add(
        &mut self,
        drag: &Drag,
        rho: f64,
        r: &Vector3<f64>,
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
        let (s, w) = if drag.linear > 0.0 && area > 0.0 {
            (kq + drag.linear * area, drag.linear / area)
        } else {
            (kq, 0.0)
        };
        if s == 0.0 {
            return;
        }
        self.acc.add_iso(s, &[r.x, r.y, r.z]);
        if w != 0.0 {
            let g = [
                a.x,
                a.y,
                a.z,
                r.y * a.z - r.z * a.y,
                r.z * a.x - r.x * a.z,
                r.x * a.y - r.y * a.x,
            ];
            self.acc.add_rank1(w, &g);
        }
        // K_i u = s u − w (a·u) a.
        let f = s * u - (w * a.dot(u)) * a;
        self.f += f;
        self.rf += r.cross(&f);
    }

    /// The system: `K` from the [`DragAcc`] sums, `b` as summed.
    pub(crate) fn sums(&self) -> DragSums {
        DragSums {
            k: self.acc.k(),
            b: Vector6::new(self.f.x, self.f.y, self.f.z, self.rf.x, self.rf.y, self.rf.z),
        }
    }
}

impl std::ops::Add for TexelDrag {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            acc: self.acc + o.acc,
            f: self.f + o.f,
            rf: self.rf + o.rf,
        }
    }
}
