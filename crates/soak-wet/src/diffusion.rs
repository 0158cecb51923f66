//! Diffusion of the liquid over the surface through a voxel field (the
//! thesis' *campo de densidad de líquido*, §5.4.1), in two modes; the model
//! is described on [`Diffusion`].

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{WetError, non_negative};
use crate::grid::FieldResolution;
use crate::layout::{Layout, NONE, octant};
use crate::reduce::{liquid_volume, wide_vectors};

/// Minimum Shepard distance, in voxels (the thesis' `Dist_min = S_V / 50`).
pub const SHEPARD_MIN_DISTANCE: f64 = 1.0 / 50.0;

/// Which diffusion scheme runs on the voxel field.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DiffusionMode {
    /// Moves liquid volumes between voxels and returns each voxel's change
    /// to its texels by area: total liquid is conserved to rounding.
    #[default]
    Conservative,
    /// The thesis' scheme (reference): Shepard averages in, Eq. 5.12,
    /// Shepard interpolation out. Smooth, but not conservative.
    Thesis,
}

/// Diffusion settings of a field.
///
/// Texels are binned into a regular grid of cubic voxels; a voxel holding
/// at least one texel is *defined*. (In a [`crate::SharedField`] each body
/// has its own cell in a voxel it shares with others, and the cells of one
/// voxel are neighbours: below, "voxel" means cell.) One diffusion step:
///
/// 1. **texels → voxels.** [`DiffusionMode::Thesis`]: the voxel's value is
///    the Shepard average of its texels' `h` (Eq. 5.9–5.10, `p = 1`, the
///    distance to the voxel centre floored at 1/50 of a voxel).
///    [`DiffusionMode::Conservative`]: the voxel holds the liquid volume
///    `M_v = Σ a_i h_i` (m³) and the capacity `C_v = Σ a_i h_max,i`.
/// 2. **the 3×3×3 kernel** (Eq. 5.12) over defined voxels, in substeps:
///    `V'_x = (1 − w·Count(x)) V_x + w Σ_{y defined} V_y`, `Count(x)` the
///    defined neighbours of `x`. The conservative mode writes the same
///    kernel in flux form on the fill fraction `φ_v = M_v / C_v`:
///    `M'_v = M_v + w Σ_u min(C_v, C_u) (φ_u − φ_v)`; each pair exchanges
///    equal and opposite amounts, so the total is conserved to rounding,
///    and where neighbours hold equal capacity it *is* Eq. 5.12 on the
///    liquid per area. Liquid flows from fuller to emptier surface, also
///    between materials of different saturation (a wet sponge on wood).
/// 3. **voxels → texels.** Thesis: each texel takes the Shepard average of
///    the defined voxels among the 8 nearest voxel centres (Eq. 5.13–5.14),
///    clamped to `[0, h_max]`. This averages and re-interpolates, so it does
///    not conserve liquid (the thesis says it does); the step reports the
///    drift. Conservative: each voxel's change `M'_v − M_v` goes back to
///    its own texels, exactly. First a smooth share: the voxels' fill
///    changes `Δφ` interpolated trilinearly at the texel (over the defined
///    voxels among the 8 nearest), times `h_max`, clamped to keep the texel
///    in `[0, h_max]`; then the voxel's rest by area: a gain fills each
///    texel's remaining room by the same fraction, a loss takes the same
///    fraction of each texel's liquid. The rest always fits (the voxel's
///    new content lies in `[0, C_v]`), so every texel stays in
///    `[0, h_max]` and the voxel's texels gain exactly `M'_v − M_v`: smooth
///    across voxel borders, conservative, and changes are added, so detail
///    finer than a voxel (a waterline) survives.
///
/// # The effective diffusion coefficient
///
/// In one substep a defined voxel sends the fraction `w β` of its content
/// to each defined neighbour (β = 1, or `min(C_v, C_u)/C_v` in the
/// conservative mode, 1 between equal neighbours). Take a flat surface
/// lying in one layer of voxels parallel to a grid plane: an interior voxel
/// has the 8 neighbours of its layer, 6 of them one voxel (Δx) away along
/// each in-plane axis. The variance of a spreading spot grows per substep
/// by `Σ_u w (Δx_u)² = 6 w Δx²` along each in-plane axis (the cross
/// moments cancel: the kernel is isotropic to second order), and a
/// diffusion with coefficient `D` grows it by `2 D Δt_s`. Hence
///
/// `D_eff = 3 w Δx² / Δt_s`, and we set `w = D Δt_s / (3 Δx²)`
///
/// from the material's [`Diffusion::coefficient`] `D` (m²/s). A volume of
/// defined voxels (all 26 neighbours) would give `9 w Δx² / Δt_s`, three
/// times as much: surfaces that cross voxel layers (oblique or curved
/// ones, or two sheets a voxel apart) spread somewhat faster than `D`; the
/// test `diffusion_physics` measures a flat plate (grid-aligned, the
/// formula holds) and a tilted one.
///
/// # Stability
///
/// The kernel is a convex combination, hence non-negative and free of new
/// extrema, while `w · Count ≤ 1`. A step of `Δt` needs the weight
/// `W = D Δt / (3 Δx²)`; it is split into `n = ⌈W · Count_max⌉` substeps of
/// `w = W / n`. Past [`Diffusion::max_substeps`] the weight is capped at
/// `1 / Count_max` per substep (diffusion slower than asked, still stable)
/// and the step says so ([`SubstepPlan::limited`] in [`DiffusionReport::plan`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Diffusion {
    /// Diffusion coefficient D (thesis Table 5.1), m²/s: a spot's variance
    /// grows by `2 D` per second along each direction of the surface (see
    /// [`Diffusion`] for how the voxel kernel realises it). Zero turns
    /// diffusion off without dropping the field.
    pub coefficient: f64,
    /// The scheme.
    #[serde(default)]
    pub mode: DiffusionMode,
    /// Voxel size.
    #[serde(default)]
    pub resolution: FieldResolution,
    /// Most substeps per step before the rate is capped (default 1024).
    #[serde(default = "default_max_substeps")]
    pub max_substeps: u32,
}

fn default_max_substeps() -> u32 {
    1024
}

impl Diffusion {
    /// Conservative diffusion with coefficient `coefficient` (m²/s) on an
    /// automatically sized field.
    pub fn new(coefficient: f64) -> Self {
        Self {
            coefficient,
            mode: DiffusionMode::Conservative,
            resolution: FieldResolution::Auto,
            max_substeps: default_max_substeps(),
        }
    }

    /// The same settings in another mode.
    pub fn with_mode(mut self, mode: DiffusionMode) -> Self {
        self.mode = mode;
        self
    }

    /// The same settings at another resolution.
    pub fn with_resolution(mut self, resolution: FieldResolution) -> Self {
        self.resolution = resolution;
        self
    }

    /// Checks the coefficient is finite and non-negative and at least one
    /// substep is allowed.
    pub fn validate(&self) -> Result<(), WetError> {
        non_negative("diffusion.coefficient", self.coefficient)?;
        if self.max_substeps == 0 {
            return Err(WetError::parameter("diffusion.max_substeps", 0.0, ">= 1"));
        }
        Ok(())
    }

    /// The substeps for a step of `dt` (s) on voxels of edge `voxel_size`
    /// (m) with at most `count_max` defined neighbours per voxel.
    pub fn plan(&self, dt: f64, voxel_size: f64, count_max: u32) -> SubstepPlan {
        let total = self.coefficient * dt / (3.0 * voxel_size * voxel_size);
        if total.is_nan() || total <= 0.0 || count_max == 0 {
            return SubstepPlan::default();
        }
        let c = count_max as f64;
        let needed = (total * c).ceil();
        if needed <= self.max_substeps as f64 {
            let n = needed.max(1.0);
            SubstepPlan {
                substeps: n as u32,
                weight: total / n,
                limited: false,
            }
        } else {
            SubstepPlan {
                substeps: self.max_substeps,
                weight: 1.0 / c,
                limited: true,
            }
        }
    }
}

/// How one step's diffusion is split.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SubstepPlan {
    /// Kernel applications.
    pub substeps: u32,
    /// Kernel weight `w` per substep (dimensionless; `w · Count ≤ 1`).
    pub weight: f64,
    /// Whether the weight was capped at `1 / Count_max` because the step
    /// needed more than [`Diffusion::max_substeps`].
    pub limited: bool,
}

/// What one diffusion step did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DiffusionReport {
    /// The substeps run.
    pub plan: SubstepPlan,
    /// Defined voxels.
    pub voxels: usize,
    /// Most defined neighbours of a voxel (`Count` of Eq. 5.12).
    pub count_max: u32,
    /// Texels that lie outside the field and were left alone.
    pub outside: usize,
    /// Change of total liquid the diffusion itself made, m³: zero to
    /// rounding in the conservative mode (not measured there, reported as
    /// 0), the thesis scheme's error otherwise.
    pub drift: f64,
}

/// Buffers of one field, reused between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    start: Vec<f64>,
    value: Vec<f64>,
    next: Vec<f64>,
    aux: Vec<f64>,
    phi: Vec<f64>,
    partials: Vec<f64>,
}

impl Scratch {
    pub fn bytes(&self) -> usize {
        8 * (self.start.capacity()
            + self.value.capacity()
            + self.next.capacity()
            + self.aux.capacity()
            + self.phi.capacity()
            + self.partials.capacity())
    }
}

/// Runs one diffusion step over the texels `h` (concatenated as in
/// `layout`) and returns the drift (m³, thesis mode only).
pub(crate) fn run(
    layout: &Layout,
    h: &mut [f64],
    mode: DiffusionMode,
    plan: &SubstepPlan,
    s: &mut Scratch,
) -> f64 {
    if plan.substeps == 0 || layout.defined() == 0 {
        return 0.0;
    }
    match mode {
        DiffusionMode::Conservative => {
            conservative(layout, h, plan, s);
            0.0
        }
        DiffusionMode::Thesis => {
            let before = liquid_volume(h, &layout.areas, &mut s.partials);
            thesis(layout, h, plan, s);
            liquid_volume(h, &layout.areas, &mut s.partials) - before
        }
    }
}

fn neighbours(layout: &Layout, v: usize) -> &[u32] {
    &layout.neighbours[layout.nstart[v] as usize..layout.nstart[v + 1] as usize]
}

fn resize(buffer: &mut Vec<f64>, n: usize) {
    buffer.clear();
    buffer.resize(n, 0.0);
}

/// Cells per task of the per-cell parallel passes (a fixed split would do
/// as well: each cell's result is computed by one task in a fixed order,
/// so the thread count changes nothing).
const CELLS_PER_TASK: usize = 64;

/// Cells per task of the passes that do little per cell (the kernel's
/// substeps, the fill changes).
const SUBSTEP_CELLS_PER_TASK: usize = 1024;

/// A slice that several tasks write at distinct indices: each cell's task
/// touches only its own texels (every binned texel is the member of
/// exactly one cell) and its own member slots.
struct Disjoint<'a> {
    ptr: *mut f64,
    len: usize,
    _slice: std::marker::PhantomData<&'a mut [f64]>,
}

// SAFETY: `Disjoint` only hands out element reads and writes through
// `unsafe fn`s whose callers promise no index is used by two tasks at once.
#[allow(unsafe_code)]
unsafe impl Sync for Disjoint<'_> {}
#[allow(unsafe_code)]
unsafe impl Send for Disjoint<'_> {}

impl<'a> Disjoint<'a> {
    fn new(slice: &'a mut [f64]) -> Self {
        Self {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _slice: std::marker::PhantomData,
        }
    }

    /// Element `i`.
    ///
    /// # Safety
    /// No other task accesses element `i` during this pass.
    #[allow(unsafe_code)]
    #[inline]
    unsafe fn get(&self, i: usize) -> f64 {
        assert!(i < self.len);
        // SAFETY: in bounds (checked), and not written concurrently (the
        // caller's promise).
        unsafe { *self.ptr.add(i) }
    }

    /// Sets element `i`.
    ///
    /// # Safety
    /// No other task accesses element `i` during this pass.
    #[allow(unsafe_code)]
    #[inline]
    unsafe fn set(&self, i: usize, x: f64) {
        assert!(i < self.len);
        // SAFETY: in bounds (checked), and not accessed concurrently (the
        // caller's promise).
        unsafe { *self.ptr.add(i) = x }
    }
}

/// Writes the values of cell `v`'s 8 nearest cells for each octant
/// (`corners` layout) into `value`, zero where a corner is not defined, and
/// a mask into `mask`, 1 where it is.
#[inline(always)]
fn corner_values(layout: &Layout, values: &[f64], v: usize, value: &mut [f64; 64], mask: &mut [f64; 64]) {
    let ids = &layout.corners[64 * v..64 * v + 64];
    for (j, &id) in ids.iter().enumerate() {
        (value[j], mask[j]) = if id != NONE {
            (values[id as usize], 1.0)
        } else {
            (0.0, 0.0)
        };
    }
}

fn conservative(layout: &Layout, h: &mut [f64], plan: &SubstepPlan, s: &mut Scratch) {
    let nv = layout.defined();
    let cap = &layout.capacity;
    resize(&mut s.start, nv);
    resize(&mut s.next, nv);
    resize(&mut s.aux, nv);
    resize(&mut s.phi, nv);
    // Each cell's liquid M_v and fill φ_v = M_v / C_v.
    s.start
        .par_iter_mut()
        .zip(s.phi.par_iter_mut())
        .enumerate()
        .with_min_len(CELLS_PER_TASK)
        .for_each(|(v, (m, p))| {
            let r = layout.slots(v);
            *m = layout.members[r.clone()]
                .iter()
                .zip(&layout.slot_area[r])
                .map(|(&i, &a)| a as f64 * h[i as usize])
                .sum();
            *p = *m / cap[v];
        });
    s.value.clear();
    s.value.extend_from_slice(&s.start);
    let w = plan.weight;
    let start = &s.start;
    for substep in 0..plan.substeps {
        // The kernel, and the fill of its result for the next substep;
        // after the last one, each cell's change of fill instead,
        // Δφ = (M' − M) / C.
        let last = substep + 1 == plan.substeps;
        let (value, phi) = (&s.value, &s.phi);
        s.next
            .par_iter_mut()
            .zip(s.aux.par_iter_mut())
            .enumerate()
            .with_min_len(SUBSTEP_CELLS_PER_TASK)
            .for_each(|(v, (out, p))| {
                let (pv, cv) = (phi[v], cap[v]);
                let flux: f64 = neighbours(layout, v)
                    .iter()
                    .map(|&u| cv.min(cap[u as usize]) * (phi[u as usize] - pv))
                    .sum();
                *out = value[v] + w * flux;
                *p = if last {
                    (out.clamp(0.0, cv) - start[v]) / cv
                } else {
                    *out / cv
                };
            });
        std::mem::swap(&mut s.value, &mut s.next);
        std::mem::swap(&mut s.phi, &mut s.aux);
    }
    let (dphi, value) = (&s.phi, &s.value);
    let back = Return {
        layout,
        dphi,
        start,
        value,
        out: Disjoint::new(h),
    };
    let wide = wide_vectors();
    (0..nv)
        .into_par_iter()
        .with_min_len(CELLS_PER_TASK)
        .for_each(|v| {
            // Only cells some cell of whose 3×3×3 block changed: the
            // others' texels keep their liquid exactly.
            let dphi = back.dphi;
            if dphi[v] != 0.0 || neighbours(layout, v).iter().any(|&u| dphi[u as usize] != 0.0) {
                SHARES.with_borrow_mut(|delta| back.cell(v, delta, wide));
            }
        });
}

thread_local! {
    /// The smooth shares of the texels of the cell a thread is returning
    /// to (see [`Return::cell_body`]): kept per thread so that, once grown
    /// to the largest cell, steps allocate nothing.
    static SHARES: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The conservative return of the cells' changes to their texels.
struct Return<'a> {
    layout: &'a Layout,
    /// Per cell: its change of fill Δφ, its liquid before and after the
    /// kernel.
    dphi: &'a [f64],
    start: &'a [f64],
    value: &'a [f64],
    out: Disjoint<'a>,
}

impl Return<'_> {
    /// Returns cell `v`'s change to its texels (`delta`: scratch).
    #[inline]
    fn cell(&self, v: usize, delta: &mut Vec<f64>, wide: bool) {
        #[cfg(target_arch = "x86_64")]
        if wide {
            // SAFETY: the processor has AVX2 (`wide_vectors`).
            #[allow(unsafe_code)]
            unsafe {
                self.cell_avx2(v, delta)
            };
            return;
        }
        let _ = wide;
        self.cell_body(v, delta);
    }

    /// [`Return::cell_body`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn cell_avx2(&self, v: usize, delta: &mut Vec<f64>) {
        self.cell_body(v, delta);
    }

    /// Per active cell, in one pass over its texels: each texel's smooth
    /// share of the change (zero where nothing nearby changed), then what
    /// the shares leave over of the cell's change, as a factor (f > 0
    /// fills that fraction of the room left, f < 0 takes that fraction of
    /// the liquid left), then the texels' new liquid. The shares of the
    /// cell's texels are kept in `delta`, small enough to stay in cache
    /// between the two loops.
    #[inline(always)]
    fn cell_body(&self, v: usize, delta: &mut Vec<f64>) {
        let (layout, out) = (self.layout, &self.out);
        let hmax = layout.segments[layout.cell_segment[v] as usize].saturation;
        let (mut near, mut defined) = ([0.0; 64], [0.0; 64]);
        corner_values(layout, self.dphi, v, &mut near, &mut defined);
        let r = layout.slots(v);
        let members = &layout.members[r.clone()];
        let fracs = &layout.slot_frac[r.clone()];
        delta.clear();
        for (members, fracs) in members.chunks(LANES).zip(fracs.chunks(LANES)) {
            // A short last group repeats its first texel in the unused
            // lanes, whose results are dropped.
            let (mut g, mut x) = ([fracs[0]; LANES], [0.0; LANES]);
            for l in 0..LANES {
                let j = if l < members.len() { l } else { 0 };
                g[l] = fracs[j];
                // SAFETY: texel `members[j]` belongs to cell `v` alone.
                #[allow(unsafe_code)]
                let h = unsafe { out.get(members[j] as usize) };
                x[l] = h;
            }
            let d = smooth_changes(&g, &near, &defined, &x, hmax);
            for &d in &d[..members.len()] {
                delta.push(d);
            }
        }
        let spread: f64 = layout.slot_area[r]
            .iter()
            .zip(delta.iter())
            .map(|(&a, &d)| a as f64 * d)
            .sum();
        let (m0, c) = (self.start[v], layout.capacity[v]);
        let rest = (self.value[v].clamp(0.0, c) - m0) - spread;
        let (room, content) = (c - m0 - spread, m0 + spread);
        let f = if rest > 0.0 && room > 0.0 {
            (rest / room).min(1.0)
        } else if rest < 0.0 && content > 0.0 {
            (rest / content).max(-1.0)
        } else {
            0.0
        };
        for (&i, &d) in members.iter().zip(delta.iter()) {
            let i = i as usize;
            // SAFETY: texel `i` belongs to cell `v` alone.
            #[allow(unsafe_code)]
            unsafe {
                let x = out.get(i) + d;
                let x = if f < 0.0 {
                    x * (1.0 + f)
                } else {
                    x + f * (hmax - x)
                };
                out.set(i, x.clamp(0.0, hmax));
            }
        }
    }
}

/// The trilinear weights of the 8 corners around a texel at `t` ∈ [0, 1]³
/// (see [`Layout::octant`]): corner `c` has `w_x · w_y · w_z`, the axis
/// weights `t_k` where bit k of `c` is set, `1 − t_k` where not, multiplied
/// in that order.
#[inline(always)]
fn trilinear(t: [f64; 3]) -> [f64; 8] {
    let axis = [[1.0 - t[0], t[0]], [1.0 - t[1], t[1]], [1.0 - t[2], t[2]]];
    let mut xy = [0.0; 4];
    for (c, xy) in xy.iter_mut().enumerate() {
        *xy = axis[0][c & 1] * axis[1][c >> 1];
    }
    let mut w = [0.0; 8];
    for (c, w) in w.iter_mut().enumerate() {
        *w = xy[c & 3] * axis[2][c >> 2];
    }
    w
}

/// Texels interpolated together (one per lane) by the field → texel
/// passes: independent lanes doing the same operations, which the compiler
/// packs into vector instructions; each lane computes the bits a texel
/// alone would.
const LANES: usize = 4;

/// `x` clamped to `[lo, hi]` like [`f64::clamp`] (NaN stays NaN), without
/// its check that `lo <= hi` (which holds for every caller): a select the
/// compiler can vectorize.
#[inline(always)]
fn clamp(x: f64, lo: f64, hi: f64) -> f64 {
    let x = if x < lo { lo } else { x };
    if x > hi { hi } else { x }
}

/// The smooth shares of texels' changes in the conservative return (their
/// positions in their cell `g`, see [`Layout::slot_frac`], and liquid
/// `h`): the cells' fill changes interpolated trilinearly at each texel
/// over the defined cells of its body among the 8 nearest (`near`,
/// `defined`: [`corner_values`] of the fill changes), times `h_max`,
/// clamped so the texel stays in `[0, h_max]`.
#[inline(always)]
fn smooth_changes(
    g: &[[f32; 3]; LANES],
    near: &[f64; 64],
    defined: &[f64; 64],
    h: &[f64; LANES],
    hmax: f64,
) -> [f64; LANES] {
    let (mut base, mut w) = ([0; LANES], [[0.0; 8]; LANES]);
    for l in 0..LANES {
        let (o, t) = octant(&g[l]);
        base[l] = 8 * o;
        w[l] = trilinear(t);
    }
    let (mut num, mut den) = ([0.0; LANES], [0.0; LANES]);
    for corner in 0..8 {
        for l in 0..LANES {
            // Undefined corners add +0 to both sums: the same bits as
            // leaving them out (neither sum can be −0).
            num[l] += w[l][corner] * near[base[l] + corner];
            den[l] += w[l][corner] * defined[base[l] + corner];
        }
    }
    let mut d = [0.0; LANES];
    for l in 0..LANES {
        let share = clamp(num[l] / den[l] * hmax, -h[l], hmax - h[l]);
        d[l] = if den[l] > 0.0 { share } else { 0.0 };
    }
    d
}

/// Shepard weight `1 / max(d, d_min)` (p = 1) for a distance `d` in voxels.
#[inline(always)]
fn shepard(d2: f64) -> f64 {
    1.0 / d2.sqrt().max(SHEPARD_MIN_DISTANCE)
}

fn thesis(layout: &Layout, h: &mut [f64], plan: &SubstepPlan, s: &mut Scratch) {
    let nv = layout.defined();
    resize(&mut s.value, nv);
    resize(&mut s.next, nv);
    s.value
        .par_iter_mut()
        .enumerate()
        .with_min_len(CELLS_PER_TASK)
        .for_each(|(v, out)| {
            let (mut num, mut den) = (0.0, 0.0);
            for k in layout.slots(v) {
                // Offsets from the cell's centre (exact: see `slot_frac`).
                let g = layout.slot_frac[k];
                let d2 = (0..3).map(|a| (g[a] as f64 - 0.5).powi(2)).sum::<f64>();
                let wgt = shepard(d2);
                num += wgt * h[layout.members[k] as usize];
                den += wgt;
            }
            *out = num / den;
        });
    let w = plan.weight;
    for _ in 0..plan.substeps {
        let value = &s.value;
        s.next
            .par_iter_mut()
            .enumerate()
            .with_min_len(SUBSTEP_CELLS_PER_TASK)
            .for_each(|(v, out)| {
                let x = value[v];
                let nb = neighbours(layout, v);
                let sum: f64 = nb.iter().map(|&u| value[u as usize]).sum();
                *out = (1.0 - w * nb.len() as f64) * x + w * sum;
            });
        std::mem::swap(&mut s.value, &mut s.next);
    }
    let back = ThesisReturn {
        layout,
        value: &s.value,
        out: Disjoint::new(h),
    };
    let wide = wide_vectors();
    (0..nv)
        .into_par_iter()
        .with_min_len(CELLS_PER_TASK)
        .for_each(|v| back.cell(v, wide));
}

/// The thesis' return of the cells' values to their texels.
struct ThesisReturn<'a> {
    layout: &'a Layout,
    /// Per cell: its value after the kernel.
    value: &'a [f64],
    out: Disjoint<'a>,
}

impl ThesisReturn<'_> {
    /// Sets cell `v`'s texels.
    #[inline]
    fn cell(&self, v: usize, wide: bool) {
        #[cfg(target_arch = "x86_64")]
        if wide {
            // SAFETY: the processor has AVX2 (`wide_vectors`).
            #[allow(unsafe_code)]
            unsafe {
                self.cell_avx2(v)
            };
            return;
        }
        let _ = wide;
        self.cell_body(v);
    }

    /// [`ThesisReturn::cell_body`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn cell_avx2(&self, v: usize) {
        self.cell_body(v);
    }

    /// Each texel of cell `v` takes the Shepard average of the defined
    /// cells among its 8 nearest, clamped to `[0, h_max]`; [`LANES`]
    /// texels at a time.
    #[inline(always)]
    fn cell_body(&self, v: usize) {
        let layout = self.layout;
        let hmax = layout.segments[layout.cell_segment[v] as usize].saturation;
        let (mut near, mut defined) = ([0.0; 64], [0.0; 64]);
        corner_values(layout, self.value, v, &mut near, &mut defined);
        let r = layout.slots(v);
        let members = &layout.members[r.clone()];
        let fracs = &layout.slot_frac[r];
        for (members, fracs) in members.chunks(LANES).zip(fracs.chunks(LANES)) {
            // A short last group repeats its first texel in the unused
            // lanes, whose results are dropped.
            let mut g = [fracs[0]; LANES];
            for l in 0..LANES {
                g[l] = fracs[if l < fracs.len() { l } else { 0 }];
            }
            let (num, den) = shepard_averages(&g, &near, &defined);
            for (l, &i) in members.iter().enumerate() {
                if den[l] > 0.0 {
                    // SAFETY: texel `i` belongs to cell `v` alone.
                    #[allow(unsafe_code)]
                    unsafe {
                        self.out.set(i as usize, clamp(num[l] / den[l], 0.0, hmax))
                    };
                }
            }
        }
    }
}

/// The sums of the thesis' Shepard interpolation at texels (their
/// positions in their cell `g`, see [`Layout::slot_frac`]) over the defined
/// cells among their 8 nearest (`near`, `defined`: [`corner_values`] of the
/// cells' values): `Σ w_c V_c` and `Σ w_c` over defined corners `c`, with
/// `w_c` the [`shepard`] weight of the distance to corner `c`'s centre.
#[inline(always)]
fn shepard_averages(
    g: &[[f32; 3]; LANES],
    near: &[f64; 64],
    defined: &[f64; 64],
) -> ([f64; LANES], [f64; LANES]) {
    let (mut base, mut t) = ([0; LANES], [[0.0; 3]; LANES]);
    for l in 0..LANES {
        let (o, tl) = octant(&g[l]);
        base[l] = 8 * o;
        t[l] = tl;
    }
    let (mut num, mut den) = ([0.0; LANES], [0.0; LANES]);
    for corner in 0..8 {
        for l in 0..LANES {
            let d2: f64 = (0..3)
                .map(|a| (t[l][a] - ((corner >> a) & 1) as f64).powi(2))
                .sum();
            let wgt = shepard(d2);
            // Undefined corners add +0 to both sums (the weight is
            // positive and finite): the same bits as leaving them out.
            num[l] += wgt * near[base[l] + corner];
            den[l] += wgt * defined[base[l] + corner];
        }
    }
    (num, den)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn substeps_keep_the_kernel_convex() {
        let d = Diffusion::new(1e-3);
        let p = d.plan(0.1, 0.01, 8);
        // W = 1e-3 · 0.1 / (3 · 1e-4) = 1/3, W · 8 = 2.67 → 3 substeps.
        assert_eq!(p.substeps, 3);
        assert!((p.weight - 1.0 / 9.0).abs() < 1e-12);
        assert!(p.weight * 8.0 <= 1.0);
        assert!(!p.limited);
        let p = d.plan(1e6, 0.01, 26);
        assert!(p.limited);
        assert_eq!(p.substeps, 1024);
        assert!((p.weight - 1.0 / 26.0).abs() < 1e-15);
        assert_eq!(Diffusion::new(0.0).plan(1.0, 0.01, 8).substeps, 0);
        assert_eq!(d.plan(0.0, 0.01, 8).substeps, 0);
        assert_eq!(d.plan(f64::INFINITY, 0.01, 8).substeps, 1024);
    }
}
